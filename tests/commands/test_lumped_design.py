"""``tactcad lumped`` in a project: K_m and K_r from the project's design, the values
``tactcad stiffness`` gives at its default level, unless --km and --kr are given (it
refused "the following arguments are required: --km, --kr")."""

from __future__ import annotations

import json
from pathlib import Path

from conftest import run_cli

TI = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3"


def test_an_arrays_project_gives_lumped_its_k_m_and_k_r(tmp_path):
    done = run_cli("lumped", "--kobj", "2", "--json", cwd=TI)
    assert done.returncode == 0, done.stdout + done.stderr
    out = json.loads(done.stdout)
    m, r = out["stiffness_source"]["unit"]
    for element, key in ((m, "k_m_N_per_mm"), (r, "k_r_N_per_mm")):
        k = json.loads(run_cli("stiffness", "--element", str(element), "--json",
                               cwd=TI).stdout)["stiffness_N_per_mm"]
        assert out[key] == k
    assert out["stiffness_source"]["model"] == "closed-form"
    assert out["r"] == (out["k_r_N_per_mm"] + 2) / (out["k_m_N_per_mm"] + 2)
    # the design word and --design read the same; --km given wins over the design's
    word = json.loads(run_cli("lumped", str(TI), "--kobj", "2", "--json").stdout)
    assert word["k_m_N_per_mm"] == out["k_m_N_per_mm"]
    given = json.loads(run_cli("lumped", "--design", str(TI), "--km", "0.5", "--kobj", "2",
                               "--json").stdout)
    assert given["k_m_N_per_mm"] == 0.5 and given["k_r_N_per_mm"] == out["k_r_N_per_mm"]
    text = run_cli("lumped", "--kobj", "2", cwd=TI).stdout
    assert "K_m and K_r from ti_array_2x3.toml unit" in text.splitlines()[0]
    # outside a project, without --km and --kr: a refusal naming both
    empty = run_cli("lumped", "--kobj", "2", "--json", cwd=tmp_path)
    assert empty.returncode == 2
    err = json.loads(empty.stdout)["error"]
    assert err["field"] == "--km and --kr" and "project folder" in err["allowed"]


def test_a_dies_project_gives_lumped_its_rows_k(die_folder):
    done = run_cli("lumped", "--r", "3", "--json", cwd=die_folder)
    assert done.returncode == 0, done.stdout + done.stderr
    out = json.loads(done.stdout)
    rows = {row["role"]: row["stiffness_N_per_mm"]
            for row in json.loads(run_cli("stiffness", "--json", cwd=die_folder).stdout)["rows"]}
    assert (out["k_m_N_per_mm"], out["k_r_N_per_mm"]) == (rows["measuring"], rows["reference"])
    assert out["stiffness_source"]["unit"] is None


def test_an_array_whose_units_differ_asks_for_the_unit():
    done = run_cli("lumped", "--kobj", "2", "--json")  # the shipped 2 x 5 example
    assert json.loads(done.stdout)["error"]["field"] == "--km and --kr"
    example = Path(__file__).resolve().parents[2] / "src" / "tactcad" / "examples" / "macro_array"
    err = json.loads(run_cli("lumped", str(example), "--kobj", "2", "--json").stdout)["error"]
    assert err["field"] == "--unit" and "3" in err["allowed"]
    one = json.loads(run_cli("lumped", str(example), "--kobj", "2", "--unit", "3",
                             "--json").stdout)
    assert one["stiffness_source"]["unit"][0] == 3
