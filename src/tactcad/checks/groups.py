"""The groups of checks ``tactcad check`` runs, declared once.

Each :class:`CheckGroup` names what it checks and the function that runs it;
:meth:`tactcad.api.Project.check` runs the registered groups in order,
``check --help`` lists them, the JUnit report files their results under the
group's test suites and the review page shows one table per group. A new
group is one module with its function plus one :func:`register_check_group`.

Running needs the group's module only: it is imported by name when the group
runs, so a command that lists the groups loads no CAD kernel.
"""

from __future__ import annotations

import importlib
import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Iterable, Iterator, Mapping, Sequence

if TYPE_CHECKING:
    from tactcad.checks.check_result import CheckResult

#: What a group's function yields: a label (the group's name, or
#: ``scene <name>`` for one scene of a per-scene group) and its results.
Found = tuple[str, list["CheckResult"]]


@dataclass(frozen=True)
class CheckContext:
    """What a group's checks read.

    Attributes:
        plan: the design's :class:`~tactcad.design.array_plan.Plan`.
        folder: the export folder checked.
        cache: the run's :class:`~tactcad.solids.cache.PartCache` (solids shared
            between groups).
        project: the validated design (:class:`tactcad.design.project.Project`),
            which the scene groups need; None checks the array alone.
        scenes: the scenes asked for (``--scene``), or None for all.
        edited: the files of the export changed (``changed``) or removed (``missing``)
            by hand since it was written, by path (:func:`tactcad.export.reuse.export_state`;
            empty for an export the check wrote), or None when not looked at.
        stale: what the export checked as it is (files edited by hand in it) is older than:
            the project's files edited since it was written, by name
            (:func:`tactcad.export.reuse.changed_inputs`); empty when it is current.
        requirements_model: how the requirements are judged: ``auto`` (``verify``'s
            default, a FEM level solved only for a requirement the closed form leaves
            undecided) or a ladder level (``closed-form``: no solve, as ``design --jaw``).
    """

    plan: Any
    folder: Path
    cache: Any
    project: Any = None
    scenes: Sequence[str] | None = None
    edited: Mapping[str, str] | None = None
    stale: Sequence[str] = ()
    requirements_model: str = "auto"


@dataclass(frozen=True)
class CheckGroup:
    """One group of checks.

    Attributes:
        name: the group's name in reports (``parts``, ``array STEP`` ...).
        checks: what it checks, for ``--help`` and the review page.
        module, function: ``function(context) -> Iterable[Found]`` runs it on
            a :class:`CheckContext`.
        suite: how the JUnit report files a result: ``group`` (one suite named
            after the group), ``array`` (the array's suite), ``part`` (the
            suite of the part or nested sheet the result names) or ``scene``
            (one suite per scene).
        on_export: False for a group that reads the design alone (it runs
            before any export is written and also with ``--scene``).
        per_scene: True when it runs on the scenes (alone with ``--scene``).
        with_scenes: True for a group on the export that runs with ``--scene`` too (it
            reads the export as a whole, whichever scenes are checked).
    """

    name: str
    checks: str
    module: str
    function: str
    suite: str = "group"
    on_export: bool = True
    per_scene: bool = False
    with_scenes: bool = False

    def run(self, context: CheckContext) -> Iterator[Found]:
        """Run the group's checks, yielding each label's results as they finish."""
        yield from getattr(importlib.import_module(self.module), self.function)(context)

    def suite_of(self, label: str, result: "CheckResult", part_names: set[str]) -> str:
        """The JUnit test suite of one of the group's results (see :attr:`suite`)."""
        if result.subject in part_names:
            return f"part:{result.subject}"
        if self.suite == "scene":
            return "scene:" + label.removeprefix("scene ")
        if self.suite == "part":
            stem = Path(result.subject.split(":", 1)[0]).stem  # "sheet.dxf: copy at (x, y)"
            base = re.sub(r"_qty\d+$", "", stem)
            return f"part:{base}" if base in part_names else f"sheet:{stem}"
        return "array" if self.suite == "array" else self.name


SUITE_RULES = ("group", "array", "part", "scene")

#: The groups in run order.
CHECK_GROUPS: dict[str, CheckGroup] = {}


