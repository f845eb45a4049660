"""The reference-load registry: the paper's load is one source, asked only for
a design that cites the paper; a new design has none; a taken name is refused."""

from __future__ import annotations

import pytest

from tactcad.design.array_plan import DEFAULT_DESIGN, EXAMPLES, load_design
from tactcad.studies.reference_loads import (REFERENCE_LOAD_SOURCES, ReferenceLoadSource,
                                             reference_load_of, register_reference_load,
                                             strength_summary)

TI = str(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")


def test_the_paper_is_one_registered_source():
    assert REFERENCE_LOAD_SOURCES["paper"].module == "tactcad.paper.paper_load"


def test_a_new_design_has_no_reference_load_and_its_records_none():
    plan = load_design(TI)
    assert reference_load_of(plan) is None
    assert not any("stress_MPa_at_reference_load" in r for r in strength_summary(plan))


def test_the_paper_design_keeps_its_load():
    plan = load_design(DEFAULT_DESIGN)
    assert reference_load_of(plan).force_N == 2.0
    assert all("stress_MPa_at_reference_load" in r for r in strength_summary(plan))


def test_a_taken_name_is_refused():
    with pytest.raises(ValueError, match="registered already"):
        register_reference_load(ReferenceLoadSource("paper", lambda raw: False, "x", "y"))
