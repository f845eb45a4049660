"""How a run is stopped: the signals that stop it, held while a process is
started, and the process's last moments.

Ctrl-C (SIGINT) and the ending signals (SIGTERM, SIGHUP;
:data:`ENDING_SIGNALS`) raise in the main thread wherever it is. Raised in
the middle of starting a process, that leaves a child half made: spawned,
but never sent its start-up data, it waits on its pipe for ever and the
parent's exit waits for it (``multiprocessing``'s exit joins its children).
So processes are started within :func:`stop_signals_held`: a stop that
arrives meanwhile is acted on once the process is whole, and the new
process starts with the stop signals blocked, so a terminal's Ctrl-C (sent
to every process of the job) does not end it half-started either; its own
start-up decides what they do (:func:`stop_signals_unblocked`).
"""

from __future__ import annotations

import os
import signal
import threading
from contextlib import contextmanager
from typing import Callable, Iterator

#: Signals that end a run like Ctrl-C does (cleaned up, then 128 + the number).
ENDING_SIGNALS = ("SIGTERM", "SIGHUP")
#: Every signal that stops a run: Ctrl-C and the ending signals.
STOP_SIGNALS = ("SIGINT", *ENDING_SIGNALS)


def stop_signal_numbers() -> list[signal.Signals]:
    """The numbers of :data:`STOP_SIGNALS` this system has."""
    return [getattr(signal, name) for name in STOP_SIGNALS if hasattr(signal, name)]


@contextmanager
def stop_signals_held(block_in_children: bool = True) -> Iterator[None]:
    """Start processes within: a stop signal that arrives meanwhile is handed
    to its handler (which raises, as it would have) when the block ends,
    not in the middle of a process start; processes started within begin
    with the stop signals blocked when ``block_in_children`` (a blocked mask
    is inherited), to be unblocked by their start-up code
    (:func:`stop_signals_unblocked`). Outside the main thread only the mask
    is set: the handlers run in the main thread, which this one does not
    interrupt."""
    numbers = stop_signal_numbers()
    held: list[int] = []
    previous = {}
    if threading.current_thread() is threading.main_thread():
        for number in numbers:
            handler = signal.getsignal(number)
            if callable(handler):  # ignored or at the default: nothing to hold
                previous[number] = signal.signal(number, lambda n, _f: held.append(n))
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, numbers) if block_in_children else None
    try:
        yield
    finally:
        if mask is not None:
            signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        _put_back(list(previous.items()))
        for number in held[:1]:  # the first stop raises; later ones add nothing
            previous[number](number, None)


#: Stop signals noted while the program loaded (None: no hold was set).
_held_while_loading: list[int] | None = None


def hold_stops_while_loading() -> None:
    """The program's first act (``tactcad``, ``python -m tactcad``): a stop
    signal that arrives while its modules load is noted, not raised, and
    :func:`act_on_held_stop` acts on it once the command can answer it.
    Raised in the middle of an import, Ctrl-C would end the run with the
    interpreter's traceback instead of the command's own line and code (a
    watch stopped at its start must end with exit 0 and "stopped")."""
    global _held_while_loading
    _held_while_loading = []
    for number in stop_signal_numbers():
        signal.signal(number, _note_held_stop)


def _note_held_stop(signum: int, _frame) -> None:
    if _held_while_loading is not None:
        _held_while_loading.append(signum)


def act_on_held_stop() -> None:
    """End the hold of :func:`hold_stops_while_loading`: Ctrl-C raises
    ``KeyboardInterrupt`` again, a signal still held goes to the handler the
    program has installed since (at its default if none), and the first stop
    that came while loading is acted on now (its handler runs and raises).
    Nothing happens where no hold was set (a command run in-process)."""
    global _held_while_loading
    held, _held_while_loading = _held_while_loading, None
    if held is None:
        return
    for number in stop_signal_numbers():
        if signal.getsignal(number) is _note_held_stop:
            signal.signal(number, signal.default_int_handler if number == signal.SIGINT
                          else signal.SIG_DFL)
    for number in held[:1]:  # the first stop acts; later ones add nothing
        signal.raise_signal(number)


