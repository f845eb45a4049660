"""A silicon die for a grasper's jaw: two rows of piezoresistive cantilevers in an SOI
wafer's device layer, the reference row stiff and the measuring row soft, paired across the
die at equal distance from the jaw's pivot, sized from the stiffness targets and the jaw's
pocket (the paper's lumped model, eq. 1-3, with K_r / K_m about 10).

The die (um; x along the jaw, y across it, the die's lower-left corner at the origin):

* a solid frame around a window over two cavities etched into the handle before the wafer
  is bonded (a cavity SOI wafer, :mod:`tactcad.products.silicon_die.vocabulary.soi_process`), one under each
  row; the window's edges across the die are the beams' roots, so the front masks'
  alignment to the buried cavities moves every root; each cavity's floor is its row's
  hard stop (:func:`cavity_depth_um`);
* row 1, the reference beams, clamped at the window's lower edge (y = frame), pointing +y;
  row 2, the measuring beams, clamped at its upper edge, pointing -y; column j of both
  rows at one x: a unit's two tips at one distance from the pivot;
* each beam of width w and the device layer's thickness t, bent out of the wafer's plane
  by the tissue's force on a post at its free end (L from the root to the post's centre);
  1 / K = (L + dL)^3 / (3 E I) + L / (kappa G A) (Euler-Bernoulli bending and Timoshenko's
  shear, :func:`beam_stiffness_N_per_mm`; E the modulus along the beam, <110> on a (100)
  wafer, :mod:`tactcad.vocabulary.crystal`), dL the frame's give at the root as extra length
  (:func:`root_extension_um`, fitted to the fem3d level on the frame);
* a U-shaped p-type piezoresistor along each beam from its root (two legs joined at the
  far end), contacted on the frame, and beside it on the frame a reference resistor of the
  same implant, unstrained: the two in series are the beam's half bridge, on three bond pads
  behind the beam (completed off the die by two fixed arms), so the implant's TCR cancels
  between them and the zero drifts only by their mismatch;
* the device layer over the window etched away except the beams (front DRIE): the etch
  breaks through into the cavities and frees the beams.

Sizing (:func:`die_plan`): the stiffness targets (:class:`tactcad.studies.inverse_design.
Targets`: K_m = sqrt(K_lo K_hi / X), K_r = X K_m) and the pitch along the die give, for each
stock device-layer thickness and beam width, the L that has K (:func:`length_for_stiffness_um`);
of the pairs whose two beams, their posts and the gap between a unit's posts
(:func:`tip_gap_um`) fit across the window, each beam at
least :data:`SLENDERNESS` times as long as it is wide, the die takes the one with the lowest
root peak stress at the rating, K_t 6 F L_m / (w t^2) (K_t of the root's fillets,
:func:`root_stress_concentration`; the thicker layer on a tie: its +-tolerance
moves K by 3 dt / t). Each row's cavity is as deep as its beam's free end goes at
:data:`STOP_MULTIPLE` x the beam's rated tip deflection, the cavity's depth tolerance
taken off. Every choice is kept with its reason.

Units: um for the layout, mm and N/mm for the mechanics' interfaces as named.
"""

from __future__ import annotations

import bisect
import contextlib
import contextvars
import functools
import math
import numbers
import warnings
from dataclasses import dataclass, field
from typing import Iterator, NamedTuple

import numpy as np

from tactcad.vocabulary.rounding import round_down
from tactcad.errors import DesignError
from tactcad.vocabulary.binding_limits import FOOTPRINT
from tactcad.vocabulary.crystal import SILICON, SILICON_P_TYPE, in_plane_direction
from tactcad.products.silicon_die.vocabulary.soi_process import (CAVITY_ALIGNMENT_UM,
                                                                 CAVITY_DEPTH_SOURCE,
                                                                 CAVITY_DEPTH_TOLERANCE_REL,
                                                                 DEFAULT_BOX_UM, DEFAULT_HANDLE_UM,
                                                                 DEVICE_LAYER_CHOICES_UM,
                                                                 DEVICE_TOLERANCE_SOURCE,
                                                                 DEVICE_TOLERANCE_UM,
                                                                 DRIE_MIN_RADIUS_SOURCE,
                                                                 DRIE_MIN_RADIUS_UM,
                                                                 METAL_SPACE_UM, SoiStack,
                                                                 drie_min_width_um)

#: Least beam length over width: Euler-Bernoulli's slender-beam form holds within a few %.
SLENDERNESS = 3.0
#: The frame's give at a beam's root as extra beam length, over the device layer's thickness
#: t, at beam widths w / t: (w / t, dL / t). A die's beam is not clamped: its root runs into
#: the device layer bonded on the handle, the cavity under the beam, and the frame turns and
#: gives under the root's moment and shear. Each value is the bending length (with
#: Timoshenko's shear over L beside it, :func:`beam_stiffness_N_per_mm`) that has the
#: stiffness of tactcad's fem3d level on the frame
#: (:func:`tactcad.products.silicon_die.mechanics.die_fem3d.die_beam_fem3d`, silicon's tensor, <110>, 1 um of
#: buried oxide, extrapolated to within about 1 % in K), less the beam's length, for a
#: 40 um layer at L / t = 10.5. A wider beam loads a wider stretch of the frame: dL grows
#: towards the plane-strain value. (An independent isotropic model, CalculiX C3D20 graded
#: at the corner, found 0.56 t on the example's section at two lengths.)
ROOT_EXTENSION_OVER_T = ((1.0, 0.415), (2.0, 0.498), (3.45, 0.542), (6.0, 0.565),
                         (12.0, 0.584))
ROOT_EXTENSION_SOURCE = ("fitted to the die's fem3d level on its frame at w / t 1-12, "
                         "L / t 10.5")
#: Timoshenko's shear coefficient of a rectangular section (5/6).
SHEAR_COEFFICIENT = 5.0 / 6.0
#: The closed form's K against the fem3d level on the frame over the design's widths and
#: lengths (relative, either way): off the fitted points (w / t 1-12, L / t 4.5-36) it lies
#: within 0.9 % of fem3d (``tactcad bench die``), whose own extrapolation moves K by up to
#: about 1 %.
CLOSED_FORM_K_ERROR_REL = 0.02
#: The frame along each long side (um): the contacts, the leads and the bond pads.
FRAME_UM = 300.0
#: The die's carrier beyond its proximal end (mm): room for the flex cable's solder pads
#: (the jaw's pocket holds the die and this shelf, :mod:`tactcad.products.silicon_die.design.die_mount`).
BOND_SHELF_MM = 1.0
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
#: The least clear gap between a unit's two posts across the window, in post widths. The
#: tissue between them couples the posts (eq. 3 reads K_obj off by their mutual compliance,
#: which the coupled inversion removes to its model's own error), and the coupling grows
#: steeply as they close: on the example die 5 um apart eq. 3 read K_obj 91 % off and the
#: inversion left 4.6 %; a post width apart, 17 % and 0.9 % (the budget's tissue terms).
TIP_GAP_OVER_POST = 1.0
#: A post stands at least this much taller than its beam's deepest stop travel (um): the
#: tissue sinks round a post, and the face must not meet it before the stop takes the
#: overload (assumption); heights are drawn to :data:`POST_STEP_UM`.
POST_CLEARANCE_UM, POST_STEP_UM = 10.0, 5.0
#: The tallest post over its side (assumption: an SU-8 or plated post on a beam's end at
#: 5:1, well inside the 10:1 and more SU-8 reaches on its own).
POST_ASPECT_MAX = 5.0
#: The deepest cavity a timed etch makes to its depth tolerance (um) (assumption: the
#: +-5 % of :data:`~tactcad.products.silicon_die.vocabulary.soi_process.CAVITY_DEPTH_TOLERANCE_REL` holds for
#: etches of a few to about 100 um; the 300-700 um handle keeps most of its thickness).
CAVITY_DEPTH_MAX_UM = 100.0
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
BOSCH_STRENGTH_SOURCE = ("Uesugi, Hirai, Sugano, Tsuchiya and Tabata, IEEJ Trans. Sensors and "
                         "Micromachines 132(9), 2012, p. 320: bars "
                         "120 x 5 x 5 um, mean 1.9 GPa as etched, 3.6 GPa after a wet etch")
#: Columns per row, pitch along the die and the die's name when the caller states none
#: (the design file's, the die command's and design's defaults).
DEFAULT_COLUMNS, DEFAULT_PITCH_UM, DEFAULT_DIE_NAME = 5, 1000.0, "mems_die"
#: Fewest and most units along a die (inclusive): a reference and a measuring beam each.
COLUMNS_RANGE = (2, 50)
#: Beam widths searched (um): from the slot rule's smallest beam to the pitch's widest.
WIDTH_STEP_UM = 5.0
#: What a die's full-scale force (``[die] full_scale_force_N``, ``--full-scale-force``) is, in
#: the words of the die's help and schema (:meth:`DiePlan.rated_force_N`): the reference row's
#: rated force, not each beam's.
FULL_SCALE_FORCE_WORDS = ("the die's full-scale force, its reference row's rated force; each "
                          "row's rated force is what its stop and limits allow (the measuring "
                          "row's less), listed per row by tactcad strength")
#: A row's hard stop, its cavity's floor, engages at this multiple of its beam's rated tip
#: deflection (the metal combs' rule, :data:`tactcad.studies.comb_design.STOP_MULTIPLE`):
#: the beam reads its whole range, an overload rests on the floor.
STOP_MULTIPLE = 1.3
#: The K_obj resolution a die must reach when its file states none (relative, 1 sigma;
#: assumption: the read-out noise moves K_obj by under 1 % anywhere in the range).
DEFAULT_KOBJ_RESOLUTION_REL = 0.01
#: Cavity depths are drawn to this step (um), rounded up.
CAVITY_STEP_UM = 0.5


@dataclass(frozen=True)
class WeibullPair:
    """A Weibull pair for the fracture strength of etched silicon: P_f = 1 - exp(-(A_eff /
    A_0) (sigma / sigma_0)^m) for a surface of effective area A_eff at peak stress sigma.
    A lab's own pair (its fab's test structures, a die file's ``[strength]`` table), or
    :data:`DESIGN_STRENGTH` when the lab states none.

    Attributes:
        modulus: m, > 1. characteristic_MPa: sigma_0, the stress at which 63.2 % of the
            test structures break (MPa). reference_area_um2: A_0, the test structures'
            effective area the pair is for (um^2). source: where the pair comes from.
        failure_probability_max: the die's largest failure probability accepted.
        stated: True for a lab's own pair, False for :data:`DESIGN_STRENGTH`.
    """

    modulus: float
    characteristic_MPa: float
    reference_area_um2: float
    source: str
    failure_probability_max: float
    stated: bool = True

    @property
    def whose(self) -> str:
        """The words that name the pair in a verdict: the lab's, or the design default."""
        return "the lab's Weibull pair" if self.stated else \
            "the design-default Weibull pair (the file states no [strength] table)"


