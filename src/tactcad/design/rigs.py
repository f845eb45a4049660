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

Units: mm, N, g.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping, Optional

from pydantic import create_model

from tactcad.design.array import Plan
from tactcad.partlib.base import PartData
from tactcad.partlib.registry import derivation_order, rig_parts_lib
from tactcad.vocabulary.schema import (Derived, Problems, Section, Text, choice,
                                       content_hash, fmt, integer, listing, number, read_assumptions,
                                       read_toml, validate)
from tactcad.vocabulary.standards import (BEARINGS, RIG_BOLTS, BearingSpec, BoltSpec,
                                          shortest_stock_length)
from tactcad.errors import DesignError

DEFAULT_RIGS = Path(__file__).resolve().parents[3] / "hardware" / "rigs.toml"

POCKET_CORNER_RADIUS_MM = 1.0  # end mill radius of the cart's vacuum pocket
#: Sample size when the rigs file gives none (the paper's phantom block), mm;
#: larger when the array's tips need it, with this margin around them.
SAMPLE_LENGTH_MM = 30.0
SAMPLE_WIDTH_MM = 20.0
SAMPLE_MARGIN_MM = 2.0



@dataclass(frozen=True)
class CartGeometry:
    """Wheeled cart top plate with a vacuum clamping area (mm)."""

    length_mm: float
    width_mm: float
    thickness_mm: float
    bearing: BearingSpec
    axle_bolt: BoltSpec
    axle_bolt_length_mm: float
    axle_height_mm: float
    axle_x_mm: float  # |x| of the axles
    axle_hole_depth_mm: float
    spacer_outer_diameter_mm: float
    spacer_inner_diameter_mm: float
    spacer_thickness_mm: float
    pocket_length_mm: float
    pocket_width_mm: float
    pocket_depth_mm: float
    suction_hole_diameter_mm: float
    suction_hole_xs_mm: tuple[float, ...]
    channel_diameter_mm: float
    channel_end_x_mm: float
    port_diameter_mm: float
    port_depth_mm: float
    holder_screw_y_mm: float  # |y| of the sample holder's two tapped holes (x = 0)
    holder_screw_diameter_mm: float
    holder_tapped_depth_mm: float

    @property
    def wheel_clearance_mm(self) -> float:
        """Underside of the cart above the wheels' contact line."""
        return self.bearing.outer_diameter_mm / 2 - self.axle_height_mm


@dataclass(frozen=True)
class SampleGeometry:
    length_mm: float
    width_mm: float
    height_mm: float
    material: str


@dataclass(frozen=True)
class SampleHolderGeometry:
    """Frame around the sample: window = sample + clearance, two screw holes."""

    window_length_mm: float
    window_width_mm: float
    outer_length_mm: float
    outer_width_mm: float
    thickness_mm: float
    corner_radius_mm: float
    screw: BoltSpec
    screw_length_mm: float
    screw_y_mm: float


@dataclass(frozen=True)
class RigDesign:
    """Validated rig dimensions, immutable. Build with :func:`load_rigs`."""

    name: str
    description: str
    source: str
    rigs_hash: str
    cart: CartGeometry
    sample: SampleGeometry
    sample_stiffness_N_per_mm: tuple[float, ...]
    holder: SampleHolderGeometry
    calibration_element: int
    derived: tuple[Derived, ...]
    assumptions: tuple[tuple[str, str], ...]
    #: the parts written one module each (:mod:`tactcad.partlib`), by key
    library: Mapping[str, PartData] = field(default_factory=dict)

    def part(self, key: str) -> Any:
        """The geometry (the data its builder reads) of part module ``key``.

        Raises:
            KeyError: no part module ``key``.
        """
        return self.library[key].geometry


# ---------------------------------------------------------------------------
# The rig file's schema: types and static ranges, one model per section
# ---------------------------------------------------------------------------
class RigsSection(Section):
    name: Text
    description: Text


class CartSection(Section):
    length_mm: number(30.0, 300.0)
    width_mm: number(30.0, 300.0)
    thickness_mm: number(5.0, 40.0)
    bearing: choice(BEARINGS, "ISO 15 deep groove ball bearings of the catalogue")
    axle_height_mm: number(1.0, 20.0)
    axle_inset_mm: number(3.0, 100.0)
    axle_hole_depth_mm: number(3.0, 40.0)
    spacer_outer_diameter_mm: number(2.0, 30.0)
    spacer_thickness_mm: number(0.2, 5.0)
    pocket_length_mm: number(2.0, 200.0)
    pocket_width_mm: number(2.0, 200.0)
    pocket_depth_mm: number(0.1, 5.0)
    suction_hole_diameter_mm: number(0.5, 5.0)
    suction_hole_count: integer(1, 20)
    suction_hole_pitch_mm: number(0.5, 50.0)
    channel_diameter_mm: number(1.0, 10.0)
    port_diameter_mm: number(2.0, 20.0)
    port_depth_mm: number(1.0, 30.0)


