"""The design, rigs and scenes files validated together, up front: every error
at once, named errors for hostile input, rigs that follow the array, closed
domains whose every point builds."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import run_cli
from tactcad.design.array_plan import DEFAULT_DESIGN, default_design_data, plan_from_dict, with_overrides
from tactcad.design.project import load_project, project_for_plan, project_from_data
from tactcad.design.rig_plan import DEFAULT_RIGS, default_rigs_data, stiffest_element
from tactcad.design.scene_specs import DEFAULT_SCENES
from tactcad.vocabulary.schema import Problems, read_toml
from tactcad.errors import DesignError, DesignErrors

ARMS = "lengths_mm = [4.0, 7.0, 6.0, 8.0, 6.0, 8.0, 5.0, 4.0, 5.0, 7.0]"


def _project_dir(tmp_path: Path, design=lambda t: t, rigs=lambda t: t, scenes=lambda t: t) -> Path:
    """A folder with the three files, each edited by its function; the design's path."""
    for src, edit in ((DEFAULT_DESIGN, design), (DEFAULT_RIGS, rigs), (DEFAULT_SCENES, scenes)):
        text = edit(src.read_text(encoding="utf-8"))
        (tmp_path / src.name).write_text(text, encoding="utf-8")
    return tmp_path / DEFAULT_DESIGN.name


def _cli(*args: str) -> subprocess.CompletedProcess:
    return run_cli(*args)


def _project(design: dict) -> tuple:
    p = Problems("d.toml")
    out = project_from_data(design, default_rigs_data(), read_toml(DEFAULT_SCENES, "scenes file"),
                            p, source="d.toml")
    return out, p.errors


def test_every_error_of_the_three_files_at_once_exit_2_and_nothing_written(tmp_path):
    design = _project_dir(
        tmp_path,
        design=lambda t: t.replace("web_thickness_mm = 0.25", "web_thickness_mm = 1.55")
                          .replace("pitch_mm = 4.0", "pitch_mm = true"),
        rigs=lambda t: t.replace("count = 3", "count = 30"),
        scenes=lambda t: t.replace('groups = ["array"]', 'groups = ["array", "trolley"]'))
    out = tmp_path / "out"
    proc = _cli("export", "--design", str(design), "--out", str(out))
    assert proc.returncode == 2, proc.stderr
    err = proc.stderr
    assert "Traceback" not in err
    for line in ("macro_array.toml: element.web_thickness_mm = 1.55: allowed 0.05 <= value <= 1 mm",
                 "macro_array.toml: array.pitch_mm = true: allowed a finite number",
                 "scenes.toml: scene.array.groups = ['trolley']: allowed groups of rig array"):
        assert line in err, err
    assert not out.exists()
    # the rigs error shows once the design is fixed (rigs are checked against the plan)
    design.write_text(DEFAULT_DESIGN.read_text())
    with pytest.raises(DesignErrors) as info:
        load_project(design)
    lines = [e.line() for e in info.value.errors]
    assert any(x.startswith("rigs.toml: weights.count = 30: allowed 0 ... 20") for x in lines), lines
    assert any(x.startswith("scenes.toml: scene.array.groups") for x in lines), lines


def test_first_error_keeps_field_value_allowed(design_data):
    data = with_overrides(design_data, {"element.web_thickness_mm": 1.9, "clamp.bolt_size": "M9"})
    with pytest.raises(DesignErrors) as info:
        plan_from_dict(data)
    err = info.value
    assert err.field == "element.web_thickness_mm" and err.value == 1.9 and "1 mm" in err.allowed
    assert [e.field for e in err.errors] == ["element.web_thickness_mm", "clamp.bolt_size"]


