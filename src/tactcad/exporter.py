"""The main job: a plan -> STEP, wire-EDM DXF and a manifest, plus the checks.

Every file is first written (atomically) into a staging folder beside the
target; only when all of them exist are they moved into place one by one
with ``os.replace``, the manifest last. A failed or interrupted build leaves
the previous exports whole.
"""

from __future__ import annotations

import hashlib
import importlib
import json
import os
import shutil
import tempfile
import time
from dataclasses import dataclass, field
from importlib import metadata
from pathlib import Path
from typing import Callable

from . import __version__
from .catalogue import PartSpec, array_contacts, array_instances, array_parts
from .design import Plan

# Writers of the main job, in order: "module:function", each called as
# function(plan, staging_dir, log) -> list of file records (dicts with at least
# "path", "part" and "kind"; STEP records also carry "solids", "volume_mm3",
# "bbox_mm" and "labels" for review). Their modules import heavy libraries
# only when called.
WRITERS = (
    "tactcad.exporter:write_array_files",
    "tactcad.scene_export:write_scene_files",
    "tactcad.drawings:write_drawing_files",
    "tactcad.render:write_image_files",
    "tactcad.bom:write_bom_files",
)

STACK_PACKAGES = ("build123d", "cadquery", "cadquery-ocp", "ezdxf", "trimesh", "manifold3d",
                  "numpy", "scipy", "scikit-fem", "gmsh", "svglib", "reportlab", "pypdfium2",
                  "pillow")


@dataclass
class ExportResult:
    out_dir: Path
    files: list[dict] = field(default_factory=list)
    seconds: float = 0.0

    def summary_lines(self) -> list[str]:
        lines = [f"{f['path']:<34} {f['bytes']:>9,d} B  {f['part']}" for f in self.files]
        total = sum(f["bytes"] for f in self.files)
        lines.append(f"{len(self.files)} files, {total:,d} B in {self.out_dir} ({self.seconds:.1f} s)")
        return lines


def stack_versions() -> dict[str, str]:
    out = {}
    for pkg in STACK_PACKAGES:
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def write_array_files(plan: Plan, staging: Path, log: Callable[[str], None]) -> list[dict]:
    """Build the array's parts and write STEP and DXF into ``staging``.

    Returns the file records (relative path, part) in a fixed order.
    """
    from .build import PartCache, location
    from .export.step import StepInstance, StepPart, write_step

    specs = array_parts(plan)
    cache = PartCache(plan, specs)
    records: list[dict] = []
    step_parts = []
    for name, spec in specs.items():
        solid = cache.solid(name)
        step_parts.append(StepPart(name, solid, spec.color))
        rel = f"step/{name}.step"
        write_step(staging / rel, [step_parts[-1]])
        records.append({"path": rel, "part": name, "kind": "step-part", "solids": 1,
                        "volume_mm3": spec.expected_volume_mm3,
                        "bbox_mm": list(spec.expected_bbox_mm), "labels": [name]})
        log(f"  wrote {rel}")
    inst = array_instances(plan)
    from .export.z_up import z_up_location
    instances = [StepInstance(i.name, i.part, z_up_location() * location(i.placement)) for i in inst]
    write_step(staging / "step/array.step", step_parts, instances, "array")
    records.append({"path": "step/array.step", "part": "array", "kind": "step-assembly",
                    **assembly_review(specs, inst)})
    log("  wrote step/array.step")
    # --- shop DXF (tactcad.export.dxf_sheet) ---
    from .export.dxf_sheet import write_shop_dxf_files
    records += write_shop_dxf_files(plan, staging, log)
    return records


