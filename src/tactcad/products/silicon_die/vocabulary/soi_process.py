"""The SOI bulk-micromachining process a silicon die is made in: its wafer stack, its masks
(one GDSII layer each) and the layout rules the masks are checked against.

A die's cantilevers are cut in the device layer of a cavity silicon-on-insulator wafer:
alignment marks are etched into the handle, then a cavity under each row of beams, each
row's to its own depth (its floor is the row's hard stop); both wafers are oxidised (the
buried oxide; the device wafer's share spans the cavities as the front etch's stop) and the
device wafer fusion-bonded over the handle and thinned. Windows over the marks let every
front mask align to them. p-type piezoresistors are implanted at each beam's root,
contacted through the oxide and wired in aluminium to bond pads on the die's heel; a hard
mask of oxide, opened over the pads, carries the beams' outline. Deep reactive-ion etching
(the Bosch process) from the front cuts the beams down to the oxide spanning the cavities,
the wafer is diced with the beams still held by it, and HF vapour frees them die by die.

Each rule carries its value and where it comes from. The DRIE aspect ratio and the wafer
ranges are the field's published figures; the lithography rules (widths, spaces,
enclosures, alignment) are stated assumptions typical of a contact-lithography MEMS line,
each marked so: a foundry's own rule deck replaces them (:data:`SOI_RULES`).

Units: um (the masks' own unit; GDSII database unit 1 nm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.errors import DesignError

#: A rule that is a stated assumption, not a published figure, starts its source so.
ASSUMED = "assumption (a foundry's rule deck replaces it): "


@dataclass(frozen=True)
class MaskLayer:
    """One photomask: its GDSII layer and datatype, and what it patterns."""

    name: str
    gds_layer: int
    datatype: int
    text: str


#: The masks in process order, and the die outline (a layout layer, not a mask).
MASKS = (
    MaskLayer("align", 8, 0, "alignment marks etched into the handle first: the cavities and "
                             "every front mask are aligned to them"),
    MaskLayer("cavity_measuring", 7, 0, "the handle's cavity under the measuring row, etched "
                                        "before bonding to its own depth (its edge the "
                                        "beams' root, its floor their hard stop)"),
    MaskLayer("cavity_reference", 5, 0, "the handle's cavity under the reference row, etched "
                                        "before bonding (its edge is the beams' root, its "
                                        "floor their hard stop)"),
    MaskLayer("mark_window", 9, 0, "windows etched through the device layer over the "
                                   "handle's marks after bonding, so the front masks see them"),
    MaskLayer("piezo", 1, 0, "boron implant: the p-type piezoresistors at the beams' roots"),
    MaskLayer("contact", 2, 0, "contact openings through the oxide onto the resistors' ends"),
    MaskLayer("metal", 3, 0, "aluminium: the leads and each beam's bond pads on the frame "
                             "behind it"),
    MaskLayer("device_etch", 4, 0, "front DRIE through the device layer: the slot around "
                                   "each beam (patterned into the hard mask)"),
    MaskLayer("pad_open", 11, 0, "openings in the hard mask's oxide over the bond pads"),
    MaskLayer("tip", 6, 0, "the post on each beam's free end that meets the tissue first "
                           "(the last lithography: nothing is patterned over the posts)"),
    MaskLayer("die", 10, 0, "the die's outline (the dicing lane's inner edge); not a mask"),
)
MASK_BY_NAME = {m.name: m for m in MASKS}


@dataclass(frozen=True)
class Rule:
    """One layout rule (um).

    Attributes:
        name: the rule's name in reports (``metal.width``).
        layer: the mask it applies to (:data:`MASKS`); ``inside``: the mask that must
            enclose it, for an enclosure rule.
        kind: ``width`` (smallest feature), ``space`` (smallest gap between features) or
            ``enclosure`` (``inside`` covers ``layer`` by at least the value).
        value_um: the limit.
        source: the figure's source, or :data:`ASSUMED` and why.
    """

    name: str
    layer: str
    kind: str
    value_um: float
    source: str
    inside: str = ""


@dataclass(frozen=True)
class SoiStack:
    """An SOI wafer's layers (um): the device layer the beams are cut in, the buried
    oxide, the handle; the device layer's thickness tolerance (the beams' stiffness goes
    as its cube)."""

    device_um: float
    box_um: float
    handle_um: float
    device_tolerance_um: float

    def __post_init__(self):
        for name, (lo, hi) in STACK_RANGES_UM.items():
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and lo <= value <= hi):
                raise DesignError(f"soi.{name}", value, f"{lo:g} ... {hi:g} um "
                                  f"({STACK_RANGE_SOURCE})")
        if not 0 <= self.device_tolerance_um < self.device_um / 2:
            raise DesignError("soi.device_tolerance_um", self.device_tolerance_um,
                              f"0 ... {self.device_um / 2:g} um (half the device layer)")

    @property
    def total_um(self) -> float:
        return self.device_um + self.box_um + self.handle_um


#: The ranges SOI wafers for MEMS are sold in (um).
STACK_RANGES_UM = {"device_um": (2.0, 100.0), "box_um": (0.5, 2.0), "handle_um": (300.0, 700.0)}
STACK_RANGE_SOURCE = ("bonded SOI wafers for MEMS: device layer 2-100 um, buried oxide "
                      "0.5-2 um, handle 300-700 um")
#: Device-layer thicknesses a design searches (um): common stock thicknesses.
DEVICE_LAYER_CHOICES_UM = (5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 40.0, 50.0, 60.0, 80.0, 100.0)
#: The device layer's thickness tolerance (um), +-: typical of bonded-and-polished SOI.
DEVICE_TOLERANCE_UM = 0.5
DEVICE_TOLERANCE_SOURCE = ("bonded-and-polished SOI: device layer to +-0.5 to 1 um (the "
                           "tighter end taken)")
#: Buried oxide and handle of the default stack (um).
DEFAULT_BOX_UM, DEFAULT_HANDLE_UM = 1.0, 400.0

#: DRIE's largest trench depth / width (Bosch process): 20 the conservative end of the
#: 20:1 to 30:1 such etches reach.
DRIE_ASPECT_RATIO = 20.0
DRIE_SOURCE = ("deep reactive-ion etching, Bosch process (Laermer and Schilp, US 5,501,893, "
               "1996): aspect ratios about 20:1 to 30:1; 20:1 taken")
#: The front masks' alignment to the buried cavities (um), +- (assumption: alignment
#: marks etched with the cavities, read through the bonded stack in infrared or opened
#: in the device layer; a front-to-back aligner's +-1 to 2 um, the looser end).
CAVITY_ALIGNMENT_UM = 2.0
#: The posts' height across one die, +- relative to their height (assumption: a spun
#: SU-8 film or a plated post varies by a few per cent of its thickness across a wafer and
#: less across a die a few millimetres wide; 2 % taken). It is what the process holds: a
#: drawing cannot ask it finer, so a die whose K_obj accuracy needs the posts flatter than
#: this is zeroed on a rigid flat (:mod:`tactcad.products.silicon_die.in_use.die_budget`).
POST_HEIGHT_TOLERANCE_REL = 0.02
#: A DRIE'd feature's width across a wafer (um), +-: the etch's bias spread (assumption: a
#: Bosch etch holds its critical dimension to about +-0.5 um, its sidewall scallops
#: 0.1-0.3 um).
DRIE_WIDTH_TOLERANCE_UM = 0.5
#: Where a dicing saw's cut lands (um), +-: the die's outline (assumption: a dicing saw's
#: cut placement, about +-10 um).
DICING_TOLERANCE_UM = 10.0
#: A timed cavity etch's depth, relative, +-.
CAVITY_DEPTH_TOLERANCE_REL = 0.05
CAVITY_DEPTH_SOURCE = (ASSUMED + "a timed DRIE of a few to tens of um holds its depth "
                       "across a wafer to about +-5 %")


def drie_min_width_um(depth_um: float) -> float:
    """The narrowest trench DRIE opens through ``depth_um`` of silicon (um): depth / the
    aspect ratio, and never below the lithography's smallest feature."""
    return max(depth_um / DRIE_ASPECT_RATIO, LITHO_MIN_UM)


