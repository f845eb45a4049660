"""A silicon die for a grasper's jaw: two rows of piezoresistive cantilevers in an SOI
wafer's device layer, the reference row stiff and the measuring row soft, paired across the
die at equal distance from the jaw's pivot, sized from the stiffness targets and the jaw's
pocket (the paper's lumped model, eq. 1-3, with K_r / K_m about 10).

The die (um; x along the jaw, y across it, the die's lower-left corner at the origin):

* a solid frame around a window over two cavities etched into the handle before the wafer
  is bonded (a cavity SOI wafer, :mod:`tactcad.vocabulary.soi_process`), one under each
  row; the window's edges across the die are the beams' roots, so the front masks'
  alignment to the buried cavities moves every root; each cavity's floor is its row's
  hard stop (:func:`cavity_depth_um`);
* row 1, the reference beams, clamped at the window's lower edge (y = frame), pointing +y;
  row 2, the measuring beams, clamped at its upper edge, pointing -y; column j of both
  rows at one x: a unit's two tips at one distance from the pivot;
* each beam of width w and the device layer's thickness t, bent out of the wafer's plane
  by the tissue's force on a post at its free end (L from the root to the post's centre);
  K = E w t^3 / (4 L^3) (Euler-Bernoulli, clamped at the root), E the modulus along the
  beam, <110> on a (100) wafer (:mod:`tactcad.vocabulary.crystal`);
* a U-shaped p-type piezoresistor along each beam from its root (two legs joined at the
  far end), contacted on the frame, and beside it on the frame a reference resistor of the
  same implant, unstrained: the two in series are the beam's half bridge, on three bond pads
  behind the beam (completed off the die by two fixed arms), so the implant's TCR cancels
  between them and the zero drifts only by their mismatch;
* the device layer over the window etched away except the beams (front DRIE): the etch
  breaks through into the cavities and frees the beams.

Sizing (:func:`die_plan`): the stiffness targets (:class:`tactcad.studies.inverse_design.
Targets`: K_m = sqrt(K_lo K_hi / X), K_r = X K_m) and the pitch along the die give, for each
stock device-layer thickness and beam width, L = (E w t^3 / (4 K))^(1/3); of the pairs whose
two beams, their posts and the slot between the tips fit across the window, each beam at
least :data:`SLENDERNESS` times as long as it is wide, the die takes the one with the lowest
root stress at the rating, 6 F L_m / (w t^2) (the thicker layer on a tie: its +-tolerance
moves K by 3 dt / t). Each row's cavity is as deep as its beam's free end goes at
:data:`STOP_MULTIPLE` x the beam's rated tip deflection, the cavity's depth tolerance
taken off. Every choice is kept with its reason.

Units: um for the layout, mm and N/mm for the mechanics' interfaces as named.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from tactcad.errors import DesignError
from tactcad.vocabulary.crystal import SILICON, SILICON_P_TYPE, in_plane_direction
from tactcad.vocabulary.soi_process import (CAVITY_ALIGNMENT_UM, CAVITY_DEPTH_SOURCE,
                                            CAVITY_DEPTH_TOLERANCE_REL, DEFAULT_BOX_UM,
                                            DEFAULT_HANDLE_UM, DEVICE_LAYER_CHOICES_UM,
                                            DEVICE_TOLERANCE_SOURCE, DEVICE_TOLERANCE_UM,
                                            SoiStack, drie_min_width_um)

#: Least beam length over width: Euler-Bernoulli's slender-beam form holds within a few %.
SLENDERNESS = 3.0
#: The frame along each long side (um): the contacts, the leads and the bond pads.
FRAME_UM = 300.0
#: Solid silicon at each end of the die beyond the outer columns' half pitch (um).
END_UM = 250.0
#: Bond pad side and the space between a beam's two pads (um).
PAD_UM, PAD_SPACE_UM = 80.0, 20.0
#: The pads' inner edge from the root line (um): room for the contacts and the jogs.
PAD_SETBACK_UM = 60.0
#: The on-die reference resistor of each beam's half bridge: the same implant, legs and gap
#: as the beam's resistor, on the frame beside the root where the beam's bending does not
#: reach (its axis this far along the die from the beam's), its far end this far from the
#: window's edge, its legs at most this long; its third pad's centre along the die (um).
REFERENCE_AXIS_UM, REFERENCE_CLEAR_UM, REFERENCE_LEGS_MAX_UM = 250.0, 20.0, 200.0
THIRD_PAD_AXIS_UM = 350.0
#: The leads' jog below each resistor's contacts (um).
LEAD_JOG_UM = 20.0
#: How far the two resistors' TCRs may differ, relative (assumption: one implant and anneal,
#: 250 um apart on one die; a diffused pair's TCRs track to about a per cent of their value):
#: the half bridge's zero drift is this share of the uncancelled one.
REFERENCE_TCR_MISMATCH_REL = 0.01
#: The post on each beam's free end: its side (at most the beam's width) and least height
#: (um).
POST_MAX_UM, POST_HEIGHT_UM = 100.0, 50.0
#: A post stands at least this much taller than its beam's deepest stop travel (um): the
#: tissue sinks round a post, and the face must not meet it before the stop takes the
#: overload (assumption); heights are drawn to :data:`POST_STEP_UM`.
POST_CLEARANCE_UM, POST_STEP_UM = 10.0, 5.0
#: The tallest post over its side (assumption: an SU-8 or plated post on a beam's end at
#: 5:1, well inside the 10:1 and more SU-8 reaches on its own).
POST_ASPECT_MAX = 5.0
#: The handle left under the deepest cavity (um) (assumption: the die's floor keeps 100 um
#: of silicon for its handling and bond).
HANDLE_FLOOR_UM = 100.0
#: Piezoresistor legs: width, gap between them (um); the implant's margin to the beam's
#: edges; the legs' run onto the frame for the contacts (um).
LEG_UM, LEG_GAP_UM, RESISTOR_MARGIN_UM, RESISTOR_RUN_UM = 8.0, 8.0, 10.0, 20.0
#: Contact side, the metal's cover beyond it and the metal lead's width (um).
CONTACT_UM, METAL_ENCLOSURE_UM, LEAD_UM = 4.0, 3.0, 6.0
#: The resistor's length over the reference beam's (both rows carry the same resistor, so
#: that the two arms of a unit start equal): a third, where the root's stress is highest.
RESISTOR_FRACTION = 1.0 / 3.0
#: The implant's depth (um), carriers taken uniform over it, and its dose (cm^-2)
#: (assumptions: a shallow boron implant after its anneal).
JUNCTION_DEPTH_UM = 0.5
IMPLANT_DOSE_PER_CM2 = 2e14
#: The mean tensile strength of Bosch-process DRIE silicon bars (MPa), as etched, and its
#: source (bars 120 x 5 x 5 um; 3.6 GPa after a wet etch of the surface residue). A
#: reference figure for the root stress, not a design strength: without the Weibull
#: modulus and stressed area of a die's own sidewalls it gives no failure probability.
BOSCH_MEAN_STRENGTH_MPA = 1900.0
BOSCH_STRENGTH_SOURCE = ("IEEJ Trans. Sensors and Micromachines 132(9), 2012, p. 320: bars "
                         "120 x 5 x 5 um, mean 1.9 GPa as etched, 3.6 GPa after a wet etch")
#: Columns per row, pitch along the die and the die's name when the caller states none
#: (the design file's, the die command's and design's defaults).
DEFAULT_COLUMNS, DEFAULT_PITCH_UM, DEFAULT_DIE_NAME = 5, 1000.0, "mems_die"
#: Beam widths searched (um): from the slot rule's smallest beam to the pitch's widest.
WIDTH_STEP_UM = 5.0
#: A row's hard stop, its cavity's floor, engages at this multiple of its beam's rated tip
#: deflection (the metal combs' rule, :data:`tactcad.studies.comb_design.STOP_MULTIPLE`):
#: the beam reads its whole range, an overload rests on the floor.
STOP_MULTIPLE = 1.3
#: Cavity depths are drawn to this step (um), rounded up.
CAVITY_STEP_UM = 0.5


@dataclass(frozen=True)
class WeibullPair:
    """A lab's Weibull pair for the fracture strength of its own etched silicon (from its
    fab's test structures; none is in the library): P_f = 1 - exp(-(A_eff / A_0)
    (sigma / sigma_0)^m) for a surface of effective area A_eff at peak stress sigma.

    Attributes:
        modulus: m, > 1. characteristic_MPa: sigma_0, the stress at which 63.2 % of the
            test structures break (MPa). reference_area_um2: A_0, the test structures'
            effective area the pair is for (um^2). source: where the pair comes from.
        failure_probability_max: the die's largest failure probability the lab accepts.
    """

    modulus: float
    characteristic_MPa: float
    reference_area_um2: float
    source: str
    failure_probability_max: float


@dataclass(frozen=True)
class Beam:
    """One cantilever of the die (um; y_root the root line, direction +1 up, -1 down)."""

    number: int
    role: str
    row: int
    column: int
    x_um: float
    y_root_um: float
    direction: int
    length_um: float
    width_um: float
    thickness_um: float

    @property
    def tip_y_um(self) -> float:
        """y of the post's centre (the tip force)."""
        return self.y_root_um + self.direction * self.length_um


