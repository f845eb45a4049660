"""Every check of the array on the files of an export: per part solid and
STEP re-import, per element DXF (read back, EDM rules, web on the file),
pairwise interference of the assembly, and the array STEP against the
figures the manifest promises a reviewer."""

from __future__ import annotations

from pathlib import Path
from typing import Callable

from tactcad.assembly.inventory import assembly_review
from tactcad.assembly.plan_locations import location
from tactcad.catalogue.array_catalogue import array_contacts, array_instances, array_parts
from tactcad.checks.dxf_shop import check_shop_dxf_files
from tactcad.checks.interference import Placed, check_interference
from tactcad.checks.result import CheckResult
from tactcad.checks.solids import check_solid
from tactcad.checks.step import check_step
from tactcad.design.array_plan import Plan
from tactcad.catalogue.files import ARRAY_STEP, part_step_name
from tactcad.solids.cache import PartCache


def run_checks(plan: Plan, out_dir: str | Path, cache: PartCache | None = None,
               done: Callable[[str, list[CheckResult]], None] | None = None) -> list[CheckResult]:
    """Every check of the array on the files in ``out_dir`` (written by
    :func:`tactcad.export.run.export`), sharing ``cache``'s solids.

    ``done(group, results)`` is called as each group finishes: ``parts``
    (solids and part STEP files), ``dxf``, ``array interference``, ``array STEP``."""
    out_dir = Path(out_dir)
    cache = cache or PartCache(plan)
    specs = array_parts(plan)
    done = done or (lambda group, results: None)
    results: list[CheckResult] = []

    def group(name: str, found: list[CheckResult]) -> None:
        results.extend(found)
        done(name, found)

    parts = []
    for name, spec in specs.items():
        parts += check_solid(spec, cache.solid(spec))
        parts += check_step(out_dir / part_step_name(name), part_step_name(name), 1,
                            spec.expected_volume_mm3, spec.expected_bbox_mm, {name})
    group("parts", parts)
    group("dxf", check_shop_dxf_files(plan, out_dir))
    inst = array_instances(plan)
    placed = [Placed(i.name, cache.solid(specs[i.part]).moved(location(i.placement))) for i in inst]
    group("array interference", check_interference(placed, array_contacts(plan)))
    review = assembly_review(specs, inst)  # what the manifest promises a reviewer
    group("array STEP", check_step(out_dir / ARRAY_STEP, ARRAY_STEP, review["solids"],
                                   review["volume_mm3"], tuple(review["bbox_mm"]),
                                   set(review["labels"])))
    return results
