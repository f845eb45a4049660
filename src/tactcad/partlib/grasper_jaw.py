"""The jaw of a laparoscopic grasper that carries the tactile insert (a
bought-in grasper body in 17-4PH or 316L stainless steel, machined to take
the insert): a bar of the shaft class's width less a clearance, a pivot pin
hole across it near its proximal end, a pocket opened from the back that
takes the insert, and a window through the jaw's face wall over the tip field
through which the tips stand proud of the face by a set height.

The pocket follows the insert's envelope (a monolithic comb's
``plan.comb.envelope_mm``: across the rows, along the row, height) plus a
clearance on every side unless the table sets it; a stated pocket is checked
against the envelope. The insert sits in the pocket with its contact faces
``tip_proud_mm`` above the jaw face; the face wall stays above the arms when
wall + proud < the element's tip height (``element.tip_height_mm``).

Not in the rigs file: the jaw is the insert's host in use, not a test rig
(``IN_USE_PART`` is the module's part; the ``grasper`` rig of a project's
scenes places it, :mod:`tactcad.assembly.rig_models`). Part frame: x along the jaw from
its proximal end (x = 0), y across it (centred), z = 0 on its back, the
grasping face at z = thickness. Units: mm, degrees.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from pathlib import PurePath
from types import SimpleNamespace
from typing import Any, Mapping, Optional

from pydantic import create_model

from tactcad.kernel.shapes import box, cut, cylinder
from tactcad.partlib.base import DrawingRecord, PartData, RigPart, Seat
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import (Derived, Problems, Section, choice, fmt, listing, number,
                                       validate)

#: Trocar classes (mm): the instrument's shaft diameter.
SHAFT_CLASSES_MM = {"5": 5.0, "10": 10.0}
#: The jaw body's steels (a bought-in grasper's jaw machined for the insert).
JAW_STEELS = ("17-4PH stainless steel", "316L stainless steel")
#: Each class's jaw where the table leaves it (mm): its width below the class (the
#: clearance), thickness, the opposing jaw's thickness and the pin. Closed, the two jaws'
#: section (width x both thicknesses) stays inside the trocar with room to spare (10 mm:
#: 6.5 x 7.1 mm, diagonal 9.6 mm; 5 mm: 3.3 x 3.5 mm, diagonal 4.8 mm), the pin with
#: 0.5 mm of steel above and below it.
CLASS_DEFAULTS_MM = {
    "5": {"width_clearance_mm": 1.7, "thickness_mm": 2.3, "opposing_jaw_mm": 1.2,
          "pin_diameter_mm": 1.0},
    "10": {"width_clearance_mm": 3.5, "thickness_mm": 5.6, "opposing_jaw_mm": 1.5,
           "pin_diameter_mm": 1.5},
}
#: Thinnest face wall over the pocket (mm): the steel the window is cut through.
FACE_WALL_MIN_MM = 0.1
#: Least steel left between the pin hole and the pocket, and behind the pocket's far end, mm.
MIN_WALL_MM = 0.5
#: The steel round the pivot pin's hole (above, below and behind it), as a fraction of the
#: jaw's thickness: a jaw's ligaments scale with its section (assumption: a tenth, 0.56 mm
#: on the 10 mm class's 5.6 mm jaw, 0.25 mm on a 2.5 mm robotic jaw).
PIN_WALL_REL = 0.1
#: The thinnest steel round a reamed pin hole whatever the jaw (mm; assumption: below it
#: the wall breaks out when the hole is reamed).
PIN_WALL_MIN_MM = 0.2
COLOR = (0.72, 0.74, 0.78)


class GrasperJawSection(Section):
    """``[grasper_jaw]``: the jaw, its pivot, pocket and tip window (mm, degrees). A lab's
    own jaw file (``design --jaw FILE``) states the keys of :data:`JAW_FILE_KEYS`."""

    shaft_class_mm: choice(SHAFT_CLASSES_MM, why="the trocar the instrument passes; its "
                           "jaw's sizes where the table leaves them (CLASS_DEFAULTS_MM)") = "10"
    shaft_diameter_mm: Optional[number(
        2.0, 20.0, why="the bore the closed jaws pass (trocar or the instrument's shaft); "
        "left out: the class's")] = None
    width_mm: Optional[number(1.0, 20.0, why="the jaw across its face; left out: the shaft "
                              "less width_clearance_mm")] = None
    width_clearance_mm: Optional[number(
        0.0, 6.0, why="the jaw's width below the shaft's diameter, where width_mm is left "
        "out; left out: the class's")] = None
    length_mm: number(5.0, 80.0, why="the jaw's body from its proximal end (heel) to its "
                      "tip") = 34.0
    thickness_mm: Optional[number(1.0, 10.0, why="the jaw's height, back to grasping face; "
                                  "left out: the class's")] = None
    opposing_jaw_mm: Optional[number(
        0.5, 10.0, why="the other jaw's height, closed on this one (both pass the shaft); "
        "left out: the class's")] = None
    pin_diameter_mm: Optional[number(0.5, 4.0, why="the pivot pin: any the jaw's body "
                                     "holds with a tenth of its thickness (at least 0.2 mm) "
                                     "of steel round the hole; left out: the class's")] = None
    pin_inset_mm: number(-40.0, 40.0, why="the pivot: the pin's axis from the jaw's heel "
                         "along the jaw; negative where the pivot lies behind the heel (the "
                         "grasper's clevis carries the jaw, no pin hole in it)") = 2.5
    pocket_clearance_mm: number(0.0, 1.0, why="the pocket's gap round the insert, each "
                                "side") = 0.1
    pocket_length_mm: Optional[number(1.0, 80.0, why="the pocket along the jaw; left out: "
                                      "the insert's row + clearance")] = None
    pocket_width_mm: Optional[number(0.5, 10.0, why="the pocket across the jaw; left out: "
                                     "across the insert's rows + clearance")] = None
    #: the region of the jaw a pocket may take (a tapered or curved jaw), a polygon of
    #: [x, y] points in the jaw's frame (x from the proximal end, y across from its axis;
    #: mm); the pocket is placed inside it. Left out: the bar between the pin's steel and
    #: the distal wall, less the side walls
    pocket_depth_mm: Optional[number(
        0.0, 10.0, lo_open=True, why="the pocket's depth as the lab machines it: from the "
        "jaw's back for a comb (the face wall the rest), from the grasping face for a die "
        "(its carrier fills what the die leaves); less than thickness_mm; left out: each "
        "construction's own")] = None
    pocket_outline_mm: Optional[listing(listing(number(-100.0, 100.0, why="a point's "
                                                       "[x, y]: x along the jaw from its heel, "
                                                       "y across it from its axis"), 2, 2,
                                                "an [x, y] point (mm)"),
                                        3, 64, "3 ... 64 [x, y] points (mm)")] = None
    face_wall_mm: number(FACE_WALL_MIN_MM, 3.0, why="the steel over the pocket the window "
                         "is cut through") = 0.3
    tip_proud_mm: number(0.0, 3.0, why="the contact faces above the jaw's face") = 0.3
    window_clearance_mm: number(0.0, 1.0, why="the window's gap round the tip field") = 0.1
    distal_wall_mm: number(0.3, 10.0, why="steel beyond the pocket's far end") = 1.0
    opening_angle_deg: number(0.0, 90.0, lo_open=True, unit="degrees",
                              why="the jaw fully open, about its pivot") = 30.0
    material: choice(JAW_STEELS) = JAW_STEELS[0]


#: What a lab's own jaw file states, each key or one of its alternatives (a tuple): the
#: jaw's size, pivot, opening and the shaft it passes. Left out, the key is refused by its
#: name (a class's default jaw is ``--jaw 5`` or ``--jaw 10``).
JAW_FILE_KEYS = (("shaft_diameter_mm", "shaft_class_mm"), ("width_mm", "width_clearance_mm"),
                 "length_mm", "thickness_mm", "pin_inset_mm", "opening_angle_deg")


def missing_jaw_file_keys(table: Mapping[str, Any]) -> list[str]:
    """The keys of :data:`JAW_FILE_KEYS` a jaw file's ``[grasper_jaw]`` leaves out (an
    alternative pair as "a or b")."""
    missing = []
    for key in JAW_FILE_KEYS:
        options = key if isinstance(key, tuple) else (key,)
        if not any(k in table for k in options):
            missing.append(" or ".join(options))
    return missing


def class_jaw_file_table(shaft_class: str) -> dict[str, Any]:
    """The keys of :data:`JAW_FILE_KEYS` for a trocar class's default jaw (the start of a
    lab's own jaw file; mm, degrees).

    Raises:
        KeyError: ``shaft_class`` not one of :data:`SHAFT_CLASSES_MM`.
    """
    j = with_class_defaults(GrasperJawSection(shaft_class_mm=shaft_class))
    return {"shaft_class_mm": shaft_class, "width_clearance_mm": j.width_clearance_mm,
            "length_mm": j.length_mm, "thickness_mm": j.thickness_mm,
            "pin_inset_mm": j.pin_inset_mm, "opening_angle_deg": j.opening_angle_deg}


def bore_mm(j: GrasperJawSection) -> float:
    """The bore the closed jaws pass (mm): ``shaft_diameter_mm``, else the class's."""
    return j.shaft_diameter_mm if j.shaft_diameter_mm is not None \
        else SHAFT_CLASSES_MM[j.shaft_class_mm]