def register_check_group(group: CheckGroup) -> None:
    """Add a group to every ``tactcad check`` (run after the others).

    Raises:
        ValueError: the name is taken or the suite rule is unknown.
    """
    if group.name in CHECK_GROUPS:
        raise ValueError(f"a check group {group.name!r} is registered already")
    if group.suite not in SUITE_RULES:
        raise ValueError(f"check group {group.name!r}: suite {group.suite!r} is not one of "
                         + ", ".join(SUITE_RULES))
    CHECK_GROUPS[group.name] = group


def group_of(label: str) -> CheckGroup:
    """The group a result label belongs to (``scene <name>`` -> the scene group).

    Raises:
        KeyError: no registered group has that label.
    """
    if label in CHECK_GROUPS:
        return CHECK_GROUPS[label]
    for group in CHECK_GROUPS.values():
        if group.per_scene and label.startswith("scene "):
            return group
    raise KeyError(label)


def groups_to_run(scenes: Sequence[str] | None = None, project: bool = True,
                  on_export: bool = True) -> list[CheckGroup]:
    """The groups a check runs, in order: all; with ``scenes`` the design's own,
    those that run with scenes and the scenes'; without a ``project`` none of the scenes'; with
    ``on_export=False`` none of those that read an export's files."""
    return [g for g in CHECK_GROUPS.values()
            if (not scenes or g.per_scene or g.with_scenes or not g.on_export)
            and (project or not g.per_scene) and (on_export or not g.on_export)]


def groups_help() -> str:
    """``parts (...); dxf (...); ...`` for ``--help``."""
    return "; ".join(f"{g.name} ({g.checks})" for g in CHECK_GROUPS.values())


def run_groups(groups: Iterable[CheckGroup], context: CheckContext,
               done: Callable[[str, list["CheckResult"]], None]) -> None:
    """Run ``groups`` in order on ``context``, calling ``done(label, results)`` as each finishes."""
    for group in groups:
        for label, found in group.run(context):
            done(label, list(found))


_CHECKS = "tactcad.checks.array_checks"
for _group in (
        CheckGroup("requirements", "the design's verification matrix with verify's verdicts "
                   "(a FEM level only for a requirement the closed form leaves undecided), "
                   "before any export", "tactcad.checks.requirement_checks", "requirement_group",
                   on_export=False),
        CheckGroup("hard stops", "each element's hard stop engages after its rated deflection "
                   "and before its yield-limited one", "tactcad.checks.stop_checks", "stop_group",
                   on_export=False),
        CheckGroup("rigs", "the test rigs against the design's rated full-scale force: no rig "
                   "loads an element beyond it, the force gauge's range and resolution fit it; and "
                   "the samples span the design's K_obj range",
                   "tactcad.checks.rig_checks", "rig_group", on_export=False),
        CheckGroup("process", "each part cut from sheet against its process's rules (sheet "
                   "range, smallest hole, web and ligament, inside radius, slot, the web's "
                   "tolerance), before any export", "tactcad.checks.process_rules",
                   "process_group", suite="part", on_export=False),
        CheckGroup("grasper", "the insert's envelope inside the grasper jaw's pocket and its "
                   "leads through the shaft's lead channel (kernel-free, before any export)",
                   "tactcad.checks.grasper_fit", "grasper_group", on_export=False),
        CheckGroup("export files", "every file the manifest lists as the export wrote it "
                   "(sha256): a file changed or removed by hand since fails and is left as it "
                   "is, never written over by the check; review files a failed FreeCAD left "
                   "out noted (info)", "tactcad.checks.export_files",
                   "export_files_group", with_scenes=True),
        CheckGroup("parts", "each part's solid: valid, volume, bounding box; its STEP "
                   "file read back", _CHECKS, "part_group", suite="part"),
        CheckGroup("dxf", "each shop DXF read back: closed contours, the process's cutting "
                   "rules, the web on the file, tabs and cut order, etch compensation, nesting",
                   _CHECKS, "dxf_group", suite="part"),
        CheckGroup("array interference", "no two parts of the array overlap beyond their "
                   "declared contacts", _CHECKS, "interference_group", suite="array"),
        CheckGroup("array STEP", "the array's STEP assembly read back against the manifest",
                   _CHECKS, "array_step_group", suite="array"),
        CheckGroup("drawings", "every drawing sheet: no text over a line or another text, "
                   "measured in paper mm", "tactcad.checks.sheet_overlap", "sheet_group"),
        CheckGroup("scenes", "per scene: rig part solids, interference, geometry sanity, STEP "
                   "and GLB read back", "tactcad.checks.scene_checks", "scene_group", suite="scene",
                   per_scene=True)):
    register_check_group(_group)
