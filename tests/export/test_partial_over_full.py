"""``export --only``/``--part`` into a folder holding an export: of the same design it
refreshes the kinds asked and keeps every other file (listed in the new manifest, sha256
checked), of another design it is refused (no mix of two designs' files); check results of
another design (``review/checks.js``) are never carried over."""

from __future__ import annotations

import hashlib
import json
import os
import shutil
from pathlib import Path

import pytest

from conftest import file_digests, run_cli
from tactcad.design.array_plan import DEFAULT_DESIGN
from tactcad.export.review_page import CHECKS_SCRIPT

BOM = {"bom.csv", "bom.md"}


@pytest.fixture
def full(exported, tmp_path) -> Path:
    """A private copy of the default design's full export."""
    out = tmp_path / "exports"
    shutil.copytree(exported[0], out)
    return out


def _manifest(out: Path) -> dict:
    return json.loads((out / "manifest.json").read_text(encoding="utf-8"))


def _listed(out: Path) -> dict[str, str]:
    """The manifest's files by path, each proven to be there with its sha256."""
    listed = {f["path"]: f["sha256"] for f in _manifest(out)["files"]}
    for rel, sha in listed.items():
        assert hashlib.sha256((out / rel).read_bytes()).hexdigest() == sha, rel
    return listed


def _checks_for(out: Path, sha256: str) -> None:
    (out / CHECKS_SCRIPT).write_text(
        'window.TACTCAD_CHECKS = ' + json.dumps({"design_sha256": sha256, "checks": []}) + ";\n",
        encoding="utf-8")


def _only_bom(out: Path, *extra: str, cache: tuple[str, ...] = ("--no-cache",)):
    return run_cli("export", "--design", str(DEFAULT_DESIGN), *cache, "--out", str(out),
                   "--only", "bom", *extra)


def test_only_bom_into_a_full_export_of_the_design_keeps_every_other_file(full):
    before, files_before = _listed(full), file_digests(full)
    assert BOM <= set(before) and any(p.endswith(".step") for p in before)
    (full / "bom.csv").write_text("an old BOM")  # the refresh must rewrite it
    r = _only_bom(full)
    assert r.returncode == 0, r.stderr
    after = _listed(full)
    # every STEP, DXF, drawing and scene still there, as it was, and listed
    assert set(after) == set(before)
    assert {p: s for p, s in after.items() if p not in BOM} == \
        {p: s for p, s in before.items() if p not in BOM}
    assert {p: s for p, s in file_digests(full).items() if p not in BOM | {"manifest.json"}} \
        == {p: s for p, s in files_before.items() if p not in BOM | {"manifest.json"}}
    assert (full / "bom.csv").read_text() != "an old BOM"
    partial = _manifest(full)["partial"]
    assert partial["only"] == ["bom"] and partial["jobs"] == ["bom"]
    assert set(partial["kept"]) == set(before) - BOM
    assert "kept as they were" in r.stdout


def test_check_results_of_the_same_design_stay_those_of_another_go(full):
    sha = _manifest(full)["design"]["sha256"]
    _checks_for(full, sha)
    assert _only_bom(full).returncode == 0
    assert sha in (full / CHECKS_SCRIPT).read_text(encoding="utf-8")  # still this export's
    _checks_for(full, "0" * 64)  # an earlier check of another design
    assert _only_bom(full).returncode == 0
    assert not (full / CHECKS_SCRIPT).exists()
    assert (full / "review" / "index.html").is_file()  # the page stays, without those results


def test_a_partial_export_of_another_design_is_refused_and_the_folder_left_whole(full):
    before = file_digests(full)
    r = _only_bom(full, "--set", "element.web_thickness_mm=0.3")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    err = r.stderr.strip().splitlines()[-1]
    old_sha = _manifest(full)["design"]["sha256"]
    assert "--out" in err and str(full) in err and old_sha[:12] in err, err
    assert "made from another design" in err and "no --only/--part" in err
    assert file_digests(full) == before


def test_a_file_changed_by_hand_is_kept_but_no_longer_listed(full):
    step = next(p for p in _listed(full) if p.endswith(".step"))
    (full / step).write_bytes(b"changed by hand")
    r = _only_bom(full)
    assert r.returncode == 0, r.stderr
    assert (full / step).read_bytes() == b"changed by hand"
    assert step not in _listed(full)
    assert "changed by hand" in r.stderr and step in r.stderr


def test_check_results_are_stale_for_any_other_design(tmp_path):
    from tactcad.export.export_owner import stale_check_results

    assert stale_check_results(tmp_path, "a" * 64) == set()  # none there
    (tmp_path / "review").mkdir()
    _checks_for(tmp_path, "a" * 64)
    assert stale_check_results(tmp_path, "a" * 64) == set()
    assert stale_check_results(tmp_path, "b" * 64) == {CHECKS_SCRIPT}
    (tmp_path / CHECKS_SCRIPT).write_text("not one tactcad wrote")
    assert stale_check_results(tmp_path, "a" * 64) == {CHECKS_SCRIPT}


