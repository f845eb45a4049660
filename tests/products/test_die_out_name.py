"""``tactcad die --out`` holds its folder's name to the rule ``design --out`` and ``tactcad
new`` keep (1-64 characters A-Z a-z 0-9 _ . -): a folder ``dié`` was written."""

from __future__ import annotations

import json

import pytest

from conftest import run_cli

TARGETS = ("--jaw", "5", "--kr-over-km", "6", "--kobj-range", "0.5", "4",
           "--full-scale-force", "0.008")


@pytest.mark.parametrize("name", ["dié", "my die", "Zange_ü_δ"])
def test_die_out_with_a_name_outside_the_rule_is_refused_before_anything_is_written(
        tmp_path, name):
    from tactcad.vocabulary.schema import NAME_ALLOWED

    r = run_cli("die", *TARGETS, "--out", name, "--json", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "--out" and error["value"] == name
    assert error["allowed"].startswith(NAME_ALLOWED)
    assert list(tmp_path.iterdir()) == []
    # the same rule as design --out: the same words
    d = run_cli("design", *TARGETS, "--out", name, "--json", cwd=tmp_path)
    assert json.loads(d.stdout)["error"]["allowed"].startswith(NAME_ALLOWED)
