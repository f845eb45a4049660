"""``manifest.json``: every file of an export with its sha256, the design's
hash, the versions of tactcad and its CAD stack, the parts, the strength
of every element and the design's requirements."""

from __future__ import annotations

import hashlib
from functools import lru_cache
from pathlib import Path

from tactcad import __version__
from tactcad.assembly.inventory import assembly_review, instance_counts
from tactcad.catalogue.array_catalogue import PartSpec, array_instances, array_parts
from tactcad.catalogue.files import ARRAY_STEP
from tactcad.design.array_plan import Plan
from tactcad.assembly.inventory import array_envelope_mm
from tactcad.studies.verification import requirements_record
from tactcad.studies.reference_loads import strength_summary
from tactcad.store import stack_versions


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def manifest(plan: Plan, out_dir: Path, records: list[dict]) -> dict:
    """The manifest: every file with its sha256, its part, the design hash, the stack."""
    files = []
    for r in records:
        p = out_dir / r["path"]
        files.append({**r, "sha256": _sha256(p), "bytes": p.stat().st_size})
    facts = design_facts(plan)
    head = ("design", "tactcad_version", "cad_stack", "units")
    return {**{k: facts[k] for k in head}, "files": files,
            **{k: v for k, v in facts.items() if k not in head}}


@lru_cache(maxsize=4)
def design_facts(plan: Plan) -> dict:
    """The manifest without its files: computed once per plan (the requirements'
    verification matrix alone takes about 0.2 s, and a run, the review page
    and ``tactcad watch``'s preview all ask for it). Shared: read it, do not
    change it."""
    specs = array_parts(plan)
    inst = array_instances(plan)
    counts = instance_counts(inst)
    parts = {n: _part_record(s, counts.get(n, 0)) for n, s in specs.items()}
    return {
        # the file's name only: an export names files relative to the project
        # folder, never by a path of the machine it was made on
        "design": {"name": plan.name, "source": Path(plan.source).name,
                   "sha256": plan.design_hash},
        "tactcad_version": __version__,
        "cad_stack": stack_versions(),
        "units": "mm",
        "parts": parts,
        "assemblies": {"array": {"file": ARRAY_STEP, "instances": len(inst),
                               **assembly_review(specs, inst)}},
        "strength": [_strength_record(r) for r in strength_summary(plan)],
        "requirements": requirements_record(plan, array_envelope_mm(plan)),
        "thermal": _thermal_record(plan),
        "derived": [{"name": d.name, "value": d.value, "unit": d.unit, "reason": d.reason}
                    for d in plan.derived],
        "assumptions": [{"field": k, "reason": v} for k, v in plan.assumptions],
    }


def _thermal_record(plan: Plan) -> dict | None:
    """The closed-form thermal drift of every element (:mod:`tactcad.mechanics.thermal_drift`);
    None when the material's CTE is unknown. The run time is left out (the manifest is
    compared across runs)."""
    from tactcad.errors import DesignError
    from tactcad.mechanics.thermal_drift import thermal_report
    from tactcad.studies.verification import requirements_of

    try:
        out = thermal_report(plan, requirements_of(plan)).as_json()
    except DesignError:
        return None
    out.pop("seconds")
    return out


def _strength_record(r: dict) -> dict:
    """An element's arm, stiffness K, yield-limited force, and its safety
    factor, gauge strain and tip deflection at the design's rated full-scale
    force (``full_scale_force_N``, the same for every element) for the
    manifest (closed form)."""
    keys = ("element", "part_name", "arm_length_mm", "model", "stiffness_N_per_mm",
            "stress_MPa_per_N", "full_scale_force_N", "yield_limited_force_N",
            "yield_safety_factor_at_full_scale", "gauge_strain_at_full_scale",
            "tip_deflection_mm_at_full_scale", "warnings")
    return {k: r[k] for k in keys}


def _part_record(spec: PartSpec, count: int) -> dict:
    return {"kind": spec.kind, "process": spec.process, "material": spec.material,
            "quantity": count, "volume_mm3": spec.expected_volume_mm3,
            "bbox_mm": list(spec.expected_bbox_mm)}
