"""The validated project: one immutable object carried from validation to the
last writer; nothing below the command line reads a design, rigs or scenes file."""

from __future__ import annotations

import ast
import dataclasses
import shutil
from pathlib import Path

import pytest

from conftest import file_digests
from tactcad.design.array_plan import DEFAULT_DESIGN
from tactcad.design.project import Project, load_project, project_for_plan
from tactcad.design.rig_plan import DEFAULT_RIGS
from tactcad.design.scene_specs import DEFAULT_SCENES
from source_trees import one_reader, parsed

SRC = Path(__file__).resolve().parents[2] / "src" / "tactcad"
#: Functions that open a design, rigs or scenes file.
FILE_READERS = {"read_toml", "load_design", "load_rigs", "load_scenes", "load_project",
                "companion_files", "default_design_data", "default_rigs_data",
                "project_for_plan", "project_with_design_data"}
#: Where they may be called: the layer that validates the files, the command line and
#: the Python API's entry points (tactcad.load; the build123d part classes, which are
#: built from the design file they are given).
READERS_ALLOWED = ("design/", "commands/", "cli.py", "api.py", "project_folder.py",
                   "assembly/part_objects.py")
#: Modules that read the shipped (paper's) design as fixed reference data, never as the
#: user's design: the stiffness-correction grid is defined on it (a study run on
#: purpose, `tactcad sweep refit`). mechanics/ reads no design file at all: the
#: paper's comparisons work on the plan they are handed, where it applies.
TEMPLATE_READERS = {"studies/correction_sweep.py": {"default_design_data"}}


def _design_copy(tmp_path: Path) -> Path:
    for f in (DEFAULT_DESIGN, DEFAULT_RIGS, DEFAULT_SCENES):
        shutil.copy(f, tmp_path / f.name)
    return tmp_path / DEFAULT_DESIGN.name


def _hashes(folder: Path) -> dict[str, str]:
    return {rel: sha for rel, sha in file_digests(folder).items()
            if Path(rel).name != "manifest.json"}


def test_project_is_immutable(project):
    assert isinstance(project, Project)
    with pytest.raises(dataclasses.FrozenInstanceError):
        project.plan = None
    with pytest.raises(TypeError):
        project.scenes["extra"] = project.scenes["array"]
    assert list(project.scenes) == ["wirecut", "array", "calibration-rig", "sample-stiffness-rig",
                                    "array-evaluation-rig"]
    assert set(project.hashes) == {"design", "rigs", "scenes"}
    assert all(len(h) == 64 for h in project.hashes.values())


def test_hashes_follow_the_validated_data_not_the_layout(tmp_path, project):
    design = _design_copy(tmp_path)
    rigs = tmp_path / "rigs.toml"
    rigs.write_text("# a comment changes no value\n" + rigs.read_text())
    same = load_project(design)
    assert same.hashes == project.hashes
    rigs.write_text(rigs.read_text().replace("length_mm = 80.0", "length_mm = 91.0", 1))
    changed = load_project(design)
    assert changed.rigs.part("cart").length_mm == 91.0
    assert changed.rigs_sha256 != project.rigs_sha256
    assert changed.design_sha256 == project.design_sha256
    assert changed.scenes_sha256 == project.scenes_sha256


@pytest.mark.slow  # a whole chain through the command line or an export
def test_rigs_file_changed_after_validation_leaves_the_export_unchanged(tmp_path):
    """The run works from the validated project: a rigs or scenes file edited
    while the run goes on cannot change what it writes."""
    from tactcad.export.run import export

    (tmp_path / "hw").mkdir()
    design = _design_copy(tmp_path / "hw")
    project = load_project(design)
    only_scene = lambda jobs: [j for j in jobs if j.name == "scene:sample-stiffness-rig"]
    export(project, tmp_path / "a", log=lambda s: None, select=only_scene, partial={})
    rigs, scenes = design.parent / "rigs.toml", design.parent / "scenes.toml"
    rigs.write_text(rigs.read_text().replace("length_mm = 80.0", "length_mm = 91.0", 1))
    scenes.write_text("this is no TOML [[[")
    export(project, tmp_path / "b", log=lambda s: None, select=only_scene, partial={})
    assert _hashes(tmp_path / "b") == _hashes(tmp_path / "a")
    # and the edit would have mattered had the files been read again
    scenes.write_text(DEFAULT_SCENES.read_text())
    edited = load_project(design)
    assert edited.rigs.part("cart") != project.rigs.part("cart")
    export(edited, tmp_path / "c", log=lambda s: None, select=only_scene, partial={})
    assert _hashes(tmp_path / "c") != _hashes(tmp_path / "a")


def test_a_plan_made_in_code_gets_its_rigs_and_scenes_named(plan):
    project = project_for_plan(plan)
    assert project.rigs_file == DEFAULT_RIGS.name and project.scenes_file == DEFAULT_SCENES.name
    # the plan, with the force gauge of the rigs it is calibrated on
    assert project.plan.rigs_force_gauge == project.rigs.part("force_gauge")
    assert dataclasses.replace(project.plan, rigs_force_gauge=plan.rigs_force_gauge) == plan
    assert project_for_plan(project.plan).plan is project.plan


def test_test_rigs_need_the_validated_rigs(plan):
    from tactcad.assembly.rig_models import rig_model
    from tactcad.errors import SceneError

    assert rig_model(plan, "array").nodes  # the array needs no rigs
    with pytest.raises(SceneError, match="needs the validated rigs"):
        rig_model(plan, "calibration")


def _calls(path: Path) -> set[str]:
    names = set()
    for node in ast.walk(parsed(path)):
        if isinstance(node, ast.Call):
            f = node.func
            names.add(f.id if isinstance(f, ast.Name) else getattr(f, "attr", ""))
    return names


def in_its_room(rel: str) -> str:
    """A module's path as its layer's room sees it: a product's own module
    (``products/<product>/<layer>/...``) in the room its folder names."""
    parts = rel.split("/")
    return "/".join(parts[2:]) if parts[0] == "products" and len(parts) > 3 else rel


@one_reader  # in the process that parsed every source for the house tests
def test_nothing_below_the_commands_reads_a_design_file():
    offenders = []
    for path in sorted(SRC.rglob("*.py")):
        rel = in_its_room(path.relative_to(SRC).as_posix())
        if rel.startswith(READERS_ALLOWED):
            continue
        found = _calls(path) & FILE_READERS - TEMPLATE_READERS.get(rel, set())
        if found:
            offenders.append(f"{rel}: {', '.join(sorted(found))}")
    assert not offenders, offenders
