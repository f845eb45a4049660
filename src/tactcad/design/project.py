"""The three design files validated together, before any geometry is built.

A design file (``macro_array.toml``) comes with a rigs file and a scenes file:
those beside it, else the defaults of ``hardware/``. :func:`load_project`
reads all three, checks each with its schema and the files against each other
(the rigs against the array's size, every scene's sample stiffness against the
rigs' samples) and reports every refusal at once, each as
``file: field = value: allowed ... (reason)``.

What it returns, a :class:`Project`, is what the rest of the run works from:
one immutable object carried from validation to the last writer. Nothing
below the command line opens a design, rigs or scenes file again, so a file
edited after validation cannot change what a run writes.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Iterator, Mapping

from tactcad.design.array import DEFAULT_DESIGN, Plan, plan_from_model, validate_design
from tactcad.design.rigs import DEFAULT_RIGS, RigDesign, rigs_path_for, validate_rigs
from tactcad.design.schema import Problems, content_hash, fmt, read_toml
from tactcad.design.scenes import DEFAULT_SCENES, SceneSpec, scenes_path_for, validate_scenes
from tactcad.errors import DesignError


class FrozenScenes(Mapping[str, SceneSpec]):
    """The validated scenes by name, in file order; read-only."""

    def __init__(self, scenes: Mapping[str, SceneSpec]):
        self._items = tuple(scenes.items())

    def __getitem__(self, name: str) -> SceneSpec:
        for key, spec in self._items:
            if key == name:
                return spec
        raise KeyError(name)

    def __iter__(self) -> Iterator[str]:
        return (key for key, _ in self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __hash__(self) -> int:
        return hash(self._items)

    def __repr__(self) -> str:
        return f"FrozenScenes({', '.join(self)})"


@dataclass(frozen=True)
class Project:
    """The three design files validated together, immutable: what a run works from.

    Attributes:
        plan: the array's :class:`~tactcad.design.array.Plan`.
        rigs: the rigs' :class:`~tactcad.design.rigs.RigDesign`, derived against ``plan``.
        scenes: the scenes by name (:class:`~tactcad.design.scenes.SceneSpec`), in file order.
        design_sha256, rigs_sha256, scenes_sha256: sha256 of each file's
            validated tables (canonical JSON; the design's after ``--set``), so
            a run can name exactly what it was made from.
        rigs_file, scenes_file: the paths the rigs and scenes were read from
            (the design's is ``plan.source``).
    """

    plan: Plan
    rigs: RigDesign
    scenes: Mapping[str, SceneSpec]
    design_sha256: str
    rigs_sha256: str
    scenes_sha256: str
    rigs_file: str = ""
    scenes_file: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.scenes, FrozenScenes):
            object.__setattr__(self, "scenes", FrozenScenes(self.scenes))

    @property
    def hashes(self) -> dict[str, str]:
        """{"design", "rigs", "scenes": sha256 of each file's validated tables}."""
        return {"design": self.design_sha256, "rigs": self.rigs_sha256,
                "scenes": self.scenes_sha256}


def project_of(plan: Plan, rigs: RigDesign, scenes: Mapping[str, SceneSpec],
               scenes_data: Mapping[str, Any] | None = None, scenes_file: str = "") -> Project:
    """A :class:`Project` of parts already validated (a plan, its rigs, scenes),
    e.g. a design made in code; ``scenes_data``: the scenes file's tables, for its hash."""
    scenes_hash = content_hash(scenes_data if scenes_data is not None
                               else {n: repr(s) for n, s in scenes.items()})
    return Project(plan, rigs, scenes, plan.design_hash, rigs.rigs_hash, scenes_hash,
                   rigs.source, scenes_file)


def _read(path: Path, what: str, problems: Problems) -> Mapping[str, Any] | None:
    try:
        return read_toml(path, what)
    except DesignError as exc:
        exc.file = path.name
        problems.extend([DesignError(exc.field, exc.value, exc.allowed, exc.why, path.name)])
        return None


def _check_sample_stiffness(scenes: Mapping[str, SceneSpec], rigs: RigDesign,
                            problems: Problems, scenes_file: str) -> None:
    known = rigs.sample_stiffness_N_per_mm
    for s in scenes.values():
        k = s.sample_stiffness_N_per_mm
        if k is not None and k not in known:
            problems.add(f"scene.{s.name}.sample_stiffness_N_per_mm", k,
                         "one of " + ", ".join(fmt(v) for v in known),
                         "the measured samples of the rigs file (sample.stiffness_N_per_mm)",
                         file=scenes_file)


def project_from_data(design: Mapping[str, Any] | None, rigs: Mapping[str, Any] | None,
                      scenes: Mapping[str, Any] | None, problems: Problems, *,
                      source: str = "<dict>", rigs_file: str = "rigs.toml",
                      scenes_file: str = "scenes.toml"):
    """Validate the three files' raw tables together (a table that could not be
    read is None; its error is already in ``problems``).

    Returns:
        (plan, rigs, scenes), any of them None when refused; every refusal is
        added to ``problems``.
    """
    plan = rig_design = None
    if design is not None:
        model, found = validate_design(design, Path(source).name)
        problems.extend(found.errors)
        if not found:
            plan = plan_from_model(model, design, source)
    if rigs is not None and plan is not None:
        rig_design, found = validate_rigs(rigs, plan, rigs_file)
        problems.extend(found.errors)
    specs: dict[str, SceneSpec] = {}
    if scenes is not None:
        specs, found = validate_scenes(scenes, scenes_file)
        problems.extend(found.errors)
    if rig_design is not None and specs:
        _check_sample_stiffness(specs, rig_design, problems, scenes_file)
    return plan, rig_design, specs


def load_project(design: str | Path | None = None) -> Project:
    """Read and validate a design file with its rigs and scenes files.

    Args:
        design: TOML design file; ``None`` means ``hardware/macro_array.toml``.

    Returns:
        The :class:`Project`: the array's plan, the rig plan derived against
        it, the scenes by name and the three files' hashes.

    Raises:
        DesignErrors: every refusal of the three files (``.errors``), each naming
            its file, field, value and allowed range; nothing is built.
    """
    path = Path(design) if design is not None else DEFAULT_DESIGN
    problems = Problems(path.name)
    return project_with_design_data(_read(path, "design file", problems), path, problems)


def project_with_design_data(data: Mapping[str, Any] | None, path: Path,
                             problems: Problems | None = None) -> Project:
    """:func:`load_project` for design tables already read (and perhaps
    changed, e.g. by ``--set``) from the design file at ``path``: the rigs
    and scenes files beside ``path`` (else the defaults) are read and every
    file is validated together.

    Raises:
        DesignErrors: as :func:`load_project`.
    """
    problems = problems if problems is not None else Problems(path.name)
    rigs_file, scenes_file = rigs_path_for(path), scenes_path_for(path)
    scenes_data = _read(scenes_file, "scenes file", problems)
    plan, rigs, scenes = project_from_data(
        data, _read(rigs_file, "rigs file", problems), scenes_data,
        problems, source=str(path), rigs_file=rigs_file.name, scenes_file=scenes_file.name)
    problems.raise_if_any()
    return project_of(plan, replace(rigs, source=str(rigs_file)), scenes, scenes_data,
                      str(scenes_file))



def project_for_plan(plan: Plan, rigs_file: str | Path | None = None,
                     scenes_file: str | Path | None = None) -> Project:
    """A :class:`Project` of a plan made in code (e.g. ``plan_from_dict``):
    the rigs and scenes files named (``None``: those of ``hardware/``) are read
    and validated against ``plan``.

    Raises:
        DesignErrors: every refusal of the rigs and scenes files.
    """
    rigs_path = Path(rigs_file) if rigs_file is not None else DEFAULT_RIGS
    scenes_path = Path(scenes_file) if scenes_file is not None else DEFAULT_SCENES
    problems = Problems(rigs_path.name)
    rigs_data = _read(rigs_path, "rigs file", problems)
    scenes_data = _read(scenes_path, "scenes file", problems)
    rigs = scenes = None
    if rigs_data is not None:
        rigs, found = validate_rigs(rigs_data, plan, rigs_path.name)
        problems.extend(found.errors)
    if scenes_data is not None:
        scenes, found = validate_scenes(scenes_data, scenes_path.name)
        problems.extend(found.errors)
    if rigs is not None and scenes:
        _check_sample_stiffness(scenes, rigs, problems, scenes_path.name)
    problems.raise_if_any()
    return project_of(plan, replace(rigs, source=str(rigs_path)), scenes, scenes_data,
                      str(scenes_path))
