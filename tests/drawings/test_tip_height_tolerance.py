"""The K_obj budget drives the drawings' tip-height tolerance (``kobj_accuracy_rel``).

The decision (:mod:`tactcad.in_use.tip_height_drawing`) is worked out once where the
export plans its drawings (:func:`tactcad.export.jobs.planned_drawings`) and handed to
the element's and the comb sheet's drawings; verify carries a row for it and the build
book names the zeroing the drawing relies on.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from tactcad.in_use.tip_height_drawing import (MACHINING_FLOOR_MM, ZEROING_PROCEDURE,
                                               choose_tip_height_tolerance)

ROOT = Path(__file__).resolve().parents[2]
TI = ROOT / "hardware" / "ti_array_2x3"
COMB = ROOT / "hardware" / "grasper_jaw_10mm"
#: The accuracy each example is stated to (``kobj_accuracy_rel``): the comb's calibration on
#: the catalogue's 0.5 N gauge (six steps to a full-scale travel of 20-35 um) alone takes up
#: to 11.7 %, so 10 % leaves its tips no room (test_the_combs_calibration_fills_ten_percent).
ACCURACY = {TI: 0.1, COMB: 0.15}


def _record(allowance, accuracy=0.1, residual=1.5e-4):
    return {"kobj_accuracy_rel": accuracy, "tolerance_for_accuracy_mm": allowance,
            "mismatch_after_zeroing_mm": residual}


def _copy_with_accuracy(folder: Path, target: Path, accuracy: float | None) -> Path:
    """A copy of an example's folder, ``kobj_accuracy_rel`` written into its design file."""
    shutil.copytree(folder, target)
    design = target / f"{folder.name}.toml"
    if accuracy is not None:
        text = design.read_text(encoding="utf-8")
        assert "\n[requirements]\n" in text
        design.write_text(text.replace("\n[requirements]\n",
                                       f"\n[requirements]\nkobj_accuracy_rel = {accuracy}\n", 1),
                          encoding="utf-8")
    return design


def _project(folder: Path, tmp_path: Path, accuracy: float | None):
    from tactcad.api import load

    return load(_copy_with_accuracy(folder, tmp_path / folder.name, accuracy))


# --- the decision ------------------------------------------------------------------------------
def test_no_stated_accuracy_makes_no_decision():
    assert choose_tip_height_tolerance(0.02, _record(0.001, accuracy=None)) is None


def test_an_allowance_machining_holds_tightens_the_drawing_to_it():
    tip = choose_tip_height_tolerance(0.02, _record(0.005))
    assert tip.drawn_mm == 0.005 and tip.holds_allowance
    assert tip.procedure is None and tip.note is None


def test_a_tightened_tolerance_is_rounded_down_to_what_the_drawing_prints():
    tip = choose_tip_height_tolerance(0.02, _record(0.0057))
    assert tip.drawn_mm == 0.005 and tip.holds_allowance


def test_a_stated_tolerance_inside_the_allowance_stays():
    tip = choose_tip_height_tolerance(0.02, _record(0.03))
    assert tip.drawn_mm == 0.02 and tip.holds_allowance and tip.note is None


def test_an_allowance_below_the_machining_floor_keeps_the_process_tolerance_and_names_zeroing():
    allowance = MACHINING_FLOOR_MM / 3
    tip = choose_tip_height_tolerance(0.02, _record(allowance, residual=2e-4))
    assert tip.drawn_mm == 0.02 and not tip.holds_allowance
    assert tip.procedure == ZEROING_PROCEDURE
    assert "tactcad calibrate" in tip.note and "0.2 um" in tip.note
    assert tip.residual_fits == (2e-4 <= 2 * allowance)


def test_no_room_left_by_the_other_terms_names_zeroing_and_does_not_fit():
    tip = choose_tip_height_tolerance(0.02, _record(None))
    assert tip.drawn_mm == 0.02 and tip.procedure == ZEROING_PROCEDURE
    assert not tip.residual_fits and "no room" in tip.note