@dataclass(frozen=True)
class DiePlan:
    """A validated die: its stack, beams, resistors, pads and outline, the mechanics at
    the closed form, and the reason for every derived dimension (um, N/mm, MPa, N).

    Attributes:
        reasons: derived dimension -> why it has its value.
    """

    name: str
    stack: SoiStack
    rows: int
    columns: int
    pitch_um: float
    die_length_um: float
    die_width_um: float
    frame_um: float
    end_um: float
    beam_width_um: float
    reference_length_um: float
    measuring_length_um: float
    post_um: float
    post_height_um: float
    resistor_length_um: float
    youngs_modulus_MPa: float
    pi_longitudinal_per_Pa: float
    k_r_N_per_mm: float
    k_m_N_per_mm: float
    targets: tuple[float, float]
    full_scale_force_N: float
    beams: tuple[Beam, ...]
    reasons: dict = field(default_factory=dict, compare=False, hash=False)
    #: the K_obj range the die reads (N/mm)
    kobj_range_N_per_mm: tuple[float, float] = (0.0, 0.0)
    #: the resistors' boron implant dose (cm^-2; :func:`tactcad.studies.die_doping.chosen_implant_dose`)
    implant_dose_per_cm2: float = IMPLANT_DOSE_PER_CM2
    #: each row's cavity depth under its beams, the row's hard stop (um): reference, measuring
    cavity_depths_um: tuple[float, float] = (0.0, 0.0)
    #: the lab's Weibull pair for its etched silicon, or None (strength then undecided)
    weibull: WeibullPair | None = None

    @property
    def window_um(self) -> tuple[float, float, float, float]:
        """The window over the cavities (x0, y0, x1, y1): the beams' roots are its long
        edges."""
        return (self.end_um, self.frame_um, self.die_length_um - self.end_um,
                self.die_width_um - self.frame_um)

    @property
    def cavity_split_y_um(self) -> float:
        """Where the reference row's cavity meets the measuring row's (um): midway between
        the two rows' free ends (each beam reaches the post's far edge)."""
        ref_end = self.frame_um + self.reference_length_um + self.post_um / 2
        meas_end = self.die_width_um - self.frame_um - self.measuring_length_um - self.post_um / 2
        return (ref_end + meas_end) / 2

    @property
    def cavities_um(self) -> dict[str, tuple[float, float, float, float]]:
        """Each row's cavity in the handle (x0, y0, x1, y1), by role: the window split at
        :attr:`cavity_split_y_um`."""
        x0, y0, x1, y1 = self.window_um
        split = self.cavity_split_y_um
        return {"reference": (x0, y0, x1, split), "measuring": (x0, split, x1, y1)}

    def cavity_depth_of(self, beam: Beam) -> float:
        """The depth of the cavity under ``beam`` (um)."""
        return self.cavity_depths_um[0 if beam.role == "reference" else 1]

    def rated_tip_um(self, beam: Beam) -> float:
        """The most ``beam``'s post centre travels in use (um): :func:`rated_tip_deflections_um`."""
        ref, meas = rated_tip_deflections_um(self.k_r_N_per_mm, self.k_m_N_per_mm,
                                             self.full_scale_force_N, self.kobj_range_N_per_mm)
        return ref if beam.role == "reference" else meas

    def stop_engagement_um(self, beam: Beam) -> tuple[float, float, float]:
        """The post centre's travel when ``beam``'s free end meets its cavity's floor (um):
        (nominal, shallowest, deepest cavity within its depth tolerance)."""
        at_post = self.cavity_depth_of(beam) / end_over_post(beam.length_um, self.post_um)
        tol = CAVITY_DEPTH_TOLERANCE_REL
        return at_post, at_post * (1 - tol), at_post * (1 + tol)

    @property
    def reference_resistor_length_um(self) -> float:
        """The on-die reference resistor's length (um): the beam resistor's, at most
        :data:`REFERENCE_LEGS_MAX_UM` (so that it and its leads fit in the frame). It need
        not match: its TCR is the same implant's, so the half bridge's zero does not drift
        whatever the two resistances (a mismatch only offsets it, tared)."""
        return min(self.resistor_length_um, REFERENCE_LEGS_MAX_UM)

    @property
    def acceptors_per_cm3(self) -> float:
        """The resistors' boron concentration (cm^-3): the dose over the junction depth."""
        return self.implant_dose_per_cm2 / (JUNCTION_DEPTH_UM * 1e-4)

    @property
    def thickness_um(self) -> float:
        """The die's thickness with its posts (um)."""
        return self.stack.total_um + self.post_height_um

    def stress_MPa_at_rating(self, beam: Beam) -> float:
        """The root's surface bending stress at the rated force (MPa): 6 F L / (w t^2)."""
        return (6 * self.full_scale_force_N * beam.length_um * 1e-3
                / (beam.width_um * 1e-3 * (beam.thickness_um * 1e-3) ** 2))

    def as_json(self) -> dict:
        return {"name": self.name, "stack": self.stack.__dict__, "rows": self.rows,
                "columns": self.columns, "pitch_um": self.pitch_um,
                "die_length_um": self.die_length_um, "die_width_um": self.die_width_um,
                "die_thickness_um": self.thickness_um,
                "beam_width_um": self.beam_width_um,
                "reference_length_um": self.reference_length_um,
                "measuring_length_um": self.measuring_length_um,
                "post_um": self.post_um, "post_height_um": self.post_height_um,
                "resistor_length_um": self.resistor_length_um,
                "youngs_modulus_MPa": self.youngs_modulus_MPa,
                "pi_longitudinal_per_Pa": self.pi_longitudinal_per_Pa,
                "K_r_N_per_mm": self.k_r_N_per_mm, "K_m_N_per_mm": self.k_m_N_per_mm,
                "targets_N_per_mm": {"K_r": self.targets[0], "K_m": self.targets[1]},
                "kobj_range_N_per_mm": list(self.kobj_range_N_per_mm),
                "full_scale_force_N": self.full_scale_force_N,
                "stress_MPa_at_rating": {b.role: self.stress_MPa_at_rating(b)
                                         for b in self.beams[:: self.columns]},
                "cavity_depths_um": {"reference": self.cavity_depths_um[0],
                                     "measuring": self.cavity_depths_um[1]},
                "weibull": None if self.weibull is None else dict(self.weibull.__dict__),
                "reasons": dict(self.reasons)}


