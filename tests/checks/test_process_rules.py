"""The process check group: each cut part against its process's rules,
passing at a rule's bound and failing just past it, with the feature, value,
rule and source in the message."""

from __future__ import annotations

import warnings
from dataclasses import replace

import pytest
from process_variants import cut_by

from tactcad.checks.groups import CHECK_GROUPS
from tactcad.checks.process_rules import part_rule_checks, process_rule_checks
from tactcad.design.array_plan import EXAMPLES, load_design, plan_from_dict, with_overrides
from tactcad.export.dxf_sheet import shop_profiles
from tactcad.vocabulary.schema import read_toml

TI = str(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")


def _element(**overrides):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plan = plan_from_dict(with_overrides(read_toml(TI, "design file"), overrides))
    return next(sp for sp in shop_profiles(plan) if sp.part.startswith("element_"))


def _result(results, check, feature=""):
    return next(r for r in results if r.check == check and feature in r.detail)


def test_the_group_is_registered_and_runs_before_any_export():
    group = CHECK_GROUPS["process"]
    assert not group.on_export and group.suite == "part"


def test_the_wire_cut_example_passes_every_rule():
    results = process_rule_checks(load_design(TI))
    assert results and all(r.passed for r in results), [r.line() for r in results if not r.passed]


@pytest.mark.parametrize("process, t", [("photochemical-etching", 0.3), ("laser-cutting", 0.5)])
def test_web_passes_at_the_process_minimum_and_fails_below(process, t):
    sp = _element(**cut_by(process, t))
    least = sp.limits.min_web_mm.value_mm
    at = _result(part_rule_checks(replace(sp, web_thickness_mm=least)), "process_min_web", "flexure web")
    below = _result(part_rule_checks(replace(sp, web_thickness_mm=least - 0.001)),
                    "process_min_web", "flexure web")
    assert at.passed and not below.passed
    assert process in below.detail and f"{least:.4g} mm" in below.detail
    assert sp.limits.min_web_mm.source in below.detail


def test_the_etched_ti_example_fails_on_its_thin_web_and_fine_tolerance():
    sp = _element(**cut_by("photochemical-etching", 0.3))
    failed = {r.check for r in part_rule_checks(sp) if not r.passed}
    assert failed == {"process_min_web"}
    tol = sp.limits.tolerance_mm.value_mm
    assert tol == pytest.approx(0.045)
    assert _result(part_rule_checks(replace(sp, web_tolerance_mm=tol)), "process_tolerance").passed
    finer = _result(part_rule_checks(replace(sp, web_tolerance_mm=tol - 0.001)), "process_tolerance")
    assert not finer.passed and "0.045" in finer.detail


def test_hole_fails_below_the_etch_minimum():
    sp = _element(**cut_by("photochemical-etching", 1.5))
    least = sp.limits.min_hole_mm.value_mm  # 1.5 x 1.5 mm for titanium: 2.25 mm < the 2.4 mm hole
    assert _result(part_rule_checks(sp), "process_min_hole").passed
    small = replace(sp.profile, holes=tuple(replace(h, radius=least / 2 - 0.001)
                                             for h in sp.profile.holes))
    assert not _result(part_rule_checks(replace(sp, profile=small)), "process_min_hole").passed


def _spacer_checks(**overrides):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plan = plan_from_dict(with_overrides(read_toml(TI, "design file"), overrides))
    return plan, [r for r in process_rule_checks(plan) if r.subject == "spacer"]


def test_a_thin_spacer_is_judged_by_what_the_process_cuts_not_by_the_flexure_model():
    """The palpation strip's 0.2 mm spacer (pitch - sheet) failed its own check against
    the 0.5-10 mm range the flexure's stiffness model is fitted over; a plain plate is
    judged by the process's cutting range, quoted with that source."""
    t = read_toml(TI, "design file")["sheet"]["thickness_mm"]
    plan, spacer = _spacer_checks(**{"array.pitch_mm": t + 0.2})
    sheet = _result(spacer, "process_sheet")
    assert all(r.passed for r in spacer), [r.line() for r in spacer]
    assert "0.1-300 mm" in sheet.detail and "stiffness correction" not in sheet.detail
    element = next(r for r in process_rule_checks(plan)
                   if r.check == "process_sheet" and r.subject.startswith("element_"))
    assert "0.5-10 mm" in element.detail and "stiffness correction" in element.detail


def test_the_spacers_process_is_the_design_files_and_refused_where_it_cannot_cut():
    t = read_toml(TI, "design file")["sheet"]["thickness_mm"]
    plan, spacer = _spacer_checks(**{"array.pitch_mm": t + 0.2, "spacer.process": "laser-cutting"})
    assert "laser-cutting" in _result(spacer, "process_sheet").detail
    with pytest.raises(Exception) as err:
        _spacer_checks(**{"array.pitch_mm": t + 2.0, "spacer.process": "photochemical-etching"})
    text = str(err.value)
    assert "spacer.process" in text and "2 mm spacer" in text and "wire-edm" in text


@pytest.mark.parametrize("field", ["element.web_tolerance_mm", "tolerances.web_thickness_mm"])
def test_a_web_tolerance_no_process_holds_is_refused_when_read(field):
    from tactcad.errors import DesignError

    data = with_overrides(read_toml(TI, "design file"), {field: 0.0})
    if field.startswith("tolerances"):
        data["element"].pop("web_tolerance_mm", None)
    with pytest.raises(DesignError) as err:
        plan_from_dict(data)
    text = str(err.value)
    assert f"{field} = 0" in text and ">= 0.01 mm" in text and "wire-edm" in text
    plan_from_dict(with_overrides(read_toml(TI, "design file"), {"element.web_tolerance_mm": 0.01}))
