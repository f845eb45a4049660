"""The tip-height tolerance a drawing holds, chosen from the K_obj budget.

The K_obj budget (:func:`tactcad.in_use.kobj_budget.tip_height_record`) gives, with
``[requirements] kobj_accuracy_rel`` stated, the tip-height tolerance (+/- mm, the
contact face's height above the clamped edge) for which the uncorrected coplanarity
term still fits the accuracy: the coplanarity allowance. This module decides what the
drawing then prints:

* the stated ``[tolerances] tip_height_mm`` already holds the allowance: it stays;
* a machining process holds the allowance (it is no finer than
  :data:`MACHINING_FLOOR_MM`): the drawing prints the allowance, rounded down to the
  0.001 mm a drawing prints (:data:`DRAWN_STEP_MM`), so the printed figure never
  loosens it;
* no machining holds it: the drawing keeps its process tolerance and names the
  procedure that makes the tolerance unnecessary (every unit zeroed on a rigid flat,
  :data:`ZEROING_PROCEDURE`) with the mismatch that procedure leaves
  (the budget's ``mismatch_after_zeroing_mm``).

The procedure's residual fits the accuracy when it is no larger than the mismatch the
allowance permits, twice the allowance (a +/- t tolerance lets two tips differ by 2 t).

Without ``kobj_accuracy_rel`` there is no decision (None): the drawing prints the
stated tolerance as before.

Units: mm; the accuracy is relative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

from tactcad.design.array_plan import Plan

#: The finest tolerance (+/- mm) a machining process is taken to hold on the contact
#: face's height above the clamped edge: 2 um. Assumption: about half of ISO 286-1's IT4
#: band over 6-18 mm (4-5 um), the finest grade precision surface grinding holds with care
#: and wire EDM with several skim cuts in a temperature-held room reaches (machine makers
#: quote a contour accuracy of about +/-2 um); production grinding holds IT5-IT6.
MACHINING_FLOOR_MM = 0.002
#: The step a drawing prints a tolerance to (mm): three decimals
#: (:func:`tactcad.drawings.sheet.fmt_mm`).
DRAWN_STEP_MM = 0.001
#: Where :data:`MACHINING_FLOOR_MM` comes from, as the drawing's basis cites it.
MACHINING_FLOOR_SOURCE = ("precision grinding or wire EDM with skim cuts: about half the "
                          "ISO 286-1 IT4 band at 6-18 mm")
#: The procedure that makes a tip-height tolerance unnecessary, as drawings and the build
#: book name it.
ZEROING_PROCEDURE = ("tips zeroed on a rigid flat before use (tactcad calibrate --flat FILE, "
                     "a gauge block face pressed on every tip)")


@dataclass(frozen=True)
class TipHeightDrawing:
    """What the drawing holds the tip height to, and why.

    Attributes:
        stated_mm: ``[tolerances] tip_height_mm`` (+/- mm).
        allowance_mm: the budget's coplanarity allowance (+/- mm), None where the other
            terms leave the accuracy no room.
        drawn_mm: the tolerance the drawing prints (+/- mm).
        residual_mm: the tip mismatch left after zeroing on a rigid flat (mm).
        kobj_accuracy_rel: ``requirements.kobj_accuracy_rel``.
        floor_mm: the finest tolerance the process holds (+/- mm).
        feature: what the tolerance holds, as the note names it.
        process: what holds ``floor_mm``, as the note names it.
        zeroing: the procedure that makes the tolerance unnecessary, as the note and the
            build book name it.
    """

    stated_mm: float
    allowance_mm: float | None
    drawn_mm: float
    residual_mm: float
    kobj_accuracy_rel: float
    floor_mm: float = MACHINING_FLOOR_MM
    feature: str = "Tip height"
    process: str = "machining"
    zeroing: str = ZEROING_PROCEDURE

    @property
    def holds_allowance(self) -> bool:
        """True when the drawn tolerance alone keeps the coplanarity term within the accuracy."""
        return self.allowance_mm is not None and self.drawn_mm <= self.allowance_mm

    @property
    def procedure(self) -> str | None:
        """The procedure the drawing relies on (:data:`ZEROING_PROCEDURE`), or None."""
        return None if self.holds_allowance else self.zeroing

    @property
    def residual_fits(self) -> bool:
        """True when the zeroed mismatch is within the mismatch the allowance permits (2 t)."""
        return self.allowance_mm is not None and self.residual_mm <= 2 * self.allowance_mm

    @property
    def note(self) -> str | None:
        """The drawing's note naming the procedure (None when the tolerance holds)."""
        if self.holds_allowance:
            return None
        if self.allowance_mm is None:
            why = "the other terms of the K_obj budget leave no room for a tip mismatch"
        else:
            why = (f"+/-{self.allowance_mm:.3g} mm would be needed, finer than {self.process} "
                   f"holds (+/-{self.floor_mm:g} mm)")
        return (f"{self.feature} to +/-{self.stated_mm:g} mm (process tolerance): for K_obj "
                f"within {100 * self.kobj_accuracy_rel:g} % {why}; {self.zeroing}, which leaves "
                f"{1e3 * self.residual_mm:.2g} um of mismatch.")

    def as_json(self) -> dict:
        """The decision as verify's record and the JSON output carry it (mm)."""
        return {"stated_mm": self.stated_mm, "allowance_mm": self.allowance_mm,
                "drawn_mm": self.drawn_mm, "residual_mm": self.residual_mm,
                "kobj_accuracy_rel": self.kobj_accuracy_rel, "floor_mm": self.floor_mm,
                "holds_allowance": self.holds_allowance, "procedure": self.procedure}