def beam_stiffness_N_per_mm(youngs_modulus_MPa: float, width_um, thickness_um, length_um):
    """K = E w t^3 / (4 L^3) of a cantilever tip-loaded out of plane (N/mm; um in)."""
    return youngs_modulus_MPa * (width_um * 1e-3) * (thickness_um * 1e-3) ** 3 / (
        4 * (length_um * 1e-3) ** 3)


def length_for_stiffness_um(youngs_modulus_MPa: float, width_um: float, thickness_um: float,
                            k_N_per_mm: float) -> float:
    """L (um) at which a beam of width w, thickness t (um) has K (N/mm): the inverse of
    :func:`beam_stiffness_N_per_mm`."""
    return 1e3 * (youngs_modulus_MPa * width_um * 1e-3 * (thickness_um * 1e-3) ** 3
                  / (4 * k_N_per_mm)) ** (1 / 3)


def die_plan(targets, room, *, columns: int = DEFAULT_COLUMNS,
             pitch_um: float = DEFAULT_PITCH_UM, name: str = DEFAULT_DIE_NAME,
             box_um: float = DEFAULT_BOX_UM, handle_um: float = DEFAULT_HANDLE_UM,
             angle_from_110_deg: float = 0.0,
             implant_dose_per_cm2: float = IMPLANT_DOSE_PER_CM2,
             dose_reason: str = "") -> DiePlan:
    """The die for ``targets`` in the jaw's ``room``.

    Args:
        targets: :class:`tactcad.studies.inverse_design.Targets` (K_r / K_m, the K_obj
            range, the rated full-scale force).
        room: :class:`tactcad.partlib.grasper_jaw.JawRoom` (its pocket, mm).
        columns: units along the die (2 ... 50). pitch_um: their spacing (um).
        box_um, handle_um: the SOI stack's buried oxide and handle (um).
        angle_from_110_deg: the beams' direction in the (100) wafer, from [110].
        implant_dose_per_cm2: the resistors' boron dose (cm^-2), > 0; ``dose_reason`` why
            (:func:`tactcad.studies.die_doping.chosen_implant_dose` gives both).

    Returns:
        :class:`DiePlan`.

    Raises:
        DesignError: a value out of range, no stock device layer and beam width fit
            (naming what binds and the largest K_m the die holds), or the rated travels
            would need stops deeper than the handle allows or posts taller than they stand
            (naming a lighter rating).
    """
    if not (isinstance(columns, int) and 2 <= columns <= 50):
        raise DesignError("--columns", columns, "an integer 2 ... 50")
    if not (math.isfinite(implant_dose_per_cm2) and 1e11 <= implant_dose_per_cm2 <= 1e17):
        raise DesignError("implant_dose_per_cm2", implant_dose_per_cm2, "1e11 ... 1e17 cm^-2")
    if not (isinstance(pitch_um, (int, float)) and math.isfinite(pitch_um)
            and LEAST_PITCH_UM <= pitch_um <= 5000.0):
        raise DesignError("--pitch-um", pitch_um, f"{LEAST_PITCH_UM:g} ... 5000 um",
                          "each beam's three bond pads and its reference resistor lie on the "
                          "frame within one pitch")
    width = round(room.across_mm * 1e3, 3)
    length = columns * pitch_um + 2 * END_UM
    if length > room.along_mm * 1e3 + 1e-6:
        raise DesignError("--columns", columns,
                          f"at most {int((room.along_mm * 1e3 - 2 * END_UM) // pitch_um)} "
                          f"columns at {pitch_um:g} um pitch in the {room.label}'s "
                          f"{room.along_mm:g} mm pocket")
    direction = in_plane_direction(angle_from_110_deg)
    E = float(SILICON.young_modulus_MPa(direction))
    window = width - 2 * FRAME_UM
    k_r, k_m = targets.k_r, targets.k_m
    fitting = _fitting_beams(E, k_r, k_m, window, pitch_um)
    if not fitting:
        raise _no_fit(targets, room, window, pitch_um, E)
    per_N, neg_t, w, slot, post, l_r, l_m = min(fitting)
    t = -neg_t
    stack = SoiStack(t, box_um, handle_um, DEVICE_TOLERANCE_UM)
    beams = []
    for row, (role, l, y0, sign) in enumerate((("reference", l_r, FRAME_UM, +1),
                                               ("measuring", l_m, width - FRAME_UM, -1)),
                                              start=1):
        for c in range(columns):
            beams.append(Beam(len(beams) + 1, role, row, c + 1,
                              END_UM + (c + 0.5) * pitch_um, y0, sign, l, w, t))
    resistor = RESISTOR_FRACTION * l_r
    tol = DEVICE_TOLERANCE_UM / t
    # the highest root stress at the rating (the longer, measuring beam's): 6 F L / (w t^2)
    root_MPa = _root_MPa(per_N, targets.full_scale_force_N)
    if root_MPa >= BOSCH_MEAN_STRENGTH_MPA:
        raise _past_strength(targets.full_scale_force_N, root_MPa)
    align = CAVITY_ALIGNMENT_UM
    rated = rated_tip_deflections_um(k_r, k_m, targets.full_scale_force_N,
                                     targets.k_obj_range_N_per_mm)
    depths = (cavity_depth_um(rated[0], l_r, post), cavity_depth_um(rated[1], l_m, post))
    deepest = max(d * (1 + CAVITY_DEPTH_TOLERANCE_REL) / end_over_post(length, post)
                  for d, length in zip(depths, (l_r, l_m)))
    post_height = post_height_um(deepest)
    tallest, room_um = POST_ASPECT_MAX * post, handle_um - HANDLE_FLOOR_UM
    if post_height > tallest:
        raise _stops_too_deep(targets.full_scale_force_N, (tallest - POST_CLEARANCE_UM) / deepest,
                              f"a post would go {deepest:.4g} um to its stop, and to stand "
                              f"{POST_CLEARANCE_UM:g} um proud there it would be taller than "
                              f"{POST_ASPECT_MAX:g} x its {post:g} um side ({tallest:g} um)")
    if max(depths) * (1 + CAVITY_DEPTH_TOLERANCE_REL) > room_um:
        raise _stops_too_deep(targets.full_scale_force_N,
                              room_um / (max(depths) * (1 + CAVITY_DEPTH_TOLERANCE_REL)),
                              f"the measuring row's {max(depths):g} um cavity (+"
                              f"{100 * CAVITY_DEPTH_TOLERANCE_REL:g} %) would leave less than "
                              f"{HANDLE_FLOOR_UM:g} um of the {handle_um:g} um handle under it")
    reasons = {
        "device_um": f"of the stock device layers ({', '.join(f'{x:g}' for x in DEVICE_LAYER_CHOICES_UM)} um) and beam widths whose two beams, posts "
                     f"and the slot between the tips fit across the {window:g} um window, "
                     f"the pair with the lowest root stress at the rating (the thicker "
                     f"layer on a tie); its +-{DEVICE_TOLERANCE_UM:g} um "
                     f"({DEVICE_TOLERANCE_SOURCE}) moves every K by +-{300 * tol:.2g} % "
                     "alike (R keeps it)",
        "beam_width_um": f"with the layer: the pair with the lowest root stress (a wider "
                         f"beam is stressed less), beside the {slot:.3g} um DRIE slot in the "
                         f"{pitch_um:g} um pitch, at most 1/{SLENDERNESS:g} of the reference "
                         "beam's length (slender: Euler-Bernoulli) and wide enough for the "
                         "resistor's two legs",
        "reference_length_um": f"K_r = {k_r:.4g} N/mm = E w t^3 / (4 L^3), E = {E / 1e3:.4g} "
                               f"GPa along the beam ({angle_from_110_deg:g} deg from <110> on "
                               f"(100), {SILICON.source.split(',')[0]})",
        "measuring_length_um": f"K_m = {k_m:.4g} N/mm the same way; K_r / K_m = "
                               f"{targets.kr_over_km:g} gives L_m / L_r = "
                               f"{targets.kr_over_km ** (1 / 3):.4g}",
        "alignment": f"the front masks' +-{align:g} um alignment to the buried cavities "
                     f"moves both rows' roots one way: K_r / K_m by "
                     f"+-{300 * align * (1 / l_r + 1 / l_m):.2g} %",
        "cavity_depths_um": (
            f"reference {depths[0]:g} um, measuring {depths[1]:g} um: each row's beam end "
            f"meets its cavity's floor at {STOP_MULTIPLE:g} x the post's rated travel "
            f"({rated[0]:.3g} um: the rated force over K_r; {rated[1]:.3g} um: the deepest "
            "the measuring post goes while its reference reads up to the rated force over "
            "the K_obj range, eq. 1), the beam's end beyond the post "
            f"(1 + 3 a / 2L), the depth's -{100 * CAVITY_DEPTH_TOLERANCE_REL:g} % "
            f"({CAVITY_DEPTH_SOURCE}) taken off, rounded up to {CAVITY_STEP_UM:g} um; the "
            "air squeezed under the beams is not modelled (a static reading)"),
        "resistor_length_um": f"{RESISTOR_FRACTION:.3g} of the reference beam, in both rows "
                              "(equal arms), where the root's stress is highest",
        "die_um": f"{width:g} um across (the {room.label}'s pocket, {room.across_mm:g} mm), "
                  f"{length:g} um along: {columns} columns at {pitch_um:g} um and "
                  f"{END_UM:g} um ends",
        "implant_dose_per_cm2": dose_reason or f"{implant_dose_per_cm2:.2g} cm^-2 (assumption)",
        "post_um": f"a post {post:g} um square and {post_height:g} um proud on each free "
                   f"end (SU-8 or plated; it meets the tissue before the beam): at least "
                   f"{POST_HEIGHT_UM:g} um and {POST_CLEARANCE_UM:g} um more than the "
                   f"deepest a post goes to its stop ({deepest:.3g} um), so that the face "
                   "never meets the tissue before the stop takes an overload",
        "strength": (f"undecided: the root's {root_MPa:.4g} MPa at the rating is "
                     f"{100 * root_MPa / BOSCH_MEAN_STRENGTH_MPA:.2g} % of the mean tensile "
                     f"strength of Bosch-etched silicon bars ({BOSCH_STRENGTH_SOURCE}); no "
                     "Weibull modulus of DRIE sidewalls with its stressed area is sourced, so "
                     "no failure probability is given"),
    }
    return DiePlan(name, stack, 2, columns, pitch_um, length, width, FRAME_UM, END_UM, w,
                   l_r, l_m, post, post_height, resistor, E,
                   float(SILICON_P_TYPE.longitudinal(direction)) * 1e-11,
                   float(beam_stiffness_N_per_mm(E, w, t, l_r)),
                   float(beam_stiffness_N_per_mm(E, w, t, l_m)), (k_r, k_m),
                   targets.full_scale_force_N, tuple(beams), reasons,
                   tuple(float(v) for v in targets.k_obj_range_N_per_mm),
                   float(implant_dose_per_cm2), depths)


