"""The element-stiffness ladder and its comparison with the paper.

Four levels, cheapest first: ``closed-form`` (exact Euler-Bernoulli notch
integrals + arm bending + shear, FEM-fitted correction), ``beam`` (1D
Timoshenko along the real profile), ``fem2d`` (P2 triangles, plane stress or
strain, Richardson error), ``fem3d`` (P2 tetrahedra, the reference). Every
level returns a :class:`~tactcad.mechanics.stiffness_result.StiffnessResult` with its
cost (wall time) and error estimate. Heavy modules are imported only when
their level is asked for.

The levels are declared once, in :data:`LEVELS` (:class:`Level`: name,
estimator, whether it meshes, typical cost); every command's ``--model``
choices and help, the strength study, the read-out and the Python API read
it. A new level is one estimator function plus one :func:`register_level`.

Units: mm, N, MPa, N/mm, s.
"""

from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Iterator

from tactcad.errors import TactcadError
from tactcad.mechanics.level_registry import LevelRegistry
from tactcad.mechanics.stiffness_result import StiffnessResult

if TYPE_CHECKING:  # annotations only: the design model costs a second to import, and every
    # command's --help reads the levels (models()) from here
    from tactcad.design.array_plan import ElementGeometry, Material


@dataclass(frozen=True)
class Level:
    """One rung of the stiffness ladder, declared once: every command's
    ``--model`` choices and help, the strength study and the read-out read it.

    Attributes:
        name: the level's name (``--model NAME``).
        module, function: its estimator, imported when the level is asked
            for: ``function(g, material, *, element=None, **options)`` ->
            :class:`~tactcad.mechanics.stiffness_result.StiffnessResult`.
        meshed: a FEM level: it reports its mesh levels through a
            ``progress`` option, writes fields and gives the peak stress
            from its own mesh; otherwise the closed-form stress formula serves.
        cost: its typical wall time per distinct element, for help texts.
    """

    name: str
    module: str
    function: str
    meshed: bool
    cost: str


class UnknownModelError(TactcadError, ValueError):
    """A level name that is not a ladder level.

    Args:
        model: the name given.
        also: other values the caller takes besides the levels (e.g. ``auto``), listed
            first in the message.
    """

    def __init__(self, model: str, also: tuple[str, ...] = ()):
        super().__init__(f"model = {model!r}: allowed {', '.join((*also, *models()))}")


#: The stiffness ladder (:mod:`tactcad.mechanics.level_registry`).
LADDER: LevelRegistry[Level] = LevelRegistry("ladder", UnknownModelError)
#: The ladder's levels by name, cheapest first (:func:`register_level` adds to it).
LEVELS: dict[str, Level] = LADDER.levels
#: Add a level to the ladder (after the others); ValueError for a name taken.
register_level = LADDER.register
#: Every ladder level's name, cheapest first.
models = LADDER.names
#: ``closed-form ~1 ms, beam ~10 ms, ...``: the levels with their cost, for help texts.
levels_help = LADDER.help

for _level in (Level("closed-form", "tactcad.mechanics.closed_form", "estimate_closed_form",
                     meshed=False, cost="~1 ms"),
               Level("beam", "tactcad.mechanics.beam", "estimate_beam", meshed=False,
                     cost="~10 ms"),
               Level("fem2d", "tactcad.mechanics.fem.fem2d", "estimate_fem2d", meshed=True,
                     cost="~1 s"),
               # measured on two cores: 13 s for the paper's 7 mm element, about 100 s for a
               # 2 x 8 strip's thin 7075 elements (their finer mesh); a die's two beams about
               # 1.5 min for the shipped dies (67 000 ... 128 000 unknowns a finer mesh), 865 s
               # wall (282 s CPU, 3.6 GB) for an atlas die of 206 000 (a 1 um sliver between
               # its posts' and beams' edges)
               Level("fem3d", "tactcad.mechanics.fem.fem3d", "estimate_fem3d", meshed=True,
                     cost="10 s-2 min an array's element, a silicon die's two beams 1.5-15 "
                          "min and up to 4 GB, growing with the mesh (progress on stderr "
                          "names its unknowns)")):
    register_level(_level)