def jaw_width_mm(j: GrasperJawSection) -> float:
    """The jaw's width (mm): ``width_mm``, else the bore less ``width_clearance_mm``
    (the table with its class defaults filled in)."""
    return j.width_mm if j.width_mm is not None else bore_mm(j) - j.width_clearance_mm


def shaft_words(j: GrasperJawSection) -> str:
    """The shaft the jaw passes, in words and as a label's key: "10" for a class, "12" for
    a stated diameter (mm)."""
    return fmt(bore_mm(j)) if j.shaft_diameter_mm is not None else j.shaft_class_mm


def pin_in_bar(g) -> bool:
    """Whether the pivot pin goes through the jaw's bar (False: behind its heel)."""
    return g.pin_x_mm > 0


def _check_stated_once(p: Problems, j: GrasperJawSection) -> None:
    """A size stated two ways is refused (the jaw's width, the shaft's diameter); ``j``
    with its class defaults (:func:`with_class_defaults`)."""
    stated = j.model_fields_set
    if j.width_mm is not None and j.width_clearance_mm is not None:
        p.add("grasper_jaw.width_clearance_mm", j.width_clearance_mm, "left out with width_mm",
              "the jaw's width is stated once: width_mm, or the shaft less width_clearance_mm")
    if "shaft_diameter_mm" in stated and "shaft_class_mm" in stated \
            and abs(j.shaft_diameter_mm - SHAFT_CLASSES_MM[j.shaft_class_mm]) > 1e-9:
        p.add("grasper_jaw.shaft_diameter_mm", j.shaft_diameter_mm,
              f"{fmt(SHAFT_CLASSES_MM[j.shaft_class_mm])} mm (shaft_class_mm = "
              f"{j.shaft_class_mm!r}) or shaft_class_mm left out", "one shaft per jaw")
    width = jaw_width_mm(j)
    if width > bore_mm(j) + 1e-9:
        p.add("grasper_jaw.width_mm", width, f"<= {fmt(bore_mm(j))} mm",
              f"the jaw passes the {fmt(bore_mm(j))} mm shaft")


def pin_wall_mm(thickness_mm: float) -> float:
    """The least steel round the pivot pin's hole in a jaw.

    Args:
        thickness_mm: the jaw's thickness, back to grasping face (mm).

    Returns:
        :data:`PIN_WALL_REL` of the thickness, at least :data:`PIN_WALL_MIN_MM` (mm).
    """
    return max(PIN_WALL_MIN_MM, PIN_WALL_REL * thickness_mm)


def pin_limits_mm(j: GrasperJawSection) -> tuple[float, float]:
    """The pins the jaw's own body allows through it.

    Args:
        j: the ``[grasper_jaw]`` table with its class defaults (:func:`with_class_defaults`).

    Returns:
        (the largest pin diameter, the least inset of the stated pin's axis from the heel),
        mm: the hole with :func:`pin_wall_mm` of steel above and below it within
        ``thickness_mm``, and behind it within the heel.
    """
    wall = pin_wall_mm(j.thickness_mm)
    return j.thickness_mm - 2 * wall, j.pin_diameter_mm / 2 + wall


def _check_pivot(p: Problems, j: GrasperJawSection) -> None:
    """The pivot pin goes through the bar with steel round it (:func:`pin_limits_mm`, from
    the jaw's own thickness), or lies behind the heel clear of it; each refusal names the
    key, its value and the range the jaw's body allows."""
    r = j.pin_diameter_mm / 2
    wall = pin_wall_mm(j.thickness_mm)
    most_d, least_x = pin_limits_mm(j)
    if j.pin_inset_mm > -r:  # through the bar (or cutting its heel)
        p.within("grasper_jaw.pin_diameter_mm", j.pin_diameter_mm, hi=round(most_d, 4),
                 why=f"the {fmt(j.thickness_mm)} mm thick jaw keeps {fmt(round(wall, 4))} mm of "
                     "steel above and below the pin hole: a tenth of its thickness, at least "
                     f"{fmt(PIN_WALL_MIN_MM)} mm")
    if -r < j.pin_inset_mm < least_x - 1e-9:
        p.add("grasper_jaw.pin_inset_mm", j.pin_inset_mm,
              f">= {fmt(round(least_x, 4))} mm (in the jaw) or <= {fmt(-r)} mm (behind its "
              "heel)", f"the {fmt(j.pin_diameter_mm)} mm pin through the jaw with "
              f"{fmt(round(wall, 4))} mm of steel behind it, or clear of the heel")
    elif j.pin_inset_mm > j.length_mm - least_x + 1e-9:
        p.add("grasper_jaw.pin_inset_mm", j.pin_inset_mm,
              f"<= {fmt(round(j.length_mm - least_x, 4))} mm",
              f"the pin inside the {fmt(j.length_mm)} mm jaw with {fmt(round(wall, 4))} mm "
              "of steel round it")


def _check_depth(p: Problems, j: GrasperJawSection) -> None:
    """A stated pocket depth lies inside the jaw: 0 < depth < ``thickness_mm``."""
    if j.pocket_depth_mm is not None:
        p.within("grasper_jaw.pocket_depth_mm", j.pocket_depth_mm, 0.0, j.thickness_mm,
                 lo_open=True, hi_open=True,
                 why=f"a pocket inside the jaw's {fmt(j.thickness_mm)} mm thickness "
                     "(thickness_mm)")


#: The keys the closed jaws' rule (:func:`_check_closed`) may name, in the order it names
#: the stated ones when no ``--set`` value decides: this jaw's thickness, its width, the
#: opposing jaw's thickness, the shaft's diameter.
CLOSED_RULE_KEYS = ("thickness_mm", "width_mm", "width_clearance_mm", "opposing_jaw_mm",
                    "shaft_diameter_mm")


def closed_rule_blame(stated: Any, set_keys: Any = ()) -> tuple[str, ...]:
    """The keys of :data:`CLOSED_RULE_KEYS` the closed jaws' rule names first: those set
    (``--set`` or ``set=``; dotted ``grasper_jaw.<key>`` or bare), then those the table
    states.

    Args:
        stated: the ``[grasper_jaw]`` keys the design states (file and set values).
        set_keys: the keys given over the file, dotted or bare.

    Returns:
        The keys in the order the rule tries them (each once).
    """
    bare = {k.split(".", 1)[1] if k.startswith("grasper_jaw.") else k for k in set_keys
            if "." not in k or k.startswith("grasper_jaw.")}
    order = [k for k in CLOSED_RULE_KEYS if k in bare] + \
        [k for k in CLOSED_RULE_KEYS if k in set(stated)]
    return tuple(dict.fromkeys(order))


