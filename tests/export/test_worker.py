"""The export run's second process: jobs marked ``worker`` run there in the
order handed over, the records come back in job order, a worker that dies
leaves its jobs to the main process, and a process that has loaded the CAD
kernel never forks one."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent('''
    import json, os, sys
    from pathlib import Path
    from tactcad.design.project import load_project
    from tactcad.export.job import Job, Run
    from tactcad.export.run import run_jobs
    from tactcad.store import Store

    staging, die = Path(sys.argv[1]), sys.argv[2] == "die"
    main_pid = os.getpid()
    if sys.argv[2] == "nofork":  # the system has no process to give
        import errno
        import tactcad.export.worker as worker

        def refuse(*args, **kwargs):
            raise OSError(errno.EAGAIN, "Resource temporarily unavailable")
        worker.ProcessPoolExecutor = refuse

    def writer(name, reads=()):
        def make(run):
            if die and name == "w1" and os.getpid() != main_pid:
                os._exit(9)  # the worker dies in its first job
            text = "".join((run.staging / r).read_text() for r in reads) + name
            (run.staging / name).write_text(text)
            return [{"path": name, "part": name, "kind": "test", "pid": os.getpid()}]
        return make

    jobs = [Job("a", "ka", writer("a")),
            Job("w1", "k1", writer("w1"), worker=True),
            Job("w2", "k2", writer("w2", ("w1",)), after=("w1",), worker=True),
            Job("w3", "k3", writer("w3", ("a",)), after=("a",), worker=True),
            Job("z", "kz", writer("z", ("w2", "w3")), after=("a", "w1", "w2", "w3"))]
    if sys.argv[2] == "order":  # a job waits for the worker while another could run
        import time
        stamps = {}

        def stamped(name, seconds=0.0, until=None):
            def make(run):
                start = time.time()
                (run.staging / f"{name}.begun").touch()
                while until is not None and not (run.staging / until).exists():
                    time.sleep(0.01)
                time.sleep(seconds)
                return [{"path": name, "part": name, "kind": "test", "pid": os.getpid(),
                         "start": start, "end": time.time()}]
            return make

        def prepare(run):
            stamps["prepared"] = time.time()
        jobs = [Job("w0", "k0", stamped("w0"), worker=True),  # a worker is forked for 2 or more
                Job("w1", "k1", stamped("w1", 1.5), worker=True),
                Job("y", "ky", stamped("y"), after=("w1",), prepare=prepare),
                # x lasts till the worker has begun w1, which it then keeps (a job not begun
                # this process takes back when it waits)
                Job("x", "kx", stamped("x", until="w1.begun"))]
        records, ran = run_jobs(Run(load_project(), staging, print), jobs, Store(None))
        print(json.dumps({"records": records, **stamps}))
        sys.exit(0)
    if sys.argv[2] == "takeback":  # this process waits for the worker, which has a queue
        import time

        def slept(name, seconds=0.0):
            def make(run):
                time.sleep(seconds)
                (run.staging / name).write_text(name)
                return [{"path": name, "part": name, "kind": "test", "pid": os.getpid()}]
            return make
        jobs = [Job("w0", "k0", slept("w0", 1.5), worker=True),
                Job("w1", "k1", slept("w1"), worker=True),
                Job("w2", "k2", slept("w2"), after=("w1",), worker=True),
                Job("w3", "k3", slept("w3"), worker=True),
                Job("w4", "k4", slept("w4"), worker=True),
                Job("y", "ky", slept("y"), after=("w0",))]
    if sys.argv[2] == "kernel":  # jobs that read a solid: the kernel is inherited
        import resource

        def cpu_at_start(name):
            def make(run):
                use = resource.getrusage(resource.RUSAGE_SELF)
                return [{"path": name, "part": name, "kind": "test", "pid": os.getpid(),
                         "cpu_s": use.ru_utime + use.ru_stime,
                         "build123d": "build123d" in sys.modules}]
            return make
        run = Run(load_project(), staging, print)
        nut = run.array[0]["nut_M2"]
        jobs = [Job("w0", "k0", cpu_at_start("w0"), (nut,), worker=True),
                Job("w1", "k1", cpu_at_start("w1"), (nut,), worker=True)]
        records, ran = run_jobs(run, jobs, Store(None))
        print(json.dumps({"main": main_pid, "records": records}))
        sys.exit(0)
    if sys.argv[2] == "prepared":  # a job's prepare, kept in a store with a folder
        import time
        from tactcad.export.jobs import keeping_run_results
        from tactcad.store import kept_result

        def prepare(run):
            with keeping_run_results(run):
                kept_result("test prepared", os.getpid, "facts")

        def reads_prepared(run):
            with keeping_run_results(run):
                made_in = kept_result("test prepared", os.getpid, "facts")
            return [{"path": "y", "part": "y", "kind": "test", "pid": os.getpid(),
                     "prepared_in": made_in}]

        def slept(name):
            def make(run):
                time.sleep(0.5)
                return [{"path": name, "part": name, "kind": "test", "pid": os.getpid()}]
            return make
        jobs = [Job("w0", "k0", slept("w0"), worker=True),
                Job("w1", "k1", slept("w1"), worker=True),
                Job("y", "ky", reads_prepared, after=("w0", "w1"), prepare=prepare)]
        store = Store(staging.parent / "store")
        records, ran = run_jobs(Run(load_project(), staging, print, store), jobs, store)
        print(json.dumps({"main": main_pid, "records": records}))
        sys.exit(0)
    if sys.argv[2] == "apart":  # jobs that read solids, and a prepare: forked before the kernel
        from tactcad.export.jobs import keeping_run_results
        from tactcad.store import kept_result

        def facts():
            return {"pid": os.getpid(), "kernel": "OCP" in sys.modules}

        def prepare(run):
            with keeping_run_results(run):
                kept_result("test prepared apart", facts, "facts")

        def reads_prepared(run):
            with keeping_run_results(run):
                made = kept_result("test prepared apart", facts, "facts")
            return [{"path": "y", "part": "y", "kind": "test", "pid": os.getpid(),
                     "prepared": made}]

        def pid_of(name):
            def make(run):
                return [{"path": name, "part": name, "kind": "test", "pid": os.getpid()}]
            return make

        events = []

        def ahead():  # another program's start-up, begun before the kernel's import
            events.append({"ahead": "OCP" in sys.modules})
            return lambda: events.append({"ended": True})  # start never took it: ended
        class Started:  # a start that never takes what ``ahead`` began
            def result(self):
                return []

            def cancel(self):
                pass
        store = Store(staging.parent / "store")
        run = Run(load_project(), staging, print, store)
        nut = run.array[0]["nut_M2"]
        jobs = [Job("w0", "k0", pid_of("w0"), (nut,), worker=True),
                Job("w1", "k1", pid_of("w1"), (nut,), worker=True),
                Job("y", "ky", reads_prepared, after=("w0", "w1"), prepare=prepare),
                Job("fc", "kfc", None, start=lambda run: Started(), ahead=ahead)]
        records, ran = run_jobs(run, jobs, store)
        print(json.dumps({"main": main_pid, "records": records, "events": events}))
        sys.exit(0)
    records, ran = run_jobs(Run(load_project(), staging, print), jobs, Store(None))
    print(json.dumps({"main": main_pid, "ran": ran, "kernel": "OCP" in sys.modules,
                      "records": records,
                      "files": {p.name: p.read_text() for p in staging.iterdir()}}))
''')


def run_script(tmp_path, mode: str) -> dict:
    staging = tmp_path / "staging"
    staging.mkdir()
    proc = subprocess.run([sys.executable, "-c", SCRIPT, str(staging), mode],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_worker_jobs_run_in_a_second_process_in_order(tmp_path):
    out = run_script(tmp_path, "live")
    pids = {r["path"]: r["pid"] for r in out["records"]}
    assert [r["path"] for r in out["records"]] == ["a", "w1", "w2", "w3", "z"]
    assert out["ran"] == 5
    assert pids["a"] == pids["z"] == out["main"]
    assert pids["w1"] == pids["w2"] != out["main"]
    assert pids["w3"] == out["main"]  # it reads a job of this process: run here
    assert out["files"] == {"a": "a", "w1": "w1", "w2": "w1w2", "w3": "aw3", "z": "w1w2aw3z"}
    assert not out["kernel"]  # no job needed a solid: the kernel never loaded here


@pytest.mark.slow
def test_this_process_works_while_the_worker_makes_what_its_next_job_reads(tmp_path):
    """A job that reads a worker's file waits; a later job that reads none runs first,
    and the waiting job's ``prepare`` runs while the worker is still busy."""
    out = run_script(tmp_path, "order")
    rec = {r["path"]: r for r in out["records"]}
    assert [r["path"] for r in out["records"]] == ["w0", "w1", "y", "x"]  # job order kept
    assert rec["w1"]["pid"] != rec["x"]["pid"] == rec["y"]["pid"]
    assert rec["x"]["end"] < rec["w1"]["end"]  # x did not wait behind y
    assert out["prepared"] < rec["w1"]["end"] <= rec["y"]["start"]


