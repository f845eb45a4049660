"""drawings/ split by responsibility: the sheet frame is a public module, no
module borrows another's private names, and no drawing module holds physics
or reads data files itself."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from tactcad.mechanics.closed_form import web_tolerance_stiffness_change
from tactcad.paper.data import largest_equal_arm_spread, table1

SRC = Path(__file__).resolve().parents[2] / "src" / "tactcad"


def test_web_tolerance_moves_stiffness_by_the_thin_hinge_law():
    up, down = web_tolerance_stiffness_change(0.25, 0.02)
    assert up == pytest.approx(1.08 ** 2.5 - 1) and down == pytest.approx(1 - 0.92 ** 2.5)
    assert up > down > 0  # K rises faster than linearly with t
    assert web_tolerance_stiffness_change(0.06, 0.08)[1] == 1.0  # no web left at the low limit
    assert web_tolerance_stiffness_change(0.3, 0.0) == (0.0, 0.0)
    for bad in ((0.0, 0.01), (-0.2, 0.01), (0.2, -0.01), (float("nan"), 0.01)):
        with pytest.raises(ValueError, match="web_mm"):
            web_tolerance_stiffness_change(*bad)


def test_table1_spread_comes_from_the_paper_data():
    arm, k_low, k_high, ratio = largest_equal_arm_spread()
    same_arm = [r.stiffness_N_per_mm for r in table1() if r.flexing_arm_length_mm == arm]
    assert len(same_arm) > 1 and (k_low, k_high) == (min(same_arm), max(same_arm))
    assert ratio == pytest.approx(k_high / k_low) and ratio > 1


def _imports(path: Path):
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module:
            yield node.module, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            yield from ((a.name, []) for a in node.names)


def test_drawings_borrow_no_private_names_and_parse_no_data():
    bad = []
    for path in sorted((SRC / "drawings").glob("*.py")):
        text = path.read_text(encoding="utf-8")
        for module, names in _imports(path):
            if module.startswith("tactcad.") and any(n.startswith("_") for n in names):
                bad.append(f"{path.name}: private name from {module}")
            if module == "csv":
                bad.append(f"{path.name}: reads CSV itself")
        if "** 2.5" in text:
            bad.append(f"{path.name}: a stiffness law (belongs to mechanics)")
    assert not bad, bad


def test_compose_is_only_the_assembly_of_a_sheet():
    assert len((SRC / "drawings" / "compose.py").read_text().splitlines()) < 400


def test_gauge_note_names_the_stc_and_the_thermal_drift_when_required():
    from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides
    from tactcad.drawings.design_notes import gauge_note

    def note(**o):
        plan = plan_from_dict(with_overrides(default_design_data(), o))
        return gauge_note(plan, plan.element(1).geometry)

    plain = note()
    assert "Gauge STC 23.4 ppm/K" in plain and "Thermal drift" not in plain
    stated = note(**{"requirements.max_thermal_drift_N_per_K": 0.5,
                     "readout.gauge_stc_ppm_per_K": 10.8})
    assert "Gauge STC 10.8 ppm/K" in stated and "required <= 0.5 N/K" in stated


def test_the_web_note_states_the_k_change_verify_reads_not_the_thin_hinge_law():
    # the drawing printed +34 % / -28 % (t^2.5) where verify's K band read +31.2 % / -26.4 %
    from tactcad.api import load
    from tactcad.drawings.design_notes import element_web_note
    from tactcad.in_use.kobj_budget import web_tolerance_k_change, web_tolerance_k_rel
    from tactcad.design.array_plan import EXAMPLES

    plan = load(str(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")).plan
    for g in plan.distinct_elements.values():
        up, dn = web_tolerance_k_change(g, plan.material)
        assert max(up, dn) == web_tolerance_k_rel(g, plan.material)
        assert f"+{up * 100:.0f} % / -{dn * 100:.0f} %" in element_web_note(plan, g)