class SampleSection(Section):
    length_mm: Optional[number(5.0, 200.0)] = None  # default: covers the tip field (30 mm at least)
    width_mm: Optional[number(5.0, 200.0)] = None  # default: covers the tip field (20 mm at least)
    height_mm: number(1.0, 100.0)
    material: Text
    stiffness_N_per_mm: listing(number(0.01, 1e4, unit="N/mm"), 1, 64,
                                "a non-empty list of at most 64 stiffnesses (N/mm)")


class SampleHolderSection(Section):
    thickness_mm: number(1.0, 50.0)
    wall_mm: number(2.0, 50.0)
    clearance_mm: number(0.05, 5.0)
    corner_radius_mm: number(0.1, 10.0)
    screw_size: choice(RIG_BOLTS, "ISO 4762 socket head cap screws of the catalogue")
    tapped_depth_mm: number(2.0, 40.0)


class CalibrationSection(Section):
    element: Optional[integer(1, 1000)] = None  # default: the stiffest element (shortest arm)


class _RigsFileBase(Section):
    """``rigs.toml``: every section required but ``[calibration]``, ``[assumptions]``
    and the tables of the part modules (:mod:`tactcad.partlib`) whose every
    field has a default."""

    rigs: RigsSection
    cart: CartSection
    sample: SampleSection
    sample_holder: SampleHolderSection
    calibration: CalibrationSection = CalibrationSection()
    assumptions: dict[str, Any] = {}


#: Place of each required section above among the part modules' tables
#: (:attr:`RigPart.order`, the order the rig parts are derived in).
_PLACES = {"rigs": 0, "sample": 10, "cart": 20, "sample_holder": 30}
#: ``[calibration]`` and ``[assumptions]`` close the required tables.
_CLOSING = ("calibration", "assumptions")


def _tables() -> dict[str, tuple[Any, Any]]:
    """Every table of the rigs file with its (type, default), in the order its
    refusals are listed: the sections above at their :data:`_PLACES` and each
    part module's required table at its :attr:`RigPart.order`, merged;
    ``[calibration]`` and ``[assumptions]`` after them, then the part tables
    that may be left out."""
    fields = _RigsFileBase.model_fields
    ranked = [(_PLACES[k], k, (fields[k].annotation, ...)) for k in fields if k not in _CLOSING]
    optional = []
    for key, part in rig_parts_lib().items():
        if part.table_required:
            ranked.append((part.order, key, (part.section, ...)))
        else:
            optional.append((key, (part.section, part.section())))
    closing = [(k, (fields[k].annotation, fields[k].default)) for k in _CLOSING]
    return {k: t for _, k, t in sorted(ranked, key=lambda r: r[0])} | dict(closing) | dict(optional)


#: The rigs file's schema: the sections above and one table per part module.
RigsFile = create_model("RigsFile", __base__=Section, __doc__=_RigsFileBase.__doc__, **_tables())


@dataclass(frozen=True)
class PartContext:
    """What a part module's derivation reads: the array's plan, the rig parts
    still derived in this module (:class:`RigDesign` without ``library``) and
    the data of the part modules it ``needs``."""

    plan: Plan
    rigs: RigDesign
    parts: Mapping[str, PartData]

    def part(self, key: str) -> PartData:
        """The derived data of part module ``key``.

        Raises:
            KeyError: ``key`` is not among the deriving part's ``needs``.
        """
        if key not in self.parts:
            raise KeyError(f"part module {key!r} is read but not declared in needs "
                           f"({', '.join(self.parts) or 'none declared'})")
        return self.parts[key]


def _library(r: Section, plan: Plan, rigs: RigDesign, p: Problems) -> dict[str, PartData]:
    """Each part module's data, derived against the array, the rig parts of this
    module and the part modules it needs (in :func:`derivation_order`), keyed
    in :func:`rig_parts_lib` order."""
    lib, done = rig_parts_lib(), {}
    for key in derivation_order():
        part = lib[key]
        context = PartContext(plan, rigs, {n: done[n] for n in part.needs})
        done[key] = part.derive(getattr(r, key), context, p)
    return {key: done[key] for key in lib}


