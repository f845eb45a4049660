"""Design file (TOML) -> validated, immutable plan.

The plan is the single source every other module reads: geometry, exports,
checks and the stiffness estimators. It holds the design values, the derived
dimensions (each with the reason it has that value) and the assumptions the
design file declares. Nothing here imports the CAD kernel.

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
import hashlib
import json
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from .errors import DesignError

DEFAULT_DESIGN = Path(__file__).resolve().parents[2] / "hardware" / "macro_array.toml"


# ---------------------------------------------------------------------------
# Catalogue data (ISO 273 medium clearance, ISO 4762 socket head cap screw,
# ISO 4032 hex nut). Values in mm.
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class BoltSpec:
    """ISO metric bolt + nut envelope data (mm)."""

    size: str
    nominal_diameter_mm: float
    clearance_hole_mm: float  # ISO 273 medium series
    thread_pitch_mm: float
    head_diameter_mm: float  # ISO 4762 d_k
    head_height_mm: float  # ISO 4762 k
    nut_width_across_flats_mm: float  # ISO 4032 s
    nut_height_mm: float  # ISO 4032 m
    catalogue_lengths_mm: tuple[float, ...]  # ISO 4762 / DIN 912 stock lengths

    @property
    def socket_across_flats_mm(self) -> float:
        """Hexagon socket size s of ISO 4762: about 0.75 d for the small sizes."""
        return 0.75 * self.nominal_diameter_mm


BOLTS: dict[str, BoltSpec] = {
    "M1.6": BoltSpec("M1.6", 1.6, 1.8, 0.35, 3.0, 1.6, 3.2, 1.3,
                     (3, 4, 5, 6, 8, 10, 12, 16, 20)),
    "M2": BoltSpec("M2", 2.0, 2.4, 0.4, 3.8, 2.0, 4.0, 1.6,
                   (4, 5, 6, 8, 10, 12, 16, 20, 25, 30)),
    "M2.5": BoltSpec("M2.5", 2.5, 2.9, 0.45, 4.5, 2.5, 5.0, 2.0,
                     (5, 6, 8, 10, 12, 16, 20, 25, 30)),
    "M3": BoltSpec("M3", 3.0, 3.4, 0.5, 5.5, 3.0, 5.5, 2.4,
                   (5, 6, 8, 10, 12, 16, 20, 25, 30, 35, 40)),
}

# Design domain: the range over which the closed-form stiffness correction is
# fitted to fem3d (data/stiffness_correction.json; web 0.05-1 mm, arm 2-20 mm,
# sheet 0.5-10 mm). The plan refuses designs outside it rather than
# extrapolate silently.
WEB_RANGE_MM = (0.05, 1.0)
ARM_RANGE_MM = (2.0, 20.0)
NOTCH_RADIUS_MAX_MM = 2.0
MIN_LIGAMENT_MM = 1.0  # material left around a bolt hole


# ---------------------------------------------------------------------------
# Plan dataclasses
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Derived:
    """A dimension the plan derives, with the reason it has that value."""

    name: str
    value: float
    unit: str
    reason: str


@dataclass(frozen=True)
class Material:
    name: str
    youngs_modulus_MPa: float
    poisson_ratio: float


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
class Hole:
    """A round through hole in a part's sketch plane (mm)."""

    x_mm: float
    y_mm: float
    diameter_mm: float


