"""Rig design file (``hardware/rigs.toml``) -> validated, immutable rig plan.

The three test rigs of the paper (calibration under a force gauge on
micro-stages, rubber-sample stiffness on a wheeled cart, array evaluation on
a vertical linear axis with 100 g weights) need dimensions the paper does not
give. They live in their own file, each with a one-line reason under
``[assumptions]``, and are read by the same schema mechanism as the array
design (:mod:`tactcad.vocabulary.schema`): every bad value is reported, all at once,
naming the field, the value and the allowed range. Values that follow from the
array (the indenter's contact face, the calibration element, the bracket
width, the stages' travel) may be left out: they are derived from the array's
plan, and a value the user did not set never fails. No CAD kernel here.

Each rig part is one module of :mod:`tactcad.partlib` (its table, its
derivation, its spec); this module builds the file's schema from the
modules' tables, derives the parts in the order their needs give and keeps
the file's own tables (``[rigs]``, ``[calibration]``, ``[assumptions]``).

Units: mm, N, g.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping, Optional

from pydantic import create_model

from tactcad.design.array_plan import DEFAULT_DESIGN, Plan
from tactcad.design.construction_registry import check_test_rigs
from tactcad.partlib.base import PartData
from tactcad.partlib.registry import derivation_order, rig_parts_lib
from tactcad.partlib.sample import stiffnesses
from tactcad.vocabulary.schema import (Derived, Problems, Section, Text, content_hash, integer,
                                       number, read_assumptions, read_toml, validate)

DEFAULT_RIGS = DEFAULT_DESIGN.parent / "rigs.toml"  # the default design's


@dataclass(frozen=True)
class RigDesign:
    """Validated rig dimensions, immutable. Build with :func:`load_rigs`.

    Attributes:
        library: every rig part's derived data (:mod:`tactcad.partlib`), by
            its key, in :attr:`RigPart.order <tactcad.partlib.base.RigPart>`.
        derived: the parts' derived dimensions with their reasons, in that order.
        evaluation_preload_N, beyond_rating_reason, beyond_rating_load_N,
            beyond_rating_rated_N: ``[evaluation]``
            (:class:`EvaluationSection`; None where left out).
    """

    name: str
    description: str
    source: str
    rigs_hash: str
    calibration_element: int
    derived: tuple[Derived, ...]
    assumptions: tuple[tuple[str, str], ...]
    library: Mapping[str, PartData] = field(default_factory=dict)
    evaluation_preload_N: float | None = None
    beyond_rating_reason: str | None = None
    beyond_rating_load_N: float | None = None
    beyond_rating_rated_N: float | None = None

    def part(self, key: str) -> Any:
        """The geometry (the data its builder reads) of part module ``key``.

        Raises:
            KeyError: no part module ``key``.
        """
        return self.library[key].geometry

    @property
    def sample_stiffness_N_per_mm(self) -> tuple[float, ...]:
        """The measured stiffness of every rubber sample (N/mm), in the file's order."""
        return stiffnesses(self.library["sample"])


# ---------------------------------------------------------------------------
# The rig file's schema: its own tables and one table per part module
# ---------------------------------------------------------------------------
class RigsSection(Section):
    name: Text
    description: Text


class CalibrationSection(Section):
    element: Optional[integer(1, 1000)] = None  # default: the stiffest element (shortest arm)


class EvaluationSection(Section):
    """``[evaluation]``: the array evaluation rig's loads besides its weights.

    ``preload_N``: the moving axis's weight on the sample before any weight is
    added (N; the paper's 3.235 N; a counterbalanced axis's net weight); left
    out, the rig's loads are unknown and ``check`` fails them.
    ``beyond_rating_reason``: why a rig that loads an element beyond the
    design's rated full-scale force is kept (``check`` then passes it, saying
    so); left out, such a rig fails.
    ``beyond_rating_load_N``, ``beyond_rating_rated_N``: what the reason was judged for,
    the most loaded element's tip force (N) and the design's rated full-scale force (N)
    then; the reason keeps the rig only while the load stays at most the one and the
    rating at least the other, so an edited design does not pass on a stale reason.
    """

    preload_N: Optional[number(0.0, 1e4, unit="N")] = None
    beyond_rating_reason: Optional[Text] = None
    beyond_rating_load_N: Optional[number(0.0, 1e4, unit="N")] = None
    beyond_rating_rated_N: Optional[number(0.0, 1e4, unit="N")] = None


#: The tables of the rigs file that are not a part's.
OWN_TABLES = ("rigs", "calibration", "evaluation", "assumptions")


def _tables() -> dict[str, tuple[Any, Any]]:
    """Every table of the rigs file with its (type, default), in the order its
    refusals are listed: ``[rigs]``, the part modules' required tables (by
    :attr:`RigPart.order`), ``[calibration]`` and ``[assumptions]``, then the
    part tables that may be left out (every field has a default)."""
    parts = rig_parts_lib().items()
    return ({"rigs": (RigsSection, ...)}
            | {key: (part.section, ...) for key, part in parts if part.table_required}
            | {"calibration": (CalibrationSection, CalibrationSection()),
               "evaluation": (EvaluationSection, EvaluationSection()),
               "assumptions": (dict[str, Any], {})}
            | {key: (part.section, part.section()) for key, part in parts if not part.table_required})


