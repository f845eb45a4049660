"""A die's grasp judges each beam against its own rated force, the one strength and verify
rate it at (:meth:`DiePlan.rated_force_N`), and its texts say so."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import DIE_EXAMPLE as EXAMPLE, run_cli

def _plan(folder: Path):
    import tactcad

    return tactcad.load(folder / EXAMPLE.name).plan


def test_each_beam_is_over_its_own_rating(die_folder):
    plan = _plan(die_folder)
    r = run_cli("grasp", "--force-N", "1", "--json", cwd=die_folder)
    assert r.returncode == 0, r.stdout + r.stderr
    tips = json.loads(r.stdout)["grasp"]["tips"]
    by_number = {b.number: b for b in plan.beams}
    measuring = [t for t in tips if by_number[t["site"]].role == "measuring"]
    assert measuring
    for t in tips:
        rated = plan.rated_force_N(by_number[t["site"]])
        assert t["rated_force_N"] == pytest.approx(rated, rel=1e-12)
        assert t["over_rating"] == (t["element_force_N"] > rated * (1 + 1e-9))
    # a measuring beam is rated below the die's full scale: the test means something
    assert all(t["rated_force_N"] < plan.full_scale_force_N for t in measuring)


def test_the_default_force_is_half_each_beams_own_rating(die_folder):
    plan = _plan(die_folder)
    text = run_cli("grasp", cwd=die_folder).stdout
    assert "half each beam's own rated force" in text
    assert f"half the rated {plan.full_scale_force_N:g} N" not in text
    record = json.loads(run_cli("grasp", "--json", cwd=die_folder).stdout)
    expected = 0.5 * sum(plan.rated_force_N(b) for b in plan.beams)
    assert record["grasp"]["total_force_N"] == pytest.approx(expected, rel=1e-6)
    assert record["full_scale_force_N"] == plan.full_scale_force_N