@pytest.mark.parametrize("edit, field, words", [
    (lambda t: t.replace("tip_height_mm = 1.5", "tip_height_mm = 1" + "0" * 400),
     "element.tip_height_mm", "a finite number"),
    (lambda t: t.replace('bolt_size = "M2"', 'bolt_size = ["M2"]'), "clamp.bolt_size", "one of M1.6"),
    (lambda t: t.replace("[design]", "x = " + "[" * 3000 + "]" * 3000 + "\n[design]"),
     "design file", "nested at most"),
    (lambda t: t.replace(ARMS, "lengths_mm = [" + ", ".join(["5.0"] * 100_000) + "]"),
     "arms.lengths_mm", "100000 items"),
    (lambda t: t.replace('name = "macro_array"', 'name = "two\\nlines"'), "design.name", "A-Z"),
    (lambda t: t.replace('name = "macro_array"', 'name = "bell\\u0007"'), "design.name", "A-Z"),
    (lambda t: t.replace('name = "macro_array"', 'name = "../up"'), "design.name", "A-Z"),
    (lambda t: t.replace("pitch_mm = 4.0", "pitch_mm = 3.000000001"), "array.pitch_mm", "3.2"),
])
def test_hostile_design_values_get_named_errors(tmp_path, edit, field, words):
    design = _project_dir(tmp_path, design=edit)
    proc = _cli("scenes", "--design", str(design))
    assert proc.returncode == 2 and "Traceback" not in proc.stderr, proc.stderr[-2000:]
    assert f"{field} = " in proc.stderr and words in proc.stderr, proc.stderr[:2000]
    assert len(proc.stderr) < 2000  # a huge value is cut, not echoed


def test_non_utf8_file_is_a_named_error(tmp_path):
    design = _project_dir(tmp_path)
    design.write_bytes(DEFAULT_DESIGN.read_bytes().replace(b"aluminium", b"alumin\xffium", 1))
    proc = _cli("scenes", "--design", str(design))
    assert proc.returncode == 2 and "UTF-8" in proc.stderr and "Traceback" not in proc.stderr


def test_a_design_file_saved_with_a_byte_order_mark_reads_as_without(tmp_path):
    # an editor's UTF-8 BOM was refused as "Invalid statement (at line 1, column 1)"
    from tactcad.vocabulary.schema import read_toml

    marked = tmp_path / "marked.toml"
    marked.write_bytes(b"\xef\xbb\xbf" + DEFAULT_DESIGN.read_bytes())
    assert read_toml(marked, "design file") == read_toml(DEFAULT_DESIGN, "design file")


@pytest.mark.parametrize("edit, field", [
    (lambda t: t.replace("[scene.wirecut]", '[scene."../../escaped"]'), 'scene.../../escaped'),
    (lambda t: t.replace("sample_stiffness_N_per_mm = 10.01", "sample_stiffness_N_per_mm = 0"),
     "scene.sample-stiffness-rig.sample_stiffness_N_per_mm"),
    (lambda t: t.replace("sample_stiffness_N_per_mm = 10.01", "sample_stiffness_N_per_mm = 9.5"),
     "scene.sample-stiffness-rig.sample_stiffness_N_per_mm"),
])
def test_bad_scenes_are_refused_up_front(tmp_path, edit, field):
    design = _project_dir(tmp_path, scenes=edit)
    with pytest.raises(DesignError) as info:
        load_project(design)
    assert info.value.field == field and info.value.file == "scenes.toml"


@pytest.mark.parametrize("overrides", [
    {"array.columns": 2, "arms.lengths_mm": [4.0, 7.0, 6.0, 8.0]},
    {"arms.lengths_mm": [4.0] * 10},
    {"element.tip_width_mm": 3.0},
    {"array.pitch_mm": 12.0, "array.columns": 2, "arms.lengths_mm": [8.0] * 4},
])
def test_rigs_follow_the_array_so_untouched_rig_values_never_fail(design_data, overrides):
    (plan, rigs, scenes), errors = _project(with_overrides(design_data, overrides))
    assert not errors, [e.line() for e in errors]
    assert rigs.calibration_element == stiffest_element(plan)
    assert rigs.part("indenter").contact_width_mm == plan.slots[0].geometry.tip_width_mm
    assert rigs.part("indenter").contact_depth_mm == plan.sheet_thickness_mm
    stack, across = plan.stack_length_mm, plan.pitch_mm + plan.slots[0].geometry.tip_width_mm
    sample = rigs.part("sample")
    assert sample.length_mm >= stack + 4 and sample.width_mm >= across + 4
    assert set(scenes) == {"wirecut", "array", "calibration-rig", "sample-stiffness-rig",
                           "array-evaluation-rig"}