#: The Weibull modulus a die is designed with when its file states no pair: the low end of
#: the 5-20 reported for etched single-crystal silicon (a low m extrapolates most harshly
#: from a test bar to a die's larger area and to a small failure probability).
DESIGN_WEIBULL_MODULUS = 5.0
#: The design-default pair's characteristic strength (MPa): the mean of the Bosch-etched bars
#: as etched (:data:`BOSCH_MEAN_STRENGTH_MPA`) taken as a Weibull mean at
#: :data:`DESIGN_WEIBULL_MODULUS`, sigma_0 = mean / Gamma(1 + 1/m) = 2.07 GPa, rounded down.
DESIGN_CHARACTERISTIC_MPA = 2000.0
#: Its reference area (um^2): the bars' two DRIE sidewalls, 2 x 120 x 5 um, the smaller
#: surface the bars' flaws can lie on (a smaller A_0 judges a die's area more harshly).
DESIGN_REFERENCE_AREA_UM2 = 1200.0
#: The die's largest failure probability at its rating and on its stops when the file
#: states none (assumption: one die in a thousand; a die file's ``[strength]`` states its own).
DESIGN_FAILURE_PROBABILITY_MAX = 1e-3
#: The pair a die is designed and judged with when its file states none: a conservative
#: design strength for Bosch-etched silicon (the constants above), so that every die's
#: rating is decided; a lab's ``[strength]`` table replaces it.
DESIGN_STRENGTH = WeibullPair(
    DESIGN_WEIBULL_MODULUS, DESIGN_CHARACTERISTIC_MPA, DESIGN_REFERENCE_AREA_UM2,
    "m the low end of the 5-20 reported for etched silicon; sigma_0 the mean "
    f"{BOSCH_MEAN_STRENGTH_MPA:g} MPa of Bosch-etched bars as etched (Uesugi et al., IEEJ "
    "Trans. SM 132(9), 2012) over Gamma(1 + 1/m), rounded down; A_0 the bars' two DRIE "
    "sidewalls", DESIGN_FAILURE_PROBABILITY_MAX, stated=False)


@dataclass(frozen=True)
class DieAttach:
    """The film that bonds the die's handle to its carrier: what the mount's pocket depth
    and the die's crosstalk (the handle on Winkler springs) read of it.

    Attributes:
        material: what the film is (the BOM's and the drawing's words).
        modulus_MPa: its Young's modulus, cured (MPa). poisson: its Poisson's ratio.
        thickness_um: the cured bond line (um).
        source: where the modulus comes from (a data sheet, a measurement, or the word
            "assumption" and why).
        stated: True when the lab's design file states it (its ``[attach]`` table); the
            crosstalk's error estimate then spans :data:`tactcad.products.silicon_die.mechanics.die_crosstalk.
            STATED_MODULUS_SPAN` instead of the assumption's.
    """

    material: str
    modulus_MPa: float
    poisson: float
    thickness_um: float
    source: str
    stated: bool = False


#: The die attach when a die's file states none (assumption): a cured silver-filled epoxy
#: film, whose modulus is a few GPa and moves with its cure and filler, at a 25 um bond line.
DEFAULT_DIE_ATTACH = DieAttach(
    "silver-filled epoxy film", 4000.0, 0.35, 25.0,
    "assumption: a cured silver-filled epoxy, a few GPa (no data sheet stated; the die's file "
    "takes one as an [attach] table)")


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
    #: the resistors' boron implant dose (cm^-2; :func:`tactcad.products.silicon_die.studies.die_doping.chosen_implant_dose`)
    implant_dose_per_cm2: float = IMPLANT_DOSE_PER_CM2
    #: each row's cavity depth under its beams, the row's hard stop (um): reference, measuring
    cavity_depths_um: tuple[float, float] = (0.0, 0.0)
    #: the lab's Weibull pair for its etched silicon, or None (strength then undecided)
    weibull: WeibullPair | None = None
    #: the K_obj resolution the die must reach over its range (relative, 1 sigma)
    kobj_resolution_rel: float = DEFAULT_KOBJ_RESOLUTION_REL
    #: True when the die's file states ``kobj_resolution_rel``: verify then judges it; else
    #: the die is sized to :data:`DEFAULT_KOBJ_RESOLUTION_REL` and verify reports it, not judged
    kobj_resolution_stated: bool = False
    #: the film bonding the die to its carrier (the lab's ``[attach]``, else the assumption)
    attach: DieAttach = DEFAULT_DIE_ATTACH
    #: the largest grasp force the die must survive in its jaw (N), or None (not judged)
    max_grasp_force_N: float | None = None
    #: the largest K_obj error the die may read with (relative: its budget's worst root sum
    #: square), or None (not judged)
    kobj_accuracy_rel: float | None = None
    #: the fillet's radius where each beam's sidewalls meet the frame at its root (um)
    root_fillet_um: float = DRIE_MIN_RADIUS_UM

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

    def thickness_words(self) -> str:
        """The die's two thicknesses in words, each named: with its posts
        (:attr:`thickness_um`) and the bonded stack without them (um)."""
        return (f"{self.thickness_um:g} um with its {self.post_height_um:g} um posts, "
                f"{self.stack.total_um:g} um stack without them")

    def rated_force_N(self, beam: Beam) -> float:
        """The most ``beam`` carries in use (N): the rated force on a reference beam; on a
        measuring beam K_m x its rated travel (:meth:`rated_tip_um`), the most it carries
        while its reference reads up to the rated force."""
        if beam.role == "reference":
            return self.full_scale_force_N
        return self.k_m_N_per_mm * self.rated_tip_um(beam) * 1e-3

    def bending_length_um(self, beam: Beam) -> float:
        """``beam``'s length from the root to its force with the frame's give at the root
        (L + dL, um; :func:`root_extension_um`): K ~ 1 / (L + dL)^3."""
        return beam.length_um + root_extension_um(beam.width_um, beam.thickness_um)

    def stress_MPa_at_rating(self, beam: Beam) -> float:
        """The root's nominal surface bending stress were ``beam`` to carry the die's rated
        (full-scale) force (MPa): 6 F L / (w t^2), the stress the piezoresistor reads; the
        fillets' peak is :meth:`peak_stress_MPa_at_rating`."""
        return (6 * self.full_scale_force_N * beam.length_um * 1e-3
                / (beam.width_um * 1e-3 * (beam.thickness_um * 1e-3) ** 2))

    def root_stress_concentration(self, beam: Beam) -> float:
        """K_t of ``beam``'s root fillets (:func:`root_stress_concentration`): the root's
        peak stress over its nominal 6 F L / (w t^2)."""
        return root_stress_concentration(self.root_fillet_um, beam.width_um, beam.thickness_um)

    def peak_stress_MPa_at_rating(self, beam: Beam) -> float:
        """The root's peak stress, on its fillets' top edge, were ``beam`` to carry the
        die's rated force (MPa): K_t x 6 F L / (w t^2); what strength, the stops and the
        rating's limits judge."""
        return self.root_stress_concentration(beam) * self.stress_MPa_at_rating(beam)

    def root_stress_MPa_at_rated_force(self, beam: Beam) -> float:
        """The root's nominal surface bending stress at the most ``beam`` carries in use
        (:meth:`rated_force_N`; MPa)."""
        return self.stress_MPa_at_rating(beam) * self.rated_force_N(beam) / self.full_scale_force_N

    def root_peak_stress_MPa_at_rated_force(self, beam: Beam) -> float:
        """The root's peak stress (K_t x the nominal) at the most ``beam`` carries in use
        (:meth:`rated_force_N`; MPa)."""
        return (self.peak_stress_MPa_at_rating(beam) * self.rated_force_N(beam)
                / self.full_scale_force_N)

    @property
    def tip_gap_um(self) -> float:
        """The clear gap between a unit's two posts across the window (um)."""
        ref, meas = self.beams[0], self.beams[self.columns]
        return abs(meas.tip_y_um - ref.tip_y_um) - self.post_um

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
                "root_fillet_um": self.root_fillet_um,
                "root_stress_concentration_factor": {
                    b.role: self.root_stress_concentration(b)
                    for b in self.beams[:: self.columns]},
                "root_nominal_stress_MPa_at_rated_force": {
                    b.role: self.root_stress_MPa_at_rated_force(b)
                    for b in self.beams[:: self.columns]},
                "root_peak_stress_MPa_at_rated_force": {
                    b.role: self.root_peak_stress_MPa_at_rated_force(b)
                    for b in self.beams[:: self.columns]},
                "tip_gap_um": self.tip_gap_um,
                "cavity_depths_um": {"reference": self.cavity_depths_um[0],
                                     "measuring": self.cavity_depths_um[1]},
                "weibull": None if self.weibull is None else dict(self.weibull.__dict__),
                "attach": dict(self.attach.__dict__),
                **({} if self.max_grasp_force_N is None
                   else {"max_grasp_force_N": self.max_grasp_force_N}),
                **({} if self.kobj_accuracy_rel is None
                   else {"kobj_accuracy_rel": self.kobj_accuracy_rel}),
                "reasons": dict(self.reasons)}


def reference_resistor_v0_um(plan: DiePlan) -> float:
    """Where a beam's on-die reference resistor's legs start (beam-local v from the root
    towards the tip, um; negative: on the frame): its closed end
    :data:`REFERENCE_CLEAR_UM` from the window's edge, or further from it where a short
    reference would bring the jog of its leads within the metal's spacing of the bond pads
    (the jog runs under the pads: its top edge is v0 less the resistor's run and the jog,
    plus half a lead)."""
    near = -REFERENCE_CLEAR_UM - plan.reference_resistor_length_um
    under_pads = (-(PAD_SETBACK_UM + PAD_UM) - METAL_SPACE_UM + RESISTOR_RUN_UM
                  + LEAD_JOG_UM - LEAD_UM / 2)
    return min(near, under_pads)


def _positive(**values: float) -> None:
    """Refuse any of ``values`` (name -> value) that is not a finite real number above 0.

    Raises:
        ValueError: naming the argument, its value and the allowed range.
    """
    for name, value in values.items():
        if type(value) is float:  # the search's own numbers: no abstract-class test per call
            if 0 < value < math.inf:
                continue
        elif not isinstance(value, bool) and isinstance(value, numbers.Real) \
                and math.isfinite(value) and value > 0:
            continue
        raise ValueError(f"{name} = {value!r}: allowed a finite number above 0")


@functools.lru_cache(maxsize=4)
def _root_extension_table(table: tuple) -> tuple[list[float], list[float]]:
    """(log(w / t), c) of :data:`ROOT_EXTENSION_OVER_T`, worked out once per table."""
    return [math.log(ratio) for ratio, _ in table], [c for _, c in table]


def root_extension_um(width_um: float, thickness_um: float) -> float:
    """The frame's give at a beam's root as extra beam length behind it (um): dL = c t, c
    interpolated in log(w / t) over :data:`ROOT_EXTENSION_OVER_T` (held at its ends outside
    the fitted widths).

    Args:
        width_um, thickness_um: the beam's width w and the device layer's thickness t (um),
            each > 0.

    Returns:
        dL (um).

    Raises:
        ValueError: a width or thickness not finite and above 0.
    """
    _positive(width_um=width_um, thickness_um=thickness_um)
    logs, cs = _root_extension_table(ROOT_EXTENSION_OVER_T)
    at = min(max(math.log(width_um / thickness_um), logs[0]), logs[-1])
    i = min(max(bisect.bisect_right(logs, at), 1), len(logs) - 1)
    share = (at - logs[i - 1]) / (logs[i] - logs[i - 1])
    return (cs[i - 1] + share * (cs[i] - cs[i - 1])) * thickness_um