@dataclass(frozen=True)
class ElementGeometry:
    """One distinct wire-cut flexure profile (element frame, mm).

    Profile: a clamped base block, a single-sided circular notch hinge at the
    base's upper front corner (flat top face over the web carries the strain
    gauge), a measuring arm of height ``arm_height_mm`` and a tip whose top
    face is the 2 x 3 mm contact face. ``arm_length_mm`` (paper: flexing arm
    length) is the lever from the notch centre to the centre of the contact
    face.
    """

    arm_length_mm: float
    web_thickness_mm: float
    notch_radius_mm: float
    tip_width_mm: float
    tip_height_mm: float
    arm_height_mm: float
    base_height_mm: float
    overall_length_mm: float
    inside_corner_radius_mm: float
    sheet_thickness_mm: float
    web_tolerance_mm: float
    bolt_holes: tuple[Hole, ...]
    start_hole_diameter_mm: float

    @property
    def part_name(self) -> str:
        """Distinct part name, e.g. ``element_a4mm`` or ``element_a4p5mm``."""
        return "element_a" + f"{self.arm_length_mm:g}".replace(".", "p") + "mm"

    @property
    def tip_centre_x_mm(self) -> float:
        return self.overall_length_mm - self.tip_width_mm / 2

    @property
    def hinge_x_mm(self) -> float:
        """x of the notch centre, i.e. the thinnest section of the web."""
        return self.tip_centre_x_mm - self.arm_length_mm

    @property
    def notch_centre_y_mm(self) -> float:
        return self.base_height_mm - self.web_thickness_mm - self.notch_radius_mm

    @property
    def base_length_mm(self) -> float:
        """Length of the clamped base block (x from 0 to the notch's back wall)."""
        return self.hinge_x_mm - self.notch_radius_mm

    @property
    def arm_underside_y_mm(self) -> float:
        return self.base_height_mm - self.arm_height_mm

    @property
    def tip_top_y_mm(self) -> float:
        return self.base_height_mm + self.tip_height_mm

    @property
    def contact_face_mm(self) -> tuple[float, float]:
        """(width along x, depth along z) of the tip contact face."""
        return (self.tip_width_mm, self.sheet_thickness_mm)


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

    def apply(self, x: float, y: float, z: float) -> tuple[float, float, float]:
        s = -1.0 if self.turned else 1.0
        return (s * x + self.dx_mm, y + self.dy_mm, s * z + self.dz_mm)


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


@dataclass(frozen=True)
class SpacerGeometry:
    """Spacer plate between neighbouring elements of a row (mm); sets the pitch."""

    length_mm: float
    height_mm: float
    thickness_mm: float
    holes: tuple[Hole, ...]


@dataclass(frozen=True)
class ClampPlateGeometry:
    """U-shaped clamp plate (array frame x/y, thickness along z; mm).

    Two legs press the two rows' bases; the bridge below the arms ties the
    rows together and carries the mounting holes.
    """

    half_length_mm: float  # |x| of the outer edges
    window_half_width_mm: float  # |x| of the legs' inner edges
    height_mm: float
    bridge_height_mm: float
    thickness_mm: float
    window_corner_radius_mm: float
    holes: tuple[Hole, ...]


@dataclass(frozen=True)
class Plan:
    """Validated design, immutable. Build with :func:`load_design`."""

    name: str
    description: str
    source: str
    design_hash: str
    material: Material
    sheet_thickness_mm: float
    rows: int
    columns: int
    pitch_mm: float
    slots: tuple[ElementSlot, ...]
    edm: EdmRules
    bolt: BoltSpec
    bolt_length_mm: float
    bolt_positions_xy_mm: tuple[tuple[float, float], ...]  # array frame, axis along z
    spacer: SpacerGeometry
    spacer_placements: tuple[Placement, ...]
    clamp: ClampPlateGeometry
    clamp_plate_z_mm: tuple[float, float]  # front face z of the front and back plate
    stack_length_mm: float
    derived: tuple[Derived, ...]
    assumptions: tuple[tuple[str, str], ...]
    raw: Mapping[str, Any] = field(repr=False, compare=False, hash=False, default_factory=dict)

    def element(self, number: int) -> ElementSlot:
        """The slot of element ``number`` (1-based, paper numbering).

        Raises:
            DesignError: no such element.
        """
        for slot in self.slots:
            if slot.number == number:
                return slot
        raise DesignError("element", number, f"1 ... {len(self.slots)}")

    @property
    def distinct_elements(self) -> dict[str, ElementGeometry]:
        """Distinct element profiles by part name, in order of first use."""
        out: dict[str, ElementGeometry] = {}
        for slot in self.slots:
            out.setdefault(slot.geometry.part_name, slot.geometry)
        return out


