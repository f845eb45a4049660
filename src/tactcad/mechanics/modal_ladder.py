"""The modal ladder: natural frequencies of one element, cheapest level first.

Three levels, declared once in :data:`MODAL_LEVELS` (as the stiffness
ladder's :data:`tactcad.mechanics.ladder.LEVELS`): ``closed-form`` (Rayleigh
quotients, first in-plane mode and an estimate of the first out-of-plane one), ``fem2d`` (plane-stress P2, in-plane
modes) and ``fem3d`` (3D P2 half model in both mid-plane families, the
reference). Every ``--model`` choice of ``tactcad modal``, its help, the
verification record and ``bench modal`` read it. Each level returns a
:class:`~tactcad.mechanics.modal_result.ModalResult` with its frequencies
(Hz), cost (s) and error estimate. A stiffness level without a modal level
of its own (``beam``) is served by the nearest cheaper one
(:func:`modal_level_for`).

Units: mm, N, Hz, s.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from tactcad.design.array_plan import ElementGeometry, Material
from tactcad.errors import TactcadError
from tactcad.mechanics.level_registry import LevelRegistry
from tactcad.mechanics.modal_result import ModalResult


@dataclass(frozen=True)
class ModalLevel:
    """One rung of the modal ladder.

    Attributes:
        name: ``--model NAME``.
        module, function: its estimator, imported when asked for:
            ``function(g, material, *, element=None, modes=3, progress=None,
            keep_shapes=False)`` -> :class:`ModalResult`.
        meshed: a FEM level (mode shapes, progress lines).
        cost: typical wall time per distinct element, for help texts.
        families: the mode families it resolves over the whole design domain
            ("in-plane": bending in the sheet's plane, the sensing direction;
            "out-of-plane": bending out of it and twisting). The closed form
            also estimates the first out-of-plane mode, verified only in sheets
            of three webs and more, so it does not list that family.
    """

    name: str
    module: str
    function: str
    meshed: bool
    cost: str
    families: tuple[str, ...] = ("in-plane",)


class UnknownModalModelError(TactcadError, ValueError):
    def __init__(self, model: str):
        super().__init__(f"model = {model!r}: allowed {', '.join(modal_models())}")


#: The modal ladder (:mod:`tactcad.mechanics.level_registry`).
MODAL_LADDER: LevelRegistry[ModalLevel] = LevelRegistry("modal", UnknownModalModelError)
#: The modal levels by name, cheapest first (:func:`register_modal_level` adds to it).
MODAL_LEVELS: dict[str, ModalLevel] = MODAL_LADDER.levels
#: Add a level to the modal ladder (after the others); ValueError for a name taken.
register_modal_level = MODAL_LADDER.register
#: Every modal level's name, cheapest first.
modal_models = MODAL_LADDER.names
#: ``closed-form ~5 ms, fem2d ~2 s, ...``: the levels with their cost.
modal_levels_help = MODAL_LADDER.help


for _level in (ModalLevel("closed-form", "tactcad.mechanics.modal_closed_form",
                          "estimate_modal_closed_form", meshed=False, cost="~5 ms"),
               ModalLevel("fem2d", "tactcad.mechanics.fem.fem_modal", "estimate_modal_fem2d",
                          meshed=True, cost="~2 s"),
               ModalLevel("fem3d", "tactcad.mechanics.fem.fem_modal", "estimate_modal_fem3d",
                          meshed=True, cost="~20 s",
                          families=("in-plane", "out-of-plane"))):
    register_modal_level(_level)


def modal_level_for(stiffness_model: str) -> str:
    """The modal level that serves a stiffness-ladder level: the same name
    when the modal ladder has it, else the nearest cheaper modal level."""
    from tactcad.mechanics.ladder import models

    if stiffness_model in MODAL_LEVELS:
        return stiffness_model
    ladder = models()
    chosen = modal_models()[0]
    for name in ladder[:ladder.index(stiffness_model) + 1] if stiffness_model in ladder else ():
        if name in MODAL_LEVELS:
            chosen = name
    return chosen


def estimate_modes(model: str, g: ElementGeometry, material: Material, *,
                   element: int | None = None, modes: int = 3, **options) -> ModalResult:
    """The lowest ``modes`` natural frequencies (Hz) of one element at ``model``.

    A FEM level's result is kept in the result store and reused for the same
    geometry, material, mode count and options
    (:meth:`~tactcad.mechanics.level_registry.LevelRegistry.run`), but for
    one with its mode shapes (``keep_shapes``), which is solved afresh.

    Raises:
        UnknownModalModelError: ``model`` is not a level of :data:`MODAL_LEVELS`.
        DesignError: the material has no density.
        ValueError: modes < 1.
    """
    result = MODAL_LADDER.run(model, (g, material), {"modes": modes, **options},
                              label=g.part_name, keep=not options.get("keep_shapes"))
    return result if result.element == element else replace(result, element=element)
