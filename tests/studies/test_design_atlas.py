"""The design atlas: its target sample, its Pareto filter, the binding limits it sorts
refusals into, and its honesty: every point is the verdict ``tactcad design`` gives."""

from __future__ import annotations

import json
import math

import pytest
from conftest import run_cli

from tactcad.errors import DesignError
from tactcad.studies.design_atlas import (AXES, COMB, DEFAULT_RANGES, DIE, SILICON, JawAtlas,
                                   atlas_targets, batches, evaluate_batch, refusal_of,
                                   pareto_front)


def rec(force, lo, hi, res, name):
    return {"name": name, "full_scale_force_N": force, "kobj_lo_N_per_mm": lo,
            "kobj_hi_N_per_mm": hi, "kobj_resolution_rel": res}


def test_pareto_front_keeps_exactly_the_non_dominated_records():
    a = rec(1.0, 1.0, 10.0, 0.10, "a")    # span 10
    b = rec(2.0, 1.0, 5.0, 0.10, "b")     # more force, less span: both on the front
    c = rec(0.5, 1.0, 5.0, 0.20, "c")     # worse than a and b in every objective
    d = rec(1.0, 1.0, 10.0, 0.05, "d")    # a with a finer resolution: dominates a
    e = rec(2.0, 1.0, 5.0, 0.10, "e")     # equal to b: neither dominates the other
    f = rec(9.0, 1.0, 50.0, math.nan, "f")  # no figure: left out, however good
    front = pareto_front([a, b, c, d, e, f])
    assert [r["name"] for r in front] == ["b", "d", "e"]


def test_pareto_front_follows_each_objectives_sense():
    a = rec(1.0, 1.0, 10.0, 0.10, "a")
    b = rec(2.0, 1.0, 10.0, 0.10, "b")
    assert [r["name"] for r in pareto_front([a, b], {"full_scale_force_N": "max"})] == ["b"]
    assert [r["name"] for r in pareto_front([a, b], {"full_scale_force_N": "min"})] == ["a"]
    with pytest.raises(DesignError, match="objectives"):
        pareto_front([a], {"full_scale_force_N": "largest"})


def test_the_sample_stays_in_its_ranges_and_repeats_with_its_seed():
    ranges = {"full_scale_force_N": (0.01, 0.5), "columns": (3, 5)}
    points = atlas_targets(64, ranges, seed=3)
    assert len(points) == 64 and [p["point"] for p in points] == list(range(64))
    for p in points:
        centre = math.sqrt(p["kobj_lo_N_per_mm"] * p["kobj_hi_N_per_mm"])
        span = p["kobj_hi_N_per_mm"] / p["kobj_lo_N_per_mm"]
        assert 0.01 * (1 - 1e-5) <= p["full_scale_force_N"] <= 0.5 * (1 + 1e-5)
        assert p["columns"] in (3, 4, 5)
        lo, hi = DEFAULT_RANGES["kobj_centre_N_per_mm"]
        assert lo * (1 - 1e-4) <= centre <= hi * (1 + 1e-4)
        lo, hi = DEFAULT_RANGES["kobj_span"]
        assert lo * (1 - 1e-4) <= span <= hi * (1 + 1e-4)
    assert {p["columns"] for p in points} == {3, 4, 5}  # every count drawn
    assert points == atlas_targets(64, ranges, seed=3)
    assert points != atlas_targets(64, ranges, seed=4)
    # log-uniform: about half the forces below the range's geometric centre
    below = sum(p["full_scale_force_N"] < math.sqrt(0.01 * 0.5) for p in points)
    assert 24 <= below <= 40


@pytest.mark.parametrize("n, ranges, seed, option", [
    (0, None, 0, "--points"),
    (10, None, -1, "--seed"),
    (10, {"full_scale_force_N": (2.0, 1.0)}, 0, "--force-range"),
    (10, {"full_scale_force_N": (0.1, 5000.0)}, 0, "--force-range"),
    (10, {"kr_over_km": (1.0, 5.0)}, 0, "--kr-over-km-range"),
    (10, {"columns": (1, 4)}, 0, "--columns-range"),
    (10, {"kobj_span": (0.5, 4.0)}, 0, "--kobj-span"),
    (10, {"webs": (0.1, 0.2)}, 0, "ranges"),
])
def test_bad_sample_options_are_refused_naming_the_option(n, ranges, seed, option):
    with pytest.raises(DesignError) as err:
        atlas_targets(n, ranges, seed)
    assert err.value.field == option
    assert err.value.allowed