#: Roark's fits of the stepped flat bar's shoulder-fillet factor (Young and Budynas,
#: *Roark's Formulas for Stress and Strain*, 7th ed., 2002, Table 17.1, case 3, from the
#: charts Peterson's *Stress Concentration Factors* collects): K_t = C1 + C2 (2h/D) +
#: C3 (2h/D)^2 + C4 (2h/D)^3, h = (D - d) / 2 the shoulder's height, each C_i = a + b
#: sqrt(h/r) + c h/r; per loading, (a, b, c) of C1 ... C4 for 0.1 <= h/r <= 2 and for
#: 2 < h/r <= 20. ``bending`` is in the plane of the fillets (case 3b): no published chart
#: covers a bar bent out of that plane, as a die's beam is.
SHOULDER_FILLET_FITS = {
    "tension": (((1.007, 1.000, -0.031), (-0.114, -0.585, 0.314), (0.241, -0.992, -0.271),
                 (-0.134, 0.577, -0.012)),
                ((1.042, 0.982, -0.036), (-0.074, -0.156, -0.010), (-3.418, 1.220, -0.005),
                 (3.450, -2.046, 0.051))),
    "bending": (((1.007, 1.000, -0.031), (-0.270, -2.404, 0.749), (0.677, 1.133, -0.904),
                 (-0.414, 0.271, 0.186)),
                ((1.042, 0.982, -0.036), (-3.599, 1.619, -0.431), (6.084, -5.607, 1.158),
                 (-2.527, 3.006, -0.691))),
}
SHOULDER_FILLET_SOURCE = ("Roark's Formulas for Stress and Strain, 7th ed. (Young and Budynas "
                          "2002), Table 17.1 case 3b: a stepped flat bar bent in the plane of "
                          "its shoulder fillets, Peterson's charts fitted")
#: The shoulder's height over the fillet's radius the fits cover.
SHOULDER_H_OVER_R_RANGE = (0.1, 20.0)


def shoulder_fillet_kt(radius_over_d: float, big_d_over_d: float,
                       loading: str = "bending") -> float:
    """K_t of a stepped flat bar's shoulder fillets (:data:`SHOULDER_FILLET_FITS`): the peak
    stress on the fillet over the nominal stress of the narrow section (tension P / (d h);
    in-plane bending 6 M / (h d^2)).

    Args:
        radius_over_d: r / d, the fillet's radius over the narrow section's width, > 0.
        big_d_over_d: D / d, the wide section over the narrow, > 1.
        loading: ``"tension"`` or ``"bending"`` (in the fillets' plane).

    Returns:
        K_t (>= 1).

    Raises:
        ValueError: an unknown loading, or h / r = (D / d - 1) / (2 r / d) outside the fits'
            :data:`SHOULDER_H_OVER_R_RANGE`.
    """
    if loading not in SHOULDER_FILLET_FITS:
        raise ValueError(f"loading = {loading!r}: allowed {sorted(SHOULDER_FILLET_FITS)}")
    _positive(radius_over_d=radius_over_d)
    h_over_r = (big_d_over_d - 1.0) / (2.0 * radius_over_d)
    lo, hi = SHOULDER_H_OVER_R_RANGE
    if not lo * (1 - 1e-9) <= h_over_r <= hi * (1 + 1e-9):  # the ends as written
        raise ValueError(f"h / r = {h_over_r:.4g} (r / d = {radius_over_d:g}, D / d = "
                         f"{big_d_over_d:g}): allowed {lo:g} ... {hi:g}, the fits' range")
    fit = SHOULDER_FILLET_FITS[loading][0 if h_over_r <= 2.0 else 1]
    cs = [a + b * math.sqrt(h_over_r) + c * h_over_r for a, b, c in fit]
    x = 1.0 - 1.0 / big_d_over_d  # 2 h / D
    return cs[0] + cs[1] * x + cs[2] * x * x + cs[3] * x ** 3


#: The root fillet's radii a die takes (um): above 0, at most this (a larger fillet is a
#: taper, not a fillet; its K_t is fitted over :data:`ROOT_KT_RANGE`); and beside each beam
#: the fillets of neighbouring beams must leave the DRIE slot open (:func:`check_root_fillet`).
ROOT_FILLET_RANGE_UM = (0.0, 20.0)
#: The root fillets' K_t at the die's fem3d level
#: (:func:`tactcad.products.silicon_die.mechanics.die_fem3d.root_peak_fem3d` at level 3, the
#: arc's element edge r / 8, within about 1 % of level 4 on the example's beams): (w / t,
#: r / t, t um, L um, K_t). A design grid over the sections the die's search explores: w / t
#: 1.5, 4, 8; r / t 0.04, 0.12, 0.36; t 20 and 50 um (w / t 8 in the 20 um layer alone:
#: its mesh is the largest); L = max(3 w, 10 t), the shortest reference beam the search
#: takes (L >= 3 w); the rest of the die (stack, cavities) the example's, unscaled, so the
#: two layers' points differ by up to 6 % at one (w / t, r / t), the fit's main residual.
#: Last, the example's reference beam (w 128, t 40, L 388 um) at r = 4, 8, 16 um (the
#: points the chart's factor was fitted to). Wall times 20-340 s a point on a core shared
#: with other work, 670-1410 s at w / t 8 (270 k unknowns).
ROOT_KT_FEM3D = (
    (1.5, 0.04, 20.0, 200.0, 2.839),
    (1.5, 0.12, 20.0, 200.0, 1.821),
    (1.5, 0.36, 20.0, 200.0, 1.411),
    (4.0, 0.04, 20.0, 240.0, 3.019),
    (4.0, 0.12, 20.0, 240.0, 1.935),
    (4.0, 0.36, 20.0, 240.0, 1.546),
    (8.0, 0.04, 20.0, 480.0, 3.070),
    (8.0, 0.12, 20.0, 480.0, 1.967),
    (8.0, 0.36, 20.0, 480.0, 1.579),
    (1.5, 0.04, 50.0, 500.0, 2.676),
    (1.5, 0.12, 50.0, 500.0, 1.860),
    (1.5, 0.36, 50.0, 500.0, 1.420),
    (4.0, 0.04, 50.0, 600.0, 2.987),
    (4.0, 0.12, 50.0, 600.0, 1.973),
    (4.0, 0.36, 50.0, 600.0, 1.548),
    (3.2, 0.1, 40.0, 388.0, 2.04),
    (3.2, 0.2, 40.0, 388.0, 1.69),
    (3.2, 0.4, 40.0, 388.0, 1.49),
)
ROOT_KT_FEM3D_SOURCE = ("tactcad's fem3d level on filleted roots (root_peak_fem3d, level 3; "
                        "silicon's tensor, <110> on (100), the beam on its frame block)")
#: ln(K_t - 1) = c0 + c1 x + c2 x^2 + c3 y, x = ln(r / t), y = ln(w / t): least squares on
#: :data:`ROOT_KT_FEM3D` (each point weighted by (K_t - 1) / K_t, so the residual is K_t's
#: relative error).
ROOT_KT_COEFFICIENTS = (-1.2346, -0.3477, 0.0611, 0.1162)
#: The (r / t, w / t) the fit covers: the grid's span.
ROOT_KT_RANGE = {"r_over_t": (0.04, 0.4), "w_over_t": (1.5, 8.0)}
#: The closed form's largest error against :data:`ROOT_KT_FEM3D` (3.7 %), rounded
#: up; twice it outside :data:`ROOT_KT_RANGE`, where the fit is carried on (the last
#: slope in ln(r / t), held in w / t) and :class:`RootKtRangeWarning` is issued.
ROOT_KT_ERROR_REL = 0.04
ROOT_KT_SOURCE = (f"fitted to {ROOT_KT_FEM3D_SOURCE} over r / t "
                  f"{ROOT_KT_RANGE['r_over_t'][0]:g}-{ROOT_KT_RANGE['r_over_t'][1]:g}, w / t "
                  f"{ROOT_KT_RANGE['w_over_t'][0]:g}-{ROOT_KT_RANGE['w_over_t'][1]:g}, within "
                  f"{100 * ROOT_KT_ERROR_REL:g} % of it there")


class RootKtRangeWarning(UserWarning):
    """A die's root K_t taken outside the (r / t, w / t) its fit covers
    (:data:`ROOT_KT_RANGE`)."""


def root_kt_outside(radius_um: float, width_um: float, thickness_um: float) -> list[str]:
    """The coordinates of :data:`ROOT_KT_RANGE` that ``r``, ``w``, ``t`` (um) leave, as
    words ("r / t 0.02 (fitted 0.04 ... 0.4)"); empty inside."""
    out = []
    for name, label, value in (("r_over_t", "r / t", radius_um / thickness_um),
                               ("w_over_t", "w / t", width_um / thickness_um)):
        lo, hi = ROOT_KT_RANGE[name]
        if not lo * (1 - 1e-9) <= value <= hi * (1 + 1e-9):
            out.append(f"{label} {value:.3g} (fitted {lo:g} ... {hi:g})")
    return out


def root_kt_error_rel(radius_um: float, width_um: float, thickness_um: float) -> float:
    """The closed form's K_t error estimate (relative): :data:`ROOT_KT_ERROR_REL` inside
    :data:`ROOT_KT_RANGE`, twice it outside."""
    outside = root_kt_outside(radius_um, width_um, thickness_um)
    return ROOT_KT_ERROR_REL * (2.0 if outside else 1.0)


def stress_at_force_error_rel(kt_error_rel: float) -> float:
    """The relative error of a root's peak stress at a given force (the rating's failure
    probability, its margin in force): K_t's, the force being stated.

    The die's ``design`` keeps this room below the limit it judges, and ``verify``'s row
    carries it, from this one rule.

    Args:
        kt_error_rel: K_t's error (:func:`root_kt_error_rel`, relative, >= 0).

    Returns:
        The relative error of the stress (and of the force at which a stress is reached).
    """
    return float(kt_error_rel)


def stress_at_travel_error_rel(kt_error_rel: float) -> float:
    """The relative error of a root's peak stress at a given post travel (a stop's force is
    K x its travel): K_t's and the closed form's K (:data:`CLOSED_FORM_K_ERROR_REL`), added.

    The die's ``design`` keeps this room below the stops' limits (a stop engaging before
    its root breaks, the failure probability on the stops), and ``verify``'s rows carry it,
    from this one rule.

    Args:
        kt_error_rel: K_t's error (:func:`root_kt_error_rel`, relative, >= 0).

    Returns:
        The relative error of the stress (and of the force at which a stress is reached).
    """
    return float(kt_error_rel) + CLOSED_FORM_K_ERROR_REL


def k_moved_error_rel(plan, figure) -> float:
    """The largest relative change of ``figure(plan)`` with K_r and K_m each moved by the
    closed form's K error (:data:`CLOSED_FORM_K_ERROR_REL`), every sign combination (as the array's
    :func:`tactcad.studies.verification.worst_and_error`).

    Args:
        plan: the die. figure: a function of a plan giving a relative figure (> 0).

    Returns:
        The relative error; inf where the figure or a moved one is not finite or not above 0.
    """
    from dataclasses import replace

    base = figure(plan)
    e = CLOSED_FORM_K_ERROR_REL
    moved = [figure(replace(plan, k_r_N_per_mm=plan.k_r_N_per_mm * (1 + sr * e),
                            k_m_N_per_mm=plan.k_m_N_per_mm * (1 + sm * e)))
             for sr in (-1, 1) for sm in (-1, 1)]
    if not all(math.isfinite(v) and v > 0 for v in (base, *moved)):
        return math.inf
    return max(abs(v / base - 1.0) for v in moved)


