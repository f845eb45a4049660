"""A tissue slab for the grasper scene (a stand-in, not a made part): a
box of stated thickness lying on the opposing jaw, which the jaw closes on.
It covers the jaw's face unless the table sets its size; its thickness is
the grasp's slab (:class:`tactcad.in_use.jaw_kinematics.JawGeometry`,
``slab_thickness_mm``, > 0 ... 100 mm). The ``grasper`` rig
places it, like the jaw (:mod:`tactcad.partlib.grasper_jaw`). Part frame: slab centred in x and
y, z = 0 on its underside. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping, Optional

from tactcad.kernel.shapes import box
from tactcad.partlib.base import PartData, RigPart, Seat
from tactcad.partlib.grasper_jaw import part_from_table
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Derived, Problems, Section, Text, choice, fmt, number

COLOR = (0.86, 0.45, 0.45)


#: How the opposing jaw can hold the tissue layer: the contact model's bases
#: (tactcad.mechanics.contact.BASES, the same words; a part names them, the model solves them).
BASES = ("bonded", "frictionless", "steinbrenner")
#: The base the grasp assumes for the tissue unless ``[tissue_slab] base`` states one: tissue
#: gripped on a jaw face does not slide on it (tactcad.in_use.grasp_experiment's
#: DEFAULT_TISSUE_BASE, the same word).
DEFAULT_BASE = "bonded"


class TissueSlabSection(Section):
    """``[tissue_slab]``: the slab (mm); a size left out covers the jaw's face; ``base``: how
    the opposing jaw holds it (``bonded``: gripped, no slip; ``frictionless``: a smooth, wet
    face; ``steinbrenner``: the approximation that states neither)."""

    thickness_mm: number(0.0, 100.0, lo_open=True) = 3.0  # assumed, as `tactcad grasp`'s default
    length_mm: Optional[number(1.0, 200.0)] = None
    width_mm: Optional[number(1.0, 200.0)] = None
    material: Text = "tissue (stand-in)"
    base: choice(BASES, "how the opposing jaw holds the tissue layer") = DEFAULT_BASE


@dataclass(frozen=True)
class TissueSlabGeometry:
    """The slab (mm)."""

    length_mm: float
    width_mm: float
    thickness_mm: float
    base: str = DEFAULT_BASE


def derive(s: TissueSlabSection, context, p: Problems) -> PartData:
    """The slab under the jaw ``context.jaw`` (a
    :class:`~tactcad.partlib.grasper_jaw.GrasperJawGeometry`).

    Args:
        s: the validated ``[tissue_slab]`` table.
        context: has ``jaw``, the jaw's geometry.
        p: refusals are added here.

    Returns:
        The slab's :class:`PartData`.
    """
    jaw = context.jaw
    why = f"covers the jaw's {fmt(jaw.length_mm)} x {fmt(jaw.width_mm)} mm face"
    length = jaw.length_mm if s.length_mm is None else s.length_mm
    width = jaw.width_mm if s.width_mm is None else s.width_mm
    if s.width_mm is not None:
        p.within("tissue_slab.width_mm", s.width_mm, round(slab_least_width_mm(jaw), 4),
                 jaw.width_mm, why=f"the slab lies on the opposing jaw, as wide as the "
                 f"{fmt(jaw.width_mm)} mm jaw's face (grasper_jaw.width_mm), and covers its "
                 "window over the tips on the jaw's axis")
    g = TissueSlabGeometry(length, width, s.thickness_mm, s.base)
    return PartData(
        name="tissue_slab", kind="purchased", process=Process("tissue or phantom", Method.BOUGHT),
        material=s.material, color=COLOR, expected_volume_mm3=length * width * s.thickness_mm,
        expected_bbox_mm=(-length / 2, -width / 2, 0.0, length / 2, width / 2, s.thickness_mm),
        geometry=g, derived=(Derived("tissue_slab_length", length, "mm", why if s.length_mm is None
                                     else "stated"),
                             Derived("tissue_slab_width", width, "mm", why if s.width_mm is None
                                     else "stated")),
        frames={"bottom": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "top": Seat((0, 0, s.thickness_mm), (0, 0, 1), (1, 0, 0))})


def slab_least_width_mm(jaw) -> float:
    """The narrowest slab (mm) that covers the jaw's window over the tips: the slab lies
    centred on the jaw's axis, the window ``window_width_mm`` wide, its centre
    ``window_offset_mm[1]`` off the axis (a
    :class:`~tactcad.partlib.grasper_jaw.GrasperJawGeometry`, mm)."""
    return jaw.window_width_mm + 2 * abs(jaw.window_offset_mm[1])


def build(g: TissueSlabGeometry):
    """Box ``length x width x thickness`` (build123d ``Solid``)."""
    return box(-g.length_mm / 2, -g.width_mm / 2, 0, g.length_mm / 2, g.width_mm / 2,
               g.thickness_mm)


def slab_part(jaw, table: Mapping[str, Any] | None = None, file: str = "") -> PartData:
    """The slab under ``jaw`` from a ``[tissue_slab]`` table (defaults where left out).

    Raises:
        DesignErrors: every refusal, each naming the field, value and allowed range.
    """
    return part_from_table("tissue_slab", TissueSlabSection, derive, table, file, jaw=jaw)


def stated_grasper_errors(plan, file: str = "", set_keys: Any = ()) -> list:
    """The refusals of the grasper a design states for its own insert: its jaw
    (``[grasper_jaw]``) by the rules :func:`~tactcad.partlib.grasper_jaw.jaw_part`
    applies (the closed jaws inside the shaft, the pivot, the pocket round the insert, the
    jaw's length to hold it, ...) and its tissue slab against that jaw (``[tissue_slab]``:
    as wide as the jaw's face at most, covering the window over the tips,
    :func:`slab_part`; judged here, where the slab's module knows both parts). Run when the
    design is read, so that no command (``verify``, ``check``, ``export``, ``grasp``) takes
    a grasper the insert cannot fit. (The shaft, ``[grasper_shaft]``, is held to the jaw's
    bore by the design's own rules, :func:`tactcad.design.array_plan.check_in_use`.) A
    design that states neither table (the paper's macro array), or whose construction does
    not seat in a jaw (the stacked array: no jaw search in its construction's entry,
    :mod:`tactcad.design.construction_registry`, and no kernel-free envelope), has none;
    the slab is judged only against a jaw that takes the insert.

    Args:
        plan: the design's plan (``plan.raw`` its tables, ``--set`` values included).
        file: the design file's name, for the messages.
        set_keys: the keys given over the file (``--set KEY=VALUE``, dotted): a rule
            between keys names the one set.

    Returns:
        Every refusal (:class:`~tactcad.errors.DesignError`: ``grasper_jaw.<key>`` or
        ``tissue_slab.<key>``, its value in mm or degrees and the allowed range); empty when
        the jaw takes the insert and the slab lies on it.
    """
    from tactcad.errors import DesignErrors
    from tactcad.partlib.grasper_jaw import design_table, insert_envelope_mm, jaw_part

    raw = getattr(plan, "raw", None) or {}
    if not {"grasper_jaw", "tissue_slab"} & set(raw) or insert_envelope_mm(plan) is None:
        return []
    errors: list = []
    try:  # the design's jaw, or the default jaw of a design that states none
        jaw = jaw_part(plan, file=file, set_keys=set_keys).geometry
    except DesignErrors as exc:
        if "grasper_jaw" in raw:
            errors.extend(exc.errors)
        return errors  # a slab is judged against a jaw that takes the insert
    if "tissue_slab" in raw:
        try:
            slab_part(jaw, design_table(plan, "tissue_slab"), file)
        except DesignErrors as exc:
            errors.extend(exc.errors)
    return errors


IN_USE_PART = RigPart(key="tissue_slab", section=TissueSlabSection, host="", derive=derive, build=build)
