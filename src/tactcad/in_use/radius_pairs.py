"""Sensing units in a pivoting jaw: each unit's two radii, the rule that lays every pair at
one radius, and the correction of R where a pair cannot be.

A unit (a row's reference and one of its measuring elements,
:func:`tactcad.mechanics.readout_chain.row_units`) reads R = e_m / e_r; in a jaw that turns
about a pin the two tips' travels differ with their radii and R carries their ratio
(:mod:`tactcad.in_use.jaw_kinematics`). Two tips side by side across the jaw's width are at
one radius, so the placement rule pairs each unit across the width and lays the units
along the jaw: on the plan's own tip sites, column by column, the tip of row 2i takes a
unit's reference and the tip of row 2i + 1 its measuring element. A single-row array has no
such pairs; its units keep their radii and R is corrected by r_r / r_m (travel in
proportion to the radius). Its counterpart, the units laid along the rows (a reference and
its measuring element side by side along the jaw, one pitch apart in radius), is what the
rule is measured against. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from tactcad.in_use.jaw_kinematics import JawGeometry, along_jaw_mm, tip_radius_mm

if TYPE_CHECKING:  # annotations only: the design model costs a second to import
    from tactcad.design.array_plan import Plan

#: The largest |r_m / r_r − 1| of a unit at "equal radius" (issue 43: within 2 %).
EQUAL_RADIUS_TOLERANCE_REL = 0.02


def insert_frame(plan: Plan) -> dict[int, tuple[float, float]]:
    """Every tip centre in the insert's frame (mm): element number -> (u, v).

    Origin the first element's tip centre; u along the first row (its first tip to its last;
    a one-column array: the array's z); v across, u turned a quarter in the face plane
    (:attr:`tactcad.design.array_plan.Plan.insert_axes`). Works from the plan's slots
    whatever the construction.
    """
    out = {}
    for slot in plan.slots:
        x, _, z = slot.tip_centre_world_mm
        out[slot.number] = plan.in_insert_frame(x, z)
    return out


@dataclass(frozen=True)
class UnitRadii:
    """One unit's two tips in the jaw.

    Attributes:
        reference, measuring: element numbers (or site labels of a paired layout).
        r_reference_mm, r_measuring_mm: their radii from the pin (mm).
    """

    reference: int
    measuring: int
    r_reference_mm: float
    r_measuring_mm: float

    @property
    def ratio(self) -> float:
        """r_m / r_r."""
        return self.r_measuring_mm / self.r_reference_mm

    @property
    def equal(self) -> bool:
        """True when the two radii agree within :data:`EQUAL_RADIUS_TOLERANCE_REL`."""
        return abs(self.ratio - 1.0) <= EQUAL_RADIUS_TOLERANCE_REL + 1e-12

    @property
    def r_correction(self) -> float:
        """The factor on the read R for travel in proportion to the radius: r_r / r_m."""
        return self.r_reference_mm / self.r_measuring_mm

    def as_json(self) -> dict:
        return {"reference": self.reference, "measuring": self.measuring,
                "r_reference_mm": self.r_reference_mm, "r_measuring_mm": self.r_measuring_mm,
                "radius_ratio": self.ratio, "equal_radius": self.equal,
                "R_correction_factor": self.r_correction}


def unit_radii(jaw: JawGeometry, positions: dict[int, tuple[float, float]],
               units: list[tuple[int, int]]) -> list[UnitRadii]:
    """Each unit's two radii (mm) from its tips' insert-frame positions.

    Args:
        jaw: the jaw.
        positions: element number -> (u, v) in the insert frame (mm), e.g. :func:`insert_frame`.
        units: (reference, measuring) element numbers.

    Raises:
        DesignError: a tip behind the pin or beyond the jaw's end.
    """
    used = sorted({n for unit in units for n in unit})
    # the farthest tip first: a jaw too short is refused for the length every tip needs
    for n in sorted(used, key=lambda n: -along_jaw_mm(jaw, *positions[n]))[:1] + used:
        tip_radius_mm(jaw, *positions[n])

    def r(n: int) -> float:
        return tip_radius_mm(jaw, *positions[n])

    return [UnitRadii(ref, meas, r(ref), r(meas)) for ref, meas in units]


@dataclass(frozen=True)
class PairSite:
    """A unit laid by the placement rule: the design's unit and the two tip sites it takes.

    Attributes:
        unit: the design's (reference, measuring) element numbers.
        reference_site, measuring_site: the plan's slots (element numbers) whose tip
            positions the unit's reference and measuring tips take.
        reference_uv_mm, measuring_uv_mm: those positions in the insert frame (mm).
    """

    unit: tuple[int, int]
    reference_site: int
    measuring_site: int
    reference_uv_mm: tuple[float, float]
    measuring_uv_mm: tuple[float, float]

    def as_json(self) -> dict:
        return {"unit": f"{self.unit[0]}/{self.unit[1]}", "reference_site": self.reference_site,
                "measuring_site": self.measuring_site,
                "reference_uv_mm": list(self.reference_uv_mm),
                "measuring_uv_mm": list(self.measuring_uv_mm)}


@dataclass(frozen=True)
class PairedLayout:
    """The placement rule's answer.

    Attributes:
        sites: the units laid across the width, in order along the jaw.
        unplaced: the design's units the array has no pair site for.
        reason: why some or all units could not be paired ("" when every unit is).
    """

    sites: tuple[PairSite, ...]
    unplaced: tuple[tuple[int, int], ...]
    reason: str

    def as_json(self) -> dict:
        return {"sites": [s.as_json() for s in self.sites],
                "unplaced": [f"{r}/{m}" for r, m in self.unplaced], "reason": self.reason}


def side_by_side(plan: Plan, across: str) -> list[tuple[int, int]]:
    """The plan's tip sites two by two (element numbers): ``across = "row"``, rows (0, 1),
    (2, 3), ... of each column, column by column; ``"column"``, columns (0, 1), (2, 3), ...
    of each row, row by row."""
    held = "column" if across == "row" else "row"
    count, span = (plan.columns, plan.rows) if across == "row" else (plan.rows, plan.columns)
    out = []
    for line in range(count):
        by = {getattr(s, across): s.number for s in plan.slots if getattr(s, held) == line}
        out += [(by[i], by[i + 1]) for i in range(0, span - 1, 2) if i in by and i + 1 in by]
    return out


def pair_sites(plan: Plan) -> list[tuple[int, int]]:
    """The plan's across-the-width site pairs (element numbers), in order along the rows:
    column by column, rows (0, 1), (2, 3), ...; none for a single row."""
    return side_by_side(plan, "row")


def row_sites(plan: Plan) -> list[tuple[int, int]]:
    """The plan's along-the-row site pairs (element numbers): row by row, columns (0, 1),
    (2, 3), ...; none for a single column. Two such tips lie one pitch apart in radius."""
    return side_by_side(plan, "column")


def laid_on(plan: Plan, units: list[tuple[int, int]], sites: list[tuple[int, int]],
            no_sites: str) -> PairedLayout:
    """The design's ``units`` laid in order on the site pairs ``sites``; units beyond them
    are listed as unplaced, ``no_sites`` the reason when there are none."""
    frame = insert_frame(plan)
    laid = tuple(PairSite(u, a, b, frame[a], frame[b]) for u, (a, b) in zip(units, sites))
    unplaced = tuple(units[len(sites):])
    if not sites:
        reason = no_sites
    elif unplaced:
        reason = f"{len(sites)} pair sites for {len(units)} units"
    else:
        reason = ""
    return PairedLayout(laid, unplaced, reason)


def along_row_layout(plan: Plan, units: list[tuple[int, int]]) -> PairedLayout:
    """Lay the design's units along the rows, each pair's two tips side by side on one row
    (:func:`row_sites`), one pitch apart in radius: the layout the equal-radius rule is
    measured against.

    Args:
        plan: the design (its tip sites).
        units: the design's (reference, measuring) element numbers, laid in this order.

    Returns:
        :class:`PairedLayout`; units beyond the sites are listed as unplaced, with why.
    """
    layout = laid_on(plan, units, row_sites(plan), "a single column has no two tips along a row")
    if layout.unplaced and layout.sites:  # an odd column count leaves each row's last tip
        return PairedLayout(layout.sites, layout.unplaced,
                            f"{len(layout.sites)} pair sites for {len(units)} units: "
                            f"{plan.columns} columns give {plan.columns // 2} side by side "
                            f"per row" + ("; each row's last tip has no neighbour along it"
                                          if plan.columns % 2 else ""))
    return layout


def paired_layout(plan: Plan, units: list[tuple[int, int]]) -> PairedLayout:
    """Lay the design's units so that each pair's two tips are at one radius: across the
    jaw's width (rows 2i and 2i + 1 of one column), units along its length, on the plan's
    own tip sites. The jaw's axis must run along the rows for the pairs to be at one radius
    (check it with :func:`unit_radii`).

    Args:
        plan: the design (its tip sites).
        units: the design's (reference, measuring) element numbers, laid in this order.

    Returns:
        :class:`PairedLayout`; units beyond the sites are listed as unplaced, with why.
    """
    layout = laid_on(plan, units, pair_sites(plan),
                     "a single row has no two tips across the jaw: the units keep their radii "
                     "and R is corrected by r_r / r_m")
    if layout.unplaced and layout.sites:
        return PairedLayout(layout.sites, layout.unplaced,
                            f"{plan.columns} columns x {plan.rows // 2} row pairs give "
                            f"{len(layout.sites)} pair sites for {len(units)} units")
    return layout