def post_height_um(deepest_stop_travel_um: float) -> float:
    """The posts' height (um): :data:`POST_HEIGHT_UM` at least, and
    :data:`POST_CLEARANCE_UM` more than the deepest a post goes to its stop, rounded up to
    :data:`POST_STEP_UM`."""
    need = deepest_stop_travel_um + POST_CLEARANCE_UM
    return max(POST_HEIGHT_UM, POST_STEP_UM * math.ceil(need / POST_STEP_UM - 1e-9))


def _stops_too_deep(force_N: float, scale: float, why: str) -> DesignError:
    """The refusal of a rating whose stops lie too deep (``why``): the travels go as the
    force, so the alternative scales it by ``scale`` (< 1), 5 % lower for the depths'
    rounding."""
    below = float(f"{0.95 * force_N * scale:.2g}")
    return DesignError("--full-scale-force", force_N, f"at most about {below:g} N", why,
                       alternatives=[{"option": f"--full-scale-force {below:g}",
                                      "words": "a lighter rating: shallower stops, shorter "
                                               "posts"}])


def end_over_post(length_um: float, post_um: float) -> float:
    """A tip-loaded cantilever's deflection at its free end, the post's far edge (L + a,
    a = post / 2), over that at the post's centre (L): 1 + 3 a / (2 L) (Euler-Bernoulli:
    the beam runs straight beyond the load, at the slope 3 delta / (2 L))."""
    return 1.0 + 0.75 * post_um / length_um


