"""The stiffness ladder is declared once (:data:`tactcad.mechanics.ladder.LEVELS`):
a new level is one function plus one registration, and every command's
``--model`` choices, help, the strength study and the Python API take it."""

from __future__ import annotations

import json
from dataclasses import replace

import pytest

import tactcad
from tactcad.cli import build_parser, main
from tactcad.mechanics import ladder
from tactcad.mechanics.stiffness_result import StiffnessResult


def estimate_double(g, material, *, element=None, **options) -> StiffnessResult:
    """A stand-in level: the closed form's K doubled (N/mm), its error 50 %."""
    base = ladder.estimate("closed-form", g, material, element=element)
    return replace(base, model="double", stiffness_N_per_mm=2 * base.stiffness_N_per_mm,
                   error_estimate_rel=0.5)


@pytest.fixture
def double_level():
    ladder.register_level(ladder.Level("double", __name__, "estimate_double", meshed=False,
                                       cost="~2 ms"))
    try:
        yield
    finally:
        del ladder.LEVELS["double"]


def _model_choices(command: str) -> tuple[str, ...]:
    sub = next(a for a in build_parser()._actions if a.__class__.__name__ == "_SubParsersAction")
    parser = sub.choices[command]
    action = next(a for a in parser._actions if "--model" in a.option_strings)
    return tuple(action.choices)


def test_the_ladder_is_four_levels_cheapest_first():
    assert ladder.models() == ("closed-form", "beam", "fem2d", "fem3d") == ladder.MODELS
    assert ladder.meshed_models() == ("fem2d", "fem3d")
    with pytest.raises(ValueError, match="registered already"):
        ladder.register_level(ladder.LEVELS["beam"])


def test_a_registered_level_reaches_every_command_and_the_api(double_level, capsys):
    for command in ("stiffness", "verify", "readout", "strength", "table2", "evaluate",
                    "calibrate"):
        assert "double" in _model_choices(command), command
    assert main(["stiffness", "--element", "8", "--model", "double", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    cf = tactcad.load().element(8).stiffness()
    assert out["model"] == "double"
    assert out["stiffness_N_per_mm"] == pytest.approx(2 * cf.stiffness_N_per_mm)
    assert "double ~2 ms" in ladder.levels_help()
    # a level without a mesh gets the closed-form stress formula in the strength study
    record = tactcad.load().element(8).strength(model="double")
    assert record.full_scale_force_N > 0


def test_an_unknown_level_is_refused_naming_the_levels():
    with pytest.raises(ladder.UnknownModelError, match="allowed closed-form, beam, fem2d, fem3d"):
        ladder.estimate("nope", tactcad.load().element(1).geometry, tactcad.load().plan.material)