def _closed_refusal(j: GrasperJawSection, key: str) -> tuple[float, str] | None:
    """(value, allowed range) of ``key`` with which the two jaws closed pass the shaft, the
    other keys as they are; None where no value of it does (or it does not set a size)."""
    width, bore, o, t = jaw_width_mm(j), bore_mm(j), j.opposing_jaw_mm, j.thickness_mm
    both_jaws = t + o
    beside = closed_thickness_limit_mm(bore, width)  # both jaws' thickness the width leaves
    across = closed_thickness_limit_mm(bore, both_jaws)  # the width both jaws leave
    # each bound within the key's own range (GrasperJawSection), else no value of it passes
    if key == "thickness_mm" and beside - o >= 1.0:
        return t, (f"<= {fmt(math.floor((beside - o) * 1e4) / 1e4)} mm with the {fmt(o)} mm "
                   "opposing jaw (opposing_jaw_mm)")
    if key == "opposing_jaw_mm" and beside - t >= 0.5:
        return o, (f"<= {fmt(math.floor((beside - t) * 1e4) / 1e4)} mm with this jaw's "
                   f"{fmt(t)} mm (thickness_mm)")
    if key == "width_mm" and j.width_mm is not None and across >= 1.0:
        return width, (f"<= {fmt(math.floor(across * 1e4) / 1e4)} mm with the jaws' "
                       f"{fmt(t)} + {fmt(o)} mm (thickness_mm, opposing_jaw_mm)")
    if key == "width_clearance_mm" and j.width_mm is None and both_jaws < bore - 1e-9 \
            and bore - across <= 6.0:
        return j.width_clearance_mm, (f">= {fmt(math.ceil((bore - across) * 1e4) / 1e4)} mm "
                                      f"with the jaws' {fmt(t)} + {fmt(o)} mm (thickness_mm, "
                                      "opposing_jaw_mm)")
    if key == "shaft_diameter_mm" and j.shaft_diameter_mm is not None:
        if j.width_mm is not None:
            least = math.hypot(width, both_jaws)
        elif j.width_clearance_mm > 1e-9:  # (D - c)^2 + T^2 <= D^2
            least = (j.width_clearance_mm ** 2 + both_jaws ** 2) / (2 * j.width_clearance_mm)
        else:
            return None
        if least > 20.0:
            return None
        return j.shaft_diameter_mm, (f">= {fmt(math.ceil(least * 1e4) / 1e4)} mm for the "
                                     f"{fmt(width)} mm wide jaws, {fmt(t)} + {fmt(o)} mm "
                                     "thick (width_mm, thickness_mm, opposing_jaw_mm)")
    return None


def _check_closed(p: Problems, j: GrasperJawSection, blame: tuple[str, ...] = ()) -> None:
    """The two jaws closed pass the shaft: width x (thickness + the opposing jaw) inside its
    bore. Refused naming the first key of ``blame`` (:func:`closed_rule_blame`: the key a
    user set, else one the table states) that some value of it lets pass, with that value's
    range; else ``thickness_mm``, with the width and opposing jaw's keys; a jaw as wide as
    the bore, which leaves no thickness at all, naming its width and the widest the two
    jaws' thicknesses pass.

    Args:
        p: refusals are added here (field, value, allowed range, reason).
        j: the table with its class defaults (:func:`with_class_defaults`; mm).
        blame: the keys to name first, in order.
    """
    width, bore = jaw_width_mm(j), bore_mm(j)
    both_jaws = j.thickness_mm + j.opposing_jaw_mm
    closed = math.hypot(width, both_jaws)
    if closed <= bore + 1e-9 or width > bore + 1e-9:  # too wide: the width's refusal says it
        return
    for key in blame if width < bore - 1e-9 else ():
        found = _closed_refusal(j, key)
        if found is not None:
            p.add(f"grasper_jaw.{key}", found[0], found[1],
                  f"the closed jaws ({fmt(width)} x {fmt(both_jaws)} mm, diagonal "
                  f"{fmt(round(closed, 4))} mm) pass the {shaft_words(j)} mm shaft")
            return
    if width >= bore - 1e-9:  # as wide as the bore: no thickness of either jaw passes
        key = "width_mm" if j.width_mm is not None else "width_clearance_mm"
        widest = math.floor(closed_thickness_limit_mm(bore, both_jaws) * 1e4) / 1e4
        value = width if key == "width_mm" else j.width_clearance_mm
        allowed = (f"<= {fmt(widest)} mm" if key == "width_mm" else
                   f">= {fmt(math.ceil((bore - widest) * 1e4) / 1e4)} mm") \
            if both_jaws < bore - 1e-9 else (f"< {fmt(bore)} mm" if key == "width_mm" else "> 0 mm")
        p.add(f"grasper_jaw.{key}", value, allowed,
              f"the closed jaws ({fmt(width)} x {fmt(both_jaws)} mm: this jaw's "
              f"{fmt(j.thickness_mm)} mm (thickness_mm) and the opposing jaw's "
              f"{fmt(j.opposing_jaw_mm)} mm (opposing_jaw_mm)) pass the {shaft_words(j)} mm "
              "shaft only narrower than it" + ("" if both_jaws < bore - 1e-9 else
                                                 "; and the two jaws together thinner than it"))
        return
    both = closed_thickness_limit_mm(bore, width)
    if j.opposing_jaw_mm >= both - 1e-9:  # no jaw thickness fits beside this opposing jaw
        p.add("grasper_jaw.opposing_jaw_mm", j.opposing_jaw_mm, f"< {fmt(round(both, 4))} mm",
              f"the {fmt(width)} mm wide jaws closed pass the {shaft_words(j)} mm shaft only "
              f"when both together are thinner than {fmt(round(both, 4))} mm; this jaw "
              f"(thickness_mm) is {fmt(j.thickness_mm)} mm")
    else:
        p.add("grasper_jaw.thickness_mm", j.thickness_mm,
              f"<= {fmt(round(closed_thickness_limit_mm(bore, width) - j.opposing_jaw_mm, 4))}"
              f" mm with the {fmt(j.opposing_jaw_mm)} mm opposing jaw (opposing_jaw_mm)",
              f"the closed jaws ({fmt(width)} x {fmt(j.thickness_mm + j.opposing_jaw_mm)} mm, "
              f"diagonal {fmt(round(closed, 4))} mm) pass the {shaft_words(j)} mm shaft; "
              + room_for_thickness_words(j))


def room_for_thickness_words(j: GrasperJawSection) -> str:
    """The jaw file's values that let the stated ``thickness_mm`` pass the shaft closed,
    each with the other keys kept: the widest jaw (``width_mm``, or the least
    ``width_clearance_mm`` where the width is left out), and the thickest opposing jaw
    (``opposing_jaw_mm``); a key no value of which in its own range lets it pass is said so.

    Args:
        j: the table with its class defaults (:func:`with_class_defaults`; mm).

    Returns:
        The words, e.g. ``for the stated 3.2 mm (thickness_mm): width_mm <= 10.1508 mm with
        the 3.2 mm opposing jaw, or opposing_jaw_mm <= 1.5958 mm with the 11 mm width``.
    """
    bore, t, o, width = bore_mm(j), j.thickness_mm, j.opposing_jaw_mm, jaw_width_mm(j)
    widest = closed_thickness_limit_mm(bore, t + o) if t + o < bore - 1e-9 else 0.0
    widest = math.floor(widest * 1e4) / 1e4
    if j.width_mm is not None:
        key_words = "width_mm" if widest < 1.0 else f"width_mm <= {fmt(widest)} mm"
    else:
        least = math.ceil((bore - widest) * 1e4) / 1e4
        key_words = "width_clearance_mm" if widest <= 0.0 or least > 6.0 else \
            f"width_clearance_mm >= {fmt(least)} mm"
    width_part = (f"{key_words} with the {fmt(o)} mm opposing jaw" if "=" in key_words else
                  f"no {key_words} with the {fmt(o)} mm opposing jaw")
    thickest = math.floor((closed_thickness_limit_mm(bore, width) - t) * 1e4) / 1e4
    opposing_part = (f"opposing_jaw_mm <= {fmt(thickest)} mm" if thickest >= 0.5 else
                     "no opposing_jaw_mm") + f" with the {fmt(width)} mm width"
    return (f"for the stated {fmt(t)} mm (thickness_mm): {width_part}, or {opposing_part}")


def pocket_start_limit_mm(j: GrasperJawSection) -> float:
    """The nearest the pocket comes to the heel (x, mm): past the pin's steel, or the
    heel's wall when the pivot lies behind the heel."""
    if j.pin_inset_mm > 0:
        return j.pin_inset_mm + j.pin_diameter_mm / 2 + MIN_WALL_MM
    return MIN_WALL_MM


@dataclass(frozen=True)
class GrasperJawGeometry:
    """The jaw, every size filled in (mm; frame: see the module doc)."""

    length_mm: float
    width_mm: float
    thickness_mm: float
    pin_x_mm: float
    pin_diameter_mm: float
    pocket_x0_mm: float
    pocket_length_mm: float
    pocket_width_mm: float
    pocket_depth_mm: float
    window_length_mm: float
    window_width_mm: float
    tip_proud_mm: float
    opening_angle_deg: float
    #: the window's centre off the pocket's (along x, across y): the insert's tip field
    #: off its envelope's centre (:func:`tip_field_offset_mm`)
    window_offset_mm: tuple[float, float] = (0.0, 0.0)
    #: the region the pocket may take, as stated (``pocket_outline_mm``), or None
    pocket_outline_mm: tuple[tuple[float, float], ...] | None = None

    @property
    def pocket_centre_x_mm(self) -> float:
        return self.pocket_x0_mm + self.pocket_length_mm / 2

    @property
    def window_centre_mm(self) -> tuple[float, float]:
        """(x, y) of the window's centre in the jaw frame (mm)."""
        return self.pocket_centre_x_mm + self.window_offset_mm[0], self.window_offset_mm[1]