def test_reference_element_is_the_stiffest_unless_named(plan):
    assert stiffest_element(plan) == 8  # the paper's: of the two 4 mm arms, element 8
    data = with_overrides(default_design_data(), {"arms.lengths_mm": [6.0, 5.0] + [7.0] * 8})
    p = plan_from_dict(data)
    assert stiffest_element(p) == 2
    rigs_data = default_rigs_data()
    rigs_data["calibration"] = {"element": 12}
    pr = Problems("d.toml")
    project_from_data(data, rigs_data, None, pr, source="d.toml")
    assert [e.field for e in pr.errors] == ["calibration.element"]


def test_a_rig_that_cannot_fit_names_the_design_field(design_data):
    # M3 bolts through a long stack leave no stock bolt for the bracket's ear as well
    data = with_overrides(design_data, {"clamp.bolt_size": "M3", "array.pitch_mm": 5.5,
                                        "array.columns": 5, "clamp.plate_thickness_mm": 5.0,
                                        "clamp.bolt_spacing_mm": 7.0, "element.overall_length_mm": 26.0,
                                        "clamp.bridge_height_mm": 5.0})
    plan_from_dict(data)  # the array alone fits
    _, errors = _project(data)
    assert [(e.file, e.field) for e in errors] == [("d.toml", "array.columns")], \
        [e.line() for e in errors]


def test_limits_are_manufacturable(design_data):
    """Lower limits come from the shop: spacer >= 0.2 mm, arm over the notch by the
    wire's inside radius, bolt spacing from nut across-corners plus a gap, the
    tip-root fillet below the contact face, distinct arms 0.01 mm apart."""
    for overrides, field, text in (
            ({"array.pitch_mm": 3.1}, "array.pitch_mm", "3.2"),
            ({"element.arm_height_mm": 0.76}, "element.arm_height_mm", "0.9"),
            ({"clamp.bolt_spacing_mm": 3.4}, "clamp.bolt_spacing_mm", "4.81"),
            ({"element.inside_corner_radius_mm": 0.5, "element.tip_height_mm": 0.55},
             "element.tip_height_mm", "0.6"),
            ({"arms.lengths_mm": [4.0, 4.005] + [6.0] * 8}, "arms.lengths_mm[2]", "4.01")):
        with pytest.raises(DesignError) as info:
            plan_from_dict(with_overrides(design_data, overrides))
        assert info.value.field == field and text in info.value.allowed, str(info.value)
    plan_from_dict(with_overrides(design_data, {"array.pitch_mm": 3.2, "element.arm_height_mm": 0.9,
                                                "clamp.bolt_spacing_mm": 4.82}))


def test_part_names_are_file_safe(design_data):
    from tactcad.catalogue.array_catalogue import array_parts

    plan = plan_from_dict(with_overrides(design_data, {"clamp.bolt_size": "M2.5"}))
    names = set(array_parts(plan))
    assert {"bolt_M2p5x30", "nut_M2p5"} <= names
    assert all("." not in n for n in names)


@pytest.mark.slow
@pytest.mark.parametrize("overrides, outside_fit", [
    # a 4 mm arm over a 0.9 mm arm height: a/h = 4.4, beyond the correction's fit (<= 4)
    ({"array.pitch_mm": 3.2, "element.arm_height_mm": 0.9, "clamp.bolt_size": "M2.5",
      "clamp.bolt_spacing_mm": 5.98, "element.tip_width_mm": 2.0}, True),
    ({"array.columns": 2, "arms.lengths_mm": [4.0, 7.0, 4.0, 7.0]}, False),
])
def test_designs_at_their_limits_export_and_check(design_data, tmp_path, overrides, outside_fit):
    """pitch, arm height and bolt spacing at their lowest accepted values with M2.5
    bolts, and a two-column array (the fewest a stacked array takes): the array exports and passes
    its checks (STEP solids and labels included); a design beyond the stiffness
    correction's fitted range is exported with that said."""
    import warnings

    from tactcad.mechanics.correction import CorrectionRangeWarning

    from tactcad.checks.array_checks import run_checks
    from tactcad.export.run import export
    from tactcad.solids.cache import PartCache

    plan = plan_from_dict(with_overrides(design_data, overrides))
    cache = PartCache(plan)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        export(project_for_plan(plan), tmp_path, log=lambda s: None, parts=cache)
    said = [w for w in caught if issubclass(w.category, CorrectionRangeWarning)]
    assert bool(said) == outside_fit, [str(w.message) for w in said[:1]]
    results = run_checks(plan, tmp_path, cache)
    bad = [r.line() for r in results if not r.passed]  # the drawings' overlap check included
    assert not bad, "\n".join(bad)


