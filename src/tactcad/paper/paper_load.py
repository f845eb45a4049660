"""The paper's design load: the 2 N tip load of its FEM design study, and the
strength figures at it for a design that cites the paper.

The general strength code (:mod:`tactcad.mechanics.element_strength`) states
an element's stress at a reference load only when its caller gives one; the
paper's load is the paper's design's, never a default for a new design. The
functions here give it for a design whose requirements cite the paper
(:func:`tactcad.design.requirements_section.cites_paper`) and none otherwise;
the CLI, the API and the export call them.

Units: N, MPa.
"""

from __future__ import annotations

from tactcad.design.array_plan import ElementGeometry, Material, Plan
from tactcad.design.requirements_section import cites_paper
from tactcad.mechanics.element_strength import ElementStress, ReferenceLoad, StrengthRecord
from tactcad.vocabulary.material_library import StrengthSettings

#: The paper's FEM design-study tip load (N).
PAPER_LOAD_N = 2.0
PAPER_LOAD = ReferenceLoad(PAPER_LOAD_N, "the paper's")


def paper_load_of(plan: Plan) -> ReferenceLoad | None:
    """:data:`PAPER_LOAD` for a design that cites the paper, else None."""
    return PAPER_LOAD if cites_paper(plan.raw) else None


def strength_summary(plan: Plan, model: str = "closed-form") -> list[dict]:
    """:func:`tactcad.studies.reference_loads.strength_summary`: the records at
    the design's rated full-scale force, with the paper's load for a design that
    cites the paper (the paper's hook there, :func:`paper_load_of`)."""
    from tactcad.studies.reference_loads import strength_summary as summary

    return summary(plan, model)