def root_stress_concentration(radius_um: float, width_um: float, thickness_um: float) -> float:
    """K_t of a die beam's root fillets under its tip force, bent out of the wafer's plane:
    the peak stress on the fillets' top edge over the root's nominal 6 F L / (w t^2).

    No published chart gives a shoulder fillet's factor for a bar bent out of the plane of
    its fillets. The in-plane one (:func:`shoulder_fillet_kt`, r / d = r / w) follows the
    fillet's radius over the beam's width, while the die's fem3d level finds the
    concentration set by the radius over the layer's thickness, the width adding a few %
    (at r = 4 um in the 40 um layer: K_t 1.93, 2.04, 2.10 at w 60, 128, 240 um, where the
    chart's r / w moves it by -12 ... +15 %). So K_t is a surface fitted to fem3d
    (:data:`ROOT_KT_FEM3D`): ln(K_t - 1) = c0 + c1 x + c2 x^2 + c3 y, x = ln(r / t),
    y = ln(w / t) (:data:`ROOT_KT_COEFFICIENTS`), within :data:`ROOT_KT_ERROR_REL` of every
    grid point. Outside :data:`ROOT_KT_RANGE` x is carried on along the last slope and y
    held at its end (:func:`root_kt_error_rel` doubles there; the die's plan warns,
    :class:`RootKtRangeWarning`).

    Args:
        radius_um: the fillet's radius r (um), > 0.
        width_um, thickness_um: the beam's w and t (um), > 0.

    Returns:
        K_t (> 1).

    Raises:
        ValueError: a radius, width or thickness not a finite number above 0.
    """
    _positive(radius_um=radius_um, width_um=width_um, thickness_um=thickness_um)
    c0, c1, c2, c3 = ROOT_KT_COEFFICIENTS
    lo, hi = (math.log(v) for v in ROOT_KT_RANGE["r_over_t"])
    x = math.log(radius_um / thickness_um)
    xc = min(max(x, lo), hi)  # the quadratic inside, its tangent beyond
    y = min(max(math.log(width_um / thickness_um), math.log(ROOT_KT_RANGE["w_over_t"][0])),
            math.log(ROOT_KT_RANGE["w_over_t"][1]))
    return 1.0 + math.exp(c0 + c1 * x + c2 * xc * (2.0 * x - xc) + c3 * y)


def check_root_fillet(root_fillet_um, width_um: float | None = None,
                      pitch_um: float | None = None, slot_um: float | None = None) -> None:
    """Refuse a root fillet radius outside :data:`ROOT_FILLET_RANGE_UM`, or, given the beam,
    one whose fillets and the neighbouring beam's close the DRIE slot between them
    (pitch - w - 2 r below the slot) or reach past half the beam's width.

    Args:
        root_fillet_um: r (um). width_um, pitch_um, slot_um: the beam's width, the pitch
            and the narrowest DRIE trench (um), or None (the range alone).

    Raises:
        DesignError: ``die.root_fillet_um``, naming the value and the allowed range.
    """
    lo, hi = ROOT_FILLET_RANGE_UM
    if isinstance(root_fillet_um, bool) or not isinstance(root_fillet_um, numbers.Real) \
            or not math.isfinite(root_fillet_um) or not lo < root_fillet_um <= hi:
        raise DesignError("die.root_fillet_um", root_fillet_um,
                          f"above {lo:g} and at most {hi:g} um",
                          "the fillet where each beam's sidewalls meet the frame; its K_t is "
                          "fitted up to there, and a larger one is a taper")
    if width_um is None:
        return
    most = min(hi, width_um / 2, (pitch_um - width_um - slot_um) / 2)
    if root_fillet_um > most:
        raise DesignError("die.root_fillet_um", root_fillet_um,
                          f"above {lo:g} and at most {most:.4g} um for the {width_um:g} um "
                          f"beams at {pitch_um:g} um pitch",
                          f"each fillet fits beside its beam (at most half its width) and "
                          f"the fillets of neighbouring beams leave the {slot_um:.3g} um DRIE "
                          "slot between them")


def clamped_beam_stiffness_N_per_mm(youngs_modulus_MPa: float, width_um, thickness_um,
                                    length_um):
    """K = E w t^3 / (4 L^3) of a cantilever clamped at its root and tip-loaded out of plane
    (N/mm; MPa and um in; Euler-Bernoulli, the textbook's clamped root)."""
    return youngs_modulus_MPa * (width_um * 1e-3) * (thickness_um * 1e-3) ** 3 / (
        4 * (length_um * 1e-3) ** 3)


def _shear_compliance_mm_per_N(width_um: float, thickness_um: float, length_um: float) -> float:
    """A cantilever's shear deflection per newton at its force, L / (kappa G A) (mm/N):
    Timoshenko, kappa = 5/6 for a rectangle, G = C44 (the shear modulus in any plane holding
    the (100) wafer's normal, whatever the beam's direction in the wafer)."""
    return (length_um * 1e-3) / (SHEAR_COEFFICIENT * SILICON.c44 * width_um * thickness_um
                                 * 1e-6)


def beam_stiffness_N_per_mm(youngs_modulus_MPa: float, width_um: float, thickness_um: float,
                            length_um: float) -> float:
    """K (N/mm) of a die's beam as made, its root run into the frame: bending over L + dL,
    dL the frame's give at the root (:func:`root_extension_um`), and Timoshenko's shear over
    L, 1 / K = (L + dL)^3 / (3 E I) + L / (kappa G A) (Timoshenko and Gere, *Mechanics of
    Materials*; I = w t^3 / 12, G = C44); within :data:`CLOSED_FORM_K_ERROR_REL` of the fem3d
    level on the frame over the design's beams.

    Args:
        youngs_modulus_MPa: E along the beam (MPa). width_um, thickness_um: w and t (um).
        length_um: L, the root to the force (um), > 0.

    Raises:
        ValueError: a modulus, width, thickness or length not a finite number above 0.
    """
    _positive(youngs_modulus_MPa=youngs_modulus_MPa, length_um=length_um)
    bending = 1.0 / clamped_beam_stiffness_N_per_mm(
        youngs_modulus_MPa, width_um, thickness_um,
        length_um + root_extension_um(width_um, thickness_um))
    return 1.0 / (bending + _shear_compliance_mm_per_N(width_um, thickness_um, length_um))


def beam_stiffnesses_N_per_mm(youngs_modulus_MPa: float, width_um: float,
                              thickness_um: np.ndarray, length_um: np.ndarray) -> np.ndarray:
    """:func:`beam_stiffness_N_per_mm` of one beam width over arrays of thicknesses and
    lengths at once (a Monte Carlo's drawn dies): the same closed form, element by element,
    in numpy (equal to the scalar's to rounding).

    Args:
        youngs_modulus_MPa: E along the beam (MPa). width_um: w (um).
        thickness_um, length_um: t and L (um), arrays of one shape, each > 0.

    Returns:
        K (N/mm), the arrays' shape.

    Raises:
        ValueError: a modulus or width not a finite number above 0, or a thickness or length
            not finite and above 0 (the first such named).
    """
    _positive(youngs_modulus_MPa=youngs_modulus_MPa, width_um=width_um)
    t = np.asarray(thickness_um, dtype=float)
    length = np.asarray(length_um, dtype=float)
    for name, values in (("thickness_um", t), ("length_um", length)):
        bad = ~(np.isfinite(values) & (values > 0))
        if bad.any():
            raise ValueError(f"{name} = {values[bad].flat[0]!r}: allowed a finite number above 0")
    logs, cs = _root_extension_table(ROOT_EXTENSION_OVER_T)
    # np.interp holds the table's end values outside it, as root_extension_um does
    root = np.interp(np.log(width_um / t), logs, cs) * t
    bending = 1.0 / clamped_beam_stiffness_N_per_mm(youngs_modulus_MPa, width_um, t,
                                                    length + root)
    return 1.0 / (bending + _shear_compliance_mm_per_N(width_um, t, length))


def length_for_stiffness_um(youngs_modulus_MPa: float, width_um: float, thickness_um: float,
                            k_N_per_mm: float) -> float:
    """L (um) at which a beam of width w, thickness t (um) on its frame has K (N/mm): the
    inverse of :func:`beam_stiffness_N_per_mm` (Newton's method from the length without
    shear, which lies above the root: the compliance is convex in L). At or below 0 when no
    beam of that section is so stiff.

    Raises:
        ValueError: a modulus, width, thickness or K not a finite number above 0.
    """
    _positive(youngs_modulus_MPa=youngs_modulus_MPa, k_N_per_mm=k_N_per_mm)
    dl = root_extension_um(width_um, thickness_um)
    three_ei = clamped_beam_stiffness_N_per_mm(youngs_modulus_MPa, width_um, thickness_um,
                                               1e3)  # K at 1 mm: 3 E I (N mm^2)
    shear = _shear_compliance_mm_per_N(width_um, thickness_um, 1e3)  # per mm of length
    length = 1e3 * (three_ei / k_N_per_mm) ** (1 / 3) - dl
    if length <= 0:
        return length
    for _ in range(50):
        lm = (length + dl) * 1e-3
        excess = lm ** 3 / three_ei + shear * length * 1e-3 - 1.0 / k_N_per_mm
        step = 1e3 * excess / (3 * lm ** 2 / three_ei + shear)
        length -= step
        if abs(step) < 1e-9 * length or length <= 0:
            break
    return length


