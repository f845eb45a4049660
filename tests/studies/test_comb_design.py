"""Designing an insert to a grasper's jaw: the comb searched inside the jaw's room."""

from __future__ import annotations

import dataclasses
import math
import re

import pytest

from tactcad.assembly.inventory import array_envelope_mm
from tactcad.errors import DesignError
from tactcad.mechanics.closed_form import estimate_closed_form
from tactcad.mechanics.hard_stops import stop_verdicts
from tactcad.design.array_plan import EXAMPLES
from tactcad.partlib.grasper_jaw import (MIN_WALL_MM, SHAFT_CLASSES_MM, GrasperJawSection,
                                         jaw_room, with_class_defaults)
from tactcad.studies.comb_design import comb_for_jaw, fastener_pairs
from tactcad.vocabulary.schema import read_toml
from tactcad.studies.inverse_design import InverseDesignError, Targets
from tactcad.studies.verification import verification_matrix

TI = "Ti-6Al-4V-annealed"


BASE = read_toml(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml", "design file")


def search(force_N: float, shaft: str = "10", room=None):
    return comb_for_jaw(Targets(10.0, (0.5, 5.0), force_N), room or jaw_room(shaft), 6, BASE,
                        grade=TI, envelope_of=array_envelope_mm)


@pytest.fixture(scope="module")
def found():
    return search(0.05)


def test_the_room_is_the_default_jaws_pocket_less_its_walls_and_clearances():
    j, room = with_class_defaults(GrasperJawSection()), jaw_room("10")
    width = SHAFT_CLASSES_MM["10"] - j.width_clearance_mm
    assert room.across_mm == pytest.approx(width - 2 * MIN_WALL_MM - 2 * j.pocket_clearance_mm)
    assert room.height_mm == pytest.approx(j.thickness_mm + j.tip_proud_mm)
    assert room.along_mm < j.length_mm - j.distal_wall_mm - j.pin_inset_mm


@pytest.mark.slow  # a whole comb search (the module's fixture)
def test_the_grasper_case_gives_a_comb_that_fits_reaches_the_ratio_and_stops_in_time(found):
    plan, room = found.plan, found.room
    assert plan.construction == "monolithic-comb" and plan.pairing == "column"
    across, along, height = plan.comb.envelope_mm
    assert across <= room.across_mm and along <= room.along_mm and height <= room.height_mm
    k = {s.number: estimate_closed_form(s.geometry, plan.material).stiffness_N_per_mm
         for s in plan.slots}
    for reference, measuring in plan.unit_pairs:
        assert k[reference] / k[measuring] == pytest.approx(10.0, rel=0.02)
    assert all(v.engages_between for v in stop_verdicts(plan, 0.05))
    records = verification_matrix(plan, "closed-form", envelope_mm=array_envelope_mm(plan))
    assert not [r["requirement"] for r in records if r["verdict"] == "fail"]
    assert [r["verdict"] for r in records if r["requirement"] == "footprint_mm"] == ["pass"]
    assert "sheet.thickness_mm" in found.data["assumptions"]
    # the grade asked, with the library's sources of its values
    from tactcad.vocabulary.material_library import material_grade

    said = found.data["assumptions"]["material.grade"]
    assert material_grade(TI).source("youngs_modulus_MPa") in said and TI in said
    # the webs' reason gives the K_m every command reports (the webs rounded to 1 um), not
    # only the one it solved for
    webs = found.data["assumptions"]["comb.web_thicknesses_mm"]
    reference, measuring = plan.unit_pairs[0]
    assert (f"as written K_m = {k[measuring]:.4g} N/mm, "
            f"K_r/K_m = {k[reference] / k[measuring]:.4g}") in webs, webs


@pytest.mark.parametrize("columns", [2, 3, 5, 6])
def test_the_combs_length_and_its_iso_2768_deviation_stay_within_the_pocket(columns):
    # a comb as long as the pocket would leave its own footprint requirement undecided
    from tactcad.design.tolerances import general_linear_tolerance_mm, tolerances_of
    from tactcad.studies.comb_design import comb_tables, sheets_of

    room = jaw_room("10")
    for sheet in sheets_of(BASE):
        d, _ = comb_tables(BASE, sheet, columns, room, Targets(10.0, (0.5, 5.0), 0.05), TI)
        along = d["array"]["pitch_mm"] * columns
        deviation = general_linear_tolerance_mm(along, tolerances_of(d).general)
        assert along + deviation <= room.along_mm + 1e-9


@pytest.mark.slow  # a whole comb search (the module's fixture)
def test_the_fasteners_are_the_first_pair_of_the_tables_the_row_and_the_jaw_hold(found):
    tried, order = found.fasteners, fastener_pairs()
    assert [(f.screw_size, f.dowel_diameter_mm) for f in tried] == order[:len(tried)]
    assert not tried[-1].failures and all(f.failures for f in tried[:-1])
    comb = found.data["comb"]
    assert (comb["screw_size"], float(comb["dowel_diameter_mm"])) == (
        tried[-1].screw_size, tried[-1].dowel_diameter_mm)
    assert found.plan.comb.envelope_mm[2] <= found.room.height_mm
    reason = found.data["assumptions"]["comb.screw_size"]
    assert reason.startswith("Searched") and all(f.label in reason for f in tried[:-1])
    assert not found.data["assumptions"]["comb.dowel_diameter_mm"].startswith("Not searched")


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_roomier_jaw_takes_the_largest_screw_and_dowel():
    roomy = dataclasses.replace(jaw_room("10"), across_mm=9.0, height_mm=8.0)
    got = search(0.05, room=roomy)
    assert (got.data["comb"]["screw_size"], float(got.data["comb"]["dowel_diameter_mm"])) == \
        fastener_pairs()[0]
    assert len(got.fasteners) == 1


@pytest.mark.slow  # a whole design search
def test_a_jaw_too_thin_for_every_comb_is_refused_naming_the_height():
    thin = dataclasses.replace(jaw_room("10"), height_mm=4.0)
    with pytest.raises(InverseDesignError) as caught:
        search(0.05, room=thin)
    assert "the comb's height" in caught.value.line() and "holds 4 mm" in caught.value.line()


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_force_no_comb_carries_is_refused_with_a_nearest_force_that_one_does():
    with pytest.raises(InverseDesignError) as caught:
        search(0.3)
    text = caught.value.line()
    assert "1 mm sheet" in text and "full_scale_force_N" in text
    nearest = float(re.search(r"--full-scale-force ([\d.]+)", text).group(1))
    assert 0.05 < nearest < 0.3
    assert search(nearest).plan is not None
    with pytest.raises(InverseDesignError):  # the frontier within 1 %, as a stacked search's
        search(round(nearest * 1.01, 5))


@pytest.mark.slow  # whole design searches at three forces
def test_a_force_whose_stops_fit_no_sheet_is_refused_with_a_lighter_force_that_designs():
    # at 5 N every candidate's stop gaps exceeded 1 mm, so none was rated and the refusal
    # said no comb carries any force in this jaw, though 0.14 N designs
    with pytest.raises(InverseDesignError) as caught:
        search(5.0)
    text = caught.value.line()
    assert "stop_gaps_mm" in text and "none to paste" not in text
    nearest = float(re.search(r"--full-scale-force ([\d.]+)", text).group(1))
    assert nearest < 5.0 and search(nearest).plan is not None
    with pytest.raises(InverseDesignError):
        search(round(nearest * 1.05, 4))  # the frontier: a little more is refused


def test_the_5_mm_class_names_the_pocket_too_narrow_for_any_sheet():
    with pytest.raises(InverseDesignError) as caught:
        search(0.05, "5")
    assert "footprint" in caught.value.line() and "5 mm jaw" in caught.value.line()


def test_an_unknown_trocar_class_is_refused_naming_the_option():
    with pytest.raises(DesignError) as caught:
        jaw_room("7")
    assert caught.value.field == "--jaw" and "10" in caught.value.allowed
    assert not math.isnan(jaw_room("10").along_mm)


@pytest.mark.slow  # a whole design search
def test_the_design_jaw_bench_prints_each_forces_seconds_and_answer():
    from tactcad.benchmarks.design_jaw_bench import design_jaw_figures, design_jaw_lines

    figures = design_jaw_figures(BASE, (0.05,))
    run = figures["runs"][0]
    assert run["found"] and run["seconds"] > 0 and run["counted"] >= 1
    lines = design_jaw_lines(figures)
    assert lines[1].startswith("  0.05 N:") and "mm sheet" in lines[1]


@pytest.mark.slow  # a whole comb search (the module's fixture)
def test_every_stop_engages_below_its_elements_fatigue_limits_or_says_the_least_gap_binds(found):
    # the measuring stops engaged at 1.3 x the rating, past their fatigue limits
    from tactcad.design.comb_plan import MIN_SET_GAP_MM
    from tactcad.mechanics.hard_stops import stop_verdicts

    verdicts = stop_verdicts(found.plan, 0.05)
    assert verdicts and all(v.engages_between for v in verdicts)
    for v in verdicts:
        assert v.below_fatigue or v.gap_mm == pytest.approx(MIN_SET_GAP_MM), v
    reason = found.data["assumptions"]["comb.stop_gaps_mm"]
    past = [v for v in verdicts if not v.below_fatigue]
    assert ("the least gap binds" in reason) == bool(past)
    assert all(f"element {v.element} at" in reason for v in past)


@pytest.mark.parametrize("multiple, rated, fatigue, expected", [
    (1.3, 1.0, 2.0, 1.3),  # the multiple comes first
    (1.3, 1.0, 1.2, 1.1),  # midway to the fatigue limit
    (1.3, 1.0, 0.9, 1.3),  # no fatigue limit above the rating: the multiple
])
def test_a_stop_engages_at_the_multiple_or_midway_to_the_fatigue_limit(multiple, rated, fatigue,
                                                                         expected):
    from tactcad.mechanics.hard_stops import engagement_force_N

    assert engagement_force_N(multiple, rated, fatigue) == pytest.approx(expected)


@pytest.mark.parametrize("margin, words", [(0.25, "with 20% to spare (+25.0%)"),
                                           (0.046, "most force to spare (+4.6%): none")])
def test_the_sheets_reason_says_the_rule_that_chose_it(margin, words):
    # "with 20% to spare (+4.6%)" said a margin the sheet did not have
    from tactcad.studies.comb_design import sheet_rule_words

    assert words in sheet_rule_words(margin)


def test_the_refusals_fewer_columns_check_stops_at_the_first_comb_that_carries_a_force():
    """Eight columns crowd the 10 mm jaw's pocket; seven or fewer carry a light force, so a
    refusal offers ``--columns``; for a single column, more columns are offered."""
    import copy

    from tactcad.studies.comb_design import comb_candidates, fewer_columns_carry, refusal_option

    targets = Targets(10.0, (0.5, 5.0), 0.01)
    base = read_toml(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml", "design file")
    room = jaw_room("10")
    searched, tried = comb_candidates(targets, room, 8, copy.deepcopy(base))
    assert all(c.plan is None for c in tried)  # the pitch binds every sheet
    assert fewer_columns_carry(searched, 8, room, targets, None, array_envelope_mm)
    assert refusal_option(searched, tried, targets, room, 8, None,
                          array_envelope_mm) == "--columns"
    assert fewer_columns_carry(searched, 1, room, targets, None, array_envelope_mm)


#: Targets whose softer element's stop cannot fit at some K_m scales: a 1.5 N and a 3 N
#: force on eq. 2's centre K_m of 0.5 N/mm (scale 1 and scales 1 ... 2 skipped), and an
#: atlas point whose K_m of 0.025 N/mm fits no stop at any scale.
STOPLESS = [Targets(10.0, (0.5, 5.0), 1.5), Targets(10.0, (0.5, 5.0), 3.0),
            Targets(15.7126, (0.0183033, 0.551098), 3.77821)]


@pytest.mark.parametrize("targets", STOPLESS)
def test_a_scale_whose_stops_cannot_fit_carries_on_no_sheet_at_any_column_count(targets):
    """Every candidate at a scale the stop bound skips is refused and rated for no force,
    on each sheet and at one to four columns, its widest stop gap past the tables' range:
    the bound leaves out only what the search would not carry."""
    from tactcad.partlib.array.comb_sheet import MAX_STOP_GAP_MM
    from tactcad.studies.comb_design import (KM_SCALES, candidate, searched_base,
                                             stop_fitting_scales, web_solves_kept)

    skipped = [s for s in KM_SCALES if s not in stop_fitting_scales(targets)]
    assert skipped and skipped == list(KM_SCALES[:len(skipped)])  # the softest pairs
    base, room = searched_base(BASE, 4), jaw_room("10")
    with web_solves_kept():
        for scale in (skipped[0], skipped[-1]):  # the softest and the one nearest the bound
            for sheet in (0.5, 0.8, 1.0):
                for columns in (1, 2, 4):
                    c = candidate(base, sheet, scale, columns, room, targets, TI,
                                  array_envelope_mm, None)
                    assert c.plan is None and not c.rated_force_N, (scale, sheet, columns)
                    if c.data is not None:  # the stops were set: they are what refuses it
                        assert max(c.data["comb"]["stop_gaps_mm"]) > MAX_STOP_GAP_MM


def test_the_stop_bound_skips_no_scale_whose_stop_gaps_fit():
    """A force whose rated deflection of K_m x 2 is 1 mm sits at the bound's edge: its scale
    is kept, the next softer one skipped; a light force keeps every scale."""
    from tactcad.studies.comb_design import (KM_SCALES, STOP_BOUND_K_SLACK, centred_km,
                                             stop_fitting_scales, stops_can_fit)

    light = Targets(10.0, (0.5, 5.0), 0.01)
    assert stop_fitting_scales(light) == KM_SCALES
    edge = Targets(10.0, (0.5, 5.0), 2.0 * STOP_BOUND_K_SLACK * centred_km(light))
    assert stops_can_fit(edge, 2.0) and not stops_can_fit(edge, 1.5)


#: Atlas points (seed 0: points 9, 21 and 23) whose fewer-column combs set stop gaps of 1.3
#: to 2.7 mm at the one scale the bound kept while its slack was 2: now none is kept.
WIDE_GAPS = [Targets(4.78643, (0.103724, 0.30022), 1.82081),
             Targets(6.71764, (0.25943, 0.96323), 4.06206),
             Targets(24.4017, (0.0624859, 0.302583), 0.628008)]


@pytest.mark.parametrize("targets", WIDE_GAPS)
def test_the_stiffest_scale_the_tighter_stop_bound_skips_sets_gaps_past_the_tables(targets):
    """At the stiffest K_m scale, skipped since the bound's slack is 1.25, every sheet's comb
    of one to three columns whose webs are solved sets a stop gap past the tables' 1 mm and
    is rated for no force: the bound leaves out only what the search would not carry."""
    from tactcad.partlib.array.comb_sheet import MAX_STOP_GAP_MM
    from tactcad.studies.comb_design import (KM_SCALES, candidate, searched_base,
                                             stop_fitting_scales, web_solves_kept)

    assert stop_fitting_scales(targets) == ()
    base, room = searched_base(BASE, 3), jaw_room("10")
    stopped = 0
    with web_solves_kept():
        for sheet in (0.5, 0.8, 1.0):
            for columns in (1, 2, 3):
                c = candidate(base, sheet, KM_SCALES[-1], columns, room, targets, TI,
                              array_envelope_mm, None)
                assert c.plan is None and not c.rated_force_N, (sheet, columns)
                if c.data is not None:
                    assert max(c.data["comb"]["stop_gaps_mm"]) > MAX_STOP_GAP_MM
                    stopped += 1
    assert stopped  # some reached their stops: the bound, not the webs, is what is tested


def test_a_solved_web_leaves_its_element_within_the_stop_bounds_slack_of_its_target():
    """The stop bound reads K at most STOP_BOUND_K_SLACK x its target: the solved webs'
    elements, as the stops read them (the plan's closed-form strength), stay within the 1 um
    rounding's 8 % of their targets on every sheet, scale and column count tried."""
    from tactcad.mechanics.element_strength import plan_strength
    from tactcad.studies.comb_design import (STOP_BOUND_K_SLACK, centred_km, comb_tables,
                                             searched_base, with_webs)

    targets = Targets(10.0, (0.5, 5.0), 0.05)
    base, room = searched_base(BASE, 4), jaw_room("10")
    ratios = []
    for sheet in (0.5, 1.0):
        for scale in (1.0, 4.0, 12.0):
            for columns in (2, 4):
                d, binding = comb_tables(base, sheet, columns, room, targets, TI)
                try:
                    d, plan, binding = with_webs(d, targets, scale)
                except DesignError:  # the tables refused before any web: nothing to read
                    continue
                if binding:
                    continue
                k_m = scale * centred_km(targets)
                for r in plan_strength(plan, targets.full_scale_force_N, "closed-form"):
                    target = targets.kr_over_km * k_m if r.element <= columns else k_m
                    ratios.append(r.stiffness_N_per_mm / target)
    assert len(ratios) >= 8
    assert max(ratios) < 1.08 < STOP_BOUND_K_SLACK


@pytest.mark.parametrize("targets, columns, carries", [
    (STOPLESS[1], 8, True),  # the pitch binds 8 columns; fewer carry at the stiffer scales
    (STOPLESS[2], 4, False),  # no scale fits a stop: nothing to judge
    (WIDE_GAPS[0], 3, False),  # stop gaps of 2.6 mm at the stiffest scale: none judged
    (WIDE_GAPS[2], 4, False),
])
def test_fewer_columns_are_found_as_the_unbounded_search_finds_them(targets, columns, carries,
                                                                    monkeypatch):
    """The refusal's search for fewer columns gives the same answer with the stop bound as
    judging every sheet at every scale of every fewer count."""
    from tactcad.studies import comb_design

    base, room = comb_design.searched_base(BASE, columns), jaw_room("10")

    def fewer():
        with comb_design.web_solves_kept():
            return (comb_design.fewer_columns_carry(base, columns, room, targets, TI,
                                                    array_envelope_mm),
                    comb_design.nearest_columns(base, columns, room, targets, TI,
                                                array_envelope_mm) if not carries else None)

    bounded = fewer()
    monkeypatch.setattr(comb_design, "stop_fitting_scales", lambda t: comb_design.KM_SCALES)
    assert bounded == fewer()
    assert bounded[0] is carries


def test_the_fewer_columns_check_reads_a_rating_from_the_limits_without_a_matrix(monkeypatch):
    """A comb of fewer columns whose closed-form limits rate it carries a force: the
    refusal's check answers so without its verification matrix (the matrix's full-scale
    force record reads the same binding limit), most of what a judgement costs."""
    from tactcad.studies import comb_design, verification

    targets, columns = STOPLESS[1], 8  # the pitch binds 8 columns; fewer carry
    base, room = comb_design.searched_base(BASE, columns), jaw_room("10")
    matrices = []
    matrix = verification.verification_matrix

    def counted(*args, **kwargs):
        matrices.append(args[0])
        return matrix(*args, **kwargs)

    monkeypatch.setattr(verification, "verification_matrix", counted)
    with comb_design.web_solves_kept():
        assert comb_design.fewer_columns_carry(base, columns, room, targets, TI,
                                               array_envelope_mm)
    assert matrices == []


@pytest.mark.parametrize("targets, columns, some", [(STOPLESS[1], 7, False),
                                                    (STOPLESS[1], 4, True),
                                                    (WIDE_GAPS[2], 2, False),
                                                    (Targets(10.0, (0.5, 5.0), 0.01), 6, True)])
def test_whether_a_candidate_carries_is_what_its_judgement_says(targets, columns, some):
    """:func:`candidate_carries`, reading a rating from the limits where they give one, says
    of every sheet at every scale what the candidate judged in full says: it counts or is
    rated for some force."""
    from tactcad.studies import comb_design

    base, room = comb_design.searched_base(BASE, columns), jaw_room("10")
    said = []
    with comb_design.web_solves_kept(), comb_design.candidates_weighed():
        for sheet in comb_design.sheets_of(base):
            for scale in comb_design.KM_SCALES:
                c = comb_design.candidate(base, sheet, scale, columns, room, targets, TI,
                                          array_envelope_mm, None)
                judged = bool((c.plan is not None and not c.failures) or c.rated_force_N)
                assert comb_design.candidate_carries(base, sheet, scale, columns, room,
                                                     targets, TI, array_envelope_mm) is judged
                said.append(judged)
    assert any(said) is some


@pytest.mark.parametrize("kr_over_km, kobj, force, columns", [
    (21.267, (2.87533, 18.4831), 0.0620327, 2),
    pytest.param(10.0, (0.5, 5.0), 0.05, 6, marks=pytest.mark.slow),  # six columns: a long search
])
def test_the_first_preferred_comb_is_the_one_the_whole_search_chooses(kr_over_km, kobj, force,
                                                                      columns):
    """Judged in the chosen one's order and stopped at the first with margin, the search
    finds the very comb that judging every sheet at every scale chooses."""
    from tactcad.studies.comb_design import chosen, comb_candidates, counting, first_preferred

    targets = Targets(kr_over_km, kobj, force)
    lazy = first_preferred(targets, jaw_room("10"), columns, BASE, grade=TI,
                           envelope_of=array_envelope_mm)
    _, tried = comb_candidates(targets, jaw_room("10"), columns, BASE, grade=TI,
                               envelope_of=array_envelope_mm)
    best = chosen(counting(tried))
    assert lazy is not None and best.force_margin_rel >= 0.2
    assert (lazy.sheet_mm, lazy.km_scale) == (best.sheet_mm, best.km_scale)
    assert lazy.data == best.data


def test_no_first_preferred_comb_where_none_carries_the_force_with_margin():
    """A force no comb carries: nothing is chosen early, the whole search decides."""
    from tactcad.studies.comb_design import first_preferred

    assert first_preferred(Targets(10.0, (0.06, 0.43), 0.9), jaw_room("10"), 6, BASE,
                           grade=TI, envelope_of=array_envelope_mm) is None


def test_a_force_bound_fails_a_force_by_the_full_scale_record_or_a_gauge_limit():
    from tactcad.studies.comb_design import REFUSED_AT_ANY_FORCE, ForceBound

    # binding 0.2 N known to 10 %: above 0.2 N the record fails or, up to 0.2 / 0.9, is
    # undecided but short of the force in its prediction: neither counts
    bound = ForceBound(binding_force_N=0.2, binding_error_rel=0.1)
    assert not bound.fails_at(0.2) and not bound.fails_at(0.1999)
    assert bound.fails_at(0.2001) and bound.fails_at(0.23)
    # a gauge limit of 0.15 N known to 5 % is not cleared above 0.15 / 1.05 = 0.1429 N
    gauged = dataclasses.replace(bound, gauge_limits=((0.15, 0.05),))
    assert not gauged.fails_at(0.142) and gauged.fails_at(0.143)
    # without an error estimate the record's nominal verdict decides, past the slack
    assert ForceBound(binding_force_N=0.2).fails_at(0.2001)
    assert not ForceBound(binding_force_N=0.2).fails_at(0.2 * (1 + 1e-7))
    assert not ForceBound().fails_at(1e6)  # nothing known: the comb must be judged
    assert REFUSED_AT_ANY_FORCE.fails_at(1e-6)


def test_a_frontier_force_no_pair_can_carry_is_refused_without_judging_a_comb(monkeypatch):
    import tactcad.studies.comb_design as comb
    from tactcad.studies.comb_design import ForceBound, comb_counts

    def judged(*args):
        raise AssertionError("a pair its bound already fails was judged again")

    monkeypatch.setattr(comb, "candidate", judged)
    pairs = [(0.5, 1.0), (0.8, 2.0)]
    bounds = {pairs[0]: comb.REFUSED_AT_ANY_FORCE,
              pairs[1]: ForceBound(binding_force_N=0.1, binding_error_rel=0.05)}
    assert not comb_counts(BASE, 0.3, 6, jaw_room("10"), Targets(10.0, (0.5, 5.0), 0.3), TI,
                           None, pairs, bounds)


@pytest.mark.slow  # four candidates judged at the closed form
def test_a_candidates_bound_does_not_move_with_the_force_and_foretells_its_failure():
    from tactcad.studies.comb_design import candidate, searched_base

    base, room = searched_base(BASE, 6), jaw_room("10")
    at = {f: candidate(base, 0.8, 4.0, 6, room, Targets(10.0, (0.5, 5.0), f), TI,
                       array_envelope_mm, None) for f in (0.05, 0.3)}
    # only the stops read the force (their widest gap moves the arms' underside, and the
    # limits' error estimates by parts in 1e9: far inside the bound's slack)
    low, high = at[0.05].force_bound, at[0.3].force_bound
    assert low.binding_force_N == pytest.approx(high.binding_force_N, rel=1e-7)
    assert len(low.gauge_limits) == len(high.gauge_limits)
    for (f, e), (f2, e2) in zip(low.gauge_limits, high.gauge_limits):
        assert f == pytest.approx(f2, rel=1e-7) and e == pytest.approx(e2, rel=1e-7)
    assert at[0.05].force_bound.fails_at(0.3) and at[0.3].failures  # and 0.3 N fails
    assert not at[0.05].force_bound.fails_at(0.05)
    refused = candidate(base, 1.5, 1.0, 6, room, Targets(10.0, (0.5, 5.0), 0.3), TI,
                        array_envelope_mm, None)
    assert refused.plan is None and refused.force_bound.refused  # the pocket, at any force


def test_kept_web_solves_give_a_fresh_solves_web_and_read_each_closed_form_once(monkeypatch):
    """Inside ``web_solves_kept`` each element's web is the one a fresh Brent solve finds,
    at every K target; a second solve of the same K reads no closed form, and a new K on
    the same element reads its bracket ends no more."""
    import tactcad.mechanics.closed_form as closed_form
    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies import comb_design

    plan = plan_from_dict(BASE)
    geometry, material = plan.element(1).geometry, plan.material
    k_here = estimate_closed_form(geometry, material).stiffness_N_per_mm
    targets = [0.7 * k_here, 1.3 * k_here, 0.9 * k_here]
    fresh = [comb_design.solved_web(geometry, material, k, 0.02, 0.6) for k in targets]
    assert all(w is not None for w in fresh)
    reads: list[float] = []
    counted = closed_form.corrected_element_k

    def counting(g, m):
        reads.append(g.web_thickness_mm)
        return counted(g, m)

    monkeypatch.setattr(closed_form, "corrected_element_k", counting)
    monkeypatch.setattr(comb_design, "_WEB_K_GRIDS", type(comb_design._WEB_K_GRIDS)())
    with comb_design.web_solves_kept():
        kept = [comb_design.solve_web(geometry, material, k, 0.02, 0.6) for k in targets]
        first_reads = len(reads)
        again = comb_design.solve_web(geometry, material, targets[0], 0.02, 0.6)
        assert len(reads) == first_reads  # the same K again: no closed form read
    assert kept == fresh and again == fresh[0]
    assert reads.count(0.02) == 1 and reads.count(0.6) == 1  # each bracket end read once
    assert comb_design._KEPT_WEBS.get() is None  # nothing kept once the search is over


@pytest.mark.parametrize("kr_over_km, kobj, force, columns", [
    (21.267, (2.87533, 18.4831), 0.12, 2),  # feasible: the softest pairs lack the margin
    (10.0, (0.5, 5.0), 0.6, 2),  # refused: every rated pair falls short of the force
])
def test_a_candidate_short_of_the_margin_by_its_limits_never_has_the_margin(
        kr_over_km, kobj, force, columns):
    """The bound that holds back a candidate's verification matrix: every candidate it
    names falls short of the force margin when judged in full, and it names some."""
    from tactcad.studies.comb_design import (FORCE_MARGIN_REL, comb_candidates,
                                             planned_limits, prepared_candidate,
                                             searched_base, short_of_margin)

    targets = Targets(kr_over_km, kobj, force)
    base = searched_base(BASE, columns)
    _, tried = comb_candidates(targets, jaw_room("10"), columns, BASE, grade=TI,
                               envelope_of=array_envelope_mm)
    named = []
    for c in tried:
        _, d, _ = prepared_candidate(base, c.sheet_mm, c.km_scale, columns, jaw_room("10"),
                                     targets, TI)
        limits = planned_limits(d)[1] if d is not None else None
        if limits is not None and short_of_margin(d, limits):
            named.append(c)
    assert named and len(named) < len(tried)
    assert all(c.force_margin_rel < FORCE_MARGIN_REL for c in named)


@pytest.mark.parametrize("kr_over_km, kobj, force, columns", [
    (10.0, (0.5, 5.0), 0.6, 2),  # refused: every rated pair falls short of the force
    # one counts, without the margin (at 2 columns the 12.6 mm arms are 12.6 x their
    # height: the closed form's error past the fitted 4 leaves no gauge limit cleared at
    # 0.15 N, and a comb that counts keeps more margin than that error)
    (10.0, (0.5, 5.0), 0.26, 3),
])
def test_without_an_answer_the_first_preferred_search_answers_as_the_whole(
        kr_over_km, kobj, force, columns):
    """Held back, each candidate is the whole search's own: its tables, margin and rating;
    those left unjudged (sketched) fail there too, the same ones count, and the nearest
    failure is the same candidate with the same first failure."""
    from tactcad.studies.comb_design import (comb_candidates, counting, first_preferred,
                                             in_search_order, nearest_failure, searched_base)

    targets = Targets(kr_over_km, kobj, force)
    judged: list = []
    assert first_preferred(targets, jaw_room("10"), columns, BASE, grade=TI,
                           envelope_of=array_envelope_mm, judged=judged) is None
    _, tried = comb_candidates(targets, jaw_room("10"), columns, BASE, grade=TI,
                               envelope_of=array_envelope_mm)
    lazy = in_search_order(judged, searched_base(BASE, columns))
    assert [(c.sheet_mm, c.km_scale, c.force_margin_rel, c.rated_force_N, c.data)
            for c in lazy] == [(c.sheet_mm, c.km_scale, c.force_margin_rel, c.rated_force_N,
                                c.data) for c in tried]
    sketched = [(c, whole) for c, whole in zip(lazy, tried) if c.sketched]
    assert sketched and all(whole.failures for _, whole in sketched)
    assert all(c.failures == whole.failures and c.limits == whole.limits
               for c, whole in zip(lazy, tried) if not c.sketched)
    assert [(c.sheet_mm, c.km_scale, c.failures) for c in counting(lazy)] == \
        [(c.sheet_mm, c.km_scale, c.failures) for c in counting(tried)]
    assert bool(counting(tried)) is (force < 0.5)
    near, whole_near = nearest_failure(lazy), nearest_failure(tried)
    assert not near.sketched
    assert (near.sheet_mm, near.km_scale, near.failures, near.limits) == \
        (whole_near.sheet_mm, whole_near.km_scale, whole_near.failures, whole_near.limits)


def test_a_sheets_starting_plan_is_planned_once_for_all_its_scales(monkeypatch):
    """Inside one search the tables a sheet starts from are planned once: every K_m scale
    gets that plan (a fresh plan's elements), or the same refusal."""
    from tactcad.design import array_plan
    from tactcad.studies import comb_design
    from tactcad.studies.comb_design import comb_tables, searched_base, starting_plan

    targets = Targets(10.0, (0.5, 5.0), 0.05)
    d, _ = comb_tables(searched_base(BASE, 2), 1.0, 2, jaw_room("10"), targets, TI)
    fresh = array_plan.plan_from_dict(d)
    refused = {**d, "sheet": {"thickness_mm": -1.0}}
    builds: list[int] = []
    real = comb_design.plan_from_dict

    def counted(tables):
        builds.append(1)
        return real(tables)

    monkeypatch.setattr(comb_design, "plan_from_dict", counted)
    monkeypatch.setattr(comb_design, "_TARGET_FREE_PLANS", type(comb_design._TARGET_FREE_PLANS)())
    with comb_design.web_solves_kept():
        first, again = starting_plan(d), starting_plan(d)
        errors = []
        for _ in range(2):
            with pytest.raises(DesignError) as exc:
                starting_plan(refused)
            errors.append([e.field for e in exc.value.errors])
    assert first is again and len(builds) == 2  # one plan, one refusal
    assert [s.geometry for s in first.slots] == [s.geometry for s in fresh.slots]
    assert errors[0] == errors[1] and errors[0]



def test_a_sheets_target_free_tables_are_made_once_a_process_for_equal_inputs_built_anew(
        monkeypatch):
    """Searches of other targets on a base and a room built anew with equal contents share
    one sheet's target-free tables (made once a process, not once a search), each search's
    tables those :func:`comb_tables` makes for its own targets; another room or sheet is
    made anew."""
    from collections import OrderedDict

    from tactcad.studies import comb_design
    from tactcad.studies.comb_design import comb_tables, searched_base, sheet_tables

    monkeypatch.setattr(comb_design, "_TARGET_FREE_TABLES", OrderedDict())
    made: list[float] = []
    real = comb_design.grid_fitted_to_sheet

    def counted(d):
        made.append(d["sheet"]["thickness_mm"])
        return real(d)

    monkeypatch.setattr(comb_design, "grid_fitted_to_sheet", counted)
    asked = [Targets(10.0, (0.5, 5.0), 0.05), Targets(4.0, (0.1, 30.0), 2.0)]
    got = []
    for targets in asked:  # each search its own base copy, room and targets
        with comb_design.web_solves_kept():
            got.append(sheet_tables(searched_base(BASE, 4), 1.0, 4,
                                    dataclasses.replace(jaw_room("10")), targets, TI))
    assert made == [1.0]
    for targets, (d, binding) in zip(asked, got):
        monkeypatch.setattr(comb_design, "grid_fitted_to_sheet", real)
        assert (d, binding) == comb_tables(searched_base(BASE, 4), 1.0, 4, jaw_room("10"),
                                           targets, TI)
        assert d["requirements"]["full_scale_force_N"] == targets.full_scale_force_N
        monkeypatch.setattr(comb_design, "grid_fitted_to_sheet", counted)
    shorter = dataclasses.replace(jaw_room("10"), along_mm=jaw_room("10").along_mm - 1.0)
    with comb_design.web_solves_kept():
        sheet_tables(searched_base(BASE, 4), 1.0, 4, shorter, asked[0], TI)
        sheet_tables(searched_base(BASE, 4), 0.8, 4, jaw_room("10"), asked[0], TI)
    assert made == [1.0, 1.0, 0.8]


def test_a_sheets_web_floor_is_read_once_for_all_its_scales(monkeypatch):
    """Inside one search the thinnest web a sheet's process leaves is worked out once for
    every K_m scale's web solve (the shared tables never change), and each solve's webs
    are those of a search that works it out each time."""
    from tactcad.studies import comb_design
    from tactcad.studies.comb_design import searched_base, sheet_tables, solved_webs

    targets = Targets(10.0, (0.5, 5.0), 0.05)
    with comb_design.web_solves_kept():
        d, _ = sheet_tables(searched_base(BASE, 4), 1.0, 4, jaw_room("10"), targets, TI)
        fresh = [solved_webs(d, targets, s)[1:] for s in comb_design.KM_SCALES]
    floors: list[int] = []
    real = comb_design.web_floor

    def counted(tables):
        floors.append(1)
        return real(tables)

    monkeypatch.setattr(comb_design, "web_floor", counted)
    with comb_design.web_solves_kept():
        d, _ = sheet_tables(searched_base(BASE, 4), 1.0, 4, jaw_room("10"), targets, TI)
        kept = [solved_webs(d, targets, s)[1:] for s in comb_design.KM_SCALES]
    assert kept == fresh and any(webs for webs, _ in kept)
    assert len(floors) == 1


@pytest.mark.parametrize("k_target", [2.0, 5.5, 11.3, 48.0, 300.0])
def test_a_solved_web_is_the_grid_web_whose_half_step_cell_holds_the_root(k_target):
    """The web search's answer on the 1 um grid: K half a step below it falls short of the
    target and K half a step above it does not (K rises with the web), as Brent's root
    rounded to the grid gives it; a target no web in the bracket reaches gives None."""
    from dataclasses import replace

    from scipy.optimize import brentq

    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies.comb_design import WEB_STEP_MM, closed_form_k, solved_web

    plan = plan_from_dict(BASE)
    g, material = plan.slots[0].geometry, plan.material

    def k(t: float) -> float:
        return closed_form_k(replace(g, web_thickness_mm=t), material)

    web = solved_web(g, material, k_target, 0.02, 1.0)
    assert k(web - WEB_STEP_MM / 2) < k_target <= k(web + WEB_STEP_MM / 2)
    root = brentq(lambda t: k(t) - k_target, 0.02, 1.0, xtol=1e-12)
    assert web == round(root / WEB_STEP_MM) * WEB_STEP_MM
    assert solved_web(g, material, k(1.0) * 1.01, 0.02, 1.0) is None
    assert solved_web(g, material, k(0.02) * 0.99, 0.02, 1.0) is None


def test_a_web_grid_is_kept_by_its_element_material_bracket_and_correction(monkeypatch):
    """The K over a web bracket a web search reads is kept per process: the same element,
    material, bracket and correction read it again; a change of any one works it out anew
    (and a target is solved on the grid it belongs to)."""
    from collections import OrderedDict

    import tactcad.mechanics.correction as correction
    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies import comb_design

    monkeypatch.setattr(comb_design, "_WEB_K_GRIDS", OrderedDict())
    plan = plan_from_dict(BASE)
    g, m = plan.element(1).geometry, plan.material
    grid = comb_design.web_k_grid(g, m, 0.02, 0.6)
    assert comb_design.web_k_grid(g, m, 0.02, 0.6) is grid
    others = [comb_design.web_k_grid(dataclasses.replace(g, arm_length_mm=3.0), m, 0.02, 0.6),
              comb_design.web_k_grid(g, dataclasses.replace(m, youngs_modulus_MPa=2e5),
                                     0.02, 0.6),
              comb_design.web_k_grid(g, m, 0.03, 0.6), comb_design.web_k_grid(g, m, 0.02, 0.5)]
    assert all(o is not grid for o in others)
    assert others[0].k_lo != grid.k_lo and others[1].k_lo != grid.k_lo  # another arm, E
    assert (others[2].first, others[3].last) == (30, 500)
    k = estimate_closed_form(g, m).stiffness_N_per_mm
    assert comb_design.solved_web(g, m, k, 0.02, 0.6) == pytest.approx(g.web_thickness_mm)
    assert comb_design.solved_web(dataclasses.replace(g, arm_length_mm=3.0), m, k, 0.02,
                                  0.6) != pytest.approx(g.web_thickness_mm)  # its own grid
    refit = dataclasses.replace(correction.load_correction(), source="a refit")
    monkeypatch.setattr(correction, "load_correction", lambda path=None: refit)
    again = comb_design.web_k_grid(g, m, 0.02, 0.6)
    assert again is not grid and again.correction is refit


def test_a_target_free_plan_is_kept_across_targets_and_planned_anew_for_other_tables(
        monkeypatch):
    """A sheet's starting plan is kept for tables that differ in the requirements the
    targets write alone: its elements are a fresh plan's; another sheet is planned anew,
    and tables whose requirements are refused on their own are planned as they are."""
    from collections import OrderedDict

    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies import comb_design
    from tactcad.studies.comb_design import comb_tables, searched_base, target_free_plan

    monkeypatch.setattr(comb_design, "_TARGET_FREE_PLANS", OrderedDict())
    base, room = searched_base(BASE, 4), jaw_room("10")

    def tables(targets, sheet=1.0):
        return comb_tables(base, sheet, 4, room, targets, TI)[0]

    a = tables(Targets(10.0, (0.5, 5.0), 0.05))
    b = tables(Targets(4.0, (0.1, 30.0), 2.0))
    kept = target_free_plan(a)
    assert target_free_plan(b) is kept
    assert [s.geometry for s in kept.slots] == [s.geometry for s in plan_from_dict(b).slots]
    other = target_free_plan(tables(Targets(10.0, (0.5, 5.0), 0.05), sheet=0.8))
    assert other is not kept and other.sheet_thickness_mm == 0.8
    inverted = {**b, "requirements": {**b["requirements"], "kobj_range_N_per_mm": [5.0, 0.5]}}
    with pytest.raises(DesignError) as fresh:
        plan_from_dict(inverted)
    with pytest.raises(DesignError) as planned:
        target_free_plan(inverted)
    assert [e.field for e in planned.value.errors] == [e.field for e in fresh.value.errors]
    assert len(comb_design._TARGET_FREE_PLANS) == 2  # the refused tables are not kept


def test_a_pair_too_tall_refused_by_its_height_leaves_the_same_fasteners_and_plan():
    """Where the reasons of the screws and dowels tried are not read (the atlas), a pair
    too tall for the jaw is refused by its height alone: the comb takes the same pair and
    its plan's figures are the full judgement's."""
    from tactcad.studies.comb_design import comb_candidates, comb_of_candidates
    from tactcad.studies.design_atlas import plan_figures

    targets, room = Targets(10.0, (0.5, 5.0), 0.0620327), jaw_room("10")
    _, tried = comb_candidates(targets, room, 2, BASE, grade=TI, envelope_of=array_envelope_mm)
    full = comb_of_candidates(tried, targets, room, 2, envelope_of=array_envelope_mm)
    fast = comb_of_candidates(tried, targets, room, 2, envelope_of=array_envelope_mm,
                              fastener_reasons=False)
    tall = [f for f in fast.fasteners if f.failures and "height" in f.failures[0]]
    assert tall and [f.label for f in fast.fasteners] == [f.label for f in full.fasteners]
    assert fast.data["comb"] == full.data["comb"]
    assert plan_figures(fast.plan, array_envelope_mm) == plan_figures(full.plan,
                                                                      array_envelope_mm)


def test_a_comb_too_soft_at_its_fewest_columns_offers_the_fewest_more_that_design():
    """Two columns leave arms too long for any web to reach K_m (one column too): the
    refusal names ``--columns`` and offers three, the nearest count that designs, which
    then designs as pasted."""
    targets = Targets(10.2571, (1.94387, 51.2684), 0.0105943)
    with pytest.raises(InverseDesignError) as caught:
        comb_for_jaw(targets, jaw_room("10"), 2, BASE, grade=TI, envelope_of=array_envelope_mm)
    assert caught.value.field == "--columns"
    assert [a["option"] for a in caught.value.alternatives] == ["--columns 3"]
    assert "none to paste" not in str(caught.value)
    pasted = comb_for_jaw(targets, jaw_room("10"), 3, BASE, grade=TI,
                          envelope_of=array_envelope_mm)
    assert pasted.plan.columns == 3


def test_a_pitch_too_short_for_the_measuring_arm_says_the_arm_it_needs():
    """Seven columns leave a 2.3 mm measuring arm, longer than the 2 mm reference's yet
    short of the 2.5 mm the search needs: the refusal's numbers say so."""
    with pytest.raises(InverseDesignError) as caught:
        comb_for_jaw(Targets(10.0, (0.5, 5.0), 0.05), jaw_room("10"), 7, BASE, grade=TI,
                     envelope_of=array_envelope_mm)
    text = str(caught.value)
    assert "leaves a measuring arm of 2.3 mm, short of the 2.5 mm it needs (0.5 mm longer " \
           "than the reference's 2 mm)" in text
    assert "not longer than" not in text


def test_a_grade_whose_comb_carries_no_force_offers_another_grade_that_designs():
    """6061-T6 at K_r/K_m 20 and K_obj 5 ... 50 N/mm: no web of any sheet reaches the
    references' K at any column count, so nothing of that grade is there to paste; the
    refusal names another grade of the library whose comb of the same columns carries a
    force, which designs as pasted, and its option stays the one the design atlas names."""
    from tactcad.studies.comb_design import comb_candidates, refusal_option

    targets, room, soft = Targets(20.0, (5.0, 50.0), 2.0), jaw_room("10"), "6061-T6"
    with pytest.raises(InverseDesignError) as caught:
        comb_for_jaw(targets, room, 2, BASE, grade=soft, envelope_of=array_envelope_mm)
    text = str(caught.value)
    assert "none to paste" not in text and f"no comb of {soft} at any column count" in text
    [offered] = caught.value.alternatives
    pasted = re.fullmatch(r"--material (\S+) --full-scale-force (\S+)", offered["option"])
    assert pasted and f"nearest: {offered['option']}" in text
    grade, force = pasted.group(1), float(pasted.group(2))
    assert grade != soft and force < targets.full_scale_force_N
    searched, tried = comb_candidates(targets, room, 2, BASE, grade=soft,
                                      envelope_of=array_envelope_mm)
    assert caught.value.field == refusal_option(searched, tried, targets, room, 2, soft,
                                                array_envelope_mm) == "--full-scale-force"
    designed = comb_for_jaw(dataclasses.replace(targets, full_scale_force_N=force), room, 2,
                            BASE, grade=grade, envelope_of=array_envelope_mm)
    assert designed.plan.columns == 2 and designed.data["material"]["grade"] == grade


def test_a_comb_no_grade_carries_says_so_with_nothing_to_paste():
    """K_obj 20 ... 200 N/mm at K_r/K_m 20 in the 10 mm jaw: no grade of the library has a
    comb that carries any force at any column count (each grade's own refusal has nothing
    to paste), and the refusal says the other grades were searched as well."""
    from tactcad.vocabulary.material_library import material_grades

    targets, room = Targets(20.0, (20.0, 200.0), 5.0), jaw_room("10")
    refusals = {}
    for grade in material_grades():
        with pytest.raises(InverseDesignError) as caught:
            comb_for_jaw(targets, room, 3, BASE, grade=grade, envelope_of=array_envelope_mm)
        refusals[grade] = caught.value
    for grade, refused in refusals.items():
        assert "none to paste" in str(refused) and not refused.alternatives
        assert "nor in any other grade of the library" in str(refused)
        assert refused.field == "--full-scale-force"


@pytest.mark.parametrize("other, pasted", [
    (("17-4PH-H900", None), "--material 17-4PH-H900"),
    (("17-4PH-H900", 0.25), "--material 17-4PH-H900 --full-scale-force 0.25"),
])
def test_another_grade_that_counts_is_offered_alone_and_one_that_carries_with_its_force(
        other, pasted):
    """A grade whose comb counts at the asked force is pasted without a force; one that
    carries a lighter force, with it; the option named stays the force's either way."""
    from tactcad.studies.comb_design import CombCandidate, refusal

    targets = Targets(20.0, (5.0, 50.0), 2.0)
    tried = [CombCandidate(0.5, 1.0, None, None, ("no web reaches K",), -math.inf, None)]
    refused = refusal(tried, targets, jaw_room("10"), 2, other_grade=other,
                      grade_asked="6061-T6")
    assert [a["option"] for a in refused.alternatives] == [pasted]
    assert str(refused).endswith(f"nearest: {pasted}") and "none to paste" not in str(refused)
    assert "no comb of 6061-T6 at any column count" in str(refused)
    assert (refused.field, refused.value) == ("--full-scale-force", 2.0)


def test_the_refusal_offers_the_grade_with_the_most_margin_not_the_first_in_the_library(
        monkeypatch):
    """Two other grades carry the force: the library lists the one with less margin first.
    The refusal offers the one with the larger margin on the full-scale force and says why
    (each grade's margin), whatever the library's order; a grade that carries nothing is
    left out, and the grade asked is not judged."""
    from tactcad.studies import comb_design
    from tactcad.vocabulary import material_library

    first, best, none = "7075-T6", "Ti-6Al-4V-annealed", "17-4PH-H900"
    margins = {first: (0.05, None), best: (0.40, None), none: None}
    judged = []

    def carried(base, columns, room, targets, grade, envelope_of):
        judged.append(grade)
        return margins[grade]

    library = {g: None for g in ("6061-T6", first, none, best)}  # less margin listed first
    monkeypatch.setattr(material_library, "material_grades", lambda: library)
    monkeypatch.setattr(comb_design, "grade_carried", carried)
    targets, room = Targets(20.0, (5.0, 50.0), 2.0), jaw_room("10")
    offer = comb_design.nearest_grade(BASE, 2, room, targets, "6061-T6", array_envelope_mm)
    assert judged == [first, none, best]  # every other grade, in the library's order
    assert (offer.grade, offer.force_N) == (best, None)
    assert "+40.0%" in offer.why and f"{first} +5.0%" in offer.why and none not in offer.why
    tried = [comb_design.CombCandidate(0.5, 1.0, None, None, ("no web reaches K",), -math.inf,
                                       None)]
    refused = comb_design.refusal(tried, targets, room, 2, other_grade=offer,
                                  grade_asked="6061-T6")
    assert [a["option"] for a in refused.alternatives] == [f"--material {best}"]
    assert offer.why in str(refused) and offer.why in refused.alternatives[0]["words"]
    # a lighter force's margin ranks below one that counts, and among lighter forces the
    # largest wins
    lighter = comb_design.best_grade({first: (-0.5, 1.0), best: (-0.2, 1.6), none: (0.0, None)})
    assert (lighter.grade, lighter.force_N) == (none, None)
    assert comb_design.best_grade({first: (-0.5, 1.0), best: (-0.2, 1.6)}).grade == best
    assert comb_design.best_grade({}) == (None, None, "")


def test_tables_a_refusals_search_knows_refused_are_refused_and_not_validated(monkeypatch):
    """The tables :func:`candidate_carries` leaves unvalidated (a notch below a web, stops
    surely set past the tables' range, a stop gap past it) are refused when validated, and
    the refusal's search of other column counts, finding no count that carries (so meeting
    every candidate), validates none of them."""
    from tactcad.studies import comb_design
    from tactcad.studies.design_atlas import tissue_default

    # an atlas point (seed 0) whose eight columns carry at no other count
    targets = Targets(26.2328, (0.946799, 15.7359), 2.51819, tissue=tissue_default())
    columns = 8
    base, room = comb_design.searched_base(BASE, columns), jaw_room("10")
    validated, known, bounded, skipped = [], [], [], []
    real = comb_design.plan_from_dict
    monkeypatch.setattr(comb_design, "plan_from_dict",
                        lambda d, *a, **k: validated.append(copy_of(d)) or real(d, *a, **k))
    with comb_design.web_solves_kept(), comb_design.candidates_weighed():
        assert not comb_design.fewer_columns_carry(base, columns, room, targets, TI,
                                                   array_envelope_mm)
        searched = list(validated)  # what the search validated (not the walk below)
        for count in sum(comb_design.other_column_counts(columns), ()):
            for sheet in comb_design.sheets_of(base):
                for scale in comb_design.stop_fitting_scales(targets):
                    refused, webbed, _ = comb_design.webbed_candidate(
                        base, sheet, scale, count, room, targets, TI)
                    if refused is not None:
                        continue
                    webbed_d = comb_design.webbed_tables(webbed.tables, webbed.webs, count)
                    if comb_design.notch_below_a_web(webbed.tables, webbed.webs):
                        known.append(webbed_d)
                        continue
                    past = comb_design.stops_past_the_tables(webbed)
                    bounded += [past]
                    _, d = comb_design.stopped_candidate(webbed)
                    if past:  # refused before its stops, or a gap past the range
                        assert d is None or comb_design.stop_gap_too_wide(d)
                        known.append(webbed_d if d is None else d)
                        skipped.append(webbed_d)  # not planned either
                    elif d is not None and comb_design.stop_gap_too_wide(d):
                        known.append(d)
    # the walk validates (the patch sees it); the search may validate none at all: the
    # sheets' starting plans are kept per process, and here every candidate's tables are
    # known refused before they are planned
    assert known and validated and any(bounded)
    keys = {comb_design.exact_key(d) for d in searched}
    assert [d for d in known + skipped if comb_design.exact_key(d) in keys] == []
    for d in known:
        with pytest.raises(DesignError):
            real(d)


@pytest.mark.parametrize("point, fits", [
    (((26.2328, (0.946799, 15.7359), 2.51819), 8), False),  # an atlas point (seed 0)
    (((10.0, (0.5, 5.0), 1.0), 6), True),  # stops that fit at some counts and sheets
])
def test_every_stop_gap_past_the_tables_is_known_before_the_stops_are_set(point, fits):
    """Each candidate the refusal's search of other column counts meets whose stop gap,
    once set, is past the tables' range is known to be before its tables are planned
    (:func:`stops_past_the_tables`), those whose notch fatigue limit is at or below the
    rating (the stop then engages at STOP_MULTIPLE x the rating) among them; none whose
    stops fit is."""
    from tactcad.studies import comb_design
    from tactcad.studies.design_atlas import tissue_default

    (kr_over_km, kobj, force), columns = point
    targets = Targets(kr_over_km, kobj, force, tissue=tissue_default())
    base, room = comb_design.searched_base(BASE, columns), jaw_room("10")
    wide, fitting = [], []
    with comb_design.web_solves_kept(), comb_design.candidates_weighed():
        for count in sum(comb_design.other_column_counts(columns), ()):
            for sheet in comb_design.sheets_of(base):
                for scale in comb_design.stop_fitting_scales(targets):
                    refused, webbed, _ = comb_design.webbed_candidate(
                        base, sheet, scale, count, room, targets, TI)
                    if refused is not None \
                            or comb_design.notch_below_a_web(webbed.tables, webbed.webs):
                        continue
                    _, d = comb_design.stopped_candidate(webbed)
                    if d is None:
                        continue
                    past = comb_design.stops_past_the_tables(webbed)
                    if comb_design.stop_gap_too_wide(d):
                        wide.append(past)
                    else:
                        fitting.append(past)
    assert wide and all(wide)
    assert bool(fitting) == fits and not any(fitting)


@pytest.mark.parametrize("fatigue_N", [0.5, 0.999, 1.0, 1.0000001, 1.2, 2.0, 10.0, None])
def test_the_least_engagement_multiple_bounds_the_stops_engagement(fatigue_N):
    """The multiple :func:`least_engagement_multiple` gives is at most the engagement over
    the rating for any lowest fatigue limit at or below the notch's (the gauge's may be
    lower), and is STOP_MULTIPLE where the notch's is at or below the rating."""
    from tactcad.mechanics.hard_stops import engagement_force_N
    from tactcad.studies.comb_design import STOP_MULTIPLE, least_engagement_multiple

    rated = 1.0
    multiple = least_engagement_multiple(fatigue_N, rated)
    for lowest in [0.1, 0.9, 1.0, 1.0 + 1e-12, 1.1, 1.5, 3.0, 20.0, math.inf]:
        if fatigue_N is not None and lowest > fatigue_N:
            continue
        assert multiple <= engagement_force_N(STOP_MULTIPLE, rated, lowest) / rated
    assert (multiple == STOP_MULTIPLE) == (fatigue_N is not None and fatigue_N < 1.0)


def copy_of(d: dict) -> dict:
    from tactcad.vocabulary.schema import copy_tables

    return copy_tables(d)


def test_a_candidate_refused_with_its_stops_is_validated_once(monkeypatch):
    """A candidate whose tables are refused once its stops are set is judged from the
    refusal its plan already met: its tables are validated once, and the candidate is the
    one judging them afresh gives."""
    from tactcad.studies import comb_design

    targets, columns = WIDE_GAPS[2], 2
    base, room = comb_design.searched_base(BASE, columns), jaw_room("10")
    with comb_design.web_solves_kept(), comb_design.candidates_weighed():
        for sheet in comb_design.sheets_of(base):
            refused, webbed, _ = comb_design.webbed_candidate(
                base, sheet, comb_design.KM_SCALES[-1], columns, room, targets, TI)
            if refused is None:
                _, d = comb_design.stopped_candidate(webbed)
                if d is not None and comb_design.stop_gap_too_wide(d):
                    break
        else:
            pytest.fail("no candidate with a stop gap past the tables")
        fresh = comb_design.judged_candidate(d, webbed.sheet_mm, webbed.km_scale,
                                             array_envelope_mm, webbed.room)
        counted = []
        real = comb_design.plan_from_dict
        monkeypatch.setattr(comb_design, "plan_from_dict",
                            lambda t, *a, **k: counted.append(t is d) or real(t, *a, **k))
        monkeypatch.setattr(comb_design, "stopped_candidate", lambda w: (None, d))
        weighed = comb_design.weighed_candidate(None, webbed, array_envelope_mm)
    assert counted == [True]
    assert weighed == fresh and weighed.plan is None and weighed.failures


@pytest.mark.slow  # a whole comb search (the module's fixture)
def test_the_comb_writes_the_k_obj_resolution_it_reaches_as_a_stacked_design_does(found):
    """requirements.md: ``tactcad design`` writes the K_obj resolution the design reaches
    (marked derived under [assumptions]) and verify judges it, whatever the construction."""
    from tactcad.design.requirements_section import DERIVED_BY_DESIGN
    from tactcad.studies.inverse_design import written_kobj_resolution
    from tactcad.studies.verification import requirements_of

    written = found.data["requirements"]["kobj_resolution_rel"]
    assert written == written_kobj_resolution(found.plan, Targets(10.0, (0.5, 5.0), 0.05))[0]
    assert found.data["assumptions"]["requirements.kobj_resolution_rel"].startswith(
        DERIVED_BY_DESIGN)
    req = requirements_of(found.plan)
    assert "kobj_resolution_rel" in req.written and "kobj_resolution_rel" not in req.stated
    row = next(r for r in verification_matrix(found.plan, "closed-form",
                                              envelope_mm=array_envelope_mm(found.plan))
               if r["requirement"] == "kobj_resolution_rel")
    assert row["verdict"] == "pass" and not row.get("informational")
