"""How a silicon die sits in a grasper's jaw: a pocket cut into the jaw's grasping face,
a carrier at its floor, the die bonded on the carrier with its device layer at the face,
the posts standing proud of it (mm).

The jaw is the class's default jaw (or a lab's own jaw table) read as the metal
constructions read it (:class:`tactcad.partlib.grasper_jaw.GrasperJawSection`). Unlike a
comb, whose tips reach through a window in a face wall, a die's posts stand only tens of
microns above its device layer, so no face wall can stand over the die: the pocket opens
at the face, and the die's frame lies flush with it (the device layer's top at the face,
:data:`DEVICE_RECESS_MM` below it), the posts proud by their height less that recess. The
carrier under the die (:data:`CARRIER_MM`, alumina) reaches past the die's proximal end by
:data:`BOND_SHELF_MM`, where the flex cable to the shaft is soldered; the die is bonded to it
by its die-attach film (the plan's :attr:`~tactcad.products.silicon_die.design.mems_die.DiePlan.attach`: the lab's
``[attach]`` table, else a 25 um silver-filled epoxy, an assumption). The pocket runs from the distal wall
towards the pivot and keeps :data:`~tactcad.partlib.grasper_jaw.MIN_WALL_MM` of steel
beside it, under it and before the pin.

Units: mm (the die plan's um converted).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping

from tactcad.products.silicon_die.design.mems_die import BOND_SHELF_MM, DEFAULT_DIE_ATTACH, DiePlan
from tactcad.errors import DesignError
from tactcad.vocabulary.binding_limits import FOOTPRINT, HEIGHT

#: The carrier's thickness (mm): a thin-film alumina substrate (assumption: a stock 0.25 mm
#: substrate, the one thin ceramics vendors list first).
CARRIER_MM = 0.25
#: The die-attach layer (mm) when the die's file states none.
DIE_ATTACH_MM = DEFAULT_DIE_ATTACH.thickness_um * 1e-3
#: The device layer's top below the jaw's face (mm): flush, the posts alone proud.
DEVICE_RECESS_MM = 0.0


@dataclass(frozen=True)
class DieMount:
    """The jaw, its face pocket, the carrier and the die's place (mm; x along the jaw from
    its heel, y across from its axis, z from its back to the grasping face).

    Attributes:
        jaw_length_mm, jaw_width_mm, jaw_thickness_mm: the jaw's bar.
        pin_x_mm, pin_diameter_mm: the pivot pin's axis along the jaw and its diameter
            (``pin_x_mm`` < 0: behind the heel, no hole in the bar).
        pocket_x0_mm, pocket_length_mm, pocket_width_mm, pocket_depth_mm: the pocket,
            open at the face, ``pocket_depth_mm`` down from it.
        carrier_x0_mm, carrier_length_mm, carrier_width_mm, carrier_mm: the carrier on
            the pocket's floor.
        attach_mm: the die-attach film between the carrier and the die.
        die_x0_mm, die_z0_mm: the die's proximal end and its handle's underside.
        die_length_mm, die_width_mm, die_stack_mm: the die without its posts.
        post_proud_mm: the posts' tops above the jaw's face.
        reasons: derived value -> why.
        opening_angle_deg: how far the jaw opens (degrees).
    """

    jaw_length_mm: float
    jaw_width_mm: float
    jaw_thickness_mm: float
    pin_x_mm: float
    pin_diameter_mm: float
    pocket_x0_mm: float
    pocket_length_mm: float
    pocket_width_mm: float
    pocket_depth_mm: float
    carrier_x0_mm: float
    carrier_length_mm: float
    carrier_width_mm: float
    carrier_mm: float
    die_x0_mm: float
    die_z0_mm: float
    die_length_mm: float
    die_width_mm: float
    die_stack_mm: float
    post_proud_mm: float
    attach_mm: float = DIE_ATTACH_MM
    reasons: dict = field(default_factory=dict, compare=False, hash=False)
    #: how far the jaw opens (degrees): the jaw table's ``opening_angle_deg`` (the grasp's)
    opening_angle_deg: float = 0.0

    @property
    def face_z_mm(self) -> float:
        return self.jaw_thickness_mm

    def as_json(self) -> dict[str, Any]:
        out = {k: getattr(self, k) for k in self.__dataclass_fields__ if k != "reasons"}
        return {**out, "reasons": dict(self.reasons)}


def die_mount(plan: DiePlan, jaw_table: Mapping[str, Any]) -> DieMount:
    """The die's mount in the jaw ``jaw_table`` states (a ``[grasper_jaw]`` table; the
    class's defaults fill it, as for a comb).

    The pocket's depth is the lab's where the table states ``pocket_depth_mm`` (the carrier
    then fills what the die and its attach leave: thicker than the stock
    :data:`CARRIER_MM`), else the die, its attach and the stock carrier.

    Args:
        plan: the die (:class:`~tactcad.products.silicon_die.design.mems_die.DiePlan`).
        jaw_table: the ``[grasper_jaw]`` table (mm, degrees).

    Returns:
        The :class:`DieMount` (mm).

    Raises:
        DesignError: the jaw cannot hold the pocket: too narrow for the die and its side
            walls, too thin for the die, carrier and the steel under them, a stated pocket
            depth outside what the die and the steel under it allow, or too short between
            the pin's steel and the distal wall (the field named with what it needs).
    """
    from tactcad.partlib.grasper_jaw import (MIN_WALL_MM, GrasperJawSection,
                                             jaw_width_mm, pocket_start_limit_mm,
                                             validated_table, with_class_defaults)

    j = with_class_defaults(validated_table("grasper_jaw", GrasperJawSection, dict(jaw_table)))
    c = j.pocket_clearance_mm
    die_l, die_w = plan.die_length_um * 1e-3, plan.die_width_um * 1e-3
    stack = (plan.stack.handle_um + plan.stack.box_um + plan.stack.device_um) * 1e-3
    width = jaw_width_mm(j)
    pocket_w = die_w + 2 * c
    if width < pocket_w + 2 * MIN_WALL_MM - 1e-9:
        raise DesignError("grasper_jaw.width_mm", round(width, 4),
                          f">= {pocket_w + 2 * MIN_WALL_MM:.4g} mm",
                          f"the die is {die_w:g} mm across; its pocket ({c:g} mm clearance each "
                          f"side) keeps {MIN_WALL_MM:g} mm side walls", limit=FOOTPRINT)
    attach = plan.attach.thickness_um * 1e-3
    least = stack + attach + CARRIER_MM + DEVICE_RECESS_MM
    if j.thickness_mm < least + MIN_WALL_MM - 1e-9:
        raise DesignError("grasper_jaw.thickness_mm", j.thickness_mm,
                          f">= {least + MIN_WALL_MM:.4g} mm",
                          f"the die ({stack:.4g} mm), its attach and carrier ({CARRIER_MM:g} mm) "
                          f"in a pocket {least:.4g} mm deep over {MIN_WALL_MM:g} mm of steel",
                          limit=HEIGHT)
    depth, carrier = least, CARRIER_MM
    if j.pocket_depth_mm is not None:  # the lab's pocket: the carrier fills what the die leaves
        most = j.thickness_mm - MIN_WALL_MM
        if not least - 1e-9 <= j.pocket_depth_mm <= most + 1e-9:
            raise DesignError("grasper_jaw.pocket_depth_mm", j.pocket_depth_mm,
                              f"{least:.4g} ... {most:.4g} mm",
                              f"from the face: the die ({stack:.4g} mm), its attach "
                              f"({attach:g} mm) and at least the {CARRIER_MM:g} mm stock "
                              f"carrier, over {MIN_WALL_MM:g} mm of steel in the "
                              f"{j.thickness_mm:g} mm jaw", limit=HEIGHT)
        depth = j.pocket_depth_mm
        carrier = depth - stack - attach - DEVICE_RECESS_MM
    carrier_l = die_l + BOND_SHELF_MM
    pocket_l = carrier_l + 2 * c
    x1 = j.length_mm - j.distal_wall_mm
    x0 = x1 - pocket_l
    least = pocket_start_limit_mm(j)
    if x0 < least - 1e-9:
        raise DesignError("grasper_jaw.length_mm", j.length_mm,
                          f">= {least + pocket_l + j.distal_wall_mm:.4g} mm",
                          f"the pin's steel, the {pocket_l:.4g} mm pocket and the "
                          f"{j.distal_wall_mm:g} mm distal wall", limit=FOOTPRINT)
    face = j.thickness_mm
    die_z0 = face - DEVICE_RECESS_MM - stack
    post_proud = plan.post_height_um * 1e-3 - DEVICE_RECESS_MM
    reasons = {
        "pocket": f"{pocket_l:.4g} x {pocket_w:.4g} x {depth:.4g} mm"
                  + (" (its depth the lab's, pocket_depth_mm)" if j.pocket_depth_mm is not None
                     else "") + ", open at the face: the "
                  f"carrier (the die's {die_l:g} mm and a {BOND_SHELF_MM:g} mm bond shelf) and "
                  f"{c:g} mm clearance each side, ending {j.distal_wall_mm:g} mm before the tip",
        "carrier": (f"{CARRIER_MM:g} mm alumina (assumption: a stock thin-film substrate)"
                    if j.pocket_depth_mm is None else
                    f"{carrier:.4g} mm alumina: the lab's {depth:g} mm pocket (pocket_depth_mm) "
                    f"less the die and its attach (assumption: a thin-film substrate lapped "
                    f"to it from stock no thinner than {CARRIER_MM:g} mm)")
                   + f", {carrier_l:.4g} x {die_w:g} mm: the die and, proximal to it, the "
                     "flex cable's solder pads",
        "die_attach": f"{attach:g} mm {plan.attach.material} ({plan.attach.source})",
        "post_proud": f"the device layer {DEVICE_RECESS_MM:g} mm below the face, its "
                      f"{plan.post_height_um:g} um posts {post_proud * 1e3:.4g} um proud: a "
                      "die's posts cannot reach through a face wall, so the pocket opens at "
                      "the face",
    }
    return DieMount(j.length_mm, width, face, j.pin_inset_mm, j.pin_diameter_mm, x0, pocket_l,
                    pocket_w, depth, x0 + c, carrier_l, die_w, carrier,
                    x0 + c + BOND_SHELF_MM, die_z0, die_l, die_w, stack, post_proud, attach,
                    reasons, float(j.opening_angle_deg))


def least_pocket_depth_mm() -> float:
    """The shallowest pocket any die takes.

    Returns:
        The thinnest stock device layer on the default buried oxide and handle, the default
        die attach and the stock carrier (mm).
    """
    from tactcad.products.silicon_die.vocabulary.soi_process import (DEFAULT_BOX_UM,
                                                                     DEFAULT_HANDLE_UM,
                                                                     DEVICE_LAYER_CHOICES_UM)

    stack = (DEFAULT_HANDLE_UM + DEFAULT_BOX_UM + min(DEVICE_LAYER_CHOICES_UM)) * 1e-3
    return stack + DIE_ATTACH_MM + CARRIER_MM + DEVICE_RECESS_MM


def die_misfit(room, jaw_table: Mapping[str, Any], columns: int,
               pitch_um: float | None = None) -> list[dict]:
    """The dimensions in which no die of ``columns`` fits the jaw, before it is planned: the
    jaw's thickness (or its stated pocket depth) against the thinnest die on its attach and
    carrier over the steel under them, the pocket's width against the die's frame, the
    pocket's length against the columns at ``pitch_um`` (default the die command's) and
    the carrier's bond shelf (mm).

    Args:
        room: the jaw's room (:class:`tactcad.partlib.grasper_jaw.JawRoom`, mm).
        jaw_table: its ``[grasper_jaw]`` table.
        columns: the die's units along it.
        pitch_um: their spacing (um).

    Returns:
        Each misfit a dict: ``words`` (the die's size against the jaw's, naming the jaw
        file's key; where no key of a lab's jaw file holds the die, why, e.g. the shaft it
        needs) and ``option`` (what to paste: fewer columns, or a jaw file's keys and values,
        each paste the jaw file read back through the jaw's own rules by
        :meth:`~tactcad.partlib.grasper_jaw.JawRoom.file_paste`; "" where there is none);
        empty when the die may fit (its plan decides).
    """
    from tactcad.partlib.grasper_jaw import (MIN_WALL_MM, GrasperJawSection, validated_table,
                                             with_class_defaults)
    from tactcad.products.silicon_die.design.mems_die import (DEFAULT_PITCH_UM, END_UM,
                                                              FRAME_UM)

    j = with_class_defaults(validated_table("grasper_jaw", GrasperJawSection, dict(jaw_table)))
    own = room.option and room.option not in ("5", "10")
    where = f" in {room.option}" if own else ""
    pitch = DEFAULT_PITCH_UM if pitch_um is None else pitch_um
    least = least_pocket_depth_mm()
    out = []
    thin = j.thickness_mm < least + MIN_WALL_MM - 1e-9
    if thin or (j.pocket_depth_mm is not None and j.pocket_depth_mm < least - 1e-9):
        # the keys to paste are the jaw file's own check's (JawRoom.file_paste): read back
        # through the jaw's rules (the closed jaws in the shaft among them) before offered
        across = 2 * FRAME_UM * 1e-3 + 0.01  # past the die's two frames, by a hundredth
        along = (columns * pitch + 2 * END_UM) * 1e-3 + BOND_SHELF_MM
        keys, why_not = room.file_paste((across, along, 0.0), face_depth_mm=least)
        why_not = f"; {why_not}" if own and why_not else ""
        option = f"{' and '.join(k for k, _ in keys)}{where}" if own and keys else ""
        if thin:
            words = (f"thickness: the thinnest die, its attach and carrier ({least:.3g} mm) "
                     f"over {MIN_WALL_MM:g} mm of steel need {least + MIN_WALL_MM:.3g} mm vs "
                     f"the jaw's {j.thickness_mm:g} mm (thickness_mm)")
        else:
            words = (f"depth: the thinnest die, its attach and carrier need {least:.3g} mm vs "
                     f"the pocket's {j.pocket_depth_mm:g} mm (pocket_depth_mm)")
        out.append({"words": words + why_not, "option": option})
    if room.across_mm * 1e3 <= 2 * FRAME_UM + 1e-6:
        out.append({"words": f"width: the die's two {FRAME_UM:g} um frames and its beams "
                             f"between need more than {2 * FRAME_UM * 1e-3:g} mm vs the "
                             f"pocket's {room.across_mm:.3g} mm inside its clearances "
                             "(pocket_width_mm, or width_mm less the side walls)",
                    "option": ""})
    along_um = (room.along_mm - BOND_SHELF_MM) * 1e3
    most = int((along_um - 2 * END_UM + 1e-6) // pitch)
    if most < columns:
        length = (columns * pitch + 2 * END_UM) * 1e-3 + BOND_SHELF_MM
        key = "pocket_length_mm" if "pocket_length_mm" in (room.table or {}) else "length_mm"
        option = f"--columns {most}" if most >= 2 else ""
        if not option and own and key == "pocket_length_mm":
            need = math.ceil(((columns * pitch + 2 * END_UM) * 1e-3 + BOND_SHELF_MM
                              + 2 * room.clearance_mm) * 100) / 100
            option = f"grasper_jaw.pocket_length_mm = {need:g}{where}"
        out.append({"words": f"length: {columns} columns at {pitch:g} um, the die's ends and "
                             f"the carrier's {BOND_SHELF_MM:g} mm bond shelf need "
                             f"{length:.3g} mm vs the pocket's {room.along_mm:.3g} mm inside "
                             f"its clearances ({key}); at most {max(most, 0)} columns fit",
                    "option": option})
    return out