def die_plan(targets, room, *, columns: int = DEFAULT_COLUMNS,
             pitch_um: float = DEFAULT_PITCH_UM, name: str = DEFAULT_DIE_NAME,
             box_um: float = DEFAULT_BOX_UM, handle_um: float = DEFAULT_HANDLE_UM,
             angle_from_110_deg: float = 0.0,
             implant_dose_per_cm2: float = IMPLANT_DOSE_PER_CM2,
             dose_reason: str = "", weibull: WeibullPair | None = None,
             root_fillet_um: float = DRIE_MIN_RADIUS_UM) -> DiePlan:
    """The die for ``targets`` in the jaw's ``room``.

    Args:
        targets: :class:`tactcad.studies.inverse_design.Targets` (K_r / K_m, the K_obj
            range, the rated full-scale force).
        room: :class:`tactcad.partlib.grasper_jaw.JawRoom` (its pocket, mm).
        columns: units along the die (2 ... 50). pitch_um: their spacing (um).
        box_um, handle_um: the SOI stack's buried oxide and handle (um).
        angle_from_110_deg: the beams' direction in the (100) wafer, from [110].
        implant_dose_per_cm2: the resistors' boron dose (cm^-2), > 0; ``dose_reason`` why
            (:func:`tactcad.products.silicon_die.studies.die_doping.chosen_implant_dose` gives both).
        weibull: the lab's Weibull pair for its etched silicon, or None for
            :data:`DESIGN_STRENGTH` (the design default): the rating's strength limits are
            the die's failure probability at the rating and on its stops
            (:func:`weibull_force_scale`), besides a stop engaging before a root's peak
            reaches the etched bars' mean strength.
        root_fillet_um: the fillet's radius where each beam's sidewalls meet the frame
            (um; :func:`check_root_fillet`): its K_t (:func:`root_stress_concentration`)
            raises the root's stress the search, the rating and the stops judge.

    Returns:
        :class:`DiePlan`.

    Raises:
        DesignError: a value out of range (``die.root_fillet_um`` outside
            :data:`ROOT_FILLET_RANGE_UM`, or wider than the slot beside the chosen beam
            leaves), no stock device layer and beam width fit
            (naming what binds and the largest K_m the die holds), or the rating past the
            roots' strength, the cavities' depth or the posts' height, or within a limit's
            model error of it (:func:`rating_limit_errors`: verify could not pass it; naming
            a lighter rating, :func:`_check_rating`).
    """
    if not (isinstance(columns, int) and 2 <= columns <= 50):
        raise DesignError("--columns", columns, "an integer 2 ... 50")
    if not (math.isfinite(implant_dose_per_cm2) and 1e11 <= implant_dose_per_cm2 <= 1e17):
        raise DesignError("implant_dose_per_cm2", implant_dose_per_cm2, "1e11 ... 1e17 cm^-2")
    check_root_fillet(root_fillet_um)
    if not (isinstance(pitch_um, (int, float)) and math.isfinite(pitch_um)
            and LEAST_PITCH_UM <= pitch_um <= 5000.0):
        raise DesignError("--pitch-um", pitch_um, f"{LEAST_PITCH_UM:g} ... 5000 um",
                          "each beam's three bond pads and its reference resistor lie on the "
                          "frame within one pitch")
    width = round(room.across_mm * 1e3, 3)
    length = columns * pitch_um + 2 * END_UM
    along_um = (room.along_mm - BOND_SHELF_MM) * 1e3  # the carrier's shelf shares the pocket
    if length > along_um + 1e-6:
        raise DesignError("--columns", columns,
                          f"at most {max(0, int((along_um - 2 * END_UM) // pitch_um))} "
                          f"columns at {pitch_um:g} um pitch in the {room.label}'s "
                          f"{room.along_mm:g} mm pocket (the die and its carrier's "
                          f"{BOND_SHELF_MM:g} mm bond shelf)", limit=FOOTPRINT)
    direction = in_plane_direction(angle_from_110_deg)
    E = float(SILICON.young_modulus_MPa(direction))
    window = width - 2 * FRAME_UM
    k_r, k_m = targets.k_r, targets.k_m
    pair = _chosen_beam_pair(E, k_r, k_m, window, pitch_um, root_fillet_um)
    weibull = DESIGN_STRENGTH if weibull is None else weibull
    strength = RatingStrength(weibull, columns)
    if pair is None:
        raise _no_fit(targets, room, window, pitch_um, E, strength, root_fillet_um)
    per_N, neg_t, w, slot, post, l_r, l_m = pair[:7]
    t = -neg_t
    check_root_fillet(root_fillet_um, w, pitch_um, slot)
    kt = root_stress_concentration(root_fillet_um, w, t)
    kt_outside = root_kt_outside(root_fillet_um, w, t)
    kt_error = root_kt_error_rel(root_fillet_um, w, t)
    if kt_outside:
        warnings.warn(f"the root fillets' K_t {kt:.3g} ({root_fillet_um:g} um fillets on the "
                      f"{w:g} x {t:g} um beams) is taken outside its fit: "
                      f"{'; '.join(kt_outside)}; estimated error up to "
                      f"{100 * kt_error:.2g} % ({ROOT_KT_SOURCE})", RootKtRangeWarning,
                      stacklevel=2)
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
    align = CAVITY_ALIGNMENT_UM
    dl = root_extension_um(w, t)
    rating = _rating_of(pair, k_r, k_m, targets.full_scale_force_N,
                        targets.k_obj_range_N_per_mm, strength)
    rated, root_MPa, depths, deepest = (rating.rated_um, rating.root_MPa, rating.depths_um,
                                        rating.deepest_um)
    post_height = post_height_um(deepest)
    _check_rating(pair, k_r, k_m, rating, targets.k_obj_range_N_per_mm)
    reasons = {
        "root_fillet_um": f"{root_fillet_um:g} um fillets where each beam's sidewalls meet the "
                          "frame, drawn into the device etch's mask"
                          + (f" ({DRIE_MIN_RADIUS_SOURCE})" if root_fillet_um == DRIE_MIN_RADIUS_UM
                             else " (the design file's)")
                          + f": K_t = {kt:.3g} (r / t {root_fillet_um / t:.3g}, w / t "
                          f"{w / t:.3g}; +-{100 * kt_error:.2g} %"
                          + (f", outside its fit: {'; '.join(kt_outside)}" if kt_outside
                             else "")
                          + "), the root's peak stress over its nominal "
                          f"6 F L / (w t^2) ({ROOT_KT_SOURCE}); the search ranks sections by "
                          "the peak, and the strength, the stops and the rating judge it",
        "device_um": f"of the stock device layers ({', '.join(f'{x:g}' for x in DEVICE_LAYER_CHOICES_UM)} um) and beam widths whose two beams, posts "
                     f"and the gap between a unit's posts (at least a post's width: the "
                     f"tissue between them couples them) fit across the {window:g} um "
                     "window, "
                     f"the pair with the lowest root peak stress (K_t x the nominal, on its "
                     f"fillets) at the rating (the thicker layer on a tie); its +-{DEVICE_TOLERANCE_UM:g} um "
                     f"({DEVICE_TOLERANCE_SOURCE}) moves every K by +-{300 * tol:.2g} % "
                     "alike (R keeps it)",
        "beam_width_um": f"with the layer: the pair with the lowest root peak stress (a "
                         f"wider beam is stressed less), beside the {slot:.3g} um DRIE slot in the "
                         f"{pitch_um:g} um pitch, at most 1/{SLENDERNESS:g} of the reference "
                         "beam's length (slender: Euler-Bernoulli), wide enough for the "
                         "resistor's two legs and at least as wide as the layer is thick",
        "reference_length_um": f"K_r = {k_r:.4g} N/mm, 1 / K = (L + dL)^3 / (3 E I) + "
                               f"L / (5/6 G w t) (bending and Timoshenko's shear), E = "
                               f"{E / 1e3:.4g} GPa along the beam ({angle_from_110_deg:g} deg "
                               f"from <110> on (100), {SILICON.source.split(',')[0]}), G = "
                               f"C44 = {SILICON.c44 / 1e3:.4g} GPa, dL = "
                               f"{dl:.3g} um the frame's give at the root "
                               f"({ROOT_EXTENSION_SOURCE}; K within "
                               f"+-{100 * CLOSED_FORM_K_ERROR_REL:g} % of it)",
        "measuring_length_um": f"K_m = {k_m:.4g} N/mm the same way (K_r / K_m = "
                               f"{targets.kr_over_km:g})",
        "tip_gap_um": f"{window - l_r - l_m - post:.4g} um clear between a unit's two posts "
                      f"across the window: at least {TIP_GAP_OVER_POST:g} post width "
                      f"({post:g} um) and the {slot:.3g} um DRIE slot (the tissue between "
                      "the posts couples them, eq. 3's error; the coupled inversion removes "
                      "it to its model's own error)",
        "alignment": f"the front masks' +-{align:g} um alignment to the buried cavities "
                     f"moves both rows' roots one way: K_r / K_m by "
                     f"+-{300 * align * (1 / (l_r + dl) + 1 / (l_m + dl)):.2g} %",
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
        "strength": (f"judged by {weibull.whose}: the die's failure probability with every "
                     f"beam at its rated force and with every beam on its deepest stop within "
                     f"{weibull.failure_probability_max:g} (m {weibull.modulus:g}, sigma_0 "
                     f"{weibull.characteristic_MPa:g} MPa on {weibull.reference_area_um2:g} "
                     f"um^2; {weibull.source}); the more stressed root's peak {root_MPa:.4g} "
                     f"MPa (K_t {kt:.3g} x the nominal) at its beam's rated force; each "
                     f"limit met with its model's error to spare, as verify judges it (the "
                     f"rating's by K_t's {100 * stress_at_force_error_rel(kt_error):.2g} %, "
                     f"the stops' by K_t's and the closed form's K's "
                     f"{100 * stress_at_travel_error_rel(kt_error):.2g} %, in force)"),
    }
    return DiePlan(name, stack, 2, columns, pitch_um, length, width, FRAME_UM, END_UM, w,
                   l_r, l_m, post, post_height, resistor, E,
                   float(SILICON_P_TYPE.longitudinal(direction)) * 1e-11,
                   float(beam_stiffness_N_per_mm(E, w, t, l_r)),
                   float(beam_stiffness_N_per_mm(E, w, t, l_m)), (k_r, k_m),
                   targets.full_scale_force_N, tuple(beams), reasons,
                   tuple(float(v) for v in targets.k_obj_range_N_per_mm),
                   float(implant_dose_per_cm2), depths, weibull,
                   root_fillet_um=float(root_fillet_um))


def post_height_um(deepest_stop_travel_um: float) -> float:
    """The posts' height (um): :data:`POST_HEIGHT_UM` at least, and
    :data:`POST_CLEARANCE_UM` more than the deepest a post goes to its stop, rounded up to
    :data:`POST_STEP_UM`."""
    need = deepest_stop_travel_um + POST_CLEARANCE_UM
    return max(POST_HEIGHT_UM, POST_STEP_UM * math.ceil(need / POST_STEP_UM - 1e-9))


@dataclass(frozen=True)
class _Rating:
    """What a pair of beams does at a rating (um, MPa, N): each post's rated travel, the
    more stressed root at its beam's rated force, the cavities' depths and the deepest a post
    goes to its stop."""

    force_N: float
    rated_um: tuple[float, float]
    root_MPa: float
    depths_um: tuple[float, float]
    deepest_um: float
    #: the larger over the rows of the deepest stop's engagement over the travel at which the
    #: root reaches the mean strength of etched silicon
    stop_over_fracture: float = 0.0
    #: the lab's Weibull pair and the columns it judges, or None (the mean strength alone)
    strength: "RatingStrength | None" = None
    #: with a pair: the factor on the rating at which the die's failure probability reaches
    #: the accepted one, every beam at its rated force, and every beam on its deepest stop
    weibull_scales: tuple[float, float] = (math.inf, math.inf)
    #: the root fillets' K_t error (relative, :func:`root_kt_error_rel`): the model errors
    #: of the limits (:func:`_rating_limit_errors`) follow from it
    kt_error_rel: float = 0.0


@dataclass(frozen=True)
class RatingStrength:
    """What a rating's strength is judged by besides the etched bars' mean: the lab's
    Weibull pair, over ``columns`` units of two beams."""

    weibull: WeibullPair
    columns: int


def effective_area_um2(length_um: float, width_um: float, thickness_um: float,
                       modulus: float) -> float:
    """A tip-loaded cantilever's effective area under its root's peak stress (um^2):
    L / (m + 1) (w + t / (m + 1)) (its tensile face and the tensile half of each sidewall;
    :mod:`tactcad.products.silicon_die.mechanics.die_strength`)."""
    return length_um / (modulus + 1.0) * (width_um + thickness_um / (modulus + 1.0))


def fillet_effective_area_um2(root_fillet_um: float, thickness_um: float,
                              modulus: float) -> float:
    """The surface of a beam's two root fillets judged at the root's peak stress (um^2):
    each fillet's arc (pi r / 2) over the tensile half of the thickness under its linear
    bending gradient (t / (2 (m + 1))), and a square of side r of the face beside it, taken
    wholly at the peak (conservative: the concentration falls off within about r of the
    fillet). 0 for no fillet."""
    r = max(float(root_fillet_um), 0.0)
    return 2.0 * (math.pi * r / 2.0 * thickness_um / (2.0 * (modulus + 1.0)) + r * r)


