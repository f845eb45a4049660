"""Design file (TOML) -> validated, immutable plan.

The plan is the single source every other module reads: geometry, exports,
checks and the stiffness estimators. It holds the design values, the derived
dimensions (each with the reason it has that value) and the assumptions the
design file declares. Nothing here imports the CAD kernel.

The array's parts are modules of :mod:`tactcad.partlib.array` (the element's
and the clamp's tables, each part's dimensions, spec, builder and drawing);
their derivation stays here, one coupled derivation of the elements, the
spacer, the clamp plates and the bolt pattern, because the part modules sit
below this layer (docs/reference/layout.md) and read the plan it makes.

Units: mm, N, MPa throughout. Frames:

* element frame: x along the arm (0 = back face of the clamped base, tip at
  +x), y up (0 = underside of the base, force on the tip acts along +y),
  z through the sheet (0 ... sheet thickness).
* array frame: x across the two rows (0 = mid-plane between them), y as the
  element frame, z along the clamped stack (0 = front face of the first
  element).
"""

from __future__ import annotations

import copy
import dataclasses
import math
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any, Iterator, Mapping

from pydantic import create_model

from tactcad.vocabulary.schema import (LIMIT_TOLERANCE_MM, DateText, Derived, FileName, Name,
                                       Problems, Section, Text, choice, content_hash, copy_tables,
                                       fmt, integer, listing, number, read_assumptions, read_toml,
                                       validate, with_counts)
from tactcad.vocabulary.material_library import (DENSITY_RANGE, SAFETY_FACTOR_RANGE, STRENGTH_RANGE_MPA,
                                          StrengthSettings, default_strength_settings,
                                          material_fields, material_grade, strength_settings)
from tactcad.design.construction_registry import (DEFAULT_CONSTRUCTION, construction,
                                                  construction_name, construction_names,
                                                  unknown_construction)
from tactcad.design.bom_section import BomSection, check_clamp_materials
from tactcad.design.readout_section import ReadoutSection, check_readout
from tactcad.design.requirements_section import RequirementsSection, check_requirements
from tactcad.design.tolerances import TolerancesSection, check_tolerances, tolerances_of
from tactcad.vocabulary.process import (CUT_PROCESSES, DEFAULT_CUT_PROCESS, THINNEST_SHEET_MM,
                                        ProcessLimits, check_sheet_process, check_spacer_process)
from tactcad.vocabulary.standards import BOLTS, BoltSpec, shortest_stock_length
from tactcad.errors import DesignError, DesignErrors
# the array's parts: their tables and dimensions (the derivation below couples them);
# the design domain's ranges are read from here too
from tactcad.partlib.array.clamp_plate import ClampPlateGeometry, ClampSection
from tactcad.partlib.array.element import (ARM_RANGE_MM, FITTED_DOMAIN,  # noqa: F401
                                           NOTCH_RADIUS_MAX_MM, WEB_RANGE_MM, ElementGeometry,
                                           ElementSection)
from tactcad.partlib.array import clamp_fixes
from tactcad.partlib.array.clamp_fixes import clamp_fixes as clamp_fix_offers
from tactcad.partlib.array.prism import Hole
from tactcad.partlib.array.spacer import SpacerGeometry
from tactcad.partlib.registry import array_parts_lib, in_use_parts
from tactcad.vocabulary.grid import (COLUMNS_RANGE, MAX_COLUMNS, MIN_PAIRED_COLUMNS,
                                     STACKED_COLUMNS_RANGE, STACKED_COLUMNS_WHY)

#: The example sensor projects shipped with tactcad, one folder each (the
#: source tree's ``hardware/``, installed as package data ``tactcad/examples``).
EXAMPLES = Path(str(resources.files("tactcad"))) / "examples"
#: The design used when none is named: the paper's 2 x 5 macro array example.
DEFAULT_DESIGN = EXAMPLES / "macro_array" / "macro_array.toml"


MIN_LIGAMENT_MM = 1.0  # material left around a bolt hole
#: Thinnest spacer plate (pitch - sheet) the shop cuts and handles flat, mm.
MIN_SPACER_MM = 0.2
#: Smallest gap between the tips of the two rows (pitch - tip width), mm.
MIN_TIP_GAP_MM = 0.2
#: Smallest gap between neighbouring nuts or bolt heads of the bolt pattern, mm.
MIN_FASTENER_GAP_MM = 0.2
#: Smallest difference between two distinct arm lengths, mm (below the wire-EDM
#: tolerance of a contour position they would be one part).
MIN_ARM_STEP_MM = 0.01
#: Straight tip side left above the tip-root fillet, mm (the contact face stays the top).
MIN_TIP_WALL_MM = 0.1
#: Shortest base below the arm underside, mm (room for the clamp bolts and a gauge pad).
MIN_BASE_BELOW_ARM_MM = 2.0
#: How a sensing unit pairs its elements: "row" (each row's reference against the
#: row's other elements) or "column" (one row of references, each against the element
#: beside it across the rows: the two tips at one distance along the row).
PAIRINGS = ("row", "column")


# ---------------------------------------------------------------------------
# Plan dataclasses
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Material:
    """Sheet material (MPa, g/cm^3). The strength fields come from the
    library grade (:mod:`tactcad.vocabulary.material_library`) unless the design gives them;
    None when neither does. ``fatigue_strength_MPa`` is the fully reversed
    (R = -1) amplitude of a smooth specimen (a library grade's datum converted:
    :func:`tactcad.vocabulary.material_library.fully_reversed_amplitude`);
    ``fatigue_cycles`` and ``fatigue_R_ratio`` (-1) belong to a library
    fatigue strength; ``ultimate_strength_MPa`` comes with a library grade
    (the surface factor at the notch needs it); ``sources`` names each
    value's document."""

    name: str
    youngs_modulus_MPa: float
    poisson_ratio: float
    grade: str | None = None
    yield_strength_MPa: float | None = None
    fatigue_strength_MPa: float | None = None
    fatigue_cycles: float | None = None
    fatigue_R_ratio: float | None = None
    density_g_per_cm3: float | None = None
    sources: tuple[tuple[str, str], ...] = ()
    ultimate_strength_MPa: float | None = None


@dataclass(frozen=True)
class EdmRules:
    """Wire-EDM limits (mm). The DXF carries the nominal contour; the wire
    offset (kerf/2) is the shop's CAM setting."""

    wire_diameter_mm: float
    spark_gap_mm: float
    start_hole_diameter_mm: float

    @property
    def min_inside_radius_mm(self) -> float:
        """Smallest inside-corner radius the wire can cut: wire radius + spark gap."""
        return self.wire_diameter_mm / 2 + self.spark_gap_mm

    @property
    def min_slot_width_mm(self) -> float:
        """Narrowest slot the wire can cut: wire diameter + two spark gaps."""
        return self.wire_diameter_mm + 2 * self.spark_gap_mm


@dataclass(frozen=True)
class Placement:
    """Rigid placement of a part into the array frame, without the CAD kernel.

    World = (sx * x + dx, y + dy, sx * z + dz) where sx = -1 for a part turned
    180 degrees about the y axis (the second row faces the first).
    """

    dx_mm: float
    dy_mm: float
    dz_mm: float
    turned: bool = False
    #: turned a quarter about the y axis: the part's x runs along the array's
    #: +z and its z along -x (a comb's row runs along the array's z)
    quarter_turn: bool = False

    def apply(self, x: float, y: float, z: float) -> tuple[float, float, float]:
        if self.quarter_turn:
            x, z = -z, x
        s = -1.0 if self.turned else 1.0
        return (s * x + self.dx_mm, y + self.dy_mm, s * z + self.dz_mm)


