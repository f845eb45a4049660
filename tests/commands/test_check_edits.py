"""`tactcad check --out DIR` never writes over files edited by hand: a file of an export of the
same design changed or removed since fails the export_file check and is left as it is; only
another design (or no export) is exported again first. An interrupt's line says what the run
had written."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import tactcad
from tactcad import atomic, cli
from tactcad.checks import groups as registry
from tactcad.checks.export_files import EDITED_CHECK
from tactcad.export.reuse import file_sha256, reuse_state
from tactcad.store import stack_versions
from tactcad.version import VERSION


def fake_export(folder: Path, design_sha256: str, files: dict[str, bytes],
                inputs: dict | None = None, name: str | None = None) -> None:
    """A folder whose manifest lists ``files`` (written with those bytes) for the design
    (named ``name`` where given: a folder holding another name's export is refused before
    any export), and ``inputs`` as the export's record of what it was made from where
    given."""
    for rel, data in files.items():
        (folder / rel).parent.mkdir(parents=True, exist_ok=True)
        (folder / rel).write_bytes(data)
    man = {"design": {"sha256": design_sha256, **({"name": name} if name else {})},
           "tactcad_version": VERSION,
           "cad_stack": stack_versions(),
           "files": [{"path": rel, "sha256": file_sha256(folder / rel)} for rel in files]}
    if inputs is not None:
        man["inputs"] = inputs
    (folder / "manifest.json").write_text(json.dumps(man), encoding="utf-8")


def inputs_of(project) -> dict:
    """The ``inputs`` an export of ``project`` (:class:`tactcad.api.Project`) records now."""
    from tactcad.export.job import Run
    from tactcad.export.jobs import export_inputs

    return export_inputs(Run(project.validated, Path(), lambda line: None))


@pytest.fixture
def export_files_only(monkeypatch):
    """The check with only its export files group (the others read a whole export), and
    an export that fails the test if the check writes one."""
    from tactcad.export import run

    monkeypatch.setattr(registry, "CHECK_GROUPS",
                        {"export files": registry.CHECK_GROUPS["export files"]})
    written = []
    monkeypatch.setattr(run, "export", lambda project, out, **kw: written.append(out))
    return written


def test_check_leaves_a_hand_edit_as_it_is_and_fails_it(tmp_path, export_files_only):
    project = tactcad.load()
    out = tmp_path / "ex"
    fake_export(out, project.plan.design_hash,
                {"dxf/spacer_qty6.dxf": b"0\nEOF\n", "drawings/spacer.svg": b"<svg/>",
                 "bom.csv": b"part,qty\n"}, inputs_of(project))
    with open(out / "dxf" / "spacer_qty6.dxf", "ab") as fh:
        fh.write(b"; note\n")
    (out / "drawings" / "spacer.svg").unlink()
    edited = (out / "dxf" / "spacer_qty6.dxf").read_bytes()

    report = project.check(out, cache=False)

    assert export_files_only == []  # nothing exported over the edits
    assert (out / "dxf" / "spacer_qty6.dxf").read_bytes() == edited
    assert not (out / "drawings" / "spacer.svg").exists()
    assert report.reused_export and report.export_refusal is None and not report.passed
    failed = {r.subject: r.detail for r in report.failures}
    assert set(failed) == {"dxf/spacer_qty6.dxf", "drawings/spacer.svg"}
    assert all(r.check == EDITED_CHECK for r in report.failures)
    assert failed["dxf/spacer_qty6.dxf"].startswith(
        "edited since the export: sha256 differs from manifest.json")
    assert failed["drawings/spacer.svg"].startswith("removed since the export")
    assert f"`tactcad export --out {out}` writes it again" in failed["dxf/spacer_qty6.dxf"]


def test_check_exports_again_only_for_another_design_or_no_export(tmp_path, export_files_only):
    project = tactcad.load()
    other = tmp_path / "other"
    fake_export(other, "f" * 64, {"bom.csv": b"part,qty\n"}, name=project.plan.name)
    with open(other / "bom.csv", "ab") as fh:
        fh.write(b"edited\n")
    report = project.check(other, cache=False)
    assert export_files_only == [other] and report.export_refusal == "made from another design"

    current = tmp_path / "current"
    fake_export(current, project.plan.design_hash, {"bom.csv": b"part,qty\n"},
                inputs_of(project))
    report = project.check(current, cache=False)
    assert export_files_only == [other] and report.passed
    assert [r.check for r in report.results] == [EDITED_CHECK]


@pytest.fixture
def project_folder(tmp_path):
    """A project folder as `tactcad new` makes it: (design file, rigs file, scenes file)."""
    from tactcad.project_folder import new_project

    made = new_project(tmp_path / "lab")
    return made.design, made.folder / "rigs.toml", made.folder / "scenes.toml"


def edited(path: Path, old: str, new: str) -> None:
    """``path`` with its one line ``old`` made ``new`` (as a person edits it)."""
    text = path.read_text(encoding="utf-8")
    assert text.count(old) == 1
    path.write_text(text.replace(old, new), encoding="utf-8")


def test_an_export_older_than_its_rigs_or_scenes_is_exported_again(
        tmp_path, project_folder, export_files_only):
    design, rigs, scenes = project_folder
    project = tactcad.load(design)
    out = tmp_path / "ex"
    fake_export(out, project.plan.design_hash, {"bom.csv": b"part,qty\n"}, inputs_of(project),
                name=project.plan.name)
    assert project.check(out, cache=False).reused_export and export_files_only == []

    edited(rigs, "height_mm = 220.0", "height_mm = 260.0")  # the column: the design stays
    after = tactcad.load(design)
    assert after.plan.design_hash == project.plan.design_hash
    report = after.check(out, cache=False)
    assert export_files_only == [out] and not report.reused_export
    assert report.export_refusal == "older than rigs.toml (changed since it was written)"

    edited(scenes, "sample_stiffness_N_per_mm = 5.0", "sample_stiffness_N_per_mm = 2.24")
    report = tactcad.load(design).check(out, cache=False)
    assert report.export_refusal == ("older than rigs.toml, scenes.toml (changed since it "
                                     "was written)")


def test_an_export_that_records_no_inputs_is_exported_again(tmp_path, export_files_only):
    """An export made before exports recorded their inputs may be older than the rigs and
    scenes: with nothing edited by hand it is written again, saying why."""
    project = tactcad.load()
    out = tmp_path / "ex"
    fake_export(out, project.plan.design_hash, {"bom.csv": b"part,qty\n"},
                name=project.plan.name)
    report = project.check(out, cache=False)
    assert export_files_only == [out]
    assert report.export_refusal.startswith("made without a record of its inputs")


def test_an_export_older_than_its_rigs_with_a_hand_edit_says_so_and_fails(
        tmp_path, project_folder, export_files_only):
    """Files edited by hand are never written over: the export is checked as it is, and
    one failing check names the input edited since and the command that writes it again."""
    from tactcad.checks.export_files import STALE_CHECK

    design, rigs, _ = project_folder
    project = tactcad.load(design)
    out = tmp_path / "ex"
    fake_export(out, project.plan.design_hash, {"bom.csv": b"part,qty\n"}, inputs_of(project))
    with open(out / "bom.csv", "ab") as fh:
        fh.write(b"edited\n")
    edited(rigs, "stiffness_N_per_mm = [5.0, 2.24, 1.0]", "stiffness_N_per_mm = [5.0, 2.24]")

    report = tactcad.load(design).check(out, cache=False)

    assert export_files_only == [] and report.reused_export
    stale = [r for r in report.failures if r.check == STALE_CHECK]
    assert len(stale) == 1 and "older than rigs.toml" in stale[0].detail
    assert f"`tactcad export --out {out}` writes it again" in stale[0].detail


def test_an_export_records_what_it_was_made_from(tmp_path, project_folder, monkeypatch):
    """The manifest's inputs are those a check plans from the project's files, whether the
    export wrote all its jobs or some: current until an input changes, then naming the
    file; no record at all is never current."""
    from tactcad.export import run
    from tactcad.export.reuse import UNRECORDED_INPUTS, changed_inputs

    design, rigs, _ = project_folder
    project = tactcad.load(design)
    run.export(project.validated, tmp_path / "some", log=lambda line: None,
               select=lambda jobs: [])
    monkeypatch.setattr(run, "run_jobs", lambda *args, **kw: ([], 0))  # every job, none made
    run.export(project.validated, tmp_path / "all", log=lambda line: None)
    recorded = json.loads((tmp_path / "some" / "manifest.json").read_text())["inputs"]

    assert json.loads((tmp_path / "all" / "manifest.json").read_text())["inputs"] == recorded
    assert [f["file"] for f in recorded["files"]] == [design.name, "rigs.toml", "scenes.toml"]
    assert changed_inputs(recorded, project.validated) == []
    edited(rigs, "height_mm = 220.0", "height_mm = 221.0")
    assert changed_inputs(recorded, tactcad.load(design).validated) == ["rigs.toml"]
    assert changed_inputs(None, project.validated) == [UNRECORDED_INPUTS]


def test_the_state_of_an_export_folder(tmp_path):
    """Edits in an export of the same design are listed, never a reason to export again;
    a partial export or another version with nothing edited is exported again."""
    sha = "a" * 64
    assert reuse_state_of(tmp_path, sha).refusal == f"no manifest.json in {tmp_path}"
    fake_export(tmp_path, sha, {"a.txt": b"a", "b.txt": b"b"})
    assert reuse_state_of(tmp_path, sha).refusal is None
    (tmp_path / "a.txt").write_text("edited")
    (tmp_path / "b.txt").unlink()
    state = reuse_state_of(tmp_path, sha)
    assert state.refusal is None and state.edited == {"a.txt": "changed", "b.txt": "missing"}
    assert reuse_state_of(tmp_path, "b" * 64).refusal == "made from another design"
    fake_export(tmp_path, sha, {"a.txt": b"a"})
    man = json.loads((tmp_path / "manifest.json").read_text())
    (tmp_path / "manifest.json").write_text(json.dumps({**man, "partial": {}}))
    assert "partial" in reuse_state_of(tmp_path, sha).refusal
    (tmp_path / "manifest.json").write_text(json.dumps({**man, "cad_stack": {}}))
    assert "CAD stack" in reuse_state_of(tmp_path, sha).refusal


def reuse_state_of(folder: Path, sha: str):
    class Plan:
        design_hash = sha
    return reuse_state(Plan(), folder)


def test_check_help_says_hand_edits_are_never_written_over(capsys):
    with pytest.raises(SystemExit):
        cli.main(["check", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "is never written over" in text and "export files" in text


def test_check_help_states_exports_rule_for_another_design(capsys):
    """check's help states export's rule: another name's export is refused, one of the same
    name made from other content (another sha256) is exported over, as export replaces it."""
    with pytest.raises(SystemExit):
        cli.main(["check", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "A DIR holding another design's export is refused" not in text
    assert "a design of another name (or product)" in text and "is refused" in text
    assert "made from other content (another sha256, e.g. another --set) is exported over, " \
           "as export replaces it" in text


def test_check_refuses_the_export_of_another_design_name(tmp_path, export_files_only):
    """As export refuses it: a folder holding another name's export, before any export."""
    from tactcad.errors import DesignError

    project = tactcad.load()
    other = tmp_path / "other"
    fake_export(other, "f" * 64, {"bom.csv": b"part,qty\n"}, name="someone_elses_array")
    with pytest.raises(DesignError) as err:
        project.check(other, cache=False)
    assert str(err.value).startswith(f"out = '{other}'")
    assert "someone_elses_array" in str(err.value) and export_files_only == []