# ---------------------------------------------------------------------------
# Rules and derivations, one rig part at a time. Each takes the validated
# file, adds every refusal to ``p`` and returns the part's geometry.
# ---------------------------------------------------------------------------
def rigs_hash(data: Mapping[str, Any]) -> str:
    """sha256 of the rig file's content (canonical JSON)."""
    return content_hash(data)


def _stock(bolt: BoltSpec, needed: float, field: str, value: Any, p: Problems) -> float:
    """Shortest stock length of ``bolt`` >= ``needed``; a refusal naming ``field`` if none."""
    length = shortest_stock_length(bolt, needed)
    if length is None:
        p.add(field, value, f"a smaller grip: {bolt.size} needs {fmt(needed)} mm, "
              f"longest stock is {fmt(max(bolt.catalogue_lengths_mm))} mm")
        return max(bolt.catalogue_lengths_mm)
    return length


def _axle_bolt(bearing: BearingSpec) -> BoltSpec | None:
    return RIG_BOLTS.get(f"M{bearing.bore_mm:g}")


def _cart(r: RigsFile, sample: SampleGeometry, p: Problems, derived: list[Derived]) -> CartGeometry:
    c = r.cart
    bearing = BEARINGS[c.bearing]
    axle_bolt = _axle_bolt(bearing)
    if axle_bolt is None:
        p.add("cart.bearing", c.bearing, "a bearing whose bore takes one of " + ", ".join(RIG_BOLTS),
              "the wheel rides on a socket head screw of the bore's size")
        axle_bolt = RIG_BOLTS["M4"]
    axle_d = axle_bolt.nominal_diameter_mm
    p.within("cart.axle_height_mm", c.axle_height_mm, axle_d / 2 + 0.8,
             bearing.outer_diameter_mm / 2, hi_open=True,
             why="0.8 mm of material below the tapped axle hole, and the wheel must reach below "
                 "the cart")
    p.within("cart.axle_inset_mm", c.axle_inset_mm, bearing.outer_diameter_mm / 2 + 1.0,
             c.length_mm / 2, hi_open=True, why="the wheels stay inside the cart's length")
    p.within("cart.axle_hole_depth_mm", c.axle_hole_depth_mm, 1.5 * axle_d, c.width_mm / 2 - 2.0,
             why="at least 1.5 d of thread, and the holes of both sides must not meet")
    sp_id = axle_bolt.clearance_hole_mm
    p.within("cart.spacer_outer_diameter_mm", c.spacer_outer_diameter_mm, sp_id + 0.5,
             bearing.bore_mm + 0.4 * (bearing.outer_diameter_mm - bearing.bore_mm),
             why="the spacer may bear on the inner ring only (about 40 % of the ring width)")
    grip = bearing.width_mm + c.spacer_thickness_mm
    axle_len = _stock(axle_bolt, grip + 1.5 * axle_d, "cart.bearing", c.bearing, p)
    if axle_len - grip > c.axle_hole_depth_mm - 0.5:
        p.add("cart.axle_hole_depth_mm", c.axle_hole_depth_mm, f">= {fmt(axle_len - grip + 0.5)} mm",
              f"the {axle_bolt.size} x {axle_len:g} wheel screw needs the thread depth")
    derived.append(Derived("wheel_screw_length", axle_len, "mm",
                           f"shortest stock {axle_bolt.size} >= wheel {fmt(bearing.width_mm)} + "
                           f"spacer {fmt(c.spacer_thickness_mm)} + 1.5 d of thread"))
    p.within("cart.pocket_length_mm", c.pocket_length_mm, hi=c.length_mm - 10.0)
    p.within("cart.pocket_width_mm", c.pocket_width_mm, hi=c.width_mm - 10.0)
    p.within("cart.pocket_depth_mm", c.pocket_depth_mm, hi=c.thickness_mm / 4)
    pitch = p.within("cart.suction_hole_pitch_mm", c.suction_hole_pitch_mm,
                     c.suction_hole_diameter_mm + 0.5, why="0.5 mm between holes")
    n = c.suction_hole_count
    span = (n - 1) * pitch + c.suction_hole_diameter_mm
    if span > c.pocket_length_mm - 1.0:
        p.add("cart.suction_hole_count", n,
              f"<= {int((c.pocket_length_mm - 1.0 - c.suction_hole_diameter_mm) // pitch) + 1}",
              f"the holes span {fmt(span)} mm in a {fmt(c.pocket_length_mm)} mm pocket")
    hole_xs = tuple((k - (n - 1) / 2) * pitch for k in range(n))
    p.within("cart.channel_diameter_mm", c.channel_diameter_mm, c.suction_hole_diameter_mm,
             c.thickness_mm / 3, why="wider than the suction holes, and a third of the plate at most")
    p.within("cart.port_diameter_mm", c.port_diameter_mm, c.channel_diameter_mm,
             c.thickness_mm - 4.0, lo_open=True)
    p.within("cart.port_depth_mm", c.port_depth_mm, hi=c.length_mm / 2 - c.pocket_length_mm / 2)
    holder_screw = RIG_BOLTS[r.sample_holder.screw_size]
    return CartGeometry(
        length_mm=c.length_mm, width_mm=c.width_mm, thickness_mm=c.thickness_mm, bearing=bearing,
        axle_bolt=axle_bolt, axle_bolt_length_mm=axle_len, axle_height_mm=c.axle_height_mm,
        axle_x_mm=c.length_mm / 2 - c.axle_inset_mm, axle_hole_depth_mm=c.axle_hole_depth_mm,
        spacer_outer_diameter_mm=c.spacer_outer_diameter_mm, spacer_inner_diameter_mm=sp_id,
        spacer_thickness_mm=c.spacer_thickness_mm, pocket_length_mm=c.pocket_length_mm,
        pocket_width_mm=c.pocket_width_mm, pocket_depth_mm=c.pocket_depth_mm,
        suction_hole_diameter_mm=c.suction_hole_diameter_mm, suction_hole_xs_mm=hole_xs,
        channel_diameter_mm=c.channel_diameter_mm,
        channel_end_x_mm=hole_xs[-1] + c.suction_hole_diameter_mm / 2 + c.channel_diameter_mm / 2,
        port_diameter_mm=c.port_diameter_mm, port_depth_mm=c.port_depth_mm,
        holder_screw_y_mm=holder_screw_y(r, sample),
        holder_screw_diameter_mm=holder_screw.nominal_diameter_mm,
        holder_tapped_depth_mm=r.sample_holder.tapped_depth_mm)