#: The lithography's smallest feature (um).
LITHO_MIN_UM = 2.0
#: The smallest corner radius the device etch draws reliably (um): twice the lithography's
#: smallest feature. Contact lithography rounds every drawn corner to about its resolution
#: (2 um) whatever the mask says, so a drawn arc prints as drawn only above that; at twice
#: it the Bosch etch's +-0.5 um bias (:data:`DRIE_WIDTH_TOLERANCE_UM`) moves the radius by
#: an eighth and its 0.1-0.3 um scallops stay a small part of it. The default of a beam
#: root's fillet (``[die] root_fillet_um``).
DRIE_MIN_RADIUS_UM = 2 * LITHO_MIN_UM
DRIE_MIN_RADIUS_SOURCE = (ASSUMED + "the smallest radius the device etch draws as drawn: twice "
                          "the lithography's 2 um smallest feature (contact lithography "
                          "rounds any corner to about its resolution; the Bosch etch's "
                          "+-0.5 um bias then moves the radius by an eighth)")
#: Aluminium's smallest width and space (um): wet-etched, its undercut takes about 1 um.
METAL_SPACE_UM = 1.5 * LITHO_MIN_UM


#: Around each alignment mark, the device layer cleared by this much (um).
MARK_WINDOW_MARGIN_UM = 20.0
#: A bond pad's edge kept under the hard mask's oxide (um): its opening inset by this.
PAD_OPEN_INSET_UM = 5.0
#: The alignment mark: a cross of two arms (um), in each end of the die's frame.
MARK_ARM_UM, MARK_WIDTH_UM = 100.0, 10.0