def test_an_interrupt_after_a_folder_was_written_says_so(tmp_path, monkeypatch, capsys):
    """The line an interrupt ends with names what the run had written (a check's export
    before its checks), and says the previous files are left only when none was."""
    from tactcad.commands import scenes as scenes_cmd

    out = tmp_path / "ex"

    def written_then_interrupted(args):
        staging = atomic.staging_dir(out)
        (staging / "a.txt").write_text("new")
        atomic.publish_dir(staging, out)
        raise KeyboardInterrupt

    monkeypatch.setattr(scenes_cmd, "run", written_then_interrupted)
    assert cli.main(["scenes"]) == cli.EXIT_INTERRUPTED
    err = capsys.readouterr().err
    assert f"this run had already written {out} before it" in err
    assert "the previous files are left as they were" not in err

    monkeypatch.setattr(scenes_cmd, "run", lambda args: (_ for _ in ()).throw(KeyboardInterrupt))
    assert cli.main(["scenes"]) == cli.EXIT_INTERRUPTED
    assert capsys.readouterr().err.strip() == \
        "tactcad: interrupted; the previous files are left as they were"


@pytest.mark.parametrize("as_json", [False, True])
def test_a_read_only_export_is_checked_and_its_review_page_left_with_a_warning(
        tmp_path, export_files_only, monkeypatch, capsys, as_json):
    """An export folder without write access printed every result, then failed
    `review/checks.js: permission denied` (exit 3; with --json the error alone): the
    results and the usual exit come out, with one warning that the page was not updated."""
    from tactcad.checks import review_results
    from tactcad.export.review_page import REVIEW_PAGE

    project = tactcad.load()
    out = tmp_path / "exports"
    fake_export(out, project.plan.design_hash, {"bom.csv": b"part,qty\n", REVIEW_PAGE: b"x"},
                inputs_of(project))

    def refused(path, data):
        raise PermissionError(13, "Permission denied", str(path))

    monkeypatch.setattr(review_results, "write_bytes_atomic", refused)
    code = cli.main(["check", "--out", str(out), "--no-cache", *(["--json"] if as_json else [])])
    captured = capsys.readouterr()
    assert code == 0 and export_files_only == []
    assert not (out / "review" / "checks.js").exists()
    said = f"{out / 'review' / 'checks.js'}: not updated (permission denied)"
    if as_json:
        doc = json.loads(captured.out)
        assert "error" not in doc and doc["failed"] == 0 and doc["checks"]
        [warning] = [w for w in doc["warnings"] if "checks.js" in w]
        assert warning.startswith(said)
    else:
        assert "passed" in captured.out and "permission denied" not in captured.out
        assert captured.err.count("checks.js") == 1 and f"tactcad: warning: {said}" in captured.err


def test_a_check_without_out_says_no_refusal_of_its_temporary_folder(tmp_path, monkeypatch,
                                                                     export_files_only, capsys):
    """Without an out the check's temporary folder held no export: its refusal ("no
    manifest.json in /tmp/...") is not an error of the run; exports/ left unread is said."""
    report = tactcad.load().check(None, cache=False)
    assert len(export_files_only) == 1 and not report.reused_export
    assert report.export_refusal is None and report.out is None
    monkeypatch.chdir(tmp_path)
    (tmp_path / "exports").mkdir()
    (tmp_path / "exports" / "manifest.json").write_text("{}", encoding="utf-8")
    cli.main(["check", "--json"])
    printed = json.loads(capsys.readouterr().out)
    assert printed["export_refusal"] is None and printed["reused_export"] is False
    cli.main(["check"])
    err = capsys.readouterr().err
    assert "--out exports checks that export as it is" in err and "no manifest.json" not in err
