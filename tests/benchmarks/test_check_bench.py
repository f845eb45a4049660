"""``tactcad bench check``: its options are checked and its table shows every group and the
program's start-up."""

from __future__ import annotations

import pytest

from conftest import run_cli
from tactcad.benchmarks.check_bench import (CHECK_GOAL_S, STARTUP_GOAL_S, check_table,
                                            startup_seconds)


def test_the_table_gives_the_median_the_goal_and_every_group():
    report = {"design": "d", "export_s": 6.0, "runs_s": [7.2, 7.3, 7.1], "median_s": 7.2,
              "in_process_s": 4.4, "goal_s": CHECK_GOAL_S, "passed": True,
              "startup_s": 0.21, "startup_goal_s": STARTUP_GOAL_S,
              "groups": [{"group": "parts", "seconds": 0.36, "checks": 70, "failed": 0},
                         {"group": "scene array", "seconds": 0.48, "checks": 38, "failed": 2}]}
    text = check_table(report)
    assert "median 7.20 s (7.20, 7.30, 7.10); goal 5 s" in text
    assert "parts" in text and "2 failed" in text.splitlines()[-1]
    startup = next(line for line in text.splitlines() if "start-up" in line)
    assert "tactcad --version" in startup and "median 0.21 s" in startup
    assert f"goal {STARTUP_GOAL_S:g} s" in startup


def test_the_start_up_is_timed_on_the_whole_program():
    seconds = startup_seconds(1)
    assert 0 < seconds < 60


@pytest.mark.parametrize("argv, needle", [
    (["bench", "check", "--runs", "0"], "--runs"),
    (["bench", "check", "--runs", "x"], "--runs"),
])
def test_bad_options_are_refused_naming_them(argv, needle):
    done = run_cli(*argv)
    assert done.returncode == 2 and needle in done.stderr and "Traceback" not in done.stderr
