"""``tactcad bench watch-stop``: ``tactcad watch`` stopped at random moments.

README: Ctrl-C, SIGTERM or SIGHUP stops a watch with exit 0 and a "stopped"
line, at any moment. Each round starts a watch on a copy of the design (its
own process group, as a terminal's job, Ctrl-C at its default) and stops it
once, alternately:

* ``start``: at a moment drawn uniformly from 0 ... ``latest_s`` after the
  program's first line (its stop signals held: :mod:`tactcad.__main__`;
  before it the interpreter is starting, and a signal ends any program
  there) through loading, the first export and serving;
* ``edit``: once the first export is current, an edit of the first arm is
  saved and the stop comes 0 ... ``EDIT_WINDOW_S`` after the save (its export
  under way, or done and serving);

and the signal alternates between a terminal's Ctrl-C (SIGINT to the whole
process group) and SIGTERM to the watch. A round is good when the watch
ended within :data:`STOP_GOAL_S` of the signal, with exit 0, no traceback
and no process of its group left behind.
"""

from __future__ import annotations

import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import asdict, dataclass
from pathlib import Path

#: Seconds from the stop signal to the watch's end (the issue's goal).
STOP_GOAL_S = 2.0
#: A stop in the ``edit`` rounds comes within this many seconds of the save.
EDIT_WINDOW_S = 4.0
#: Seconds the first export is waited for in an ``edit`` round.
FIRST_EXPORT_S = 600.0
#: Seconds the program is given to reach its first line (the interpreter's start).
PROGRAM_START_S = 30.0
#: Seconds a watch that did not end is given after SIGKILL of its group.
KILL_WAIT_S = 10.0


@dataclass
class StopRound:
    """One watch stopped once: the moment (s after the start, or after the
    edit's save), how it was stopped and how it ended (None: not within
    ``wait_s``, then killed)."""

    phase: str
    signal: str
    moment_s: float
    ended_s: float | None
    exit_code: int | None
    traceback: bool
    stopped_line: bool
    left_behind: int

    @property
    def good(self) -> bool:
        return (self.ended_s is not None and self.ended_s <= STOP_GOAL_S and self.exit_code == 0
                and not self.traceback and self.stopped_line and not self.left_behind)


def _group(pgid: int) -> list[int]:
    """The processes of process group ``pgid`` still running (zombies left out)."""
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":
            out.append(int(stat.parent.name))
    return out


def program_started(proc: subprocess.Popen) -> bool:
    """Wait until ``proc`` runs the program's first line: SIGTERM caught
    (``SigCgt`` of ``/proc/<pid>/status``; the interpreter alone leaves it at
    its default). False if it ended or did not get there within
    :data:`PROGRAM_START_S`; True at once where there is no ``/proc``."""
    status = Path(f"/proc/{proc.pid}/status")
    if not Path("/proc/self/status").exists():
        return True
    end = time.perf_counter() + PROGRAM_START_S
    while time.perf_counter() < end and proc.poll() is None:
        try:
            caught = next(line.split()[1] for line in status.read_text().splitlines()
                          if line.startswith("SigCgt:"))
        except (OSError, StopIteration):
            caught = "0"
        if int(caught, 16) >> (signal.SIGTERM - 1) & 1:
            return True
        time.sleep(0.002)
    return False


def _at_default() -> None:
    """``preexec_fn``: Ctrl-C at its default, as a terminal's job has it."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def stop_round(files: list[Path], phase: str, signum: int, moment_s: float,
               store_from: Path | None = None, wait_s: float = 30.0) -> StopRound:
    """Start a watch on a copy of ``files`` (the design file first), stop it
    with ``signum`` at ``moment_s`` of ``phase`` (see the module doc); how it ended."""
    from tactcad.benchmarks.bench_watch import arm_length_of_edit, edit_first_arm

    with tempfile.TemporaryDirectory(prefix="tactcad-bench-stop-") as tmp:
        folder = Path(tmp)
        for f in files:
            shutil.copyfile(f, folder / f.name)
        store = folder / "store"
        if store_from is not None:
            shutil.copytree(store_from, store)
        proc = subprocess.Popen([sys.executable, "-m", "tactcad", "watch", "--design",
                                 str(folder / files[0].name), "--out", str(folder / "out"),
                                 "--port", "0", "--cache", str(store)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                start_new_session=True, preexec_fn=_at_default)
        lines: list[str] = []
        current = threading.Event()

        def read() -> None:
            for line in proc.stderr:
                lines.append(line)
                if "export current" in line:
                    current.set()
        reader = threading.Thread(target=read, daemon=True)
        reader.start()
        try:
            if not program_started(proc):
                raise TimeoutError(f"bench watch-stop: the program did not start in "
                                   f"{PROGRAM_START_S:g} s")
            if phase == "edit":
                if not current.wait(FIRST_EXPORT_S):
                    raise TimeoutError(f"bench watch-stop: no first export in {FIRST_EXPORT_S:g} s")
                edit_first_arm(folder / files[0].name, arm_length_of_edit(0))
            time.sleep(moment_s)
            t0 = time.perf_counter()
            if signum == signal.SIGINT:
                os.killpg(proc.pid, signum)  # a terminal's Ctrl-C: every process of the job
            else:
                proc.send_signal(signum)
            try:
                code: int | None = proc.wait(wait_s)
                ended: float | None = time.perf_counter() - t0
            except subprocess.TimeoutExpired:
                code = ended = None
            end = time.perf_counter() + STOP_GOAL_S
            while _group(proc.pid) and time.perf_counter() < end:
                time.sleep(0.05)  # children the watch ended may take a moment to go
            left = len(_group(proc.pid))
        finally:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            proc.wait(KILL_WAIT_S)
            reader.join(KILL_WAIT_S)
        err = "".join(lines)
        return StopRound(phase, signal.Signals(signum).name, round(moment_s, 3),
                         None if ended is None else round(ended, 3), code,
                         "Traceback" in err, "watch: stopped" in err, left)


def stop_figures(files: list[Path], rounds: int = 20, latest_s: float = 12.0, seed: int = 0,
                 store_from: Path | None = None, log=print) -> dict:
    """``rounds`` watches stopped at random moments (:func:`stop_round`;
    moments from ``random.Random(seed)``): every round and how many were good.

    Raises:
        TimeoutError: an ``edit`` round's first export was not current in time.
    """
    rng = random.Random(seed)
    done = []
    for k in range(rounds):
        phase = ("start", "edit")[k % 2]
        signum = (signal.SIGINT, signal.SIGTERM)[(k // 2) % 2]
        moment = rng.uniform(0.0, latest_s if phase == "start" else EDIT_WINDOW_S)
        one = stop_round(files, phase, signum, moment, store_from)
        done.append(one)
        log(f"round {k}: {one.phase} + {one.moment_s:.2f} s, {one.signal}: "
            + ("did not end" if one.ended_s is None else
               f"exit {one.exit_code} in {one.ended_s:.2f} s")
            + ("" if one.good else " (not good)"))
    ended = [r.ended_s for r in done if r.ended_s is not None]
    return {"rounds": [asdict(r) | {"good": r.good} for r in done],
            "good": sum(r.good for r in done), "of": rounds, "goal_s": STOP_GOAL_S,
            "slowest_s": max(ended, default=None), "seed": seed, "latest_s": latest_s,
            "cpus": os.cpu_count()}