def rated_tip_deflections_um(k_r: float, k_m: float, force_N: float,
                             kobj_range_N_per_mm) -> tuple[float, float]:
    """The most each row's post travels in use (um): the reference's at the rated force,
    F / K_r; the measuring one's while its reference reads up to F over the K_obj range,
    F (K_r + K_lo) / (K_r (K_m + K_lo)) (eq. 1, uncoupled: the pair pressed into one K_obj
    by one travel; deepest at the softest tissue when K_r > K_m).

    Args:
        k_r, k_m: the rows' stiffness (N/mm). force_N: the rated force (N).
        kobj_range_N_per_mm: (K_lo, K_hi) (N/mm).
    """
    lo = min(kobj_range_N_per_mm)
    reference = force_N / k_r
    measuring = force_N * (k_r + lo) / (k_r * (k_m + lo))
    return 1e3 * reference, 1e3 * max(measuring, reference)


def cavity_depth_um(rated_um: float, length_um: float, post_um: float) -> float:
    """A row's cavity depth (um): its beam's end meets the floor when the post has
    travelled :data:`STOP_MULTIPLE` x ``rated_um`` in the shallowest cavity the depth
    tolerance allows; rounded up to :data:`CAVITY_STEP_UM`."""
    need = (STOP_MULTIPLE * rated_um * end_over_post(length_um, post_um)
            / (1.0 - CAVITY_DEPTH_TOLERANCE_REL))
    return CAVITY_STEP_UM * math.ceil(need / CAVITY_STEP_UM - 1e-9)