def outline_stretch_mm(outline, across_mm: float) -> tuple[float, float] | None:
    """The longest stretch (x0, x1) along the jaw over which ``outline`` (polygon points in
    the jaw's frame, mm) holds a band ``across_mm`` wide centred on the jaw's axis; None
    when it holds none. Exact: between two breakpoints (a vertex, or an edge crossing the
    band's sides) a cross-section is inside for all of the stretch or for none of it."""
    import shapely.geometry as sg

    poly = sg.Polygon(outline)
    h = across_mm / 2
    pts = list(outline) + [outline[0]]
    xs = {x for x, y in outline}
    for (xa, ya), (xb, yb) in zip(pts, pts[1:]):
        for side in (-h, h):
            if (ya - side) * (yb - side) < 0:
                xs.add(xa + (side - ya) * (xb - xa) / (yb - ya))
    xs = sorted(xs)
    good = [(a, b) for a, b in zip(xs, xs[1:])
            if b > a and poly.covers(sg.LineString([((a + b) / 2, -h), ((a + b) / 2, h)]))]
    merged: list[list[float]] = []
    for a, b in good:
        if merged and abs(merged[-1][1] - a) < 1e-12:
            merged[-1][1] = b
        else:
            merged.append([a, b])
    best = max(merged, key=lambda s: s[1] - s[0], default=None)
    return None if best is None else (best[0], best[1])


def _pocket_in_outline(p: Problems, outline, width_mm: float, length_mm: float,
                       fallback_x0: float) -> float:
    """The pocket's proximal end (x, mm) centred in the longest stretch of ``outline`` that
    holds it ``width_mm`` wide on the jaw's axis; a refusal when none is ``length_mm`` long."""
    stretch = outline_stretch_mm(outline, width_mm)
    if stretch is None or stretch[1] - stretch[0] < length_mm - 1e-9:
        got = "none" if stretch is None else f"{fmt(round(stretch[1] - stretch[0], 4))} mm"
        p.add("grasper_jaw.pocket_outline_mm", [list(q) for q in outline],
              f"an outline holding the {fmt(width_mm)} x {fmt(length_mm)} mm pocket on the "
              "jaw's axis", f"its longest stretch {fmt(width_mm)} mm wide: {got}")
        return fallback_x0
    return (stretch[0] + stretch[1] - length_mm) / 2


def _check_outline(p: Problems, outline, x_lo: float, x_hi: float, half_width: float) -> bool:
    """A stated outline is one simple polygon inside the jaw's body (between the pin's
    steel and the distal wall along, inside the side walls across)."""
    from shapely import Polygon, is_valid  # the function: a shape's .is_valid is the kernel's

    field = "grasper_jaw.pocket_outline_mm"
    poly = Polygon(outline)
    if not is_valid(poly) or poly.area <= 0:
        p.add(field, [list(q) for q in outline], "a simple polygon of non-zero area",
              "its edges cross or it has no area")
        return False
    x0, y0, x1, y1 = poly.bounds
    if x0 < x_lo - 1e-9 or x1 > x_hi + 1e-9 or max(-y0, y1) > half_width + 1e-9:
        p.add(field, [list(q) for q in outline],
              f"points with {fmt(x_lo)} <= x <= {fmt(x_hi)} mm and |y| <= {fmt(half_width)} mm",
              "the jaw's body between the pin's steel and the distal wall, inside its "
              f"{fmt(MIN_WALL_MM)} mm side walls")
        return False
    return True


