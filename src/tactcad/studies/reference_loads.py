"""The reference loads a design's strength records state besides its rated
full-scale force, as a registry: each source says which designs it answers
for (a test on the design's tables that needs nothing of the source) and
names the function that gives the load, imported only for such a design.

The paper's 2 N design-study load is one source (:mod:`tactcad.paper.paper_load`,
for a design whose requirements cite the paper): a design that does not cite
the paper never imports the paper's package on its way through ``export``,
``check``, ``design`` or ``strength``. The strength records at the rated
full-scale force with the design's reference load are
:func:`strength_summary`'s, the one call the manifest, the review page and
the commands make.

Units: N.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Any, Callable, Mapping

from tactcad.design.array_plan import Plan
from tactcad.design.requirements_section import cites_paper
from tactcad.mechanics import element_strength as strength
from tactcad.mechanics.element_strength import ReferenceLoad


@dataclass(frozen=True)
class ReferenceLoadSource:
    """One source of a reference load.

    Attributes:
        name: the source's name (``paper``).
        applies: ``applies(raw) -> bool`` on the design's tables (``plan.raw``);
            it must not import the source's module.
        module, function: ``function(plan) -> ReferenceLoad | None``, imported
            only for a design the source applies to.
    """

    name: str
    applies: Callable[[Mapping[str, Any]], bool]
    module: str
    function: str


#: The sources in registration order; the first that applies gives the load.
REFERENCE_LOAD_SOURCES: dict[str, ReferenceLoadSource] = {}


def register_reference_load(source: ReferenceLoadSource) -> None:
    """Add a source of reference loads (asked after the others).

    Raises:
        ValueError: the name is taken.
    """
    if source.name in REFERENCE_LOAD_SOURCES:
        raise ValueError(f"a reference-load source {source.name!r} is registered already")
    REFERENCE_LOAD_SOURCES[source.name] = source


def reference_load_of(plan: Plan) -> ReferenceLoad | None:
    """The reference load of ``plan`` from the first source that applies to
    it (its module imported now), or None: a new design has none."""
    for source in REFERENCE_LOAD_SOURCES.values():
        if source.applies(plan.raw):
            return getattr(importlib.import_module(source.module), source.function)(plan)
    return None


def strength_summary(plan: Plan, model: str = "closed-form") -> list[dict]:
    """:func:`tactcad.mechanics.element_strength.strength_summary` at the
    design's rated full-scale force (:func:`~tactcad.studies.verification.rated_full_scale_force`),
    with its reference load (:func:`reference_load_of`) when it has one.

    Raises:
        ValueError: unknown model.
        DesignError: the material has no yield strength.
    """
    from tactcad.studies.verification import rated_full_scale_force

    return strength.strength_summary(plan, rated_full_scale_force(plan), model,
                                     reference_load_of(plan))


register_reference_load(ReferenceLoadSource("paper", cites_paper, "tactcad.paper.paper_load",
                                            "paper_load_of"))
