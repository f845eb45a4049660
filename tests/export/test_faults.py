"""Faults of the disk: a failed write of any kind is exit 3 naming the file and
"disk full", the previous set stays whole, leftovers that cannot be removed
are named in one warning; a missing input file is bad input (exit 2)."""

from __future__ import annotations

import errno
import json
import os
import shutil
import subprocess
import uuid
from pathlib import Path

import pytest

from conftest import file_digests
from tactcad import atomic, cli


def export(out: Path, *extra: str) -> int:
    return cli.main(["export", "--no-cache", "--quiet", "--out", str(out), *extra])


def _tmpfs(options: str):
    """A tmpfs mounted with ``options`` (root only; the test is skipped elsewhere)."""
    if os.geteuid() != 0 or not shutil.which("mount"):
        pytest.skip("mounting a tmpfs needs root")
    mnt = Path(f"/tmp/tactcad-tinydisk-{uuid.uuid4().hex[:8]}")
    mnt.mkdir()
    if subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(mnt)],
                      capture_output=True).returncode:
        mnt.rmdir()
        pytest.skip("cannot mount a tmpfs here")
    try:
        yield mnt
    finally:
        subprocess.run(["umount", str(mnt)], check=False)
        mnt.rmdir()


@pytest.fixture
def tiny_disk():
    """A 1 MiB tmpfs."""
    yield from _tmpfs("size=1m")


@pytest.fixture
def few_inodes():
    """A tmpfs of 16 files and folders at most (a disk full of small files)."""
    yield from _tmpfs("size=1m,nr_inodes=16")


def fill_inodes(disk: Path, left: int) -> None:
    """Make empty files on ``disk`` until only ``left`` more can be made."""
    made = []
    try:
        while True:
            made.append(disk / f"f{len(made)}")
            made[-1].touch()
    except OSError as exc:
        assert exc.errno == errno.ENOSPC
    for path in made[-1 - left:-1]:
        path.unlink()


def fill(disk: Path) -> None:
    """Fill ``disk`` to the last byte."""
    for k, size in enumerate((65536, 512, 1)):
        try:
            with open(disk / f"filler{k}", "wb") as fh:
                while True:
                    fh.write(b"\0" * size)
                    fh.flush()
        except OSError as exc:
            assert exc.errno == errno.ENOSPC


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_full_disk_is_exit_3_naming_the_file_and_the_old_set_stays_whole(tiny_disk, capsys):
    out = tiny_disk / "ex"
    assert export(out, "--only", "bom") == 0
    before = file_digests(out)
    fill(tiny_disk)
    capsys.readouterr()
    assert export(out, "--only", "bom", "--set", "element.web_thickness_mm=0.3") == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "disk full" in err and f"{out}/" in err
    assert ".staging-" not in err
    assert file_digests(out) == before
    assert not list(tiny_disk.glob(".ex.staging-*"))


def test_a_full_disk_is_json_with_exit_3(tiny_disk, capsys):
    fill(tiny_disk)
    assert cli.main(["export", "--no-cache", "--json", "--only", "bom",
                     "--out", str(tiny_disk / "ex")]) == 3
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["exit_code"] == 3 and "disk full" in err["message"]


# no room for the staging folder; for a file in it (the lock beside the folder takes one)
@pytest.mark.parametrize("left", [0, 2])
def test_a_disk_without_room_for_a_file_names_the_export_folder_not_a_hidden_one(
        few_inodes, capsys, left):
    out = few_inodes / "ex"
    fill_inodes(few_inodes, left)
    assert export(out, "--only", "bom") == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "disk full" in err, err
    assert f"{out}/bom." in err if left else f"{out}: disk full" in err
    assert ".staging-" not in err and ".part" not in err
    assert not out.exists()


@pytest.mark.parametrize("disk", ["tiny_disk", "few_inodes"])
def test_a_full_disk_in_new_names_the_projects_file_not_the_staging_folder(disk, request, capsys):
    mnt = request.getfixturevalue(disk)
    fill(mnt) if disk == "tiny_disk" else fill_inodes(mnt, 1)
    assert cli.main(["new", str(mnt / "p")]) == 3
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{mnt / 'p'}/" in err and "disk full" in err, err
    assert ".staging-" not in err
    assert not (mnt / "p").exists() and not list(mnt.glob(".p.staging-*"))


class _Refused(RuntimeError):
    pass


def _fail_silently(*args, **kwargs):
    raise _Refused("the writer failed")  # as OpenCascade or freecadcmd do: no cause given


def _fail_enospc(path, *args, **kwargs):
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))


@pytest.mark.slow
@pytest.mark.parametrize("kind,module,name,extra", [
    ("STEP", "tactcad.kernel.step_writer", "_write_doc", ["--only", "step", "--part", "spacer"]),
    ("GLB", "tactcad.export.glb", "write_glb", ["--scene", "wirecut"]),
    ("PDF", "tactcad.drawings.pdf", "svgs_to_pdf", ["--only", "drawings"]),
    ("FCStd", "tactcad.export.freecad_review", "start_review_files", ["--only", "review"]),
])
def test_every_writer_failing_on_a_full_disk_is_exit_3(kind, module, name, extra, tmp_path,
                                                       monkeypatch, capsys):
    import importlib

    if kind == "FCStd" and not shutil.which("freecadcmd"):
        pytest.skip("freecadcmd is not installed")
    monkeypatch.setenv("TACTCAD_WORKERS", "0")  # the patched writer runs in this process
    out = tmp_path / "ex"
    assert export(out, "--only", "bom") == 0
    before = file_digests(out)
    mod = importlib.import_module(module)
    real_free = atomic.free_bytes
    monkeypatch.setattr(mod, name, _fail_silently)
    monkeypatch.setattr(atomic, "free_bytes", lambda p: 0)  # the disk is full
    capsys.readouterr()
    assert export(out, *extra) == 3, kind
    err = capsys.readouterr().err
    assert "disk full" in err and str(out) in err and ".staging-" not in err, err
    assert file_digests(out) == before
    # with room on the disk the same failure is not put down to the disk
    monkeypatch.setattr(atomic, "free_bytes", real_free)
    with pytest.raises(_Refused):
        export(out, *extra)
    assert file_digests(out) == before