def soi_rules(stack: SoiStack) -> tuple[Rule, ...]:
    """The rules the masks of a die on ``stack`` are checked against (:class:`Rule`)."""
    litho = ASSUMED + "contact lithography resolves about 2 um"
    return (
        Rule("device_etch.width", "device_etch", "width", drie_min_width_um(stack.device_um),
             f"{DRIE_SOURCE}: {stack.device_um:g} um of device layer"),
        Rule("device_etch.space", "device_etch", "space", 2 * LITHO_MIN_UM,
             ASSUMED + "a beam or frame between two slots at least twice the lithography's "
                       "smallest feature"),
        Rule("cavity_reference.width", "cavity_reference", "width", 2 * LITHO_MIN_UM,
             ASSUMED + "a cavity at least twice the smallest feature across (at most "
                       "100 um deep and as wide as the beams' row: DRIE's aspect ratio does "
                       "not bind)"),
        Rule("cavity_measuring.width", "cavity_measuring", "width", 2 * LITHO_MIN_UM,
             ASSUMED + "a cavity at least twice the smallest feature across (at most "
                       "100 um deep and as wide as the beams' row: DRIE's aspect ratio does "
                       "not bind)"),
        Rule("piezo.width", "piezo", "width", LITHO_MIN_UM, litho),
        Rule("piezo.space", "piezo", "space", 2 * LITHO_MIN_UM,
             ASSUMED + "two implants' lateral diffusion kept apart"),
        Rule("contact.width", "contact", "width", 2 * LITHO_MIN_UM,
             ASSUMED + "a contact at least twice the smallest feature, for its resistance"),
        Rule("metal.width", "metal", "width", METAL_SPACE_UM,
             ASSUMED + "aluminium wet-etched: its undercut takes about 1 um"),
        Rule("metal.space", "metal", "space", METAL_SPACE_UM,
             ASSUMED + "aluminium wet-etched: its undercut takes about 1 um"),
        Rule("metal.contact_enclosure", "contact", "enclosure", LITHO_MIN_UM,
             ASSUMED + "the metal covers each contact by one alignment step", inside="metal"),
        Rule("piezo.contact_enclosure", "contact", "enclosure", LITHO_MIN_UM,
             ASSUMED + "the implant covers each contact by one alignment step",
             inside="piezo"),
        Rule("tip.width", "tip", "width", 10.0,
             ASSUMED + "a post at least 10 um across stands on its beam"),
        Rule("align.width", "align", "width", 2 * LITHO_MIN_UM,
             ASSUMED + "a mark's arm at least twice the smallest feature, read by the "
                       "aligner's optics"),
        Rule("mark_window.align_enclosure", "align", "enclosure", MARK_WINDOW_MARGIN_UM,
             ASSUMED + "the device layer cleared around each mark by the aligner's capture "
                       "range", inside="mark_window"),
        Rule("pad_open.metal_enclosure", "pad_open", "enclosure", LITHO_MIN_UM,
             ASSUMED + "each pad's edge stays under oxide by one alignment step",
             inside="metal"),
    )

