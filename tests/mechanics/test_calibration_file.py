"""A calibration data file read and fitted with one set of refusals (``calibrate --data``,
``budget --calibration``): a column that never changes, a gauge deflection past the travel
(z in mm, one element's force in mN, one spike), an element the design lacks, a header with
no readings, a wrong encoding, an ambiguous TDMS channel; the refusals' JSON fields; a
simulated run written to the digit."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from conftest import run_cli

from tactcad.mechanics import calibration as cal
from tactcad.mechanics.calibration import CalibrationError
from tactcad.mechanics.calibration_file import read_calibration
from tactcad.mechanics.measured_io import parse_csv_text, read_measured

ROOT = Path(__file__).resolve().parents[2]
TI = str(ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")  # elements 1 ... 6
HEADER = "element,run,z_um,force_N,signal_V"
K_SENSOR = 30.0  # N/mm, stated in each file
STEPS_UM = np.linspace(0.0, 100.0, 7)


def readings(elements=range(1, 7), z_scale=1.0, force_scale=None, spike=None) -> list[list]:
    """Rows of a plausible calibration (element e of K = 4 + e N/mm, 2 runs), with the
    slips asked: Z travel times ``z_scale``, ``force_scale`` {element: factor}, ``spike``
    (row index, force N)."""
    rng = np.random.default_rng(3)
    rows = []
    for e in elements:
        k = 4.0 + e
        k_app = k * K_SENSOR / (k + K_SENSOR)
        for run in (1, 2):
            for z in STEPS_UM:
                force = k_app * 1e-3 * z + rng.normal(0, 1e-3)
                deflection = force / k
                signal = -0.2 * deflection + rng.normal(0, 1e-5)
                rows.append([e, run, z * z_scale,
                             force * (force_scale or {}).get(e, 1.0), signal])
    if spike is not None:
        rows[spike[0]][3] = spike[1]
    return rows


def write(path: Path, rows, head: str = HEADER) -> Path:
    """``rows`` as a calibration CSV (line 1 the gauge's stiffness, line 2 the header, the
    reading of row i on line i + 3)."""
    lines = [f"# k_sensor_N_per_mm = {K_SENSOR:g}", head]
    lines += [",".join(repr(float(x)) if i > 1 else str(int(x)) for i, x in enumerate(r))
              for r in rows]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def refusal(path, **kw) -> CalibrationError:
    with pytest.raises(CalibrationError) as err:
        read_calibration(path, **kw)
    return err.value


def test_plausible_readings_fit_every_element(tmp_path):
    got = read_calibration(write(tmp_path / "ok.csv", readings()), element_numbers=range(1, 7))
    assert [round(f.K_N_per_mm) for f in got.fits.values()] == [5, 6, 7, 8, 9, 10]
    assert got.info.places[2][0] == "line 17"  # 14 readings of element 1 on lines 3 ... 16


@pytest.mark.parametrize("column, index, words", [
    ("force_N", 3, "force constant: the force gauge read 0 N at every step"),
    ("signal_V", 4, "signal constant: the bridge read 0 V at every step"),
    ("z_um", 2, "z constant: the Z axis stood at 0 um at every step")])
def test_a_column_that_never_changes_is_refused_by_name(tmp_path, column, index, words):
    rows = readings()
    for r in rows:
        if r[0] == 2:
            r[index] = 0.0
    path = write(tmp_path / "flat.csv", rows)
    err = refusal(path)
    assert f"{path}: element 2: column {column}: {words}" in str(err)
    assert err.field == column and "0" in err.value and err.allowed


def test_a_signal_of_noise_alone_is_refused(tmp_path):
    rows = readings()
    noise = np.random.default_rng(7).normal(0, 1e-5, len(rows))
    for r, n in zip(rows, noise):
        if r[0] == 3:
            r[4] = float(n)
    path = write(tmp_path / "noise.csv", rows)
    err = refusal(path)
    assert f"{path}: element 3: column signal_V: K_v = " in str(err)
    assert "no slope above the noise" in str(err) and err.field == "signal_V"


@pytest.mark.parametrize("command", ["calibrate", "budget"])
@pytest.mark.parametrize("index, column", [(3, "force_N"), (4, "signal_V")])
def test_commands_refuse_a_dead_channel_in_json_without_a_traceback(tmp_path, command, index,
                                                                    column):
    rows = readings()
    for r in rows:
        r[index] = 0.0
    path = write(tmp_path / "dead.csv", rows)
    option = "--data" if command == "calibrate" else "--calibration"
    r = run_cli(command, "--design", TI, option, str(path), "--json")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == column and str(path) in error["message"]
    assert error["value"] and error["allowed"]


def test_a_header_with_no_readings_below_it_in_an_lvm_file_is_refused(tmp_path):
    head = ["LabVIEW Measurement\t", "Writer_Version\t2", "Reader_Version\t2", "Separator\tTab",
            "Decimal_Separator\t.", "Multi_Headings\tNo", "X_Columns\tOne",
            "***End_of_Header***\t", "", "Channels\t5", "***End_of_Header***\t",
            "X_Value\t" + HEADER.replace(",", "\t") + "\tComment"]
    path = tmp_path / "empty.lvm"
    path.write_text("\n".join(head) + "\n", encoding="utf-8")
    err = refusal(path)
    assert f"{path}: line {len(head)}: no readings below the header" in str(err)
    assert (err.field, err.value) == ("--data", str(path))
    r = run_cli("budget", "--design", TI, "--calibration", str(path), "--json")
    error = json.loads(r.stdout)["error"]
    assert r.returncode == 2 and (error["field"], error["value"]) == ("--calibration", str(path))


def test_z_in_mm_is_named_as_the_likely_cause(tmp_path):
    path = write(tmp_path / "mm.csv", readings(z_scale=1e-3))
    err = refusal(path)
    text = str(err)
    assert text.startswith(f"{path}: element 1: fitted K = ")
    assert "F/K_s exceeds the Z travel" in text and "z_um written in mm" in text
    assert "force_N written in mN" not in text and "k_sensor_N_per_mm = 30 N/mm" in text
    assert err.field == "z_um"


def test_one_elements_force_in_mN_names_that_element_and_its_unit(tmp_path):
    rows = readings(force_scale={4: 1e3})
    path = write(tmp_path / "mN.csv", rows)
    err = refusal(path)
    text = str(err)
    assert text.startswith(f"{path}: element 4: ")
    assert "force_N written in mN" in text and "z_um written in mm" not in text
    # the reading where the gauge takes the most: element 4's largest force, on its line
    largest = max(range(len(rows)), key=lambda i: rows[i][3])
    assert err.field == "force_N" and err.value.startswith(f"line {largest + 3}: ")


def test_a_single_spike_is_named_as_an_outlier_at_its_line(tmp_path):
    rows = readings(spike=(3, 2.5))  # element 1, run 1, 50 um: 2.5 N
    path = write(tmp_path / "spike.csv", rows)
    text = str(refusal(path))
    assert f"{path}: element 1: " in text and "an outlier at line 6: force_N = 2.5 N" in text
    assert "written in" not in text


def test_an_element_the_design_lacks_is_named_with_file_and_line(tmp_path):
    rows = readings() + [[9, 1, z, 0.01 * z, -1e-3 * z] for z in STEPS_UM]
    path = write(tmp_path / "nine.csv", rows)
    err = refusal(path, element_numbers=range(1, 7), option="--calibration")
    first = 2 + len(readings()) + 1
    assert f"--calibration = {path}: line {first}, column element = 9" in str(err)
    assert "1 ... 6" in str(err) and (err.field, err.value) == ("element", 9)


def test_budget_refuses_what_calibrate_refuses_in_the_same_words(tmp_path):
    path = write(tmp_path / "mN.csv", readings(force_scale={4: 1e3}))
    a = run_cli("calibrate", "--design", TI, "--data", str(path), "--json")
    b = run_cli("budget", "--design", TI, "--calibration", str(path), "--json")
    assert a.returncode == b.returncode == 2
    ea, eb = json.loads(a.stdout)["error"], json.loads(b.stdout)["error"]
    assert ea["message"] == eb["message"] and "element 4" in ea["message"]


def test_a_nan_cell_fills_the_json_fields(tmp_path):
    rows = readings()
    path = write(tmp_path / "nan.csv", rows)
    text = path.read_text().replace(repr(float(rows[0][3])), "NaN", 1)
    path.write_text(text)
    r = run_cli("calibrate", "--design", TI, "--data", str(path), "--json")
    error = json.loads(r.stdout)["error"]
    assert r.returncode == 2 and f"{path}: line 3, column force_N" in error["message"]
    assert (error["field"], error["value"], error["allowed"]) == ("force_N", "NaN",
                                                                   "a finite number")


def test_a_file_in_another_encoding_is_named_briefly_with_the_one_that_reads(tmp_path):
    lines = [HEADER.replace(",", ";")] + [";".join(str(x).replace(".", ",") for x in r)
                                          for r in readings()]
    raw = ("\n".join(lines) + "\n").encode("utf-8")
    path = tmp_path / "semi.csv"
    path.write_bytes(raw if len(raw) % 2 == 0 else raw + b"\n")
    err = refusal(path, encoding="utf-16")
    text = str(err)
    assert text.startswith(f"{path} does not read as UTF-16: ")
    assert text.endswith("try --encoding utf-8") and len(text) < 400
    assert err.field == "--encoding"
    assert read_measured(path, encoding="utf-8")[1].readings == len(readings())


def test_a_channel_in_two_tdms_groups_is_refused_as_ambiguous(tmp_path):
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter

    cols = np.array(readings(), dtype=float).T
    path = tmp_path / "two.tdms"
    with TdmsWriter(path) as writer:
        writer.write_segment([
            RootObject(), GroupObject("rig"), GroupObject("Dev1"), GroupObject("Dev2"),
            ChannelObject("rig", "element", cols[0].astype(np.int32)),
            ChannelObject("rig", "run", cols[1].astype(np.int32)),
            ChannelObject("rig", "z_um", cols[2]), ChannelObject("Dev1", "force_N", cols[3]),
            ChannelObject("Dev1", "signal_V", cols[4]), ChannelObject("Dev2", "force_N", cols[3])])
    err = refusal(path)
    assert "'force_N' is ambiguous: it is in groups Dev1 and Dev2" in str(err)
    assert "--map force_N=Dev1/force_N" in str(err) and err.field == "force_N"
    chosen = read_calibration(path, mapping={"force_N": "Dev2/force_N"})
    assert chosen.info.mapping["force_N"] == "Dev2/force_N"


def test_a_written_calibration_refits_to_the_same_constants():
    data = {1: cal.synthetic_calibration(6.0, -0.2, 0.01, noise_signal_V=1.3e-5, seed=1,
                                         k_sensor_N_per_mm=K_SENSOR)}
    back, _ = parse_csv_text(cal.format_calibration_csv(data))
    a, b = (cal.fit_calibration(d[1].z_travel_um, d[1].force_N, d[1].signal_V,
                                d[1].k_sensor_N_per_mm) for d in (data, back))
    assert b.stderr_K_v_V_per_mm == pytest.approx(a.stderr_K_v_V_per_mm, rel=1e-9)
    assert b.K_v_V_per_mm == pytest.approx(a.K_v_V_per_mm, rel=1e-12)
    np.testing.assert_array_equal(back[1].signal_V, data[1].signal_V)