def _put_back(handlers: list) -> None:
    """Install ``handlers`` ((signal, handler) pairs) each in a ``finally`` of
    the one before: a handler put back may run (and raise) at once, and the
    others are put back all the same."""
    if handlers:
        try:
            signal.signal(*handlers[0])
        finally:
            _put_back(handlers[1:])


def spawn_ready() -> None:
    """Start ``multiprocessing``'s resource tracker now if it is not running,
    before :func:`stop_signals_held` for a ``spawn`` start: the tracker's own
    start unblocks SIGINT and SIGTERM in the calling thread when it is done
    (CPython's ``resource_tracker.ensure_running``), which would start the
    new process with them unblocked."""
    from multiprocessing import resource_tracker

    resource_tracker.ensure_running()


def stop_signals_unblocked(ignore: tuple[str, ...] = ("SIGINT",)) -> None:
    """A started process's first act (see :func:`stop_signals_held`): the
    signals ``ignore`` ignored (Ctrl-C is the parent's to handle: it stops
    this process), the other stop signals at their defaults (the process
    ends at once; its parent cleans up), then every stop signal unblocked
    (one sent meanwhile is acted on now, or dropped if ignored)."""
    for number in stop_signal_numbers():
        ignored = number.name in ignore
        signal.signal(number, signal.SIG_IGN if ignored else signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, stop_signal_numbers())


def exit_at_once_on_stop(code: int) -> Callable[[], None]:
    """From now on a stop signal ends the process at once with ``code``
    (``os._exit``): for a process that is already ending (its command has
    returned, or a watch is closing down), where a second Ctrl-C or a
    SIGTERM must neither raise in the middle of its clean-up (the
    interpreter's ``Exception ignored in atexit callback``) nor wait for it.
    Only in the main thread (signals are the main thread's).

    Returns:
        A function that puts the previous handlers back, for a caller whose
        process goes on (a command run in-process, as the API and tests do).
    """
    previous: dict = {}
    if threading.current_thread() is threading.main_thread():
        for number in stop_signal_numbers():
            if signal.getsignal(number) is not signal.SIG_IGN:
                previous[number] = signal.signal(number, lambda _n, _f: os._exit(code))
    return lambda: _put_back(list(previous.items()))


#: Bytes that hold a C ``struct sigaction`` on any system (Linux x86-64: 152).
_SIGACTION_BYTES = 1024


@contextmanager
def signal_dispositions_kept() -> Iterator[None]:
    """Put every signal's disposition back as it was, at the level of the
    operating system, when the block ends: around a native library that
    installs signal handlers of its own and leaves the signals at their
    defaults. gmsh's initialisation does (its OpenCascade's
    ``OSD::SetSignal``, set and unset): SIGPIPE is no longer ignored, so a
    later write to a closed pipe (a killed worker's) ends the whole process
    at once instead of raising ``BrokenPipeError``; Python's SIGTERM handler
    and ``faulthandler``'s handlers are gone. Python's ``signal.getsignal``
    answers from its own table and does not see the change, so the
    dispositions are read and written with the C library's ``sigaction``;
    where there is none (Windows) nothing is kept."""
    import ctypes

    try:
        sigaction = ctypes.CDLL(None, use_errno=True).sigaction
    except (OSError, AttributeError, TypeError):  # no C library to ask
        sigaction = None
    saved = {}
    for number in signal.valid_signals() if sigaction is not None else ():
        if number not in (signal.SIGKILL, signal.SIGSTOP):  # never caught nor changed
            action = ctypes.create_string_buffer(_SIGACTION_BYTES)
            if sigaction(int(number), None, action) == 0:
                saved[number] = action
    try:
        yield
    finally:
        for number, action in saved.items():
            sigaction(int(number), action, None)


#: Programs started by this process (``subprocess.Popen``, :func:`popen_held`) not yet
#: known to be reaped: :func:`end_child_processes` ends and reaps those still running.
_programs: list = []


