"""`grasp --angle-deg` has one range, the jaw's own (0 ... its opening), and a value under
it is refused in the same words as one over it (-1 said "0 ... 90", 90 "0 ... 30")."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import run_cli


def _allowed(*argv, cwd=None) -> str:
    r = run_cli("grasp", *argv, "--json", cwd=cwd)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "--angle-deg"
    return error["allowed"]


@pytest.mark.parametrize("where", ["array", "die"])
def test_an_angle_under_and_over_the_jaws_range_are_refused_alike(where, tmp_path, die_folder):
    cwd = die_folder if where == "die" else tmp_path
    under, over = _allowed("--angle-deg", "-1", cwd=cwd), _allowed("--angle-deg", "90", cwd=cwd)
    assert under == over and under.startswith("0 ... ") and "the jaw's opening" in under


ROOT = Path(__file__).resolve().parents[2]


def test_the_apis_angle_is_refused_in_the_commands_words():
    # the API checked angle_deg against 0 ... 90 degrees before the jaw saw it
    import tactcad
    from tactcad.errors import DesignError

    project = tactcad.load(ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")
    said = set()
    for angle in (-1.0, 90.0):
        with pytest.raises(DesignError) as err:
            project.grasp(angle_deg=angle)
        assert err.value.field == "angle_deg"
        said.add(err.value.allowed)
    cli_said = _allowed("--angle-deg", "90", "--design",
                        str(ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"))
    assert said == {cli_said}
    with pytest.raises(DesignError, match="the jaw's opening"):
        project.grasp(angle_deg=float("nan"))


def test_an_angle_outside_the_jaws_range_is_refused_before_any_model_runs(capsys):
    # with arms 5.5 x their height the comb's closed form ran first and said its range
    # warning before the refusal
    from tactcad import cli

    design = str(ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")
    assert cli.main(["grasp", "--design", design, "--set", "element.arm_height_mm=0.55",
                     "--angle-deg", "1e6"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("tactcad: error: --angle-deg = 1000000.0: allowed 0 ... ") and \
        "the jaw's opening" in err and "warning" not in err, err