def holder_screw_y(r: RigsFile, sample: SampleGeometry) -> float:
    """|y| of the sample holder's two screws: mid-wall beside the window (mm)."""
    h = r.sample_holder
    return (sample.width_mm + 2 * h.clearance_mm) / 2 + h.wall_mm / 2


def tip_field(plan: Plan) -> tuple[float, float]:
    """(along the stack, across the rows) extent of the array's contact faces, mm."""
    g = plan.slots[0].geometry
    return plan.stack_length_mm, plan.pitch_mm + g.tip_width_mm


def _sample(r: RigsFile, plan: Plan, p: Problems) -> tuple[SampleGeometry, tuple[float, ...]]:
    """The sample carries every tip of the array with a margin; its size follows the
    array unless the file sets it (30 x 20 mm at least, as the paper's)."""
    s, c = r.sample, r.cart
    along, across = tip_field(plan)
    need_l, need_w = along + 2 * SAMPLE_MARGIN_MM, across + 2 * SAMPLE_MARGIN_MM
    why = (f"every tip of the array rests on the sample with {fmt(SAMPLE_MARGIN_MM)} mm to spare "
           f"(tip field {fmt(along)} x {fmt(across)} mm)")
    length = max(SAMPLE_LENGTH_MM, need_l) if s.length_mm is None else \
        p.within("sample.length_mm", s.length_mm, need_l, why=why)
    width = max(SAMPLE_WIDTH_MM, need_w) if s.width_mm is None else \
        p.within("sample.width_mm", s.width_mm, need_w, why=why)
    if length < c.pocket_length_mm + 4.0 or width < c.pocket_width_mm + 4.0:
        short = length < c.pocket_length_mm + 4.0
        p.add("sample.length_mm" if short else "sample.width_mm", length if short else width,
              f">= vacuum pocket + 4 mm ({fmt(c.pocket_length_mm + 4)} x "
              f"{fmt(c.pocket_width_mm + 4)} mm)", "the sample must seal the pocket with a 2 mm margin")
    stiffness = tuple(s.stiffness_N_per_mm)
    if len(set(stiffness)) != len(stiffness):
        p.add("sample.stiffness_N_per_mm", list(stiffness), "distinct values",
              "each stiffness names one sample part")
    return SampleGeometry(length, width, s.height_mm, s.material), stiffness


