"""Review of the FreeCAD review files (``review/<scene>.FCStd``): open each
with ``freecadcmd`` as a reviewer would and compare what it shows with the
manifest: the tree (root, one container per group, instance labels), the
part each instance links to, the solid count, and the global bounding box,
which must equal the Z-up box of the scene's STEP record. The colours are
read from the file's ``GuiDocument.xml`` (FreeCAD keeps them in the view
providers): one per part, the same as in STEP and GLB.
"""

from __future__ import annotations

import json
import re
import zipfile
from pathlib import Path

from tactcad.export.freecad_review import run_freecad_script
from tactcad.checks.check_result import CheckResult

SCRIPT = Path(__file__).with_name("freecad_fcstd_script.py")
BBOX_TOL_MM = 1e-4
_VP_RE = re.compile(r'<ViewProvider name="part_([^"]+)".*?name="ShapeColor".*?value="(\d+)"', re.S)


def read_review_files(paths: list[str | Path]) -> dict:
    """What FreeCAD shows of each file: {path: {label, roots, tree, group_bbox_mm,
    bbox_mm, solids, linked, part_labels} or {error}} (see the script).

    Raises:
        RuntimeError: no ``freecadcmd`` or FreeCAD failed.
    """
    return run_freecad_script(SCRIPT, [str(Path(p).resolve()) for p in paths])


def part_colours(path: str | Path) -> dict[str, tuple[float, float, float]]:
    """Part name -> RGB (0 ... 1) of the part features' view providers in an FCStd file."""
    with zipfile.ZipFile(path) as z:
        xml = z.read("GuiDocument.xml").decode()
    out = {}
    for name, value in _VP_RE.findall(xml):
        v = int(value)  # FreeCAD packs RGBA as 0xRRGGBBAA
        out[name] = ((v >> 24 & 255) / 255, (v >> 16 & 255) / 255, (v >> 8 & 255) / 255)
    return out


def compare_review(found: dict, record: dict, step_record: dict, colours: dict,
                   expected_colours: dict) -> list[CheckResult]:
    """Rows comparing FreeCAD's reading of one review file with the manifest."""
    name = record["path"]
    if "error" in found:
        return [CheckResult("fcstd_open", name, False, found["error"].strip().splitlines()[-1])]
    out = [CheckResult("fcstd_tree", name, found["tree"] == record["groups"]
                       and found["roots"] == sorted([record["part"], "parts"]),
                       f"root {record['part']}, groups {', '.join(found['tree'])}")]
    out.append(CheckResult("fcstd_solids", name, found["solids"] == step_record["solids"],
                           f"{found['solids']} solids (STEP {step_record['solids']})"))
    dev = max(abs(a - b) for a, b in zip(found["bbox_mm"], step_record["bbox_mm"]))
    out.append(CheckResult("fcstd_z_up_bbox", name, dev <= BBOX_TOL_MM,
                           f"box {[round(v, 3) for v in found['bbox_mm']]}, Z-up STEP record "
                           f"deviation {dev:.1e} mm"))
    linked = set(found["linked"].values())
    out.append(CheckResult("fcstd_parts", name, linked == set(step_record["labels"]),
                           f"{len(linked)} parts linked"))
    off = [p for p, c in expected_colours.items()
           if p not in colours or max(abs(a - b) for a, b in zip(colours[p], c)) > 1 / 255]
    out.append(CheckResult("fcstd_colours", name, not off,
                           "every part its colour" if not off else f"wrong colour: {', '.join(off)}"))
    return out


def check_review_files(out_dir: str | Path) -> tuple[list[CheckResult], dict]:
    """Every review file of ``out_dir/manifest.json`` opened in FreeCAD and
    compared with its record and its scene's STEP record (see module doc).

    Raises:
        RuntimeError: no ``freecadcmd`` or FreeCAD failed.
    """
    out_dir = Path(out_dir)
    man = json.loads((out_dir / "manifest.json").read_text())
    by_path = {f["path"]: f for f in man["files"]}
    records = [f for f in man["files"] if f.get("kind") == "freecad-review"]
    found = read_review_files([out_dir / r["path"] for r in records])
    rows = []
    for r in records:
        path = out_dir / r["path"]
        step = by_path[r["step"]]
        rows += compare_review(found["files"].get(str(path.resolve()), {"error": "not read"}), r,
                               step, part_colours(path), r["colours"])
    return rows, found
