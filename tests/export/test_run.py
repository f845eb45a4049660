"""The main job end to end: files, manifest, reproducibility, atomicity, checks."""

from __future__ import annotations

import hashlib
import json

import pytest

from conftest import file_digests
from tactcad.checks.check_result import failures
from tactcad.design.project import load_project
from tactcad.checks.array_checks import run_checks
from tactcad.export.run import export
from tactcad.store import Store


def test_expected_files(exported, plan):
    out, _ = exported
    names = {p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()}
    for part in plan.distinct_elements:
        assert f"step/{part}.step" in names
    assert {"step/spacer.step", "step/clamp_plate.step", "step/bolt_M2x30.step", "step/nut_M2.step",
            "step/array.step", "manifest.json"} <= names
    assert {f"dxf/{part}_qty2.dxf" for part in plan.distinct_elements} <= names
    assert {"dxf/spacer_qty8.dxf", "dxf/sheet_aluminium_3mm.dxf", "dxf/sheet_aluminium_1mm.dxf"} <= names
    assert not [n for n in names if n.startswith("dxf/element_") and "_qty" not in n]
    assert not [n for n in names if ".staging" in n or n.endswith(".part")]


def test_manifest_lists_every_file_with_its_hash(exported, plan):
    out, _ = exported
    man = json.loads((out / "manifest.json").read_text())
    assert man["design"]["sha256"] == plan.design_hash
    assert man["cad_stack"]["build123d"] == "0.10.0"
    assert man["cad_stack"]["cadquery-ocp"].startswith("7.8.1")
    on_disk = {p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()} - {"manifest.json"}
    assert {f["path"] for f in man["files"]} == on_disk
    for f in man["files"]:
        assert hashlib.sha256((out / f["path"]).read_bytes()).hexdigest() == f["sha256"]
        assert f["part"]
    assert man["parts"]["spacer"]["quantity"] == 8
    assert sum(p["quantity"] for p in man["parts"].values()) == man["assemblies"]["array"]["instances"]


def test_step_header_in_mm_ap214_and_flat_instanced_assembly(exported):
    out, _ = exported
    text = (out / "step/array.step").read_text()
    assert "AUTOMOTIVE_DESIGN" in text  # AP214
    assert "SI_UNIT(.MILLI.,.METRE.)" in text
    assert text.count("MANIFOLD_SOLID_BREP") == 10  # each distinct part stored once (gauge too)
    assert text.count("NEXT_ASSEMBLY_USAGE_OCCURRENCE") == 38  # placed 38 times (10 gauges)
    assert "'element_8'" in text and "'clamp_plate_back'" in text


def test_failed_export_leaves_previous_files_whole(default_store, tmp_path, monkeypatch, project):
    out = tmp_path / "ex"
    export(project, out, log=lambda s: None, store=Store(default_store))  # the set in place
    before = file_digests(out)
    import tactcad.export.dxf_sheet as dxf_mod

    calls = {"n": 0}
    real = dxf_mod.write_dxf

    def flaky(path, content, version="R2010"):
        calls["n"] += 1
        if calls["n"] == 4:
            raise OSError("disk full (simulated)")
        return real(path, content, version)

    monkeypatch.setattr(dxf_mod, "write_dxf", flaky)
    thicker = load_project()  # same project; the failure, not the content, is under test
    with pytest.raises(OSError, match="simulated"):
        export(thicker, out, log=lambda s: None)
    assert file_digests(out) == before
    assert not list(out.parent.glob(f".{out.name}.staging-*"))


def test_all_checks_pass_on_the_default_design(exported, plan):
    out, _ = exported
    results = run_checks(plan, out)
    assert not failures(results), "\n".join(r.line() for r in failures(results))
    checks = {r.check for r in results}
    assert {"is_valid", "no_free_boundaries", "volume", "watertight_mesh", "dxf_web_thickness",
            "edm_start_holes", "edm_inside_radius", "step_volume", "interference",
            "contact_touching", "dxf_lead_in", "dxf_extents", "dxf_part_marks", "sheet_gap",
            "sheet_copies"} <= checks


@pytest.mark.slow
def test_changed_web_reaches_the_dxf(tmp_path):
    """A value given as a user gives it (``set=``, as ``--set``) reaches the wire-EDM
    file that ``export --only dxf`` writes, built afresh (no store)."""
    import tactcad
    from tactcad.checks.dxf_readback import read_dxf, thinnest_ligament

    project = tactcad.load(set={"element.web_thickness_mm": 0.31})
    project.export(tmp_path, only="dxf", cache=False)
    reading = read_dxf(tmp_path / "dxf/element_a4mm_qty2.dxf")
    outer = max(reading.contours, key=lambda c: len(c.segments))
    assert thinnest_ligament(outer.segments) == pytest.approx(0.31, abs=1e-9)


def test_a_moved_copy_of_the_design_has_the_same_job_keys(tmp_path):
    """The store reuses an export's jobs for the same design in another folder
    (a git worktree of the previous commit, a CI checkout): no job's key holds
    the design file's path, every key still follows the files' contents."""
    import shutil

    from tactcad.commands.watch import watched_files
    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.export.job import Run
    from tactcad.export.jobs import all_jobs

    def copy(folder):
        folder.mkdir(parents=True)
        for f in watched_files(DEFAULT_DESIGN):
            shutil.copyfile(f, folder / f.name)
        return folder

    def keys(folder):
        run = Run(load_project(folder / DEFAULT_DESIGN.name), tmp_path / "staging")
        return {j.name: j.key for j in all_jobs(run)}

    here, moved = copy(tmp_path / "here"), copy(tmp_path / "elsewhere" / "renamed")
    assert keys(here) == keys(moved)
    rigs = moved / "rigs.toml"
    text = rigs.read_text(encoding="utf-8")
    rigs.write_text(text.replace("length_mm = 260.0", "length_mm = 270.0", 1), encoding="utf-8")
    before, edited = keys(here), keys(moved)  # the base plate 10 mm longer
    assert {n for n in before if edited[n] != before[n]} >= {"bom", "drawing:base_plate"}


def test_a_run_solves_each_scene_once(project, tmp_path, monkeypatch):
    """The scene's STEP and glTF job, its review file and the build book's pictures read
    one solved scene per run (each solve places every part by its joints)."""
    from tactcad.assembly import scene_solver
    from tactcad.export.job import Run
    from tactcad.export.jobs import _scene

    solved = []
    real = scene_solver.build_scene
    monkeypatch.setattr(scene_solver, "build_scene",
                        lambda p, name, cache=None: solved.append(name) or real(p, name, cache))
    run = Run(project, tmp_path, log=lambda line: None)
    first = run.scene("wirecut")
    records = _scene("wirecut")(run)
    assert run.scene("wirecut") is first and solved == ["wirecut"]
    assert {r["kind"] for r in records} == {"step-scene", "glb-scene"}
