"""A command says the closed form's correction range warning once: the element as drawn
and the two ends of its web tolerance (the K band `verify` reads), and every element past
the fitted arm / arm height, make one line naming the worst aspect and its error."""

from __future__ import annotations

import dataclasses
import json
import re
import warnings
from pathlib import Path

import pytest

from tactcad import cli
from tactcad.commands.notices import WarningLines
from tactcad.mechanics.correction import CorrectionRangeWarning

JAW = Path(__file__).resolve().parents[2] / "src" / "tactcad" / "examples" / "grasper_jaw_10mm" \
    / "grasper_jaw_10mm.toml"
#: the 10 mm jaw's comb, its arms 0.55 mm high: arm / arm height 3.6 (references), 5.5 and
#: 4.5 (the measuring arms, 3 and 2.5 mm): two of them past the fitted 4
LONG = ["--set", "element.arm_height_mm=0.55",
        "--set", "arms.lengths_mm=[2,2,2,2,2,2,3,3,3,2.5,2.5,2.5]"]


def _range_lines(lines: list[str]) -> list[str]:
    return [w for w in lines if "correction used outside its fitted range" in w]


def test_verify_says_the_range_warning_once_naming_the_worst_aspect_and_its_error(capsys):
    assert cli.main(["verify", "--design", str(JAW), "--model", "closed-form", "--json",
                     "--no-cache", *LONG]) in (0, 1)
    doc = json.loads(capsys.readouterr().out)
    said = _range_lines(doc["warnings"])
    assert len(said) == 1, said
    text = said[0]
    assert "arm_over_arm_height (arm length / arm height) 4.545 ... 5.455" in text
    assert "web tolerance" in text  # the tolerance ends are in it, not said apart
    worst = re.search(r"estimated error up to ([0-9.]+) % at the worst, arm length / arm "
                      r"height 5\.455", text)
    assert worst, text
    # the error named is the worst estimate's: the 3 mm arm's, at the thicker end of its
    # web tolerance (a stiffer web leaves the arm more of the compliance), the correction's
    # as the closed form gives it (the bare element's: the gauge layer's share is not it)
    from tactcad.api import load
    from tactcad.mechanics.closed_form import estimate_closed_form

    plan = load(JAW, set={"element.arm_height_mm": 0.55,
                          "arms.lengths_mm": [2] * 6 + [3] * 3 + [2.5] * 3}).plan
    errs = {}
    for n in (7, 10):
        g = plan.element(n).geometry.bare()
        for dt in (-g.web_tolerance_mm, 0.0, g.web_tolerance_mm):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                errs[n, dt] = estimate_closed_form(dataclasses.replace(
                    g, web_thickness_mm=g.web_thickness_mm + dt), plan.material).error_estimate_rel
    assert float(worst.group(1)) == pytest.approx(100 * max(errs.values()), abs=0.051)
    assert errs[7, 0.0] > errs[10, 0.0] > 0.0094  # the longer arm errs more, both past 0.94 %


def test_one_warning_alone_keeps_its_text_and_a_bare_text_is_not_lost():
    notes = WarningLines(echo=False)
    with notes.capture():
        warnings.warn(CorrectionRangeWarning("closed-form stiffness correction used outside its "
                                             "fitted range at 1 of 1 points (x)", 0.01,
                                             {"arm_over_arm_height": (5, 5, 1, 4)}))
        warnings.warn("closed-form stiffness correction used outside its fitted range: plain",
                      CorrectionRangeWarning)
        warnings.warn("something else")
    assert notes.lines[0] == "something else"
    assert len(_range_lines(notes.lines)) == 1
    assert "(x)" in notes.lines[1] and ": plain" in notes.lines[1]


def test_the_tolerance_end_that_alone_leaves_a_range_is_said_so():
    w = [CorrectionRangeWarning("a", 0.02, {"arm_over_arm_height": (6, 6, 1, 4)}),
         CorrectionRangeWarning("b", 0.03, {"t_over_R": (1.05, 1.05, 0.025, 1),
                                            "arm_over_arm_height": (6, 6, 1, 4)},
                                "at a web tolerance's end, web 0.31 mm, drawn 0.3 mm")]
    text = CorrectionRangeWarning.merged_text(w)
    assert "t_over_R (web thickness / notch radius) 1.05, fitted 0.025 ... 1 (only at a web " \
           "tolerance's end)" in text
    assert "estimated error up to 3 % at the worst, web thickness / notch radius 1.05, arm " \
           "length / arm height 6 at a web tolerance's end, web 0.31 mm" in text
