"""The insert in use, kernel-free: the array seated in a laparoscopic grasper's jaw, the jaw
turned about its pin above a tissue slab on the opposing jaw (the ``grasper`` rig of a
project's scenes, :mod:`tactcad.assembly.rig_models`).

Parts: the jaw (:mod:`tactcad.partlib.grasper_jaw`, its pocket sized on the insert's
envelope), the shaft (:mod:`tactcad.partlib.grasper_shaft`) and the slab
(:mod:`tactcad.partlib.tissue_slab`), each from the design's table of it (its defaults
where left out; :func:`tactcad.partlib.grasper_jaw.design_table`). The array's
``jaw_seat`` frame (the centre of its envelope on the tip plane, given by its construction)
is mated, flipped, onto the jaw's ``insert`` frame: the insert centred in the pocket, its
contact faces ``tip_proud_mm`` above the jaw's face, the first column nearest the pin.

Scene frame (mm, y up): x along the closed jaw from its pin to its tip, z across it. The
slab lies on the opposing jaw (y = 0 ... slab thickness) from in front of the pin and of
where the jaw's heel swings below the slab's top as the jaw opens (:func:`slab_start_mm`);
the pin sits where the closed jaw's contact faces rest on the slab's top face. The scene's
``jaw_angle_deg`` turns the jaw about the pin (0: closed on the slab, every tip on its top
face; left out: the jaw's opening angle). The shaft runs back from behind the jaw's heel, clear of the jaw's sweep.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tactcad.catalogue.rig_catalogue import library_spec
from tactcad.design.array_plan import Plan
from tactcad.design.scene_specs import SceneSpec
from tactcad.geometry.frames import Frame

#: Gap between the shaft's distal end and the circle the jaw's heel sweeps about the pin, mm.
SHAFT_CLEARANCE_MM = 0.5


def jaw_root(jaw, angle_deg: float, pin_world: tuple[float, float, float]) -> Frame:
    """The jaw's part frame in the scene, turned ``angle_deg`` about its pin (degrees; the
    distal end up), face down, its pin hole's axis at ``pin_world`` (mm)."""
    a = math.radians(angle_deg)
    x_dir = (math.cos(a), math.sin(a), 0.0)
    z_dir = (math.sin(a), -math.cos(a), 0.0)  # the grasping face looks down at the slab
    y_dir = (0.0, 0.0, 1.0)
    pin = (jaw.pin_x_mm, 0.0, jaw.thickness_mm / 2)
    origin = tuple(pin_world[i] - (pin[0] * x_dir[i] + pin[1] * y_dir[i] + pin[2] * z_dir[i])
                   for i in range(3))
    return Frame(origin, x_dir, z_dir)


def pin_height_mm(jaw, slab_thickness_mm: float) -> float:
    """The pin's height above the opposing jaw (mm): the closed jaw's contact faces
    (``tip_proud_mm`` above its face) rest on the slab's top."""
    return slab_thickness_mm + jaw.thickness_mm + jaw.tip_proud_mm - jaw.thickness_mm / 2


def heel_reach_mm(jaw, angle_deg: float) -> float:
    """How far in front of the pin (x, mm) the jaw dips below the closed contact plane when
    turned ``angle_deg`` open: the heel behind the pin swings down as the jaw opens. Its
    face edge, a distance d along the jaw from the pin, lies
    ``tip_proud + t/2 (1 - cos a) + d sin a`` above the slab's top; the last point below it,
    d0, lies at x = d0 cos a + t/2 sin a (-inf: no part of the jaw dips)."""
    a = math.radians(angle_deg)
    if math.sin(a) <= 0:
        return -math.inf
    t = jaw.thickness_mm
    d0 = -(jaw.tip_proud_mm + t / 2 * (1 - math.cos(a))) / math.sin(a)
    if d0 <= -jaw.pin_x_mm:  # the heel stays above the slab's top
        return -math.inf
    return d0 * math.cos(a) + t / 2 * math.sin(a)


def slab_start_mm(jaw, angle_deg: float, steps: int = 90) -> float:
    """The slab's near end (x, mm): :data:`SHAFT_CLEARANCE_MM` in front of the pin, or of
    the farthest the jaw's heel reaches below the slab's top on its way open to
    ``angle_deg`` (sampled every ``angle_deg / steps``), whichever is farther."""
    reach = max(heel_reach_mm(jaw, angle_deg * i / steps) for i in range(1, steps + 1))
    return max(reach, 0.0) + SHAFT_CLEARANCE_MM


def shaft_offset_mm(jaw) -> float:
    """How far behind the pin the shaft's distal end lies (mm): beyond the jaw's heel's
    sweep about the pin, plus :data:`SHAFT_CLEARANCE_MM`."""
    heel = math.hypot(jaw.pin_x_mm, jaw.thickness_mm / 2)
    return heel + SHAFT_CLEARANCE_MM


@dataclass(frozen=True)
class GrasperLayout:
    """The grasper rig's own parts and where they lie (the array is mated by the rig model).

    Attributes:
        specs: the jaw's, slab's and shaft's part specs by part name.
        roots: part name -> its part frame in the scene.
        angle_deg: the jaw's angle about its pin (degrees).
    """

    specs: dict
    roots: dict
    angle_deg: float


def grasper_layout(plan: Plan, scene: SceneSpec | None = None) -> GrasperLayout:
    """The jaw, slab and shaft for ``plan`` and their places (see the module doc).

    Args:
        plan: the design; its construction must give the insert's envelope (the comb).
        scene: the scene (its ``jaw_angle_deg``); None: the jaw at its opening angle.

    Raises:
        DesignErrors: the jaw cannot take the insert (each refusal names the jaw's field).
    """
    from tactcad.partlib.grasper_jaw import design_table, jaw_part
    from tactcad.partlib.grasper_shaft import shaft_part
    from tactcad.partlib.tissue_slab import slab_part

    jaw = library_spec(jaw_part(plan), "grasper_jaw")
    slab = library_spec(slab_part(jaw.geometry, design_table(plan, "tissue_slab")), "tissue_slab")
    shaft = library_spec(shaft_part(design_table(plan, "grasper_shaft")), "grasper_shaft")
    g, h = jaw.geometry, slab.geometry.thickness_mm
    angle = g.opening_angle_deg if scene is None or scene.jaw_angle_deg is None \
        else scene.jaw_angle_deg
    pin = (0.0, pin_height_mm(g, h), 0.0)
    # the slab in front of where the jaw's heel swings down as it opens (the widest angle
    # any scene turns it to), so every scene of the design puts the slab in one place
    slab_centre = slab_start_mm(g, max(g.opening_angle_deg, angle)) \
        + slab.geometry.length_mm / 2
    roots = {jaw.name: jaw_root(g, angle, pin),
             slab.name: Frame((slab_centre, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
             shaft.name: Frame((-shaft_offset_mm(g), pin[1], 0.0), (-1.0, 0.0, 0.0),
                               (0.0, 1.0, 0.0))}
    return GrasperLayout({s.name: s for s in (jaw, slab, shaft)}, roots, float(angle))