# ---------------------------------------------------------------------------
# Reading and validating
# ---------------------------------------------------------------------------
_SCHEMA: dict[str, tuple[str, ...]] = {
    "design": ("name", "description"),
    "material": ("name", "youngs_modulus_MPa", "poisson_ratio"),
    "sheet": ("thickness_mm",),
    "array": ("rows", "columns", "pitch_mm"),
    "element": ("web_thickness_mm", "notch_radius_mm", "tip_width_mm", "tip_height_mm",
                "arm_height_mm", "base_height_mm", "overall_length_mm",
                "inside_corner_radius_mm", "web_tolerance_mm"),
    "arms": ("lengths_mm",),
    "clamp": ("bolt_size", "bolt_spacing_mm", "plate_thickness_mm", "bridge_height_mm",
              "arm_clearance_mm"),
    "edm": ("wire_diameter_mm", "spark_gap_mm", "start_hole_diameter_mm"),
}
_OPTIONAL_SECTIONS = ("assumptions",)


def _fmt(x: float) -> str:
    return f"{x:.6g}"


class _Reader:
    """Typed, range-checked access to the raw TOML tables."""

    def __init__(self, data: Mapping[str, Any]):
        self.data = data

    def raw(self, section: str, key: str) -> Any:
        return self.data[section][key]

    def text(self, section: str, key: str) -> str:
        value = self.raw(section, key)
        if not isinstance(value, str) or not value.strip():
            raise DesignError(f"{section}.{key}", value, "a non-empty string")
        return value

    def number(self, section: str, key: str, lo: float | None = None, hi: float | None = None,
               *, lo_open: bool = False, hi_open: bool = False, unit: str = "mm",
               why: str = "") -> float:
        name = f"{section}.{key}"
        value = self.raw(section, key)
        return _check_number(name, value, lo, hi, lo_open=lo_open, hi_open=hi_open, unit=unit,
                             why=why)

    def integer(self, section: str, key: str, lo: int, hi: int, why: str = "") -> int:
        name = f"{section}.{key}"
        value = self.raw(section, key)
        if isinstance(value, bool) or not isinstance(value, int):
            raise DesignError(name, value, f"an integer {lo} ... {hi}", why)
        if not lo <= value <= hi:
            raise DesignError(name, value, f"{lo} ... {hi}", why)
        return value


def _range_text(lo, hi, lo_open, hi_open, unit) -> str:
    u = f" {unit}" if unit else ""
    if lo is not None and hi is not None:
        return f"{_fmt(lo)} {'<' if lo_open else '<='} value {'<' if hi_open else '<='} {_fmt(hi)}{u}"
    if lo is not None:
        return f"value {'>' if lo_open else '>='} {_fmt(lo)}{u}"
    if hi is not None:
        return f"value {'<' if hi_open else '<='} {_fmt(hi)}{u}"
    return "a finite number"


def _check_number(name: str, value: Any, lo: float | None, hi: float | None, *,
                  lo_open: bool = False, hi_open: bool = False, unit: str = "mm",
                  why: str = "") -> float:
    allowed = _range_text(lo, hi, lo_open, hi_open, unit)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise DesignError(name, value, "a finite number, " + allowed, why)
    v = float(value)
    if lo is not None and (v < lo or (lo_open and v == lo)):
        raise DesignError(name, value, allowed, why)
    if hi is not None and (v > hi or (hi_open and v == hi)):
        raise DesignError(name, value, allowed, why)
    return v


