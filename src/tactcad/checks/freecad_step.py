"""Design review in FreeCAD: open exported STEP files with ``freecadcmd``
(FreeCAD's headless command line, Debian package ``freecad-python3``) and
compare what a reviewer sees (solid count, part labels, volume, bounding
box) with the manifest's records.

FreeCAD runs its own Python (the system ``python3``), so the review script
(:mod:`tactcad.checks.freecad_step_script`, which imports nothing from tactcad)
runs in a subprocess (:func:`tactcad.export.freecad_review.run_freecad_script`)
and writes its findings to a JSON file.
"""

from __future__ import annotations

import json
import time
from pathlib import Path

from tactcad.checks.check_result import CheckResult
from tactcad.export.freecad_review import freecadcmd, run_freecad_script

SCRIPT = Path(__file__).with_name("freecad_step_script.py")
VOLUME_RTOL = 1e-6
BBOX_TOL_MM = 1e-4


class FreeCADUnavailable(RuntimeError):
    """``freecadcmd`` is not installed."""


def run_freecad_review(paths: list[str | Path], timeout_s: float = 600.0) -> dict:
    """Import every STEP file in FreeCAD; returns the script's JSON plus
    ``wall_seconds`` (including FreeCAD's start).

    Raises:
        FreeCADUnavailable: no ``freecadcmd``.
        RuntimeError: FreeCAD crashed or wrote no result (its output is in the message).
    """
    if freecadcmd() is None:
        raise FreeCADUnavailable("freecadcmd not found (Debian package freecad-python3)")
    t0 = time.perf_counter()
    result = run_freecad_script(SCRIPT, [str(Path(p).resolve()) for p in paths], timeout_s)
    result["wall_seconds"] = time.perf_counter() - t0
    return result


def compare(found: dict, record: dict, name: str) -> list[CheckResult]:
    """Rows comparing FreeCAD's reading of one file with its manifest record."""
    if "error" in found:
        return [CheckResult("freecad_import", name, False, found["error"].strip().splitlines()[-1])]
    out = [CheckResult("freecad_solids", name, found["solids"] == record["solids"],
                       f"{found['solids']} (manifest {record['solids']})")]
    rel = abs(found["volume_mm3"] - record["volume_mm3"]) / record["volume_mm3"]
    out.append(CheckResult("freecad_volume", name, rel <= VOLUME_RTOL,
                           f"{found['volume_mm3']:.4f} mm3, rel {rel:.1e}"))
    dev = max(abs(a - b) for a, b in zip(found["bbox_mm"], record["bbox_mm"]))
    out.append(CheckResult("freecad_bbox", name, dev <= BBOX_TOL_MM, f"max deviation {dev:.1e} mm"))
    same = sorted(found["labels"]) == sorted(record["labels"])
    out.append(CheckResult("freecad_labels", name, same,
                           f"{len(found['labels'])} part labels" + ("" if same else
                           f": {found['labels']} vs {record['labels']}")))
    bare = found["shape_read"]
    rel2 = abs(bare["volume_mm3"] - record["volume_mm3"]) / record["volume_mm3"]
    out.append(CheckResult("freecad_shape_read", name,
                           bare["solids"] == record["solids"] and rel2 <= VOLUME_RTOL,
                           f"Part.read: {bare['solids']} solids, volume rel {rel2:.1e}"))
    return out


def review_exports(out_dir: str | Path) -> tuple[list[CheckResult], dict]:
    """FreeCAD review of every STEP file listed in ``out_dir/manifest.json``.

    Raises:
        FreeCADUnavailable: no ``freecadcmd``.
    """
    out_dir = Path(out_dir)
    man = json.loads((out_dir / "manifest.json").read_text())
    records = [f for f in man["files"] if f["path"].endswith(".step") and "solids" in f]
    found = run_freecad_review([out_dir / f["path"] for f in records])
    rows = []
    for f in records:
        key = str((out_dir / f["path"]).resolve())
        rows += compare(found["files"].get(key, {"error": "not reviewed"}), f, f["path"])
    return rows, found
