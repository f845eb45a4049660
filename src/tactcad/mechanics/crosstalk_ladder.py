"""The crosstalk ladder: every array construction's crosstalk levels, one registry, and the
result they all give.

A level models one construction's coupling: the stacked array's clamped stack of bases and
spacers (``stack-*``, :mod:`tactcad.mechanics.stack_crosstalk`), a monolithic comb's row
sheet on its dowel pins and screws (``comb-*``, :mod:`tactcad.mechanics.comb_crosstalk`).
Each is declared once in :data:`CROSSTALK_LEVELS`, cheapest first, with the construction
it describes and the function that reads its inputs from a plan (both imported by name
only when asked, :mod:`tactcad.mechanics.level_registry`). :func:`plan_crosstalk` runs a
plan's level: left out, the cheapest of its construction's (each states its error); a
level of another construction is refused before anything is solved, naming the plan's
own levels to paste.

Every level answers in one shape (:class:`CrosstalkResult`): each gauge's grid-averaged
strain per newton on each tip, each tip's displacement per newton, crosstalk_rel (the
largest off-diagonal over its diagonal), the decoupling matrix, the tip matrix's asymmetry
(Maxwell-Betti), the level's error estimate and its cost.

Units: mm, N, s; strain dimensionless.
"""

from __future__ import annotations

import importlib
import time
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from tactcad.errors import DesignError, TactcadError
from tactcad.mechanics.level_registry import LevelRegistry


@dataclass(frozen=True)
class CrosstalkLevel:
    """One level of the crosstalk ladder: ``--model NAME``, its estimator
    ``function(inputs) -> CrosstalkResult`` in ``module``, its typical cost,
    whether it meshes (its results are then kept in the result store), the
    construction it describes, ``inputs``, the ``"module:function"`` that reads
    its inputs from a plan (``function(plan, **changes)``), and ``verifies``: True
    for the level its construction's verification record, export decoupling files
    and K_obj budget read (:func:`verify_level`; none marked: the cheapest)."""

    name: str
    module: str
    function: str
    cost: str
    meshed: bool = False
    construction: str = "stacked"
    inputs: str = "tactcad.mechanics.stack_crosstalk:stack_inputs"
    verifies: bool = False

    def read_inputs(self, plan: Any, **changes: Any) -> Any:
        """The level's inputs from ``plan`` (``changes``: what its reader takes)."""
        module, function = self.inputs.split(":")
        return getattr(importlib.import_module(module), function)(plan, **changes)


class UnknownCrosstalkModelError(TactcadError, ValueError):
    def __init__(self, model: str):
        super().__init__(f"crosstalk model = {model!r}: allowed {', '.join(crosstalk_models())}")


#: The crosstalk ladder (:mod:`tactcad.mechanics.level_registry`).
CROSSTALK_LADDER: LevelRegistry[CrosstalkLevel] = LevelRegistry("crosstalk",
                                                               UnknownCrosstalkModelError)
#: The crosstalk levels by name, cheapest first within a construction
#: (:func:`register_crosstalk_level` adds to it).
CROSSTALK_LEVELS: dict[str, CrosstalkLevel] = CROSSTALK_LADDER.levels
#: Add a crosstalk level (after the others); ValueError for a name taken.
register_crosstalk_level = CROSSTALK_LADDER.register
#: Every crosstalk level's name (each construction's cheapest first).
crosstalk_models = CROSSTALK_LADDER.names

_COMB = "monolithic-comb"
_COMB_INPUTS = "tactcad.mechanics.comb_crosstalk:comb_inputs"
for _level in (CrosstalkLevel("stack-beam", "tactcad.mechanics.stack_crosstalk",
                              "estimate_stack_beam", "~5 ms"),
               CrosstalkLevel("stack-timoshenko", "tactcad.mechanics.stack_crosstalk",
                              "estimate_stack_timoshenko", "~15 ms", verifies=True),
               CrosstalkLevel("stack-fem3d", "tactcad.mechanics.stack_fem3d",
                              "estimate_stack_fem3d", "~30 s", meshed=True),
               CrosstalkLevel("comb-beam", "tactcad.mechanics.comb_crosstalk",
                              "estimate_comb_beam", "~15 ms", construction=_COMB,
                              inputs=_COMB_INPUTS),
               CrosstalkLevel("comb-fem2d", "tactcad.mechanics.comb_fem2d",
                              "estimate_comb_fem2d", "~5 s", meshed=True, construction=_COMB,
                              inputs=_COMB_INPUTS)):
    register_crosstalk_level(_level)

