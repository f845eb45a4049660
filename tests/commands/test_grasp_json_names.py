"""``grasp --json`` names the design's K_obj range ``kobj_range_N_per_mm``, as ``budget
--json``, ``verify --json`` and the glossary do (it was ``K_obj_range_N_per_mm``). The old
key is still written beside it with the same value, deprecated, and the record lists it in
``deprecated_keys`` (old -> new), the budget's mechanism; on an array, a die and in the
API."""

from __future__ import annotations

import json
from pathlib import Path

from conftest import DIE_EXAMPLE, run_cli

ROOT = Path(__file__).resolve().parents[2]
TI = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
OLD, NEW = "K_obj_range_N_per_mm", "kobj_range_N_per_mm"


def _json(*argv, cwd=None) -> dict:
    r = run_cli(*argv, "--json", cwd=cwd)
    assert r.returncode in (0, 1), r.stdout + r.stderr
    return json.loads(r.stdout)


def _renamed_as_declared(record: dict) -> None:
    assert record["deprecated_keys"] == {OLD: NEW}
    for old, new in record["deprecated_keys"].items():
        assert record[old] == record[new]


def test_an_arrays_grasp_names_the_range_as_budget_does():
    grasp = _json("grasp", "--design", TI)
    budget = _json("budget", "--design", TI)
    assert grasp[NEW] == budget[NEW] == [1.0, 5.0]
    _renamed_as_declared(grasp)


def test_the_api_grasp_is_the_commands_record_with_the_new_name():
    import tactcad

    record = tactcad.load(TI).grasp()
    assert record[NEW] == [1.0, 5.0]
    _renamed_as_declared(record)


def test_a_dies_grasp_names_the_range_as_its_design_does(die_folder):
    import tactcad

    grasp = _json("grasp", cwd=die_folder)
    assert grasp[NEW] == list(tactcad.load(die_folder / DIE_EXAMPLE.name).plan.kobj_range_N_per_mm)
    _renamed_as_declared(grasp)
