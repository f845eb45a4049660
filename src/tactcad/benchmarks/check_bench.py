"""``tactcad bench check``: ``tactcad check`` on a current export, as a CI job
or a reviewer runs it.

The design is exported once into a folder (``--out``, else a temporary one);
then ``tactcad check`` runs on that current export as a whole process
(``--runs`` times: start-up, imports and every group, what the user waits
for), and once in this process with each group's seconds (the groups of
:data:`tactcad.checks.groups.CHECK_GROUPS`, in order). Goal on two cores:
5 s per check.

Units: s.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Sequence

#: The goal for ``tactcad check`` on a current export, two cores (s).
CHECK_GOAL_S = 5.0
#: The goal for the program's start-up, ``tactcad --version`` as a whole process (s): the
#: command line imports no command module and no numerical library before it parses.
STARTUP_GOAL_S = 0.3


def check_figures(design_argv: Sequence[str], project, out: str | Path | None,
                  runs: int) -> dict:
    """Seconds of ``tactcad check`` on a current export of ``project``.

    Args:
        design_argv: the ``--design`` / ``--set`` arguments naming the design
            for the whole-process runs (the same design as ``project``).
        project: the :class:`tactcad.api.Project` to export and check in-process.
        out: the export folder (made current first), or None for a temporary one.
        runs: whole-process runs (>= 1).

    Returns:
        ``{"design", "export_s", "runs_s": [...], "median_s", "groups":
        [{"group", "seconds", "checks", "failed"}], "in_process_s", "goal_s",
        "passed", "startup_s", "startup_goal_s"}``: ``startup_s`` the median of ``runs``
        whole-process ``tactcad --version`` (s, :func:`startup_seconds`).

    Raises:
        RuntimeError: a whole-process check ended with an exit code other than 0 or 1.
    """
    with tempfile.TemporaryDirectory(prefix="tactcad-bench-check-") as tmp:
        folder = Path(out) if out is not None else Path(tmp) / "exports"
        t0 = time.perf_counter()
        project.export(folder)
        export_s = time.perf_counter() - t0
        walls = [_whole_process(design_argv, folder) for _ in range(runs)]
        marks: list[tuple[str, float, int, int]] = []
        t0 = time.perf_counter()
        report = project.check(folder, on_group=lambda label, results: marks.append(
            (label, time.perf_counter() - t0, len(results),
             sum(not r.passed for r in results))))
        in_process = time.perf_counter() - t0
    groups, before = [], 0.0
    for label, at, count, failed in marks:
        groups.append({"group": label, "seconds": at - before, "checks": count,
                       "failed": failed})
        before = at
    return {"design": project.name, "export_s": export_s, "runs_s": walls,
            "median_s": statistics.median(walls), "groups": groups,
            "in_process_s": in_process, "goal_s": CHECK_GOAL_S, "passed": report.passed,
            "startup_s": startup_seconds(runs), "startup_goal_s": STARTUP_GOAL_S}


def startup_seconds(runs: int) -> float:
    """The median wall time of ``runs`` whole-process ``tactcad --version`` (s): the
    interpreter's start, the command line's imports and its parse, what every command waits
    for before its own work.

    Args:
        runs: whole-process runs (>= 1).

    Returns:
        the median (s).

    Raises:
        RuntimeError: a run ended with an exit code other than 0.
    """
    walls = []
    for _ in range(runs):
        t0 = time.perf_counter()
        done = subprocess.run([sys.executable, "-m", "tactcad", "--version"],
                              capture_output=True, text=True)
        walls.append(time.perf_counter() - t0)
        if done.returncode != 0:
            raise RuntimeError(f"tactcad --version ended with exit {done.returncode}: "
                               f"{done.stderr.strip()[-300:]}")
    return statistics.median(walls)


def _whole_process(design_argv: Sequence[str], folder: Path) -> float:
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "tactcad.cli", "check", *design_argv, "--out",
                           str(folder), "--quiet"], capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    if done.returncode not in (0, 1):
        raise RuntimeError(f"tactcad check ended with exit {done.returncode}: "
                           f"{done.stderr.strip()[-300:]}")
    return seconds


def check_table(report: dict) -> str:
    """The figures as text: the whole-process runs, the start-up, then each group's seconds."""
    runs = ", ".join(f"{s:.2f}" for s in report["runs_s"])
    lines = [f"tactcad bench check: {report['design']} (export {report['export_s']:.1f} s)",
             f"  check on the current export, whole process: median {report['median_s']:.2f} s "
             f"({runs}); goal {report['goal_s']:g} s on two cores",
             f"  start-up (tactcad --version, whole process): median "
             f"{report['startup_s']:.2f} s; goal {report['startup_goal_s']:g} s",
             f"  in this process: {report['in_process_s']:.2f} s, by group:"]
    lines += [f"    {g['group']:<28} {g['seconds']:6.2f} s  {g['checks']:4d} checks"
              + (f", {g['failed']} failed" if g["failed"] else "") for g in report["groups"]]
    return "\n".join(lines)
