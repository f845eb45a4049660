"""Scenes file (``hardware/scenes.toml``) -> validated scene specs (no CAD kernel).

A scene names its rig, the groups of parts it shows and their level of
detail; :mod:`tactcad.assembly.scene_solver` assembles it. The file is read by the
schema mechanism of :mod:`tactcad.vocabulary.schema`: every refusal at once.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping, Optional

from tactcad.design.array_plan import DEFAULT_DESIGN
from tactcad.vocabulary.schema import (NAME_ALLOWED, NAME_PATTERN, Problems, Section, Text, choice,
                                       listing, number, read_toml, validate)

DEFAULT_SCENES = DEFAULT_DESIGN.parent / "scenes.toml"  # the default design's
#: Levels of detail: ``full`` (fabricated parts as made) and ``envelope``
#: (bought parts as their catalogue envelope).
LEVELS = ("envelope", "full")
MODELLED = {"fabricated": "full", "purchased": "envelope"}
#: Every rig and the groups of parts it has (a design may leave a group empty,
#: e.g. ``spacers`` of a one-column array).
RIG_GROUPS: dict[str, tuple[str, ...]] = {
    "wirecut": ("elements", "spacers"),
    "array": ("array",),
    "calibration": ("base_plate", "column", "z_axis", "force_gauge", "indenter", "xy_stage",
                    "bracket", "array"),
    "sample-stiffness": ("base_plate", "column", "z_axis", "force_gauge", "indenter", "cart",
                         "sample_holder", "sample"),
    "array-evaluation": ("base_plate", "column", "linear_axis", "carrier", "hanger_bar", "weights",
                         "bracket", "array", "cart", "sample_holder", "sample"),
    "grasper": ("jaw", "array", "tissue", "shaft"),
}
RIGS = tuple(RIG_GROUPS)
#: The scenes a project without test rigs can show (the array alone, its cut sheet, the
#: insert in a grasper's jaw).
RIGS_WITHOUT_TEST_RIGS = ("array", "wirecut", "grasper")
#: The grasper's jaw angle a scene may set, degrees (0: closed on the tissue).
JAW_ANGLE_RANGE_DEG = (0.0, 90.0)
MAX_SCENES = 64


@dataclass(frozen=True)
class SceneSpec:
    """One scene of ``scenes.toml``."""

    name: str
    rig: str
    description: str
    groups: tuple[str, ...]
    detail: Mapping[str, str]  # kind -> level
    sample_stiffness_N_per_mm: float | None = None
    #: rig ``grasper``: the jaw's angle about its pin (degrees; 0 closed on the tissue;
    #: None: the jaw's opening angle)
    jaw_angle_deg: float | None = None


class DetailTable(Section):
    fabricated: Optional[choice(LEVELS)] = None
    purchased: Optional[choice(LEVELS)] = None


class SceneTable(Section):
    rig: choice(RIGS)
    description: Text
    groups: listing(str, 1, 32, "a non-empty list of group names")
    detail: DetailTable = DetailTable()
    sample_stiffness_N_per_mm: Optional[number(0.0, 1e4, lo_open=True, unit="N/mm",
                                               why="a stiffness of the sample list of rigs.toml")] = None
    jaw_angle_deg: Optional[number(*JAW_ANGLE_RANGE_DEG, unit="degrees",
                                   why="rig grasper: the jaw's angle about its pin, 0 closed on "
                                       "the tissue")] = None


class ScenesFile(Section):
    detail: DetailTable = DetailTable()
    scene: dict[str, SceneTable]


def _detail(field: str, table: DetailTable, default: Mapping[str, str],
            p: Problems) -> dict[str, str]:
    out = dict(default)
    for kind, modelled in MODELLED.items():
        level = getattr(table, kind)
        if level is None:
            continue
        if level != modelled:
            p.add(f"{field}.{kind}", level, f'"{modelled}"',
                  f"{kind} parts are modelled at level {modelled} only")
        out[kind] = level
    return out


def _scene(name: str, t: SceneTable, default: Mapping[str, str], p: Problems) -> SceneSpec:
    f = f"scene.{name}"
    if not re.match(NAME_PATTERN, name):
        p.add(f, name, "scene names of " + NAME_ALLOWED, "a scene's name is its file name")
    if len(set(t.groups)) != len(t.groups):
        p.add(f"{f}.groups", t.groups, "each group once")
    unknown = [g for g in t.groups if g not in RIG_GROUPS[t.rig]]
    if unknown:
        p.add(f"{f}.groups", unknown, "groups of rig " + t.rig + ": " + ", ".join(RIG_GROUPS[t.rig]),
              "unknown group")
    if t.jaw_angle_deg is not None and t.rig != "grasper":
        p.add(f"{f}.jaw_angle_deg", t.jaw_angle_deg, "left out", "only rig grasper has a jaw")
    return SceneSpec(name, t.rig, t.description.strip(), tuple(t.groups),
                     _detail(f"{f}.detail", t.detail, default, p), t.sample_stiffness_N_per_mm,
                     t.jaw_angle_deg)


def validate_scenes(data: Mapping[str, Any], file: str = "") -> tuple[dict[str, SceneSpec], Problems]:
    """The scenes and every refusal of a scenes file."""
    p = Problems(file)
    model = validate(ScenesFile, data, p)
    if model is None:
        return {}, p
    if not model.scene or len(model.scene) > MAX_SCENES:
        p.add("scene", f"{len(model.scene)} scenes", f"1 ... {MAX_SCENES} [scene.<name>] tables")
    default = _detail("detail", model.detail, MODELLED, p)
    return {name: _scene(name, t, default, p) for name, t in model.scene.items()}, p


def load_scenes(path: str | Path | None = None) -> dict[str, SceneSpec]:
    """Read and validate a scenes file. A description's words (``$grid``) are left as
    written: :func:`tactcad.design.project.load_project` fills them in from the design.

    Raises:
        DesignError: unreadable file, unknown key, bad rig, group or level
            (:class:`~tactcad.errors.DesignErrors` lists every one).
    """
    p = Path(path) if path is not None else DEFAULT_SCENES
    scenes, problems = validate_scenes(read_toml(p, "scenes file"), p.name)
    problems.raise_if_any()
    return scenes