def test_a_negative_tolerance_is_refused_naming_the_field():
    with pytest.raises(ValueError, match=r"tolerances\.tip_height_mm = -0\.1: allowed >= 0 mm"):
        choose_tip_height_tolerance(-0.1, _record(0.001))


# --- the export's plan of the drawings ---------------------------------------------------------
@pytest.mark.parametrize("folder, tip_builder", [(TI, "element"), (COMB, "comb_sheet")])
def test_the_planned_drawings_hold_the_budgets_allowance_or_carry_the_procedure(
        tmp_path, folder, tip_builder):
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.export.jobs import planned_drawings
    from tactcad.in_use.kobj_budget import kobj_budget
    from tactcad.studies.verification import calibration_gauge
    from tactcad.studies.verification import requirements_of

    plan = _project(folder, tmp_path, ACCURACY[folder]).plan
    req = requirements_of(plan)
    record = kobj_budget(plan, req.kobj_range_N_per_mm, req.full_scale_force_N,
                         force_gauge=calibration_gauge(plan)).tip_height
    planned = planned_drawings(plan, list(array_parts(plan).values()))
    with_tips = [tip for spec, tip in planned if spec.builder == tip_builder]
    assert with_tips and all(tip is not None for tip in with_tips)
    assert all(tip is None for spec, tip in planned if spec.builder != tip_builder)
    for tip in with_tips:
        assert tip.allowance_mm == record["tolerance_for_accuracy_mm"]
        assert tip.residual_mm == record["mismatch_after_zeroing_mm"]
        holds = tip.drawn_mm <= tip.allowance_mm
        assert holds or ("tactcad calibrate" in tip.note and tip.residual_fits)
    # both examples need microns, finer than machining: the process tolerance stays
    assert all(t.allowance_mm < MACHINING_FLOOR_MM and t.drawn_mm == 0.02 for t in with_tips)


def test_a_loose_accuracy_on_the_ti_example_tightens_the_drawn_tolerance(tmp_path):
    """At 100 % the allowance is microns that machining holds: the element drawing prints it
    (rounded down) instead of +/-0.02 mm, with no zeroing note, and verify passes it as drawn."""
    from tactcad.export.drawn_tolerances import tip_height_drawing
    from tactcad.studies.verification import (accuracy_budget, element_figures,
                                              requirements_of, tip_height_tolerance_record)

    plan = _project(TI, tmp_path, 1.0).plan
    tip = tip_height_drawing(plan)
    assert MACHINING_FLOOR_MM <= tip.allowance_mm < 0.02
    assert tip.drawn_mm <= tip.allowance_mm < tip.drawn_mm + 0.001 and tip.note is None
    d = _compose(plan, "element", tip)
    assert d.dimensions["overall_height"].endswith(f"±{tip.drawn_mm:g}")
    assert not any("tactcad calibrate" in n for n in d.notes)
    fig = element_figures(plan)
    row = tip_height_tolerance_record(plan, fig, accuracy_budget(plan, fig, requirements_of(plan, fig)))
    assert row["pass"] and row["binding_words"].startswith(f"drawn +/-{tip.drawn_mm:.3g} mm holds")


def test_without_the_accuracy_no_drawing_gets_a_decision_and_its_hash_is_unchanged(tmp_path):
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.drawings.compose import drawing_inputs
    from tactcad.export.jobs import planned_drawings

    plan = _project(TI, tmp_path, None).plan
    specs = list(array_parts(plan).values())
    assert all(tip is None for _, tip in planned_drawings(plan, specs))
    assert all(drawing_inputs(plan, s, None) == drawing_inputs(plan, s) for s in specs)


# --- the drawings --------------------------------------------------------------------------
def _compose(plan, builder: str, tip):
    from tactcad.catalogue.array_catalogue import array_instances, array_parts
    from tactcad.assembly.inventory import instance_counts
    from tactcad.drawings.compose import compose
    from tactcad.solids.cache import PartCache

    spec = next(s for s in array_parts(plan).values() if s.builder == builder)
    qty = instance_counts(array_instances(plan))[spec.name]
    return compose(plan, spec, PartCache(plan).solid(spec), qty, tip)


