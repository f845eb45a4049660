"""The process check group: each cut part against its process's rules,
passing at a rule's bound and failing just past it, with the feature, value,
rule and source in the message."""

from __future__ import annotations

import warnings
from dataclasses import replace

import pytest

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
    sp = _element(**{"element.process": process, "sheet.thickness_mm": t})
    least = sp.limits.min_web_mm.value_mm
    at = _result(part_rule_checks(replace(sp, web_thickness_mm=least)), "process_min_web", "flexure web")
    below = _result(part_rule_checks(replace(sp, web_thickness_mm=least - 0.001)),
                    "process_min_web", "flexure web")
    assert at.passed and not below.passed
    assert process in below.detail and f"{least:.4g} mm" in below.detail
    assert sp.limits.min_web_mm.source in below.detail


def test_the_etched_ti_example_fails_on_its_thin_web_and_fine_tolerance():
    sp = _element(**{"element.process": "photochemical-etching", "sheet.thickness_mm": 0.3})
    failed = {r.check for r in part_rule_checks(sp) if not r.passed}
    assert failed == {"process_min_web", "process_tolerance"}
    tol = sp.limits.tolerance_mm.value_mm
    assert tol == pytest.approx(0.045)
    assert _result(part_rule_checks(replace(sp, web_tolerance_mm=tol)), "process_tolerance").passed


def test_hole_fails_below_the_etch_minimum():
    sp = _element(**{"element.process": "photochemical-etching", "sheet.thickness_mm": 1.5})
    least = sp.limits.min_hole_mm.value_mm  # 1.5 x 1.5 mm for titanium: 2.25 mm < the 2.4 mm hole
    assert _result(part_rule_checks(sp), "process_min_hole").passed
    small = replace(sp.profile, holes=tuple(replace(h, radius=least / 2 - 0.001)
                                             for h in sp.profile.holes))
    assert not _result(part_rule_checks(replace(sp, profile=small)), "process_min_hole").passed
