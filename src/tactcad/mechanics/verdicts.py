"""A prediction's verdict against a requirement: pass, fail or undecided; a row
reported, not judged (a figure the lab states no requirement for), has the
verdict ``info`` (:func:`reported_not_judged`).

A prediction with relative error estimate e and margin m (positive: met) on a
requirement that needs margin t passes when m - t >= e, fails when
m - t < -e, and is undecided in between: the level that predicted it cannot
tell. So a requirement met at exactly its threshold with a nonzero error is
undecided, and one met there with no error (a geometric fact) passes.

A record of several items (the rows' pairs of K_r / K_m, the elements'
first resonances or thermal drifts, the footprint's axes) judges each item on
its own margin and error and takes the worst item's verdict
(:func:`deciding_item`): one item that fails beyond its error fails the
record, whatever the item with the smallest margin says.

Units: relative (dimensionless).
"""

from __future__ import annotations

import math
from typing import Sequence

#: A requirement's verdict at one level (:func:`verdict`).
VERDICTS = ("pass", "fail", "undecided")
#: The verdict of a row reported, not judged (:func:`reported_not_judged`): neither a pass
#: nor a failure, and never counted as either.
INFO = "info"
#: Verdicts from the worst: a multi-item record takes its worst item's.
VERDICT_RANK = {"fail": 0, "undecided": 1, "pass": 2}


def verdict(margin_rel: float | None, error_rel: float | None, threshold_rel: float,
            nominal_pass: bool) -> str:
    """``pass`` when the margin clears its threshold by at least the level's
    error estimate, ``fail`` when it misses it by more, else ``undecided``
    (the level cannot tell). Without a finite margin or error: the nominal
    verdict.

    Args:
        margin_rel: the record's margin (positive: met), or None (infinite).
        error_rel: the prediction's relative error estimate, or None.
        threshold_rel: the margin the requirement needs (0; -K band for K_r/K_m).
        nominal_pass: the verdict on the nominal prediction.

    Returns:
        One of :data:`VERDICTS`.
    """
    if margin_rel is None or error_rel is None or not math.isfinite(error_rel):
        return "pass" if nominal_pass else "fail"
    clearance = margin_rel - threshold_rel
    if clearance >= error_rel:
        return "pass"
    if clearance < -error_rel:
        return "fail"
    return "undecided"


def reported_not_judged(record: dict) -> dict:
    """``record`` as a row reported, not judged: a figure of the design's own that the lab
    states no requirement for (a K band the design file leaves out, a K_obj resolution
    derived from the very prediction it would be tested against), which no prediction can
    fail. One convention for every output that shows such a row: ``verdict`` :data:`INFO`,
    ``informational`` True, ``pass``, ``target`` and ``margin_rel`` None (no target, no
    margin), the value the row would have been held to kept as ``reference_value``.

    Args:
        record: a verification record (``target``, ``margin_rel``, ``pass``, ...).

    Returns:
        A new record (``record`` unchanged).
    """
    reference = record.get("reference_value", record.get("target"))
    return {**record, "informational": True, "verdict": INFO, "pass": None, "target": None,
            "margin_rel": None, "reference_value": reference}


def judged(item: dict, threshold_rel: float = 0.0) -> dict:
    """``item`` (a dict with ``margin_rel`` and ``error_estimate_rel``) with its own
    ``verdict`` (:func:`verdict`, nominally met at margin >= ``threshold_rel``)."""
    m, e = item["margin_rel"], item["error_estimate_rel"]
    return {**item, "verdict": verdict(m, e, threshold_rel, m is None or m >= threshold_rel)}


def deciding_item(items: Sequence[dict]) -> dict:
    """The item that decides a record of several (each with ``verdict`` and
    ``margin_rel``): the worst verdict; among equal verdicts the smallest margin
    (None, an infinite margin, last).

    Raises:
        ValueError: no items.
    """
    if not items:
        raise ValueError("a record needs at least one item")
    return min(items, key=lambda it: (VERDICT_RANK[it["verdict"]],
                                      math.inf if it["margin_rel"] is None else it["margin_rel"]))