def test_the_element_drawing_prints_the_decision(tmp_path):
    from tactcad.export.drawn_tolerances import tip_height_drawing

    plan = _project(TI, tmp_path, 0.1).plan
    zeroed = _compose(plan, "element", tip_height_drawing(plan))
    assert zeroed.dimensions["overall_height"].endswith("±0.02")
    assert any("tactcad calibrate" in n and "um of mismatch" in n for n in zeroed.notes)
    tightened = choose_tip_height_tolerance(0.02, _record(0.005))
    d = _compose(plan, "element", tightened)
    assert d.dimensions["overall_height"].endswith("±0.005")
    assert not any("tactcad calibrate" in n for n in d.notes)
    plain = _compose(plan, "element", None)
    assert plain.dimensions["overall_height"].endswith("±0.02")
    assert not any("tactcad calibrate" in n for n in plain.notes)


def test_the_comb_sheet_drawing_tolerances_its_contact_faces(tmp_path):
    from tactcad.export.drawn_tolerances import tip_height_drawing

    plan = _project(COMB, tmp_path, 0.1).plan
    d = _compose(plan, "comb_sheet", tip_height_drawing(plan))
    faces = [n for n in d.notes if n.startswith("Contact faces")]
    assert len(faces) == 1 and "±0.02 above the spine's underside" in faces[0]
    assert any("tactcad calibrate" in n for n in d.notes)
    plain = _compose(plan, "comb_sheet", None)
    assert not any(n.startswith("Contact faces") or "tactcad calibrate" in n
                   for n in plain.notes)


# --- verify and the build book -------------------------------------------------------------
@pytest.mark.parametrize("folder", [TI, COMB])
def test_verify_has_the_tip_height_row_and_it_passes_by_the_zeroing(tmp_path, folder):
    from tactcad.studies.verification import (TIP_HEIGHT_REQUIREMENT, accuracy_budget,
                                              element_figures, requirements_of,
                                              tip_height_tolerance_record)

    plan = _project(folder, tmp_path, ACCURACY[folder]).plan
    fig = element_figures(plan)
    req = requirements_of(plan, fig)
    row = tip_height_tolerance_record(plan, fig, accuracy_budget(plan, fig, req))
    assert row["requirement"] == TIP_HEIGHT_REQUIREMENT and row["pass"]
    assert row["target"] == row["tip_height"]["allowance_mm"]
    assert "zeroed on a rigid flat" in row["binding_words"]
    assert row["margin_rel"] == pytest.approx(
        2 * row["target"] / row["tip_height"]["residual_mm"] - 1)


def test_the_combs_calibration_fills_ten_percent(tmp_path):
    """At 10 % the comb's tip-height row fails, and its budget names the force gauge
    resolution that would leave the tips room rather than passing silently."""
    from tactcad.studies.verification import (accuracy_budget, element_figures,
                                              requirements_of, tip_height_tolerance_record)

    plan = _project(COMB, tmp_path, 0.1).plan
    fig = element_figures(plan)
    req = requirements_of(plan, fig)
    budget = accuracy_budget(plan, fig, req)
    assert not tip_height_tolerance_record(plan, fig, budget)["pass"]
    notes = budget.notes
    assert notes["calibration_gauge_fits"] is False
    assert 0 < notes["calibration_gauge_resolution_needed_N"] < plan_gauge_resolution(plan)
    assert "of the stated accuracy 10 %" in notes["calibration_allowance"]


def plan_gauge_resolution(plan) -> float:
    from tactcad.studies.verification import calibration_gauge

    return calibration_gauge(plan).gauge.resolution_N


def test_the_verification_matrix_carries_the_row_only_with_the_accuracy(tmp_path):
    from tactcad.studies.verification import TIP_HEIGHT_REQUIREMENT, verification_matrix

    stated = verification_matrix(_project(TI, tmp_path / "a", 0.1).plan)
    row = next(r for r in stated if r["requirement"] == TIP_HEIGHT_REQUIREMENT)
    assert row["verdict"] == "pass"
    plain = verification_matrix(_project(TI, tmp_path / "b", None).plan)
    assert all(r["requirement"] != TIP_HEIGHT_REQUIREMENT for r in plain)