def choose_tip_height_tolerance(stated_mm: float, tip_record: Mapping,
                                floor_mm: float = MACHINING_FLOOR_MM,
                                **words: str) -> TipHeightDrawing | None:
    """The tolerance the drawing holds the tip height to (see the module docstring).

    Args:
        stated_mm: ``[tolerances] tip_height_mm`` (+/- mm, >= 0).
        tip_record: the budget's tip-height record
            (:attr:`tactcad.in_use.kobj_budget.KobjBudget.tip_height`): its
            ``kobj_accuracy_rel``, ``tolerance_for_accuracy_mm`` and
            ``mismatch_after_zeroing_mm``.
        floor_mm: the finest tolerance machining holds (+/- mm, > 0).
        words: ``feature``, ``process`` and ``zeroing`` of :class:`TipHeightDrawing`, where
            they differ from a machined tip's (a die's posts).

    Returns:
        :class:`TipHeightDrawing`, or None when the record states no accuracy.

    Raises:
        ValueError: ``stated_mm`` < 0 or ``floor_mm`` <= 0, named with its value.
    """
    if not stated_mm >= 0:
        raise ValueError(f"tolerances.tip_height_mm = {stated_mm}: allowed >= 0 mm")
    if not floor_mm > 0:
        raise ValueError(f"floor_mm = {floor_mm}: allowed > 0 mm")
    accuracy = tip_record.get("kobj_accuracy_rel")
    if accuracy is None:
        return None
    allowance = tip_record.get("tolerance_for_accuracy_mm")
    drawn = stated_mm
    # an allowance finer than machining holds, or than a drawing prints, is not drawn
    if allowance is not None and max(floor_mm, DRAWN_STEP_MM) <= allowance < stated_mm:
        # a process holds it: the drawing tightens to it, on the step it prints
        drawn = round(math.floor(allowance / DRAWN_STEP_MM + 1e-9) * DRAWN_STEP_MM, 6)
    return TipHeightDrawing(float(stated_mm), None if allowance is None else float(allowance),
                            drawn, float(tip_record["mismatch_after_zeroing_mm"]),
                            float(accuracy), float(floor_mm), **words)


def tip_height_from_budget(plan: Plan, budget) -> TipHeightDrawing | None:
    """:func:`choose_tip_height_tolerance` on a budget's tip-height record with the plan's
    stated tolerance.

    Args:
        plan: the design (its ``[tolerances] tip_height_mm``).
        budget: its :class:`~tactcad.in_use.kobj_budget.KobjBudget`.

    Returns:
        :class:`TipHeightDrawing`, or None when the design states no ``kobj_accuracy_rel``.
    """
    from tactcad.design.tolerances import tolerances_of

    return choose_tip_height_tolerance(tolerances_of(plan.raw).tip_height_mm, budget.tip_height)
