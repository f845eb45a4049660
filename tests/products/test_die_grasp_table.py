"""A die's ``grasp`` table prints each unit's true K_obj and R, the columns ``K_obj true``
and ``R true`` an array's grasp table has: the header's one K_obj is the tissue under one
post on the slab's thickness, while under the wedge each unit's error is measured against
its own posts' true K_obj (``--json``'s ``K_obj_true_N_per_mm``), which the table did not
show."""

from __future__ import annotations

import json
from pathlib import Path

from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
TI = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def _table(text: str) -> tuple[list[str], list[list[str]]]:
    """The first Markdown table of ``text``: its header cells and its rows' cells."""
    rows = [[c.strip() for c in line.strip().strip("|").split("|")]
            for line in text.splitlines() if line.startswith("| ")]
    return rows[0], [r for r in rows[1:] if set(r) != {"---"}]


def test_a_dies_table_shows_the_true_kobj_and_r_each_error_is_against(die_folder):
    text = run_cli("grasp", cwd=die_folder)
    assert text.returncode == 0, text.stdout + text.stderr
    record = json.loads(run_cli("grasp", "--json", cwd=die_folder).stdout)
    header, rows = _table(text.stdout)
    array_header, _ = _table(run_cli("grasp", "--design", TI).stdout)
    for column in ("K_obj true", "R true"):  # as the array's table names them
        assert column in header and column in array_header
    units = record["grasp"]["units"]
    assert len(rows) == len(units)
    k_true, r_true = header.index("K_obj true"), header.index("R true")
    for row, unit in zip(rows, units, strict=True):
        assert row[0] == unit["unit"]
        assert row[k_true] == f"{unit['K_obj_true_N_per_mm']:.4g}"
        assert row[r_true] == f"{unit['R_true']:.4g}"
        # the error printed is the read K_obj against that true one, not the header's
        assert unit["error_rel"] == \
            unit["K_obj_read_N_per_mm"] / unit["K_obj_true_N_per_mm"] - 1
    # under the wedge the units' true K_obj are their own, and the header says so
    assert any(u["K_obj_true_N_per_mm"] != record["K_obj_N_per_mm"] for u in units)
    assert "its own true K_obj" in text.stdout.splitlines()[0]
