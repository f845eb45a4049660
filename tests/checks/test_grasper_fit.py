"""The insert in the grasper jaw's pocket and its leads in the shaft (kernel-free)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from tactcad.checks.grasper_fit import grasper_group, pocket_clearances_mm, pocket_fit
from tactcad.checks.groups import CheckContext
from tactcad.design.array_plan import load_design
from tactcad.partlib.grasper_jaw import insert_envelope_mm, jaw_part

GRASPER = Path(__file__).parents[2] / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def comb_plan():
    return load_design(GRASPER)


def test_the_default_jaw_holds_the_comb_and_the_shaft_its_leads(comb_plan):
    found = list(grasper_group(CheckContext(comb_plan, Path("."), None)))
    assert [label for label, _ in found] == ["grasper"]
    results = found[0][1]
    assert [r.check for r in results] == ["pocket fit", "lead channel", "equal radius"]
    assert all(r.passed for r in results), [r.line() for r in results]


def test_a_pocket_narrower_than_the_envelope_fails_naming_the_side(comb_plan):
    env = insert_envelope_mm(comb_plan)
    jaw = jaw_part(comb_plan).geometry
    tip_h = comb_plan.slots[0].geometry.tip_height_mm
    narrow = replace(jaw, pocket_width_mm=env[0] - 0.2)
    result = pocket_fit(env, narrow, tip_h)
    assert not result.passed and "interferes at across" in result.detail
    assert pocket_clearances_mm(env, narrow, tip_h)["across"] == pytest.approx(-0.1)


def test_a_face_wall_down_on_the_arms_fails(comb_plan):
    env = insert_envelope_mm(comb_plan)
    jaw = jaw_part(comb_plan).geometry
    tip_h = comb_plan.slots[0].geometry.tip_height_mm
    low_wall = replace(jaw, pocket_depth_mm=jaw.thickness_mm + jaw.tip_proud_mm - tip_h - 0.05)
    result = pocket_fit(env, low_wall, tip_h)
    assert not result.passed and "under_wall" in result.detail


def test_the_stacked_array_has_no_kernel_free_grasper_check():
    plan = load_design(Path(__file__).parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")
    assert list(grasper_group(CheckContext(plan, Path("."), None))) == []


def test_a_comb_paired_along_its_rows_fails_equal_radius_naming_the_worst_unit():
    from comb_variants import row_paired_comb

    from tactcad.checks.grasper_fit import equal_radius_result

    result = equal_radius_result(row_paired_comb())
    assert not result.passed
    assert "row pairing" in result.detail and "unit 1/6" in result.detail


def test_a_jaw_its_rules_refuse_fails_its_pocket_fit_row_and_the_group_goes_on():
    """A plan made in code skips the load's refusal: the group reports the jaw as a failed
    row naming the key, value and range (and runs its other checks), never an abort."""
    import tomllib

    from tactcad.design.array_plan import plan_from_dict

    data = tomllib.loads(GRASPER.read_text(encoding="utf-8"))
    data["grasper_jaw"] = {**data["grasper_jaw"], "length_mm": 20.0}
    found = list(grasper_group(CheckContext(plan_from_dict(data), Path("."), None)))
    assert [label for label, _ in found] == ["grasper"]
    results = found[0][1]
    assert [r.check for r in results] == ["pocket fit", "lead channel", "equal radius"]
    fit = results[0]
    assert not fit.passed and "grasper_jaw.length_mm = 20.0: allowed value >= " in fit.detail
    assert not results[2].passed and "not judged" in results[2].detail
