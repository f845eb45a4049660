"""A grasp whose contact does not settle on a very thin slab is refused naming
--slab-thickness-mm and its value (it named a field `grasp` no option has)."""

from __future__ import annotations

import argparse
import json

from conftest import run_cli


def test_an_unsettled_contact_names_the_slab_thickness_given():
    from tactcad.commands.options import grasp_option_error
    from tactcad.in_use.grasp_experiment import UnsettledContact

    exc = UnsettledContact("grasp", "the stops and lift-off did not settle",
                           "a settled contact within 100 passes")
    error = grasp_option_error(exc, argparse.Namespace(slab_thickness_mm=0.001))
    assert (error.field, error.value) == ("--slab-thickness-mm", 0.001)
    assert "thicker than 0.001 mm" in error.allowed and "did not settle" in error.why


def test_a_dies_grasp_on_a_slab_too_thin_to_settle_names_the_option(tmp_path):
    made = run_cli("design", "--jaw", "5", "--kr-over-km", "8", "--kobj-range", "0.4", "4",
                   "--full-scale-force", "0.008", "--out", "mydie", cwd=tmp_path)
    assert made.returncode == 0, made.stdout + made.stderr
    r = run_cli("grasp", "--slab-thickness-mm", "0.001", "--profile", "slab", "--json",
                cwd=tmp_path / "mydie")
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("--slab-thickness-mm", 0.001)
    assert "settle" in error["allowed"] and "did not settle" in error["message"]