def test_only_bom_into_a_full_export_names_the_files_the_folder_keeps(full, exported):
    """The partial BOM names each part's drawing, DXF and STEP files kept from the earlier
    export, as the full export's BOM does: the same bytes. The earlier folder's files are
    copied in before the jobs run, never linked: a hard link to one outside stays as it was."""
    outside = full.parent / "bom.md.link"
    os.link(full / "bom.md", outside)
    r = _only_bom(full)
    assert r.returncode == 0, r.stderr
    for name in BOM:
        assert (full / name).read_bytes() == (exported[0] / name).read_bytes(), name
    assert outside.read_bytes() == (exported[0] / "bom.md").read_bytes()


def test_a_partial_bom_without_the_earlier_files_is_not_reused_where_they_are(full, tmp_path):
    """``--only bom`` into a new folder names no file (none is there); the store hands that
    BOM to no run that finds the earlier export's files, and a second run into a copy of
    the same export reuses the one made there."""
    store, alone = tmp_path / "store", tmp_path / "alone"
    again = tmp_path / "again"
    shutil.copytree(full, again)
    expected = {name: (full / name).read_bytes() for name in BOM}
    r = _only_bom(alone, cache=("--cache", str(store)))
    assert r.returncode == 0, r.stderr
    assert (alone / "bom.csv").read_bytes() != expected["bom.csv"]
    assert sorted(p.name for p in alone.iterdir()) == ["bom.csv", "bom.md", "manifest.json"]
    for out in (full, again):
        r = _only_bom(out, "--json", cache=("--cache", str(store)))
        assert r.returncode == 0, r.stderr
        assert {name: (out / name).read_bytes() for name in BOM} == expected
    assert json.loads(r.stdout)["jobs_reused"] == 1


def test_a_job_reading_the_files_of_jobs_left_out_is_keyed_by_the_files_kept():
    """:func:`~tactcad.export.selection.with_kept_files`: the kept files' paths and sha256
    go into the key of a job reading the files of jobs left out, and only of such a job."""
    from tactcad.export.job import Job
    from tactcad.export.selection import with_kept_files

    jobs = [Job("step:a", "k1", None), Job("bom", "k2", None, after=("step:a", "dxf:shop"))]
    kept = [{"path": "dxf/shop.dxf", "sha256": "1" * 64}]
    assert with_kept_files(jobs, ()) == jobs
    keyed = with_kept_files(jobs, kept)
    assert keyed[0] == jobs[0] and keyed[1].key != "k2"
    other = with_kept_files(jobs, [{"path": "dxf/shop.dxf", "sha256": "2" * 64}])
    assert other[1].key not in ("k2", keyed[1].key)
    both = [jobs[0], Job("dxf:shop", "k3", None), jobs[1]]
    assert with_kept_files(both, kept) == both  # reads only files written now


def test_the_earlier_files_are_copied_in_before_the_jobs_only_of_the_same_design(tmp_path):
    """:func:`~tactcad.export.run.carried_before_jobs`: the files the earlier manifest lists,
    unchanged, copied (never linked: a writer writing in place would change the earlier
    export through the link); none of another design's export, nor of a folder with none."""
    from tactcad.export.run import carried_before_jobs

    out, staging = tmp_path / "out", tmp_path / "staging"
    (out / "step").mkdir(parents=True)
    staging.mkdir()
    (out / "step" / "a.step").write_bytes(b"kept")
    (out / "b.svg").write_bytes(b"changed by hand")
    (out / "notes.txt").write_bytes(b"the lab's")
    files = [{"path": "step/a.step", "sha256": hashlib.sha256(b"kept").hexdigest()},
             {"path": "b.svg", "sha256": hashlib.sha256(b"as written").hexdigest()}]
    (out / "manifest.json").write_text(json.dumps(
        {"design": {"name": "d", "sha256": "a" * 64}, "files": files}), encoding="utf-8")
    assert carried_before_jobs(out, staging, "b" * 64) == ()
    assert not any(staging.iterdir())
    carried = carried_before_jobs(out, staging, "a" * 64)
    assert [f["path"] for f in carried] == ["step/a.step"]
    assert sorted(p.relative_to(staging).as_posix() for p in staging.rglob("*")
                  if p.is_file()) == ["step/a.step"]
    assert (staging / "step" / "a.step").read_bytes() == b"kept"
    assert not os.path.samefile(staging / "step" / "a.step", out / "step" / "a.step")
    assert carried_before_jobs(tmp_path / "none", tmp_path / "s2", "a" * 64) == ()