@dataclass(frozen=True)
class JawRoom:
    """The room a grasper's jaw leaves its insert (mm).

    Attributes:
        shaft_class_mm: the shaft the jaw passes: a trocar class ("5" or "10") or a stated
            diameter ("12"), mm.
        across_mm, along_mm: the pocket's width and length less its clearances: the
            stated pocket's, else the largest the jaw's body holds.
        height_mm: the insert's largest height (jaw thickness + the tips' proud height).
        option: the ``--jaw`` value that names this jaw (a class or a file).
        table: the ``[grasper_jaw]`` table a design for this jaw states (the class alone
            for a class's default jaw).
    """

    shaft_class_mm: str
    across_mm: float
    along_mm: float
    height_mm: float
    option: str = ""
    table: Mapping[str, Any] | None = None
    outline: tuple[tuple[float, float], ...] | None = None
    clearance_mm: float = 0.0

    def along_for(self, across_mm: float) -> float:
        """The pocket's length less its clearances (mm) for an insert ``across_mm`` wide:
        ``along_mm`` within ``across_mm``; with an outline, its longest stretch that
        holds the insert and its clearances; 0 where none does."""
        if self.outline is None:
            return self.along_mm if across_mm <= self.across_mm + 1e-9 else 0.0
        stretch = outline_stretch_mm(self.outline, across_mm + 2 * self.clearance_mm)
        return 0.0 if stretch is None else max(stretch[1] - stretch[0] - 2 * self.clearance_mm,
                                               0.0)

    def file_keys_to_hold(self, env: tuple[float, float, float]) -> list[tuple[str, str]]:
        """The ``[grasper_jaw]`` settings (``key = value`` to write in a lab's own jaw file,
        with why) that make its pocket hold an insert of envelope ``env`` (across, along,
        height; mm): :meth:`file_paste`'s keys (none where no jaw of its shaft holds it)."""
        return self.file_paste(env)[0]

    def file_paste(self, env: tuple[float, float, float],
                   face_depth_mm: float | None = None) -> tuple[list[tuple[str, str]], str]:
        """The ``[grasper_jaw]`` settings that make a lab's own jaw hold an insert of
        envelope ``env``: a thicker jaw (and its pocket depth, where the file states one),
        the width that still passes the shaft closed and holds the pocket with its side
        walls, a wider pocket. Every paste is the jaw file with those keys read back through
        the jaw's own rules (:func:`jaw_room`: each key's range, the pivot, the depth, the
        closed jaws inside the shaft) and its room holding the insert; none is offered
        otherwise.

        Args:
            env: the insert's envelope (across its rows, along, height; mm).
            face_depth_mm: for an insert in a pocket open at the grasping face (a silicon
                die): the least depth from the face it takes (mm); the jaw then needs that
                depth over :data:`MIN_WALL_MM` of steel, a stated ``pocket_depth_mm`` (from
                the face) is pasted to lie between them, and ``env``'s height is not read.
                None (a comb, its pocket from the back under a face wall): ``env``'s height
                against :attr:`height_mm`.

        Returns:
            (the settings: ``("grasper_jaw.key = value", why)`` each, mm; why there are none
            where a jaw of this shaft would hold the insert but none of its keys does, e.g.
            "needs a shaft of at least 10.08 mm", else ""). Both empty for a class's default
            jaw (no file to edit) or a room that already holds ``env``.
        """
        from tactcad.errors import DesignErrors

        if not self.option or self.option in SHAFT_CLASSES_MM:
            return [], ""
        table = dict(self.table or {})
        j = with_class_defaults(validated_table("grasper_jaw", GrasperJawSection, table))
        bore, c = bore_mm(j), self.clearance_mm
        update: dict[str, float] = {}
        why: dict[str, str] = {}
        thick = j.thickness_mm
        if face_depth_mm is None and env[2] > self.height_mm + 1e-9:
            thick = math.ceil((j.thickness_mm + env[2] - self.height_mm) * 100) / 100
            update["thickness_mm"] = thick
            why["thickness_mm"] = (f"the insert stands {env[2]:.4g} mm high; the jaw's thickness "
                                   f"and the tips' proud height hold {self.height_mm:.4g} mm")
            if j.pocket_depth_mm is not None:  # the comb's pocket from the back, its face wall kept
                update["pocket_depth_mm"] = round(thick - j.face_wall_mm, 2)
                why["pocket_depth_mm"] = (f"the pocket from the back of the {thick:g} mm jaw, "
                                          f"leaving the {j.face_wall_mm:g} mm face wall")
        if face_depth_mm is not None:  # a pocket open at the face over the steel under it
            depth = j.pocket_depth_mm
            if depth is not None and depth < face_depth_mm - 1e-9:
                depth = math.ceil(round(face_depth_mm * 100, 6)) / 100
                update["pocket_depth_mm"] = depth
                why["pocket_depth_mm"] = (f"the insert takes a pocket {face_depth_mm:.4g} mm "
                                          "deep from the face")
            need = (face_depth_mm if depth is None else max(depth, face_depth_mm)) + MIN_WALL_MM
            if thick < need - 1e-9:
                thick = math.ceil(round(need * 100, 6)) / 100
                update["thickness_mm"] = thick
                why["thickness_mm"] = (f"the pocket open at the face, "
                                       f"{need - MIN_WALL_MM:.4g} mm deep, over {MIN_WALL_MM:g} "
                                       f"mm of steel")
        pocket_w = j.pocket_width_mm
        if env[0] > self.across_mm + 1e-9 and (pocket_w is not None or self.outline is None):
            pocket_w = math.ceil((env[0] + 2 * c) * 100) / 100
            if j.pocket_width_mm is not None or jaw_width_mm(j) >= pocket_w + 2 * MIN_WALL_MM:
                update["pocket_width_mm"] = pocket_w
                why["pocket_width_mm"] = (f"the insert is {env[0]:.4g} mm across its rows, with "
                                          f"the pocket's {c:g} mm clearance each side")
        held = pocket_w if pocket_w is not None else env[0] + 2 * c
        least_w = math.ceil(round((held + 2 * MIN_WALL_MM) * 100, 6)) / 100
        closed = thick + j.opposing_jaw_mm
        widest = math.floor(closed_thickness_limit_mm(bore, closed) * 100) / 100 \
            if closed < bore else 0.0
        if widest < least_w - 1e-9:  # no width of this shaft holds the pocket closed
            shaft = math.ceil(round(math.hypot(least_w, closed) * 100, 6)) / 100
            return [], no_shaft_words(bore, thick, least_w, held, shaft, j)
        width = jaw_width_mm(j)
        new_w = widest if width > widest + 1e-9 else least_w if width < least_w - 1e-9 else width
        if new_w != width:
            words = (f"the closed jaws ({thick:g} + {j.opposing_jaw_mm:g} mm) pass the {bore:g} "
                     "mm shaft" if new_w < width else
                     f"the pocket and its {MIN_WALL_MM:g} mm side walls")
            if j.width_mm is None:  # the file states the width as a clearance below the shaft
                update["width_clearance_mm"] = round(bore - new_w, 2)
                why["width_clearance_mm"] = words
            else:
                update["width_mm"] = new_w
                why["width_mm"] = words
        if not update:
            return [], ""
        try:
            room = jaw_room({**table, **update}, self.option)
        except DesignErrors as exc:
            return [], ("no keys of this jaw file hold it: the jaw they make is refused ("
                        + "; ".join(f"{e.field} = {e.value}: allowed {e.allowed}"
                                    for e in exc.errors) + ")")
        if face_depth_mm is not None:  # the pasted jaw's steel under its pocket
            k = with_class_defaults(validated_table("grasper_jaw", GrasperJawSection,
                                                    {**table, **update}))
            depth = face_depth_mm if k.pocket_depth_mm is None else k.pocket_depth_mm
            if depth < face_depth_mm - 1e-9 or k.thickness_mm < depth + MIN_WALL_MM - 1e-9:
                return [], (f"no keys of this jaw file hold it: its {k.thickness_mm:g} mm jaw "
                            f"(thickness_mm) then keeps a {depth:g} mm pocket (pocket_depth_mm)"
                            f", the insert {face_depth_mm:.4g} mm deep over {MIN_WALL_MM:g} mm "
                            "of steel")
        high = env[2] if face_depth_mm is None else 0.0  # a face pocket: its depth, above
        if room.height_mm < high - 1e-9 or room.along_for(env[0]) <= 0:
            return [], ("no keys of this jaw file hold it: its pocket "
                        + ("(pocket_outline_mm) " if self.outline else "")
                        + f"then holds {room.across_mm:.4g} mm across and {room.height_mm:.4g} "
                        f"mm high, the insert {env[0]:.4g} x {env[2]:.4g} mm")
        order = ("thickness_mm", "pocket_depth_mm", "width_mm", "width_clearance_mm",
                 "pocket_width_mm")
        return [(f"grasper_jaw.{k} = {update[k]:g}", why[k]) for k in order if k in update], ""

    @property
    def label(self) -> str:
        """The jaw in words: a trocar class's "10 mm jaw" (the jaw of a 10 mm instrument,
        not its width); a file's by the shaft it passes and the file's name, "6.5 mm-shaft
        jaw of my_jaw.toml" (its width is the file's ``width_mm``)."""
        if self.option and self.option not in SHAFT_CLASSES_MM:
            return f"{self.shaft_class_mm} mm-shaft jaw of {PurePath(self.option).name}"
        return f"{self.shaft_class_mm} mm jaw"


def jaw_room(jaw: str | Mapping[str, Any], file: str = "") -> JawRoom:
    """The room a jaw leaves its insert, by this module's rules: a trocar class's default
    jaw, or a ``[grasper_jaw]`` table (a lab's own jaw; every field left out takes its
    default). Its pocket where the table states one (width, length), else the most the
    jaw's body holds: between the pin's steel and the distal wall along, between the side
    walls across.

    Args:
        jaw: a class of :data:`SHAFT_CLASSES_MM` or the table's values.
        file: the table's file, for the messages (it is also ``option``).

    Raises:
        DesignError: ``--jaw`` not a class of :data:`SHAFT_CLASSES_MM`.
        DesignErrors: the table refused (each field, value and allowed range), or a stated
            pocket the jaw's body cannot hold.
    """
    from tactcad.errors import DesignError

    if isinstance(jaw, str):
        if jaw not in SHAFT_CLASSES_MM:
            raise DesignError("--jaw", jaw, " or ".join(SHAFT_CLASSES_MM) + " (mm trocar class) "
                              "or a TOML file with a [grasper_jaw] table")
        table: dict[str, Any] = {"shaft_class_mm": jaw}
    else:
        table = dict(jaw)
    p = Problems(file)
    j, unread = _jaw_read(p, table, file, own_file=not isinstance(jaw, str))
    # every rule between keys whose values were read: all refusals at once
    rules = ((_check_stated_once, {"width_mm", "width_clearance_mm", "shaft_diameter_mm",
                                   "shaft_class_mm"}),
             (_check_pivot, {"pin_diameter_mm", "pin_inset_mm", "thickness_mm", "length_mm"}),
             (_check_depth, {"pocket_depth_mm", "thickness_mm"}),
             (_check_closed, {"thickness_mm", "opposing_jaw_mm", "width_mm",
                              "width_clearance_mm", "shaft_diameter_mm", "shaft_class_mm"}))
    for rule, keys in rules:
        if not keys & unread:
            rule(p, j)
    width = jaw_width_mm(j)
    most_along = j.length_mm - j.distal_wall_mm - pocket_start_limit_mm(j)
    most_across = width - 2 * MIN_WALL_MM
    across = along = 0.0
    if not {"pocket_width_mm", "width_mm", "width_clearance_mm"} & unread:
        across = _stated_pocket(p, "grasper_jaw.pocket_width_mm", j.pocket_width_mm,
                                most_across, f"the {fmt(width)} mm jaw less {fmt(MIN_WALL_MM)} "
                                "mm side walls")
    if not {"pocket_length_mm", "length_mm", "pin_inset_mm", "pin_diameter_mm"} & unread:
        along = _stated_pocket(p, "grasper_jaw.pocket_length_mm", j.pocket_length_mm,
                               most_along, "the jaw between the pin's steel and the distal wall")
    outline = tuple(tuple(q) for q in j.pocket_outline_mm) if j.pocket_outline_mm else None
    if outline:
        x_hi = j.length_mm - j.distal_wall_mm
        _check_outline(p, outline, x_hi - most_along, x_hi, most_across / 2)
    if p.errors:
        from tactcad.errors import DesignErrors

        raise DesignErrors(p.errors, what="the jaw file" if file else "the jaw")
    c = j.pocket_clearance_mm
    if outline:  # its widest band on the axis and its longest stretch (bounds of the room)
        across, along = round(_widest_band_mm(outline), 3), round(_longest_on_axis_mm(outline), 3)
    return JawRoom(shaft_words(j), max(across - 2 * c, 0.0), max(along - 2 * c, 0.0),
                   j.thickness_mm + j.tip_proud_mm,
                   option=jaw if isinstance(jaw, str) else file, table=table, outline=outline,
                   clearance_mm=c)


