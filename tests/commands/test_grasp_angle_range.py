"""`grasp --angle-deg` has one range, the jaw's own (0 ... its opening), and a value under
it is refused in the same words as one over it (-1 said "0 ... 90", 90 "0 ... 30")."""

from __future__ import annotations

import json

import pytest

from conftest import run_cli


def _allowed(*argv, cwd=None) -> str:
    r = run_cli("grasp", *argv, "--json", cwd=cwd)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "--angle-deg"
    return error["allowed"]


@pytest.mark.parametrize("where", ["array", "die"])
def test_an_angle_under_and_over_the_jaws_range_are_refused_alike(where, tmp_path, die_folder):
    cwd = die_folder if where == "die" else tmp_path
    under, over = _allowed("--angle-deg", "-1", cwd=cwd), _allowed("--angle-deg", "90", cwd=cwd)
    assert under == over and under.startswith("0 ... ") and "the jaw's opening" in under
