"""STEP round trip: re-import the file and compare with what was exported."""

from __future__ import annotations

from pathlib import Path

from tactcad.checks.check_result import CheckResult
from tactcad.kernel.step_writer import read_step_summary

VOLUME_RTOL = 1e-6
BBOX_TOL_MM = 1e-5


def check_step(path: str | Path, name: str, solids: int, volume_mm3: float,
               bbox_mm: tuple[float, ...], labels: set[str]) -> list[CheckResult]:
    """Re-import ``path`` and compare solid count, volume, bbox and part labels."""
    try:
        s = read_step_summary(path)
    except Exception as exc:  # an unreadable file is a failed check, not a crash
        return [CheckResult("step_reimport", name, False, f"{type(exc).__name__}: {exc}")]
    if s["solids"] == 0:  # import_step reads an unparsable file as an empty shape
        return [CheckResult("step_reimport", name, False, "no solid could be read")]
    rel = abs(s["volume_mm3"] - volume_mm3) / volume_mm3
    dev = max(abs(a - b) for a, b in zip(s["bbox_mm"], bbox_mm))
    return [
        CheckResult("step_solid_count", name, s["solids"] == solids, f"{s['solids']} (expected {solids})"),
        CheckResult("step_volume", name, rel <= VOLUME_RTOL, f"rel {rel:.1e}"),
        CheckResult("step_bbox", name, dev <= BBOX_TOL_MM, f"max deviation {dev:.1e} mm"),
        CheckResult("step_labels", name, set(s["labels"]) == labels,
                    f"{len(s['labels'])} labels" + ("" if set(s["labels"]) == labels else
                                                    f", expected {sorted(labels)}")),
    ]
