"""``design --footprint``: a design that fits is found by shorter elements,
thinner webs or another sheet; one that cannot fit is refused naming the
footprint and the nearest one that does."""

from __future__ import annotations

import re

import pytest

from tactcad.assembly.inventory import array_envelope_mm
from tactcad.cli import main
from tactcad.design.project import load_project
from tactcad.errors import DesignError
from tactcad.studies.footprint_fit import design_within_footprint, fits
from tactcad.studies.inverse_design import Targets, design_for_targets
from tactcad.studies.verification import verification_matrix

pytestmark = pytest.mark.filterwarnings(
    "ignore::tactcad.mechanics.correction.CorrectionRangeWarning")

#: The fingertip case: 2 x 4, 17-4PH, K_r/K_m 6 over 5-50 N/mm at 0.5 N.
FINGERTIP = Targets(6.0, (5.0, 50.0), 0.5)
LAYOUT = dict(grade="17-4PH-H900", columns=4)


@pytest.mark.slow  # whole design searches
def test_a_footprint_smaller_than_the_plain_design_is_met_by_another_sheet(plan):
    plain = design_for_targets(plan, FINGERTIP, **LAYOUT)
    x, y, _ = array_envelope_mm(plain.plan)
    footprint = (x - 5.0, y - 4.0)  # 50 x 23 for 55 x 27
    d = design_within_footprint(plan, FINGERTIP, footprint, array_envelope_mm, **LAYOUT)
    env = array_envelope_mm(d.plan)
    assert fits(env, footprint) and not fits((x, y), footprint)
    assert d.plan.sheet_thickness_mm < plain.plan.sheet_thickness_mm  # a thinner stack
    assert "--footprint" in d.data["assumptions"]["sheet.thickness_mm"]
    assert d.data["requirements"]["footprint_mm"] == list(footprint)
    records = {r["requirement"]: r for r in verification_matrix(d.plan, envelope_mm=env)}
    assert records["footprint_mm"]["verdict"] == "pass"
    # every judged row passes; the K band the design states none for is reported only
    assert {k: r["verdict"] for k, r in records.items() if r["verdict"] != "pass"} == {
        "k_tolerance_rel": "info", "k_tolerance_rel_toleranced": "info"}, records


@pytest.mark.slow  # a whole design search
def test_a_footprint_too_small_names_the_nearest_that_fits_and_that_one_does(plan):
    with pytest.raises(DesignError) as exc:
        design_within_footprint(plan, FINGERTIP, (40.0, 20.0), array_envelope_mm, **LAYOUT)
    text = str(exc.value)
    assert "--footprint" in text and "40" in text
    x, y = (float(v) for v in re.search(r"at least ([0-9.]+) x ([0-9.]+) mm", text).groups())
    assert x > 40.0 or y > 20.0
    d = design_within_footprint(plan, FINGERTIP, (x, y), array_envelope_mm, **LAYOUT)
    assert fits(array_envelope_mm(d.plan), (x, y))


@pytest.mark.slow
def test_the_exported_step_of_a_footprint_design_lies_inside_it(tmp_path, capsys):
    from tactcad.kernel.step_writer import read_step_summary

    folder = tmp_path / "fingertip"
    assert main(["design", "--kr-over-km", "6", "--kobj-range", "5", "50", "--full-scale-force",
                 "0.5", "--material", "17-4PH", "--columns", "4", "--footprint", "50", "23",
                 "--out", str(folder), "--verify", "none", "--quiet"]) == 0
    design = folder / "fingertip.toml"
    assert "--footprint 50 23" in design.read_text(encoding="utf-8")
    assert main(["export", "--design", str(design), "--only", "step", "--out",
                 str(tmp_path / "out"), "--quiet"]) == 0
    box = read_step_summary(tmp_path / "out" / "step" / "array.step")["bbox_mm"]
    size = [box[k + 3] - box[k] for k in range(3)]
    assert size[0] <= 50.0 + 1e-6 and size[1] <= 23.0 + 1e-6, size
    assert size == pytest.approx(list(array_envelope_mm(load_project(design).plan)), abs=1e-3)


def test_a_design_that_fits_as_asked_is_kept_and_its_own_errors_are_its_own(plan):
    """A footprint the plain design fits changes nothing but stating it; a bad
    design name is refused naming it, not taken for a footprint that no design fits."""
    plain = design_for_targets(plan, FINGERTIP, **LAYOUT)
    d = design_within_footprint(plan, FINGERTIP, (1e4, 1e4), array_envelope_mm, **LAYOUT)
    assert d.data["arms"] == plain.data["arms"] and d.data["element"] == plain.data["element"]
    assert d.data["assumptions"] == plain.data["assumptions"]  # no reason of a change
    assert d.data["requirements"]["footprint_mm"] == [1e4, 1e4]
    with pytest.raises(DesignError, match="design.name"):
        design_within_footprint(plan, FINGERTIP, (1.0, 1.0), array_envelope_mm, name="x é",
                                **LAYOUT)
