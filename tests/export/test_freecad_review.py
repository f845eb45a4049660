"""One FreeCAD process kept for many review runs (``tactcad watch``): the
same file bytes as a new process per run, and a run made again by a new
process when the kept one dies."""

from __future__ import annotations

import json
import os
import signal

import pytest

from tactcad.errors import FreecadAheadWarning
from tactcad.export import freecad_review as fr

pytestmark = pytest.mark.slow


def _assemblies(width_mm: float):
    import build123d as bd

    box, pin = bd.Box(width_mm, 4, 2), bd.Cylinder(1, 6)
    eye = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    moved = ((1.0, 0.0, 0.0, 12.0),) + eye[1:]
    parts = (fr.ReviewPart("plate", box, (0.6, 0.6, 0.7)), fr.ReviewPart("pin", pin, (0.9, 0.2, 0.1)))
    inst = (fr.ReviewInstance("plate", "plate", "base", eye),
            fr.ReviewInstance("pin_1", "pin", "pins", eye),
            fr.ReviewInstance("pin_2", "pin", "pins", moved))
    return [fr.ReviewAssembly("one", "one.step", parts, inst),
            fr.ReviewAssembly("two", "two.step", parts[:1], inst[:1])]


def _files(folder, width_mm):
    fr.write_review_files(folder, _assemblies(width_mm), lambda s: None)
    return {p.name: p.read_bytes() for p in sorted((folder / "review").glob("*.FCStd"))}


def test_a_kept_freecad_writes_the_bytes_of_a_new_one(freecad, tmp_path):
    fresh = [_files(tmp_path / f"fresh{k}", w) for k, w in enumerate((10.0, 11.0))]
    fr.keep_freecad(True)
    try:
        kept = [_files(tmp_path / f"kept{k}", w) for k, w in enumerate((10.0, 11.0, 10.0))]
        server = fr._Kept.server
        assert server is not None and server.alive  # one process answered all three runs
        assert kept == fresh + fresh[:1] and len(kept[0]) == 2
        # the kept process dies: the run is made by a new process, the same bytes
        os.kill(server._proc.pid, signal.SIGKILL)
        server._proc.wait()
        assert _files(tmp_path / "after-kill", 11.0) == fresh[1]
        assert fr._Kept.server is not server and fr._Kept.server.alive
    finally:
        fr.keep_freecad(False)
    assert fr._Kept.server is None and not server.alive


def test_a_run_whose_kept_freecad_dies_is_made_by_a_new_process(freecad, tmp_path, monkeypatch):
    fresh = _files(tmp_path / "fresh", 10.0)
    submit = fr.FreecadServer.submit

    def submit_and_die(self, payload, out):
        number = submit(self, payload, out)
        os.kill(self._proc.pid, signal.SIGKILL)
        return number

    fr.keep_freecad(True)
    try:
        monkeypatch.setattr(fr.FreecadServer, "submit", submit_and_die)
        assert _files(tmp_path / "died", 10.0) == fresh
        monkeypatch.setattr(fr.FreecadServer, "submit", submit)
        dead = fr._Kept.server
        assert _files(tmp_path / "next", 10.0) == fresh and fr._Kept.server is not dead
    finally:
        fr.keep_freecad(False)