def beam_weibull_risk(length_um: float, width_um: float, thickness_um: float,
                      nominal_MPa: float, root_kt: float, root_fillet_um: float,
                      pair: WeibullPair) -> float:
    """A tip-loaded beam's Weibull risk of rupture (P_f = 1 - exp(-risk)): its bending
    surface at the root's nominal stress (:func:`effective_area_um2`) and its root fillets
    at the peak, K_t x the nominal (:func:`fillet_effective_area_um2`).

    Args:
        length_um, width_um, thickness_um: the beam (um). nominal_MPa: 6 F L / (w t^2) at
            its force (MPa). root_kt: K_t of its root fillets. root_fillet_um: their radius.
        pair: the Weibull pair judged by.
    """
    m = pair.modulus
    return (weibull_risk(effective_area_um2(length_um, width_um, thickness_um, m),
                         nominal_MPa, pair)
            + weibull_risk(fillet_effective_area_um2(root_fillet_um, thickness_um, m),
                           root_kt * nominal_MPa, pair))


def weibull_risk(area_um2: float, peak_MPa: float, pair: WeibullPair) -> float:
    """A surface's Weibull risk of rupture, (A_eff / A_0) (sigma / sigma_0)^m, so that
    P_f = 1 - exp(-risk) (0 at no tension)."""
    if peak_MPa <= 0:
        return 0.0
    return area_um2 / pair.reference_area_um2 * (peak_MPa / pair.characteristic_MPa) ** pair.modulus


def force_scale_of_risk(risk: float, probability: float, modulus: float) -> float:
    """The factor on every force at which a total ``risk`` (at the forces as they are)
    reaches ``probability``: stresses go as the forces, the risk as s^m, so
    s = (-ln(1 - P) / risk)^(1/m) (inf at no risk)."""
    if risk <= 0:
        return math.inf
    return (-math.log1p(-probability) / risk) ** (1.0 / modulus)


def weibull_force_scale(pair: WeibullPair, count: int, roots) -> float:
    """The factor on every beam's force at which ``count`` units of the beams ``roots``
    ((length um, width um, thickness um, nominal root stress MPa, K_t, fillet radius um) per
    beam of a unit) fail with the pair's accepted probability (:func:`force_scale_of_risk`
    of their summed :func:`beam_weibull_risk`)."""
    risk = count * sum(beam_weibull_risk(l, w, t, stress, kt, r, pair)
                       for l, w, t, stress, kt, r in roots)
    return force_scale_of_risk(risk, pair.failure_probability_max, pair.modulus)


def _rating_of(pair: BeamPair, k_r: float, k_m: float, force_N: float, kobj_range,
               strength: RatingStrength | None = None) -> _Rating:
    """:class:`_Rating` of a fitting ``pair`` at ``force_N``, every root's stress its peak on
    the fillets (K_t x 6 F L / (w t^2), :func:`root_stress_concentration`):
    each root at its own beam's rated force (the reference's F, the measuring beam's K_m x
    its rated travel: it never carries more while its reference reads up to F); with a
    ``strength``, the Weibull scales of the rating and of every beam on its deepest stop."""
    t, w, post = pair.thickness_um, pair.width_um, pair.post_um
    l_r, l_m = pair.reference_length_um, pair.measuring_length_um
    kt = root_stress_concentration(pair.root_fillet_um, w, t)

    def root_MPa(f_N: float, length: float) -> float:  # the peak, on the fillets
        return kt * 6 * f_N * length * 1e-3 / (w * 1e-3 * (t * 1e-3) ** 2)

    rated = rated_tip_deflections_um(k_r, k_m, force_N, kobj_range)
    roots = (root_MPa(force_N, l_r), root_MPa(k_m * rated[1] * 1e-3, l_m))
    depths = (cavity_depth_um(rated[0], l_r, post), cavity_depth_um(rated[1], l_m, post))
    engage = [d * (1 + CAVITY_DEPTH_TOLERANCE_REL) / end_over_post(length, post)
              for d, length in zip(depths, (l_r, l_m))]
    fracture = [fracture_travel_um(k, length, w, t, kt) for k, length in ((k_r, l_r), (k_m, l_m))]
    scales = (math.inf, math.inf)
    if strength is not None:
        on_stop = (root_MPa(k_r * engage[0] * 1e-3, l_r), root_MPa(k_m * engage[1] * 1e-3, l_m))
        r = pair.root_fillet_um  # the Weibull risk takes the nominal and the fillets' K_t
        scales = tuple(weibull_force_scale(strength.weibull, strength.columns,
                                           [(l_r, w, t, peaks[0] / kt, kt, r),
                                            (l_m, w, t, peaks[1] / kt, kt, r)])
                       for peaks in (roots, on_stop))
    return _Rating(force_N, rated, max(roots), depths, max(engage),
                   max(e / f for e, f in zip(engage, fracture)), strength, scales,
                   root_kt_error_rel(pair.root_fillet_um, w, t))


def _rating_limits(rating: _Rating, post_um: float) -> list[tuple[float, str]]:
    """The ratings at which each limit binds, with what binds (N, words); each scales with
    the force (the roots' stress, the stops' depths and the posts' travel go as F): the more
    stressed root's peak (K_t x the nominal) at the mean strength of etched silicon, the
    stops engaging before it, the deeper cavity at
    :data:`CAVITY_DEPTH_MAX_UM` after its tolerance, the posts at :data:`POST_ASPECT_MAX` x
    their side."""
    force_N, depths_um, deepest_um = rating.force_N, rating.depths_um, rating.deepest_um
    deepest_cavity = max(depths_um) * (1 + CAVITY_DEPTH_TOLERANCE_REL)
    tallest = POST_ASPECT_MAX * post_um
    if rating.strength is None:
        strength = [(force_N * BOSCH_MEAN_STRENGTH_MPA / rating.root_MPa,
                     f"the more stressed root's peak (K_t x 6 F L / (w t^2), on its fillets) "
                     f"at the mean tensile strength of Bosch-etched "
                     f"silicon ({BOSCH_MEAN_STRENGTH_MPA:g} MPa, {BOSCH_STRENGTH_SOURCE}; "
                     f"{rating.root_MPa:.4g} MPa at {force_N:g} N, at its beam's rated force)")]
    else:
        strength = [(force_N * scale, _weibull_words(rating, where))
                    for scale, where in zip(rating.weibull_scales, _WEIBULL_LOADINGS)]
    return [
        *strength,
        (force_N / rating.stop_over_fracture if rating.stop_over_fracture > 0 else math.inf,
         "a row's stop, in its deepest cavity, engaging only as its root's peak reaches the mean "
         f"strength ({100 * rating.stop_over_fracture:.3g} % of that travel at {force_N:g} N)"),
        (force_N * CAVITY_DEPTH_MAX_UM / deepest_cavity,
         f"the measuring row's cavity at the {CAVITY_DEPTH_MAX_UM:g} um a timed etch holds to "
         f"its +-{100 * CAVITY_DEPTH_TOLERANCE_REL:g} %, its deep end ({max(depths_um):g} um "
         f"+{100 * CAVITY_DEPTH_TOLERANCE_REL:g} %: {deepest_cavity:.4g} um at {force_N:g} N)"),
        (force_N * (tallest - POST_CLEARANCE_UM) / deepest_um if tallest >= POST_HEIGHT_UM
         else math.inf,  # the least post taller than the aspect allows: no rating helps
         f"a post standing {POST_CLEARANCE_UM:g} um proud at its stop taller than "
         f"{POST_ASPECT_MAX:g} x its {post_um:g} um side ({tallest:g} um; its stop at "
         f"{deepest_um:.4g} um of travel at {force_N:g} N)")]


def _rating_limit_codes(rating: _Rating) -> list[str]:
    """The code of each limit of :func:`_rating_limits`, in its order
    (:mod:`tactcad.vocabulary.binding_limits`): the strength ones (one with the mean
    strength, two with a Weibull pair), then the stop engaging before fracture, the
    cavity's depth and the post's height, all three the stops'."""
    from tactcad.vocabulary.binding_limits import STOP, STRENGTH

    return [STRENGTH] * (1 if rating.strength is None else 2) + [STOP, STOP, STOP]


def _rating_limit_errors(rating: _Rating) -> list[float]:
    """The model error of each limit of :func:`_rating_limits`, in its order (relative, in
    force), the ones ``verify`` judges the same limits by: the failure probability at the
    rating :func:`stress_at_force_error_rel` (K_t's); the mean strength without a pair, the
    failure probability on the stops and a stop engaging before its root breaks
    :func:`stress_at_travel_error_rel` (K_t's and K's); the cavity's depth and the post's
    height 0 (drawn sizes and the etch's stated tolerance, no model between)."""
    travel = stress_at_travel_error_rel(rating.kt_error_rel)
    strength = ([travel] if rating.strength is None
                else [stress_at_force_error_rel(rating.kt_error_rel), travel])
    return [*strength, travel, 0.0, 0.0]


def _plan_rating(plan: DiePlan) -> _Rating:
    """:class:`_Rating` of ``plan``'s beams at its rated force."""
    ref, meas = plan.beams[0], plan.beams[plan.columns]
    pair = BeamPair(0.0, -ref.thickness_um, ref.width_um, 0.0, plan.post_um, ref.length_um,
                    meas.length_um, plan.root_fillet_um)
    strength = None if plan.weibull is None else RatingStrength(plan.weibull, plan.columns)
    return _rating_of(pair, plan.k_r_N_per_mm, plan.k_m_N_per_mm, plan.full_scale_force_N,
                      plan.kobj_range_N_per_mm, strength)


def rating_limits(plan: DiePlan) -> list[tuple[float, str]]:
    """The ratings at which each limit of ``plan``'s rating binds, with what binds (N,
    words; :func:`_rating_limits` on the plan's beams): the largest rating the die allows is
    the least of them."""
    return _rating_limits(_plan_rating(plan), plan.post_um)


def rating_limit_errors(plan: DiePlan) -> list[float]:
    """The model error of each limit of :func:`rating_limits`, in its order.

    Args:
        plan: the die (:class:`DiePlan`).

    Returns:
        Each limit's relative error in force (:func:`_rating_limit_errors`): ``design``
        accepts a rating only below limit / (1 + error), so that ``verify`` passes it.
    """
    return _rating_limit_errors(_plan_rating(plan))


def largest_verified_rating(plan: DiePlan) -> tuple[float, str, float]:
    """The largest rating ``plan``'s die, as drawn, verifies: the least over its limits
    (:func:`rating_limits`) of limit / (1 + error) (:func:`rating_limit_errors`), the
    rating past which ``verify`` leaves a limit undecided and ``design`` refuses.

    Args:
        plan: the die (:class:`DiePlan`).

    Returns:
        (the rating (N), what binds it (words), the nominal least limit (N): the same
        limits without their model error's room).
    """
    limits = rating_limits(plan)
    room = [(limit / (1.0 + error), words)
            for (limit, words), error in zip(limits, rating_limit_errors(plan))]
    force, binds = min(room, key=lambda limit: limit[0])
    return force, binds, min(limit for limit, _ in limits)


def _within_limits(rating: _Rating, post_um: float) -> bool:
    """Whether ``rating`` is within every limit with its model's error to spare: F (1 + e)
    below each limit (its margin, limit / F - 1, larger than e), so that ``verify`` passes
    each row rather than leaving it undecided."""
    return all(rating.force_N * (1.0 + error) < limit
               for (limit, _), error in zip(_rating_limits(rating, post_um),
                                            _rating_limit_errors(rating)))


