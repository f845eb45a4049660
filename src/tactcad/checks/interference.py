"""Pairwise interference of placed parts with OpenCascade booleans.

Every pair whose bounding boxes overlap is intersected; the common volume
must be <= 1e-6 mm^3. A boolean that fails or raises is a failure, never
"no overlap". Declared contacts are additionally checked to touch.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

from tactcad.checks.check_result import CheckResult
from tactcad.kernel.inspect import bounding_box, common_volume, distance
from tactcad.kernel.shapes import Shape

OVERLAP_TOL_MM3 = 1e-6
CONTACT_TOL_MM = 1e-6


@dataclass(frozen=True)
class Placed:
    name: str
    shape: Shape


def check_interference(placed: list[Placed], contacts: set[frozenset[str]]) -> list[CheckResult]:
    """Overlap volume of every pair with overlapping boxes, and touching of declared contacts."""
    out: list[CheckResult] = []
    boxes = {p.name: bounding_box(p.shape) for p in placed}
    tested = 0
    for a, b in itertools.combinations(placed, 2):
        pair = frozenset({a.name, b.name})
        subject = f"{a.name} / {b.name}"
        if not boxes[a.name].overlaps(boxes[b.name], CONTACT_TOL_MM):
            if pair in contacts:
                out.append(CheckResult("contact_touching", subject, False, "boxes apart"))
            continue
        tested += 1
        try:
            vol = common_volume(a.shape, b.shape)
        except Exception as exc:
            out.append(CheckResult("interference", subject, False, f"boolean failed: {exc}"))
            continue
        if vol > OVERLAP_TOL_MM3:
            out.append(CheckResult("interference", subject, False, f"overlap {vol:.6g} mm3"))
        if pair in contacts:
            gap = distance(a.shape, b.shape)
            out.append(CheckResult("contact_touching", subject, gap <= CONTACT_TOL_MM,
                                   f"gap {gap:.1e} mm"))
    out.append(CheckResult("interference", f"{len(placed)} parts", not any(
        r.check == "interference" and not r.passed for r in out),
        f"{tested} pairs intersected, overlap limit {OVERLAP_TOL_MM3:g} mm3"))
    return out
