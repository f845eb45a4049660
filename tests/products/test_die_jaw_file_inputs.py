"""A die project's jaw file is one of its inputs: its export's manifest records it
(``inputs``), and a check finds an export older than an edit of it (a pin or an opening
that leaves the die's plan as it was), exporting again or, with files edited by hand,
failing ``export_inputs``; ``tactcad.load_die`` takes a project folder as ``load`` does."""

from __future__ import annotations

import argparse
import json
import shutil
from pathlib import Path

import pytest

from tactcad.errors import DesignError

ROBOT = Path(__file__).resolve().parents[2] / "hardware" / "robotic_jaw_8mm_mems"
DESIGN = "robotic_jaw_8mm_mems.toml"
JAW = "robotic_jaw_8mm_mems_jaw.toml"


@pytest.fixture
def robot_folder(tmp_path) -> Path:
    """A project folder holding a copy of the shipped robotic die and its jaw file."""
    for name in (DESIGN, JAW):
        shutil.copy(ROBOT / name, tmp_path / name)
    return tmp_path


def _planned(folder: Path):
    from tactcad.commands.die import _die_args, die_asked, plan_of

    args = argparse.Namespace(overrides=[], json=False, quiet=True)
    return plan_of(die_asked(_die_args(folder / DESIGN, args, Path("."))))


def _fake_export(out: Path, planned, listed: dict[str, str]) -> None:
    """A manifest of ``planned``'s export as the export writes its head and ``inputs``,
    listing ``listed`` (path -> sha256), and its record with the plan."""
    from tactcad.commands.finite_json import dumps
    from tactcad.store import stack_versions
    from tactcad.version import VERSION

    out.mkdir()
    name = planned.plan.name
    (out / "manifest.json").write_text(json.dumps({
        "design": {"name": name, **planned.source}, "inputs": planned.inputs,
        "product": "silicon-die", "tactcad_version": VERSION, "cad_stack": stack_versions(),
        "files": [{"path": p, "sha256": s} for p, s in listed.items()]}), encoding="utf-8")
    (out / f"{name}.json").write_text(json.dumps({"die": json.loads(dumps(
        planned.plan.as_json()))}), encoding="utf-8")


def _edit_jaw(folder: Path) -> None:
    text = (folder / JAW).read_text(encoding="utf-8")
    edited = text.replace("pin_inset_mm = 1.1", "pin_inset_mm = 1.3").replace(
        "opening_angle_deg = 45.0", "opening_angle_deg = 60.0")
    assert edited != text
    (folder / JAW).write_text(edited, encoding="utf-8")


def test_the_inputs_name_the_design_and_jaw_files_with_their_sha256(robot_folder):
    import hashlib

    inputs = _planned(robot_folder).inputs
    assert [(f["role"], f["file"]) for f in inputs["files"]] == [("design", DESIGN),
                                                                  ("jaw", JAW)]
    assert inputs["files"][1]["sha256"] == hashlib.sha256(
        (robot_folder / JAW).read_bytes()).hexdigest()


def test_an_export_older_than_an_edit_of_the_jaw_file_is_exported_again(robot_folder):
    """A pin and an opening edited: the die's plan is the same, its mount and grasp not;
    the check finds the export older than the jaw file, as an array's than rigs.toml."""
    from tactcad.commands.die import _die_export_state

    planned = _planned(robot_folder)
    out = robot_folder / "exports"
    _fake_export(out, planned, {})
    record = out / f"{planned.plan.name}.json"
    assert _die_export_state(out, planned, record).refusal is None  # current
    _edit_jaw(robot_folder)
    now = _planned(robot_folder)
    assert now.plan == planned.plan  # the plan alone does not see the edit
    state = _die_export_state(out, now, record)
    assert state.refusal == f"older than {JAW} (changed since it was written)"
    assert state.stale == (JAW,)


def test_a_hand_edited_export_older_than_the_jaw_file_fails_export_inputs(robot_folder):
    """Files edited by hand are never written over: the export is checked as it is, with
    one failing check naming the jaw file, counted as a check of the files."""
    from tactcad.commands.die import die_check, on_the_files

    planned = _planned(robot_folder)
    out = robot_folder / "exports"
    _fake_export(out, planned, {"edited.csv": "0" * 64})
    _edit_jaw(robot_folder)
    said = []
    args = argparse.Namespace(out=str(out), junit=None, overrides=[], scene=None, json=True,
                              quiet=True)
    found = die_check(robot_folder / DESIGN, args, said.append)
    assert found.reused_export and found.export_refusal is None
    assert f"older than {JAW}" in said[-1]
    stale = [c for c in found.checks if c.check == "export_inputs"]
    assert len(stale) == 1 and stale[0].status == "fail" and JAW in stale[0].detail
    assert on_the_files("export_inputs")


def test_the_record_of_an_unrecorded_export_with_a_jaw_file_is_stale(robot_folder):
    from tactcad.export.reuse import UNRECORDED_INPUTS
    from tactcad.products.silicon_die.export.die_inputs import changed_die_inputs, die_inputs

    with_jaw = die_inputs(robot_folder / DESIGN, robot_folder / JAW)
    assert changed_die_inputs(None, with_jaw) == [UNRECORDED_INPUTS]
    assert changed_die_inputs(None, die_inputs(robot_folder / DESIGN, "")) == []
    assert changed_die_inputs(with_jaw, with_jaw) == []


def test_load_die_takes_a_project_folder_and_refuses_none_outside_a_dies(robot_folder,
                                                                          monkeypatch):
    import tactcad

    assert tactcad.load_die(robot_folder).name == tactcad.load(robot_folder).name
    monkeypatch.chdir(robot_folder)
    assert tactcad.load_die().source.name == DESIGN  # the working folder's die
    empty = robot_folder / "empty"
    empty.mkdir()
    monkeypatch.chdir(empty)
    with pytest.raises(DesignError) as caught:
        tactcad.load_die()
    assert caught.value.field == "path" and "die" in caught.value.allowed
    with pytest.raises(DesignError) as caught:
        tactcad.load_die(3)
    assert caught.value.field == "path"


def test_load_die_names_a_jaw_file_as_one(robot_folder):
    """A lab's jaw file given where its die's design is wanted is named a jaw file, with the
    command that reads it, not as an array's design file."""
    import tactcad

    with pytest.raises(DesignError) as caught:
        tactcad.load_die(robot_folder / JAW)
    assert "jaw file" in caught.value.why and "array" not in caught.value.why
    assert caught.value.alternatives[0]["option"].startswith("--jaw ")


@pytest.mark.slow  # a whole export of a die, then the check's export again
def test_check_exports_again_after_a_hand_edit_of_the_jaw_file(robot_folder):
    """The lab's case: export, then the pin and the opening edited in the jaw file. The
    check printed the export as current; it now exports again, and the record and the
    manifest hold the jaw as edited."""
    from conftest import run_cli

    r = run_cli("export", "--out", "exports", cwd=robot_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    manifest = json.loads((robot_folder / "exports" / "manifest.json").read_text("utf-8"))
    assert [f["file"] for f in manifest["inputs"]["files"]] == [DESIGN, JAW]
    _edit_jaw(robot_folder)
    r = run_cli("check", "--out", "exports", cwd=robot_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    assert f"exporting to exports first: older than {JAW}" in r.stdout + r.stderr
    record = (robot_folder / "exports" / "robotic_jaw_8mm_mems.json").read_text("utf-8")
    assert '"opening_angle_deg": 60.0' in record
    again = run_cli("check", "--out", "exports", cwd=robot_folder)
    assert "as it is (same design, every file as listed)" in again.stdout + again.stderr