def _past_strength(force_N: float, root_MPa: float) -> DesignError:
    """The refusal of a rating at which even the least stressed fitting pair's measuring
    root reaches the mean strength of etched silicon: half such dies would break at it."""
    breaking_N = force_N * BOSCH_MEAN_STRENGTH_MPA / root_MPa
    below = float(f"{0.99 * breaking_N:.2g}")
    return DesignError("--full-scale-force", force_N, f"below {breaking_N:.3g} N",
                       f"the measuring beam's root reaches the mean tensile strength of "
                       f"Bosch-etched silicon ({BOSCH_MEAN_STRENGTH_MPA:g} MPa, "
                       f"{BOSCH_STRENGTH_SOURCE}) at {breaking_N:.3g} N with the least stressed "
                       f"beams that fit (root {root_MPa:.4g} MPa at {force_N:g} N)",
                       alternatives=[{"option": f"--full-scale-force {below:g}",
                                      "words": "below the mean strength (its failure "
                                               "probability is not sized: no Weibull modulus)"}])


def pads_span_um() -> float:
    """How far along the die one beam's pads and reference resistor reach (um): from the
    first pad's outer edge to the third pad's."""
    first = PAD_SPACE_UM / 2 + PAD_UM
    return first + THIRD_PAD_AXIS_UM + PAD_UM / 2


