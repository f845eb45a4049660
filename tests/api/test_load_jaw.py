"""A design's stated ``[grasper_jaw]`` is judged when the design is read: the jaw's part
rules (the closed jaws in the shaft, the jaw long enough for the insert's pocket) refuse
it in ``tactcad.load``, ``load_design`` and every command, not first part-way through
``check``."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import tactcad
from tactcad import cli
from tactcad.design.array_plan import load_design
from tactcad.errors import DesignErrors

EXAMPLES = Path(tactcad.__file__).parent / "examples"
COMB = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.mark.parametrize("override, field, words", [
    # the insert's pocket, the pin's steel and the distal wall need a longer jaw
    ({"grasper_jaw.length_mm": 20.0}, "grasper_jaw.length_mm", "value >= "),
    # 7.5 mm wide, the 10 mm class's jaws closed (5.6 + 1.5 mm) pass no 10 mm trocar
    ({"grasper_jaw.width_mm": 7.5}, "grasper_jaw.thickness_mm", "<= "),
])
def test_load_refuses_a_stated_jaw_the_insert_cannot_fit(override, field, words):
    with pytest.raises(DesignErrors) as err:
        tactcad.load(COMB, set=override)
    e = next(e for e in err.value.errors if e.field.startswith("grasper_jaw."))
    assert e.field == field and words in e.allowed
    assert e.value == pytest.approx(override.get(field, 5.6))


def test_check_refuses_the_jaw_up_front_naming_the_set_value(tmp_path, capsys):
    code = cli.main(["check", "--design", str(COMB), "--set", "grasper_jaw.length_mm=20",
                     "--out", str(tmp_path / "chk"), "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and error["field"] == "grasper_jaw.length_mm" and error["value"] == 20.0
    assert error["message"].startswith("--set grasper_jaw.length_mm=20: ")
    assert not (tmp_path / "chk").exists()  # refused before anything is judged or written


def test_load_design_refuses_a_stated_jaw_the_insert_cannot_fit(tmp_path):
    text = COMB.read_text(encoding="utf-8").replace("length_mm = 34.0", "length_mm = 20.0")
    assert "length_mm = 20.0" in text
    bad = tmp_path / COMB.name
    bad.write_text(text, encoding="utf-8")
    with pytest.raises(DesignErrors) as err:
        load_design(bad)
    assert [e.field for e in err.value.errors] == ["grasper_jaw.length_mm"]
    assert err.value.errors[0].file == COMB.name


@pytest.mark.parametrize("design", [None, COMB, EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml"])
def test_designs_whose_jaw_fits_or_that_state_none_still_load(design):
    project = tactcad.load(design)
    assert project.plan.slots