#: The rigs file's schema: ``[rigs]``, ``[calibration]``, ``[assumptions]``
#: and one table per part module (:mod:`tactcad.partlib`).
RigsFile = create_model("RigsFile", __base__=Section, __doc__=_tables.__doc__, **_tables())


@dataclass(frozen=True)
class PartContext:
    """What a part module's derivation reads: the array's plan, and the data
    and validated tables of the part modules it ``needs``."""

    plan: Plan
    parts: Mapping[str, PartData]
    tables: Mapping[str, Section]

    def part(self, key: str) -> PartData:
        """The derived data of part module ``key``.

        Raises:
            KeyError: ``key`` is not among the deriving part's ``needs``.
        """
        return self.parts[self._needed(key)]

    def table(self, key: str) -> Section:
        """The validated ``rigs.toml`` table of part module ``key``.

        Raises:
            KeyError: ``key`` is not among the deriving part's ``needs``.
        """
        return self.tables[self._needed(key)]

    def _needed(self, key: str) -> str:
        if key not in self.parts:
            raise KeyError(f"part module {key!r} is read but not declared in needs "
                           f"({', '.join(self.parts) or 'none declared'})")
        return key


def _library(r: Section, plan: Plan, p: Problems) -> dict[str, PartData]:
    """Each part module's data, derived against the array and the part modules
    it needs (in :func:`derivation_order`), keyed in :func:`rig_parts_lib`
    order. Every part derives even after a refusal: every refusal at once."""
    lib, done = rig_parts_lib(), {}
    for key in derivation_order():
        part = lib[key]
        context = PartContext(plan, {n: done[n] for n in part.needs},
                              {n: getattr(r, n) for n in part.needs})
        done[key] = part.derive(getattr(r, key), context, p)
    return {key: done[key] for key in lib}


def rigs_hash(data: Mapping[str, Any]) -> str:
    """sha256 of the rig file's content (canonical JSON)."""
    return content_hash(data)


def stiffest_element(plan: Plan) -> int:
    """The reference element: the stiffest, i.e. the shortest arm (K ~ 1/a^2); of
    equal arms the highest number (the paper's reference element 8 of the two 4 mm arms)."""
    return max(plan.slots, key=lambda s: (-s.geometry.arm_length_mm, s.number)).number


def _calibration_element(r: Section, plan: Plan, p: Problems) -> int:
    n = r.calibration.element
    if n is None:
        return stiffest_element(plan)
    if n > len(plan.slots):
        p.add("calibration.element", n, f"1 ... {len(plan.slots)}",
              "an element of the array (leave it out for the stiffest)")
    return n


def validate_rigs(data: Mapping[str, Any], plan: Plan,
                  file: str = "") -> tuple[RigDesign | None, Problems]:
    """The rig plan and every refusal of the rig file against the array ``plan``."""
    p = Problems(file)
    r = validate(RigsFile, data, p)
    assumptions = read_assumptions(data, RigsFile, p, "cart.bearing")
    if r is None or not check_test_rigs(plan, p, Path(plan.source).name):
        return None, p
    library = _library(r, plan, p)
    cal = _calibration_element(r, plan, p)
    if p:
        return None, p
    return RigDesign(
        name=r.rigs.name, description=r.rigs.description, source=file, rigs_hash=rigs_hash(data),
        calibration_element=cal, derived=tuple(d for part in library.values() for d in part.derived),
        assumptions=assumptions, library=library, evaluation_preload_N=r.evaluation.preload_N,
        beyond_rating_reason=r.evaluation.beyond_rating_reason,
        beyond_rating_load_N=r.evaluation.beyond_rating_load_N,
        beyond_rating_rated_N=r.evaluation.beyond_rating_rated_N), p


def rigs_from_dict(data: Mapping[str, Any], plan: Plan, source: str = "<dict>",
                   file: str = "") -> RigDesign:
    """Validate raw rig tables against the array ``plan``. See :func:`load_rigs`.

    Raises:
        DesignErrors: every refusal at once.
    """
    rigs, problems = validate_rigs(data, plan, file)
    problems.raise_if_any()
    return _with_source(rigs, source)


def _with_source(rigs: RigDesign, source: str) -> RigDesign:
    return replace(rigs, source=source)


def load_rigs(path: str | Path | None = None, *, array_plan: Plan) -> RigDesign:
    """Read a rig file and return its validated rig plan (see
    :func:`tactcad.design.project.load_project` for the three files together).

    Args:
        path: TOML rig file; ``None`` means ``hardware/rigs.toml``.
        array_plan: the array's :class:`~tactcad.design.array_plan.Plan` the rigs are
            derived against (bracket mounting holes, bolt grip).

    Raises:
        DesignError: unreadable file, missing/unknown key, or a value outside
            its allowed range (the message names file, field, value and range).
    """
    p = Path(path) if path is not None else DEFAULT_RIGS
    return rigs_from_dict(read_toml(p, "rigs file"), array_plan, source=str(p), file=p.name)


def default_rigs_data() -> dict[str, Any]:
    """Raw TOML tables of the default rig file (a fresh copy)."""
    return read_toml(DEFAULT_RIGS, "rigs file")