def test_the_verify_command_prints_and_returns_the_row(tmp_path):
    import json

    from conftest import run_cli

    design = _copy_with_accuracy(TI, tmp_path / "ti", 0.1)
    done = run_cli("verify", "--design", str(design), "--model", "closed-form", "--json")
    rows = [r for r in json.loads(done.stdout)["matrix"]
            if r["requirement"] == "tip_height_tolerance_mm"]
    assert len(rows) == 1 and rows[0]["verdict"] == "pass"
    assert rows[0]["tip_height"]["procedure"].startswith("tips zeroed on a rigid flat")
    text = run_cli("verify", "--design", str(design), "--model", "closed-form").stdout
    target = re.escape(f"{rows[0]['target']:.4g}")
    assert re.search(rf"\| tip_height_tolerance_mm \| {target} \|.*\| PASS \| zeroed on a rigid "
                     r"flat", text)


def test_a_tightened_drawing_passes_by_its_tolerance():
    from tactcad.studies.verification import Figures, tip_height_tolerance_record

    class Budget:  # the two fields the record reads
        tip_height = _record(0.005)
        units = [{"uncertainty_rel": 0.04}]

    class Plan:
        raw = {"tolerances": {"tip_height_mm": 0.02}}

    fig = Figures("closed-form", {}, {}, {}, {})
    row = tip_height_tolerance_record(Plan(), fig, Budget())
    assert row["pass"] and row["predicted"] == 0.005 and row["margin_rel"] == pytest.approx(0)
    assert row["binding_words"].startswith("drawn +/-0.005 mm holds it")


def test_the_build_book_names_the_zeroing_the_drawing_relies_on():
    from tactcad.assembly.build_steps import READOUT_STEP, BookContext, tip_zeroing_note

    zeroing = tip_zeroing_note(choose_tip_height_tolerance(0.02, _record(5e-4)))
    assert "tactcad calibrate --flat" in zeroing and "+/-0.02 mm" in zeroing
    assert tip_zeroing_note(choose_tip_height_tolerance(0.02, _record(0.005))) is None
    assert tip_zeroing_note(None) is None
    book = BookContext(6, "", "", None, 0, {}, zeroing)
    assert zeroing in READOUT_STEP.notes(book)
    assert zeroing not in READOUT_STEP.notes(BookContext(6, "", "", None, 0, {}))


def test_the_kit_steps_of_the_ti_example_name_the_zeroing(tmp_path):
    from tactcad.assembly.inventory import design_assemblies
    from tactcad.export.bom import complete_kit, kit_steps

    def notes(accuracy, name):
        project = _project(TI, tmp_path / name, accuracy).validated
        assembled = design_assemblies(project)
        steps = kit_steps(project, complete_kit(project, assembled), assembled[0])
        return [n for s in steps for n in s.notes]

    assert any("tactcad calibrate --flat" in n for n in notes(0.1, "stated"))
    assert not any("tactcad calibrate --flat" in n for n in notes(None, "plain"))


def _svg_text(path: Path) -> str:
    """Every text of an SVG, one space between (wrapped note lines joined again)."""
    import xml.etree.ElementTree as ET

    root = ET.parse(path).getroot()
    return " ".join(t.strip() for el in root.iter() if el.tag.endswith("text")
                    for t in el.itertext() if t.strip())


@pytest.mark.slow
def test_the_exported_element_drawings_carry_the_decision(tmp_path):
    """End to end: the Ti example with kobj_accuracy_rel = 0.1 exported; every element
    drawing prints the process tolerance with the zeroing note and its residual."""
    project = _project(TI, tmp_path, 0.1)
    out = tmp_path / "exports"
    project.export(out, only="drawings", cache=False)
    svgs = sorted((out / "drawings").glob("element_*.svg"))
    assert svgs
    for svg in svgs:
        text = _svg_text(svg)
        assert "tactcad calibrate --flat" in text and "um of mismatch" in text
        assert re.search(r"\d ±0\.02\b", text)