def popen_held(args: list[str], **kwargs):
    """``subprocess.Popen(args, **kwargs)`` within :func:`stop_signals_held` (the
    program's stop signals not blocked), noted for :func:`end_child_processes`; a stop
    that arrived meanwhile (raised as the hold ends) ends and reaps the program before it
    is raised on, so no caller is left with a child it never got.

    Args:
        args: the program and its arguments.
        kwargs: ``subprocess.Popen``'s other arguments.

    Returns:
        The ``subprocess.Popen``.

    Raises:
        KeyboardInterrupt: a stop signal arrived while the program started.
        OSError: the program cannot be started.
    """
    import subprocess

    proc = None
    try:
        with stop_signals_held(block_in_children=False):  # never a Popen half made
            proc = subprocess.Popen(args, **kwargs)
            _programs[:] = [p for p in _programs if p.returncode is None] + [proc]
    except BaseException:
        if proc is not None:
            end_program(proc)
        raise
    return proc


def end_program(proc, wait_s: float = 1.0) -> None:
    """End a started program and reap it: SIGTERM if it still runs, up to ``wait_s``
    seconds to end, then SIGKILL; a child never reaped stays a zombie, re-parented to a
    PID 1 that may never reap it (a container's).

    Args:
        proc: the ``subprocess.Popen``.
        wait_s: longest wait after SIGTERM, s.
    """
    import subprocess

    if proc.poll() is None:
        try:
            proc.terminate()
            proc.wait(timeout=wait_s)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        except OSError:  # ended and reaped meanwhile
            pass


def end_programs(wait_s: float = 1.0) -> None:
    """End and reap every program started with :func:`popen_held` still running
    (:func:`end_program`), and forget them all.

    Args:
        wait_s: longest wait for each after SIGTERM, s.
    """
    for proc in list(_programs):
        end_program(proc, wait_s)
    _programs.clear()


def end_child_processes(wait_s: float = 1.0) -> None:
    """Kill every ``multiprocessing`` child of this process still running and
    reap it (each waited for at most ``wait_s`` seconds): a process that
    ends must not leave one, and ``multiprocessing``'s exit would wait for
    it for as long as it runs (a child never sent its work waits for ever).
    The drawing worker and the page's server hold nothing that needs a
    goodbye: their parent has the files and the sockets. The programs started
    with :func:`popen_held` (FreeCAD) still running are ended and reaped too
    (:func:`end_program`).

    Args:
        wait_s: longest wait for each child, s.
    """
    import sys

    end_programs(wait_s)
    if "multiprocessing" not in sys.modules:  # none was started
        return
    children = sys.modules["multiprocessing"].active_children()
    for child in children:
        child.kill()
    for child in children:
        child.join(wait_s)


def pool_shut_down(pool, wait_s: float = 5.0, kill: bool = False) -> None:
    """Shut ``pool`` (a :class:`concurrent.futures.ProcessPoolExecutor`) down
    without waiting on its processes, but wait, at most ``wait_s`` seconds,
    for its manager thread to end. Given up with ``wait=False``, the pool's
    queues are held only by that thread, so their named semaphores (``spawn``
    pools) are freed there as it ends; a process that exits meanwhile
    (``os._exit``) can have unlinked one without telling ``multiprocessing``'s
    resource tracker, which then warns of a leaked semaphore as the run ends.
    ``shutdown(wait=True)`` is not used: it joins the thread for as long as it
    takes, and a worker killed in the middle of a transfer can leave it
    waiting on a pipe.

    Args:
        pool: the executor.
        wait_s: longest wait for the manager thread, s.
        kill: SIGKILL the pool's processes first (a run interrupted while they
            work: the thread would otherwise wait for their tasks to end).
    """
    thread = getattr(pool, "_executor_manager_thread", None)  # CPython's names, 3.9 ... 3.13
    if kill:
        for process in list((getattr(pool, "_processes", None) or {}).values()):
            try:
                process.kill()
            except (OSError, ValueError, AttributeError):  # already ended, or never started
                pass
    pool.shutdown(wait=False, cancel_futures=True)
    if thread is not None and thread is not threading.current_thread():
        thread.join(wait_s)