def _lighter_rating(pair: BeamPair, k_r: float, k_m: float, rating: _Rating,
                    kobj_range) -> float | None:
    """The rating to paste for ``pair`` when ``rating`` passes a limit (or comes within its
    model's error of one): the largest rating within every limit by its error
    (:func:`_within_limits`), found by bisection (the limits grow with
    the force, the cavities' depths and the posts' heights in steps), rounded down to three
    significant digits, so that it designs and 1 % more does not; None when none from
    :data:`LIGHTEST_PASTE_N` up designs (a limit that does not fall with the rating: the
    shallowest cavity or the least post drawn)."""
    post = pair.post_um

    def holds(force: float) -> bool:
        return _within_limits(_rating_of(pair, k_r, k_m, force, kobj_range, rating.strength),
                              post)

    low = min(limit for limit, _ in _rating_limits(rating, post))  # the limits scale with F
    for _ in range(SCALE_STEPS):  # a force within every limit, stepping down from there
        if not low >= LIGHTEST_PASTE_N:
            return None
        if holds(low):
            break
        low *= 0.95
    else:
        return None
    high = low * 1.05
    while holds(high):  # and one past them: the asked rating itself is
        low, high = high, high * 1.05
        if high > rating.force_N:
            high = rating.force_N
            break
    for _ in range(FRONTIER_BISECTIONS):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if holds(middle) else (low, middle)
    paste = round_down(low, 3)
    return paste if holds(paste) else None


#: Bisections of the rating's frontier: 40 halve its bracket (5 % wide) to 1e-13.
FRONTIER_BISECTIONS = 40


#: Whether a refused rating's refusal pastes the lighter rating that designs (a bisection
#: costing tens of plans); off inside :func:`lighter_rating_unsaid`.
_PASTE_LIGHTER = contextvars.ContextVar("paste the lighter rating", default=True)


@contextlib.contextmanager
def lighter_rating_unsaid() -> Iterator[None]:
    """Inside, a rating past a limit is refused without the lighter rating to paste: the
    same option, reasons and limit code, none of the bisection. For a design atlas, which
    records the verdict and not the rating to paste.

    Yields:
        None; on leaving, refusals paste the lighter rating again.
    """
    token = _PASTE_LIGHTER.set(False)
    try:
        yield
    finally:
        _PASTE_LIGHTER.reset(token)


#: Where the die's failure probability is judged, in :func:`_rating_limits`' order.
_WEIBULL_LOADINGS = ("every beam at its rated force", "every beam on its deepest stop")


def _weibull_words(rating: _Rating, where: str) -> str:
    """The failure-probability limit in words, ``where`` the loading judged."""
    accepted = rating.strength.weibull.failure_probability_max
    return (f"the die's failure probability, {where}, at the {accepted:g} "
            f"{rating.strength.weibull.whose} accepts")


def _passed_words(passed: list[tuple[float, str]], rating: _Rating) -> list[str]:
    """The words of the limits a rating passes, each once: the failure probability passed
    at both loadings is one limit said with both.

    Args:
        passed: (limit N, words) of each limit passed, in :func:`_rating_limits`' order.
        rating: the rating judged.

    Returns:
        The words, in order.
    """
    words = [w for _, w in passed]
    if rating.strength is None:
        return words
    both = [_weibull_words(rating, where) for where in _WEIBULL_LOADINGS]
    if all(w in words for w in both):
        at = words.index(both[0])
        words = [w for w in words if w not in both]
        words.insert(at, _weibull_words(rating, " and ".join(_WEIBULL_LOADINGS)))
    return words


def _check_rating(pair: BeamPair, k_r: float, k_m: float, rating: _Rating, kobj_range) -> None:
    """Refuse a rating past any of :func:`_rating_limits`, or within its model's error of
    one (:func:`_rating_limit_errors`: verify would leave it undecided): the refusal names
    every such limit and pastes the rating below all of them by their errors
    (:func:`_lighter_rating`), or says that no lighter rating helps.

    Raises:
        DesignError: ``--full-scale-force``, the rating past a limit or within its error.
    """
    limits = _rating_limits(rating, pair.post_um)
    errors = _rating_limit_errors(rating)
    force_N = rating.force_N
    passed = [(limit, why) for limit, why in limits if force_N >= limit]
    # within a limit, but not by its model's error: verify could not pass it
    close = [(limit, why, error) for (limit, why), error in zip(limits, errors)
             if force_N < limit <= force_N * (1.0 + error)]
    if not passed and not close:
        return
    code = next(c for (limit, _), error, c in zip(limits, errors, _rating_limit_codes(rating))
                if force_N * (1.0 + error) >= limit)
    why = "; ".join([*(["past " + "; past ".join(_passed_words(passed, rating))]
                       if passed else []),
                     *(f"within its model's {100 * error:.2g} % error of {words}: a margin "
                       f"of {100 * (limit / force_N - 1.0):+.2g} %, which verify could not "
                       "pass" for limit, words, error in close)])
    if not _PASTE_LIGHTER.get():
        raise DesignError("--full-scale-force", force_N, "a lighter rating", why, limit=code)
    below = _lighter_rating(pair, k_r, k_m, rating, kobj_range)
    if below is None:
        raise DesignError("--full-scale-force", force_N, "no rating of these beams",
                          f"{why}; no lighter rating down to {LIGHTEST_PASTE_N:g} N is within "
                          "every limit: the shallowest cavity and the least post drawn do not "
                          "shrink with it" + ("" if rating.strength is None else
                                              " (a stronger etch than "
                                              f"{rating.strength.weibull.whose} states, or "
                                              "a stiffer K_obj range)"), limit=code)
    raise DesignError("--full-scale-force", force_N, f"at most {below:g} N", why, limit=code,
                      alternatives=[{"option": f"--full-scale-force {below:g}",
                                     "words": "a lighter rating, below every limit by its model's "
                                              "error" + (
                                         " (strength at the mean of etched bars; its failure "
                                         "probability needs a Weibull pair)"
                                         if rating.strength is None else "")}])