@dataclass(frozen=True)
class HardStop:
    """An element's overload stop (element frame, mm): a gap under the arm's
    free end that closes on a fixed face (the comb's spine) and so stops the
    tip before the notch yields.

    Attributes:
        element: the element's number.
        gap_mm: the stop's gap at the arm's free end (mm): the travel there
            when it engages.
        lever_mm: the gap's distance from the notch centre (mm); the tip's
            travel at engagement is ``gap x arm length / lever``.
        kind: ``cut`` (the gap is cut in the sheet, at least the process's
            minimum slot) or ``set`` (the cut gap is the minimum slot and a
            shim set at assembly closes it to ``gap_mm``).
        cut_mm: the gap the process cuts (mm).
    """

    element: int
    gap_mm: float
    lever_mm: float
    kind: str
    cut_mm: float


@dataclass(frozen=True)
class ElementSlot:
    """One of the array's sensing elements: its number, position and profile."""

    number: int
    row: int
    column: int
    geometry: ElementGeometry
    placement: Placement

    @property
    def tip_centre_world_mm(self) -> tuple[float, float, float]:
        g = self.geometry
        return self.placement.apply(g.tip_centre_x_mm, g.tip_top_y_mm, g.sheet_thickness_mm / 2)

    @property
    def contact_face_world_mm(self) -> tuple[float, float]:
        """(extent along the world's x, along its z) of the tip's contact face (mm): the
        element's ``contact_face_mm`` (width along its x, the sheet along its z) turned with
        it, so a quarter-turned element (a comb's rows) lays its sheet along x."""
        w, d = self.geometry.contact_face_mm
        return (d, w) if self.placement.quarter_turn else (w, d)