def _jaw_read(p: Problems, table: Mapping[str, Any], file: str,
              own_file: bool) -> tuple[GrasperJawSection, set[str]]:
    """The jaw table validated with its class defaults, every refusal of a key's own range
    (and, for a lab's own file, each key of :data:`JAW_FILE_KEYS` left out) added to ``p``;
    with the keys it refused (or left out) read as their defaults, so that the rules between
    the other keys still run: (the table, the keys not read from it)."""
    from tactcad.errors import DesignErrors

    unread: set[str] = set()
    if own_file:
        for key in missing_jaw_file_keys(table):
            p.add(f"grasper_jaw.{key}", None, "a value stated in the jaw file",
                  "a lab's jaw file states the jaw's size, pivot, opening and shaft")
            unread.update(key.split(" or "))
    try:
        j = validated_table("grasper_jaw", GrasperJawSection, table, file)
    except DesignErrors as exc:
        p.extend(exc.errors)
        bad = {e.field.split(".")[1].split("[")[0] for e in exc.errors
               if e.field.startswith("grasper_jaw.") and e.field.count(".") >= 1}
        unread.update(bad)
        try:  # the rest read without the refused keys (an unknown key refused alone)
            j = validated_table("grasper_jaw", GrasperJawSection,
                                {k: v for k, v in table.items() if k not in bad}, file)
        except DesignErrors:
            j = GrasperJawSection()
            unread.update(table)
    return with_class_defaults(j), unread | class_filled_unread(table, unread)


def class_filled_unread(table: Mapping[str, Any], unread: set[str]) -> set[str]:
    """The sizes a jaw table leaves to its class (:data:`CLASS_DEFAULTS_MM`) that are not read
    from it either: when its class is not known (``shaft_diameter_mm`` refused or left out
    and no class stated, or ``shaft_class_mm`` refused), the class the table falls back to would fill them, so no rule
    judges them (a refusal of a pin the file never states would follow from the other).

    Args:
        table: the jaw table as the file states it. unread: the keys refused or left out.

    Returns:
        The keys to read as not stated (empty when the class is known).
    """
    known = "shaft_class_mm" in table and "shaft_class_mm" not in unread  # stated: it wins
    if known or not {"shaft_diameter_mm", "shaft_class_mm"} & unread:
        return set()
    return {k for k in CLASS_DEFAULTS_MM[next(iter(CLASS_DEFAULTS_MM))] if k not in table}


def _widest_band_mm(outline) -> float:
    """The widest band centred on the jaw's axis that some stretch of ``outline`` holds (mm,
    to 1 µm)."""
    lo, hi = 0.0, 200.0
    while hi - lo > 1e-3:
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if outline_stretch_mm(outline, mid) else (lo, mid)
    return lo


def _longest_on_axis_mm(outline) -> float:
    """The longest stretch of ``outline`` along the jaw's axis (mm; a band 1 µm wide)."""
    stretch = outline_stretch_mm(outline, 1e-3)
    return 0.0 if stretch is None else stretch[1] - stretch[0]


def _stated_pocket(p: Problems, field: str, stated: float | None, most: float, why: str) -> float:
    """A pocket side of the room: the stated one within the most the jaw holds, else the most."""
    if most <= 0:
        p.add(field, stated, "a jaw with room for a pocket", f"{why} leaves {fmt(most)} mm")
        return 0.0
    return most if stated is None else p.within(field, stated, hi=most, why=why)


def no_shaft_words(bore_mm: float, thick_mm: float, least_width_mm: float, held_mm: float,
                   shaft_mm: float, jaw) -> str:
    """Why no jaw of the shaft holds the insert, each size named as the insert's need or
    as the jaw file's value (a need that equals another key's value read as that value).

    Args:
        bore_mm: the jaw file's shaft (mm). thick_mm: the jaw thickness the insert needs
            (mm). least_width_mm: the jaw width it needs (mm). held_mm: its pocket's width
            (mm). shaft_mm: the least shaft such closed jaws pass (mm). jaw: the jaw file's
            :class:`GrasperJawSection` (its thickness, opposing jaw and width).

    Returns:
        The words, e.g. ``no jaw of the 7 mm shaft holds it: it needs closed jaws 5.5 mm
        thick (thickness_mm; this jaw's 2.1 mm) + 2.1 mm (opposing_jaw_mm) ...``.
    """
    return (f"no jaw of the {bore_mm:g} mm shaft holds it: it needs closed jaws {thick_mm:g} mm "
            f"thick (thickness_mm; this jaw's {jaw.thickness_mm:g} mm) + "
            f"{jaw.opposing_jaw_mm:g} mm (opposing_jaw_mm, this jaw's) and at least "
            f"{least_width_mm:g} mm wide (width_mm; this jaw's {jaw_width_mm(jaw):g} mm) for "
            f"the {held_mm:.4g} mm pocket and its {MIN_WALL_MM:g} mm side walls; such jaws need "
            f"a shaft of at least {shaft_mm:g} mm (shaft_diameter_mm; this jaw's {bore_mm:g} "
            "mm)")


def closed_thickness_limit_mm(trocar_mm: float, width_mm: float) -> float:
    """The thickest closed pair of jaws (mm) of width ``width_mm`` whose
    rectangular section passes a round trocar of ``trocar_mm``: sqrt(D² - w²)."""
    return math.sqrt(max(trocar_mm ** 2 - width_mm ** 2, 0.0))


def insert_envelope_mm(plan) -> tuple[float, float, float] | None:
    """The insert's envelope (across the rows, along the row, height; mm) read
    from the plan without a kernel: a monolithic comb's; None for another
    construction (the stacked array's envelope is the assembly layer's)."""
    comb = getattr(plan, "comb", None)
    return None if comb is None else tuple(float(v) for v in comb.envelope_mm)


def tip_field_offset_mm(plan) -> tuple[float, float]:
    """(along the row, across the rows) of the insert's tip field centre off its envelope's
    centre (mm; 0, 0 without a comb): the window lies over the tips, the pocket round the
    envelope."""
    comb = getattr(plan, "comb", None)
    if comb is None:
        return 0.0, 0.0
    (z0, z1), (x0, x1) = plan.tip_field_box_mm
    cx, cz = comb.envelope_centre_mm
    return (z0 + z1) / 2 - cz, (x0 + x1) / 2 - cx


def _clamped(value: float, bound: float) -> float:
    return max(min(value, bound), -bound)


def _pocket_side(p: Problems, field: str, stated: float | None, need: float | None,
                 why: str) -> float:
    """A pocket size: the envelope's need when left out, else the stated size
    checked against it."""
    if stated is None:
        if need is None:
            p.add(field, None, "a size in mm", "the insert's envelope is not known without a "
                  "kernel for this construction: state the pocket")
            return 1.0
        return need
    return stated if need is None else p.within(field, stated, need, why=why)


def defaults_class(j: GrasperJawSection) -> str:
    """The class whose sizes fill what the table leaves out: the stated class, else (a
    stated shaft diameter) the largest class it holds, else the smallest."""
    if j.shaft_diameter_mm is None or "shaft_class_mm" in j.model_fields_set:
        return j.shaft_class_mm
    held = [k for k, d in SHAFT_CLASSES_MM.items() if d <= j.shaft_diameter_mm + 1e-9]
    return max(held, key=SHAFT_CLASSES_MM.get) if held else min(SHAFT_CLASSES_MM,
                                                                key=SHAFT_CLASSES_MM.get)


def with_class_defaults(j: GrasperJawSection) -> GrasperJawSection:
    """The table with every size it leaves out that depends on the class filled in
    (:data:`CLASS_DEFAULTS_MM`)."""
    own = dict(CLASS_DEFAULTS_MM[defaults_class(j)])
    if j.width_mm is not None:  # the width stated: no clearance to fill in
        own.pop("width_clearance_mm")
    return j.model_copy(update={k: v for k, v in own.items() if getattr(j, k) is None})