@pytest.mark.slow
def test_arm_height_at_its_lower_limit_meshes_for_fem2d(design_data):
    from tactcad.mechanics.fem.fem2d import solve_fem2d

    plan = plan_from_dict(with_overrides(design_data, {"element.arm_height_mm": 0.9}))
    k = solve_fem2d(plan.element(1).geometry, plan.material, size_factor=2.0).stiffness_N_per_mm
    assert 0 < k < 1e4


def test_lumped_names_what_the_user_gave_and_never_prints_infinity():
    proc = _cli("lumped", "--km", "1", "--kr", "2", "--kobj", "1e308")
    assert proc.returncode == 2 and "--kobj = 1e+308" in proc.stderr and "R = 1.0:" not in proc.stderr
    proc = _cli("lumped", "--km", "1e-308", "--kr", "1e308", "--kobj", "1", "--json")
    # with --json the error is a JSON object on stdout, and still never Infinity
    assert proc.returncode == 2 and "finite" in proc.stdout and "Infinity" not in proc.stdout
    assert json.loads(proc.stdout)["error"]["exit_code"] == 2
    proc = _cli("lumped", "--km", "15.25", "--kr", "80.38", "--kobj", "3.85", "--json")
    assert proc.returncode == 0 and json.loads(proc.stdout)["r"] > 1