#: What each construction's levels model, for a refusal of a level of another's.
MODELLED = {"stacked": "the stacked array's clamped stack of element bases and spacers "
                       "between the clamp plates",
            _COMB: "a monolithic comb's row sheet: its spine, posts and elements on the dowel "
                   "pins and screws"}


def construction_levels(construction: str) -> tuple[str, ...]:
    """The levels that describe ``construction``, cheapest first (none: no model of it)."""
    return tuple(n for n, lv in CROSSTALK_LEVELS.items() if lv.construction == construction)


def modelled_constructions() -> tuple[str, ...]:
    """The constructions some crosstalk level describes, in the ladder's order."""
    return tuple(dict.fromkeys(lv.construction for lv in CROSSTALK_LEVELS.values()))


def default_level(construction: str) -> str | None:
    """The level a plan of ``construction`` is given when none is asked: its cheapest
    (each level states its error estimate); None when no level describes it."""
    levels = construction_levels(construction)
    return levels[0] if levels else None


def verify_level(construction: str) -> str | None:
    """The level that answers for ``construction`` wherever one level stands for it: the
    verification matrix's ``max_crosstalk_rel`` record, the export's decoupling files and
    the K_obj budget's crosstalk term. The level its registration marks ``verifies``
    (the stacked array's ``stack-timoshenko``), else its :func:`default_level` (a
    comb's ``comb-beam``); None when no level describes it.

    Args:
        construction: a construction's name (``array.construction``).

    Returns:
        The level's name, or None.
    """
    marked = [n for n in construction_levels(construction) if CROSSTALK_LEVELS[n].verifies]
    return marked[0] if marked else default_level(construction)


def crosstalk_reason(plan: Any) -> str:
    """"" when a crosstalk level describes ``plan``'s construction, else why not (one
    sentence, for the manifest's ``left_out`` and the K_obj budget's crosstalk term).

    Args:
        plan: a design's plan (its ``construction``).

    Returns:
        The reason, or "".
    """
    if construction_levels(plan.construction):
        return ""
    return (f"no crosstalk level describes the construction {plan.construction} (the "
            f"crosstalk ladder models {', '.join(modelled_constructions())})")


def level_for(plan: Any, model: str | None = None) -> CrosstalkLevel:
    """The level that answers ``plan``'s crosstalk: ``model``, or its construction's
    :func:`default_level` when None. Nothing is solved.

    Raises:
        UnknownCrosstalkModelError: ``model`` is no level.
        DesignError: no level describes the plan's construction (``array.construction``),
            or ``model`` describes another construction (``--model``; the plan's own levels
            are its alternatives, each to paste).
    """
    if model is not None and model not in CROSSTALK_LEVELS:
        raise UnknownCrosstalkModelError(model)
    construction = plan.construction
    levels = construction_levels(construction)
    if not levels:
        raise DesignError("array.construction", construction,
                          f"a construction a crosstalk model describes "
                          f"({', '.join(modelled_constructions())})",
                          f"no crosstalk level describes the construction {construction}")
    if model is None:
        return CROSSTALK_LEVELS[levels[0]]
    if model not in levels:
        other = CROSSTALK_LEVELS[model].construction
        raise DesignError(
            "--model", model, f"one of {', '.join(levels)} for a {construction} design",
            f"{model} models {MODELLED.get(other, other)}; a {construction} design's coupling "
            f"is {MODELLED.get(construction, construction)}",
            alternatives=[{"option": f"--model {n}",
                           "words": f"the {construction} design's {n} level "
                                    f"({CROSSTALK_LEVELS[n].cost})"
                                    + (", the default" if n == levels[0] else "")}
                          for n in levels])
    return CROSSTALK_LEVELS[model]


