"""Specs carry what their writers need: builders, drawings and DXF read the
part's own geometry, never the plan's element table; the array's parts are
made once per plan."""

from __future__ import annotations

import re
from pathlib import Path

from tactcad.catalogue import array_catalogue as catalogue
from tactcad.design.array_plan import plan_from_dict

SRC = Path(__file__).resolve().parents[2] / "src" / "tactcad"


def test_array_specs_carry_their_geometry(plan):
    specs = catalogue.array_parts(plan)
    for name, g in plan.distinct_elements.items():
        assert specs[name].geometry is g
        assert g.web_centre_mm == (g.hinge_x_mm, g.base_height_mm - g.web_thickness_mm / 2)
        assert g.contact_centre_mm == (g.tip_centre_x_mm, g.tip_top_y_mm)
    assert specs["clamp_plate"].geometry is plan.clamp
    assert specs[catalogue.nut_name(plan.bolt)].geometry is plan.bolt


def test_array_parts_are_made_once_per_plan(design_data, monkeypatch):
    from tactcad.partlib.array import element

    calls = []
    real = element.element_profile
    monkeypatch.setattr(element, "element_profile", lambda g: calls.append(g) or real(g))
    plan = plan_from_dict(design_data)
    first = catalogue.array_parts(plan)
    made = len(calls)
    assert made == len(plan.distinct_elements)
    again = catalogue.array_parts(plan)
    assert len(calls) == made and again == first and again is not first  # a fresh dict


def test_no_writer_reaches_back_into_the_plan_for_an_element():
    offenders = [p.relative_to(SRC).as_posix() for p in SRC.rglob("*.py")
                 if p.parts[-2] in ("solids", "array", "drawings", "export", "checks")
                 and re.search(r"distinct_elements\[", p.read_text(encoding="utf-8"))]
    assert not offenders, offenders


def test_every_part_has_a_typed_process(project):
    """The shop reads the process's method, never its words: a bought part
    has no stock, every fabricated one a blank of its method."""
    import pickle

    import pytest

    from tactcad.assembly.inventory import design_assemblies
    from tactcad.catalogue.shop import stock_size

    specs, _ = design_assemblies(project)
    for spec in specs.values():
        assert isinstance(spec.process, catalogue.Process), spec.name
        assert (spec.process.method is catalogue.Method.BOUGHT) == (spec.kind == "purchased")
        if spec.kind == "fabricated":
            assert stock_size(spec)
        else:
            with pytest.raises(ValueError, match="no raw stock"):
                stock_size(spec)
    p = catalogue.Process("milling from plate", catalogue.Method.PLATE)
    again = pickle.loads(pickle.dumps(p))
    assert again == "milling from plate" and again.method is catalogue.Method.PLATE
    with pytest.raises(TypeError, match="Method"):
        catalogue.Process("turning", "bar")
