"""``tactcad design --jaw``: every option a refusal offers designs when pasted (an offered
force carries the accuracy it then needs, offered columns the force), and a missed
``--kobj-accuracy`` is met by any comb that counts before it is refused."""

from __future__ import annotations

import json

import pytest
from conftest import run_cli

from tactcad.errors import DesignError

JAW_CASE = ["design", "--jaw", "10", "--kr-over-km", "10", "--kobj-range", "0.5", "5"]


@pytest.mark.slow  # whole jaw searches, each offer's pasted line searched again
@pytest.mark.parametrize("asked", [
    ["--full-scale-force", "0.3", "--kobj-accuracy", "0.05"],
    ["--full-scale-force", "0.3", "--columns", "12"],
    ["--kr-over-km", "3", "--full-scale-force", "0.5", "--kobj-accuracy", "0.05"],
])
def test_every_offer_of_a_jaw_refusal_designs_when_pasted(tmp_path, asked):
    line = [*JAW_CASE, *asked, "--json"]
    r = run_cli(*line, "--out", str(tmp_path / "asked"))
    assert r.returncode == 2, r.stderr
    offers = [a["option"] for a in json.loads(r.stdout)["error"]["alternatives"]]
    assert offers
    for i, offer in enumerate(offers):
        r = run_cli(*line, *offer.split(), "--out", str(tmp_path / f"pasted{i}"))
        assert r.returncode == 0, (offer, r.stdout[-600:])


@pytest.mark.slow  # a whole jaw search, its combs judged in turn
def test_a_missed_accuracy_takes_the_first_comb_that_counts_and_meets_it(tmp_path):
    r = run_cli(*JAW_CASE, "--full-scale-force", "0.05", "--material", "Ti-6Al-4V",
                "--kobj-accuracy", "0.12", "--json", "--out", str(tmp_path / "ti"))
    assert r.returncode == 0, r.stdout[-600:]


def test_a_pasted_option_replaces_the_one_asked_and_adds_the_others():
    from tactcad.commands.design import pasted_line

    words = ["--full-scale-force", "0.3", "--columns", "12", "--out", "x"]
    assert pasted_line(words, "--columns 6 --full-scale-force 0.144 --kobj-accuracy 0.2") == [
        "--full-scale-force", "0.144", "--columns", "6", "--out", "x", "--kobj-accuracy", "0.2"]


def test_an_offer_is_widened_only_by_another_target_of_its_own_construction():
    from tactcad.commands.design import widened_paste

    refusal = DesignError("--kobj-accuracy", 0.05, ">= 0.16", alternatives=[
        {"option": "--construction mems-die --kobj-accuracy 0.2"},
        {"option": "--construction monolithic-comb --kobj-accuracy 0.16"}])
    assert widened_paste("--construction monolithic-comb --full-scale-force 0.144",
                         refusal) == ("--construction monolithic-comb --full-scale-force "
                                      "0.144 --kobj-accuracy 0.16")
    other = DesignError("--jaw", "10", "a jaw", alternatives=[{"option": "--jaw 12"}])
    assert widened_paste("--columns 6", other) is None
