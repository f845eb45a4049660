"""A second process for an export run: the jobs marked ``worker`` (the
drawings, their PDF and PNG) run there while this process writes the STEP
files, scenes and images, so both cores work.

The worker is forked (one process of a
:class:`concurrent.futures.ProcessPoolExecutor`, fork context) as the run
starts (the stop signals held meanwhile:
:func:`tactcad.stopping.stop_signals_held`), and only while this process
has not loaded the CAD kernel:
OpenCascade's thread pool does not survive a fork, so a process that has built or meshed a solid never forks
(:func:`can_fork`), and the run then goes on in one process with the same
result. The kernel's modules are imported here just before the fork
(:func:`load_before_fork`: an import builds no solid and starts no thread), so
the worker inherits them instead of importing them again (about a sixth of a
cold export's CPU seconds).
The worker inherits the run and its jobs; it builds no solid: this process
builds each distinct part once and hands the worker the solids a job reads,
pickled (OpenCascade's binary BREP). Jobs in the worker run one at a time,
in the order they were handed over, so a job always finds the files of the
jobs it reads (``after``) when those were handed over before it. The run's
process, with nothing of its own left to make but jobs that read the
worker's files, takes back the last of the worker's jobs not yet begun
(:func:`tactcad.export.run.run_jobs`), so neither process waits while the
other has a queue.

``tactcad watch`` keeps one worker for its whole session
(:class:`SessionWorker`): started by the ``spawn`` method, so it does not
matter that the watching process has loaded the kernel, and told each run
what it needs (the validated project, the staging folder, the store and the
function that plans the run's jobs), from which it plans the same jobs
again; it keeps the solids it was handed by their content, so a run hands
over only the parts that changed.

Either worker is ended by its parent's handle on the process (kept from the
moment it starts: :class:`_Started`), SIGKILL and reaped: a stop does not
wait for the pool's own shutdown, nor for the worker to have started.

``TACTCAD_WORKERS=0`` keeps every run in one process.
"""

from __future__ import annotations

import multiprocessing
import os
import pickle
import signal
import sys
import time
import warnings
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Any, Callable, Collection, Mapping, Sequence

from tactcad.export.job import Job, Run, solid_key
from tactcad.stopping import (pool_shut_down, spawn_ready, stop_signals_held,
                              stop_signals_unblocked)

#: The run and its jobs by name: set before the fork for a worker forked per
#: run to inherit, or by each run's first message to a session worker.
_INHERITED: dict[str, Any] = {}
#: A session worker's solids and meshes by content key, kept across runs.
_KEPT: dict[str, dict] = {"solids": {}, "meshes": {}}
#: What a session worker's run logged since the last job (sent back with its records).
_LOGGED: list[str] = []

#: Modules the worker needs (the kernel and the drawings): a worker forked for a run inherits
#: them (:func:`load_before_fork`), one kept across runs (``tactcad watch``) imports them
#: while it waits for its first job.
PRELOAD = ("build123d", "tactcad.solids.build", "tactcad.drawings.compose",
           "tactcad.drawings.pdf", "tactcad.export.render")


def can_fork() -> bool:
    """True if this process may fork a worker: two or more CPUs, the fork
    start method, ``TACTCAD_WORKERS`` not ``0``, and the CAD kernel not yet
    loaded here (see the module doc)."""
    return (os.environ.get("TACTCAD_WORKERS", "1") != "0"
            and (os.cpu_count() or 1) >= 2
            and "fork" in multiprocessing.get_all_start_methods()
            and "OCP" not in sys.modules)


def load_before_fork() -> None:
    """Import :data:`PRELOAD` (the CAD kernel, OCP and build123d, with the drawing modules)
    in this process, where :func:`can_fork` holds, just before the worker is forked: the
    worker then inherits the modules instead of importing them itself (1.5-2 CPU s on
    two cores), and this process needs most of them for its own jobs. Importing builds no
    solid and starts no kernel thread (OpenCascade's thread pool starts with the first
    build or mesh), so the fork stays safe."""
    import importlib

    for module in PRELOAD:
        importlib.import_module(module)


