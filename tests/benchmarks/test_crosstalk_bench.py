"""``tactcad bench crosstalk`` prints each level's cost and error."""

import json

import pytest
from conftest import run_cli

from tactcad.mechanics.stack_crosstalk import crosstalk_models


@pytest.mark.slow  # runs the 3D level on a 2 x 2 array
def test_every_level_has_cost_and_error():
    r = run_cli("bench", "crosstalk", "--set", "array.columns=2",
                "--set", "arms.lengths_mm=[4,6,5,7]", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert [q["model"] for q in d["levels"]] == list(crosstalk_models())
    for q in d["levels"]:
        assert q["solve_s"] > 0 and q["crosstalk_rel"] > 0 and q["error_estimate_rel"] >= 0
        assert q["asymmetry_rel"] < 1e-12
