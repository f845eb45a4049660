"""``tactcad crosstalk``: JSON, the sweep, bad options refused."""

import json

import pytest

from conftest import run_cli


def test_json_has_the_matrices_and_the_sweep():
    r = run_cli("crosstalk", "--set", "array.columns=2", "--set", "arms.lengths_mm=[4,6,5,7]",
                "--sweep", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert len(d["sensitivity_strain_per_N"]) == 4 and d["crosstalk_rel"] > 0
    plates = [q["crosstalk_rel"] for q in d["sweep"] if q["parameter"] == "plate_thickness_mm"]
    assert plates == sorted(plates, reverse=True) and plates[0] > plates[-1]
    assert {q["parameter"] for q in d["sweep"]} == {"plate_thickness_mm", "bolt_spacing_mm",
                                                    "spacer_grade"}


def test_unknown_model_is_refused_in_one_line():
    r = run_cli("crosstalk", "--model", "fem9d", "--json")
    assert r.returncode == 2
    assert "stack-beam" in json.loads(r.stdout)["error"]["message"]


COMB = "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml"


def test_a_comb_answers_at_its_own_cheapest_level():
    # the comb was refused ("no stack crosstalk model"); its spine now couples its elements
    r = run_cli("crosstalk", "--design", COMB, "--json")
    assert r.returncode == 0, r.stdout + r.stderr
    d = json.loads(r.stdout)
    assert d["model"] == "comb-beam" and d["elements"] == list(range(1, 13))
    assert len(d["sensitivity_strain_per_N"]) == 12 == len(d["compliance_mm_per_N"])
    assert 0 < d["crosstalk_rel"] < 1e-3 and d["error_estimate_rel"] > 0
    assert d["asymmetry_rel"] < 1e-12 and "spine" in d["basis"]
    q = d["in_force"]
    assert q["gauge"] != q["loaded_element"] and q["force_resolution_steps"] > 0
    text = run_cli("crosstalk", "--design", COMB)
    assert text.returncode == 0 and "comb-beam" in text.stdout and "Maxwell-Betti" in text.stdout


def test_a_comb_of_its_own_at_the_plane_fe():
    """Not the shipped comb: a wider pitch, longer posts and other webs, at the FE level (in
    a jaw long enough for the longer comb)."""
    webs = [0.15] * 6 + [0.1] * 6
    r = run_cli("crosstalk", "--design", COMB, "--set", "array.pitch_mm=5.0",
                "--set", "grasper_jaw.length_mm=36",
                "--set", "comb.post_length_mm=1.0", "--set", f"comb.web_thicknesses_mm={webs}",
                "--model", "comb-fem2d", "--json")
    assert r.returncode == 0, r.stdout + r.stderr
    d = json.loads(r.stdout)
    assert d["model"] == "comb-fem2d" and d["asymmetry_rel"] < 1e-12
    assert 0 < d["crosstalk_rel"] < 1e-4 and 0 < d["error_estimate_rel"] < 0.1
    S = d["sensitivity_strain_per_N"]
    assert all(S[i][j] == 0 for i in range(6) for j in range(6, 12))  # the rows do not couple


def _solves_nothing(monkeypatch):
    from tactcad.mechanics import crosstalk_ladder

    def solved(*args, **kwargs):
        raise AssertionError("a level was read or solved")

    monkeypatch.setattr(crosstalk_ladder.CrosstalkLevel, "read_inputs", solved)
    monkeypatch.setattr(crosstalk_ladder.CROSSTALK_LADDER, "run", solved)


def test_a_stack_level_on_a_comb_is_refused_before_any_solve_naming_the_combs(monkeypatch):
    _solves_nothing(monkeypatch)
    r = run_cli("crosstalk", "--design", COMB, "--model", "stack-timoshenko", "--json")
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("--model", "stack-timoshenko")
    assert error["allowed"].startswith("one of comb-beam, comb-fem2d")
    assert [a["option"] for a in error["alternatives"]] == ["--model comb-beam",
                                                            "--model comb-fem2d"]
    # --sweep varies a clamped stack's plates and bolts: a comb has none
    r = run_cli("crosstalk", "--design", COMB, "--sweep", "--json")
    assert r.returncode == 2 and json.loads(r.stdout)["error"]["field"] == "--sweep"


def test_a_comb_level_on_the_stacked_array_is_refused_naming_the_stacks(monkeypatch):
    _solves_nothing(monkeypatch)
    r = run_cli("crosstalk", "--model", "comb-fem2d", "--json")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("--model", "comb-fem2d")
    assert "stack-beam" in error["allowed"] and "comb" in error["message"]
    assert error["alternatives"][0]["option"] == "--model stack-beam"


def test_help_names_every_constructions_levels():
    from tactcad.cli import build_parser, command_parser

    shown = command_parser(build_parser(["crosstalk"]), ["crosstalk"])[0].format_help()
    for level in ("stack-beam", "stack-fem3d", "comb-beam", "comb-fem2d", "attach-fem3d"):
        assert level in shown, level


DIE = "hardware/grasper_jaw_5mm_mems/grasper_jaw_5mm_mems.toml"


@pytest.mark.slow  # the example die's handle meshed and solved per unit (about 25 s)
def test_a_dies_crosstalk_is_its_own_through_its_handle_and_an_arrays_options_are_refused():
    # the die was refused ("not modelled"); its crosstalk is now the handle-and-attach FE's
    r = run_cli("crosstalk", "--design", DIE, "--set", "die.columns=2", "--json")
    assert r.returncode == 0, r.stdout + r.stderr
    d = json.loads(r.stdout)
    assert d["model"] == "attach-fem3d" and len(d["reading_per_N"]) == 4
    assert 0 < d["crosstalk_rel"] < 1e-3 and d["error_estimate_rel"] > 0
    assert d["worst"]["beam"] != d["worst"]["loaded_post"]
    q = d["in_force"]
    assert q["beam"] != q["loaded_beam"] and q["force_resolution_steps"] > 0
    for option in (("--model", "stack-fem3d"), ("--sweep",)):
        r = run_cli("crosstalk", "--design", DIE, *option, "--json")
        assert r.returncode == 2 and "Traceback" not in r.stderr, option
        error = json.loads(r.stdout)["error"]
        assert error["field"] == option[0] and "die" in error["message"], error


def test_a_die_too_large_for_the_fe_is_refused_with_fewer_columns_to_paste():
    # 28 columns (27 now: the most the pocket holds) ran out of memory with a raw traceback; the mesh's size is known first
    # (at a lighter rating: 27 columns of beams carry 27/5 of the example's fracture risk)
    r = run_cli("crosstalk", "--design", DIE, "--set", "die.columns=27", "--set",
                "die.full_scale_force_N=0.006", "--json")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "die.columns" and error["value"] == 27
    most = int(error["alternatives"][0]["option"].split("=")[-1])
    assert 2 <= most < 27


def test_a_dies_crosstalk_is_kept_in_the_result_store_and_says_what_it_solves(tmp_path,
                                                                             monkeypatch):
    """The die's FE costs a minute: a second run of the same die reuses it (--cache), a
    changed die solves again, and each run says which it did."""
    from dataclasses import replace

    from tactcad.products.silicon_die.commands.die_views import _crosstalk_kept
    from tactcad.products.silicon_die.design.mems_die import die_plan
    from tactcad.products.silicon_die.mechanics import die_crosstalk as dx
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.store import Store, keeping_results
    from tactcad.studies.inverse_design import Targets

    solved = []
    monkeypatch.setattr(dx, "die_crosstalk", lambda plan: solved.append(plan) or len(solved))
    plan = die_plan(Targets(10.0, (0.5, 5.0), 0.009), jaw_room("5"), columns=2)
    heard = []
    with keeping_results(Store(tmp_path / "store")):
        first = _crosstalk_kept(plan, 1000, heard.append)
    with keeping_results(Store(tmp_path / "store")):  # a later run, the same store
        again = _crosstalk_kept(plan, 1000, heard.append)
        softer = replace(plan, attach=replace(plan.attach, modulus_MPa=100.0))
        other = _crosstalk_kept(softer, 1000, heard.append)
    # each says whether it was reused: a reused result's cost is the earlier solve's
    assert (first, again, other) == ((1, False), (1, True), (2, False)) and solved == [plan, softer]
    assert "3D FE" in heard[0] and "reused" in heard[1] and "3D FE" in heard[2]
    # the count is the mesh's bound before the windows are cut, not the solve's own
    assert "at most 1000 degrees of freedom" in heard[0]


def test_a_stack_level_on_a_die_is_refused_before_any_solve_and_help_names_the_dies(
        die_folder, monkeypatch):
    """`--model stack-beam` on a die was taken (it was the default) and ignored; a level a
    die cannot use is refused naming the die's, before the die is planned or solved."""
    from tactcad.products.silicon_die.commands import die_views
    from tactcad.products.silicon_die.mechanics import die_crosstalk as dx

    def no_solve(*args, **kwargs):
        raise AssertionError("the die was planned or solved")

    monkeypatch.setattr(dx, "die_crosstalk", no_solve)
    monkeypatch.setattr(die_views, "_planned", no_solve)
    for level in ("stack-beam", "stack-timoshenko"):
        r = run_cli("crosstalk", "--model", level, "--json", cwd=die_folder)
        assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
        error = json.loads(r.stdout)["error"]
        assert (error["field"], error["value"]) == ("--model", level)
        assert error["allowed"].startswith(f"one of {dx.CROSSTALK_LEVEL} for a die")
        assert error["alternatives"][0]["option"] == f"--model {dx.CROSSTALK_LEVEL}"
    from tactcad.cli import build_parser, command_parser

    shown = command_parser(build_parser(["crosstalk"]), ["crosstalk"])[0].format_help()
    assert dx.CROSSTALK_LEVEL in shown and "stack-beam" in shown


def test_the_dies_level_on_an_array_is_refused_naming_the_stack_levels():
    r = run_cli("crosstalk", "--model", "attach-fem3d", "--json")
    assert r.returncode == 2
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("--model", "attach-fem3d")
    assert "stack-beam" in error["allowed"] and "silicon die" in error["message"]
    r = run_cli("crosstalk", "--json")  # left out: the stack's cheapest level, as before
    assert r.returncode == 0 and json.loads(r.stdout)["model"] == "stack-beam", r.stderr