#: The smallest pitch along the die (um): one beam's pads and reference resistor, and the
#: pad space to the next beam's.
LEAST_PITCH_UM = pads_span_um() + PAD_SPACE_UM


def _resistor_width_um() -> float:
    """The narrowest beam that holds the U-shaped resistor with its margins (um)."""
    return 2 * LEG_UM + LEG_GAP_UM + 2 * RESISTOR_MARGIN_UM


def _widths(widest: float, narrowest: float) -> list[float]:
    """Beam widths from ``widest`` down, on a :data:`WIDTH_STEP_UM` grid (um)."""
    n = int(math.floor((widest - narrowest) / WIDTH_STEP_UM))
    return [round(widest - i * WIDTH_STEP_UM, 6) for i in range(max(n, 0) + 1)
            if widest - i * WIDTH_STEP_UM >= narrowest]


def _beam_pair(E: float, k_r: float, k_m: float, window: float, t: float, w: float,
               slot: float) -> tuple | None:
    """(root stress per N of the measuring beam, -t, w, slot, post, L_r, L_m) of the pair of
    beams of width ``w`` in a ``t`` layer, or None when the two beams, the post and the slot
    between the tips do not fit across the window or the reference beam is not slender
    (L_r >= :data:`SLENDERNESS` w); um."""
    post = min(w, POST_MAX_UM)
    l_r = length_for_stiffness_um(E, w, t, k_r)
    l_m = length_for_stiffness_um(E, w, t, k_m)
    if l_r + l_m + post + slot <= window and l_r >= SLENDERNESS * w:
        return 6 * l_m / (w * t * t), -t, w, slot, post, l_r, l_m
    return None