def can_spawn() -> bool:
    """True if a session worker may be started: two or more CPUs and
    ``TACTCAD_WORKERS`` not ``0`` (``spawn`` starts a new interpreter, so the
    kernel loaded here does not matter)."""
    return os.environ.get("TACTCAD_WORKERS", "1") != "0" and (os.cpu_count() or 1) >= 2


def session_worker() -> "SessionWorker | None":
    """A :class:`SessionWorker` when one may be started (:func:`can_spawn`) and
    the system gives a process; else None (every run makes all its jobs)."""
    if not can_spawn():
        return None
    try:
        return SessionWorker()
    except OSError:
        return None


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


#: the attribute a job's error raised in the worker carries back: (its warnings, its
#: logged lines), which the run's process says before the error
ISSUED_BEFORE = "issued_in_worker"

class Worker:
    """The run's second process (see the module doc); :meth:`submit` hands it
    a job, :meth:`close` ends it once its jobs are done, :meth:`kill` at once
    (on an error or an interrupt). A worker that dies fails its jobs with
    :class:`concurrent.futures.process.BrokenProcessPool`; none is forked again."""

    def __init__(self, run: Run, jobs: Sequence[Job], kernel: bool = False):
        """Fork the worker for ``run``'s ``jobs``; ``kernel``: the run builds solids, so the
        kernel's modules are imported here first and inherited (:func:`load_before_fork`).

        Raises:
            OSError: no process to be had (memory, process limit).
        """
        self._context = _Started("fork")
        self._blobs: dict[str, bytes | None] = {}  # part name -> its hand-over (see _hand_over)
        if kernel:
            load_before_fork()  # the worker inherits the kernel's modules (see the module doc)
        _INHERITED.update(run=run, jobs={j.name: j for j in jobs})
        try:
            self._pool = _started_pool(self._context)  # forks now, before any solid is built
        finally:
            _INHERITED.clear()  # the worker has its copy; this process needs none

    def submit(self, job: Job, solids: Mapping[str, Any]) -> "_JobFuture":
        """Hand ``job`` over with the solids it reads (by part name); the
        future's ``result()`` gives the job's records or raises its error, and
        warns here what the job warned there."""
        # written here, read in the job: a hand-over the worker cannot read
        # fails that job, never the pool's own reader (whose traceback would
        # reach the terminal)
        return _JobFuture(self._pool.submit(_run_job, job.name, _hand_over(solids, self._blobs)),
                          lambda line: None)

    def close(self) -> None:
        self._pool.shutdown(wait=True)

    def kill(self) -> None:
        _kill(self._context.processes)
        pool_shut_down(self._pool, KILL_REAP_S)


def prepared_there(run: Run) -> bool:
    """True if a job's ``prepare`` run in another process (:class:`Preparing`) serves this
    process: the run's store has a folder, where that process keeps the results
    (:func:`tactcad.store.kept_result`) this process then reads back, warnings and all; a
    store of no folder keeps nothing
    between processes, so the run's process prepares for itself.

    Args:
        run: the export run.

    Returns:
        True when the run's store has a folder.
    """
    return run.store.root is not None