def test_freecad_started_ahead_writes_the_bytes_of_a_new_one_and_ends_with_its_run(
        freecad, tmp_path):
    """An export starts FreeCAD while it imports the kernel (``start_freecad_ahead``): the
    run's review files are its one request, the same bytes a FreeCAD started for them
    writes, and it ends with that run; one no run took is ended by the function returned.
    A process forked meanwhile (the drawing worker) lets go of its stdin, so FreeCAD sees
    that pipe close when the run's process closes it."""
    fresh = _files(tmp_path / "fresh", 10.0)
    unclaimed = fr.start_freecad_ahead()
    server = fr._Ahead.server
    assert server is not None and server.alive
    child = os.fork()
    if child == 0:  # the forked worker's start: its copies of the pipes let go
        fr.forget_ahead_in_child()
        os._exit(0 if all(os.readlink(f"/proc/self/fd/{fd}") == os.devnull
                          for fd in server.fds()) else 1)
    _, status = os.waitpid(child, 0)
    assert os.waitstatus_to_exitcode(status) == 0
    assert _files(tmp_path / "ahead", 10.0) == fresh
    assert fr._Ahead.server is None and not server.alive  # ended with its run
    unclaimed()  # taken: nothing to end
    unclaimed = fr.start_freecad_ahead()
    left = fr._Ahead.server
    unclaimed()  # no run took it: ended
    assert fr._Ahead.server is None and not left.alive


def test_a_kept_freecad_answers_without_pythonunbuffered(freecad, tmp_path, monkeypatch):
    """FreeCAD's ``sys.stdout``, once its main window is shown, prints through C's stdout,
    block-buffered on a pipe unless PYTHONUNBUFFERED is set (a lab's shell, or the
    installed-wheel test's clean environment, does not set it): the serving script's
    answer goes to the pipe itself, so it comes as the request is done."""
    monkeypatch.delenv("PYTHONUNBUFFERED", raising=False)
    server = fr.FreecadServer()
    try:
        number = server.submit([], tmp_path / "result.json")
        server.wait(number, timeout_s=60.0)  # unanswered before: the line stayed in FreeCAD
        assert json.loads((tmp_path / "result.json").read_text())["files"] == {}
        assert server.alive
    finally:
        server.close()
    assert not server.alive


def test_freecad_started_ahead_that_gives_no_answer_is_replaced(freecad, tmp_path,
                                                                 monkeypatch):
    """A FreeCAD started ahead that gives no answer within ``AHEAD_ANSWER_S`` is ended; a
    FreeCAD started for the review files writes them, the same bytes, and one warning
    (the command's ``tactcad: warning:`` line) says so."""
    fresh = _files(tmp_path / "fresh", 10.0)

    def unsent(self, payload, out):  # a request FreeCAD never answers
        self._count += 1
        return self._count

    monkeypatch.setattr(fr, "AHEAD_ANSWER_S", 1.0)
    monkeypatch.setattr(fr.FreecadServer, "submit", unsent)
    unclaimed = fr.start_freecad_ahead()
    server, said = fr._Ahead.server, []
    try:
        with pytest.warns(FreecadAheadWarning) as caught:
            fr.write_review_files(tmp_path / "ahead", _assemblies(10.0), said.append)
        got = {p.name: p.read_bytes()
               for p in sorted((tmp_path / "ahead" / "review").glob("*.FCStd"))}
        assert got == fresh
        assert [str(w.message) for w in caught if w.category is FreecadAheadWarning] == [
            "the FreeCAD started ahead of the export gave no answer in 1 s: it was ended, "
            "and the review files were written by a FreeCAD started for them"]
        assert not [line for line in said if "no answer" in line]
        assert fr._Ahead.server is None and not server.alive
    finally:
        unclaimed()


def test_a_request_is_sent_without_waiting_on_freecad(freecad, tmp_path):
    """A request's payload (a large scene's is more than a pipe holds) goes in a file and
    the line on FreeCAD's stdin names it, so sending returns at once even while FreeCAD
    reads nothing (stopped here); before, the run's process waited in the write."""
    import threading

    server = fr.FreecadServer()
    os.kill(server._proc.pid, signal.SIGSTOP)
    sent = []
    try:
        payload = [{"name": "x" * 300_000, "parts": [], "groups": []}]
        sender = threading.Thread(target=lambda: sent.append(
            server.submit(payload, tmp_path / "result.json")), daemon=True)
        sender.start()
        sender.join(timeout=20.0)
        assert sent == [1]
    finally:
        server.end()  # killed, stopped or not: a write still waiting fails
    assert not server.alive
