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
    # 7.5 mm wide, the 10 mm class's jaws closed (5.6 + 1.5 mm) pass no 10 mm trocar: the
    # width set is named, not the class's thickness the design never states
    ({"grasper_jaw.width_mm": 7.5}, "grasper_jaw.width_mm", "<= "),
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


def _refusal(argv, capsys):
    """The exit code and the JSON error of ``tactcad`` run with ``argv``."""
    code = cli.main(argv)
    return code, json.loads(capsys.readouterr().out)["error"]


def _bound(allowed: str) -> float:
    """The number of an ``allowed`` text's ``<= X mm`` or ``>= X mm``."""
    return float(allowed.split(" ")[1])


@pytest.mark.parametrize("key, value", [
    ("width_mm", 9.5),            # narrower than the shaft, too wide beside 5.6 + 1.5 mm
    ("width_mm", 7.5),
    ("width_clearance_mm", 2.0),  # the shaft less 2 mm: 8 mm wide
    ("thickness_mm", 8.0),        # 6.5 mm wide: the two jaws 9.5 mm thick
    ("opposing_jaw_mm", 4.0),
])
def test_verify_names_the_jaw_key_set_that_breaks_the_closed_jaws_rule(key, value, capsys):
    """The closed jaws (width x both thicknesses) pass the shaft: a refusal of a value set
    on the command line names that key, its value and the range that passes, and the
    range's bound is a value the design loads with."""
    code, error = _refusal(["verify", "--design", str(COMB), "--set",
                            f"grasper_jaw.{key}={value}", "--no-cache", "--json"], capsys)
    assert code == 2 and error["field"] == f"grasper_jaw.{key}" and error["value"] == value
    assert error["message"].startswith(f"--set grasper_jaw.{key}={value}: ")
    bound = _bound(error["allowed"])
    assert (bound > value) if key == "width_clearance_mm" else (bound < value)
    assert tactcad.load(COMB, set={f"grasper_jaw.{key}": bound}).plan.slots


def test_a_jaw_wider_than_its_shaft_is_refused_naming_its_width(capsys):
    code, error = _refusal(["verify", "--design", str(COMB), "--set",
                            "grasper_jaw.width_mm=12.5", "--no-cache", "--json"], capsys)
    assert code == 2 and error["field"] == "grasper_jaw.width_mm" and error["value"] == 12.5
    assert _bound(error["allowed"]) == 10.0  # the 10 mm class's shaft


def _jaw_width_mm() -> float:
    from tactcad.partlib.grasper_jaw import jaw_part

    return jaw_part(tactcad.load(COMB).plan).geometry.width_mm


@pytest.mark.parametrize("scale", [1.5, 0.2])
def test_a_tissue_slab_off_the_jaws_face_is_refused_at_load(scale, tmp_path, capsys):
    """A slab wider than the jaw's face (it lies on the opposing jaw) or too narrow to lie
    under the window over the tips is refused when the design is read, naming the key,
    its value and the range, before anything is judged or written."""
    width = round(_jaw_width_mm() * scale, 3)
    code, error = _refusal(["check", "--design", str(COMB), "--set",
                            f"tissue_slab.width_mm={width}", "--out", str(tmp_path / "chk"),
                            "--json"], capsys)
    assert code == 2 and error["field"] == "tissue_slab.width_mm" and error["value"] == width
    assert error["allowed"].endswith(f"<= {_jaw_width_mm():g} mm")
    assert not (tmp_path / "chk").exists()


def test_a_tissue_slab_as_wide_as_the_jaws_face_loads():
    project = tactcad.load(COMB, set={"tissue_slab.width_mm": _jaw_width_mm()})
    assert project.plan.raw["tissue_slab"]["width_mm"] == _jaw_width_mm()


@pytest.mark.parametrize("thickness", [0, -1.0])
def test_a_tissue_slab_without_thickness_is_refused_at_load(thickness, capsys):
    code, error = _refusal(["verify", "--design", str(COMB), "--set",
                            f"tissue_slab.thickness_mm={thickness}", "--no-cache", "--json"],
                           capsys)
    assert code == 2 and error["field"] == "tissue_slab.thickness_mm"
    assert "0 < value" in error["allowed"]