def check_keys(data: Mapping[str, Any], schema: Mapping[str, Any],
               optional_sections: tuple[str, ...] = _OPTIONAL_SECTIONS, what: str = "<design>") -> None:
    """Refuse unknown sections and keys and report missing ones.

    Args:
        data: the parsed TOML tables.
        schema: section -> its keys (any iterable of key names).
        optional_sections: sections that may be present but are not in ``schema``.
        what: name of the whole file for the error when it is not a table.

    Raises:
        DesignError: naming the section or ``section.key``.
    """
    if not isinstance(data, Mapping):
        raise DesignError(what, type(data).__name__, "a TOML table")
    for section in data:
        if section not in schema and section not in optional_sections:
            raise DesignError(section, "<table>", "sections " + ", ".join(
                [*schema, *optional_sections]), "unknown section")
    for section, keys in schema.items():
        table = data.get(section)
        if not isinstance(table, Mapping):
            raise DesignError(section, table, f"a [{section}] table with keys " + ", ".join(keys),
                              "missing section" if table is None else "")
        for key in table:
            if key not in keys:
                raise DesignError(f"{section}.{key}", table[key], "keys " + ", ".join(keys),
                                  "unknown key")
        for key in keys:
            if key not in table:
                raise DesignError(f"{section}.{key}", None, "a value (key is missing)",
                                  "missing key")


_ASSUMPTION_KEY = re.compile(r"^([a-z_]+)\.([A-Za-z0-9_]+)(\[\d+\])?$")


def read_assumptions(data: Mapping[str, Any], schema: Mapping[str, Any],
                     example: str = "element.notch_radius_mm") -> tuple[tuple[str, str], ...]:
    """The ``[assumptions]`` table: ``"section.key" = "one-line reason"`` pairs,
    each key naming a field of ``schema``.

    Raises:
        DesignError: a key naming no field, or an empty reason.
    """
    table = data.get("assumptions", {})
    if not isinstance(table, Mapping):
        raise DesignError("assumptions", table, "a table of 'section.key' = \"reason\"")
    out = []
    for key, reason in table.items():
        m = _ASSUMPTION_KEY.match(key)
        if not m or m.group(1) not in schema or m.group(2) not in schema[m.group(1)]:
            raise DesignError(f"assumptions.{key}", reason,
                              f"keys naming a field of this file, e.g. '{example}'")
        if not isinstance(reason, str) or not reason.strip():
            raise DesignError(f"assumptions.{key}", reason, "a one-line reason (non-empty string)")
        out.append((key, reason.strip()))
    return tuple(out)


