"""`calibrate` names an element the design has not before counting its readings: element
99 with one reading said "element 99: readings = 1: allowed >= 3", with four "element 99 is
not in the design"."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
TI = str(ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")  # elements 1 ... 6
HEADER = "element,run,z_um,force_N,signal_V"


def _csv(path: Path, rows) -> Path:
    path.write_text("\n".join([HEADER, *(",".join(map(str, r)) for r in rows)]) + "\n",
                    encoding="utf-8")
    return path


@pytest.mark.parametrize("count", [1, 2, 4])
def test_an_element_the_design_has_not_is_named_whatever_its_readings(tmp_path, count):
    path = _csv(tmp_path / "c.csv", [[99, 1, 10.0 * i, 0.01 * i, -1e-4 * i]
                                     for i in range(count)])
    r = run_cli("calibrate", "--design", TI, "--data", str(path), "--json")
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("element", 99)
    assert "element 99 is not in the design" in error["message"]
    assert "1 ... 6" in error["allowed"]


def test_too_few_readings_of_a_designed_element_are_still_refused_as_such(tmp_path):
    path = _csv(tmp_path / "c.csv", [[2, 1, 0.0, 0.0, 0.0]])
    r = run_cli("calibrate", "--design", TI, "--data", str(path), "--json")
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("readings", 1)
