"""One verdict per requirement on the review page: its verification table (the manifest's
closed-form matrix) once read ``full_scale_force_N UNDECIDED ... closed-form`` while its
checks said ``pass ... (fem3d)``. A row the closed form leaves undecided and a higher level
computes anew says so and names the command that decides it; once ``tactcad check`` has
written ``review/checks.js`` for the design, the page shows the verdict it climbed to."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest

import tactcad
from tactcad.export.review_page import UNDECIDED_CLIMBS, verdict_cell, verification_view

JS = Path(tactcad.__file__).parent / "data" / "review_page.js"
ROW = {"requirement": "full_scale_force_N", "target": 0.8, "predicted": 0.8039,
       "error_estimate_rel": 0.1, "margin_rel": 0.0049, "model": "closed-form",
       "pass": False, "verdict": "undecided", "level_fixed": False}


def test_an_undecided_closed_form_row_names_the_command_that_decides_it():
    rows = next(iter(verification_view({"closed_form_matrix": [ROW]}).values()))
    assert rows[0]["verdict"] == UNDECIDED_CLIMBS
    assert "undecided at closed form" in UNDECIDED_CLIMBS.lower()
    assert "tactcad verify" in UNDECIDED_CLIMBS


@pytest.mark.parametrize("change, shown", [({"level_fixed": True}, "UNDECIDED"),
                                           ({"verdict": "pass", "pass": True}, "PASS"),
                                           ({"verdict": "fail"}, "FAIL"),
                                           ({"verdict": "info"}, "INFO")])
def test_a_row_no_level_decides_anew_keeps_its_verdict(change, shown):
    assert verdict_cell({**ROW, **change}) == shown


def test_the_pages_script_words_the_row_as_the_python_does():
    assert f"const UNDECIDED_CLIMBS = '{UNDECIDED_CLIMBS}';" in JS.read_text(encoding="utf-8")


def _decided(row, checks):
    """The page script's ``decidedRow`` run by Node on ``row`` and ``checks``."""
    js = JS.read_text(encoding="utf-8")
    start = js.index("const UNDECIDED_CLIMBS")
    code = js[start:js.index("function checksOfThisDesign")]
    program = (code + f"\nprocess.stdout.write(JSON.stringify(decidedRow("
               f"{json.dumps(row)}, {json.dumps(checks)})));\n")
    out = subprocess.run([shutil.which("node"), "-e", program], capture_output=True, text=True,
                         check=True, timeout=60)
    return json.loads(out.stdout)


CHECK = {"check": "requirement", "subject": "full_scale_force_N", "passed": True,
         "status": "pass", "detail": "pass: target 0.8, predicted 0.8965, margin +12.1 % "
                                     "(error 0.83 %, fem3d), binds: material fatigue strength"}


@pytest.mark.skipif(shutil.which("node") is None, reason="needs Node to run the page's script")
def test_the_page_shows_the_verdict_check_climbed_to():
    row = {"requirement": "full_scale_force_N", "verdict": UNDECIDED_CLIMBS,
           "model": "closed-form"}
    said = _decided(row, [CHECK])
    assert said["verdict"] == "PASS at fem3d (tactcad check); undecided at closed form"
    assert said["model"] == "closed-form"  # the row's figures stay the manifest's
    still = _decided(row, [{**CHECK, "status": "undecided",
                            "detail": CHECK["detail"].replace("pass:", "undecided:")}])
    assert still["verdict"] == "UNDECIDED up to fem3d (tactcad check)"
    assert _decided(row, []) == row  # check not run: the row names verify
    decided = {**row, "verdict": "PASS"}  # a row the closed form decided is its own
    assert _decided(decided, [{**CHECK, "status": "fail", "passed": False}]) == decided
