"""How a part comes to be: the typed process every part carries into its BOM
row, title block and manifest, and from which the shop data (raw stock, blank
allowances, surface finish: :mod:`tactcad.catalogue.shop`) follows; and the
registry of the processes that cut a part from sheet (:data:`CUT_PROCESSES`); a cut
process also carries the fatigue surface factor of the surface it leaves
(:class:`SurfaceFatigue`), which the strength model applies at the notch root.

A cut process owns its rules and what its shop receives:

* its rules: the sheet it takes, the smallest hole, slot and web, the
  smallest inside radius, the tolerance it holds, each as a :class:`Figure`
  with the rule and its source (:meth:`CutProcess.limits`);
* its shop file: by how much the drawn outline is offset (etch compensation),
  whether the parts are held by tabs (micro-joints) with a stated cut order,
  and the notes the file carries (:class:`ShopFile`).

The design file chooses an element's process (``[element] process``, one of
:func:`process_names`, ``wire-edm`` when left out); the part's spec carries it
(:attr:`Process.key`), the process check group checks the part against its
rules (:mod:`tactcad.checks.process_rules`) and the DXF writer draws what
:attr:`CutProcess.shop` says (:mod:`tactcad.export.dxf_sheet`). A new process
is one :func:`register_process`.

Units: mm. The figures are vendors' design-guide values: rules of practice a
shop confirms for its own machines, not guarantees.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from typing import Callable, Protocol

from tactcad.errors import DesignError


class Method(Enum):
    """How a part comes to be: the typed half of its :class:`Process`; the raw
    stock, the blank allowances and the surface finish follow from it
    (:mod:`tactcad.catalogue.shop`)."""

    SHEET = "cut from sheet"          # wire EDM, etching or laser: sheet blank
    PLATE = "milled from plate"       # sawn plate blank, faced both sides
    BAR = "cut from bar stock"        # sawn and faced rectangular bar
    ROUND_BAR = "turned from round bar"
    CAST = "cast"                     # moulded to size
    BOUGHT = "bought"                 # a catalogue part: no stock


@dataclass(frozen=True)
class SurfaceFatigue:
    """The fatigue surface factor of the surface a process leaves (Marin's k_a:
    the fatigue strength of the part's surface over that of the polished
    specimen the library's data come from).

    k_a = min(ceiling, a S_u^b) (Marin's form, S_u in MPa), so a harder alloy
    loses more to the same surface.

    Attributes:
        surface: the surface in words.
        marin_a_MPa, marin_b: Marin's coefficients for the surface class (S_u in MPa).
        ceiling: the largest factor taken whatever S_u (<= 1).
        reason: why these values, with the sources.
    """

    surface: str
    marin_a_MPa: float
    marin_b: float
    ceiling: float
    reason: str

    def factor(self, ultimate_MPa: float) -> float:
        """k_a of this surface on an alloy of ultimate strength ``ultimate_MPa`` (MPa, > 0).

        Raises:
            ValueError: a non-positive ultimate strength.
        """
        if not ultimate_MPa > 0:
            raise ValueError(f"ultimate strength must be > 0 MPa; got {ultimate_MPa!r}")
        return min(self.ceiling, self.marin_a_MPa * ultimate_MPa ** self.marin_b)


#: A finished (skim-cut) wire-EDM surface: the notch root of every element.
WIRE_EDM_SURFACE = SurfaceFatigue(
    surface="wire EDM with finishing skim cuts (recast layer at the notch root)",
    marin_a_MPa=4.51, marin_b=-0.265, ceiling=0.9,
    reason=("Marin's factor of a machined surface, k_a = 4.51 S_u^-0.265 (Shigley's Mechanical "
            "Engineering Design, 9th ed., Table 6-2, after Noll and Lipson 1946), as the "
            "surface class a finished wire-EDM cut matches: trim-pass wire EDM of titanium "
            "alloys fatigues like flank milling (Antar et al., Procedia CIRP 2013, "
            "Ti-6Al-2Sn-4Zr-6Mo: no significant difference at the 5 % level) and like grinding "
            "(Klocke et al., Procedia Eng. 19, 2011, Ti-6Al-4V); a main cut without skims "
            "leaves a thicker recast layer that lowers it further (Mower, Int. J. Fatigue 64, "
            "2014, Ti-6Al-4V), so the drawing's skim cuts (Ra 0.8 at the web) are part of the "
            "assumption. Marin's fit comes from steels and gives ~1 for a soft aluminium "
            "alloy, yet its recast layer still carries microcracks: the factor is capped at "
            "0.9 for every alloy (a judgement, not a measurement). 6061-T6: 0.90, 7075-T6: "
            "0.84, Ti-6Al-4V: 0.73, CuBe C17200: 0.70, 17-4 PH H900: 0.67."))


class Process(str):
    """A part's process as the BOM, title block and manifest print it (the
    text), typed by its :class:`Method` (``.method``), which is what the shop
    data reads: ``Process("milling from plate", Method.PLATE)``. A part cut
    from sheet names its cut process too (``.key``, a name of
    :data:`CUT_PROCESSES`; None for any other part) and ``.surface``, the fatigue
    surface factor of the cut surface (:class:`SurfaceFatigue`, None when the
    process does not state one)."""

    method: Method
    key: str | None
    surface: SurfaceFatigue | None

    def __new__(cls, text: str, method: Method, key: str | None = None,
                surface: SurfaceFatigue | None = None) -> "Process":
        if not isinstance(method, Method):
            raise TypeError(f"Process {text!r}: method must be a Method, not {method!r}")
        obj = super().__new__(cls, text)
        obj.method = method
        obj.key = key
        obj.surface = surface
        return obj

    def __getnewargs__(self) -> tuple:  # pickles whole
        return (str(self), self.method, self.key, self.surface)


# --- the cut processes -----------------------------------------------------------
INCH_MM = 25.4


class WireSettings(Protocol):
    """The design's wire-EDM settings (``[edm]``: :class:`~tactcad.design.array_plan.EdmRules`)."""

    wire_diameter_mm: float
    spark_gap_mm: float

    @property
    def min_inside_radius_mm(self) -> float: ...

    @property
    def min_slot_width_mm(self) -> float: ...


@dataclass(frozen=True)
class Figure:
    """One rule's figure for one sheet: the value (mm), the rule that gives it
    and the rule's source."""

    value_mm: float
    rule: str
    source: str

    def as_json(self) -> dict:
        return {"value_mm": round(self.value_mm, 6), "rule": self.rule, "source": self.source}


@dataclass(frozen=True)
class ProcessLimits:
    """What a process can make from a sheet of ``thickness_mm`` (mm).

    Attributes:
        min_hole_mm: smallest round hole diameter.
        min_slot_mm: narrowest slot (a gap between two cut edges).
        min_web_mm: thinnest web or finger of material left between cuts.
        min_inside_radius_mm: smallest radius of a concave corner of the part.
        tolerance_mm: +/- on a cut edge's position the process holds.
        compensation_per_side_mm: how far the shop file's outline lies outside
            the nominal part (etch compensation); 0 when the shop's CAM offsets.
        kerf_mm: width of the cut (None for etching, which has no kerf).
    """

    process: str
    thickness_mm: float
    min_hole_mm: Figure
    min_slot_mm: Figure
    min_web_mm: Figure
    min_inside_radius_mm: Figure
    tolerance_mm: Figure
    compensation_per_side_mm: Figure
    kerf_mm: Figure | None = None

    def figures(self) -> dict[str, Figure]:
        """The figures by name, in the order above (kerf only when there is one)."""
        names = ("min_hole_mm", "min_slot_mm", "min_web_mm", "min_inside_radius_mm",
                 "tolerance_mm", "compensation_per_side_mm", "kerf_mm")
        return {n: getattr(self, n) for n in names if getattr(self, n) is not None}


@dataclass(frozen=True)
class TabRule:
    """Holding tabs (micro-joints): stretches of the outer contour left uncut so
    a small part does not drop or tip when its contour closes; broken or cut
    off last. By the part's largest side L (mm): ``sizes`` lists (L up to,
    tab count, tab width mm), first match; a part longer than the last bound
    needs none (it rests on the table and is clamped)."""

    sizes: tuple[tuple[float, int, float], ...]
    source: str

    def tabs_for(self, largest_side_mm: float) -> tuple[int, float]:
        """(count, width mm) of the tabs of a part whose largest side is
        ``largest_side_mm``; (0, 0.0) when it needs none."""
        for bound, count, width in self.sizes:
            if largest_side_mm <= bound:
                return count, width
        return 0, 0.0

    def text(self) -> str:
        lo = 0.0
        parts = []
        for bound, count, width in self.sizes:
            parts.append(f"L {lo:g}-{bound:g} mm: {count} x {width:g} mm")
            lo = bound
        return "; ".join(parts) + f"; above {lo:g} mm none"


#: The cut order's steps after the inner contours: with holding tabs, without.
TAB_CUT_ORDER = ("2 outer contour, leaving the tabs uncut",
                 "3 tabs last: secure the part, then cut or break them off and dress the stubs")
PLAIN_CUT_ORDER = ("2 outer contour",)


@dataclass(frozen=True)
class ShopFile:
    """What a process's shop receives in its DXF.

    Attributes:
        kind: what the file is, written into it (``cutting DXF``, ``etch artwork``).
        offset_outline: True: the drawn outline is the nominal one offset
            outward by :attr:`ProcessLimits.compensation_per_side_mm`
            (holes shrink by it), so the made part lands on the nominal.
        tabs: the tab rule, or None when the parts are not held by tabs.
        lead_ins: the file carries start points and lead-ins (a cutting tool
            that enters the sheet).
        notes: what the shop must know, one sentence each.
        start_holes: the file carries a drilled start hole in each cut-out
            (layer ``START_HOLE``: a wire is threaded through it); False for a
            beam that pierces at the lead-in's start.
    """

    kind: str
    offset_outline: bool
    tabs: TabRule | None
    lead_ins: bool
    notes: tuple[str, ...]
    start_holes: bool = False

    @property
    def cut_order(self) -> tuple[str, ...]:
        """The stated cut order (empty for a process that does not cut contour by contour)."""
        if not self.lead_ins:
            return ()
        entry = "start hole" if self.start_holes else "pierce point"
        return ((f"1 inner contours (holes, each from its {entry})",)
                + (TAB_CUT_ORDER if self.tabs else PLAIN_CUT_ORDER))


@dataclass(frozen=True)
class CutProcess:
    """One process that cuts parts from sheet: its rules and its shop file.

    Attributes:
        name: the design file's word (``[element] process``).
        text: the process as the BOM and title block print it (``wire EDM from sheet``).
        sheet_range_mm: (thinnest, thickest) sheet it takes, with ``sheet_source``.
        limits_of: ``limits_of(thickness_mm, wire, material) -> ProcessLimits``.
        shop: what its shop file holds.
        surface: the cut surface and what it does to the part (fatigue at a notch).
    """

    name: str
    text: str
    sheet_range_mm: tuple[float, float]
    sheet_source: str
    limits_of: Callable[[float, WireSettings, str], ProcessLimits]
    shop: ShopFile
    surface: str
    sources: tuple[str, ...] = field(default=())
    fatigue_surface: SurfaceFatigue | None = None
    flexure_sheet_range_mm: tuple[float, float] | None = None
    flexure_sheet_source: str = ""

    def flexure_sheet(self) -> tuple[float, float, str]:
        """(thinnest, thickest, source) of the sheet a flexure cut by this process may be
        (mm): the process's own range narrowed by the flexure model's fitted range where it
        states one (:attr:`flexure_sheet_range_mm`)."""
        if self.flexure_sheet_range_mm is None:
            return (*self.sheet_range_mm, self.sheet_source)
        lo = max(self.sheet_range_mm[0], self.flexure_sheet_range_mm[0])
        hi = min(self.sheet_range_mm[1], self.flexure_sheet_range_mm[1])
        return lo, hi, self.flexure_sheet_source

    def holds_sheet(self, thickness_mm: float) -> bool:
        """True when the process cuts a plate of ``thickness_mm`` (mm)."""
        lo, hi = self.sheet_range_mm
        return lo - 1e-12 <= thickness_mm <= hi + 1e-12

    def limits(self, thickness_mm: float, wire: WireSettings, material: str = "") -> ProcessLimits:
        """The process's limits for a sheet of ``thickness_mm`` (mm) of ``material``
        (``wire``: the design's wire-EDM settings, read by wire EDM only)."""
        return self.limits_of(thickness_mm, wire, material)

    def part_process(self) -> Process:
        """The :class:`Process` a part cut by this process carries."""
        return Process(self.text, Method.SHEET, self.name, self.fatigue_surface)


#: The cut processes by name, in registration order.
CUT_PROCESSES: dict[str, CutProcess] = {}
DEFAULT_CUT_PROCESS = "wire-edm"


def register_process(process: CutProcess) -> None:
    """Add a cut process (a design may then choose it).

    Raises:
        ValueError: the name is taken.
    """
    if process.name in CUT_PROCESSES:
        raise ValueError(f"a cut process {process.name!r} is registered already")
    CUT_PROCESSES[process.name] = process


def process_names() -> tuple[str, ...]:
    """Every cut process's name, in registration order."""
    return tuple(CUT_PROCESSES)


def cut_process(name: str, field_name: str = "element.process") -> CutProcess:
    """The cut process ``name``.

    Raises:
        DesignError: no process of that name, naming the allowed ones.
    """
    try:
        return CUT_PROCESSES[name]
    except (KeyError, TypeError):
        raise DesignError(field_name, name, "one of " + ", ".join(CUT_PROCESSES),
                          "the processes that cut a part from sheet") from None


# --- wire EDM ------------------------------------------------------------------
#: What wire EDM cuts (mm): a plate up to the machine's cutting height; foil thinner
#: than 0.1 mm is cut clamped between sacrificial plates, not on its own.
WIRE_CUT_SHEET_MM = (0.1, 300.0)
WIRE_CUT_SHEET_SOURCE = ("cutting heights of 300-600 mm on standard machines (First Rate Mold, "
                         "'Cutting by spark erosion with travelling wire electrodes'); "
                         "micrometre-scale fins of 0.117-0.5 mm cut in D2 steel (Ahmed et al., "
                         "Micromachines 12(1):1, 2020); foil under 0.1 mm is cut clamped "
                         "between sacrificial plates (shop practice)")
#: A wire-cut flexure's sheet in a design: the stiffness correction's fitted range
#: (sheet 0.5-10 mm, data/stiffness_correction.json); a thinner flexure is etched or laser
#: cut. A rule of the flexure's model, not of the cut: a plain plate (a spacer) is judged
#: by :data:`WIRE_CUT_SHEET_MM`.
WIRE_SHEET_MM = (0.5, 10.0)
WIRE_SHEET_SOURCE = ("the range the closed form's stiffness correction is fitted over "
                     "(data/stiffness_correction.json); a thinner wire-cut flexure is outside "
                     "the model: etch or laser cut it")
WIRE_TOLERANCE_MM = 0.01
WIRE_TOLERANCE_SOURCE = ("Mecvil, 'Wire EDM: tolerances, materials and industrial applications' "
                         "(mecvil.com): +/-0.02 mm roughing, +/-0.01 mm standard finish "
                         "(2-3 passes), +/-0.005 mm fine finish")
WIRE_SURFACE = ("Wire EDM leaves a recast (white) layer a few micrometres deep that lowers the "
                "fatigue strength at the cut surface: fatigue data of polished specimens need a "
                "surface factor at an EDM notch root, or skim cuts remove most of it")
MICRO_JOINT_SOURCE = ("OSH Cut, 'Understanding micro-joints' (oshcut.com/design-guide): the "
                      "fewest and smallest joints, for small or narrow parts that would drop or "
                      "tip; Lapas, 'Micro-joints in laser cutting' (lapas.io): parts under "
                      "150 mm are at risk. Widths: tactcad's choice, below the wire's "
                      "slot (a tab a few tenths of a mm is broken by hand)")
#: Tab count and width by the part's largest side (mm): a small part one thin
#: tab (it breaks off by hand), longer parts two or three so they stay flat.
EDM_TABS = TabRule(((20.0, 1, 0.3), (60.0, 2, 0.5), (150.0, 3, 0.8)), MICRO_JOINT_SOURCE)


def _wire_limits(t: float, wire: WireSettings, material: str) -> ProcessLimits:
    r = wire.min_inside_radius_mm
    slot = wire.min_slot_width_mm
    wire_rule = "design's [edm]: wire diameter + 2 spark gaps"
    return ProcessLimits(
        "wire-edm", t,
        min_hole_mm=Figure(slot, wire_rule, "the wire passes the hole"),
        min_slot_mm=Figure(slot, wire_rule, "the wire cuts its own width plus the spark gaps"),
        min_web_mm=Figure(0.0, "no process minimum: the wire exerts no cutting force",
                          "the web's tolerance governs"),
        min_inside_radius_mm=Figure(r, "wire radius + spark gap (design's [edm])",
                                    "the wire's path cannot turn tighter than its own radius"),
        tolerance_mm=Figure(WIRE_TOLERANCE_MM, "standard finish, 2-3 passes",
                            WIRE_TOLERANCE_SOURCE),
        compensation_per_side_mm=Figure(0.0, "nominal contour; the wire offset (kerf / 2) is "
                                        "the shop's CAM setting", "shop practice"),
        kerf_mm=Figure(slot, wire_rule, "the wire and its spark gaps"))


# --- photochemical etching -----------------------------------------------------
ETCH_SHEET_MM = (0.025, 1.5)
ETCH_SHEET_SOURCE = ("photochemical machining of metal foil about 0.025-1.5 mm thick "
                     "(Precision Micro, Tech-Etch and Conard design guides)")
#: Tech-Etch, 'Flat parts photo etching design guide', Table 1 (holes or slots) and
#: Table 2 (web or finger); Advanced Metal Etching, 'Technical guidelines', Tables 2-3.
TECH_ETCH = ("Tech-Etch, 'Design guide: flat parts photo etching' (techetch.com), Tables 1-2; "
             "Advanced Metal Etching, 'Technical guidelines' (metaletching.com), Tables 2-3")
ETCH_THIN_MM = 0.005 * INCH_MM   # below 0.005 in the guides' thin-foil row applies
ETCH_FLOOR_MM = 0.003 * INCH_MM  # smallest hole, slot or web on thin foil
#: Hole/slot factor on the thickness: 1.1 for the alloys the guides list (stainless and
#: carbon steel, copper alloys, nickel alloys); 1.5 for any other (titanium, aluminium).
ETCH_LISTED_ALLOYS = ("stainless", "steel", "copper", "brass", "bronze", "beryllium", "nickel",
                      "alloy 42", "kovar", "invar", "molybdenum")
ETCH_HOLE_FACTOR = 1.1
ETCH_OTHER_HOLE_FACTOR = 1.5
ETCH_WEB_FACTOR = 1.0
#: Etch factor = depth / undercut per side (Kohken: 1.5-3.5 usual; etchingmachine.org:
#: precision work 3-4): 2.5, the middle of the usual range.
ETCH_FACTOR = 2.5
ETCH_FACTOR_SOURCE = ("Kohken, 'Etching factor' (kohkenc.co.jp): depth / side etch, usually "
                      "1.5-3.5; etchingmachine.org, 'Etching tolerance and precision': 3-4 "
                      "for precision work")
ETCH_TOLERANCE_REL = 0.15
ETCH_TOLERANCE_FLOOR_MM = 0.0005 * INCH_MM
ETCH_TOLERANCE_SOURCE = ("Conard, 'Photo etching: what to know about dimensional tolerances' "
                         "(conardcorp.com): PCMI's +/-10 % of thickness at best, quoted at "
                         "+/-15 %; floor: the phototool's +/-0.0005 in centre to centre within "
                         "1 in (Advanced Metal Etching Table 4)")
ETCH_SURFACE = ("an etched edge is burr- and stress-free but not square: etching from both sides "
                "leaves a cusp at mid-thickness, and outside corners round to about 0.75 x the "
                "thickness (Tech-Etch); no heat-affected zone or recast layer")


def etch_hole_factor(material: str) -> tuple[float, str]:
    """The hole/slot factor on the thickness for ``material`` and its reason."""
    if any(a in material.lower() for a in ETCH_LISTED_ALLOYS):
        return ETCH_HOLE_FACTOR, "1.1 x thickness (alloys the guides list)"
    return ETCH_OTHER_HOLE_FACTOR, ("1.5 x thickness: an alloy the guides do not list (the upper "
                                    "end of their 1.0-1.5; ask the etcher)")


def _etch_limits(t: float, wire: WireSettings, material: str) -> ProcessLimits:
    factor, why = etch_hole_factor(material)
    if t < ETCH_THIN_MM:
        hole = Figure(max(t, ETCH_FLOOR_MM), "at least the thickness, 0.076 mm minimum "
                      "(foil under 0.127 mm)", TECH_ETCH)
    else:
        hole = Figure(factor * t, why, TECH_ETCH)
    web = Figure(max(ETCH_WEB_FACTOR * t, ETCH_FLOOR_MM),
                 "at least the thickness, 0.076 mm minimum", TECH_ETCH)
    undercut = t / 2 / ETCH_FACTOR
    return ProcessLimits(
        "photochemical-etching", t, min_hole_mm=hole, min_slot_mm=hole, min_web_mm=web,
        min_inside_radius_mm=Figure(undercut, "the undercut per side (thickness / 2 / etch "
                                    "factor): the etch rounds a sharp inside corner to it",
                                    ETCH_FACTOR_SOURCE),
        tolerance_mm=Figure(max(ETCH_TOLERANCE_REL * t, ETCH_TOLERANCE_FLOOR_MM),
                            "15 % of the thickness, at least 0.013 mm", ETCH_TOLERANCE_SOURCE),
        compensation_per_side_mm=Figure(
            undercut, f"etched from both sides, each to half the thickness: undercut per side = "
            f"thickness / 2 / etch factor {ETCH_FACTOR:g}", ETCH_FACTOR_SOURCE))


# --- laser cutting -------------------------------------------------------------
LASER_SHEET_MM = (0.05, 3.0)
LASER_KERF_MM = 0.1
LASER_KERF_SOURCE = ("thin-sheet fibre laser kerf a few hundredths to a tenth of a mm; 0.1 mm, "
                     "the wide end, for the smallest slot (SMS Laser, 'Laser cutting design "
                     "rules' (smslaserfab.com): 0.13-0.38 mm on general sheet)")
LASER_FEATURE_FACTOR = 0.7
LASER_HOLE_FACTOR = 1.0
LASER_SOURCE = ("Acute Laser, 'Laser cutting: minimum dimensions' (acutelaser.com.au): hole "
                "0.7 x, web and slot 0.7 x the thickness, accuracy about 0.1 mm at 0.5 mm; "
                "SMS Laser: holes at least the thickness")
LASER_TOLERANCE_SOURCE = ("Acute Laser: about +/-0.1 mm at 0.5 mm sheet; 2F Prototypes, 'How "
                          "thick are laser cut parts?': steel under 1 mm +/-0.12 mm, 1-3 mm "
                          "+/-0.15 mm")
LASER_SURFACE = ("a heat-affected zone along the cut edge (about 0.1-0.5 mm, tempered or "
                 "re-hardened, with micro-cracks and dross on the exit side) lowers the "
                 "fatigue strength at a notch: remove it at a flexure's web (etch or polish) "
                 "or apply a surface factor")


def _laser_limits(t: float, wire: WireSettings, material: str) -> ProcessLimits:
    kerf = Figure(LASER_KERF_MM, "the beam's cut width on thin sheet", LASER_KERF_SOURCE)
    feature = max(LASER_FEATURE_FACTOR * t, LASER_KERF_MM)
    return ProcessLimits(
        "laser-cutting", t,
        min_hole_mm=Figure(max(LASER_HOLE_FACTOR * t, LASER_KERF_MM),
                           "at least the thickness and the kerf", LASER_SOURCE),
        min_slot_mm=Figure(feature, "0.7 x thickness, at least the kerf", LASER_SOURCE),
        min_web_mm=Figure(feature, "0.7 x thickness, at least the kerf", LASER_SOURCE),
        min_inside_radius_mm=Figure(LASER_KERF_MM / 2, "half the kerf (the beam's radius)",
                                    LASER_KERF_SOURCE),
        tolerance_mm=Figure(0.1 if t <= 1.0 else 0.15, "+/-0.1 mm up to 1 mm sheet, "
                            "+/-0.15 mm to 3 mm", LASER_TOLERANCE_SOURCE),
        compensation_per_side_mm=Figure(0.0, "nominal contour; the kerf offset (kerf / 2) is "
                                        "the shop's CAM setting", LASER_KERF_SOURCE),
        kerf_mm=kerf)


#: An etched edge: no recast layer, but the etch profile's rough, cusped wall; no fatigue
#: data of etched notches were found, so the machined class is taken, as for wire EDM.
ETCHED_SURFACE = SurfaceFatigue(
    surface="photochemically etched edge (etch profile, no recast layer)",
    marin_a_MPa=4.51, marin_b=-0.265, ceiling=0.9,
    reason=("no fatigue data of photochemically etched notches found: Marin's machined-surface "
            "factor k_a = 4.51 S_u^-0.265 (Shigley's Mechanical Engineering Design, 9th ed., "
            "Table 6-2), capped at 0.9 as for wire EDM; an assumption to replace by the "
            "etcher's coupon data"))
#: A laser-cut edge: a heat-affected zone and dross at the edge; taken as the machined class
#: like wire EDM, for want of notch data.
LASER_CUT_SURFACE = SurfaceFatigue(
    surface="laser-cut edge (heat-affected zone, striations)",
    marin_a_MPa=4.51, marin_b=-0.265, ceiling=0.9,
    reason=("no fatigue data of laser-cut notches found: Marin's machined-surface factor "
            "k_a = 4.51 S_u^-0.265 (Shigley's Mechanical Engineering Design, 9th ed., Table "
            "6-2), capped at 0.9 as for wire EDM; the heat-affected zone may lower it further"))


for _process in (
        CutProcess(
            "wire-edm", "wire EDM from sheet", WIRE_CUT_SHEET_MM, WIRE_CUT_SHEET_SOURCE,
            _wire_limits,
            ShopFile("wire-EDM cutting DXF", False, EDM_TABS, True,
                     ("nominal contour: the wire offset (kerf / 2) is the CAM's",
                      "tabs (layer TAB) are left uncut and cut last",
                      WIRE_SURFACE + "."), start_holes=True),
            WIRE_SURFACE, (WIRE_TOLERANCE_SOURCE, MICRO_JOINT_SOURCE), WIRE_EDM_SURFACE,
            flexure_sheet_range_mm=WIRE_SHEET_MM, flexure_sheet_source=WIRE_SHEET_SOURCE),
        CutProcess(
            "photochemical-etching", "photochemical etching from foil", ETCH_SHEET_MM,
            ETCH_SHEET_SOURCE, _etch_limits,
            ShopFile("etch artwork DXF", True, None, False,
                     ("outline compensated: offset outward by the undercut per side (holes "
                      "smaller by it); the etched part lands on the nominal",
                      "one artwork for both phototools: the back side's is its mirror image, "
                      "registered to the front's; etch from both sides",
                      "parts are held in the fret by the etcher's own tabs")),
            ETCH_SURFACE, (TECH_ETCH, ETCH_FACTOR_SOURCE, ETCH_TOLERANCE_SOURCE),
            ETCHED_SURFACE),
        CutProcess(
            "laser-cutting", "laser cutting from sheet", LASER_SHEET_MM, LASER_SOURCE,
            _laser_limits,
            ShopFile("laser cutting DXF", False, EDM_TABS, True,
                     ("nominal contour: kerf compensation (kerf / 2 outward of the part) is "
                      "the CAM's",
                      "micro-joints (layer TAB) are left uncut and broken off last",
                      "each cut pierces at its lead-in's start: no drilled start holes",
                      LASER_SURFACE + ".")),
            LASER_SURFACE, (LASER_SOURCE, LASER_KERF_SOURCE, LASER_TOLERANCE_SOURCE),
            LASER_CUT_SURFACE)):
    register_process(_process)


#: The thinnest sheet a design may name: the thinnest any cut process takes
#: (each process refuses a sheet outside its own range: :func:`check_sheet_process`).
THINNEST_SHEET_MM = min(p.flexure_sheet()[0] for p in CUT_PROCESSES.values())


def check_sheet_process(d, p) -> None:
    """Cross-field rule of a design file: the sheet lies in the range of the
    element's process (:attr:`CutProcess.sheet_range_mm`).

    Args:
        d: the validated design file (``d.sheet.thickness_mm``, ``d.element.process``).
        p: the :class:`~tactcad.vocabulary.schema.Problems` the refusal is added to.
    """
    name = getattr(d.element, "process", None) or DEFAULT_CUT_PROCESS
    process = CUT_PROCESSES[name]
    lo, hi, source = process.flexure_sheet()
    t = d.sheet.thickness_mm
    if not lo - 1e-12 <= t <= hi + 1e-12:
        others = [q.name for q in CUT_PROCESSES.values()
                  if q.flexure_sheet()[0] <= t <= q.flexure_sheet()[1] and q.name != name]
        p.add("sheet.thickness_mm", t, f"{lo:g} <= value <= {hi:g} mm for element.process = "
              f"{name!r}" + (f", or element.process one of {', '.join(others)}" if others else ""),
              source)


def check_spacer_process(d, p) -> None:
    """Cross-field rule of a stacked design: a stated ``[spacer] process`` cuts the
    spacer's plate (thickness = array pitch - sheet, mm), so a spacer is judged by its
    process's cutting range, not by a flexure's.

    Args:
        d: the validated design file (``d.spacer``, ``d.array.pitch_mm``, ``d.sheet.thickness_mm``).
        p: the :class:`~tactcad.vocabulary.schema.Problems` the refusal is added to.
    """
    name = getattr(getattr(d, "spacer", None), "process", None)
    if name is None or d.array.columns < 2:
        return
    t = d.array.pitch_mm - d.sheet.thickness_mm
    process = CUT_PROCESSES[name]
    if t > 0 and not process.holds_sheet(t):
        lo, hi = process.sheet_range_mm
        fits = [q.name for q in CUT_PROCESSES.values() if q.holds_sheet(t)]
        p.add("spacer.process", name,
              f"a process that cuts the {t:g} mm spacer (pitch - sheet); {name} cuts "
              f"{lo:g}-{hi:g} mm" + (f": one of {', '.join(fits)}" if fits else ""),
              process.sheet_source)


def first_process_holding(thickness_mm: float) -> str:
    """The name of the first registered cut process that cuts a plate of
    ``thickness_mm`` (mm); the default process when none does (its own check then
    names the range)."""
    fits = [q.name for q in CUT_PROCESSES.values() if q.holds_sheet(thickness_mm)]
    return fits[0] if fits else DEFAULT_CUT_PROCESS


#: The default cut process's part process (wire EDM): what an element is made by when the
#: design does not say; its surface factor is the one strength applies at the notch root.
ELEMENT_PROCESS = CUT_PROCESSES[DEFAULT_CUT_PROCESS].part_process()
