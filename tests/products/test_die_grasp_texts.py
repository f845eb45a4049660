"""What a die's grasp says follows what it was asked: without tissue coupling it names no
coupling left in the reading."""

from __future__ import annotations

import json

import pytest

from conftest import DIE_EXAMPLE as EXAMPLE, run_cli

def test_no_coupling_caveat_without_coupling(die_folder):
    off = run_cli("grasp", "--coupling", "none", cwd=die_folder)
    assert off.returncode == 0, off.stdout + off.stderr
    assert "coupling between neighbouring posts stays in it" not in off.stdout
    assert "not coupled between the posts" in off.stdout
    on = run_cli("grasp", cwd=die_folder).stdout
    assert "coupling between neighbouring posts stays in it" in on
    record = json.loads(run_cli("grasp", "--coupling", "none", "--json",
                                cwd=die_folder).stdout)
    assert "stays in it" not in record["reasons"]["error"]


@pytest.mark.parametrize("kobj", ["1000", "0.01"])
def test_a_kobj_outside_the_dies_range_is_warned_and_not_read(die_folder, kobj):
    import tactcad

    lo, hi = tactcad.load(die_folder / EXAMPLE.name).plan.kobj_range_N_per_mm
    r = run_cli("grasp", "--kobj", kobj, cwd=die_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    warning = next(line for line in r.stdout.splitlines() if line.startswith("warning:"))
    assert f"--kobj {float(kobj):g} N/mm" in warning and f"{lo:g} ... {hi:g} N/mm" in warning
    assert not any(line.endswith("| yes |") for line in r.stdout.splitlines())
    record = json.loads(run_cli("grasp", "--kobj", kobj, "--json", cwd=die_folder).stdout)
    assert record["warnings"] and not any(u["reads"] for u in record["grasp"]["units"])
    inside = json.loads(run_cli("grasp", "--json", cwd=die_folder).stdout)
    assert not inside["warnings"] and all(u["in_kobj_range"] for u in inside["grasp"]["units"])


def test_no_line_of_a_passing_grasp_starts_with_error(die_folder):
    """A grasp that exits 0 wrote its eq. 3 caveat as "error: eq. 3 on the read R: ...", a
    line a CI log's grep for "error:" took for a failure; it names the K_obj error now."""
    r = run_cli("grasp", cwd=die_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    assert not [line for line in r.stdout.splitlines() if line.lstrip().startswith("error:")]
    assert any(line.startswith("K_obj error of eq. 3 on the read R:")
               for line in r.stdout.splitlines())