def derive(j: GrasperJawSection, context, p: Problems) -> PartData:
    """The jaw for the array's insert (``context.plan``).

    Args:
        j: the validated ``[grasper_jaw]`` table.
        context: has ``plan`` (the array's plan).
        p: refusals are added here (field, value, allowed range, reason).

    Returns:
        The jaw's :class:`PartData` with its derived sizes and their reasons.
    """
    plan = context.plan
    blame = closed_rule_blame(j.model_fields_set, getattr(context, "set_keys", ()))
    j = with_class_defaults(j)
    c = j.pocket_clearance_mm
    env = insert_envelope_mm(plan)
    _check_stated_once(p, j)
    width, bore, shaft = jaw_width_mm(j), bore_mm(j), shaft_words(j)
    why_env = (f"the insert's envelope {' x '.join(fmt(v) for v in env)} mm (across x along x "
               f"height) + {fmt(c)} mm each side" if env else "")
    pl = _pocket_side(p, "grasper_jaw.pocket_length_mm", j.pocket_length_mm,
                      env and env[1] + 2 * c, why_env)
    pw = _pocket_side(p, "grasper_jaw.pocket_width_mm", j.pocket_width_mm,
                      env and env[0] + 2 * c, why_env)
    if width < pw + 2 * MIN_WALL_MM - 1e-9:
        p.add("grasper_jaw.width_mm", width, f">= {fmt(pw + 2 * MIN_WALL_MM)} mm",
              f"the jaw holds the {fmt(pw)} mm pocket with {fmt(MIN_WALL_MM)} mm side walls")
    tip_h = plan.slots[0].geometry.tip_height_mm
    if j.pocket_depth_mm is not None:  # the lab's pocket: the face wall what it leaves
        j = _with_stated_depth(p, j, tip_h)
    depth = j.thickness_mm - j.face_wall_mm
    # face wall + proud height < the tip's height: the arms stay clear below the face wall;
    # the field to change is the proud height when no face wall would do
    if j.pocket_depth_mm is not None:
        pass  # the stated depth is judged by these rules (_with_stated_depth)
    elif tip_h - j.tip_proud_mm <= FACE_WALL_MIN_MM:
        p.within("grasper_jaw.tip_proud_mm", j.tip_proud_mm, hi=tip_h - j.face_wall_mm,
                 hi_open=True, why=f"tip_proud_mm + the {fmt(j.face_wall_mm)} mm face wall < "
                 f"the element's tip height {fmt(tip_h)} mm, so the arms stay clear below the "
                 "face wall")
    else:
        p.within("grasper_jaw.face_wall_mm", j.face_wall_mm, hi=tip_h - j.tip_proud_mm,
                 hi_open=True, why=f"face wall + tip_proud_mm ({fmt(j.tip_proud_mm)} mm) < the "
                 f"element's tip height {fmt(tip_h)} mm, so the arms stay clear below the face wall")
    if env:
        p.within("grasper_jaw.thickness_mm", j.thickness_mm, env[2] - j.tip_proud_mm,
                 why=f"the insert ({fmt(env[2])} mm high) stands {fmt(j.tip_proud_mm)} mm proud "
                     "and stays inside the jaw's back")
    closed = math.hypot(width, j.thickness_mm + j.opposing_jaw_mm)
    _check_closed(p, j, blame)
    x1 = j.length_mm - j.distal_wall_mm
    x0 = x1 - pl
    least = pocket_start_limit_mm(j)
    outline = tuple(tuple(q) for q in j.pocket_outline_mm) if j.pocket_outline_mm else None
    if outline and _check_outline(p, outline, least, x1, width / 2 - MIN_WALL_MM):
        x0 = _pocket_in_outline(p, outline, pw, pl, x0)
    p.within("grasper_jaw.length_mm", j.length_mm, least + pl + j.distal_wall_mm,
             why=f"pin, {fmt(MIN_WALL_MM)} mm of steel, the {fmt(pl)} mm pocket and the distal wall")
    _check_pivot(p, j)
    field_along, field_across = plan.tip_field_mm
    wl = min(field_along + 2 * j.window_clearance_mm, pl)
    ww = min(field_across + 2 * j.window_clearance_mm, pw)
    off = tip_field_offset_mm(plan)
    # the window stays inside the pocket's outline (its walls carry the face wall)
    off = (_clamped(off[0], (pl - wl) / 2), _clamped(off[1], (pw - ww) / 2))
    g = GrasperJawGeometry(j.length_mm, width, j.thickness_mm, j.pin_inset_mm, j.pin_diameter_mm,
                           x0, pl, pw, depth, wl, ww, j.tip_proud_mm, j.opening_angle_deg, off,
                           outline)
    derived = (
        Derived("grasper_jaw_width", width, "mm",
                "stated" if j.width_mm is not None else
                f"shaft {shaft} mm less {fmt(j.width_clearance_mm)} mm clearance"),
        Derived("grasper_jaw_closed_diagonal", closed, "mm",
                f"both jaws closed, {fmt(width)} x {fmt(j.thickness_mm + j.opposing_jaw_mm)} mm, "
                f"inside the {shaft} mm shaft"),
        Derived("grasper_jaw_pocket_length", pl, "mm", why_env or "stated"),
        Derived("grasper_jaw_pocket_width", pw, "mm", why_env or "stated"),
        Derived("grasper_jaw_pocket_depth", depth, "mm",
                f"stated (pocket_depth_mm), leaving a {fmt(round(j.face_wall_mm, 4))} mm face "
                "wall" if j.pocket_depth_mm is not None else
                f"thickness {fmt(j.thickness_mm)} less the face wall {fmt(j.face_wall_mm)} mm"),
        Derived("grasper_jaw_window_length", wl, "mm",
                f"tip field {fmt(field_along)} mm + {fmt(j.window_clearance_mm)} mm each end"),
        Derived("grasper_jaw_window_width", ww, "mm",
                f"tip field {fmt(field_across)} mm + {fmt(j.window_clearance_mm)} mm each side"),
        Derived("grasper_jaw_window_offset", off[0], "mm",
                f"along the jaw from the pocket's centre: the tip field's centre off the insert's "
                f"envelope's ({fmt(round(off[1], 6))} mm across)"))
    return PartData(
        name="grasper_jaw", kind="fabricated",
        process=Process("bought-in grasper jaw, machined for the insert: pocket and tip window by "
                        "wire EDM and milling" + (", pin hole reamed" if pin_in_bar(g) else ""),
                        Method.BAR),
        material=j.material, color=COLOR,
        expected_volume_mm3=jaw_volume_mm3(g), expected_bbox_mm=(0.0, -width / 2, 0.0,
                                                                j.length_mm, width / 2,
                                                                j.thickness_mm),
        geometry=g, derived=derived, attributes={"opening_angle_deg": j.opening_angle_deg},
        frames={"pivot": Seat((j.pin_inset_mm, 0, j.thickness_mm / 2), (0, 1, 0), (1, 0, 0)),
                "face": Seat((g.pocket_centre_x_mm, 0, j.thickness_mm), (0, 0, 1), (1, 0, 0)),
                "pocket": Seat((g.pocket_centre_x_mm, 0, depth), (0, 0, -1), (1, 0, 0)),
                # where the insert's contact faces lie: tip_proud_mm above the face, centred
                # on the pocket; its x across the jaw takes the array's x (across the rows)
                "insert": Seat((g.pocket_centre_x_mm, 0, j.thickness_mm + j.tip_proud_mm),
                               (0, 0, -1), (0, 1, 0))})


def _with_stated_depth(p: Problems, j: GrasperJawSection, tip_h: float) -> GrasperJawSection:
    """The table with the face wall a stated pocket depth leaves (``thickness_mm`` less
    ``pocket_depth_mm``, the pocket cut from the back), the depth refused where that wall is
    thinner than :data:`FACE_WALL_MIN_MM` or leaves the arms no room below it (wall + proud
    height < the element's tip height ``tip_h``, mm), or where a face wall is stated too."""
    _check_depth(p, j)
    if "face_wall_mm" in j.model_fields_set:
        p.add("grasper_jaw.face_wall_mm", j.face_wall_mm, "left out with pocket_depth_mm",
              "the face wall is what the stated pocket depth leaves of the jaw's thickness")
    least = j.thickness_mm - (tip_h - j.tip_proud_mm)
    most = j.thickness_mm - FACE_WALL_MIN_MM
    if not least < j.pocket_depth_mm <= most + 1e-9:
        p.add("grasper_jaw.pocket_depth_mm", j.pocket_depth_mm,
              f"{fmt(round(max(least, 0.0), 4))} < value <= {fmt(round(most, 4))} mm"
              if least < most else "none: the tips are too short for this jaw",
              f"a comb's pocket from the back leaves a face wall of at least "
              f"{fmt(FACE_WALL_MIN_MM)} mm, and wall + tip_proud_mm ({fmt(j.tip_proud_mm)} mm) < "
              f"the element's tip height {fmt(tip_h)} mm, so the arms stay clear below it")
    wall = min(max(j.thickness_mm - j.pocket_depth_mm, FACE_WALL_MIN_MM), 3.0)
    return j.model_copy(update={"face_wall_mm": wall})