def design_hash(data: Mapping[str, Any]) -> str:
    """sha256 of the design's content (canonical JSON), independent of comments/layout."""
    canonical = json.dumps(data, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(canonical.encode()).hexdigest()


def load_design(path: str | Path | None = None) -> Plan:
    """Read a design file and return its validated plan.

    Args:
        path: TOML design file; ``None`` means the paper's macro array
            (``hardware/macro_array.toml``).

    Raises:
        DesignError: unreadable file, missing/unknown key, or a value outside
            its allowed range (the message names field, value and range).
    """
    p = Path(path) if path is not None else DEFAULT_DESIGN
    return plan_from_dict(read_toml(p, "design file"), source=str(p))


def read_toml(path: Path, what: str) -> dict[str, Any]:
    """Parse a TOML file.

    Raises:
        DesignError: naming ``what`` (e.g. "design file") and the path, when the
            file cannot be read or is not valid TOML.
    """
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise DesignError(what, str(path), "a readable TOML file", exc.strerror or "") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DesignError(what, str(path), "valid TOML", str(exc)) from None


def with_overrides(data: Mapping[str, Any], overrides: Mapping[str, Any]) -> dict[str, Any]:
    """Deep copy of raw design data with ``{"section.key": value}`` replaced."""
    out = copy.deepcopy(dict(data))
    for dotted, value in overrides.items():
        section, key = dotted.split(".", 1)
        out.setdefault(section, {})[key] = value
    return out


def default_design_data() -> dict[str, Any]:
    """Raw TOML tables of the default design (a fresh copy)."""
    return tomllib.loads(DEFAULT_DESIGN.read_text(encoding="utf-8"))


def plan_from_dict(data: Mapping[str, Any], source: str = "<dict>") -> Plan:
    """Validate raw design tables and derive the plan. See :func:`load_design`."""
    check_keys(data, _SCHEMA)
    r = _Reader(data)
    assumptions = read_assumptions(data, _SCHEMA)
    derived: list[Derived] = []

    name = r.text("design", "name")
    description = r.text("design", "description")
    material = Material(
        name=r.text("material", "name"),
        youngs_modulus_MPa=r.number("material", "youngs_modulus_MPa", 1e3, 1e6, unit="MPa"),
        poisson_ratio=r.number("material", "poisson_ratio", 0.0, 0.5, lo_open=True, hi_open=True,
                               unit=""),
    )
    sheet = r.number("sheet", "thickness_mm", 0.5, 10.0)

    rows = r.integer("array", "rows", 2, 2, why="the model is two clamped rows facing each other")
    columns = r.integer("array", "columns", 1, 12)
    pitch = r.number("array", "pitch_mm", sheet, 20.0, lo_open=True,
                     why=f"pitch must exceed sheet.thickness_mm = {_fmt(sheet)} mm so a spacer fits")
    spacer_t = pitch - sheet

    edm = EdmRules(
        wire_diameter_mm=r.number("edm", "wire_diameter_mm", 0.02, 0.35),
        spark_gap_mm=r.number("edm", "spark_gap_mm", 0.0, 0.1),
        start_hole_diameter_mm=r.number("edm", "start_hole_diameter_mm", 0.3, 3.0),
    )

    web = r.number("element", "web_thickness_mm", *WEB_RANGE_MM,
                   why="the range over which the closed-form correction is fitted to fem3d")
    radius_lo = max(web, edm.min_inside_radius_mm, edm.min_slot_width_mm / 2)
    notch_r = r.number("element", "notch_radius_mm", radius_lo, NOTCH_RADIUS_MAX_MM,
                       why="R >= web thickness (t/R <= 1) and >= wire radius + spark gap")
    tip_w = r.number("element", "tip_width_mm", 0.5, pitch, hi_open=True,
                     why=f"tips of the two rows need a gap at pitch {_fmt(pitch)} mm")
    tip_h = r.number("element", "tip_height_mm", 0.3, 5.0)
    arm_h = r.number("element", "arm_height_mm", web + notch_r, 5.0, lo_open=True,
                     why="the arm must be taller than web + notch radius so the notch opens below it")
    base_h = r.number("element", "base_height_mm", arm_h + 2.0, 30.0,
                      why="base must reach at least 2 mm below the arm underside")
    overall = r.number("element", "overall_length_mm", 10.0, 60.0)
    corner_r = r.number("element", "inside_corner_radius_mm", edm.min_inside_radius_mm, 1.0,
                        why="inside corner radius >= wire radius + spark gap")
    web_tol = r.number("element", "web_tolerance_mm", 0.0, 0.1)

    bolt_size = r.raw("clamp", "bolt_size")
    if bolt_size not in BOLTS:
        raise DesignError("clamp.bolt_size", bolt_size, "one of " + ", ".join(BOLTS))
    bolt = BOLTS[bolt_size]
    bolt_spacing = r.number("clamp", "bolt_spacing_mm", bolt.clearance_hole_mm + MIN_LIGAMENT_MM,
                            40.0, why="neighbouring bolt holes need a 1 mm ligament")
    plate_t = r.number("clamp", "plate_thickness_mm", 1.0, 10.0)
    arm_clear = r.number("clamp", "arm_clearance_mm", 0.2, 3.0)
    bridge_h = r.number("clamp", "bridge_height_mm", 1.0, base_h - arm_h - arm_clear,
                        why="the bridge must stay below the arm underside with the arm clearance")
    if edm.start_hole_diameter_mm >= bolt.clearance_hole_mm:
        raise DesignError("edm.start_hole_diameter_mm", edm.start_hole_diameter_mm,
                          f"< {_fmt(bolt.clearance_hole_mm)} mm",
                          "the start hole must lie inside the bolt hole it starts")

    n_elements = rows * columns
    arms = r.raw("arms", "lengths_mm")
    if not isinstance(arms, list) or len(arms) != n_elements:
        raise DesignError("arms.lengths_mm", arms, f"a list of {n_elements} lengths (rows x columns)")
    arm_lengths = []
    tip_root = tip_w / 2 + corner_r + notch_r + 0.5
    for i, a in enumerate(arms, start=1):
        fname = f"arms.lengths_mm[{i}]"
        a = _check_number(fname, a, *ARM_RANGE_MM,
                          why="the range over which the closed-form correction is fitted to fem3d")
        if a <= tip_w:
            raise DesignError(fname, a, f"> element.tip_width_mm = {_fmt(tip_w)} mm",
                              "arm shorter than the tip")
        if a < tip_root:
            raise DesignError(fname, a, f">= {_fmt(tip_root)} mm",
                              "the tip root fillet must clear the notch by 0.5 mm")
        arm_lengths.append(a)

    # --- derived: the clamped base, bolt pattern, spacer and clamp plates ---
    tip_cx = overall - tip_w / 2
    base_lengths = [tip_cx - a - notch_r for a in arm_lengths]
    leg = min(base_lengths) - arm_clear
    derived.append(Derived("clamp_leg_length", leg, "mm",
                           "shortest clamped base (longest arm) less the arm clearance, so neither "
                           "spacer nor clamp touches a flexing arm"))
    hole_d = bolt.clearance_hole_mm
    hole_xs = (leg / 2 - bolt_spacing / 2, leg / 2 + bolt_spacing / 2)
    hole_y = (base_h - arm_h) / 2
    needed = bolt_spacing + hole_d + 2 * MIN_LIGAMENT_MM
    if leg < needed:
        worst = 1 + base_lengths.index(min(base_lengths))
        raise DesignError(f"arms.lengths_mm[{worst}]", arm_lengths[worst - 1],
                          f"<= {_fmt(arm_lengths[worst - 1] - (needed - leg))} mm, or raise "
                          f"element.overall_length_mm above {_fmt(overall + needed - leg)} mm",
                          f"the clamped base leaves {_fmt(leg)} mm for a bolt pattern that needs "
                          f"{_fmt(needed)} mm")
    if hole_y - hole_d / 2 < MIN_LIGAMENT_MM:
        raise DesignError("element.base_height_mm", base_h,
                          f">= {_fmt(arm_h + hole_d + 2 * MIN_LIGAMENT_MM)} mm",
                          "bolt holes below the arm need a 1 mm ligament")
    holes = tuple(Hole(x, hole_y, hole_d) for x in hole_xs)
    derived.append(Derived("bolt_hole_y", hole_y, "mm",
                           "bolt holes centred in the base height below the arm underside"))
    derived.append(Derived("bolt_hole_diameter", hole_d, "mm",
                           f"ISO 273 medium clearance for {bolt.size}"))
    derived.append(Derived("spacer_thickness", spacer_t, "mm", "pitch minus sheet thickness"))

    stack = (columns - 1) * pitch + sheet
    grip = stack + 2 * plate_t
    needed_len = grip + bolt.nut_height_mm + 2 * bolt.thread_pitch_mm
    lengths = [L for L in bolt.catalogue_lengths_mm if L >= needed_len]
    if not lengths:
        raise DesignError("array.columns", columns,
                          f"fewer columns or a larger bolt than {bolt.size}",
                          f"bolt needs {_fmt(needed_len)} mm, longest stock {bolt.size} is "
                          f"{_fmt(max(bolt.catalogue_lengths_mm))} mm")
    bolt_len = float(lengths[0])
    derived.append(Derived("bolt_length", bolt_len, "mm",
                           f"shortest stock {bolt.size} length >= grip {_fmt(grip)} + nut "
                           f"{_fmt(bolt.nut_height_mm)} + 2 thread pitches"))

    def element_geometry(a: float) -> ElementGeometry:
        return ElementGeometry(
            arm_length_mm=a, web_thickness_mm=web, notch_radius_mm=notch_r, tip_width_mm=tip_w,
            tip_height_mm=tip_h, arm_height_mm=arm_h, base_height_mm=base_h,
            overall_length_mm=overall, inside_corner_radius_mm=corner_r,
            sheet_thickness_mm=sheet, web_tolerance_mm=web_tol, bolt_holes=holes,
            start_hole_diameter_mm=edm.start_hole_diameter_mm)

    # Row 0 runs along +x towards the mid-plane, row 1 is turned 180 deg about y.
    slots = []
    for idx, a in enumerate(arm_lengths):
        row, col = divmod(idx, columns)
        if row == 0:
            pl = Placement(-pitch / 2 - tip_cx, 0.0, col * pitch)
        else:
            pl = Placement(pitch / 2 + tip_cx, 0.0, col * pitch + sheet, turned=True)
        slots.append(ElementSlot(idx + 1, row, col, element_geometry(a), pl))
    derived.append(Derived("tip_centre_offset", pitch / 2, "mm",
                           "each row's tips sit half a pitch from the mid-plane"))

    spacer = SpacerGeometry(length_mm=leg, height_mm=base_h, thickness_mm=spacer_t, holes=holes)
    spacer_pl = []
    for row in range(rows):
        for col in range(columns - 1):
            if row == 0:
                spacer_pl.append(Placement(-pitch / 2 - tip_cx, 0.0, col * pitch + sheet))
            else:
                spacer_pl.append(Placement(pitch / 2 + tip_cx, 0.0, (col + 1) * pitch, turned=True))

    half = pitch / 2 + tip_cx
    window = half - leg
    mount_d = hole_d
    clamp_holes = [Hole(-half + x, hole_y, hole_d) for x in hole_xs]
    clamp_holes += [Hole(half - x, hole_y, hole_d) for x in hole_xs]
    # Mounting bolts run through the whole stack below the arms, between the
    # two rows' innermost base ends (shortest arm = longest base).
    inner_end = half - max(base_lengths)
    mount_x = inner_end / 2
    if inner_end - mount_x - bolt.nominal_diameter_mm / 2 < arm_clear:
        raise DesignError("clamp.bolt_size", bolt.size, "a smaller bolt",
                          f"a mounting bolt at x = {_fmt(mount_x)} mm would pass within "
                          f"{_fmt(arm_clear)} mm of the element bases ending at x = {_fmt(inner_end)} mm")
    clamp_holes += [Hole(sx * mount_x, bridge_h / 2, mount_d) for sx in (-1, 1)]
    derived.append(Derived("mounting_hole_x", mount_x, "mm",
                           "mounting bolts centred between the two rows' innermost base ends, "
                           "clear of every element"))
    if bridge_h / 2 - mount_d / 2 < 0.5:
        raise DesignError("clamp.bridge_height_mm", bridge_h, f">= {_fmt(mount_d + 1.0)} mm",
                          "mounting holes in the bridge need 0.5 mm of material around them")
    clamp = ClampPlateGeometry(half_length_mm=half, window_half_width_mm=window, height_mm=base_h,
                               bridge_height_mm=bridge_h, thickness_mm=plate_t,
                               window_corner_radius_mm=min(1.0, bridge_h / 2, (base_h - bridge_h) / 2),
                               holes=tuple(clamp_holes))
    derived.append(Derived("clamp_window_half_width", window, "mm",
                           "legs cover the clamped bases only; the window leaves the arms free"))
    bolt_xy = tuple((h.x_mm, h.y_mm) for h in clamp_holes[:4])

    return Plan(
        name=name, description=description, source=source, design_hash=design_hash(data),
        material=material, sheet_thickness_mm=sheet, rows=rows, columns=columns, pitch_mm=pitch,
        slots=tuple(slots), edm=edm, bolt=bolt, bolt_length_mm=bolt_len,
        bolt_positions_xy_mm=bolt_xy, spacer=spacer, spacer_placements=tuple(spacer_pl),
        clamp=clamp, clamp_plate_z_mm=(-plate_t, stack), stack_length_mm=stack,
        derived=tuple(derived), assumptions=assumptions, raw=copy.deepcopy(dict(data)),
    )
