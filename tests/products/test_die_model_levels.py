"""Every die command takes `--model` at the levels it computes and refuses any other in one
wording, naming the levels it takes (`allowed one of closed-form, ...`)."""

from __future__ import annotations

import json

import pytest

from conftest import run_cli

TAKES = {"verify": ("closed-form",), "readout": ("closed-form",),
         "modal": ("closed-form", "fem3d"),
         "budget": ("closed-form",), "thermal": ("closed-form",), "grasp": ("closed-form",),
         "strength": ("closed-form",), "stiffness": ("closed-form", "fem3d")}


def test_verify_takes_the_closed_form_it_prints(die_folder):
    r = run_cli("verify", "--model", "closed-form", "--json", cwd=die_folder)
    assert r.returncode in (0, 1), r.stdout + r.stderr
    assert json.loads(r.stdout)["model"] == "closed-form"


@pytest.mark.parametrize("command", ["modal", "readout", "strength"])
def test_a_die_command_takes_closed_form(die_folder, command):
    r = run_cli(command, "--model", "closed-form", "--json", cwd=die_folder)
    assert r.returncode in (0, 1), r.stdout + r.stderr
    assert "error" not in json.loads(r.stdout)


@pytest.mark.parametrize("command", sorted(TAKES))
def test_a_level_a_die_command_does_not_compute_is_refused_naming_its_levels(
        die_folder, command):
    r = run_cli(command, "--model", "fem2d", "--json", cwd=die_folder)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("--model", "fem2d")
    assert error["allowed"] == "one of " + ", ".join(TAKES[command]) + " for a die"