def _run_prepare(name: str) -> None:
    """A job's ``prepare`` in the :class:`Preparing` process: its results kept in the
    run's store (:func:`tactcad.export.jobs.keeping_run_results`), where the run's process
    reads them back and issues their warnings there; none is issued here."""
    from tactcad.export.jobs import keeping_run_results

    run: Run = _INHERITED["run"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # issued again where the kept value is read
        with keeping_run_results(run):
            _INHERITED["prepares"][name](run)


class _Started:
    """The multiprocessing context (``method``: ``fork`` or ``spawn``) a pool
    is given, keeping each process the pool makes with it (``processes``):
    its parent's handle, so the process can be killed from the moment it
    starts, before it has run a line (the pool's own list is private)."""

    def __init__(self, method: str):
        self._context = multiprocessing.get_context(method)
        self.processes: list = []

    def __getattr__(self, name: str):
        return getattr(self._context, name)

    def Process(self, *args, **kwargs):  # noqa: N802 (multiprocessing's name)
        process = self._context.Process(*args, **kwargs)
        self.processes.append(process)
        return process


def _started_pool(context: _Started) -> ProcessPoolExecutor:
    """A one-process pool on ``context``, its process started now with the
    stop signals held (:func:`tactcad.stopping.stop_signals_held`: never left
    half-started by a Ctrl-C; one that came meanwhile raises once it is
    whole, after the process is killed here).

    Raises:
        OSError: no process to be had (memory, process limit).
        KeyboardInterrupt: a stop came while the process started.
    """
    if context.get_start_method() == "spawn":
        spawn_ready()
    try:
        with stop_signals_held():
            pool = ProcessPoolExecutor(1, mp_context=context, initializer=_start)
            pool.submit(int)  # starts it now (spawn: it loads the kernel while the run plans)
    except BaseException:
        _kill(context.processes)
        raise
    return pool


def _kill(processes: Sequence) -> None:
    """SIGKILL each of ``processes`` that was started and reap it (the pool's
    shutdown is not waited for: a worker killed mid-transfer can leave it
    waiting on a pipe)."""
    started = [p for p in processes if p.pid is not None]
    for process in started:
        process.kill()
    deadline = time.monotonic() + KILL_REAP_S
    for process in started:
        # the pool's own thread may reap it first: this join then finds no child and
        # returns before that thread has set the exit code; ask again until it has
        while process.exitcode is None and time.monotonic() < deadline:
            process.join(0.05)
            if process.exitcode is None:
                time.sleep(0.001)


#: Seconds a killed worker is waited for to be reaped (it ends at once).
KILL_REAP_S = 5.0


class NotMadeHere(BrokenProcessPool):
    """A job the worker could not make although it runs (its solids did not
    read back, or it plans the job otherwise): the run makes it itself."""


class SessionWorker:
    """The worker of a ``tactcad watch`` session (see the module doc), kept
    from :meth:`__init__` to :meth:`close`. :meth:`begin` readies it for one
    run and gives that run's hand-over (the interface of :class:`Worker`). A
    worker that died, or was killed with an interrupted run, is started again
    for the next run; its run's jobs are made by the run itself meanwhile."""

    def __init__(self):
        self._pool: ProcessPoolExecutor | None = None
        self.broken = True
        self._start()

    def _start(self) -> None:
        self._context = _Started("spawn")
        self._blobs: dict[str, bytes | None] = {}  # content key -> hand-over the worker holds
        self._pool = _started_pool(self._context)
        self.broken = False

    @property
    def pid(self) -> int:
        """The worker's process id (0: none started)."""
        return next((p.pid for p in self._context.processes if p.pid is not None), 0)

    def begin(self, run: Run, planner: Callable[[Run], Sequence[Job]]) -> "_SessionRun | None":
        """Ready the worker for ``run``, whose jobs ``planner(run)`` plans (a
        module-level function, so it can be sent); None when it cannot be
        sent or no worker can be started (the run then makes every job)."""
        try:
            if self.broken:
                pool_shut_down(self._pool, KILL_REAP_S)
                self._start()
            context = pickle.dumps((run.project, run.staging, run.store, run.dxf_version, planner))
            self._pool.submit(_begin_run, context)
        except (pickle.PicklingError, TypeError, AttributeError):  # a planner made in place
            return None
        except (OSError, RuntimeError):  # no process to be had; or the pool is broken
            self.broken = True
            return None
        return _SessionRun(self, run.log)

    def keep_only(self, keys: Collection[str]) -> None:
        """Forget the hand-overs of parts whose content key is not in ``keys``
        (the worker drops those solids itself as its next run begins)."""
        from tactcad.export.live_parts import keep_only

        keep_only(keys, self._blobs)

    def kill(self) -> None:
        """End the worker at once (its run was interrupted); the next run starts another."""
        self.broken = True
        _kill(self._context.processes)
        pool_shut_down(self._pool, KILL_REAP_S)

    def close(self) -> None:
        """End the worker (the session ends): at once, as :meth:`kill`."""
        self.kill()


class _SessionRun:
    """One run's hand-over to a :class:`SessionWorker`: solids by content
    (:func:`solid_key`), each sent once per session."""

    def __init__(self, session: SessionWorker, log: Callable[[str], None]):
        self._session, self._log = session, log

    def submit(self, job: Job, solids: Mapping[str, Any]) -> "_JobFuture":
        session = self._session
        keyed = {solid_key(s): solids[s.name] for s in job.needs}
        new = {k: solid for k, solid in keyed.items() if k not in session._blobs}
        try:
            future = session._pool.submit(_run_job, job.name, _hand_over(new, session._blobs),
                                          job.key)
        except RuntimeError as exc:  # BrokenProcessPool (a RuntimeError) or shut down
            future = Future()
            future.set_exception(BrokenProcessPool(str(exc)))
        return _JobFuture(future, self._log, session)

    def close(self) -> None:  # the session keeps its worker
        pass

    def kill(self) -> None:
        self._session.kill()


class _JobFuture:
    """A worker job's future: ``result()`` re-issues in this process the
    warnings the job issued in the worker (so the run reports each once) and
    logs what the job logged there, then gives the records."""

    def __init__(self, future: Future, log: Callable[[str], None],
                 session: SessionWorker | None = None):
        self._future, self._log, self._session = future, log, session

    def result(self) -> list[dict]:
        try:
            records, issued, logged = self._future.result()
        except BrokenProcessPool as exc:
            if self._session is not None and not isinstance(exc, NotMadeHere):
                self._session.broken = True  # the process is gone: the next run starts one
            raise
        except Exception as exc:  # the job's own error: what it warned and logged first
            self._reissue(*getattr(exc, ISSUED_BEFORE, ((), ())))
            raise
        self._reissue(issued, logged)
        return records

    def _reissue(self, issued, logged) -> None:
        for line in logged:
            self._log(line)
        for said in issued:
            if isinstance(said, Warning):
                warnings.warn(said, stacklevel=3)
            else:
                message, category = said
                warnings.warn(message, category, stacklevel=3)

    def done(self) -> bool:
        """True once the job has finished (or failed) in the worker."""
        return self._future.done()

    def cancel(self) -> bool:
        return self._future.cancel()


def _start() -> None:
    """The worker's start: it leaves Ctrl-C to the run's process, ends at once
    on the other stop signals and with the run's process (:func:`_child_start`),
    lets go of a FreeCAD started ahead by that process
    (:func:`tactcad.export.freecad_review.forget_ahead_in_child`), then imports the
    kernel and the drawing modules."""
    _child_start()
    if "tactcad.export.freecad_review" in sys.modules:  # else no FreeCAD was started
        from tactcad.export.freecad_review import forget_ahead_in_child

        forget_ahead_in_child()
    import importlib

    for module in PRELOAD:
        importlib.import_module(module)


def _child_start() -> None:
    """A child process's first act: Ctrl-C left to the run's process, the other stop
    signals end it at once (:func:`tactcad.stopping.stop_signals_unblocked`), and so does
    the end of the run's process (Linux's PR_SET_PDEATHSIG), so a killed run leaves no
    process behind."""
    stop_signals_unblocked()
    try:  # Linux: SIGKILL when the parent dies, so a killed run leaves no worker behind
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        if os.getppid() == 1:
            os._exit(1)
    except (OSError, AttributeError):
        pass


class Preparing:
    """The ``prepare`` of a run's jobs (the review page's design facts: kernel-free) in a
    process of their own, forked before the run's process imports the CAD kernel, so the
    facts are worked out on the second core while this one loads the kernel (about 1.5 CPU
    s, with one core otherwise idle) and the drawing worker, forked after that import,
    starts on its drawings at once. Its results are kept in the run's store (a store with a
    folder: :func:`prepared_there`), where each job reads them back, warnings and all.

    :meth:`result` waits for the process; :meth:`kill` ends it at once (a failed or
    interrupted run). A process that fails or dies leaves the work to the jobs, which do it
    as they would have (the failure is theirs to say)."""

    def __init__(self, run: Run, jobs: Sequence[Job]):
        """Fork the process for the ``prepare`` of ``jobs``, in their order.

        Raises:
            OSError: no process to be had (memory, process limit).
        """
        self._context = _Started("fork")
        _INHERITED.update(run=run, prepares={j.name: j.prepare for j in jobs})
        try:
            with stop_signals_held():
                process = self._context.Process(target=_prepare_all,
                                                args=([j.name for j in jobs],), daemon=True)
                process.start()
        except BaseException:
            _kill(self._context.processes)
            raise
        finally:
            _INHERITED.clear()  # the process has its copy; this one needs none
        self._process = process

    def result(self) -> None:
        """Wait for every ``prepare`` to be kept.

        Raises:
            RuntimeError: the process failed or died (the jobs then work it out themselves).
        """
        self._process.join()
        if self._process.exitcode != 0:
            raise RuntimeError(f"the jobs' prepare process ended with {self._process.exitcode}")

    def kill(self) -> None:
        """End the process at once and reap it."""
        _kill(self._context.processes)


def _prepare_all(names: Sequence[str]) -> None:
    """The :class:`Preparing` process: each named job's ``prepare`` (:func:`_run_prepare`);
    an error ends it with code 1, silently (the job meets it again and says it)."""
    _child_start()
    try:
        for name in names:
            _run_prepare(name)
    except BaseException:
        sys.exit(1)


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


def _begin_run(context: bytes) -> None:
    """A session worker's start of a run: the run and its jobs, planned here
    as the run's process planned them (see :class:`SessionWorker`)."""
    from tactcad.export.live_parts import LiveParts, keep_only

    _INHERITED.clear()  # a run that cannot begin leaves no other run's jobs to find
    project, staging, store, dxf_version, planner = pickle.loads(context)
    run = Run(project, staging, _LOGGED.append, store, dxf_version)
    run.parts = LiveParts(project.plan, _KEPT["solids"], _KEPT["meshes"])
    jobs = planner(run)
    # the parts of earlier designs are not needed again: memory stays that of one design
    keep_only({solid_key(s) for j in jobs for s in j.needs}, _KEPT["solids"], _KEPT["meshes"])
    _INHERITED.update(run=run, jobs={j.name: j for j in jobs}, by_content=True)


def carried_warning(message: Warning | str, category: type[Warning]
                    ) -> Warning | tuple[str, type[Warning]]:
    """A warning the worker issued, as it is sent back to the run's process: its own object
    where that pickles and reads back, so it keeps what it carries beside its text (a
    :class:`~tactcad.mechanics.gauge_strain.GaugeStrainRangeWarning`'s ``error_rel``, the
    figure a run's closing line on alike warnings reports); else its text and category.

    Args:
        message: the warning as caught (``warnings.WarningMessage.message``).
        category: its category.

    Returns:
        The warning object, or (its text, its category).
    """
    if isinstance(message, Warning):
        try:
            pickle.loads(pickle.dumps(message))
            return message
        except Exception:  # a library's warning may hold what does not pickle
            pass
    return str(message), category


def _run_job(name: str, handed: bytes, key: str | None = None
             ) -> tuple[list[dict], list[Warning | tuple[str, type[Warning]]], list[str]]:
    """The job's records, the warnings it issued (:func:`carried_warning`) and the
    lines it logged, which the run's process reports (:class:`_JobFuture`).
    ``handed``: the solids the job reads (:func:`_hand_over`), by part name,
    or by content (:func:`solid_key`) in a session worker, which keeps them.
    ``key``: the job's content key, checked against the job planned here.

    Raises:
        NotMadeHere: the solids cannot be read, or the job is not planned
            here as in the run; the run then makes the job itself, as for a
            worker that died (the worker itself is sound).
    """
    try:
        solids = {part: pickle.loads(blob) for part, blob in pickle.loads(handed).items()}
    except Exception as exc:  # the kernel's reader raises its own failure types
        raise NotMadeHere(f"the solids handed to {name} cannot be read: {exc}") from None
    job = _INHERITED.get("jobs", {}).get(name)
    if job is None or (key is not None and job.key != key):
        raise NotMadeHere(f"{name} is not planned in the worker as in the run")
    run: Run = _INHERITED["run"]
    by_content = _INHERITED.get("by_content", False)
    for spec in {s.name: s for s in job.needs}.values():
        got = solids.get(solid_key(spec) if by_content else spec.name)
        if got is not None:  # else built here on first use (see _hand_over), or kept
            run.parts.adopt(spec, got)
    _LOGGED.clear()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            records = job.make(run)
        except Exception as exc:  # its warnings go back with it: said before the error
            setattr(exc, ISSUED_BEFORE, ([carried_warning(w.message, w.category)
                                          for w in caught], _LOGGED[:]))
            raise
    # kept here as it finishes: a run stopped or killed before collecting it keeps it too
    run.store.keep(job.key, run.staging, records)
    return records, [carried_warning(w.message, w.category) for w in caught], _LOGGED[:]