def test_a_stacked_array_is_not_held_to_a_jaw_it_does_not_seat_in():
    """The stacked array's construction seats in no jaw (no jaw search in its registry
    entry): a [grasper_jaw] it states is not judged against it."""
    from tactcad.design.construction_registry import construction

    assert not construction("stacked").jaw_design
    project = tactcad.load(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml",
                           set={"grasper_jaw.width_mm": 7.5})
    assert project.plan.construction == "stacked"


def test_of_two_keys_set_the_one_some_value_of_which_passes_is_named():
    """Both jaws together (5.6 + 9 mm) thicker than the 10 mm shaft: no width of the jaw
    passes, so the refusal names the other key set, the opposing jaw, with its range."""
    set_ = {"grasper_jaw.width_mm": 7.0, "grasper_jaw.opposing_jaw_mm": 9.0}
    with pytest.raises(DesignErrors) as err:
        tactcad.load(COMB, set=set_)
    e = next(e for e in err.value.errors if e.field.startswith("grasper_jaw."))
    assert e.field == "grasper_jaw.opposing_jaw_mm" and e.value == 9.0 and e.file == "set"
    bound = _bound(e.allowed)
    assert 0.5 <= bound < 9.0
    assert tactcad.load(COMB, set={**set_, "grasper_jaw.opposing_jaw_mm": bound}).plan.slots


STACKED = EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml"
JAW_SET = ["--set", "grasper_jaw.width_mm=7.5"]


def test_a_stacked_arrays_stated_jaw_is_said_passed_over_naming_what_is_judged():
    """A [grasper_jaw] a stacked array states is not judged: the load says so in one
    warning naming the table, the construction and those judged against a jaw."""
    from tactcad.errors import JawNotJudgedWarning

    with pytest.warns(JawNotJudgedWarning) as said:
        tactcad.load(STACKED, set={"grasper_jaw.width_mm": 7.5})
    texts = [str(w.message) for w in said if w.category is JawNotJudgedWarning]
    assert len(texts) == 1, texts
    text = texts[0]
    assert "\n" not in text and text.startswith(f"{STACKED.name}: [grasper_jaw]")
    assert 'array.construction = "stacked"' in text and "not judged against a jaw" in text
    assert 'array.construction = "monolithic-comb"' in text and "silicon die" in text


@pytest.mark.parametrize("design, overrides", [
    (STACKED, {}),  # no jaw stated: nothing to say
    (COMB, {}),  # the comb is judged against its jaw
    (COMB, {"grasper_jaw.length_mm": 34.0}),
])
def test_no_jaw_warning_where_none_is_passed_over(design, overrides, recwarn):
    from tactcad.errors import JawNotJudgedWarning

    tactcad.load(design, set=overrides)
    load_design(design)
    assert not [w for w in recwarn if w.category is JawNotJudgedWarning]


def test_load_design_says_a_stacked_arrays_jaw_passed_over(tmp_path):
    from tactcad.errors import JawNotJudgedWarning

    mine = tmp_path / "my_stack.toml"
    mine.write_text(STACKED.read_text(encoding="utf-8")
                    + '\n[grasper_jaw]\nshaft_class_mm = "10"\n', encoding="utf-8")
    with pytest.warns(JawNotJudgedWarning, match=r"^my_stack\.toml: \[grasper_jaw\] stated"):
        load_design(mine)


def test_a_commands_run_says_the_passed_over_jaw_once_json_lists_it_quiet_silences_it(
        capsys):
    argv = ["strength", "--design", str(STACKED), *JAW_SET]
    assert cli.main(argv) == 0
    err = capsys.readouterr().err
    lines = [x for x in err.splitlines() if "[grasper_jaw]" in x]
    assert len(lines) == 1 and lines[0].startswith("tactcad: warning: "), err
    assert "monolithic-comb" in lines[0]
    assert cli.main([*argv, "--json"]) == 0
    out = capsys.readouterr()
    warned = [w for w in json.loads(out.out)["warnings"] if "[grasper_jaw]" in w]
    assert len(warned) == 1 and "[grasper_jaw]" not in out.err, out.err
    assert cli.main([*argv, "--quiet"]) == 0
    assert "[grasper_jaw]" not in capsys.readouterr().err