@dataclass(frozen=True)
class Plan:
    """Validated design, immutable. Build with :func:`load_design`."""

    name: str
    description: str
    #: the design file as given; out of the plan's repr and so of every job's
    #: key (no output depends on the folder: a moved or checked-out copy reuses the store)
    source: str = field(repr=False)
    design_hash: str
    material: Material
    sheet_thickness_mm: float
    rows: int
    columns: int
    pitch_mm: float
    slots: tuple[ElementSlot, ...]
    edm: EdmRules
    derived: tuple[Derived, ...]
    assumptions: tuple[tuple[str, str], ...]
    # the stacked construction's bolts, spacers and clamp plates (None in another construction)
    bolt: BoltSpec | None = None
    bolt_length_mm: float | None = None
    bolt_positions_xy_mm: tuple[tuple[float, float], ...] = ()  # array frame, axis along z
    spacer: SpacerGeometry | None = None
    spacer_placements: tuple[Placement, ...] = ()
    clamp: ClampPlateGeometry | None = None
    clamp_plate_z_mm: tuple[float, float] | None = None  # front face z of the front and back plate
    stack_length_mm: float | None = None
    #: the monolithic comb's sheets, spacer and fasteners (None in another construction)
    comb: Any = None
    #: each element's hard stop (:class:`HardStop`), in element order; () when the
    #: construction gives its elements none
    hard_stops: tuple["HardStop", ...] = ()
    #: The reference elements and why (:func:`unit_references`): one per row with
    #: ``pairing`` "row", one per column (all in one row) with "column".
    references: tuple[int, ...] = ()
    references_reason: str = ""
    #: How the sensing units pair their elements (:data:`PAIRINGS`).
    pairing: str = "row"
    strength: StrengthSettings = field(default_factory=default_strength_settings)
    #: the construction that derived it (:mod:`tactcad.design.construction_registry`)
    construction: str = DEFAULT_CONSTRUCTION
    #: the force gauge of the project's rigs file (``[force_gauge]``), which its elements are
    #: calibrated on; None for a plan without rigs (made in code, or a construction with no
    #: test rigs): :func:`tactcad.studies.verification.calibration_gauge` then takes the
    #: catalogue's for the rated force
    rigs_force_gauge: Any = None
    raw: Mapping[str, Any] = field(repr=False, compare=False, hash=False, default_factory=dict)
    #: The ``[material]`` keys ``raw`` holds from the grade, not from the file
    #: (:func:`grade_filled`): the manifest's ``stated`` leaves them out.
    from_grade: tuple[str, ...] = field(default=(), repr=False, compare=False, hash=False)

    def element(self, number: int) -> ElementSlot:
        """The slot of element ``number`` (1-based, paper numbering).

        Raises:
            DesignError: no such element.
        """
        for slot in self.slots:
            if slot.number == number:
                return slot
        raise DesignError("element", number, f"1 ... {len(self.slots)}")

    def row_slots(self, row: int) -> tuple[ElementSlot, ...]:
        """The slots of one row (0-based), in column order."""
        return tuple(s for s in self.slots if s.row == row)

    def reference_for(self, slot: ElementSlot) -> ElementSlot:
        """The reference ``slot`` is read against: its row's (pairing "row") or the
        reference row's element in its column (pairing "column", the pair side by side
        across the rows, so both tips lie at one distance along the row)."""
        index = slot.column if self.pairing == "column" else slot.row
        return self.slots[self.references[index] - 1]

    @property
    def unit_pairs(self) -> tuple[tuple[int, int], ...]:
        """(reference, measuring) element numbers of every pair the pairing makes, in element
        order (the read-out keeps those whose measuring element is the softer,
        :func:`tactcad.mechanics.readout_chain.row_units`)."""
        return tuple((self.reference_for(s).number, s.number) for s in self.slots
                     if s.number not in self.references)

    @property
    def tip_field_box_mm(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """((z min, z max), (x min, x max)) of every contact face in the array frame (mm),
        from the slots' placements, whatever the construction."""
        xs, zs = [], []
        for slot in self.slots:
            g = slot.geometry
            for x in (g.overall_length_mm - g.tip_width_mm, g.overall_length_mm):
                for z in (0.0, g.sheet_thickness_mm):
                    wx, _, wz = slot.placement.apply(x, g.tip_top_y_mm, z)
                    xs.append(wx)
                    zs.append(wz)
        return (min(zs), max(zs)), (min(xs), max(xs))

    @property
    def insert_axes(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """The insert's frame in the array's (x, z) plane (mm): its origin, the first
        element's tip centre, and the unit vector u along the first row (its first tip to
        its last; a one-column array: the array's z). v is u turned a quarter."""
        row = self.row_slots(0)
        x0, _, z0 = row[0].tip_centre_world_mm
        x1, _, z1 = row[-1].tip_centre_world_mm
        length = math.hypot(x1 - x0, z1 - z0)
        u = ((x1 - x0) / length, (z1 - z0) / length) if length > 1e-9 else (0.0, 1.0)
        return (x0, z0), u

    def in_insert_frame(self, x_mm: float, z_mm: float) -> tuple[float, float]:
        """A point of the array's (x, z) plane in the insert's frame (u, v; mm)."""
        (x0, z0), (ux, uz) = self.insert_axes
        dx, dz = x_mm - x0, z_mm - z0
        return dx * ux + dz * uz, -dx * uz + dz * ux

    @property
    def tip_field_mm(self) -> tuple[float, float]:
        """(along the array's z, across its x) extent of every contact face (mm)."""
        (z0, z1), (x0, x1) = self.tip_field_box_mm
        return z1 - z0, x1 - x0

    @property
    def distinct_elements(self) -> dict[str, ElementGeometry]:
        """Distinct element profiles by part name, in order of first use."""
        out: dict[str, ElementGeometry] = {}
        for slot in self.slots:
            out.setdefault(slot.geometry.part_name, slot.geometry)
        return out


# ---------------------------------------------------------------------------
# The design file's schema: types and static ranges (pydantic), one model per section
# ---------------------------------------------------------------------------
class DesignSection(Section):
    name: Name
    description: Text
    revision: Text = None  # printed in the drawings' title blocks (default "A")
    # the revision's date, ISO 8601; the sheets print it unless SOURCE_DATE_EPOCH is set
    date: DateText = None


class MaterialSection(Section):
    """Name, E and nu; optionally a library grade (yield, fatigue strength,
    density; E and nu from the grade where the table omits them) and the
    design's own strength values (:mod:`tactcad.vocabulary.material_library`)."""

    name: Text
    youngs_modulus_MPa: number(1e3, 1e6, unit="MPa")
    poisson_ratio: number(0.0, 0.5, lo_open=True, hi_open=True, unit="")
    # optional: None when absent (a given value is checked against its range)
    grade: Text = None
    yield_strength_MPa: number(*STRENGTH_RANGE_MPA, unit="MPa") = None
    fatigue_strength_MPa: number(*STRENGTH_RANGE_MPA, unit="MPa") = None
    density_g_per_cm3: number(*DENSITY_RANGE, unit="g/cm^3") = None


class StrengthSection(Section):
    """Safety factor on yield at the full-scale force, and the strain gauge
    (both optional: :mod:`tactcad.vocabulary.material_library` gives the defaults)."""

    safety_factor: number(*SAFETY_FACTOR_RANGE, unit="") = None
    gauge: Text = None


class SheetSection(Section):
    #: down to the thinnest foil a cut process takes; each process checks its own range
    #: (:func:`tactcad.vocabulary.process.check_sheet_process`)
    thickness_mm: number(THINNEST_SHEET_MM, 10.0)


class ArraySection(Section):
    #: how the array is made (:mod:`tactcad.design.construction_registry`); ``stacked`` when left out
    construction: Text = None
    #: how each sensing unit pairs a reference with a measuring element (:data:`PAIRINGS`);
    #: ``row`` when left out
    pairing: choice(PAIRINGS) = None
    rows: integer(2, 2, why="the model is two clamped rows facing each other")
    columns: integer(*COLUMNS_RANGE)
    pitch_mm: number(0.0, 20.0, lo_open=True)


class ArmsSection(Section):
    lengths_mm: listing(number(*ARM_RANGE_MM, why=FITTED_DOMAIN), 2, 2 * MAX_COLUMNS,
                        "a list of rows x columns lengths (mm)")
    #: The reference elements: with ``array.pairing`` "row" one per row, in row
    #: order (left out: each row's shortest arm, its stiffest element); with "column"
    #: the reference row's elements in column order (left out: the row of shorter arms).
    reference_elements: listing(integer(1, 2 * MAX_COLUMNS), 1, MAX_COLUMNS,
                                "one element number per row, or with array.pairing = "
                                "'column' one row's elements") = None


class EdmSection(Section):
    wire_diameter_mm: number(0.02, 0.35)
    spark_gap_mm: number(0.0, 0.1)
    start_hole_diameter_mm: number(0.3, 3.0)


class FilesSection(Section):
    """The project's other files, relative to the design file's folder (the
    rigs and scenes files; ``rigs.toml`` and ``scenes.toml`` when left out)."""

    rigs: FileName = None
    scenes: FileName = None


class DesignTables(Section):
    """``macro_array.toml``: every section required, ``[assumptions]`` optional."""

    design: DesignSection
    material: MaterialSection
    sheet: SheetSection
    array: ArraySection
    element: ElementSection
    arms: ArmsSection
    clamp: ClampSection
    edm: EdmSection
    strength: StrengthSection = None
    requirements: RequirementsSection = None
    readout: ReadoutSection = None
    tolerances: TolerancesSection = None
    bom: BomSection = None
    files: FilesSection = None
    assumptions: dict[str, Any] = {}


def _part_tables() -> dict[str, tuple[Any, Any]]:
    """The tables array part modules read (:attr:`ArrayPart.section`), each optional."""
    return {key: (part.section, None) for key, part in array_parts_lib().items()
            if part.section is not None}


def in_use_tables() -> dict[str, tuple[Any, Any]]:
    """The tables of the sensor's parts in use (``[grasper_jaw]``, ``[grasper_shaft]``,
    ``[tissue_slab]``; :func:`tactcad.partlib.registry.in_use_parts`), each optional: a
    design states the grasper its insert is for, and the grasper scene, the ``grasper``
    checks and ``design --jaw`` read it (every field left out takes its default)."""
    return {key: (part.section, None) for key, part in in_use_parts().items()}


#: The design file's schema: :class:`DesignTables`, the optional table of
#: each array part module that reads one (:mod:`tactcad.partlib.array`) and
#: of each part in use (:func:`in_use_tables`).
DesignFile = create_model("DesignFile", __base__=DesignTables, __doc__=DesignTables.__doc__,
                          **_part_tables(), **in_use_tables())


# ---------------------------------------------------------------------------
# Cross-field rules: ranges that depend on other fields (every one reported)
# ---------------------------------------------------------------------------
def edm_rules(d: DesignFile) -> EdmRules:
    return EdmRules(d.edm.wire_diameter_mm, d.edm.spark_gap_mm, d.edm.start_hole_diameter_mm)


def element_process_limits(data: Mapping[str, Any]) -> ProcessLimits:
    """What the element's cut process (``[element] process``) makes from the design's
    sheet, for its material and wire settings (raw tables, or a validated file's dump; mm)."""
    el, mat, edm = data["element"], data["material"], data["edm"]
    wire = EdmRules(float(edm["wire_diameter_mm"]), float(edm["spark_gap_mm"]),
                    float(edm["start_hole_diameter_mm"]))
    material = " ".join(str(mat.get(k) or "") for k in ("grade", "name"))
    return CUT_PROCESSES[el.get("process") or DEFAULT_CUT_PROCESS].limits(
        float(data["sheet"]["thickness_mm"]), wire, material)


def check_web_tolerance_held(d: Any, p: Problems) -> None:
    """Cross-field rule: the web's drawn tolerance (``tolerances.web_thickness_mm`` or
    ``element.web_tolerance_mm``; left out, the default) is one the element's cut process
    holds on the design's sheet (the ``process_tolerance`` check's figure), so that a
    value no process can hold is refused when the file is read, not first by ``check``."""
    tol_table = getattr(d, "tolerances", None)
    stated = [(f, v) for f, v in
              (("tolerances.web_thickness_mm", getattr(tol_table, "web_thickness_mm", None)),
               ("element.web_tolerance_mm", d.element.web_tolerance_mm)) if v is not None]
    if not stated:
        return
    field, tol = stated[0]
    limits = element_process_limits(d.model_dump(exclude_none=True))
    held = limits.tolerance_mm
    if tol < held.value_mm - 1e-12:
        p.add(field, tol, f">= {fmt(held.value_mm)} mm: what {limits.process} holds on a "
              f"{fmt(d.sheet.thickness_mm)} mm sheet ({held.rule})", held.source)


def _check_array(d: DesignFile, p: Problems) -> None:
    sheet = d.sheet.thickness_mm
    p.within("array.pitch_mm", d.array.pitch_mm, sheet + MIN_SPACER_MM,
             why=f"pitch must exceed sheet.thickness_mm = {fmt(sheet)} mm by a spacer of at least "
                 f"{fmt(MIN_SPACER_MM)} mm")
    widest_tip = d.array.pitch_mm - MIN_TIP_GAP_MM
    if widest_tip > 0:  # else no tip fits the pitch: the pitch's own refusal says why
        p.within("element.tip_width_mm", d.element.tip_width_mm, hi=widest_tip,
                 why=f"tips of the two rows need a {fmt(MIN_TIP_GAP_MM)} mm gap at pitch "
                     f"{fmt(d.array.pitch_mm)} mm")


def _check_element(d: DesignFile, p: Problems) -> None:
    e, edm = d.element, edm_rules(d)
    r_min = edm.min_inside_radius_mm
    p.within("element.notch_radius_mm", e.notch_radius_mm,
             max(e.web_thickness_mm, r_min, edm.min_slot_width_mm / 2), NOTCH_RADIUS_MAX_MM,
             why="R >= web thickness (t/R <= 1) and >= wire radius + spark gap")
    over = e.web_thickness_mm + e.notch_radius_mm
    p.within("element.arm_height_mm", e.arm_height_mm, over + r_min,
             why=f"the arm must reach below web + notch radius = {fmt(over)} mm by the wire's "
                 f"inside radius {fmt(r_min)} mm so the notch opens below it with a cuttable corner")
    p.within("element.base_height_mm", e.base_height_mm, e.arm_height_mm + MIN_BASE_BELOW_ARM_MM,
             why=f"base must reach at least {fmt(MIN_BASE_BELOW_ARM_MM)} mm below the arm underside")
    p.within("element.inside_corner_radius_mm", e.inside_corner_radius_mm, r_min,
             why="inside corner radius >= wire radius + spark gap")
    p.within("element.tip_height_mm", e.tip_height_mm, e.inside_corner_radius_mm + MIN_TIP_WALL_MM,
             why=f"the tip-root fillet (element.inside_corner_radius_mm) must end on the tip's side, "
                 f"{fmt(MIN_TIP_WALL_MM)} mm below the contact face")


def _check_clamp(d: DesignFile, p: Problems) -> None:
    e, c = d.element, d.clamp
    bolt = BOLTS[c.bolt_size]
    hole = bolt.clearance_hole_mm
    widest = max(bolt.nut_across_corners_mm, bolt.head_diameter_mm)
    p.within("clamp.bolt_spacing_mm", c.bolt_spacing_mm,
             max(hole + MIN_LIGAMENT_MM, widest + MIN_FASTENER_GAP_MM),
             why=f"neighbouring {bolt.size} nuts ({fmt(bolt.nut_across_corners_mm)} mm across "
                 f"corners) and heads ({fmt(bolt.head_diameter_mm)} mm) need a "
                 f"{fmt(MIN_FASTENER_GAP_MM)} mm gap, holes a {fmt(MIN_LIGAMENT_MM)} mm ligament")
    p.within("element.base_height_mm", e.base_height_mm,
             e.arm_height_mm + hole + 2 * MIN_LIGAMENT_MM,
             why=f"{bolt.size} bolt holes below the arm need a {fmt(MIN_LIGAMENT_MM)} mm ligament")
    p.within("clamp.bridge_height_mm", c.bridge_height_mm, hole + 1.0,
             e.base_height_mm - e.arm_height_mm - c.arm_clearance_mm,
             why="the bridge must carry the mounting holes with 0.5 mm around them and stay below "
                 "the arm underside with the arm clearance")
    if d.edm.start_hole_diameter_mm >= hole:
        p.add("edm.start_hole_diameter_mm", d.edm.start_hole_diameter_mm, f"< {fmt(hole)} mm",
              "the start hole must lie inside the bolt hole it starts")


def _check_arms(d: DesignFile, p: Problems) -> None:
    e = d.element
    n = d.array.rows * d.array.columns
    arms = d.arms.lengths_mm
    if len(arms) != n:
        p.add("arms.lengths_mm", arms, f"a list of {n} lengths (rows x columns)")
        return
    check_references(d, p)
    tip_root = e.tip_width_mm / 2 + e.inside_corner_radius_mm + e.notch_radius_mm + 0.5
    distinct = sorted(set(arms))
    for shorter, longer in zip(distinct, distinct[1:]):
        if longer - shorter < MIN_ARM_STEP_MM - LIMIT_TOLERANCE_MM:
            i = arms.index(longer) + 1
            p.add(f"arms.lengths_mm[{i}]", longer,
                  f"{fmt(shorter)} mm (the same part) or at least {fmt(shorter + MIN_ARM_STEP_MM)} mm",
                  f"arms closer than {fmt(MIN_ARM_STEP_MM)} mm cannot be told apart once cut; "
                  f"each distinct arm is its own part")
    for i, a in enumerate(arms, start=1):
        if a <= e.tip_width_mm:
            p.add(f"arms.lengths_mm[{i}]", a, f"> element.tip_width_mm = {fmt(e.tip_width_mm)} mm",
                  "arm shorter than the tip")
        elif a < tip_root - LIMIT_TOLERANCE_MM:
            p.add(f"arms.lengths_mm[{i}]", a, f">= {fmt(tip_root)} mm",
                  "the tip root fillet must clear the notch by 0.5 mm")


def check_in_use(d: Any, p: Problems) -> None:
    """The grasper's shaft is the one its jaw passes: a stated ``[grasper_shaft]``
    class or diameter is the jaw's (left out, it takes the jaw's)."""
    from tactcad.partlib.grasper_jaw import bore_mm
    from tactcad.partlib.grasper_shaft import shaft_diameter_mm

    jaw, shaft = getattr(d, "grasper_jaw", None), getattr(d, "grasper_shaft", None)
    stated = {"shaft_class_mm", "outer_diameter_mm"} & set(getattr(shaft, "model_fields_set", ()))
    if jaw is None or shaft is None or not stated:
        return
    if abs(shaft_diameter_mm(shaft) - bore_mm(jaw)) > 1e-9:
        field = "outer_diameter_mm" if "outer_diameter_mm" in stated else "shaft_class_mm"
        p.add(f"grasper_shaft.{field}", getattr(shaft, field),
              f"{fmt(bore_mm(jaw))} mm, the jaw's shaft (grasper_jaw.shaft_class_mm or "
              "shaft_diameter_mm), or left out", "the jaw and its shaft pass one trocar")


# the grid on the sheet after the sheet's own rules: a sheet refused is named first
DESIGN_RULES = (_check_array, _check_element, _check_clamp, _check_arms, check_requirements,
                check_tolerances, check_clamp_materials, check_sheet_process, check_readout,
                check_spacer_process, check_web_tolerance_held, check_in_use)


# ---------------------------------------------------------------------------
# Derivations: small pure functions from the validated file to the plan
# ---------------------------------------------------------------------------
def tip_centre_x(d: DesignFile) -> float:
    """x of the contact face centre in the element frame (mm)."""
    return d.element.overall_length_mm - d.element.tip_width_mm / 2


def base_lengths(d: DesignFile) -> list[float]:
    """Clamped base length of each element (mm): tip centre - arm - notch radius."""
    return [tip_centre_x(d) - a - d.element.notch_radius_mm for a in d.arms.lengths_mm]


def clamp_leg(d: DesignFile) -> Derived:
    leg = min(base_lengths(d)) - d.clamp.arm_clearance_mm
    return Derived("clamp_leg_length", leg, "mm",
                   "shortest clamped base (longest arm) less the arm clearance, so neither "
                   "spacer nor clamp touches a flexing arm")


def bolt_holes(d: DesignFile, leg: float) -> tuple[Hole, Hole]:
    """The two clamp bolt holes of every element and spacer (element frame)."""
    hole_d = BOLTS[d.clamp.bolt_size].clearance_hole_mm
    y = (d.element.base_height_mm - d.element.arm_height_mm) / 2
    s = d.clamp.bolt_spacing_mm
    return Hole(leg / 2 - s / 2, y, hole_d), Hole(leg / 2 + s / 2, y, hole_d)


def stacked_columns_error(data: Mapping[str, Any], file: str = "") -> DesignError | None:
    """The refusal of a stacked array's design file whose ``array.columns`` is outside
    :data:`STACKED_COLUMNS_RANGE` (a row of one column has no element to measure against
    its reference); None for another construction, a count in range, or a value the
    schema refuses (not an integer, outside :data:`COLUMNS_RANGE`).

    Args:
        data: the design file's tables (raw: judged beside the schema's refusals).
        file: the file's name for the message.

    Returns:
        The refusal naming ``array.columns``, its value and the range, or None.
    """
    from tactcad.design.construction_registry import construction_name

    array = data.get("array") if isinstance(data, Mapping) else None
    columns = array.get("columns") if isinstance(array, Mapping) else None
    lo, hi = STACKED_COLUMNS_RANGE
    if (construction_name(data) != DEFAULT_CONSTRUCTION or isinstance(columns, bool)
            or not isinstance(columns, int) or not COLUMNS_RANGE[0] <= columns < lo):
        return None
    return DesignError("array.columns", columns, f"{lo} ... {hi} for a stacked array",
                       STACKED_COLUMNS_WHY, file=file)


def pairing_of(d: Any) -> str:
    """The design's unit pairing (:data:`PAIRINGS`), "row" when ``array.pairing`` is left out."""
    return d.array.pairing or "row"


def check_references(d: Any, p: Problems) -> None:
    """The named references fit the pairing: one per row, each in its row ("row"), or
    every element of one row in column order ("column")."""
    refs, rows, columns = d.arms.reference_elements, d.array.rows, d.array.columns
    if refs is None:
        return
    if pairing_of(d) == "column":
        row_firsts = [r * columns + 1 for r in range(rows)]
        if not any(refs == list(range(f, f + columns)) for f in row_firsts):
            options = " or ".join(str(list(range(f, f + columns))) for f in row_firsts)
            p.add("arms.reference_elements", refs, f"one row's elements in column order: {options}",
                  "with array.pairing = 'column' every column's reference lies in one row")
        return
    if len(refs) != rows:
        p.add("arms.reference_elements", refs, f"a list of {rows} element numbers, one per row")
        return
    for row, number in enumerate(refs):
        first = row * columns + 1
        if not first <= number < first + columns:
            p.add(f"arms.reference_elements[{row + 1}]", number,
                  f"an element of row {row + 1}: {first} ... {first + columns - 1}",
                  "each row's reference is pressed beside that row's measuring elements")


def unit_references(d: Any) -> tuple[tuple[int, ...], str]:
    """The reference elements (numbers) and the reason, by the design's pairing:
    "row": each row's, as the file names them, else the row's shortest arm (its
    stiffest element, as every element of a stacked array shares the web and notch;
    the lower number on a tie); "column": the named row's elements, else the row
    of the shorter arms in sum (row 1 on a tie)."""
    refs = d.arms.reference_elements
    c, rows, arms = d.array.columns, d.array.rows, d.arms.lengths_mm
    if pairing_of(d) == "column":
        if refs is not None:
            return tuple(refs), ("named by arms.reference_elements: each column's reference, "
                                 "its pair beside it across the rows")
        row = min(range(rows), key=lambda r: (sum(arms[r * c:(r + 1) * c]), r))
        return tuple(range(row * c + 1, row * c + c + 1)), (
            f"not named: row {row + 1}, the shorter arms; each column's pair lies side by side "
            "across the rows")
    if refs is not None:
        return tuple(refs), "named by arms.reference_elements"
    chosen = tuple(min(range(r * c + 1, r * c + c + 1), key=lambda n: (arms[n - 1], n))
                   for r in range(rows))
    return chosen, "not named: each row's shortest arm, its stiffest element"


def _check_bolt_pattern(d: DesignFile, p: Problems) -> None:
    bolt = BOLTS[d.clamp.bolt_size]
    bases = base_lengths(d)
    leg = clamp_leg(d).value
    # the holes need a ligament to the leg's ends (nuts and heads may overhang them)
    needed = d.clamp.bolt_spacing_mm + bolt.clearance_hole_mm + 2 * MIN_LIGAMENT_MM
    if leg < needed - LIMIT_TOLERANCE_MM:
        worst = 1 + bases.index(min(bases))
        arm = d.arms.lengths_mm[worst - 1]
        p.add(f"arms.lengths_mm[{worst}]", arm,
              f"<= {fmt(arm - (needed - leg))} mm, or raise element.overall_length_mm above "
              f"{fmt(d.element.overall_length_mm + needed - leg)} mm",
              f"the clamped base leaves {fmt(leg)} mm for a bolt pattern that needs {fmt(needed)} mm")


def stack_length(d: DesignFile) -> float:
    """Length of the element/spacer stack along z (mm)."""
    return (d.array.columns - 1) * d.array.pitch_mm + d.sheet.thickness_mm


def bolt_length(d: DesignFile) -> tuple[float | None, Derived]:
    bolt = BOLTS[d.clamp.bolt_size]
    grip = stack_length(d) + 2 * d.clamp.plate_thickness_mm
    needed = grip + bolt.nut_height_mm + 2 * bolt.thread_pitch_mm
    length = shortest_stock_length(bolt, needed)
    return length, Derived("bolt_length", length or needed, "mm",
                           f"shortest stock {bolt.size} length >= grip {fmt(grip)} + nut "
                           f"{fmt(bolt.nut_height_mm)} + 2 thread pitches")


def _check_bolt_length(d: DesignFile, p: Problems) -> None:
    length, why = bolt_length(d)
    bolt = BOLTS[d.clamp.bolt_size]
    if length is None:  # offer only the changes that pass this rule and the others

        # tried with the rigs' bracket ear too, which the bracket bolt grips as well
        allowed, alternatives = clamp_fix_offers(d.model_dump(exclude_none=True, by_alias=True),
                                                 bracket_ear_mm())
        p.errors.append(DesignError(
            "array.columns", d.array.columns, allowed,
            f"bolt needs {fmt(why.value)} mm, longest stock {bolt.size} is "
            f"{fmt(max(bolt.catalogue_lengths_mm))} mm", p.file, alternatives))


def _default_bracket_ear_mm() -> float:
    """Thickness (mm) of the default rigs' bracket ear, which the bracket bolt grips
    besides the clamp plates and the stack."""
    import tomllib

    with open(DEFAULT_DESIGN.parent / "rigs.toml", "rb") as fh:
        return float(tomllib.load(fh)["bracket"]["ear_thickness_mm"])


#: The bracket ear (mm) of the rigs the design being validated goes with, while its project
#: validates it (:func:`rigs_bracket_ear`); None: no rigs of its own known (the default
#: rigs' ear, :func:`_default_bracket_ear_mm`).
_RIGS_EAR_MM: ContextVar[float | None] = ContextVar("rigs_ear_mm", default=None)


@contextmanager
def rigs_bracket_ear(ear_mm: float | None) -> Iterator[None]:
    """Within it, a clamp bolt too short for its stack is offered only the changes that
    also clamp the bracket ear ``ear_mm`` (mm) of the design's own rigs (None: the default
    rigs' ear).

    Args:
        ear_mm: ``[bracket] ear_thickness_mm`` of the design's rigs file (mm), or None.
    """
    token = _RIGS_EAR_MM.set(ear_mm)
    try:
        yield
    finally:
        _RIGS_EAR_MM.reset(token)


def bracket_ear_mm() -> float:
    """The bracket ear (mm) a clamp refusal's offers are tried with: the design's own rigs'
    (:func:`rigs_bracket_ear`), else the default rigs'."""
    ear = _RIGS_EAR_MM.get()
    return _default_bracket_ear_mm() if ear is None else ear


def stated_ear_mm(rigs: Mapping[str, Any] | None) -> float | None:
    """The bracket ear a rigs file's tables state (mm), or None when they state none that
    reads as a thickness (the rigs' own validation refuses it; the default rigs' ear is
    tried meanwhile).

    Args:
        rigs: the rigs file's raw tables, or None (no rigs file).

    Returns:
        ``[bracket] ear_thickness_mm`` as a float (mm), or None.
    """
    bracket = rigs.get("bracket") if isinstance(rigs, Mapping) else None
    ear = bracket.get("ear_thickness_mm") if isinstance(bracket, Mapping) else None
    if isinstance(ear, bool) or not isinstance(ear, (int, float)):
        return None
    return float(ear) if math.isfinite(ear) and ear > 0 else None


def half_length(d: DesignFile) -> float:
    """|x| of the clamp plate's outer edges = the elements' back faces (mm)."""
    return d.array.pitch_mm / 2 + tip_centre_x(d)


def mounting_hole_x(d: DesignFile) -> tuple[float, float]:
    """(|x| of the two mounting bolts, |x| where the innermost element bases end), mm.
    The mounting bolts run through the stack below the arms, centred between the
    two rows' innermost base ends (shortest arm = longest base)."""
    inner_end = half_length(d) - max(base_lengths(d))
    return inner_end / 2, inner_end


def _check_mounting(d: DesignFile, p: Problems) -> None:
    bolt = BOLTS[d.clamp.bolt_size]
    x, inner_end = mounting_hole_x(d)
    widest = max(bolt.nut_across_corners_mm, bolt.head_diameter_mm)
    # the heads/nuts of the two mounting bolts face each other across x = 0
    if inner_end - x - bolt.nominal_diameter_mm / 2 < d.clamp.arm_clearance_mm - LIMIT_TOLERANCE_MM or \
            2 * x < widest + MIN_FASTENER_GAP_MM - LIMIT_TOLERANCE_MM:
        p.add("clamp.bolt_size", bolt.size, "a smaller bolt",
              f"mounting bolts at x = +-{fmt(x)} mm need {fmt(d.clamp.arm_clearance_mm)} mm to the "
              f"element bases ending at x = {fmt(inner_end)} mm and their heads "
              f"{fmt(MIN_FASTENER_GAP_MM)} mm apart")


DERIVED_RULES = (_check_bolt_pattern, _check_bolt_length, _check_mounting)


def web_tolerance(d: DesignFile) -> float:
    """+/- web thickness (mm): ``[tolerances] web_thickness_mm``, else
    ``element.web_tolerance_mm`` (:func:`tactcad.design.tolerances.tolerances_of`)."""
    return tolerances_of(d.model_dump(exclude_none=True)).web_thickness_mm


def element_geometry(d: DesignFile, arm_mm: float, holes: tuple[Hole, ...]) -> ElementGeometry:
    e = d.element
    return ElementGeometry(
        arm_length_mm=arm_mm, web_thickness_mm=e.web_thickness_mm,
        notch_radius_mm=e.notch_radius_mm, tip_width_mm=e.tip_width_mm,
        tip_height_mm=e.tip_height_mm, arm_height_mm=e.arm_height_mm,
        base_height_mm=e.base_height_mm, overall_length_mm=e.overall_length_mm,
        inside_corner_radius_mm=e.inside_corner_radius_mm, sheet_thickness_mm=d.sheet.thickness_mm,
        web_tolerance_mm=web_tolerance(d), bolt_holes=holes,
        start_hole_diameter_mm=d.edm.start_hole_diameter_mm,
        process=e.process or DEFAULT_CUT_PROCESS)


def element_slots(d: DesignFile, holes: tuple[Hole, ...]) -> tuple[ElementSlot, ...]:
    """Row 0 runs along +x towards the mid-plane, row 1 is turned 180 deg about y."""
    pitch, sheet, cols = d.array.pitch_mm, d.sheet.thickness_mm, d.array.columns
    cx = tip_centre_x(d)
    slots = []
    for idx, a in enumerate(d.arms.lengths_mm):
        row, col = divmod(idx, cols)
        if row == 0:
            pl = Placement(-pitch / 2 - cx, 0.0, col * pitch)
        else:
            pl = Placement(pitch / 2 + cx, 0.0, col * pitch + sheet, turned=True)
        slots.append(ElementSlot(idx + 1, row, col, element_geometry(d, a, holes), pl))
    return tuple(slots)


def spacer_placements(d: DesignFile) -> tuple[Placement, ...]:
    pitch, sheet, cx = d.array.pitch_mm, d.sheet.thickness_mm, tip_centre_x(d)
    out = []
    for row in range(d.array.rows):
        for col in range(d.array.columns - 1):
            if row == 0:
                out.append(Placement(-pitch / 2 - cx, 0.0, col * pitch + sheet))
            else:
                out.append(Placement(pitch / 2 + cx, 0.0, (col + 1) * pitch, turned=True))
    return tuple(out)


def clamp_plate(d: DesignFile, leg: float, holes: tuple[Hole, Hole]) -> ClampPlateGeometry:
    """U-shaped clamp plate: the element bolt holes of both rows and two mounting holes."""
    half = half_length(d)
    base_h, bridge_h = d.element.base_height_mm, d.clamp.bridge_height_mm
    hole_d, y = holes[0].diameter_mm, holes[0].y_mm
    plate_holes = [Hole(-half + h.x_mm, y, hole_d) for h in holes]
    plate_holes += [Hole(half - h.x_mm, y, hole_d) for h in holes]
    mount_x, _ = mounting_hole_x(d)
    plate_holes += [Hole(sx * mount_x, bridge_h / 2, hole_d) for sx in (-1, 1)]
    return ClampPlateGeometry(half_length_mm=half, window_half_width_mm=half - leg,
                              height_mm=base_h, bridge_height_mm=bridge_h,
                              thickness_mm=d.clamp.plate_thickness_mm,
                              window_corner_radius_mm=min(1.0, bridge_h / 2, (base_h - bridge_h) / 2),
                              holes=tuple(plate_holes))


def derived_values(d: DesignFile, leg: Derived, holes: tuple[Hole, Hole],
                   clamp: ClampPlateGeometry) -> tuple[Derived, ...]:
    bolt = BOLTS[d.clamp.bolt_size]
    return (
        leg,
        Derived("bolt_hole_y", holes[0].y_mm, "mm",
                "bolt holes centred in the base height below the arm underside"),
        Derived("bolt_hole_diameter", holes[0].diameter_mm, "mm",
                f"ISO 273 medium clearance for {bolt.size}"),
        Derived("spacer_thickness", d.array.pitch_mm - d.sheet.thickness_mm, "mm",
                "pitch minus sheet thickness"),
        bolt_length(d)[1],
        Derived("tip_centre_offset", d.array.pitch_mm / 2, "mm",
                "each row's tips sit half a pitch from the mid-plane"),
        Derived("mounting_hole_x", mounting_hole_x(d)[0], "mm",
                "mounting bolts centred between the two rows' innermost base ends, "
                "clear of every element"),
        Derived("clamp_window_half_width", clamp.window_half_width_mm, "mm",
                "legs cover the clamped bases only; the window leaves the arms free"),
    )


# ---------------------------------------------------------------------------
# Public API
# ---------------------------------------------------------------------------
def validate_design(data: Mapping[str, Any], file: str = "") -> tuple[Any, Problems]:
    """The design file's model and every refusal, by the construction its
    ``[array] construction`` chooses (:mod:`tactcad.design.construction_registry`).

    Args:
        data: the design file's tables.
        file: the file's name for the messages.

    Returns:
        (the construction's model of the file, or None; the refusals). An
        unknown construction is one refusal naming the allowed ones.
    """
    name = construction_name(data)
    if name not in construction_names():
        p = Problems(file)
        error = unknown_construction(name)
        p.add(error.field, error.value, error.allowed, error.why)
        return None, p
    return construction(name).validate(data, file)


def validate_tables(data: Mapping[str, Any], file: str = "") -> tuple[DesignFile | None, Problems]:
    """The stacked construction's model of the design file and every refusal
    (types and ranges, then the cross-field rules, then the rules of the
    derived bolt pattern)."""
    p = Problems(file)
    data = with_grade_defaults(data)
    model = validate(DesignFile, data, p)
    with_counts(p, data)  # a per-element list refused: how many values it takes
    read_assumptions(data, DesignFile, p, "element.notch_radius_mm")
    grade_error = _grade_error(data)
    refuse_grade(p, grade_error)
    if model is None:
        return None, p
    try:
        material_fields(data["material"])
        strength_settings(data.get("strength"))
    except DesignError as exc:  # an unknown grade or gauge
        if grade_error is None:
            p.extend([exc])
    for rule in DESIGN_RULES:
        rule(model, p)
    if not p:
        for rule in DERIVED_RULES:
            rule(model, p)
    return model, p


clamp_fixes.DESIGN_CHECK[:] = [lambda data: validate_tables(data)[1]]


def _grade_error(data: Mapping[str, Any]) -> DesignError | None:
    """The refusal of an unknown ``material.grade``, or None."""
    mat = data.get("material") if isinstance(data, Mapping) else None
    if not isinstance(mat, Mapping) or not isinstance(mat.get("grade"), str):
        return None  # a grade that is no text is refused by the schema
    try:
        material_grade(mat["grade"])
    except DesignError as exc:
        return exc
    return None


def refuse_grade(p: Problems, grade_error: DesignError | None) -> None:
    """Refuse an unknown ``material.grade`` in ``p``: the grade, not the E and nu it would
    have supplied (a table that omits them is refused only for its grade).

    Args:
        p: the design's refusals so far (changed in place).
        grade_error: :func:`_grade_error`'s refusal, or None (nothing is changed).
    """
    if grade_error is None:
        return
    p.errors = [e for e in p.errors if e.field not in (
        "material.youngs_modulus_MPa", "material.poisson_ratio") or e.value is not None]
    p.add(grade_error.field, grade_error.value, grade_error.allowed, grade_error.why)


def with_grade_defaults(data: Mapping[str, Any]) -> Mapping[str, Any]:
    """``data`` with ``[material]``'s E and nu taken from its library grade
    where the table omits them (an unknown grade is refused later)."""
    mat = data.get("material") if isinstance(data, Mapping) else None
    if not isinstance(mat, Mapping) or not isinstance(mat.get("grade"), str):
        return data
    try:
        g = material_grade(mat["grade"])
    except DesignError:
        return data
    filled = {k: getattr(g, k) for k in ("youngs_modulus_MPa", "poisson_ratio") if k not in mat}
    return {**data, "material": {**mat, **filled}} if filled else data


def grade_filled(data: Mapping[str, Any]) -> tuple[str, ...]:
    """The ``[material]`` keys :func:`with_grade_defaults` takes from the grade because the
    file leaves them out (``youngs_modulus_MPa`` in MPa, ``poisson_ratio``).

    Args:
        data: the design file's tables, as read.

    Returns:
        The keys, in the material table's order after its own ones (empty where the file
        states both or names no library grade).
    """
    mat = data.get("material") if isinstance(data, Mapping) else None
    if not isinstance(mat, Mapping):
        return ()
    return tuple(k for k in with_grade_defaults(data)["material"] if k not in mat)


def shaping_tables(data: Mapping[str, Any]) -> dict[str, Any]:
    """The design's tables less ``[files]``: where the rigs and scenes files
    lie shapes no part (their contents are hashed on their own)."""
    return {k: v for k, v in data.items() if k != "files"}


def plan_from_model(d: Any, data: Mapping[str, Any], source: str) -> Plan:
    """The plan of a design that passed :func:`validate_design`, derived by
    its construction (:mod:`tactcad.design.construction_registry`), each element
    carrying its bonded gauge (:func:`with_gauges`)."""
    return with_gauges(construction(construction_name(data)).derive(d, data, source))


def with_gauges(plan: Plan) -> Plan:
    """``plan`` with each element's bonded gauge (:class:`~tactcad.partlib.array.element.
    GaugeStack`: the read-out's grid, its height over the face and the installation's
    modulus, :func:`tactcad.design.readout_section.readout_of`): every element is read by
    one, and the stiffness it has in use is with it. A stack of no height or no modulus
    (the file may state either 0) is no layer: the elements stay bare."""
    from tactcad.design.readout_section import readout_of
    from tactcad.partlib.array.element import GaugeStack

    chain = readout_of(plan.raw, plan.strength.gauge)
    stack = None
    if chain.grid_height_mm > 0 and chain.gauge_backing_modulus_MPa > 0:
        stack = GaugeStack(chain.grid_length_mm, chain.grid_width_mm, chain.grid_height_mm,
                           chain.gauge_backing_modulus_MPa)
    return dataclasses.replace(plan, slots=tuple(
        dataclasses.replace(s, geometry=dataclasses.replace(s.geometry, gauge=stack))
        for s in plan.slots))


def derive_plan(d: DesignFile, data: Mapping[str, Any], source: str) -> Plan:
    """The stacked construction's plan of a design that passed :func:`validate_tables`:
    the elements, spacers, clamp plates and bolt pattern, each derived
    dimension with its reason."""
    p = Problems()
    from_grade = grade_filled(data)
    data = with_grade_defaults(data)
    leg = clamp_leg(d)
    holes = bolt_holes(d, leg.value)
    clamp = clamp_plate(d, leg.value, holes)
    spacer = SpacerGeometry(length_mm=leg.value, height_mm=d.element.base_height_mm,
                            thickness_mm=d.array.pitch_mm - d.sheet.thickness_mm, holes=holes)
    stack = stack_length(d)
    return Plan(
        name=d.design.name, description=d.design.description, source=source,
        design_hash=design_hash(shaping_tables(data)),
        material=Material(d.material.name, d.material.youngs_modulus_MPa, d.material.poisson_ratio,
                          **material_fields(data["material"])),
        strength=strength_settings(data.get("strength")),
        sheet_thickness_mm=d.sheet.thickness_mm, rows=d.array.rows, columns=d.array.columns,
        pitch_mm=d.array.pitch_mm, slots=element_slots(d, holes), edm=edm_rules(d),
        bolt=BOLTS[d.clamp.bolt_size], bolt_length_mm=bolt_length(d)[0],
        bolt_positions_xy_mm=tuple((h.x_mm, h.y_mm) for h in clamp.holes[:4]), spacer=spacer,
        spacer_placements=spacer_placements(d), clamp=clamp,
        clamp_plate_z_mm=(-d.clamp.plate_thickness_mm, stack), stack_length_mm=stack,
        derived=derived_values(d, leg, holes, clamp),
        references=unit_references(d)[0], references_reason=unit_references(d)[1],
        pairing=pairing_of(d),
        assumptions=read_assumptions(data, DesignFile, p, "element.notch_radius_mm"),
        raw=copy_tables(dict(data)), from_grade=from_grade,
    )


def plan_from_dict(data: Mapping[str, Any], source: str = "<dict>", file: str = "") -> Plan:
    """Validate raw design tables and derive the plan. See :func:`load_design`.

    Raises:
        DesignErrors: every refusal at once (``.field`` etc. are the first one's).
    """
    model, problems = validate_design(data, file)
    problems.raise_if_any()
    return plan_from_model(model, data, source)


design_hash = content_hash


def load_design(path: str | Path | None = None) -> Plan:
    """Read a design file and return its validated plan (the array alone; see
    :func:`tactcad.design.project.load_project` for the design with its rigs and scenes).

    Args:
        path: TOML design file; ``None`` means the paper's macro array
            (``hardware/macro_array.toml``).

    Raises:
        DesignError: unreadable file, missing/unknown key, or a value outside
            its allowed range (the message names file, field, value and range;
            :class:`~tactcad.errors.DesignErrors` lists every one found); a silicon
            die's file (made by ``tactcad die``); a stated ``[grasper_jaw]`` its insert
            cannot fit (:func:`tactcad.partlib.tissue_slab.stated_grasper_errors`).
    """
    from tactcad.design.file_kind import read_array_tables
    from tactcad.design.construction_registry import warn_jaw_not_judged
    from tactcad.partlib.tissue_slab import stated_grasper_errors

    p = Path(path) if path is not None else DEFAULT_DESIGN
    plan = plan_from_dict(read_array_tables(p), source=str(p), file=p.name)
    jaw_errors = stated_grasper_errors(plan, p.name)  # the jaw it states takes its insert
    if jaw_errors:
        raise DesignErrors(jaw_errors)
    warn_jaw_not_judged(plan, p.name)  # a jaw a stacked array passes over, said
    return plan


def with_overrides(data: Mapping[str, Any], overrides: Mapping[str, Any]) -> dict[str, Any]:
    """Deep copy of raw design data with ``{"section.key": value}`` replaced."""
    out = copy.deepcopy(dict(data))
    for dotted, value in overrides.items():
        section, key = dotted.split(".", 1)
        out.setdefault(section, {})[key] = value
    return out


def default_design_data() -> dict[str, Any]:
    """Raw TOML tables of the default design (a fresh copy)."""
    return read_toml(DEFAULT_DESIGN, "design file")


def placed_parts(plan: Plan) -> list[tuple[str, str, Placement]]:
    """The stacked array's placed parts but the gauges (the construction
    registry's ``placed_parts``): elements, spacers, both clamp plates, bolts
    and nuts as (instance name, part name, placement), array frame, mm."""
    from tactcad.partlib.array.fasteners import bolt_name, nut_name

    out = [(f"element_{s.number}", s.geometry.part_name, s.placement) for s in plan.slots]
    out += [(f"spacer_{i}", "spacer", pl) for i, pl in enumerate(plan.spacer_placements, start=1)]
    z_front, z_back = plan.clamp_plate_z_mm
    out.append(("clamp_plate_front", "clamp_plate", Placement(0.0, 0.0, z_front)))
    out.append(("clamp_plate_back", "clamp_plate", Placement(0.0, 0.0, z_back)))
    bolt, nut = bolt_name(plan.bolt, plan.bolt_length_mm), nut_name(plan.bolt)
    z_nut = z_back + plan.clamp.thickness_mm
    for i, (x, y) in enumerate(plan.bolt_positions_xy_mm, start=1):
        out.append((f"bolt_{i}", bolt, Placement(x, y, z_front)))
        out.append((f"nut_{i}", nut, Placement(x, y, z_nut)))
    return out


def element_holder(plan: Plan, slot: ElementSlot) -> str:
    """Each element of the stack is its own instance."""
    return f"element_{slot.number}"


def touching(plan: Plan) -> set[frozenset[str]]:
    """The stack's face contacts: each element with the spacers either side of
    it in its row and the end elements with the clamp plates; bolts on the
    front plate, nuts on the back plate, each bolt in its nut."""
    pairs: set[frozenset[str]] = set()
    per_row = plan.columns
    for s in plan.slots:
        col, row_offset = s.column, s.row * (per_row - 1)
        for k in (col, col + 1):  # spacer before / after the element in its row
            if 1 <= k <= per_row - 1:
                pairs.add(frozenset({f"element_{s.number}", f"spacer_{row_offset + k}"}))
        if col == 0:
            pairs.add(frozenset({f"element_{s.number}", "clamp_plate_front"}))
        if col == per_row - 1:
            pairs.add(frozenset({f"element_{s.number}", "clamp_plate_back"}))
    for i in range(1, len(plan.bolt_positions_xy_mm) + 1):
        pairs.add(frozenset({f"bolt_{i}", "clamp_plate_front"}))
        pairs.add(frozenset({f"nut_{i}", "clamp_plate_back"}))
        pairs.add(frozenset({f"bolt_{i}", f"nut_{i}"}))
    return pairs


def mount_frames(plan: Plan) -> dict[str, Any]:
    """The stack's mount for the test rigs: ``mount`` on the front clamp plate
    between its two bridge holes (the bracket's ear seats there) and ``nut_k``
    on the back clamp plate at bridge hole k (the through bolts' nuts)."""
    from tactcad.geometry.frames import Frame

    c = plan.clamp
    mount = c.holes[-2:]
    y_h = mount[0].y_mm
    z_front, z_back = plan.clamp_plate_z_mm
    frames = {"mount": Frame((0.0, y_h, z_front), (1, 0, 0), (0, 0, -1), "clamp_plate_front")}
    for k, h in enumerate(mount, start=1):
        frames[f"nut_{k}"] = Frame((h.x_mm, y_h, z_back + c.thickness_mm), (1, 0, 0), (0, 0, 1),
                                   "clamp_plate_back")
    return frames
