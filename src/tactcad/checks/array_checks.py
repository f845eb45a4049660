"""The array's check groups (:mod:`tactcad.checks.groups`) on the files of an
export: per part solid and STEP re-import, per element DXF (read back, EDM
rules, web on the file), pairwise interference of the assembly, and the array
STEP against the figures the manifest promises a reviewer."""

from __future__ import annotations

from pathlib import Path
from typing import Callable, Iterator

from tactcad.assembly.inventory import assembly_review
from tactcad.assembly.plan_locations import location
from tactcad.kernel.locations import placed
from tactcad.catalogue.array_catalogue import array_contacts, array_instances, array_parts
from tactcad.checks.groups import CheckContext, Found, groups_to_run, run_groups
from tactcad.checks.check_result import CheckResult
from tactcad.checks.dxf_shop import check_shop_dxf_files
from tactcad.checks.interference import Placed, check_interference
from tactcad.checks.solids import check_solid
from tactcad.checks.step_readback import check_step
from tactcad.catalogue.files import ARRAY_STEP, part_step_name
from tactcad.solids.cache import PartCache


def run_checks(plan, out_dir: str | Path, cache: PartCache | None = None,
               done: Callable[[str, list[CheckResult]], None] | None = None) -> list[CheckResult]:
    """Every registered check group of the array's export files in ``out_dir``
    (not the scenes', not the design's own), sharing ``cache``'s solids;
    ``done(group, results)`` is called as each group finishes."""
    results: list[CheckResult] = []

    def group(name: str, found: list[CheckResult]) -> None:
        results.extend(found)
        if done is not None:
            done(name, found)

    context = CheckContext(plan, Path(out_dir), cache or PartCache(plan))
    run_groups([g for g in groups_to_run(project=False) if g.on_export], context, group)
    return results


def part_group(context: CheckContext) -> Iterator[Found]:
    """``parts``: each array part's solid and its STEP file read back."""
    plan, cache, out_dir = context.plan, context.cache, context.folder
    found = []
    for name, spec in array_parts(plan).items():
        found += check_solid(spec, cache.solid(spec))
        found += check_step(out_dir / part_step_name(name), part_step_name(name), 1,
                            spec.expected_volume_mm3, spec.expected_bbox_mm, {name})
    yield "parts", found


def dxf_group(context: CheckContext) -> Iterator[Found]:
    """``dxf``: the shop DXF files read back."""
    yield "dxf", check_shop_dxf_files(context.plan, context.folder)


def interference_group(context: CheckContext) -> Iterator[Found]:
    """``array interference``: the placed array parts, pairwise."""
    plan, cache = context.plan, context.cache
    specs = array_parts(plan)
    shapes = [Placed(i.name, placed(cache.solid(specs[i.part]), location(i.placement)))
              for i in array_instances(plan)]
    yield "array interference", check_interference(shapes, array_contacts(plan))


def array_step_group(context: CheckContext) -> Iterator[Found]:
    """``array STEP``: the array's STEP file against what the manifest promises a reviewer."""
    plan = context.plan
    review = assembly_review(array_parts(plan), array_instances(plan))
    yield "array STEP", check_step(context.folder / ARRAY_STEP, ARRAY_STEP, review["solids"],
                                   review["volume_mm3"], tuple(review["bbox_mm"]),
                                   set(review["labels"]))
