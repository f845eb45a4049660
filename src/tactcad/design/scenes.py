"""Scenes file (``hardware/scenes.toml``) -> validated scene specs (no CAD kernel).

A scene names its rig, the groups of parts it shows and their level of
detail; :mod:`tactcad.assembly.scenes` assembles it.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from tactcad.design.array import Plan, read_toml
from tactcad.errors import DesignError

DEFAULT_SCENES = Path(__file__).resolve().parents[3] / "hardware" / "scenes.toml"
#: Levels of detail: ``full`` (fabricated parts as made) and ``envelope``
#: (bought parts as their catalogue envelope).
LEVELS = ("envelope", "full")
RIGS = ("wirecut", "array", "calibration", "sample-stiffness", "array-evaluation")


@dataclass(frozen=True)
class SceneSpec:
    """One scene of ``scenes.toml``."""

    name: str
    rig: str
    description: str
    groups: tuple[str, ...]
    detail: Mapping[str, str]  # kind -> level
    sample_stiffness_N_per_mm: float | None = None


def scenes_path_for(plan: Plan) -> Path:
    """``scenes.toml`` beside the design file, else the default one."""
    src = Path(getattr(plan, "source", "") or "")
    candidate = src.parent / "scenes.toml"
    return candidate if src.name and candidate.is_file() else DEFAULT_SCENES


def load_scenes(path: str | Path | None = None) -> dict[str, SceneSpec]:
    """Read and validate a scenes file (group names are checked against the
    rig when a scene is assembled).

    Raises:
        DesignError: unreadable file, unknown key, bad rig or level.
    """
    p = Path(path) if path is not None else DEFAULT_SCENES
    data = read_toml(p, "scenes file")
    for key in data:
        if key not in ("detail", "scene"):
            raise DesignError(key, "<table>", "sections detail, scene", "unknown section")
    default = _detail("detail", data.get("detail", {}), {"fabricated": "full",
                                                          "purchased": "envelope"})
    scenes = data.get("scene", {})
    if not isinstance(scenes, Mapping) or not scenes:
        raise DesignError("scene", scenes, "one or more [scene.<name>] tables")
    out = {}
    allowed = {"rig", "description", "groups", "detail", "sample_stiffness_N_per_mm"}
    for name, t in scenes.items():
        f = f"scene.{name}"
        if not isinstance(t, Mapping):
            raise DesignError(f, t, "a table")
        for key in t:
            if key not in allowed:
                raise DesignError(f"{f}.{key}", t[key], "keys " + ", ".join(sorted(allowed)),
                                  "unknown key")
        rig = t.get("rig")
        if rig not in RIGS:
            raise DesignError(f"{f}.rig", rig, "one of " + ", ".join(RIGS))
        desc = t.get("description")
        if not isinstance(desc, str) or not desc.strip():
            raise DesignError(f"{f}.description", desc, "a non-empty string")
        groups = t.get("groups")
        if not isinstance(groups, list) or not groups or not all(isinstance(g, str) for g in groups):
            raise DesignError(f"{f}.groups", groups, "a non-empty list of group names")
        if len(set(groups)) != len(groups):
            raise DesignError(f"{f}.groups", groups, "each group once")
        k = t.get("sample_stiffness_N_per_mm")
        if k is not None and (isinstance(k, bool) or not isinstance(k, (int, float))):
            raise DesignError(f"{f}.sample_stiffness_N_per_mm", k, "a stiffness (N/mm) of rigs.toml")
        out[name] = SceneSpec(name, rig, desc.strip(), tuple(groups),
                              _detail(f"{f}.detail", t.get("detail", {}), default),
                              None if k is None else float(k))
    return out


def _detail(field_name: str, table: Any, default: Mapping[str, str]) -> dict[str, str]:
    if not isinstance(table, Mapping):
        raise DesignError(field_name, table, "a table kind = level")
    out = dict(default)
    for kind, level in table.items():
        if kind not in ("fabricated", "purchased"):
            raise DesignError(f"{field_name}.{kind}", level, "keys fabricated, purchased")
        modelled = "full" if kind == "fabricated" else "envelope"
        if level not in LEVELS:
            raise DesignError(f"{field_name}.{kind}", level, "one of " + ", ".join(LEVELS))
        if level != modelled:
            raise DesignError(f"{field_name}.{kind}", level, f'"{modelled}"',
                              f"{kind} parts are modelled at level {modelled} only")
        out[kind] = level
    return out


