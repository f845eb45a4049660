"""The three design files validated together, before any geometry is built.

A design file (``macro_array.toml``) comes with a rigs file and a scenes file:
those beside it, else the defaults of ``hardware/``. :func:`load_project`
reads all three, checks each with its schema and the files against each other
(the rigs against the array's size, every scene's sample stiffness against the
rigs' samples) and reports every refusal at once, each as
``file: field = value: allowed ... (reason)``.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any, Mapping

from tactcad.design.array import DEFAULT_DESIGN, Plan, plan_from_model, validate_design
from tactcad.design.rigs import RigDesign, rigs_path_for, validate_rigs
from tactcad.design.schema import Problems, fmt, read_toml
from tactcad.design.scenes import SceneSpec, scenes_path_for, validate_scenes
from tactcad.errors import DesignError


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


def load_project(design: str | Path | None = None) -> tuple[Plan, RigDesign, dict[str, SceneSpec]]:
    """Read and validate a design file with its rigs and scenes files.

    Args:
        design: TOML design file; ``None`` means ``hardware/macro_array.toml``.

    Returns:
        (plan, rigs, scenes): the array's plan, the rig plan derived against it,
        the scenes by name.

    Raises:
        DesignErrors: every refusal of the three files (``.errors``), each naming
            its file, field, value and allowed range; nothing is built.
    """
    path = Path(design) if design is not None else DEFAULT_DESIGN
    problems = Problems(path.name)
    return project_with_design_data(_read(path, "design file", problems), path, problems)


def project_with_design_data(data: Mapping[str, Any] | None, path: Path,
                             problems: Problems | None = None
                             ) -> tuple[Plan, RigDesign, dict[str, SceneSpec]]:
    """:func:`load_project` for design tables already read (and perhaps
    changed, e.g. by ``--set``) from the design file at ``path``: the rigs
    and scenes files beside ``path`` (else the defaults) are read and every
    file is validated together.

    Raises:
        DesignErrors: as :func:`load_project`.
    """
    problems = problems if problems is not None else Problems(path.name)
    probe = _Located(str(path))
    rigs_file, scenes_file = rigs_path_for(probe), scenes_path_for(probe)
    plan, rigs, scenes = project_from_data(
        data, _read(rigs_file, "rigs file", problems), _read(scenes_file, "scenes file", problems),
        problems, source=str(path), rigs_file=rigs_file.name, scenes_file=scenes_file.name)
    problems.raise_if_any()
    return plan, replace(rigs, source=str(rigs_file)), scenes


class _Located:
    """Stand-in for a plan: only its source path, to find the files beside it."""

    def __init__(self, source: str):
        self.source = source