def test_batches_cover_every_point_once():
    points = [{"point": i} for i in range(7)]
    cut = batches(points, 3)
    assert [len(b) for b in cut] == [3, 3, 1]
    assert [p for b in cut for p in b] == points
    with pytest.raises(DesignError, match="--batch"):
        batches(points, 0)


def test_a_refusal_is_sorted_by_the_limit_code_it_carries_not_its_words():
    """The code is read from the refusal; words that name another limit do not move it."""
    from tactcad.vocabulary.binding_limits import BINDING_LIMITS, OTHER, STOP

    coded = DesignError("--full-scale-force", 2.0, "at most 1 N",
                        "the comb's height and its yield strength", limit=STOP)
    assert refusal_of(coded).limit == STOP
    assert refusal_of(DesignError("--columns", 1, "2 ... 50")).limit == OTHER
    assert STOP in BINDING_LIMITS


def test_a_die_rated_past_its_strength_carries_the_strength_code():
    """The 5 mm jaw's die at 4 N: its roots' failure probability binds first."""
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.products.silicon_die.studies.die_doping import doped_die_plan
    from tactcad.studies.design_atlas import targets_of
    from tactcad.vocabulary.binding_limits import STRENGTH

    point = {"kr_over_km": 10.0, "kobj_lo_N_per_mm": 0.5, "kobj_hi_N_per_mm": 5.0,
             "full_scale_force_N": 4.0}
    with pytest.raises(DesignError) as err:
        doped_die_plan(targets_of(point), jaw_room("5"), columns=4)
    assert err.value.field == "--full-scale-force" and err.value.limit == STRENGTH


def test_a_comb_with_more_columns_than_its_pitch_holds_carries_the_sheet_code():
    """Eight columns in the 10 mm jaw's pocket leave no measuring arm on any sheet."""
    from tactcad.studies.comb_design import comb_candidates
    from tactcad.studies.design_atlas import targets_of
    from tactcad.vocabulary.binding_limits import SHEET

    atlas = jaw_atlas("10", [(COMB, "Ti-6Al-4V-annealed")])
    point = {"kr_over_km": 10.0, "kobj_lo_N_per_mm": 0.5, "kobj_hi_N_per_mm": 5.0,
             "full_scale_force_N": 0.01}
    _, tried = comb_candidates(targets_of(point), atlas.room, 8, atlas.comb_base,
                               grade="Ti-6Al-4V-annealed")
    assert tried and all(c.plan is None and c.limits == (SHEET,) for c in tried)


@pytest.mark.parametrize("point", [
    # K_m of 0.025 N/mm at 3.8 N: no scale's stops fit, the stiffest alone is judged
    {"point": 3, "kr_over_km": 15.7126, "kobj_lo_N_per_mm": 0.0183033,
     "kobj_hi_N_per_mm": 0.551098, "full_scale_force_N": 3.77821, "columns": 4},
    # K_m of 0.058 N/mm at 0.88 N: the two stiffest scales judged, six left out
    pytest.param({"point": 3, "kr_over_km": 9.06395, "kobj_lo_N_per_mm": 0.0639312,
                  "kobj_hi_N_per_mm": 0.428655, "full_scale_force_N": 0.87967, "columns": 6},
                 marks=pytest.mark.slow),  # every sheet at every scale, twice
])
def test_a_comb_point_judged_at_the_scales_whose_stops_fit_is_the_whole_searchs_record(
        point, monkeypatch):
    """Leaving out the K_m scales whose stops cannot fit changes no comb record: its
    verdict, binding limit and words and the option it names are those of judging every
    sheet at every scale."""
    from tactcad.studies import comb_design
    from tactcad.studies.design_atlas import targets_of

    atlas = jaw_atlas("10", [(COMB, "Ti-6Al-4V-annealed"), (COMB, "17-4PH-H900")])
    assert len(comb_design.atlas_scales(targets_of(point))) < len(comb_design.KM_SCALES)
    skipping = evaluate_batch(atlas, [point])
    monkeypatch.setattr(comb_design, "atlas_scales", lambda targets: comb_design.KM_SCALES)
    whole = evaluate_batch(atlas, [point])
    assert [r["feasible"] for r in whole] == [False, False]
    assert all(r["binding_detail"] for r in whole)
    assert json.dumps(skipping, sort_keys=True) == json.dumps(whole, sort_keys=True)


