"""The grasper a design states (``[grasper_jaw]``, ``[tissue_slab]``), seen from the
insert: the jaw's pin, length and opening and the slab's thickness in the insert's frame,
the values the grasp experiment and the equal-radius check take instead of their defaults.

The insert sits in the jaw as the grasper scene seats it (:mod:`tactcad.assembly.grasper_rig`):
its envelope centred in the pocket, the array's z (along the rows) along the jaw's x, the
first column nearest the pin. Insert frame (:func:`tactcad.in_use.radius_pairs.insert_frame`):
origin the first element's tip centre, u along the first row, v across. Units: mm, degrees.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class StatedGrasper:
    """The design's grasper in the insert's frame (mm, degrees).

    Attributes:
        pivot_u_mm, pivot_v_mm: the jaw's pin (along the rows, across them).
        pin_to_tip_mm: from the pin to the jaw's tip (its end; the jaw's own
            ``length_mm`` less the pin's ``pin_x_mm``).
        opening_angle_deg: the jaw's full opening.
        slab_thickness_mm: the tissue slab's thickness.
        tissue_base: how the opposing jaw holds the tissue (``[tissue_slab] base``).
    """

    pivot_u_mm: float
    pivot_v_mm: float
    pin_to_tip_mm: float
    opening_angle_deg: float
    slab_thickness_mm: float
    tissue_base: str = "bonded"

    def words(self) -> str:
        """The jaw and tissue in words, for a record that uses them."""
        return (f"the design's [grasper_jaw]: pin {-self.pivot_u_mm:.4g} mm behind the first "
                f"tip along the rows, pin to tip {self.pin_to_tip_mm:.4g} mm, "
                f"{self.opening_angle_deg:g} degrees open; a {self.slab_thickness_mm:g} mm slab "
                f"on a {self.tissue_base} base ([tissue_slab])")


def stated_grasper(plan: Any) -> StatedGrasper | None:
    """The grasper of a design that states ``[grasper_jaw]`` and whose construction gives
    its envelope without a kernel (the monolithic comb); None otherwise.

    Raises:
        DesignErrors: the jaw cannot take the insert (each refusal names the jaw's field).
    """
    raw = getattr(plan, "raw", None) or {}
    comb = getattr(plan, "comb", None)
    if "grasper_jaw" not in raw or comb is None:
        return None
    from tactcad.partlib.grasper_jaw import design_table, jaw_part
    from tactcad.partlib.tissue_slab import slab_part

    jaw = jaw_part(plan).geometry
    slab = slab_part(jaw, design_table(plan, "tissue_slab")).geometry
    cx, cz = comb.envelope_centre_mm
    # the pin in the array's frame: on the jaw's axis (the envelope's centre across), its
    # distance from the pocket's centre along the jaw's x, which is the array's z
    pivot_u, pivot_v = plan.in_insert_frame(cx, cz + jaw.pin_x_mm - jaw.pocket_centre_x_mm)
    return StatedGrasper(pivot_u_mm=pivot_u, pivot_v_mm=pivot_v,
                         pin_to_tip_mm=jaw.length_mm - jaw.pin_x_mm,
                         opening_angle_deg=jaw.opening_angle_deg,
                         slab_thickness_mm=slab.thickness_mm, tissue_base=slab.base)


def stated_shaft_bore_mm(plan: Any) -> float | None:
    """The bore of the shaft the design states (``[grasper_shaft]``, or its defaults for a
    stated ``[grasper_jaw]``), in mm: the channel its leads run through; None where the
    design states no grasper.

    Raises:
        DesignErrors: the stated table refused (each refusal names its field).
    """
    from tactcad.partlib.grasper_jaw import design_table
    from tactcad.partlib.grasper_shaft import shaft_part

    raw = getattr(plan, "raw", None) or {}
    if "grasper_jaw" not in raw and "grasper_shaft" not in raw:
        return None
    return shaft_part(design_table(plan, "grasper_shaft")).geometry.bore_diameter_mm
