"""``tactcad bench crosstalk`` prints each level's cost and error."""

import json

import pytest
from conftest import run_cli

from tactcad.mechanics.crosstalk_ladder import construction_levels


@pytest.mark.slow  # runs the 3D level on a 2 x 2 array
def test_every_level_has_cost_and_error():
    r = run_cli("bench", "crosstalk", "--set", "array.columns=2",
                "--set", "arms.lengths_mm=[4,6,5,7]", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    # a stacked array's levels, not a comb's
    assert [q["model"] for q in d["levels"]] == list(construction_levels("stacked"))
    for q in d["levels"]:
        assert q["solve_s"] > 0 and q["crosstalk_rel"] > 0 and q["error_estimate_rel"] >= 0
        assert q["asymmetry_rel"] < 1e-12


@pytest.mark.slow  # the comb's plane FE twice (about 20 s)
def test_a_comb_benches_its_own_levels():
    """The shipped comb: the spine beam and the row sheets' plane FE, each with its cost
    and its error, the beam's distance to the FE beside them."""
    r = run_cli("bench", "crosstalk", "--design",
                "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert [q["model"] for q in d["levels"]] == list(construction_levels("monolithic-comb"))
    beam, fem = d["levels"]
    for q in d["levels"]:
        assert q["solve_s"] > 0 and q["crosstalk_rel"] > 0 and q["error_estimate_rel"] > 0
        assert q["asymmetry_rel"] < 1e-12 and q["elements"] == 12
    assert fem["vs_last_level_rel"] == 0 and beam["vs_last_level_rel"] > 0
    assert beam["solve_s"] < fem["solve_s"]
    text = run_cli("bench", "crosstalk", "--design",
                   "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml")
    assert "comb-fem2d" in text.stdout and "error estimate" in text.stdout