@pytest.mark.slow
def test_this_process_takes_back_the_workers_last_jobs_not_begun_while_it_waits(tmp_path):
    """With nothing of its own to run, this process makes the worker's queued jobs from
    the last one back, each read by no job left to the worker; the records keep job order."""
    out = run_script(tmp_path, "takeback")
    pids = {r["path"]: r["pid"] for r in out["records"]}
    assert [r["path"] for r in out["records"]] == ["w0", "w1", "w2", "w3", "w4", "y"]
    assert out["ran"] == 6
    assert pids["w4"] == pids["w3"] == pids["y"] == out["main"]  # taken back, last first
    assert out["files"] == {n: n for n in ("w0", "w1", "w2", "w3", "w4", "y")}


@pytest.mark.slow
def test_a_worker_forked_for_jobs_that_read_solids_inherits_the_kernel(tmp_path):
    """The kernel's modules are imported before the fork, not again in the worker (1.5-2
    CPU s there before): its first job finds them, having spent next to no CPU."""
    out = run_script(tmp_path, "kernel")
    first = out["records"][0]
    assert first["pid"] != out["main"]
    assert first["build123d"]
    assert first["cpu_s"] < 0.5, first


@pytest.mark.slow
def test_a_jobs_prepare_runs_in_another_process_and_is_read_back_here(tmp_path):
    """With a store that has a folder, the review page's kind of ``prepare`` (reading no
    file) runs in a forked process; the job, in this process, reads its kept result back
    instead of working it out again."""
    out = run_script(tmp_path, "prepared")
    rec = {r["path"]: r for r in out["records"]}
    assert rec["y"]["pid"] == out["main"]
    assert rec["y"]["prepared_in"] != out["main"]  # kept by the worker, read back here


