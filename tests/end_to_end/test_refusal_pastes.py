"""Every option a ``tactcad design`` refusal offers designs when pasted, and the largest
force it offers is the one the design then reports.

A lab's review pasted a CuBe refusal's ``--material 17-4PH-H900`` ("meets every target"):
refused again, offering ``--kr-over-km 8.22`` (refused, offering 8.21) and the very
``--kobj-range 1 20`` asked; the alternatives were judged on one layout, not by the search
that a pasted command runs. Its ``--full-scale-force 0.281`` then designed and reported
0.2849 N, which designed too."""

from __future__ import annotations

import json
import shlex

import pytest

from tactcad import cli

#: The review's refusals: K_r/K_m 8 over 1-20 N/mm at 0.3 N, 2 x 3, CuBe and 17-4PH.
CASE = ["--kr-over-km", "8", "--kobj-range", "1", "20", "--full-scale-force", "0.3",
        "--columns", "3", "--verify", "none", "--no-cache", "--json"]


def flag_groups(argv: list[str]) -> list[list[str]]:
    """``argv`` as [flag, its values...] groups."""
    groups: list[list[str]] = []
    for token in argv:
        if token.startswith("--"):
            groups.append([token])
        else:
            groups[-1].append(token)
    return groups


def pasted(argv: list[str], option: str) -> list[str]:
    """``argv`` with ``option`` pasted: each flag it gives replaces the same flag's values
    (a ``--set`` is added)."""
    new = flag_groups(shlex.split(option))
    given = {g[0] for g in new if g[0] != "--set"}
    kept = [g for g in flag_groups(argv) if g[0] not in given]
    return [token for group in (*kept, *new) for token in group]


def run(argv: list[str], capsys) -> tuple[int, dict]:
    code = cli.main(["design", *argv])
    out = capsys.readouterr().out
    return code, json.loads(out)


@pytest.mark.slow  # two refusals and a whole design search per option offered
@pytest.mark.parametrize("material", ["CuBe-C17200-TF00", "17-4PH-H900"])
def test_every_option_a_refusal_offers_designs_when_pasted(material, tmp_path, capsys):
    asked = [*CASE, "--material", material]
    code, report = run([*asked, "--out", str(tmp_path / "refused.toml")], capsys)
    assert code == 2, report
    alternatives = report["error"]["alternatives"]
    assert alternatives
    forces_last = sorted(alternatives, key=lambda a: a["option"].startswith("--full-scale"))
    for i, alt in enumerate(forces_last):
        argv = pasted(asked, alt["option"])
        assert flag_groups(argv) != flag_groups(asked), f"offered what was asked: {alt}"
        code, got = run([*argv, "--out", str(tmp_path / f"paste{i}.toml")], capsys)
        assert code == 0, f"pasted {alt['option']!r}: {got.get('error', {}).get('message')}"
        if alt["option"].split()[0] == "--full-scale-force":  # the refusal's figure, reported
            offered = float(alt["option"].split()[1])
            assert got["across_layouts_force_N"] == pytest.approx(offered, abs=1e-12), got