def _holder(r: RigsFile, s: SampleGeometry, p: Problems,
            derived: list[Derived]) -> SampleHolderGeometry:
    h, c = r.sample_holder, r.cart
    p.within("sample_holder.thickness_mm", h.thickness_mm, hi=s.height_mm, hi_open=True,
             why="the sample must stand proud of its holder")
    p.within("sample_holder.corner_radius_mm", h.corner_radius_mm,
             hi=h.clearance_mm * (2 + math.sqrt(2)),
             why="the window's corner arc must clear the sample's sharp corner")
    screw = RIG_BOLTS[h.screw_size]
    if h.wall_mm < screw.head_diameter_mm + 1.0:
        p.add("sample_holder.wall_mm", h.wall_mm, f">= {fmt(screw.head_diameter_mm + 1.0)} mm",
              f"the {h.screw_size} head must sit on the wall")
    p.within("sample_holder.tapped_depth_mm", h.tapped_depth_mm, hi=c.thickness_mm - 1.0)
    screw_len = _stock(screw, h.thickness_mm + 1.5 * screw.nominal_diameter_mm,
                       "sample_holder.thickness_mm", h.thickness_mm, p)
    if screw_len - h.thickness_mm > h.tapped_depth_mm - 0.5:
        p.add("sample_holder.tapped_depth_mm", h.tapped_depth_mm,
              f">= {fmt(screw_len - h.thickness_mm + 0.5)} mm",
              f"the {h.screw_size} x {screw_len:g} holder screw needs the thread depth")
    win_l, win_w = s.length_mm + 2 * h.clearance_mm, s.width_mm + 2 * h.clearance_mm
    screw_y = holder_screw_y(r, s)
    if win_l + 2 * h.wall_mm > c.length_mm or win_w + 2 * h.wall_mm > c.width_mm:
        p.add("sample_holder.wall_mm", h.wall_mm,
              f"<= {fmt(min((c.length_mm - win_l) / 2, (c.width_mm - win_w) / 2))} mm",
              "the holder must fit on the cart")
    d = screw.nominal_diameter_mm
    if screw_y - d / 2 < c.channel_diameter_mm / 2 + 1.0 or screw_y + d / 2 > c.width_mm / 2 - 1.0:
        p.add("sample_holder.wall_mm", h.wall_mm, "a value that keeps the holder screws "
              "1 mm from the vacuum channel and the cart's sides")
    if screw_y - d / 2 < c.pocket_width_mm / 2 + 1.0:
        p.add("cart.pocket_width_mm", c.pocket_width_mm,
              f"<= {fmt(2 * (screw_y - d / 2 - 1.0))} mm",
              "the holder screws must stay 1 mm outside the vacuum pocket")
    derived.append(Derived("sample_holder_screw_length", screw_len, "mm",
                           f"shortest stock {h.screw_size} >= holder {fmt(h.thickness_mm)} + 1.5 d "
                           "of thread"))
    return SampleHolderGeometry(win_l, win_w, win_l + 2 * h.wall_mm, win_w + 2 * h.wall_mm,
                                h.thickness_mm, h.corner_radius_mm, screw, screw_len, screw_y)


def stiffest_element(plan: Plan) -> int:
    """The reference element: the stiffest, i.e. the shortest arm (K ~ 1/a^2); of
    equal arms the highest number (the paper's reference element 8 of the two 4 mm arms)."""
    return max(plan.slots, key=lambda s: (-s.geometry.arm_length_mm, s.number)).number


def _calibration_element(r: RigsFile, plan: Plan, p: Problems) -> int:
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
    if r is None:
        return None, p
    derived: list[Derived] = []
    sample, stiffness = _sample(r, plan, p)
    cart = _cart(r, sample, p, derived)
    holder = _holder(r, sample, p, derived)
    rig_design = RigDesign(
        name=r.rigs.name, description=r.rigs.description, source=file, rigs_hash=rigs_hash(data),
        cart=cart, sample=sample, sample_stiffness_N_per_mm=stiffness,
        holder=holder,
        calibration_element=0, derived=(), assumptions=assumptions)
    # the part modules derive even after a refusal above: every refusal at once
    library = _library(r, plan, rig_design, p)
    cal = _calibration_element(r, plan, p)
    if p:
        return None, p
    derived += [d for part in library.values() for d in part.derived]
    return replace(rig_design, derived=tuple(derived), library=library, calibration_element=cal), p


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
        array_plan: the array's :class:`~tactcad.design.array.Plan` the rigs are
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


def rigs_path_for(design_file: Path) -> Path:
    """``rigs.toml`` beside the design file, else the default one."""
    candidate = design_file.parent / "rigs.toml"
    return candidate if design_file.name and candidate.is_file() else DEFAULT_RIGS
