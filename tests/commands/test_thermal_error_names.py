"""`thermal --json` gives each element's grid strain with the grid strain's own error
(`grid_strain_error_rel`), beside K's (`error_estimate_rel`), as `stiffness --json` names
them (the grid strain stood beside K's error alone)."""

from __future__ import annotations

import json

from conftest import run_cli


def test_thermal_states_the_grid_strains_own_error_as_stiffness_does(tmp_path):
    made = run_cli("design", "--jaw", "10", "--kr-over-km", "6", "--kobj-range", "0.3", "3",
                   "--full-scale-force", "0.121", "--material", "17-4PH-H900", "--out",
                   "mycomb", cwd=tmp_path)
    assert made.returncode == 0, made.stdout + made.stderr
    folder = tmp_path / "mycomb"
    thermal = json.loads(run_cli("thermal", "--json", cwd=folder).stdout)
    for element in thermal["elements"]:
        number = element["element"]
        stiffness = json.loads(run_cli("stiffness", "--element", str(number), "--json",
                                       cwd=folder).stdout)
        assert element["grid_strain_per_N"] == stiffness["grid_strain_per_N"]
        assert element["grid_strain_error_rel"] == stiffness["grid_strain_error_rel"]
        assert element["error_estimate_rel"] == stiffness["error_estimate_rel"]
    assert any("grid_strain_error_rel" in note for note in thermal["notes"])
