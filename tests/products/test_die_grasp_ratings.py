"""A die's grasp judges each beam against its own rated force, the one strength and verify
rate it at (:meth:`DiePlan.rated_force_N`), and its texts say so."""

from __future__ import annotations

import json
import re
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


def test_the_full_scale_force_is_described_as_the_reference_rows_rating(capsys):
    # each row is rated at what its stop and limits allow: the full-scale force is the
    # reference row's; the measuring row's is less, so "the rated force on each beam" is wrong
    import tactcad
    from tactcad import cli
    from tactcad.products.silicon_die.design.die_file import DieSection

    plan = tactcad.load(EXAMPLE).plan
    rated = {b.role: plan.rated_force_N(b) for b in plan.beams}
    assert rated["reference"] == plan.full_scale_force_N > rated["measuring"]
    texts = {"[die] full_scale_force_N": str(DieSection.model_fields["full_scale_force_N"])}
    for command in ("die", "design"):
        with pytest.raises(SystemExit):
            cli.main([command, "--help"])
        help_text = " ".join(capsys.readouterr().out.split())
        # the option's own text: from its name in the options' list (after the usage's) to
        # the next option's
        entry = help_text.rsplit("--full-scale-force F ", 1)[-1]
        texts[f"{command} --help"] = re.split(r" --[a-z]", entry, maxsplit=1)[0]
    for where, text in texts.items():
        assert "each beam" not in text, where
        assert "reference row's rated force" in " ".join(text.split()), where
        assert "tactcad strength" in text, where
