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
                   "--full-scale-force", "0.0075", "--out", "mydie", cwd=tmp_path)
    assert made.returncode == 0, made.stdout + made.stderr
    r = run_cli("grasp", "--slab-thickness-mm", "0.001", "--profile", "slab", "--json",
                cwd=tmp_path / "mydie")
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("--slab-thickness-mm", 0.001)
    # refused before any solve: the contact solves do not converge on a layer that thin
    # (its contact then did not settle either)
    assert "contact solves converge" in error["allowed"] and "100" in error["allowed"]
    assert "thinner than the contact model resolves" in error["message"]


def test_at_the_default_thickness_the_refusal_names_the_option_too():
    """Not given, the slab's thickness is the default: an unsettled contact there names
    --slab-thickness-mm with that default and the thicker range to give (it named a field
    ``grasp`` no option has)."""
    from tactcad.commands.options import grasp_option_error
    from tactcad.in_use.grasp_experiment import UnsettledContact

    exc = UnsettledContact("jaw.slab_thickness_mm", 0.002, "a slab on which the contact "
                           "settles", "the stops and lift-off did not settle")
    error = grasp_option_error(exc, argparse.Namespace(slab_thickness_mm=None))
    assert (error.field, error.value) == ("--slab-thickness-mm", 0.002)
    assert "0.002" in error.allowed and "100" in error.allowed and "default" in error.why


def test_a_dies_grasp_at_a_default_too_thin_names_the_option(tmp_path, monkeypatch):
    from tactcad.products.silicon_die.in_use import die_grasp

    made = run_cli("design", "--jaw", "5", "--kr-over-km", "8", "--kobj-range", "0.4", "4",
                   "--full-scale-force", "0.0075", "--out", "mydie", cwd=tmp_path)
    assert made.returncode == 0, made.stdout + made.stderr
    monkeypatch.setattr(die_grasp, "DEFAULT_SLAB_MM", 0.001)  # a default too thin to settle
    r = run_cli("grasp", "--profile", "slab", "--json", cwd=tmp_path / "mydie")
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("--slab-thickness-mm", 0.001)
    assert "contact solves converge" in error["allowed"] and "100" in error["allowed"]
    assert "thinner than the contact model resolves" in error["message"]
    assert "default" in error["message"]
    text = run_cli("grasp", "--profile", "slab", cwd=tmp_path / "mydie")
    assert text.returncode == 2 and "--slab-thickness-mm" in text.stderr, text.stderr