def jaw_atlas(jaw: str, products) -> JawAtlas:
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.design.array_plan import EXAMPLES, read_toml
    from tactcad.partlib.grasper_jaw import jaw_room

    base = read_toml(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml", "design file")
    return JawAtlas(jaw, jaw_room(jaw), base, array_envelope_mm, tuple(products))


def design_verdict(record: dict, tmp_path) -> tuple[int, dict]:
    """``tactcad design`` run on a record's own command line (its --out in ``tmp_path``)."""
    import shlex

    words = shlex.split(record["command"])[2:]  # less "tactcad design"
    words[-1] = str(tmp_path / words[-1])
    r = run_cli("design", *words, "--json")
    return r.returncode, json.loads(r.stdout)


def agrees_with_design(record: dict, tmp_path) -> None:
    code, answer = design_verdict(record, tmp_path)
    if record["feasible"]:
        assert code == 0, (record["command"], answer)
    else:
        error = answer["error"]
        assert code != 0
        assert error["field"] == record["design_field"], record["command"]
        assert error.get("limit") == record["binding_limit"], record["command"]
        assert record["binding_detail"] and record["binding_detail"] in error["message"]


def written_die_figures(design_file) -> dict:
    """The figures of the die ``design`` wrote, re-planned from its file as ``tactcad die``
    plans it (the atlas's own figure functions on that plan; the largest rating as
    ``tactcad strength --json`` reports it)."""
    import argparse
    from pathlib import Path

    import tactcad
    from tactcad.commands.die import _die_args, die_asked, plan_of
    from tactcad.products.silicon_die.mechanics.die_dynamics import first_resonance_Hz
    from tactcad.products.silicon_die.studies.die_doping import worst_readout_error_rel

    args = _die_args(Path(design_file), argparse.Namespace(overrides=[]), Path("."))
    plan = plan_of(die_asked(args)).plan
    return {"kobj_resolution_rel": worst_readout_error_rel(plan),
            "max_force_N": tactcad.load(design_file).strength()["largest_rating_N"],
            "lowest_first_Hz": min(first_resonance_Hz(plan, b) for b in plan.beams),
            "layer_um": plan.stack.device_um}


def near_frontier(records: list[dict], count: int) -> list[dict]:
    """Points a step each side of feasible records' own frontier: the rating 3 % under and
    5 % over the largest force each allows (``max_force_N``; the limits grow a little with
    the rating, the cavities' depths in steps, so the frontier lies a little above it)."""
    from tactcad.studies.design_atlas import _g

    out = []
    for r in [r for r in records if r["feasible"]][:count]:
        for step, factor in ((0, 0.97), (1, 1.05)):
            out.append({k: r[k] for k in ("kr_over_km", "kobj_lo_N_per_mm",
                                          "kobj_hi_N_per_mm", "columns")}
                       | {"point": 1000 + 2 * r["point"] + step,
                          "full_scale_force_N": _g(factor * r["max_force_N"])})
    return out


def test_drawn_die_points_and_their_frontier_are_the_verdicts_and_figures_design_gives(
        tmp_path):
    """The honesty property (issue 70): drawn atlas points of the 5 mm jaw's die, feasible
    and refused, and points a step each side of the feasible ones' frontier, each run
    through ``tactcad design``: the same verdict, option and limit code; a feasible one's
    figures those of the die design wrote. ``make test`` draws a few,
    ``TACTCAD_TEST_DEPTH=deep`` the issue's 50 (and exports and checks the feasible ones)."""
    from depth import DEPTH, draws

    atlas = jaw_atlas("5", [(DIE, SILICON)])
    drawn = draws(4, 40)
    points = atlas_targets(drawn, {"full_scale_force_N": (0.002, 0.05)}, seed=11)
    records = evaluate_batch(atlas, points)
    records += evaluate_batch(atlas, near_frontier(records, draws(1, 5)))
    assert {r["feasible"] for r in records} == {True, False}
    for r in records:
        agrees_with_design(r, tmp_path)
        if not r["feasible"]:
            continue
        written = tmp_path / r["command"].rsplit(" ", 1)[-1]
        again = written_die_figures(written)
        for key, value in again.items():
            assert r[key] == pytest.approx(value, rel=1e-12), (key, r["command"])
        if DEPTH == "deep":
            out = tmp_path / f"export_{r['point']}"
            e = run_cli("export", "--design", written, "--out", out)
            assert e.returncode == 0, e.stdout + e.stderr
            c = run_cli("check", "--design", written, "--out", out)
            assert c.returncode == 0, c.stdout


def test_every_die_point_of_an_atlas_is_the_verdict_design_gives(tmp_path):
    """The honesty property on the 10 mm jaw's die: a handful of drawn points, feasible and
    refused, each judged as ``tactcad design --construction mems-die`` judges it."""
    atlas = jaw_atlas("10", [(DIE, SILICON)])
    points = atlas_targets(8, {"full_scale_force_N": (0.002, 0.1)}, seed=1)
    records = evaluate_batch(atlas, points)
    assert len(records) == 8 and set(AXES[:1]) <= set(records[0])
    assert {r["feasible"] for r in records} == {True, False}  # both kinds judged
    for r in records:
        agrees_with_design(r, tmp_path)
        if r["feasible"]:
            assert r["layer_um"] > 0 and r["lowest_first_Hz"] > 0
            assert 0 < r["kobj_resolution_rel"] < 1
            assert r["max_force_N"] >= r["full_scale_force_N"] * (1 - 1e-9)
        else:
            assert r["binding_limit"] != "other"


@pytest.mark.slow  # each comb point is a search of every sheet, each refusal its frontier
def test_comb_points_of_an_atlas_are_the_verdicts_design_gives(tmp_path):
    atlas = jaw_atlas("10", [(COMB, "Ti-6Al-4V-annealed")])
    feasible = {"point": 0, "kr_over_km": 10.0, "kobj_lo_N_per_mm": 0.5,
                "kobj_hi_N_per_mm": 5.0, "full_scale_force_N": 0.01, "columns": 6}
    refused = {**feasible, "point": 1, "full_scale_force_N": 0.9, "kobj_lo_N_per_mm": 0.06,
               "kobj_hi_N_per_mm": 0.43}
    # too many columns for the pocket: no candidate has a plan, the refusal offers fewer
    crowded = {"point": 2, "kr_over_km": 4.29128, "kobj_lo_N_per_mm": 0.400251,
               "kobj_hi_N_per_mm": 5.65791, "full_scale_force_N": 0.026679, "columns": 7}
    records = evaluate_batch(atlas, [feasible, refused, crowded])
    assert [r["feasible"] for r in records] == [True, False, False]
    assert records[0]["sheet_mm"] > 0 and records[0]["max_force_N"] >= 0.01
    assert [r["design_field"] for r in records[1:]] == ["--full-scale-force", "--columns"]
    for r in records:
        agrees_with_design(r, tmp_path)


def test_ctrl_c_keeps_the_batches_that_finished_and_cancels_the_rest():
    """Ctrl-C while the atlas waits (raised here as the first batch reports): the records
    of the batches that finished are returned, the run marked incomplete."""
    from distributed import Client

    from tactcad.studies.design_atlas import run_atlas

    atlas = jaw_atlas("5", [(DIE, SILICON)])
    points = atlas_targets(6, {"full_scale_force_N": (0.001, 0.05)}, seed=2)

    def interrupted(done: int, total: int) -> None:
        raise KeyboardInterrupt

    with Client(processes=False, n_workers=1, threads_per_worker=1,
                dashboard_address=None) as client:
        records, complete = run_atlas(atlas, points, client, batch_size=2,
                                      progress=interrupted)
        everything, finished = run_atlas(atlas, points, client, batch_size=2)
    assert complete is False and finished is True
    assert len(records) == 2 and len(everything) == 6
    kept = {r["point"] for r in records}
    same = [r for r in everything if r["point"] in kept]
    assert json.dumps(same, sort_keys=True) == json.dumps(records, sort_keys=True)


def test_the_feasible_boundary_is_the_largest_feasible_force_in_each_span_step():
    from tactcad.studies.design_atlas import feasible_boundary

    def r(span, force, feasible):
        return {"kobj_lo_N_per_mm": 1.0, "kobj_hi_N_per_mm": span,
                "full_scale_force_N": force, "feasible": feasible}

    records = [r(2.0, 0.1, True), r(2.5, 0.3, True), r(3.0, 9.0, False),
               r(30.0, 0.02, True), r(50.0, 0.05, False)]
    steps = feasible_boundary(records, bins=2)
    # spans 2 ... 50 cut at sqrt(100) = 10: the refused 9 N and 0.05 N bound nothing
    assert [round(s[2], 6) for s in steps] == [0.3, 0.02]
    assert steps[0][0] == pytest.approx(2.0) and steps[0][1] == pytest.approx(10.0)
    assert steps[1][1] == pytest.approx(50.0)
    assert feasible_boundary([r(2.0, 0.1, False)], bins=3) == []
    with pytest.raises(DesignError, match="bins"):
        feasible_boundary(records, bins=0)


@pytest.mark.slow  # six comb searches, half of them judging every candidate
def test_comb_records_are_the_same_whether_pairs_short_of_the_margin_wait_or_not(monkeypatch):
    """Holding back the verification of candidates whose limits fall short of the force
    margin changes no record: feasible points keep their figures, refused ones their limit,
    words and option."""
    from tactcad.studies import comb_design

    atlas = jaw_atlas("10", [(COMB, "Ti-6Al-4V-annealed")])
    points = [{"point": 0, "kr_over_km": 21.267, "kobj_lo_N_per_mm": 2.87533,
               "kobj_hi_N_per_mm": 18.4831, "full_scale_force_N": 0.12, "columns": 2},
              {"point": 1, "kr_over_km": 10.0, "kobj_lo_N_per_mm": 0.5,
               "kobj_hi_N_per_mm": 5.0, "full_scale_force_N": 0.6, "columns": 2},
              {"point": 2, "kr_over_km": 6.0, "kobj_lo_N_per_mm": 0.8,
               "kobj_hi_N_per_mm": 8.0, "full_scale_force_N": 0.2, "columns": 3}]
    waiting = evaluate_batch(atlas, points)
    monkeypatch.setattr(comb_design, "short_of_margin", lambda d, limits: False)
    judged_in_turn = evaluate_batch(atlas, points)
    assert any(r["feasible"] for r in waiting) and not all(r["feasible"] for r in waiting)
    assert json.dumps(waiting, sort_keys=True) == json.dumps(judged_in_turn, sort_keys=True)


def test_each_materials_command_at_a_point_writes_its_own_file():
    # every comb material's line at a point wrote atlas_monolithic_comb_<point>.toml, so the
    # second pasted was refused as "a file that does not exist yet"
    from tactcad.studies.design_atlas import design_command

    point = {"point": 6, "kr_over_km": 8.0, "kobj_lo_N_per_mm": 0.5, "kobj_hi_N_per_mm": 5.0,
             "full_scale_force_N": 0.1, "columns": 4}
    outs = {m: design_command("10", COMB, m, point).split("--out ")[1]
            for m in ("Ti-6Al-4V-annealed", "17-4PH-H900", "7075-T6")}
    assert len(set(outs.values())) == 3
    assert all(o.endswith("_6.toml") and o.replace("_", "").replace(".", "").isalnum()
               for o in outs.values())
    assert design_command("5", DIE, SILICON, point).endswith("--out die_6.toml")


def test_the_names_an_atlas_writes_are_short_distinct_design_names():
    # atlas_monolithic_comb_ti_6al_4v_annealed_0 (42 characters) ran its drawings' number
    # past the title block; a project's point folder added the project's name to it
    import re

    from tactcad.studies.design_atlas import (GRADE_KEYS, beside_folder_name,
                                              command_beside_project, design_command,
                                              written_name)
    from tactcad.vocabulary.schema import NAME_PATTERN

    assert written_name(COMB, "Ti-6Al-4V-annealed", 0) == "comb_ti64_0.toml"
    grades = [*GRADE_KEYS, "Ti-6Al-4V-annealed-ELI", "Ti-6Al-4V annealed", "ti64", "X"]
    names = {(g, p): written_name(COMB, g, p).removesuffix(".toml")
             for g in grades for p in (0, 7, 99_999)}
    names[DIE, 99_999] = written_name(DIE, SILICON, 99_999).removesuffix(".toml")
    assert len(set(names.values())) == len(names)
    assert all(re.fullmatch(NAME_PATTERN, n) and len(n) <= 27 for n in names.values())
    for project in ("lab", "a" * 64, "lab_" * 16):
        for n in names.values():
            folder = beside_folder_name(project, n)
            assert re.fullmatch(NAME_PATTERN, folder) and folder.endswith("_" + n)
            assert len(folder) <= 64 and folder.startswith(project[:3])
    point = {"point": 99_999, "kr_over_km": 8.0, "kobj_lo_N_per_mm": 0.5,
             "kobj_hi_N_per_mm": 5.0, "full_scale_force_N": 0.1, "columns": 4}
    die_line = command_beside_project(design_command("5", DIE, SILICON, point), "a" * 64)
    assert die_line.endswith(" --out ../" + "a" * 22 + "_die_99999")  # a die's 32 characters
    comb_line = command_beside_project(design_command("5", COMB, "7075-T6", point), "a" * 64)
    assert comb_line.endswith(" --out ../" + "a" * 46 + "_comb_al7075_99999")


@pytest.mark.slow  # twelve comb searches, half of them weighing every candidate
def test_comb_records_are_the_same_whether_pairs_short_by_strength_wait_or_not(monkeypatch):
    """Setting aside, with its webs alone, a candidate whose yield or fatigue limit already
    lacks the force margin (weighed only when none has the margin, and then only where it
    can change the record) changes no record: feasible points keep their figures, refused
    ones their limit, words and option (a force no comb carries, stops that fit at no
    sheet, grades either side of their frontier)."""
    from tactcad.studies import comb_design

    atlas = jaw_atlas("10", [(COMB, "6061-T6"), (COMB, "Ti-6Al-4V-annealed")])
    points = [{"point": 3, "kr_over_km": 15.7126, "kobj_lo_N_per_mm": 0.0183033,
               "kobj_hi_N_per_mm": 0.551098, "full_scale_force_N": 3.77821, "columns": 4},
              {"point": 4, "kr_over_km": 12.1472, "kobj_lo_N_per_mm": 0.395847,
               "kobj_hi_N_per_mm": 4.17276, "full_scale_force_N": 0.998227, "columns": 3},
              {"point": 7, "kr_over_km": 28.6453, "kobj_lo_N_per_mm": 0.385629,
               "kobj_hi_N_per_mm": 0.934451, "full_scale_force_N": 0.0934922, "columns": 2}]
    set_aside = []
    real = comb_design.short_by_strength
    monkeypatch.setattr(comb_design, "short_by_strength",
                        lambda w: set_aside.append(real(w)) or set_aside[-1])
    waiting = evaluate_batch(atlas, points)
    monkeypatch.setattr(comb_design, "short_by_strength", lambda w: None)
    weighed = evaluate_batch(atlas, points)
    assert any(set_aside) and {r["binding_limit"] for r in waiting} == {"", "stop", "force"}
    assert json.dumps(waiting, sort_keys=True) == json.dumps(weighed, sort_keys=True)


def test_a_comb_points_f1_is_the_first_frequency_modal_reports_with_the_gauge(capsys):
    """``lowest_first_Hz`` is ``tactcad modal --json``'s, under its name (the elements with
    their gauge installations' mass), not the bare element's."""
    from pathlib import Path

    import tactcad
    from tactcad.cli import main
    from tactcad.studies.design_atlas import plan_figures

    design = Path(__file__).resolve().parents[2] / "hardware" / "grasper_jaw_10mm" / \
        "grasper_jaw_10mm.toml"
    from tactcad.assembly.inventory import array_envelope_mm

    f1 = plan_figures(tactcad.load(design).plan, array_envelope_mm)["lowest_first_Hz"]
    capsys.readouterr()
    main(["modal", "--design", str(design), "--json"])
    modal = json.loads(capsys.readouterr().out)
    assert f1 == pytest.approx(modal["lowest_first_Hz"], rel=1e-12)
    assert all(f1 < e["bare_first_Hz"] for e in modal["elements"] if e.get("bare_first_Hz"))


def test_a_die_points_max_force_is_the_largest_rating_strength_reports_on_its_file(tmp_path):
    """``max_force_N`` of a die is the least of its rating limits with their model errors'
    room (an on-stop failure probability may bind before the in-use one ``verify`` names):
    ``tactcad strength --json``'s ``largest_rating_N`` on the die ``design`` writes, and the
    API's, above the rating ``design`` accepted and below the nominal least limit."""
    import tactcad

    atlas = jaw_atlas("5", [(DIE, SILICON)])
    point = {"point": 0, "kr_over_km": 7.7252, "kobj_lo_N_per_mm": 1.07717,
             "kobj_hi_N_per_mm": 3.73352, "full_scale_force_N": 0.00905571, "columns": 8}
    record = evaluate_batch(atlas, [point])[0]
    assert record["feasible"], record
    code, _ = design_verdict(record, tmp_path)
    assert code == 0
    written = tmp_path / record["command"].rsplit(" ", 1)[-1]
    printed = run_cli("strength", "--design", written, "--json")
    strength = json.loads(printed.stdout)
    assert strength["largest_rating_N"] == pytest.approx(record["max_force_N"], rel=1e-12)
    assert "on its deepest stop" in strength["largest_rating_binds"]
    assert tactcad.load(written).strength()["largest_rating_N"] == strength["largest_rating_N"]
    assert strength["largest_rating_N"] < strength["largest_rating_nominal_N"]
    assert record["max_force_N"] >= record["full_scale_force_N"]


def test_a_feasible_combs_figures_read_from_its_search_are_the_written_designs(monkeypatch):
    """The figures of a feasible comb read from its chosen candidate's verification matrix
    (its search worked it out) are those the written design's own matrix gives, and the
    written design's matrix is not worked out again."""
    from tactcad.studies import verification
    from tactcad.studies.comb_design import (candidates_weighed, comb_of_candidates,
                                             first_preferred)
    from tactcad.studies.design_atlas import plan_figures, targets_of

    atlas = jaw_atlas("10", [(COMB, "Ti-6Al-4V-annealed")])
    point = {"point": 0, "kr_over_km": 21.267, "kobj_lo_N_per_mm": 2.87533,
             "kobj_hi_N_per_mm": 18.4831, "full_scale_force_N": 0.12, "columns": 2}
    targets = targets_of(point)
    with candidates_weighed():
        best = first_preferred(targets, atlas.room, 2, atlas.comb_base, grade=COMB_TI,
                               envelope_of=atlas.envelope_of)
        assert best is not None and best.predicted
        design = comb_of_candidates([best], targets, atlas.room, 2,
                                    envelope_of=atlas.envelope_of, fastener_reasons=False)
    assert design.chosen is not None and design.chosen.predicted
    fresh = plan_figures(design.plan, atlas.envelope_of)
    judged = []  # the names of the plans whose matrix is worked out
    matrix = verification.verification_matrix
    monkeypatch.setattr(verification, "verification_matrix",
                        lambda plan, *a, **k: judged.append(plan.name) or matrix(plan, *a, **k))
    read = plan_figures(design.plan, atlas.envelope_of, design.chosen.predicted)
    assert read == fresh and judged == []
    record = evaluate_batch(atlas, [point])[0]
    assert record["feasible"] and {k: record[k] for k in fresh} == fresh
    # the candidates' matrices alone: not the written design's (its name)
    assert judged and design.plan.name not in judged


COMB_TI = "Ti-6Al-4V-annealed"