def fracture_travel_um(k_N_per_mm: float, length_um: float, width_um: float,
                       thickness_um: float, root_kt: float) -> float:
    """The post's travel (um) at which a cantilever's root peak reaches the mean strength of
    etched silicon (:data:`BOSCH_MEAN_STRENGTH_MPA`): sigma = K_t 6 K L delta / (w t^2).

    Args:
        k_N_per_mm: the beam's K (N/mm). length_um, width_um, thickness_um: L, w, t (um).
        root_kt: K_t of the root's fillets (:func:`root_stress_concentration`), >= 1.

    Returns:
        The travel (um)."""
    return 1e3 * BOSCH_MEAN_STRENGTH_MPA * width_um * 1e-3 * (thickness_um * 1e-3) ** 2 / (
        6 * root_kt * k_N_per_mm * length_um * 1e-3)


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
    tolerance allows; rounded up to :data:`CAVITY_STEP_UM`, one step at the least (a
    travel within the rounding's slack made it 0 um, and every limit scaled by it
    divided by zero)."""
    need = (STOP_MULTIPLE * rated_um * end_over_post(length_um, post_um)
            / (1.0 - CAVITY_DEPTH_TOLERANCE_REL))
    return CAVITY_STEP_UM * max(1, math.ceil(need / CAVITY_STEP_UM - 1e-9))


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


class BeamPair(NamedTuple):
    """A reference and a measuring beam of one width in one device layer (um), ordered as
    the search prefers them: the lowest root peak stress per newton of the measuring beam
    (K_t 6 L / (w t^2), K_t of its fillets: :func:`root_stress_concentration`) first,
    then the thicker layer (``neg_t``: -t), then the narrower beam."""

    root_MPa_per_N: float
    neg_t: float
    width_um: float
    slot_um: float
    post_um: float
    reference_length_um: float
    measuring_length_um: float
    #: the root fillets' radius (um)
    root_fillet_um: float = DRIE_MIN_RADIUS_UM

    @property
    def thickness_um(self) -> float:
        return -self.neg_t


def tip_gap_um(slot_um: float, post_um: float) -> float:
    """The least clear gap between a unit's two posts (um): the DRIE slot, and at least
    :data:`TIP_GAP_OVER_POST` post widths."""
    return max(slot_um, TIP_GAP_OVER_POST * post_um)


def _beam_pair(E: float, k_r: float, k_m: float, window: float, t: float, w: float,
               slot: float, fillet_um: float = DRIE_MIN_RADIUS_UM) -> BeamPair | None:
    """The :class:`BeamPair` of width ``w`` in a ``t`` layer, or None when the two beams,
    the post and the gap between a unit's posts (:func:`tip_gap_um`) do not fit across the
    window or the reference beam is not slender (L_r >= :data:`SLENDERNESS` w); um."""
    post = min(w, POST_MAX_UM)
    l_r = length_for_stiffness_um(E, w, t, k_r)
    l_m = length_for_stiffness_um(E, w, t, k_m)
    if l_r + l_m + post + tip_gap_um(slot, post) <= window and l_r >= SLENDERNESS * w:
        kt = root_stress_concentration(fillet_um, w, t)
        return BeamPair(kt * 6 * l_m / (w * t * t), -t, w, slot, post, l_r, l_m, fillet_um)
    return None


def _layer_widths(pitch_um: float, fillet_um: float = DRIE_MIN_RADIUS_UM
                  ) -> tuple[tuple[float, float, tuple[float, ...]], ...]:
    """(device layer, DRIE slot, beam widths) per stock layer (um): widths that leave room
    for the resistor and are at least the layer's thickness (a beam thicker than wide bends
    more easily sideways, under the tissue's shear, than out of the wafer's plane), and
    leave the slot open between the root fillets (``fillet_um``) of neighbouring beams.

    Args:
        pitch_um: the beams' pitch along the die (um).
        fillet_um: the root fillets' radius (um).

    Returns:
        One (t, slot, widths) per stock layer (um), read only: kept per process
        (:func:`_layer_widths_of`), as a refusal's search asks it hundreds of times.
    """
    return _layer_widths_of(pitch_um, fillet_um, _resistor_width_um())


@functools.lru_cache(maxsize=64)
def _layer_widths_of(pitch_um: float, fillet_um: float, resistor_um: float
                     ) -> tuple[tuple[float, float, tuple[float, ...]], ...]:
    """:func:`_layer_widths` for the narrowest beam that holds the resistor,
    ``resistor_um`` (:func:`_resistor_width_um`), a value of its key so that a changed
    resistor is never answered from an earlier one.

    Args:
        pitch_um: the beams' pitch along the die (um).
        fillet_um: the root fillets' radius (um).
        resistor_um: the narrowest beam holding the resistor with its margins (um).

    Returns:
        One (t, slot, widths) per stock layer (um).
    """
    out = []
    for t in DEVICE_LAYER_CHOICES_UM:
        slot = drie_min_width_um(t)
        out.append((t, slot, tuple(w for w in _widths(pitch_um - slot, max(resistor_um, t))
                                    if w <= pitch_um - slot - 2 * fillet_um)))
    return tuple(out)


def _fitting_beams(E: float, k_r: float, k_m: float, window: float, pitch_um: float,
                   fillet_um: float = DRIE_MIN_RADIUS_UM) -> list:
    """Every stock device layer and beam width whose pair fits (:func:`_beam_pair`)."""
    pairs = (_beam_pair(E, k_r, k_m, window, t, w, slot, fillet_um)
             for t, slot, widths in _layer_widths(pitch_um, fillet_um) for w in widths)
    return [p for p in pairs if p is not None]


@functools.lru_cache(maxsize=64)
def _section_table(E: float, pitch_um: float, fillet_um: float) -> dict:
    """Every stock layer's beam sections of :func:`_layer_widths` as numpy arrays (um; the
    per-section terms of :func:`length_for_stiffness_um` that do not depend on K): t, w, the
    slot, the post, dL, 3 E I (N mm^2), the shear compliance per mm of length (mm/N / mm)
    and the fillets' K_t. Computed once per modulus, pitch and fillet by the scalar
    functions themselves."""
    rows = [(t, w, slot) for t, slot, widths in _layer_widths(pitch_um, fillet_um)
            for w in widths]
    t = np.array([r[0] for r in rows], float)
    w = np.array([r[1] for r in rows], float)
    return {"t": t, "w": w, "slot": np.array([r[2] for r in rows], float),
            "post": np.minimum(w, POST_MAX_UM),
            "dl": np.array([root_extension_um(wi, ti) for ti, wi in zip(t, w)]),
            "three_ei": np.array([clamped_beam_stiffness_N_per_mm(E, wi, ti, 1e3)
                                  for ti, wi in zip(t, w)]),
            "shear": np.array([_shear_compliance_mm_per_N(wi, ti, 1e3)
                               for ti, wi in zip(t, w)]),
            "kt": np.array([root_stress_concentration(fillet_um, wi, ti)
                            for ti, wi in zip(t, w)])}


def _lengths_for_stiffness_um(table: dict, k_N_per_mm: float) -> np.ndarray:
    """:func:`length_for_stiffness_um` for every section of a :func:`_section_table` at
    once (um; the same Newton steps, vectorised; at or below 0 where no beam is so stiff)."""
    dl, three_ei, shear = table["dl"], table["three_ei"], table["shear"]
    length = 1e3 * (three_ei / k_N_per_mm) ** (1 / 3) - dl
    active = length > 0
    for _ in range(50):
        if not active.any():
            break
        lm = (length + dl) * 1e-3
        excess = lm ** 3 / three_ei + shear * length * 1e-3 - 1.0 / k_N_per_mm
        step = 1e3 * excess / (3 * lm ** 2 / three_ei + shear)
        length = np.where(active, length - step, length)
        active &= ~((np.abs(step) < 1e-9 * length) | (length <= 0))
    return length


#: The relative band within which the vectorised screen of :func:`_chosen_beam_pair` hands a
#: section to the scalar :func:`_beam_pair` (its fit or its rank too near to call in floats
#: that may differ from the scalar's in the last digits).
_SCREEN_BAND_REL = 1e-7


def _chosen_beam_pair(E: float, k_r: float, k_m: float, window: float, pitch_um: float,
                      fillet_um: float = DRIE_MIN_RADIUS_UM) -> BeamPair | None:
    """``min(_fitting_beams(...))``, the pair :func:`die_plan` chooses, found by screening
    every section at once (numpy) and judging by the scalar :func:`_beam_pair` only the
    sections whose fit or rank lies within :data:`_SCREEN_BAND_REL` of deciding: the same
    answer in a fraction of the time.

    Args:
        E: the beams' modulus (MPa). k_r, k_m: K_r and K_m (N/mm). window: the die's window
            across (um). pitch_um: the columns' pitch (um). fillet_um: the root fillets (um).

    Returns:
        The chosen :class:`BeamPair`, or None when no section fits.

    Raises:
        ValueError: a modulus or K not a finite number above 0.

    Source: the beam model of :func:`beam_stiffness_N_per_mm` (Timoshenko and Gere),
    inverted as :func:`length_for_stiffness_um` inverts it.
    """
    _positive(youngs_modulus_MPa=E, k_N_per_mm=k_r)
    _positive(k_N_per_mm=k_m)
    table = _section_table(float(E), float(pitch_um), float(fillet_um))
    if table["t"].size == 0:
        return None
    t, w, post = table["t"], table["w"], table["post"]
    l_r = _lengths_for_stiffness_um(table, k_r)
    l_m = _lengths_for_stiffness_um(table, k_m)
    gap = np.maximum(table["slot"], TIP_GAP_OVER_POST * post)
    across = window - (l_r + l_m + post + gap)  # >= 0: fits across
    slender = l_r - SLENDERNESS * w  # >= 0: slender
    band = _SCREEN_BAND_REL * (window + np.abs(l_r) + np.abs(l_m) + post + gap)
    sure = (across >= band) & (slender >= band)
    unsure = ~sure & (across > -band) & (slender > -band)
    key = table["kt"] * 6 * l_m / (w * t * t)
    scored = sure | unsure
    if not scored.any():
        return None
    least = key[sure].min() if sure.any() else np.inf
    near = scored & (key <= least * (1 + _SCREEN_BAND_REL) + 1e-300)
    pairs = [_beam_pair(E, k_r, k_m, window, float(t[i]), float(w[i]),
                        float(table["slot"][i]), fillet_um) for i in np.flatnonzero(near)]
    pairs = [p for p in pairs if p is not None]
    if pairs:
        return min(pairs)
    # every near section failed its scalar fit: the scalar search decides (rare)
    fitting = _fitting_beams(E, k_r, k_m, window, pitch_um, fillet_um)
    return min(fitting) if fitting else None


def _any_fitting_beam(E: float, k_r: float, k_m: float, window: float, pitch_um: float,
                      fillet_um: float = DRIE_MIN_RADIUS_UM) -> bool:
    """Whether :func:`_fitting_beams` finds any: each layer's narrowest width decides it, as
    the beams' lengths (L ~ w^(1/3)) and the post grow with the width while the slenderness
    L_r / w falls."""
    return any(_beam_pair(E, k_r, k_m, window, t, min(widths), slot, fillet_um) is not None
               for t, slot, widths in _layer_widths(pitch_um, fillet_um) if widths)


#: Steps of the K_obj range's scale a refusal searches for its alternative (x 1.05 each).
SCALE_STEPS = 200
#: The lightest rating a refusal pastes (N): below it no die reads K_obj anyway.
LIGHTEST_PASTE_N = 1e-6


def _force_that_designs(E: float, k_r: float, k_m: float, window: float, pitch_um: float,
                        force_N: float, kobj_range,
                        strength: RatingStrength | None = None,
                        fillet_um: float = DRIE_MIN_RADIUS_UM) -> float | None:
    """None when no pair of beams with these stiffnesses fits the window; else the rating
    that designs with them: ``force_N`` within its limits (:func:`_rating_limits`), else the
    lighter one a refusal would paste (:func:`_lighter_rating`), else ``force_N`` (no rating
    helps: the plan's refusal of the rating says so)."""
    if not _any_fitting_beam(E, k_r, k_m, window, pitch_um, fillet_um):
        return None
    pair = _chosen_beam_pair(E, k_r, k_m, window, pitch_um, fillet_um)
    rating = _rating_of(pair, k_r, k_m, force_N, kobj_range, strength)
    if _within_limits(rating, pair.post_um):
        return force_N
    lighter = _lighter_rating(pair, k_r, k_m, rating, kobj_range)
    # no rating of these beams within a lab's weak pair: the beams fit, and the plan's own
    # rating refusal says why nothing lighter helps
    return force_N if lighter is None else lighter


def _with_force(option: str, force: float, asked: float) -> str:
    """``option``, and the lighter rating to paste with it where the asked one does not
    design."""
    return option if force == asked else f"{option} --full-scale-force {force:g}"


def _no_fit(targets, room, window: float, pitch_um: float, E: float,
            strength: RatingStrength | None = None,
            fillet_um: float = DRIE_MIN_RADIUS_UM) -> DesignError:
    """The refusal: no stock layer and width fits. Which way the targets miss (stiffer
    tissue fits: the beams were too long for the window; softer fits: too stubby to be
    slender beams) and the nearest scale of the K_obj range that designs (K_m and K_r go
    as the range's scale), as a pasteable alternative."""
    from tactcad.vocabulary.binding_limits import LAYER

    lo, hi = targets.k_obj_range_N_per_mm
    asked = targets.full_scale_force_N
    for step in range(1, SCALE_STEPS + 1):
        for scale, way in ((1.05 ** step, "stiffer"), (1.05 ** -step, "softer")):
            a, b = float(f"{lo * scale:.4g}"), float(f"{hi * scale:.4g}")  # as pasted
            x = targets.kr_over_km
            k_m = math.sqrt(a * b / x)
            force = _force_that_designs(E, x * k_m, k_m, window, pitch_um, asked, (a, b),
                                        strength, fillet_um)
            if force is not None:
                why = ("the beams are too long for the window: the softest pair that fits "
                       f"has K_m = {targets.k_m * scale:.4g} N/mm" if way == "stiffer" else
                       "the reference beam would be too short to bend as a slender beam: the "
                       f"stiffest that does has K_r = {targets.k_r * scale:.4g} N/mm")
                return DesignError(
                    "--kobj-range", [lo, hi],
                    f"K_r {targets.k_r:.4g} and K_m {targets.k_m:.4g} N/mm in slender beams "
                    f"(>= {SLENDERNESS:g} widths) that fit across the {window:g} um window of "
                    f"the {room.label}", why,
                    alternatives=[{"option": _with_force(f"--kobj-range {a:g} {b:g}", force,
                                                         asked),
                                   "words": f"the same span of tissues, {way}, that fits"}],
                    limit=LAYER)
    fit = _fitting_ratio(targets, window, pitch_um, E, strength, fillet_um)
    if fit is not None:
        ratio, force = fit
        return DesignError(
            "--kr-over-km", targets.kr_over_km,
            f"at most about {ratio:g} for the K_obj range {lo:g} ... {hi:g} N/mm in the "
            f"{room.label}",
            f"the two beams' lengths part as the ratio's cube root: at {targets.kr_over_km:g} "
            f"no pair of slender beams (>= {SLENDERNESS:g} widths) fits across the {window:g} "
            f"um window at any scale of the K_obj range within x{1.05 ** SCALE_STEPS:.3g}",
            alternatives=[{"option": _with_force(f"--kr-over-km {ratio:g}", force, asked),
                           "words": "a smaller stiffness ratio whose beams fit"}],
            limit=LAYER)
    return DesignError("--kobj-range", [lo, hi], "targets whose beams fit the die",
                       f"no K_obj range within x{1.05 ** SCALE_STEPS:.3g} of this one fits the "
                       f"{window:g} um window at {pitch_um:g} um pitch: a wider jaw", limit=LAYER)


def _fitting_ratio(targets, window: float, pitch_um: float, E: float,
                   strength: RatingStrength | None = None,
                   fillet_um: float = DRIE_MIN_RADIUS_UM) -> tuple | None:
    """(the largest K_r / K_m below the asked one, three digits, x 1/1.05 steps, whose beams
    fit for the same K_obj range, the rating that designs with it), or None
    (K_m = sqrt(K_lo K_hi / X), K_r = X K_m)."""
    lo, hi = targets.k_obj_range_N_per_mm
    for step in range(1, SCALE_STEPS + 1):
        ratio = float(f"{targets.kr_over_km / 1.05 ** step:.3g}")
        if ratio <= 1.0:
            return None
        k_m = math.sqrt(lo * hi / ratio)
        force = _force_that_designs(E, ratio * k_m, k_m, window, pitch_um,
                                    targets.full_scale_force_N, (lo, hi), strength, fillet_um)
        if force is not None:
            return ratio, force
    return None