def plan_crosstalk(plan: Any, model: str | None = None, **changes: Any) -> "CrosstalkResult":
    """The crosstalk of ``plan`` at ``model`` (None: its construction's cheapest level),
    ``changes`` passed to the level's input reader (the stack's take
    :func:`tactcad.mechanics.stack_crosstalk.stack_inputs`' changes). A level of another
    construction is refused before the plan's inputs are read or anything is solved.
    A meshed level's result is kept in the result store and reused for the same inputs
    (:meth:`~tactcad.mechanics.level_registry.LevelRegistry.run`).

    Raises:
        UnknownCrosstalkModelError, DesignError: as :func:`level_for`.
        CrosstalkInputError: a change the level's reader does not take.
    """
    level = level_for(plan, model)
    inputs = level.read_inputs(plan, **changes)
    return CROSSTALK_LADDER.run(level.name, (inputs,), {}, label=level.construction)


class CrosstalkInputError(TactcadError, ValueError):
    def __init__(self, field: str, value, allowed: str):
        super().__init__(f"{field} = {value!r}: allowed {allowed}")


# ---------------------------------------------------------------------------
# The result every level gives
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class CrosstalkResult:
    """The array's crosstalk at one level.

    Attributes:
        model: the level's name. elements: element numbers (matrix order).
        sensitivity: n x n, gauge i's grid-averaged strain per newton on tip j (1/N).
        compliance: n x n, tip i's displacement per newton on tip j (mm/N).
        crosstalk_rel: max over i of max_{j != i} |S_ij| / |S_ii|.
        worst: (gauge, loaded element) of that maximum.
        decoupling: inverse of S normalised by its diagonal (S_ij / S_ii).
        asymmetry_rel: max |C - C^T| / max |C| (Maxwell-Betti).
        error_estimate_rel: the level's (its module's docstring). seconds: wall time (s).
        basis: the model in words.
    """

    model: str
    elements: tuple[int, ...]
    sensitivity: np.ndarray
    compliance: np.ndarray
    crosstalk_rel: float
    worst: tuple[int, int]
    decoupling: np.ndarray
    asymmetry_rel: float
    error_estimate_rel: float
    seconds: float
    basis: str

    def as_json(self) -> dict:
        return {"model": self.model, "elements": list(self.elements),
                "crosstalk_rel": self.crosstalk_rel,
                "worst": {"gauge": self.worst[0], "loaded_element": self.worst[1]},
                "error_estimate_rel": self.error_estimate_rel, "seconds": self.seconds,
                "asymmetry_rel": self.asymmetry_rel,
                "sensitivity_strain_per_N": self.sensitivity.tolist(),
                "compliance_mm_per_N": self.compliance.tolist(),
                "decoupling": self.decoupling.tolist(), "basis": self.basis}


def crosstalk_of(S: np.ndarray) -> tuple[float, tuple[int, int]]:
    """(max_i max_{j != i} |S_ij| / |S_ii|, (i, j) of it); 0 for one element."""
    ratio = np.abs(S) / np.abs(np.diag(S))[:, None]
    np.fill_diagonal(ratio, 0.0)
    i, j = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
    return float(ratio[i, j]), (int(i), int(j))


def decoupling_matrix(S: np.ndarray) -> np.ndarray:
    """Inverse of S normalised by its diagonal: forces = D @ (readings / own sensitivity)."""
    return np.linalg.inv(S / np.diag(S)[:, None])


def asymmetry_of(C: np.ndarray) -> float:
    """max |C - C^T| / max |C| of a tip matrix (0: Maxwell-Betti holds exactly)."""
    return float(np.max(np.abs(C - C.T)) / np.max(np.abs(C)))


def result_of(model: str, numbers: tuple[int, ...], S: np.ndarray, C: np.ndarray,
              error: float, t0: float, basis: str,
              clock: Callable[[], float] = time.perf_counter) -> CrosstalkResult:
    """The :class:`CrosstalkResult` of the matrices ``S`` and ``C`` (plan order ``numbers``),
    the level's error estimate and its start time ``t0`` (``clock``'s)."""
    rel, (i, j) = crosstalk_of(S)
    return CrosstalkResult(model, tuple(numbers), S, C, rel, (numbers[i], numbers[j]),
                           decoupling_matrix(S), asymmetry_of(C), error, clock() - t0, basis)