def assembly_review(specs: dict[str, PartSpec], instances) -> dict:
    """What a reviewer should find on re-import of an assembly STEP: solid
    count, total volume (mm^3), bounding box (mm, Z-up frame of the STEP) and part labels. The box is
    computed from the expected part boxes and placements, not from the CAD."""
    corners = []
    for i in instances:
        x0, y0, z0, x1, y1, z1 = specs[i.part].expected_bbox_mm
        corners += [i.placement.apply(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    lo = [min(c[k] for c in corners) for k in range(3)]
    hi = [max(c[k] for c in corners) for k in range(3)]
    from .export.z_up import z_up_bbox

    return {"solids": len(instances),
            "volume_mm3": sum(specs[i.part].expected_volume_mm3 for i in instances),
            "bbox_mm": z_up_bbox(lo + hi),  # the STEP file is Z up
            "labels": sorted({i.part for i in instances})}


def manifest(plan: Plan, out_dir: Path, records: list[dict]) -> dict:
    """The manifest: every file with its sha256, its part, the design hash, the stack."""
    specs = array_parts(plan)
    inst = array_instances(plan)
    counts: dict[str, int] = {}
    for i in inst:
        counts[i.part] = counts.get(i.part, 0) + 1
    files = []
    for r in records:
        p = out_dir / r["path"]
        files.append({**r, "sha256": _sha256(p), "bytes": p.stat().st_size})
    parts = {n: _part_record(s, counts.get(n, 0)) for n, s in specs.items()}
    return {
        "design": {"name": plan.name, "source": plan.source, "sha256": plan.design_hash},
        "tactcad_version": __version__,
        "cad_stack": stack_versions(),
        "units": "mm",
        "files": files,
        "parts": parts,
        "assemblies": {"array": {"file": "step/array.step", "instances": len(inst),
                               **assembly_review(specs, inst)}},
        "derived": [{"name": d.name, "value": d.value, "unit": d.unit, "reason": d.reason}
                    for d in plan.derived],
        "assumptions": [{"field": k, "reason": v} for k, v in plan.assumptions],
    }


def _part_record(spec: PartSpec, count: int) -> dict:
    return {"kind": spec.kind, "process": spec.process, "material": spec.material,
            "quantity": count, "volume_mm3": spec.expected_volume_mm3,
            "bbox_mm": list(spec.expected_bbox_mm)}


def export(plan: Plan, out_dir: str | Path, log: Callable[[str], None] = print) -> ExportResult:
    """Write all exports of ``plan`` into ``out_dir`` (see module doc).

    Raises:
        DesignError: never here (the plan is already valid); OS errors propagate
            and leave ``out_dir`` as it was.
    """
    t0 = time.perf_counter()
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=".staging-", dir=out_dir))
    try:
        records = []
        for entry in WRITERS:
            module, func = entry.split(":")
            records += getattr(importlib.import_module(module), func)(plan, staging, log)
        man = manifest(plan, staging, records)
        man_bytes = (json.dumps(man, indent=2, sort_keys=False) + "\n").encode()
        for r in records:
            target = out_dir / r["path"]
            target.parent.mkdir(parents=True, exist_ok=True)
            os.replace(staging / r["path"], target)
        from .export.atomic import write_bytes_atomic
        write_bytes_atomic(out_dir / "manifest.json", man_bytes)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    result = ExportResult(out_dir, files=man["files"] + [{
        "path": "manifest.json", "bytes": len(man_bytes), "part": "-"}])
    result.seconds = time.perf_counter() - t0
    return result


def run_checks(plan: Plan, out_dir: str | Path) -> list:
    """Every check of the array on the files in ``out_dir`` (written by :func:`export`)."""
    from .build import PartCache, location
    from .checks.interference import Placed, check_interference
    from .checks.solids import check_solid
    from .checks.step import check_step

    out_dir = Path(out_dir)
    specs = array_parts(plan)
    cache = PartCache(plan, specs)
    results = []
    for name, spec in specs.items():
        solid = cache.solid(name)
        results += check_solid(spec, solid)
        results += check_step(out_dir / f"step/{name}.step", f"step/{name}.step", 1,
                              spec.expected_volume_mm3, spec.expected_bbox_mm, {name})
    # --- shop DXF (tactcad.checks.dxf_shop) ---
    from .checks.dxf_shop import check_shop_dxf_files
    results += check_shop_dxf_files(plan, out_dir)
    inst = array_instances(plan)
    placed = [Placed(i.name, cache.solid(i.part).moved(location(i.placement))) for i in inst]
    results += check_interference(placed, array_contacts(plan))
    review = assembly_review(specs, inst)  # what the manifest promises a reviewer
    results += check_step(out_dir / "step/array.step", "step/array.step", review["solids"],
                          review["volume_mm3"], tuple(review["bbox_mm"]), set(review["labels"]))
    return results