def jaw_volume_mm3(g: GrasperJawGeometry) -> float:
    """The jaw's volume (mm^3): bar less pin hole, pocket and window (each cut
    lies inside the bar and they do not overlap)."""

    bar = g.length_mm * g.width_mm * g.thickness_mm
    pin = math.pi * (g.pin_diameter_mm / 2) ** 2 * g.width_mm if pin_in_bar(g) else 0.0
    pocket = g.pocket_length_mm * g.pocket_width_mm * g.pocket_depth_mm
    window = g.window_length_mm * g.window_width_mm * (g.thickness_mm - g.pocket_depth_mm)
    return bar - pin - pocket - window


def build(g: GrasperJawGeometry):
    """The jaw bar with its pin hole, back pocket and face window (build123d ``Solid``)."""
    w = g.width_mm / 2
    bar = box(0, -w, 0, g.length_mm, w, g.thickness_mm)
    x0, pw = g.pocket_x0_mm, g.pocket_width_mm / 2
    pocket = box(x0, -pw, 0, x0 + g.pocket_length_mm, pw, g.pocket_depth_mm)
    (cx, cy), wl, ww = g.window_centre_mm, g.window_length_mm / 2, g.window_width_mm / 2
    window = box(cx - wl, cy - ww, g.pocket_depth_mm, cx + wl, cy + ww, g.thickness_mm)
    if not pin_in_bar(g):  # the pivot behind the heel: the grasper's clevis holds the jaw
        return cut(bar, pocket, window)
    pin = cylinder(g.pin_diameter_mm / 2, (g.pin_x_mm, -w, g.thickness_mm / 2), (0, 1, 0),
                   g.width_mm)
    return cut(bar, pin, pocket, window)


def notes_after(g: GrasperJawGeometry, pen) -> list[str]:
    """The drawing's notes after the process note: the pocket's depth and the face wall, the
    insert's fit and the pivot (its pin hole, or the clevis behind the heel)."""
    wall = g.thickness_mm - g.pocket_depth_mm
    pivot = (f"Pin hole Ø{pen.fmt_mm(g.pin_diameter_mm)} H7 across the jaw, its axis "
             f"{pen.fmt_mm(g.pin_x_mm)} mm from the heel at mid-height "
             f"({pen.fmt_mm(g.thickness_mm / 2)} mm), reamed for the grasper's pivot pin."
             if pin_in_bar(g) else
             f"The pivot lies {pen.fmt_mm(-g.pin_x_mm)} mm behind the heel in the grasper's "
             "clevis: no pin hole in the jaw.")
    return [f"Pocket {pen.fmt_mm(g.pocket_length_mm)} x {pen.fmt_mm(g.pocket_width_mm)} mm, "
            f"{pen.fmt_mm(g.pocket_depth_mm)} mm deep from the back, leaving a "
            f"{pen.fmt_mm(wall)} mm face wall; the window "
            f"{pen.fmt_mm(g.window_length_mm)} x {pen.fmt_mm(g.window_width_mm)} mm through it.",
            f"The insert goes into the pocket from the back; its contact faces stand "
            f"{pen.fmt_mm(g.tip_proud_mm)} mm proud of the jaw face through the window.",
            pivot]


def dimensions(d, solid, pen) -> None:
    """The general set one tier out, and in the view of the jaw's face: the pocket (from the
    heel, along and across) and the window (from the heel, along and across), each on its own
    tier. Seen from another side (a jaw thinner than it is wide is seen on its face), the
    pocket and window are in the notes only."""
    g, f = d.spec.geometry, d.front
    u0, v0, u1, v1 = f.bbox
    face_view = (abs(u0) < 1e-6 and abs(u1 - g.length_mm) < 1e-6
                 and abs((v1 - v0) - g.width_mm) < 1e-6)
    pen.generic_dims(d, solid, top_k=2 if face_view else 0, right_k=2 if face_view else 0)
    if not face_view:
        return
    x0, x1 = g.pocket_x0_mm, g.pocket_x0_mm + g.pocket_length_mm
    (cx, cy), wl, ww = g.window_centre_mm, g.window_length_mm / 2, g.window_width_mm / 2
    pw = g.pocket_width_mm / 2
    pen.dim(d, f, (0.0, v1), (x0, v1), "h", "top", 0, pen.fmt_mm(x0), "pocket_from_heel")
    pen.dim(d, f, (x0, pw), (x1, pw), "h", "top", 0, pen.fmt_mm(g.pocket_length_mm),
            "pocket_length")
    pen.dim(d, f, (0.0, v1), (cx - wl, cy + ww), "h", "top", 1, pen.fmt_mm(cx - wl),
            "window_from_heel")
    pen.dim(d, f, (cx - wl, cy + ww), (cx + wl, cy + ww), "h", "top", 1,
            pen.fmt_mm(g.window_length_mm), "window_length")
    pen.dim(d, f, (x1, -pw), (x1, pw), "v", "right", 0, pen.fmt_mm(g.pocket_width_mm),
            "pocket_width")
    pen.dim(d, f, (cx + wl, cy - ww), (cx + wl, cy + ww), "v", "right", 1,
            pen.fmt_mm(g.window_width_mm), "window_width")



def part_from_table(key: str, section: type[Section], derive, table: Mapping[str, Any] | None,
                    file: str = "", **context: Any) -> PartData:
    """A part module's data from its table ``[key]`` alone (defaults where left
    out), outside a rigs file: validated as the rigs file validates it, so a
    refusal names ``key.field``; ``context`` holds what the derivation reads
    (``plan=...``, ``jaw=...``).

    Raises:
        DesignErrors: every refusal, each naming the field, value and allowed range.
    """
    p = Problems(file)
    out = derive(validated_table(key, section, table, file), SimpleNamespace(**context), p)
    p.raise_if_any()
    return out


@functools.lru_cache(maxsize=64)
def _file_model(key: str, section: type[Section]) -> type[Section]:
    """A file model holding ``[key]`` of ``section`` (built once: pydantic's model
    construction costs milliseconds, and a design atlas asks it for every point)."""
    return create_model(f"{section.__name__}File", __base__=Section, **{key: (section, section())})


def validated_table(key: str, section: type[Section], table: Mapping[str, Any] | None,
                    file: str = "") -> Any:
    """The table ``[key]`` validated as a design or rigs file validates it (defaults where
    left out), so a refusal names ``key.field``.

    Raises:
        DesignErrors: every refusal, each naming the field, value and allowed range.
    """
    p = Problems(file)
    t = validate(_file_model(key, section), {key: dict(table or {})}, p)
    p.raise_if_any()
    return getattr(t, key)


def design_table(plan, key: str) -> dict[str, Any]:
    """The design's table ``[key]`` of a part in use (``grasper_jaw``, ``grasper_shaft``,
    ``tissue_slab``; empty where the design leaves it out). The shaft takes the jaw's
    trocar class or stated shaft diameter unless its table states one (the load checks they
    agree)."""
    raw = getattr(plan, "raw", None) or {}
    table = dict(raw.get(key) or {})
    jaw = raw.get("grasper_jaw") or {}
    stated = {k: k for k in ("shaft_class_mm",)} | {"outer_diameter_mm": "shaft_diameter_mm"}
    if key == "grasper_shaft" and not any(k in table for k in stated):
        table.update({k: jaw[j] for k, j in stated.items() if j in jaw})
    return table


def jaw_part(plan, table: Mapping[str, Any] | None = None, file: str = "",
             set_keys: Any = ()) -> PartData:
    """The jaw for ``plan`` from a ``[grasper_jaw]`` table, by default the design's own
    (:func:`design_table`; defaults where left out).

    Args:
        plan: the design's plan (its insert).
        table: the ``[grasper_jaw]`` table (mm, degrees); None: the design's.
        file: the design file's name, for the messages.
        set_keys: the keys given over the file (``--set``, dotted): a rule between keys
            names the one set (:func:`closed_rule_blame`).

    Returns:
        The jaw's :class:`PartData`.

    Raises:
        DesignErrors: every refusal, each naming the field, value and allowed range.
    """
    if table is None:
        table = design_table(plan, "grasper_jaw")
    return part_from_table("grasper_jaw", GrasperJawSection, derive, table, file, plan=plan,
                           set_keys=tuple(set_keys))


IN_USE_PART = RigPart(key="grasper_jaw", section=GrasperJawSection, host="", derive=derive, build=build,
              drawing=DrawingRecord(hole_table=False, notes_after=notes_after,
                                    dimensions=dimensions))
