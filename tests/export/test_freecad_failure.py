"""A FreeCAD that fails, and a run stopped as FreeCAD starts.

A ``freecadcmd`` that ends without its result costs the export its FreeCAD review files
only: the other files are written, the manifest lists what is there, one warning names
FreeCAD's exit and the file holding its output, and no store entry is kept (the next
export asks FreeCAD again). A stop that arrives while a program starts ends and reaps it:
no child of the run is left running or a zombie.
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
from contextlib import contextmanager
from pathlib import Path

import psutil
import pytest

from tactcad import cli, stopping
from tactcad.checks.export_files import export_files_group
from tactcad.checks.groups import CheckContext
from tactcad.export import freecad_review


def fake_freecadcmd(folder: Path, body: str) -> Path:
    """A ``freecadcmd`` shell script in ``folder`` running ``body``; the folder's path.

    Args:
        folder: where the script is written (made if missing).
        body: the script's shell lines.

    Returns:
        ``folder``, to put first on ``PATH``.
    """
    folder.mkdir(parents=True, exist_ok=True)
    exe = folder / "freecadcmd"
    exe.write_text("#!/bin/sh\n" + body + "\n")
    exe.chmod(0o755)
    return folder


def children() -> set[int]:
    """The PIDs of this process's children, running or zombies."""
    return {c.pid for c in psutil.Process().children()}


@pytest.mark.slow  # two exports of the review files
def test_a_failing_freecad_leaves_the_export_whole_without_its_review_files(
        tmp_path, monkeypatch, capsys):
    fake = fake_freecadcmd(tmp_path / "bin", 'echo "fc said out"\necho "fc said err" >&2\nexit 3')
    monkeypatch.setenv("PATH", f"{fake}:{os.environ['PATH']}")
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # FreeCAD's output is kept there
    out, cache = tmp_path / "ex", tmp_path / "cache"
    for attempt in (1, 2):  # not kept in the store: the second export runs FreeCAD again
        assert cli.main(["export", "--cache", str(cache), "--out", str(out),
                         "--only", "review"]) == 0
        err = capsys.readouterr().err
        assert "Traceback" not in err
        lines = [line for line in err.splitlines() if "FCStd" in line]
        assert len(lines) == 1 and "freecadcmd exited 3 without a result" in lines[0], err
        log = Path(lines[0].split("its output is in ")[1].split(")")[0])
        assert log.parent == tmp_path and "fc said out" in log.read_text()
        assert "fc said err" in log.read_text()
        log.unlink()
        man = json.loads((out / "manifest.json").read_text())
        assert "review/index.html" in {f["path"] for f in man["files"]}, attempt
        assert not any(f["path"].endswith(".FCStd") for f in man["files"])
        assert not list(out.rglob("*.FCStd"))
        assert [r["what"] for r in man["not_written"]] == ["review/*.FCStd"], attempt
        assert "freecadcmd exited 3" in man["not_written"][0]["reason"]
        assert all(p.endswith(".FCStd") for p in man["not_written"][0]["files"])
        found = list(export_files_group(CheckContext(None, out, None, edited={})))
        notes = [r for _, results in found for r in results if r.info]
        assert len(notes) == 1 and "once FreeCAD works" in notes[0].detail, found


def _export(*args: str) -> None:
    assert cli.main(["export", "--quiet", *args]) == 0


@pytest.mark.slow  # two exports of the review files
def test_a_failing_freecad_over_an_export_keeps_its_review_files_and_says_so(
        tmp_path, monkeypatch, capsys, freecad):
    """``--only review`` with a failing FreeCAD over an export holding the review files:
    the earlier files are kept and listed (``partial.kept``), no ``not_written`` record
    names them, and the warning says they are kept (before: a record naming the 5 files
    present and a warning saying the manifest did not list them)."""
    out = tmp_path / "ex"
    _export("--no-cache", "--out", str(out), "--only", "review")
    before = json.loads((out / "manifest.json").read_text())
    reviews = sorted(f["path"] for f in before["files"] if f["path"].endswith(".FCStd"))
    assert reviews
    fake = fake_freecadcmd(tmp_path / "bin", "exit 3")
    monkeypatch.setenv("PATH", f"{fake}:{os.environ['PATH']}")
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # FreeCAD's output is kept there
    capsys.readouterr()
    assert cli.main(["export", "--no-cache", "--out", str(out), "--only", "review"]) == 0
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "FCStd" in line]
    assert len(lines) == 1 and "freecadcmd exited 3" in lines[0], err
    assert "does not list the review files" not in lines[0]
    assert ("the earlier export's review files are kept as they were, listed in "
            "manifest.json under partial.kept") in lines[0]
    man = json.loads((out / "manifest.json").read_text())
    assert sorted(f["path"] for f in man["files"] if f["path"].endswith(".FCStd")) == reviews
    assert set(reviews) <= set(man["partial"]["kept"])
    assert all((out / p).is_file() for p in reviews)
    assert "not_written" not in man