@pytest.mark.slow
def test_a_jobs_prepare_runs_apart_before_the_kernel_is_imported(tmp_path):
    """A run whose jobs read solids imports the kernel before it forks its drawing worker;
    the review page's kind of ``prepare`` runs in a process forked before that import (on
    the core the import leaves idle), neither this process nor the worker, and another
    program's start-up (``ahead``: FreeCAD's) begins before the import too, ended at the
    run's end when no ``start`` took it."""
    out = run_script(tmp_path, "apart")
    rec = {r["path"]: r for r in out["records"]}
    worker = rec["w0"]["pid"]
    assert worker != out["main"] and rec["y"]["pid"] == out["main"]
    made = rec["y"]["prepared"]
    assert made["pid"] not in (out["main"], worker)
    assert made["kernel"] is False  # forked before the kernel's import
    assert out["events"] == [{"ahead": False}, {"ended": True}]


@pytest.mark.slow
def test_a_worker_that_dies_leaves_its_jobs_to_the_main_process(tmp_path):
    out = run_script(tmp_path, "die")
    pids = {r["path"]: r["pid"] for r in out["records"]}
    assert set(pids.values()) == {out["main"]}
    assert out["files"] == {"a": "a", "w1": "w1", "w2": "w1w2", "w3": "aw3", "z": "w1w2aw3z"}


def test_no_fork_once_the_kernel_is_loaded(monkeypatch):
    from tactcad.export.worker import can_fork

    import OCP  # noqa: F401  (this test process has the kernel)

    assert not can_fork()


def test_worker_jobs_read_only_done_or_worker_jobs():
    from tactcad.export.job import Job
    from tactcad.export.worker import worker_jobs

    jobs = [Job("a", "ka", None), Job("w1", "k1", None, after=("a",), worker=True),
            Job("w2", "k2", None, after=("w1",), worker=True), Job("w3", "k3", None, worker=True)]
    assert [j.name for j in worker_jobs(jobs, {})] == ["w3"]  # w1 reads a, run here
    assert [j.name for j in worker_jobs(jobs, {"a": []})] == ["w1", "w2", "w3"]


@pytest.mark.slow
def test_no_process_to_fork_runs_everything_here(tmp_path):
    out = run_script(tmp_path, "nofork")
    assert {r["pid"] for r in out["records"]} == {out["main"]}
    assert out["files"] == {"a": "a", "w1": "w1", "w2": "w1w2", "w3": "aw3", "z": "w1w2aw3z"}