def test_fuzz_script_runs_and_summarises(tmp_path):
    """Validation only (-n draws with no part built is covered by the property
    test; here the script's out-of-domain path and summary)."""
    proc = subprocess.run([sys.executable, str(Path(__file__).parents[2] / "scripts" / "fuzz.py"),
                           "-n", "6", "--wild", "1.0", "--quiet"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "6 tried, 0 accepted" in proc.stdout and "0 tracebacks" in proc.stdout and "6 of 6 out-of-domain draws refused" in proc.stdout


def test_a_long_path_in_a_refusal_keeps_its_file_name(tmp_path):
    from tactcad.errors import MAX_VALUE_CHARS, short_repr

    deep = tmp_path / ("d" * 3 * MAX_VALUE_CHARS) / "nothere.toml"
    text = short_repr(str(deep))
    assert text.startswith(repr(str(deep))[:10]) and "nothere.toml'" in text
    assert f"({len(str(deep))} characters)" in text  # the path's, not its quoted repr's
    assert len(text) < MAX_VALUE_CHARS + 40


@pytest.mark.parametrize("value, words", [(0, "0 < value <= 100 N"), (150, "0 < value <= 100 N"),
                                          ("five", "a finite number")])
def test_max_grasp_force_out_of_range_is_refused_naming_it(design_data, value, words):
    data = with_overrides(design_data, {"requirements.max_grasp_force_N": value})
    with pytest.raises(DesignErrors) as info:
        plan_from_dict(data)
    line = next(e.line() for e in info.value.errors
                if e.field == "requirements.max_grasp_force_N")
    assert words in line and repr(value) in line, line


def test_a_pitch_no_tip_fits_is_refused_as_the_pitch_alone(tmp_path):
    # the tip width's refusal followed with "allowed value <= -0.1 mm"
    proc = _cli("scenes", "--design", str(_project_dir(tmp_path)), "--set", "array.pitch_mm=0.1")
    assert proc.returncode == 2 and "array.pitch_mm = 0.1" in proc.stderr
    assert "tip_width_mm" not in proc.stderr and "<= -" not in proc.stderr
    near = _cli("scenes", "--design", str(_project_dir(tmp_path)), "--set", "array.pitch_mm=2.0")
    assert "element.tip_width_mm" in near.stderr  # a pitch a narrower tip fits: still named


# --- a design that can read K_obj: two columns a row, a reference stiffer than its row ------
TI_EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def test_a_stacked_array_of_one_column_is_refused_with_the_range_design_help_gives(capsys):
    import tactcad
    from tactcad import cli
    from tactcad.design.array_plan import STACKED_COLUMNS_RANGE

    lo, hi = STACKED_COLUMNS_RANGE
    with pytest.raises(DesignErrors) as err:
        tactcad.load(TI_EXAMPLE, set={"array.columns": lo - 1, "arms.lengths_mm": [4.0, 7.0]})
    assert err.value.field == "array.columns" and err.value.value == lo - 1
    assert err.value.allowed == f"{lo} ... {hi} for a stacked array"
    assert "no element left to measure" in err.value.why
    with pytest.raises(SystemExit):
        cli.main(["design", "--help"])
    helped = " ".join(capsys.readouterr().out.split())
    assert f"{lo} ... {hi} for a stacked array" in helped
    # the fewest is taken
    tactcad.load(TI_EXAMPLE, set={"array.columns": lo, "arms.lengths_mm": [19.6, 6.196] * lo})


def test_a_named_reference_softer_than_its_row_is_refused_with_the_stiffnesses():
    import tactcad
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element

    k = ladder_stiffness_by_element(plan_from_dict(read_toml(TI_EXAMPLE, "design")))
    with pytest.raises(DesignErrors) as err:
        tactcad.load(TI_EXAMPLE, set={"arms.reference_elements": [2, 4]})  # 4 is row 2's soft
    (refused,) = err.value.errors
    assert refused.field == "arms.reference_elements[2]" and refused.value == 4
    assert "K_r > K_m" in refused.allowed and "eq. 2-3" in refused.why
    assert f"element 4 has K = {k[4]:.4g} N/mm" in refused.allowed
    assert f"element 5 {k[5]:.4g} N/mm" in refused.allowed and k[5] > k[4]
    assert "the stiffest of its row is element 5" in refused.allowed
    assert tactcad.load(TI_EXAMPLE, set={"arms.reference_elements": [2, 5]}).plan.references \
        == (2, 5)


def test_a_row_of_equal_elements_with_no_reference_named_is_refused():
    import tactcad

    with pytest.raises(DesignErrors) as err:  # the Ti example names none: each row's stiffest
        tactcad.load(TI_EXAMPLE, set={"arms.lengths_mm": [6.196, 6.196, 19.605] * 2})
    refused = err.value.errors
    assert [e.field for e in refused] == ["arms.lengths_mm"] * 2
    assert "(the file names none)" in refused[0].allowed and "is 1 for every K_obj" in refused[0].why
    assert "element 1 has K" in refused[0].allowed and "element 2 " in refused[0].allowed
    tactcad.load(TI_EXAMPLE, set={"arms.lengths_mm": [6.196, 6.3, 19.605] * 2})  # one stiffest


def test_a_soft_reference_is_refused_by_the_commands_that_read_the_design(tmp_path):
    import shutil

    text = TI_EXAMPLE.read_text(encoding="utf-8")
    design = tmp_path / "soft_ref.toml"
    for companion in ("rigs.toml", "scenes.toml"):
        shutil.copy(TI_EXAMPLE.parent / companion, tmp_path / companion)
    design.write_text(text.replace("[arms]", "[arms]\nreference_elements = [2, 4]", 1),
                      encoding="utf-8")
    for command in ("evaluate", "grasp"):
        r = run_cli(command, "--design", str(design))
        assert r.returncode == 2, (command, r.stdout[-300:])
        assert "arms.reference_elements[2] = 4" in r.stderr and "K_r > K_m" in r.stderr
        assert "Traceback" not in r.stderr


def test_a_boolean_for_an_integer_key_is_echoed_as_the_file_holds_it(tmp_path):
    """``columns = true`` was echoed in Python's spelling, ``array.columns = True``, which
    pasted back into the file is no TOML; the file's and a --set's refusal say ``true``."""
    design = _project_dir(tmp_path, design=lambda t: t.replace("columns = 5", "columns = true"))
    proc = _cli("scenes", "--design", str(design))
    assert proc.returncode == 2, proc.stderr[-2000:]
    assert "array.columns = true: allowed an integer" in proc.stderr, proc.stderr
    assert "True" not in proc.stderr
    given = _cli("scenes", "--set", "array.columns=false")
    assert "array.columns = false: allowed an integer" in given.stderr, given.stderr
    # a value of the Python API keeps Python's spelling (no file gave it)
    assert DesignError("number", True, "an integer").line() == "number = True: allowed an integer"
