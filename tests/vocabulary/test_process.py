"""The cut-process registry: every rule's figure at its bounds, its source,
the design file's choice and the refusal of an unknown process."""

import pickle

import pytest
from process_variants import cut_by

from tactcad.design.array_plan import (EXAMPLES, EdmRules, load_design, plan_from_dict,
                                       with_overrides)
from tactcad.errors import DesignError
from tactcad.vocabulary.process import (CUT_PROCESSES, ETCH_FACTOR, ETCH_FLOOR_MM, ETCH_THIN_MM,
                                        ETCH_TOLERANCE_FLOOR_MM, LASER_KERF_MM, Method, Process,
                                        cut_process, process_names)
from tactcad.vocabulary.schema import read_toml

TI = str(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")
WIRE = EdmRules(0.25, 0.025, 0.8)


def test_the_three_processes_are_registered_wire_edm_first():
    assert process_names()[:3] == ("wire-edm", "photochemical-etching", "laser-cutting")


@pytest.mark.parametrize("name", sorted(CUT_PROCESSES))
@pytest.mark.parametrize("t", [0.05, 0.3, 1.0])
def test_every_figure_names_its_rule_and_source(name, t):
    limits = cut_process(name).limits(t, WIRE, "stainless steel")
    for key, fig in limits.figures().items():
        assert fig.value_mm >= 0, key
        assert fig.rule and fig.source, key


def test_unknown_process_is_refused_naming_the_allowed_ones():
    with pytest.raises(DesignError) as exc:
        cut_process("etching")
    for name in CUT_PROCESSES:
        assert name in str(exc.value)
    assert exc.value.field == "element.process"


def test_process_pickles_with_its_key():
    p = cut_process("laser-cutting").part_process()
    q = pickle.loads(pickle.dumps(p))
    assert (q, q.method, q.key) == ("laser cutting from sheet", Method.SHEET, "laser-cutting")
    assert Process("milling", Method.PLATE).key is None


def test_wire_edm_limits_follow_the_design_wire():
    lim = cut_process("wire-edm").limits(3.0, WIRE)
    assert lim.min_inside_radius_mm.value_mm == pytest.approx(0.125 + 0.025)
    assert lim.min_slot_mm.value_mm == pytest.approx(0.25 + 0.05)
    assert lim.compensation_per_side_mm.value_mm == 0.0


@pytest.mark.parametrize("material, factor", [("stainless steel 1.4310", 1.1),
                                              ("Ti-6Al-4V-annealed", 1.5)])
def test_etch_hole_is_a_factor_of_the_thickness_by_alloy(material, factor):
    lim = cut_process("photochemical-etching").limits(0.3, WIRE, material)
    assert lim.min_hole_mm.value_mm == pytest.approx(factor * 0.3)
    assert lim.min_web_mm.value_mm == pytest.approx(0.3)


def test_etch_thin_foil_takes_the_floor():
    t = ETCH_THIN_MM * 0.5
    lim = cut_process("photochemical-etching").limits(t, WIRE, "stainless")
    assert lim.min_hole_mm.value_mm == pytest.approx(max(t, ETCH_FLOOR_MM))
    assert lim.min_web_mm.value_mm == pytest.approx(ETCH_FLOOR_MM)
    assert lim.tolerance_mm.value_mm == pytest.approx(ETCH_TOLERANCE_FLOOR_MM)


def test_etch_compensation_is_half_the_thickness_over_the_etch_factor():
    lim = cut_process("photochemical-etching").limits(0.4, WIRE, "stainless")
    assert lim.compensation_per_side_mm.value_mm == pytest.approx(0.2 / ETCH_FACTOR)
    assert lim.tolerance_mm.value_mm == pytest.approx(0.06)


@pytest.mark.parametrize("t, tol", [(1.0, 0.1), (1.01, 0.15)])
def test_laser_tolerance_steps_at_one_mm(t, tol):
    lim = cut_process("laser-cutting").limits(t, WIRE)
    assert lim.tolerance_mm.value_mm == tol
    assert lim.kerf_mm.value_mm == LASER_KERF_MM
    assert lim.min_web_mm.value_mm == pytest.approx(max(0.7 * t, LASER_KERF_MM))


def test_tab_rule_by_part_size():
    tabs = cut_process("wire-edm").shop.tabs
    assert tabs.tabs_for(20.0) == (1, 0.3)
    assert tabs.tabs_for(20.01) == (2, 0.5)
    assert tabs.tabs_for(150.01) == (0, 0.0)
    assert cut_process("photochemical-etching").shop.tabs is None


def _ti(**overrides):
    return with_overrides(read_toml(TI, "design file"), overrides)


def test_design_chooses_the_element_process():
    assert load_design(TI).slots[0].geometry.process == "wire-edm"
    plan = plan_from_dict(_ti(**cut_by("photochemical-etching", 0.3)))
    assert {s.geometry.process for s in plan.slots} == {"photochemical-etching"}


def test_design_refuses_an_unknown_process_naming_the_allowed_ones():
    with pytest.raises(DesignError) as exc:
        plan_from_dict(_ti(**{"element.process": "waterjet"}))
    assert "wire-edm, photochemical-etching, laser-cutting" in str(exc.value)


@pytest.mark.parametrize("process, t, ok", [
    ("wire-edm", 0.5, True), ("wire-edm", 0.49, False),
    ("photochemical-etching", 1.5, True), ("photochemical-etching", 1.51, False),
    ("laser-cutting", 0.3, True)])
def test_sheet_lies_in_the_process_range(process, t, ok):
    data = _ti(**(cut_by(process, t) if ok else {"element.process": process,
                                                 "sheet.thickness_mm": t}))
    if ok:
        plan_from_dict(data)
        return
    with pytest.raises(DesignError) as exc:
        plan_from_dict(data)
    assert exc.value.field == "sheet.thickness_mm" and process in str(exc.value)
