"""A die's posts: with ``kobj_accuracy_rel`` stated, the K_obj budget gives the post-height
tolerance the accuracy needs; the drawing prints the process's tolerance and, where the
accuracy needs flatter posts, names the zeroing on an optical flat with what it leaves; and
``verify``'s ``tip_height_tolerance_mm`` row judges the drawn tolerance or that procedure
against the need, as for the metal arrays' tips."""

from __future__ import annotations

import dataclasses

import pytest

from tactcad.checks.sheet_overlap import sheet_file_results
from tactcad.partlib.grasper_jaw import jaw_room
from tactcad.products.silicon_die.design.die_mount import die_mount
from tactcad.products.silicon_die.design.mems_die import die_plan
from tactcad.products.silicon_die.drawings.die_sheet import die_sheet
from tactcad.products.silicon_die.in_use import die_budget as db
from tactcad.products.silicon_die.studies.die_verification import die_verification
from tactcad.studies.inverse_design import Targets
from tactcad.studies.verification import TIP_HEIGHT_REQUIREMENT


@pytest.fixture(scope="module")
def plan():
    return die_plan(Targets(10.0, (0.5, 5.0), 0.009), jaw_room("5"))


def _row(plan) -> dict | None:
    return next((r for r in die_verification(plan) if r["requirement"] == TIP_HEIGHT_REQUIREMENT),
                None)


def test_without_an_accuracy_the_drawing_and_verify_say_nothing_of_the_posts_flatness(plan):
    budget = db.die_budget(plan)
    assert db.post_height_drawing(budget) is None
    assert _row(plan) is None
    svg = die_sheet(plan, die_mount(plan, {"shaft_class_mm": "5"})).svg()
    assert "optical flat" not in svg
    tol_um = 1e3 * db.post_height_tolerance_mm(plan)
    assert f"posts {plan.post_height_um:g} um +-{tol_um:.3g} um high" in svg


def test_an_accuracy_finer_than_the_posts_hold_draws_the_zeroing_and_verify_judges_it(
        plan, tmp_path):
    stated = dataclasses.replace(plan, kobj_accuracy_rel=0.05)
    budget = db.die_budget(stated)
    tip = db.post_height_drawing(budget)
    # a micron of post height is worth tens of per cent of K_obj: no process holds it
    assert tip.allowance_mm is not None and tip.allowance_mm < tip.stated_mm
    assert not tip.holds_allowance and tip.residual_fits
    assert tip.drawn_mm == pytest.approx(db.post_height_tolerance_mm(plan))
    row = _row(stated)
    assert row["verdict"] == "pass" and "optical flat" in row["binding_words"]
    assert row["target"] == pytest.approx(tip.allowance_mm)
    assert row["margin_rel"] == pytest.approx(2 * tip.allowance_mm / tip.residual_mm - 1)
    path = tmp_path / "die.svg"
    path.write_text(die_sheet(stated, die_mount(stated, {"shaft_class_mm": "5"}), tip).svg(),
                    encoding="utf-8")
    text = path.read_text(encoding="utf-8")
    assert "7. Post height to" in text and "optical flat" in text
    assert not [r.line() for r in sheet_file_results(path) if not r.passed]


def test_a_flat_too_rough_for_the_accuracy_fails_the_row(plan, monkeypatch):
    stated = dataclasses.replace(plan, kobj_accuracy_rel=0.05)
    # a flat as rough as the posts' own tolerance leaves what the process left
    monkeypatch.setattr(db, "OPTICAL_FLAT_FLATNESS_MM", db.post_height_tolerance_mm(plan))
    row = _row(stated)
    assert row["verdict"] == "fail"
    assert row["predicted"] > row["target"]