def _layer_widths(pitch_um: float) -> list[tuple[float, float, list[float]]]:
    """(device layer, DRIE slot, beam widths that leave room for the resistor) per stock layer (um)."""
    out = []
    for t in DEVICE_LAYER_CHOICES_UM:
        slot = drie_min_width_um(t)
        out.append((t, slot, _widths(pitch_um - slot, _resistor_width_um())))
    return out


def _fitting_beams(E: float, k_r: float, k_m: float, window: float, pitch_um: float) -> list:
    """Every stock device layer and beam width whose pair fits (:func:`_beam_pair`)."""
    pairs = (_beam_pair(E, k_r, k_m, window, t, w, slot)
             for t, slot, widths in _layer_widths(pitch_um) for w in widths)
    return [p for p in pairs if p is not None]


def _any_fitting_beam(E: float, k_r: float, k_m: float, window: float, pitch_um: float) -> bool:
    """Whether :func:`_fitting_beams` finds any: each layer's narrowest width decides it, as
    the beams' lengths (L ~ w^(1/3)) and the post grow with the width while the slenderness
    L_r / w falls."""
    return any(_beam_pair(E, k_r, k_m, window, t, min(widths), slot) is not None
               for t, slot, widths in _layer_widths(pitch_um) if widths)


#: Steps of the K_obj range's scale a refusal searches for its alternative (x 1.05 each).
SCALE_STEPS = 200


def _root_MPa(per_N: float, force_N: float) -> float:
    """The measuring root's surface stress (MPa) at ``force_N`` from a pair's 6 L_m / (w t^2)
    (:func:`_beam_pair`'s first figure, 1/um^2): N/um^2 is 1e6 MPa."""
    return force_N * per_N * 1e6


def _designs(E: float, k_r: float, k_m: float, window: float, pitch_um: float,
             force_N: float) -> bool:
    """Whether a die designs at these stiffnesses: a fitting pair (:func:`_any_fitting_beam`)
    whose least stressed measuring root stays below the mean strength at ``force_N``."""
    if not _any_fitting_beam(E, k_r, k_m, window, pitch_um):
        return False
    per_N = min(_fitting_beams(E, k_r, k_m, window, pitch_um))[0]
    return _root_MPa(per_N, force_N) < BOSCH_MEAN_STRENGTH_MPA


def _no_fit(targets, room, window: float, pitch_um: float, E: float) -> DesignError:
    """The refusal: no stock layer and width fits. Which way the targets miss (stiffer
    tissue fits: the beams were too long for the window; softer fits: too stubby to be
    slender beams) and the nearest scale of the K_obj range that designs (K_m and K_r go
    as the range's scale), as a pasteable alternative."""
    lo, hi = targets.k_obj_range_N_per_mm
    for step in range(1, SCALE_STEPS + 1):
        for scale, way in ((1.05 ** step, "stiffer"), (1.05 ** -step, "softer")):
            if _designs(E, targets.k_r * scale, targets.k_m * scale, window, pitch_um,
                        targets.full_scale_force_N):
                why = ("the beams are too long for the window: the softest pair that fits "
                       f"has K_m = {targets.k_m * scale:.4g} N/mm" if way == "stiffer" else
                       "the reference beam would be too short to bend as a slender beam: the "
                       f"stiffest that does has K_r = {targets.k_r * scale:.4g} N/mm")
                return DesignError(
                    "--kobj-range", [lo, hi],
                    f"K_r {targets.k_r:.4g} and K_m {targets.k_m:.4g} N/mm in slender beams "
                    f"(>= {SLENDERNESS:g} widths) that fit across the {window:g} um window of "
                    f"the {room.label}", why,
                    alternatives=[{"option": f"--kobj-range {lo * scale:.4g} {hi * scale:.4g}",
                                   "words": f"the same span of tissues, {way}, that fits"}])
    return DesignError("--kobj-range", [lo, hi], "targets whose beams fit the die",
                       f"no K_obj range within x{1.05 ** SCALE_STEPS:.3g} of this one fits the "
                       f"{window:g} um window at {pitch_um:g} um pitch: a wider jaw")