def test_a_hand_over_the_worker_cannot_read_is_a_broken_pool_the_run_answers():
    """The solids are read inside the job: an unreadable hand-over fails that
    job as a dead worker would (the run makes it itself), with no traceback
    from the pool's own reader."""
    from concurrent.futures.process import BrokenProcessPool

    from tactcad.export.worker import _run_job

    with pytest.raises(BrokenProcessPool, match="element_a4mm"):
        _run_job("element_a4mm", b"\x80\x04 not a pickle")


class _UnpicklableWarning(UserWarning):
    """A library's warning holding what does not pickle (a function made in place)."""

    def __init__(self, text: str):
        super().__init__(text)
        self.hook = lambda: None


def test_warnings_a_worker_job_issued_keep_their_error_for_the_runs_closing_line(monkeypatch):
    """A worker job's warnings come back to the run's process with what they carry beside
    their text: the closing line on alike gauge-strain warnings gives the largest of their
    estimated errors (a cold export said 0.0 %), and a warning that cannot be pickled
    comes back as its text."""
    import pickle
    import types
    import warnings
    from concurrent.futures import Future

    from tactcad.commands.notices import WarningLines
    from tactcad.export import worker
    from tactcad.mechanics.gauge_strain import GaugeStrainRangeWarning
    from tactcad.store import Store

    errors = (0.021, 0.027, 0.024)

    def make(run):
        for error in errors:
            warnings.warn(GaugeStrainRangeWarning(f"gauge strain at b/t {error}", error))
        warnings.warn(_UnpicklableWarning("a library's own warning"))
        return [{"path": "p", "part": "p", "kind": "test"}]

    job = types.SimpleNamespace(needs=(), key="k", make=make)
    run = types.SimpleNamespace(store=Store(None), staging=None)  # the worker keeps nothing
    monkeypatch.setattr(worker, "_INHERITED", {"run": run, "jobs": {"j": job}})
    sent = pickle.loads(pickle.dumps(worker._run_job("j", pickle.dumps({}))))  # as the pool
    future: Future = Future()
    future.set_result(sent)
    notes = WarningLines(echo=False)
    with notes.capture():
        assert worker._JobFuture(future, lambda line: None).result() == sent[0]
    assert notes.lines == ["gauge strain at b/t 0.021", "a library's own warning",
                           f"{GaugeStrainRangeWarning.fold_as}: 2 more alike, estimated "
                           f"error up to {100 * max(errors[1:]):.1f} %"]


def test_a_worker_job_that_raises_says_its_warnings_before_its_error(monkeypatch):
    """A job that warned in the worker and then raised lost its warnings (the run's
    process said the error alone, where the same job run in the process says both)."""
    import pickle
    import types
    import warnings
    from concurrent.futures import Future

    from tactcad.commands.notices import WarningLines
    from tactcad.export import worker

    def make(run):
        warnings.warn("the gauge's grid is wider than the sheet")
        raise ValueError("the drawing does not fit its sheet")

    job = types.SimpleNamespace(needs=(), key="k", make=make)
    monkeypatch.setattr(worker, "_INHERITED", {"run": None, "jobs": {"j": job}})
    with pytest.raises(ValueError) as raised:
        worker._run_job("j", pickle.dumps({}))
    future: Future = Future()
    future.set_exception(pickle.loads(pickle.dumps(raised.value)))  # as the pool sends it
    notes = WarningLines(echo=False)
    with notes.capture(), pytest.raises(ValueError, match="does not fit its sheet"):
        worker._JobFuture(future, lambda line: None).result()
    assert notes.lines == ["the gauge's grid is wider than the sheet"]


@pytest.mark.slow
def test_a_planner_that_cannot_be_sent_leaves_the_run_to_itself(tmp_path):
    """A session worker is told each run's planner by reference: a planner
    made in place (a lambda) cannot be sent, so the run makes its own jobs;
    closing the session ends the worker process."""
    import os
    import time

    from tactcad.design.project import load_project
    from tactcad.export.job import Run
    from tactcad.export.jobs import all_jobs
    from tactcad.export.worker import SessionWorker

    session = SessionWorker()
    try:
        run = Run(load_project(), tmp_path)
        assert session.begin(run, lambda r: all_jobs(r)) is None
        assert session.begin(run, all_jobs) is not None
        end = time.monotonic() + 120
        while not session.pid and time.monotonic() < end:
            time.sleep(0.1)
        pid = session.pid
        assert pid not in (0, os.getpid())
    finally:
        session.close()
    end = time.monotonic() + 15
    while os.path.exists(f"/proc/{pid}") and time.monotonic() < end:
        time.sleep(0.1)
    assert not os.path.exists(f"/proc/{pid}")


