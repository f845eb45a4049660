"""`design --jaw` says how many of its candidates count in a sentence ("48 candidates, 2 of
them count"; it said "48 candidates, 2 count")."""

from __future__ import annotations

import pytest

from conftest import run_cli


@pytest.mark.parametrize("counted, words", [(0, "none of them counts"),
                                            (1, "1 of them counts"),
                                            (2, "2 of them count")])
def test_the_counted_candidates_in_words(counted, words):
    from tactcad.commands.design import counted_words

    assert counted_words(counted) == words


def test_a_jaws_design_says_how_many_of_its_candidates_count(tmp_path):
    r = run_cli("design", "--jaw", "10", "--kr-over-km", "6", "--kobj-range", "0.3", "3",
                "--full-scale-force", "0.121", "--material", "17-4PH-H900", "--out", "comb",
                cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    line = next(x for x in r.stdout.splitlines() if " candidates, " in x)
    assert line.strip().split(", ", 1)[1].split()[1:3] == ["of", "them"], line