@pytest.mark.slow
def test_a_writer_raising_enospc_names_the_export_path_not_the_staging(tmp_path, monkeypatch,
                                                                       capsys):
    from tactcad.export import bom

    monkeypatch.setattr(bom, "write_bom_files", lambda plan, staging, *a: _fail_enospc(
        staging / "bom.csv"))
    assert export(tmp_path / "ex", "--only", "bom") == 3
    err = capsys.readouterr().err
    assert f"{tmp_path / 'ex'}/bom.csv: disk full" in err


@pytest.mark.slow  # a whole export
def test_leftovers_that_cannot_be_removed_are_named_in_one_warning(tmp_path, monkeypatch,
                                                                   capsys):
    out = tmp_path / "ex"
    stuck = tmp_path / ".ex.staging-killed"
    (stuck / "sub").mkdir(parents=True)
    (stuck / "sub" / "a.step").write_text("x")
    real = shutil.rmtree

    def rmtree(path, onerror=None, **kw):
        if Path(path) == stuck:  # a read-only leftover (root could remove anything)
            onerror(os.unlink, str(stuck / "sub" / "a.step"), None)
            return None
        return real(path, onerror=onerror, **kw) if onerror else real(path, **kw)

    monkeypatch.setattr(atomic.shutil, "rmtree", rmtree)
    assert cli.main(["export", "--no-cache", "--out", str(out), "--only", "bom"]) == 0
    warnings = [ln for ln in capsys.readouterr().err.splitlines() if "warning" in ln]
    assert len(warnings) == 1 and f"{stuck} (0.0 MB)" in warnings[0]  # the folder, not its files
    assert warnings[0].startswith("tactcad: warning: could not remove 1 leftover path")


def _removal_denied(monkeypatch, folder: Path) -> None:
    """Removing anything in ``folder`` fails as for another user's files (root, as tests
    run in CI, could remove anything): each path is told to ``onerror`` with EACCES."""
    real = shutil.rmtree

    def rmtree(path, onerror=None, **kw):
        if Path(path) != folder:
            return real(path, onerror=onerror, **kw) if onerror else real(path, **kw)
        for p in sorted(folder.rglob("*"), reverse=True):
            try:
                raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), str(p))
            except PermissionError as exc:
                onerror(os.unlink, str(p), (PermissionError, exc, None))
        return None

    monkeypatch.setattr(atomic.shutil, "rmtree", rmtree)


def test_an_old_export_that_cannot_be_removed_is_named_and_the_next_run_removes_it(
        tmp_path, monkeypatch):
    out, staging = tmp_path / "ex", atomic.staging_dir(tmp_path / "ex")
    (out / "step").mkdir(parents=True)
    (out / "step" / "old.step").write_bytes(b"x" * 2_000_000)
    (staging / "new.txt").write_text("new")
    _removal_denied(monkeypatch, staging)  # after the swap it holds the old export

    with pytest.warns(UserWarning) as said:
        atomic.publish_dir(staging, out)

    assert (out / "new.txt").read_text() == "new"
    (text,) = [str(w.message) for w in said]
    assert f"the old export replaced in {out} could not be removed (permission denied" in text
    assert f"kept as {staging} (2.0 MB)" in text
    assert atomic.leftover_staging(out) == [staging]  # the next run finds it ...
    monkeypatch.undo()
    assert atomic.remove_tree(staging) == [] and atomic.leftover_staging(out) == []  # ... and can


def test_a_renamed_aside_old_export_is_a_leftover_too(tmp_path):
    aside = tmp_path / ".ex.old-abc"
    (aside / "old").mkdir(parents=True)
    assert atomic.leftover_staging(tmp_path / "ex") == [aside]


def test_an_export_whose_files_this_user_cannot_remove_is_refused_up_front(tmp_path,
                                                                          monkeypatch, capsys):
    """An old export of another user's (its folders not writable here) would stay hidden
    beside the new one: the export is refused before any work, naming the folder and why."""
    out = tmp_path / "ex"
    (out / "step").mkdir(parents=True)
    (out / "manifest.json").write_text("{}")
    real = os.access
    monkeypatch.setattr(atomic.os, "access", lambda p, mode, **kw: False
                        if Path(p) == out / "step" else real(p, mode, **kw))
    assert export(out, "--only", "bom") == 2
    err = capsys.readouterr().err
    assert "the export there cannot be replaced" in err
    assert f"({out / 'step'}: permission denied)" in err
    assert sorted(p.name for p in out.iterdir()) == ["manifest.json", "step"]
    assert atomic.leftover_staging(out) == []


@pytest.mark.parametrize("argv", [["stiffness", "--element", "1", "--design", "/no/such.toml"],
                                  ["calibrate", "--data", "/no/such.csv"],
                                  ["stiffness", "--element", "1", "--design", "/"]])
def test_a_missing_or_unreadable_input_file_is_bad_input(argv, capsys):
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and argv[-1] in err