def test_a_stop_while_a_process_starts_acts_once_it_is_whole():
    """A stop signal inside ``stop_signals_held`` raises when the block ends,
    not in the middle (where a half-started child would wait on its pipe for
    ever); the handler is put back; a child started inside begins with the
    stop signals blocked, so a terminal's Ctrl-C does not end it half-started."""
    import signal
    import threading
    from concurrent.futures import ProcessPoolExecutor

    import multiprocessing

    from tactcad.stopping import spawn_ready, stop_signals_held

    class Stopped(Exception):
        pass

    def stop(number, frame):
        raise Stopped(number)

    before = signal.signal(signal.SIGTERM, stop)
    reached = False
    try:
        spawn_ready()
        with pytest.raises(Stopped):
            with stop_signals_held():
                # to the main thread, whose mask the block holds: a signal to the process may
                # be taken by another thread of the test runner's process (its I/O threads)
                # and reach the handler in the middle of the block
                signal.pthread_kill(threading.main_thread().ident, signal.SIGTERM)
                pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn"))
                child_mask = pool.submit(signal.pthread_sigmask, signal.SIG_BLOCK, []).result()
                reached = True
        pool.shutdown()
        assert reached and signal.getsignal(signal.SIGTERM) is stop
        assert {signal.SIGINT, signal.SIGTERM, signal.SIGHUP} <= child_mask
        assert signal.SIGTERM not in signal.pthread_sigmask(signal.SIG_BLOCK, [])
    finally:
        signal.signal(signal.SIGTERM, before)


def test_a_session_worker_killed_as_it_starts_is_gone_at_once():
    """The worker is killed by its parent's handle from the moment it is
    started, before its own start-up has run (a pid the worker writes itself
    is not there yet), and reaped: nothing is left for the exit to wait on."""
    import multiprocessing
    import os

    from tactcad.export.worker import SessionWorker

    worker = SessionWorker()
    pid = worker.pid
    assert pid and os.path.exists(f"/proc/{pid}")
    worker.close()
    assert not os.path.exists(f"/proc/{pid}")  # killed and reaped
    assert pid not in {p.pid for p in multiprocessing.active_children()}


def test_a_killed_session_worker_frees_its_semaphores_before_kill_returns():
    """Killing the worker waits for its pool's manager thread, which frees the
    pool's named semaphores as it ends: a process that ends with ``os._exit``
    right after (as the ``tactcad`` program does, its ``atexit`` handlers run first) leaves the resource
    tracker nothing to warn of ("leaked semaphore"). Repeated, since without
    the wait it is a race between the thread and the exit."""
    import subprocess
    import sys

    script = (
        "import os, threading\n"
        "from tactcad.export.worker import SessionWorker\n"
        "for _ in range(3):\n"
        "    w = SessionWorker()\n"
        "    thread = w._pool._executor_manager_thread\n"
        "    w.kill()\n"
        "    assert not thread.is_alive(), 'manager thread still running'\n"
        "import atexit\n"
        "w = SessionWorker(); w.kill(); atexit._run_exitfuncs(); os._exit(0)\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    assert "leaked" not in done.stderr and "Traceback" not in done.stderr, done.stderr


def test_ending_at_once_on_a_stop_is_undone_for_a_process_that_goes_on():
    """A watch run in-process (the API, the tests) that was stopped ends its
    clean-up with stop signals ending the process at once; when it returns,
    the process's own handlers are back (else a later Ctrl-C would os._exit
    the caller)."""
    import signal

    from tactcad.stopping import exit_at_once_on_stop, stop_signal_numbers

    before = {n: signal.getsignal(n) for n in stop_signal_numbers()}
    undo = exit_at_once_on_stop(0)
    during = {n: signal.getsignal(n) for n in stop_signal_numbers()}
    undo()
    assert all(during[n] is not before[n] for n in before if before[n] is not signal.SIG_IGN)
    assert {n: signal.getsignal(n) for n in stop_signal_numbers()} == before
