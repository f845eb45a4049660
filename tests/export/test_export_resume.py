"""A stopped export keeps its finished jobs in the store, and only there.

Jobs here are small stand-ins that write one text file each, so the run's
order of work is the subject, not the CAD: the first export puts a set in
place, the second is stopped (``KeyboardInterrupt``) in its third job, the
third finishes what the second left.
"""

from __future__ import annotations

import pytest

from conftest import file_digests
from tactcad.atomic import changed_paths, forget_changed
from tactcad.export.job import Job
from tactcad.export.run import _write_set
from tactcad.store import Store, content_key

NAMES = ("one", "two", "three", "four")


def _jobs(edition: str, made: list[str], stop_at: str | None = None):
    """The run's planner: one job per name of :data:`NAMES`, writing ``<name>.txt``
    with ``edition`` in it (so each edition has its own keys); the job ``stop_at``
    raises ``KeyboardInterrupt`` as Ctrl-C would in the middle of its work."""

    def job(name: str) -> Job:
        def make(run):
            if name == stop_at:
                raise KeyboardInterrupt
            (run.staging / f"{name}.txt").write_text(f"{name} {edition}\n")
            made.append(name)
            return [{"path": f"{name}.txt", "part": name, "kind": "text"}]

        return Job(name, content_key("resume test", name, edition), make)

    return lambda run: [job(name) for name in NAMES]


def _export(project, out, store, edition, made, stop_at=None):
    return _write_set(out, _jobs(edition, made, stop_at), project, lambda s: None, store,
                      with_manifest=True)


def test_a_stopped_export_keeps_its_finished_jobs_for_the_next_run(project, tmp_path):
    out, store = tmp_path / "ex", Store(tmp_path / "store")
    _export(project, out, store, "first", [])
    before = file_digests(out)

    made: list[str] = []
    with pytest.raises(KeyboardInterrupt):
        _export(project, out, store, "second", made, stop_at="three")
    assert made == ["one", "two"]
    # the export folder is all or nothing: the first set, whole, and no staging left
    assert file_digests(out) == before
    assert not list(tmp_path.glob(".ex.staging-*"))

    made.clear()
    result = _export(project, out, store, "second", made)
    assert made == ["three", "four"]  # the two finished before the stop came from the store
    assert (result.jobs_run, result.jobs_reused) == (2, 2)
    assert {p: (out / f"{p}.txt").read_text() for p in NAMES} == {
        p: f"{p} second\n" for p in NAMES}


def test_a_keep_stopped_part_way_leaves_no_entry(tmp_path, monkeypatch):
    import tactcad.store as store_mod

    staging = tmp_path / "staging"
    staging.mkdir()
    (staging / "a.txt").write_text("a\n")
    store = Store(tmp_path / "store")

    def stopped(*_args, **_kw):
        raise KeyboardInterrupt

    monkeypatch.setattr(store_mod, "file_sha256", stopped)
    with pytest.raises(KeyboardInterrupt):
        store.keep("ab" + "0" * 62, staging, [{"path": "a.txt"}])
    assert [p for p in (tmp_path / "store").rglob("*") if p.is_file()] == []


def test_a_store_entry_is_not_among_the_files_an_interrupt_names(tmp_path):
    forget_changed()
    store = Store(tmp_path / "store")
    store.remember("cd" + "1" * 62, {"value": 1})
    assert store.recall("cd" + "1" * 62) == (True, {"value": 1})
    assert changed_paths() == []


def test_a_store_entry_is_written_without_fsync_and_a_damaged_one_is_a_miss(tmp_path,
                                                                          monkeypatch):
    """A store entry is not flushed to the disk (milliseconds each, a second of a cold
    export); what a power cut could leave of it (nothing, or its start) reads as a miss.
    An export's own files still are flushed."""
    import os

    from tactcad.atomic import write_bytes_atomic

    synced = []
    real_fsync = os.fsync
    monkeypatch.setattr(os, "fsync", lambda fd: synced.append(fd) or real_fsync(fd))
    store, key = Store(tmp_path / "store"), "cd" + "3" * 62
    store.remember(key, {"value": list(range(100))})
    assert synced == [] and store.recall(key) == (True, {"value": list(range(100))})
    kept = store._memo_path(key)
    whole = kept.read_bytes()
    for damaged in (b"", whole[: len(whole) // 2], b"\0" * len(whole)):
        kept.write_bytes(damaged)
        assert store.recall(key) == (False, None)
    write_bytes_atomic(tmp_path / "export" / "a.txt", b"a")
    assert len(synced) == 1


def test_an_interrupted_export_names_no_store_entry(tmp_path, monkeypatch, capsys):
    """The line a stopped export ends with is about the lab's files: what the run kept in
    its store (a projected view, a solve) is no file it wrote for them."""
    from tactcad import cli
    from tactcad.commands import export as export_cmd

    def kept_then_interrupted(args):
        Store(tmp_path / "store").remember("ef" + "2" * 62, [1, 2, 3])
        raise KeyboardInterrupt

    monkeypatch.setattr(export_cmd, "run", kept_then_interrupted)
    assert cli.main(["export", "--out", str(tmp_path / "ex")]) == cli.EXIT_INTERRUPTED
    assert capsys.readouterr().err.strip() == \
        "tactcad: interrupted; the previous files are left as they were"


def test_the_worker_keeps_each_job_as_it_finishes(project, tmp_path, monkeypatch):
    """A job made in the run's second process is in the store before the run collects it,
    so a run killed between the two keeps it all the same."""
    import pickle

    import tactcad.export.worker as worker_mod
    from tactcad.export.job import Run

    staging = tmp_path / "staging"
    staging.mkdir()
    store = Store(tmp_path / "store")
    run = Run(project, staging, lambda s: None, store)
    made: list[str] = []
    jobs = {job.name: job for job in _jobs("worker", made)(run)}
    monkeypatch.setattr(worker_mod, "_INHERITED", {"run": run, "jobs": jobs})
    records, _, _ = worker_mod._run_job("two", pickle.dumps({}), jobs["two"].key)

    fetched = tmp_path / "fetched"
    assert store.fetch(jobs["two"].key, fetched) == records
    assert (fetched / "two.txt").read_text() == "two worker\n"
