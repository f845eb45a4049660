"""``tactcad budget --calibration`` reads a calibration file with ``calibrate --data``'s reader
and audit: each flag calibrate raises is one of the budget's warnings (text, ``--json`` and the
API), and an element without readings leaves its units' calibration term unfitted, named so
in the notes. A spreadsheet workbook is refused as one by both commands."""

import io
import json
import zipfile
from pathlib import Path

import pytest
from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
MACRO = str(ROOT / "hardware" / "macro_array" / "macro_array.toml")
EXAMPLE = ROOT / "hardware" / "macro_array" / "calibration_example.csv"


@pytest.fixture(scope="module")
def short(tmp_path_factory) -> Path:
    """The macro array's example readings without element 3's rows (the example itself has
    none of element 5)."""
    path = tmp_path_factory.mktemp("cal") / "short.csv"
    lines = EXAMPLE.read_text(encoding="utf-8").splitlines(keepends=True)
    path.write_text("".join(line for line in lines if not line.startswith("3,")),
                    encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def flags(short) -> list[str]:
    r = run_cli("calibrate", "--design", MACRO, "--data", str(short), "--json")
    assert r.returncode == 0, r.stderr
    return [f["text"] for f in json.loads(r.stdout)["audit"]["flags"]]


@pytest.fixture(scope="module")
def budget(short) -> dict:
    r = run_cli("budget", "--design", MACRO, "--calibration", str(short), "--points", "2",
                "--json")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def test_every_flag_calibrate_raises_is_a_budget_warning(flags, budget, short):
    # the budget said nothing: warnings [] and the note "fitted standard errors of the file"
    assert any(t.startswith("element 3: no readings") for t in flags)
    assert any(t.startswith("element 5: no readings") for t in flags)
    assert any("needs a" in t and "web, design" in t for t in flags)  # K far off the design
    for text in flags:
        said = [w for w in budget["warnings"] if text in w]
        assert len(said) == 1, (text, budget["warnings"])
        assert said[0].startswith(f"--calibration = {short}: ")
    assert budget["calibration_file"]["elements_without_readings"] == [3, 5]
    assert [f["text"] for f in budget["calibration_file"]["flags"]] == flags


def test_an_element_without_readings_leaves_its_units_term_unfitted_named_in_the_notes(
        budget):
    notes = budget["notes"]
    assert notes["calibration_unfitted_elements"] == [3, 5]
    unfitted = [f"{u['reference_element']}/{u['measuring_element']}" for u in budget["units"]
                if {u["reference_element"], u["measuring_element"]} & {3, 5}]
    assert unfitted
    assert "elements 3, 5 without readings" in notes["calibration"]
    assert "without a calibration file" in notes["calibration"]
    for unit in unfitted:
        assert unit in notes["calibration"]


def test_the_text_says_the_flags_too(short, flags):
    r = run_cli("budget", "--design", MACRO, "--calibration", str(short), "--points", "2")
    assert r.returncode == 0, r.stderr
    for text in flags:
        assert f"  warning: --calibration = {short}: {text}" in r.stdout


def test_the_api_budget_reads_and_audits_the_file_as_the_command(short, budget):
    from tactcad.api import load

    got = load(MACRO).budget(calibration=str(short))
    texts = [f["text"] for f in budget["calibration_file"]["flags"]]
    for text in texts:
        assert any(text in w for w in got["warnings"]), text
    assert got["notes"]["calibration_unfitted_elements"] == [3, 5]


def _xlsx() -> bytes:
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w") as z:
        z.writestr("[Content_Types].xml", "<Types/>")
        z.writestr("xl/workbook.xml", "<workbook/>")
    return out.getvalue()


@pytest.mark.parametrize("name, raw, kind", [
    ("real.xlsx", _xlsx(), ".xlsx"),
    ("real.csv", _xlsx(), ".xlsx"),  # by its bytes, not its name
    ("old.xls", b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + bytes(500), ".xls")],
    ids=["xlsx", "xlsx-named-csv", "xls"])
@pytest.mark.parametrize("command, option", [("calibrate", "--data"),
                                             ("budget", "--calibration")])
def test_a_spreadsheet_workbook_is_refused_as_one_naming_the_option(tmp_path, name, raw, kind,
                                                                    command, option):
    # it was "byte 0x84 is not utf-8 text ... give --encoding"
    path = tmp_path / name
    path.write_bytes(raw)
    r = run_cli(command, "--design", MACRO, option, str(path), "--json")
    assert r.returncode == 2
    error = json.loads(r.stdout)["error"]
    assert error["message"].startswith(f"{option} = {path}: a spreadsheet workbook")
    assert kind in error["message"] and "save the sheet as CSV" in error["message"]
    assert "encoding" not in error["message"]
    assert error["field"] == option and "CSV" in error["allowed"] and ".tdms" in error["allowed"]


def test_a_csv_named_xlsx_is_still_read_as_csv(tmp_path):
    path = tmp_path / "cal.xlsx"
    path.write_bytes(EXAMPLE.read_bytes())
    r = run_cli("calibrate", "--design", MACRO, "--data", str(path), "--json")
    assert r.returncode == 0, r.stderr


def test_a_zeroing_run_that_is_a_workbook_is_refused_as_one(tmp_path):
    path = tmp_path / "flat.xlsx"
    path.write_bytes(_xlsx())
    r = run_cli("calibrate", "--design", MACRO, "--flat", str(path), "--json")
    assert r.returncode == 2
    message = json.loads(r.stdout)["error"]["message"]
    assert "a spreadsheet workbook" in message and "element,step,deflection_um" in message
    assert "encoding" not in message
