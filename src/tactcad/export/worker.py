"""A second process for an export run: the jobs marked ``worker`` (the
drawings, their PDF and PNG) run there while this process writes the STEP
files, scenes and images, so both cores work.

The worker is forked (one process of a
:class:`concurrent.futures.ProcessPoolExecutor`, fork context) as the run
starts, and only while this process has not loaded the CAD kernel:
OpenCascade's thread pool does not survive a fork, so a process that has built or meshed a solid never forks
(:func:`can_fork`), and the run then goes on in one process with the same
result. Forked first, both processes import the kernel at the same time.
The worker inherits the run and its jobs; it builds no solid: this process
builds each distinct part once and hands the worker the solids a job reads,
pickled (OpenCascade's binary BREP). Jobs in the worker run one at a time,
in the order they were handed over, so a job always finds the files of the
jobs it reads (``after``) when those were handed over before it.

``TACTCAD_WORKERS=0`` keeps every run in one process.
"""

from __future__ import annotations

import multiprocessing
import os
import pickle
import signal
import sys
import warnings
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Any, Mapping, Sequence

from tactcad.export.job import Job, Run

#: The run and its jobs by name, set before the fork for the worker to inherit.
_INHERITED: dict[str, Any] = {}

#: Modules the worker imports while it waits for its first job (the kernel and the drawings).
PRELOAD = ("tactcad.parts.registry", "tactcad.drawings.compose", "tactcad.drawings.pdf",
           "tactcad.export.render")


def can_fork() -> bool:
    """True if this process may fork a worker: two or more CPUs, the fork
    start method, ``TACTCAD_WORKERS`` not ``0``, and the CAD kernel not yet
    loaded here (see the module doc)."""
    return (os.environ.get("TACTCAD_WORKERS", "1") != "0"
            and (os.cpu_count() or 1) >= 2
            and "fork" in multiprocessing.get_all_start_methods()
            and "OCP" not in sys.modules)


def worker_jobs(todo: Sequence[Job], done: Mapping[str, Any]) -> list[Job]:
    """The jobs of ``todo`` that go to the worker: marked ``worker`` and reading
    only files of jobs already done or themselves going to the worker."""
    chosen: list[Job] = []
    names: set[str] = set()
    for job in todo:
        if job.worker and job.start is None and all(a in done or a in names for a in job.after):
            chosen.append(job)
            names.add(job.name)
    return chosen


class Worker:
    """The run's second process (see the module doc); :meth:`submit` hands it
    a job, :meth:`close` ends it once its jobs are done, :meth:`kill` at once
    (on an error or an interrupt). A worker that dies fails its jobs with
    :class:`concurrent.futures.process.BrokenProcessPool`; none is forked again."""

    def __init__(self, run: Run, jobs: Sequence[Job]):
        fork = multiprocessing.get_context("fork")
        self._pid = fork.Value("i", 0, lock=False)  # the worker's, for kill()
        self._blobs: dict[str, bytes | None] = {}  # part name -> its hand-over (see _hand_over)
        _INHERITED.update(run=run, jobs={j.name: j for j in jobs})
        try:
            self._pool = ProcessPoolExecutor(1, mp_context=fork, initializer=_start,
                                             initargs=(self._pid,))
            self._pool.submit(int)  # forks now, before the kernel loads here
        finally:
            _INHERITED.clear()  # the worker has its copy; this process needs none

    def submit(self, job: Job, solids: Mapping[str, Any]) -> "_JobFuture":
        """Hand ``job`` over with the solids it reads (by part name); the
        future's ``result()`` gives the job's records or raises its error, and
        warns here what the job warned there."""
        # written here, read in the job: a hand-over the worker cannot read
        # fails that job, never the pool's own reader (whose traceback would
        # reach the terminal)
        return _JobFuture(self._pool.submit(_run_job, job.name, _hand_over(solids, self._blobs)))

    def close(self) -> None:
        self._pool.shutdown(wait=True)

    def kill(self) -> None:
        if self._pid.value:
            try:
                os.kill(self._pid.value, signal.SIGKILL)
            except ProcessLookupError:
                pass
        self._pool.shutdown(wait=False, cancel_futures=True)


class _JobFuture:
    """A worker job's future: ``result()`` re-issues in this process the
    warnings the job issued in the worker (so the run reports each once),
    then gives the records."""

    def __init__(self, future: Future):
        self._future = future

    def result(self) -> list[dict]:
        records, issued = self._future.result()
        for message, category in issued:
            warnings.warn(message, category, stacklevel=2)
        return records

    def cancel(self) -> bool:
        return self._future.cancel()


def _start(pid) -> None:
    """The worker's start: it tells its pid, dies with the run's process and
    leaves Ctrl-C to it, then imports the kernel and the drawing modules."""
    pid.value = os.getpid()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:  # Linux: SIGKILL when the parent dies, so a killed run leaves no worker behind
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        if os.getppid() == 1:
            os._exit(1)
    except (OSError, AttributeError):
        pass
    import importlib

    for module in PRELOAD:
        importlib.import_module(module)


def _hand_over(solids: Mapping[str, Any], blobs: dict[str, bytes | None]) -> bytes:
    """The solids, pickled for the worker as build123d pickles them
    (OpenCascade's binary BinTools format), each one that reads back: the
    binary reader fails on some solids (the terminal board's plated holes:
    'UnExpected BRep_PointRepresentation'), and those the worker builds again
    from their specs, the same solid by the same builder. ``blobs`` keeps each
    part's hand-over (None: not readable) for the run's later jobs, so a part
    is written and tried once per run."""
    for name, solid in solids.items():
        if name not in blobs:
            blob = pickle.dumps(solid)
            try:
                pickle.loads(blob)
            except Exception:  # the kernel's reader raises its own failure types
                blob = None
            blobs[name] = blob
    return pickle.dumps({name: blobs[name] for name in solids if blobs[name] is not None})


def _run_job(name: str, handed: bytes) -> tuple[list[dict], list[tuple[str, type]]]:
    """The job's records and the warnings it issued (message, category), which
    the run's process reports (:class:`_JobFuture`). ``handed``: the solids
    the job reads, by part name (:func:`_hand_over`).

    Raises:
        BrokenProcessPool: the solids cannot be read; the run then makes the
            job itself, as for a worker that died.
    """
    try:
        solids = {part: pickle.loads(blob) for part, blob in pickle.loads(handed).items()}
    except Exception as exc:  # the kernel's reader raises its own failure types
        raise BrokenProcessPool(f"the solids handed to {name} cannot be read: {exc}") from None
    run: Run = _INHERITED["run"]
    for spec in {s.name: s for s in _INHERITED["jobs"][name].needs}.values():
        if spec.name in solids:  # else built here on first use (see _hand_over)
            run.parts.adopt(spec, solids[spec.name])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        records = _INHERITED["jobs"][name].make(run)
    return records, [(str(w.message), w.category) for w in caught]