def meshed_models() -> tuple[str, ...]:
    """The FEM levels (:attr:`Level.meshed`)."""
    return tuple(n for n, level in LEVELS.items() if level.meshed)


def is_meshed(model: str) -> bool:
    """True for a FEM level (False for an unknown name)."""
    level = LEVELS.get(model)
    return level is not None and level.meshed


#: The built-in levels' names (what :func:`models` gives before any registration).
MODELS = models()


def estimate(model: str, g: ElementGeometry, material: Material, *, element: int | None = None,
             **options) -> StiffnessResult:
    """Tip stiffness of one element at the given ladder level.

    ``element`` and the level's ``options`` are keyword-only (each level's
    estimator takes them so). A FEM level's result is kept in the result
    store and reused for the same geometry, material and options
    (:meth:`~tactcad.mechanics.level_registry.LevelRegistry.run`), whichever
    element number asks.

    Raises:
        UnknownModelError: ``model`` is not a level of :data:`LEVELS`.
    """
    kept = _KEPT_CLOSED_FORM.get()
    if kept is not None and model == CLOSED_FORM and not options:
        key = (g, material)
        result = kept.get(key)
        if result is None:
            result = kept[key] = LADDER.run(model, (g, material), options, label=g.part_name)
    else:
        result = LADDER.run(model, (g, material), options, label=g.part_name)
    return result if result.element == element else replace(result, element=element)


#: The closed-form level's name (the estimates :func:`closed_form_estimates_kept` keeps).
CLOSED_FORM = "closed-form"
#: Closed-form estimates already made inside :func:`closed_form_estimates_kept` (None
#: outside it), by (geometry, material).
_KEPT_CLOSED_FORM: ContextVar[dict | None] = ContextVar("kept_closed_form_estimates",
                                                        default=None)


@contextmanager
def closed_form_estimates_kept() -> Iterator[None]:
    """Keep every closed-form :func:`estimate` (no options) made while inside, by geometry
    and material: a search judging a candidate reads the same element's closed form for its
    stops, limits, stresses, K band and verification matrix, and the closed form is a pure
    function of them (its range warnings are said the first time only, so enter it where
    they are not said at all: :func:`tactcad.mechanics.correction.range_warnings_unsaid`).
    Nested uses share the outer one's estimates.

    Returns:
        A context manager; the estimates are dropped on leaving the outermost (a kept
        result's ``wall_time_s`` is its first evaluation's).
    """
    from tactcad.store import memo_scope

    with memo_scope(_KEPT_CLOSED_FORM):
        yield


def gauge_rise_error_rel(model: str) -> float:
    """The error of ``model``'s K rise from the bonded gauge, relative to the rise
    (:data:`tactcad.mechanics.bonded_layer.CLOSED_FORM_LAYER_ERROR_REL` and
    :data:`~tactcad.mechanics.bonded_layer.BEAM_LAYER_ERROR_REL`; 0 for a finite-element
    level: it meshes the layer, and its discretisation error is K's own)."""
    from tactcad.mechanics.bonded_layer import BEAM_LAYER_ERROR_REL, CLOSED_FORM_LAYER_ERROR_REL

    return {"closed-form": CLOSED_FORM_LAYER_ERROR_REL,
            "beam": BEAM_LAYER_ERROR_REL}.get(model, 0.0)


def gauge_k_rise(model: str, g: ElementGeometry, material: Material) -> float:
    """How much the bonded gauge ``g`` carries raises its K at ``model``, relative:
    K(g) / K(g as cut) - 1 (0 for a bare ``g``); both from :func:`estimate` (a FEM level's
    solves from the result store when kept).

    Raises:
        UnknownModelError: ``model`` is not a level of :data:`LEVELS`.
    """
    if g.gauge is None:
        return 0.0
    return (estimate(model, g, material).stiffness_N_per_mm
            / estimate(model, g.bare(), material).stiffness_N_per_mm - 1.0)
