"""Time the test suite as ``make test`` and ``make test-fast`` run it.

Runs each pytest command once, in this checkout, and prints its wall seconds,
its test counts (passed, failed, skipped ...), the cores this process may use
and the load average before and after, beside the goals (the whole suite in
5 min, the fast set in 60 s, on two cores). Other work on the machine slows
the runs; the load average says how much there was.

    python scripts/bench_tests.py [--test-jobs N] [--fast-jobs N] [--only fast|test]

Exit 1 when a run fails (a failed test is a failed benchmark), else 0; a goal
missed is printed, not an error (the figure depends on the machine).
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: seconds: the goals the figures are read against
GOALS = {"test": 300.0, "test-fast": 60.0}
#: the Makefile's ONE_THREAD: one single-threaded process per core
ONE_THREAD = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
COUNTS = re.compile(r"(\d+) (passed|failed|skipped|xfailed|xpassed|errors?|deselected)")


def pytest_command(target: str, jobs: str) -> list[str]:
    """The pytest command line of ``make <target>`` (the Makefile's, with ``-n jobs``)."""
    cmd = [sys.executable, "-m", "pytest", "-q", "-n", jobs, "--dist", "loadgroup"]
    return cmd + (["-m", "not slow"] if target == "test-fast" else [])


def suite_env() -> dict[str, str]:
    """The environment ``make`` gives the suite: one thread a process, the bytecode cache on."""
    env = {**os.environ, **ONE_THREAD}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def counts_of(summary: str) -> dict[str, int]:
    """``{"passed": 950, "skipped": 1}`` from pytest's last line."""
    return {("errors" if k.startswith("error") else k): int(n) for n, k in COUNTS.findall(summary)}


def cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


def load() -> str:
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def run(target: str, jobs: str) -> tuple[float, dict[str, int], int]:
    cmd = pytest_command(target, jobs)
    print(f"make {target}: {' '.join(cmd[1:])}   (load before {load()})", flush=True)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, env=suite_env())
    wall = time.perf_counter() - t0
    lines = [ln for ln in proc.stdout.splitlines() if ln.strip()]
    last = lines[-1] if lines else ""
    if proc.returncode != 0:
        sys.stdout.write(proc.stdout[-4000:])
        sys.stderr.write(proc.stderr[-2000:])
    return wall, counts_of(last), proc.returncode


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--test-jobs", default="auto", help="make test's TEST_JOBS (default %(default)s)")
    ap.add_argument("--fast-jobs", default="auto", help="make test-fast's FAST_JOBS (default %(default)s)")
    ap.add_argument("--only", choices=("fast", "test"), help="time one of the two")
    args = ap.parse_args(argv)
    targets = [("test-fast", args.fast_jobs), ("test", args.test_jobs)]
    if args.only:
        targets = [t for t in targets if t[0] == ("test-fast" if args.only == "fast" else "test")]
    rows, failed = [], False
    for target, jobs in targets:
        wall, counts, rc = run(target, jobs)
        failed |= rc != 0
        rows.append((target, jobs, wall, counts, rc, load()))
    print(f"\n{cores()} cores, Python {sys.version.split()[0]}")
    for target, jobs, wall, counts, rc, after in rows:
        goal = GOALS[target]
        said = ", ".join(f"{n} {k}" for k, n in counts.items()) or "no summary"
        verdict = "within" if wall <= goal else "over"
        print(f"make {target:<9} -n {jobs:<4} {wall:7.1f} s  ({wall / 60:.1f} min; {said}; "
              f"exit {rc}) {verdict} the goal of {goal:.0f} s; load after {after}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
