"""``export --only``/``--part`` into a folder holding an export: of the same design it
refreshes the kinds asked and keeps every other file (listed in the new manifest, sha256
checked), of another design it is refused (no mix of two designs' files); check results of
another design (``review/checks.js``) are never carried over."""

from __future__ import annotations

import hashlib
import json
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


def _only_bom(out: Path, *extra: str):
    return run_cli("export", "--design", str(DEFAULT_DESIGN), "--no-cache", "--out", str(out),
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
