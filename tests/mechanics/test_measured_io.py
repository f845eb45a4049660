"""Measured calibration data in the formats a lab has: CSV variants, LabVIEW LVM, TDMS."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tactcad.cli import main
from tactcad.paper import calibration_audit as ca
from tactcad.mechanics.calibration import CalibrationError
from tactcad.mechanics.measured_io import parse_csv_text, parse_mapping, read_measured

REPO = Path(__file__).resolve().parents[2]
HW = REPO / "hardware" / "macro_array"
DAQ_MAP = parse_mapping(["force_N=Dev1/ai0,signal_V=Dev1/ai1"])
EXAMPLES = {  # file -> (options, what the reader must report)
    "calibration_example_excel.csv": ({}, "utf-8 with byte order mark, comma-separated, decimal point"),
    "calibration_example_semicolon.csv": ({"encoding": "cp1252"},
                                          "cp1252, semicolon-separated, decimal comma"),
    "calibration_example.lvm": ({"mapping": DAQ_MAP}, "lvm, utf-8, tab-separated"),
    "calibration_example.tdms": ({"mapping": DAQ_MAP}, "tdms, columns "),
}


def fitted(path, **kw) -> dict[int, tuple[float, float, float]]:
    data, _ = read_measured(path, **kw)
    return {e: (c.K_N_per_mm, c.K_v_V_per_mm, c.V0_V) for e, c in ca.fit_all(data).items()}


@pytest.fixture(scope="module")
def reference():
    return fitted(HW / "calibration_example.csv")


@pytest.mark.parametrize("name", EXAMPLES)
def test_every_example_format_gives_the_same_fitted_K(name, reference):
    options, described = EXAMPLES[name]
    got = fitted(HW / name, **options)
    assert list(got) == list(reference)
    for e, (k, kv, v0) in reference.items():
        assert got[e][0] == pytest.approx(k, abs=1e-9, rel=0)
        assert got[e][1] == pytest.approx(kv, abs=1e-9, rel=0)
        assert got[e][2] == pytest.approx(v0, abs=1e-9, rel=0)
    assert described in read_measured(HW / name, **options)[1].describe()


def test_examples_are_the_generator_script_output(tmp_path):
    """The committed examples are what the script makes from the CSV (same readings)."""
    subprocess.run([sys.executable, str(REPO / "scripts" / "make_calibration_examples.py"),
                    str(tmp_path)], check=True, capture_output=True)
    for name in EXAMPLES:
        assert (tmp_path / name).read_bytes() == (HW / name).read_bytes(), name


def _example_text(sep=",", decimal=".") -> str:
    text = (HW / "calibration_example.csv").read_text(encoding="utf-8")
    body = [ln for ln in text.splitlines() if not ln.startswith("#")]
    return "\n".join(ln.replace(",", "\0").replace(".", decimal).replace("\0", sep)
                     for ln in body) + "\n"


@pytest.mark.parametrize("sep,decimal,said", [("\t", ".", "tab-separated, decimal point"),
                                              ("\t", ",", "tab-separated, decimal comma"),
                                              (";", ".", "semicolon-separated, decimal point")])
def test_separator_and_decimal_are_detected_and_stated(sep, decimal, said, reference):
    data, info = parse_csv_text(_example_text(sep, decimal), "x.csv")
    assert said in info.describe()
    fits = ca.fit_all(data)
    assert fits[8].K_N_per_mm == pytest.approx(reference[8][0], abs=1e-9, rel=0)


@pytest.mark.parametrize("sep", [",", ";", "\t"])
def test_a_separator_ending_every_line_names_no_column(sep, reference):
    # a spreadsheet may save each line with a separator at its end
    text = "".join(line + sep + "\n" for line in _example_text(sep).splitlines())
    fits = ca.fit_all(parse_csv_text(text, "x.csv")[0])
    assert fits[8].K_N_per_mm == pytest.approx(reference[8][0], abs=1e-9, rel=0)


def test_a_value_past_the_header_is_still_refused():
    lines = _example_text().splitlines()
    lines[3] += ",7"
    with pytest.raises(CalibrationError, match="line"):
        parse_csv_text("\n".join(lines) + "\n", "x.csv")


def test_utf16_with_byte_order_mark_is_read(tmp_path, reference):
    path = tmp_path / "u16.csv"
    path.write_bytes(_example_text().encode("utf-16"))
    assert fitted(path)[1][0] == pytest.approx(reference[1][0], abs=1e-9, rel=0)


def test_a_non_utf8_file_is_refused_with_line_and_column_and_read_by_name(tmp_path):
    path = tmp_path / "latin.csv"
    path.write_bytes(("# Z in µm\n" + _example_text()).encode("latin-1"))
    with pytest.raises(CalibrationError) as err:
        read_measured(path)
    assert f"{path}: line 1, column 8: byte 0xB5 is not utf-8" in str(err.value)
    assert "--encoding" in str(err.value)
    assert read_measured(path, encoding="latin-1")[1].encoding == "latin-1"


@pytest.mark.parametrize("name", ["no-such-codec", "rot13", "", "utf-8\0"])
def test_an_unknown_encoding_is_refused_by_name(name, tmp_path):
    path = tmp_path / "a.csv"
    path.write_text(_example_text())
    with pytest.raises(CalibrationError, match="--encoding = "):
        read_measured(path, encoding=name)


@pytest.mark.parametrize("change,needle", [
    (lambda t: t.replace("0,0003", "0,0x03", 1), "line 2, column force_N = '0,0x03': allowed a number"),
    (lambda t: t.replace("-1,0103", "-1.0103", 1), "line 2, column signal_V = '-1.0103': allowed a "
                                                   "number with a decimal comma"),
    (lambda t: t.replace("1;1;25;", "1;1;", 1), "line 3, column 5: 4 values: allowed 5"),
    (lambda t: t.replace("force_N", "Kraft", 1), "missing ['force_N']"),
])
def test_damaged_semicolon_file_names_file_line_and_column(change, needle):
    with pytest.raises(CalibrationError) as err:
        parse_csv_text(change(_example_text(";", ",")), "eu.csv")
    assert str(err.value).startswith("eu.csv: line ")
    assert needle in str(err.value)


def test_lvm_bad_cell_names_line_and_channel(tmp_path):
    text = (HW / "calibration_example.lvm").read_text(encoding="utf-8")
    lines = text.splitlines()
    row = lines.index(next(ln for ln in lines if ln.startswith("X_Value"))) + 3  # third reading
    cells = lines[row].split("\t")
    cells[4] = "oops"
    lines[row] = "\t".join(cells)
    path = tmp_path / "bad.lvm"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(CalibrationError) as err:
        read_measured(path, mapping=DAQ_MAP)
    assert f"{path}: line {row + 1}, column force_N (channel 'Dev1/ai0'): 'oops'" in str(err.value)


def test_lvm_and_tdms_without_a_map_name_the_channels_they_have():
    for name in ("calibration_example.lvm", "calibration_example.tdms"):
        with pytest.raises(CalibrationError) as err:
            read_measured(HW / name)
        assert "missing force_N, signal_V" in str(err.value) and "Dev1/ai0" in str(err.value)


@pytest.mark.parametrize("text", ["force_N", "nope=x", "force_N=", "force_N=a,force_N=b"])
def test_a_bad_map_is_refused(text):
    with pytest.raises(CalibrationError, match="--map"):
        parse_mapping([text])


@pytest.mark.filterwarnings("ignore::tactcad.mechanics.measured_io.MeasuredDataWarning")
def test_a_damaged_tdms_file_is_refused(tmp_path):
    raw = (HW / "calibration_example.tdms").read_bytes()
    for k, cut in enumerate((raw[:40], raw[:len(raw) // 2], b"TDSm" + bytes(range(200)))):
        path = tmp_path / f"cut{k}.tdms"
        path.write_bytes(cut)
        with pytest.raises(CalibrationError) as err:
            read_measured(path, mapping=DAQ_MAP)
        assert str(path) in str(err.value)


@pytest.mark.filterwarnings("ignore::tactcad.mechanics.measured_io.MeasuredDataWarning")
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.binary(max_size=400), st.sampled_from(["x.csv", "x.lvm", "x.tdms", "x.dat"]))
def test_any_bytes_are_read_or_refused_by_name(tmp_path_factory, raw, name):
    path = tmp_path_factory.mktemp("fz") / name
    path.write_bytes(raw)
    try:
        read_measured(path, mapping=DAQ_MAP if name.endswith(("lvm", "tdms")) else None)
    except CalibrationError as exc:
        assert str(path) in str(exc) or str(exc).startswith("--")


def test_calibrate_command_reads_tdms_and_says_how(capsys):
    code = main(["calibrate", "--data", str(HW / "calibration_example.tdms"),
                 "--map", "force_N=Dev1/ai0", "--map", "signal_V=Dev1/ai1", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert out["data_file"]["format"] == "tdms" and out["data_file"]["readings"] == 189
    assert np.isfinite([f["K_N_per_mm"] for f in out["fits"]]).all()


def test_calibrate_command_refuses_a_non_utf8_file_in_one_line(tmp_path, capsys):
    path = tmp_path / "x.csv"
    path.write_bytes(b"element,run,z_um,force_N,signal_V\n1,1,\xff,0,0\n")
    assert main(["calibrate", "--data", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "line 2, column 5: byte 0xFF" in err and "Traceback" not in err


def test_a_tdms_file_cut_short_is_reported_in_tactcad_lines_only(tmp_path, capsys):
    path = tmp_path / "cut.tdms"
    path.write_bytes((HW / "calibration_example.tdms").read_bytes()[:-10])
    assert main(["calibrate", "--data", str(path), "--map", "force_N=Dev1/ai0,signal_V=Dev1/ai1"]) == 2
    lines = capsys.readouterr().err.splitlines()
    assert all(ln.startswith(("tactcad: warning: ", "tactcad: error: ", "tactcad: design: "))
               for ln in lines), lines
    assert any("npTDMS: Last segment of file has less data" in ln for ln in lines)
    assert lines[-1].startswith(f"tactcad: error: {path}: channel lengths")