@pytest.mark.slow  # an export of the review files
def test_a_partial_export_without_the_review_job_carries_the_not_written_record(
        tmp_path, monkeypatch):
    """After an export whose FreeCAD failed, a partial export that does not run the review
    job keeps the ``not_written`` record while the files are still absent (before: dropped)."""
    out, path = tmp_path / "ex", os.environ["PATH"]
    fake = fake_freecadcmd(tmp_path / "bin", "exit 3")
    monkeypatch.setenv("PATH", f"{fake}:{path}")
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # FreeCAD's output is kept there
    _export("--no-cache", "--out", str(out), "--only", "review")
    recorded = json.loads((out / "manifest.json").read_text())["not_written"]
    assert recorded and recorded[0]["files"]
    monkeypatch.setenv("PATH", path)  # FreeCAD works again; the review job does not run
    _export("--no-cache", "--out", str(out), "--only", "bom")
    man = json.loads((out / "manifest.json").read_text())
    assert man.get("not_written") == recorded
    assert not any((out / p).exists() for p in recorded[0]["files"])


#: ``tactcad`` with FreeCAD's wait patched: a process of its own, whose kernel is not loaded
#: yet, so the export starts FreeCAD ahead (it does not once the kernel is loaded here).
PATCHED_WAIT_CLI = ("import sys\nfrom tactcad.export import freecad_review\n"
                    "freecad_review.AHEAD_ANSWER_S = float(sys.argv[1])\n"
                    "from tactcad import cli\nsys.exit(cli.main(sys.argv[2:]))")


@pytest.mark.slow  # an export of the review files
def test_a_freecad_started_ahead_without_answer_is_one_warning_line(tmp_path, freecad):
    """The FreeCAD started ahead of the kernel import (its serving mode) that gives no answer
    in ``AHEAD_ANSWER_S`` is ended and the review files are written by a FreeCAD started
    for them; ``tactcad export`` says so in one ``tactcad: warning:`` line (before, the
    line went to the run's log, which the command discards)."""
    import sys

    real = Path(freecad).resolve()
    fake = fake_freecadcmd(tmp_path / "bin", 'if [ -n "$TACTCAD_FC_SERVE" ]; then exec sleep 60; '
                                             f'fi\nexec "{real}" "$@"')
    env = dict(os.environ, PATH=f"{fake}:{os.environ['PATH']}")
    env.pop("TACTCAD_WORKERS", None)  # the export forks, and so starts FreeCAD ahead
    out = tmp_path / "ex"
    done = subprocess.run([sys.executable, "-c", PATCHED_WAIT_CLI, "2", "export", "--no-cache",
                           "--out", str(out), "--only", "review"], env=env, cwd=tmp_path,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    said = [line for line in done.stderr.splitlines() if "no answer" in line]
    assert said == ["tactcad: warning: the FreeCAD started ahead of the export gave no answer "
                    "in 2 s: it was ended, and the review files were written by a FreeCAD "
                    "started for them"], done.stderr
    man = json.loads((out / "manifest.json").read_text())
    assert [f["path"] for f in man["files"] if f["path"].endswith(".FCStd")]
    assert "not_written" not in man


@contextmanager
def _stopped_as_held(stops: list[int] | None = None):
    """A :func:`tactcad.stopping.stop_signals_held` during which Ctrl-C came: raised
    as the hold ends, the program started within it already running. With ``stops``,
    only a hold in which a child was started raises (noted in ``stops``)."""
    before = children()
    yield
    if stops is None or children() - before:
        if stops is not None:
            stops.append(1)
        raise KeyboardInterrupt


@pytest.mark.slow  # an export of the review files
def test_a_stop_as_freecad_starts_leaves_no_child_running_or_a_zombie(tmp_path, monkeypatch):
    fake = fake_freecadcmd(tmp_path / "bin", "exec sleep 60")
    monkeypatch.setenv("PATH", f"{fake}:{os.environ['PATH']}")
    monkeypatch.setenv("TACTCAD_WORKERS", "0")  # FreeCAD the only child: started for its run
    before, stops = children(), []
    monkeypatch.setattr(stopping, "stop_signals_held", lambda **kw: _stopped_as_held(stops))
    monkeypatch.setattr(freecad_review, "stop_signals_held",
                        lambda **kw: _stopped_as_held(stops), raising=False)
    try:
        code = cli.main(["export", "--no-cache", "--quiet", "--out", str(tmp_path / "ex"),
                         "--only", "review"])
    except KeyboardInterrupt:
        code = None
    assert stops == [1] and code != 0  # stopped as FreeCAD started
    left = children() - before
    assert not left, [(p, psutil.Process(p).status()) for p in left]
    assert not (tmp_path / "ex").exists()


def test_a_program_started_as_a_stop_came_is_ended_and_reaped(monkeypatch):
    monkeypatch.setattr(stopping, "stop_signals_held", lambda **kw: _stopped_as_held())
    before = children()
    with pytest.raises(KeyboardInterrupt):
        stopping.popen_held(["sleep", "60"])
    assert children() == before


def test_the_programs_started_are_ended_and_reaped_at_the_end():
    before = children()
    proc = stopping.popen_held(["sleep", "60"])
    done = stopping.popen_held(["true"])
    done.wait()
    stopping.end_programs(wait_s=5.0)
    assert proc.returncode is not None and children() == before


def test_a_program_ignoring_sigterm_is_killed():
    proc = subprocess.Popen(["sh", "-c", "trap '' TERM; echo ready; while :; do sleep 0.1; done"],
                            stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline() == "ready\n"
    stopping.end_program(proc, wait_s=0.3)
    proc.stdout.close()
    assert proc.returncode == -9
