"""``[requirements] max_grasp_force_N``: at that grasp force every element's force on its
spring stays within its overload limit (yield with the safety factor, the gauge's largest
strain; verify, the grasp's force mode with its default jaw); a hard stop takes the rest."""
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TI = str(ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")


def _record(force_N):
    from tactcad.api import load
    from tactcad.studies.verification import element_figures, max_grasp_force_record, requirements_of

    sets = {} if force_N is None else {"requirements.max_grasp_force_N": force_N}
    plan = load(TI, set=sets).plan
    fig = element_figures(plan)
    return max_grasp_force_record(plan, fig, requirements_of(plan, fig))


def test_not_stated_is_not_judged():
    assert _record(None) is None


@pytest.mark.slow  # a whole chain through the command line or an export
def test_elements_beyond_their_overload_limit_fail_named_with_force_and_limit():
    r = _record(1.0)
    over = [it for it in r["elements"] if it["element_force_N"] > it["overload_limit_N"]]
    assert over and r["verdict"] == "fail" and not r["pass"]
    for it in over:
        assert any(s.startswith(f"element {it['element']}: {it['element_force_N']:.4g} N")
                   and f"limit {it['overload_limit_N']:.4g} N" in s for s in r["over_limit"])
    # past the rated force is said apart from over the limit
    assert all(f"rated {r['rated_force_N']:.4g} N" in s for s in r["past_rating"])
    # the grasp's tip forces sum to the grasp force stated
    assert r["grasp"]["as_laid_out"]["grasp_force_N"] == pytest.approx(1.0)
    assert "3 mm slab" in r["basis"] and "60 degrees" in r["basis"]


@pytest.mark.slow  # contact solves of whole grasps
def test_a_light_grasp_within_every_limit_passes():
    r = _record(1.0)
    w = next(it for it in r["elements"] if it["element"] == r["binding_element"])
    # the element forces grow with the grasp force: scale well below the deciding limit
    light = _record(1.0 * w["overload_limit_N"] / w["element_force_N"] / 3)
    assert light["verdict"] == "pass" and light["pass"]
    assert all(it["element_force_N"] * (1 + light["error_estimate_rel"]) <= it["overload_limit_N"]
               for it in light["elements"])


def test_inside_the_models_error_is_undecided():
    lo, hi = 0.01, 1.0  # the deciding element's force below / above its limit
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        r = _record(mid)
        if abs(r["margin_rel"]) < r["error_estimate_rel"] / 2:
            break
        lo, hi = (mid, hi) if r["margin_rel"] > 0 else (lo, mid)
    assert r["verdict"] == "undecided"


def test_a_grasp_force_the_jaw_cannot_reach_fails_with_why():
    r = _record(99.0)
    assert r["verdict"] == "fail" and r["predicted"] is None and "out of reach" in r["basis"]


def test_the_matrix_carries_it_only_when_stated():
    from tactcad.api import load
    from tactcad.studies.verification import verification_matrix

    def names(sets):
        return [r["requirement"] for r in verification_matrix(load(TI, set=sets).plan)]

    assert "max_grasp_force_N" not in names({})
    rec = [r for r in verification_matrix(load(TI, set={"requirements.max_grasp_force_N": 1.0}).plan)
           if r["requirement"] == "max_grasp_force_N"]
    assert rec and rec[0]["stated"] and rec[0]["verdict"] == "fail"


def test_a_hard_stop_takes_the_force_beyond_its_engagement():
    from tactcad.design.array_plan import plan_from_dict, with_overrides
    from tactcad.in_use.grasp_experiment import stop_travels
    from tactcad.studies.verification import element_figures, max_grasp_force_record, requirements_of
    from tactcad.vocabulary.schema import read_toml

    path = ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
    plan = plan_from_dict(with_overrides(read_toml(path, "design file"),
                                         {"requirements.max_grasp_force_N": 5.0}),
                          source=str(path), file=path.name)
    assert plan.hard_stops
    fig = element_figures(plan)
    r = max_grasp_force_record(plan, fig, requirements_of(plan, fig))
    stops = stop_travels(plan)
    on_stop = [it for it in r["elements"] if it["on_stop"]]
    assert on_stop and all(it["stop_force_N"] > 0 for it in on_stop)
    for it in on_stop:  # the element carries K e_s, no more
        assert it["element_force_N"] == pytest.approx(
            fig.k_of(it["element"]) * stops[it["element"]], rel=1e-9)
    # the stops keep every element of the grasper insert below its overload limit at 5 N,
    # though past its rated force
    assert r["pass"] and r["verdict"] == "pass" and r["past_rating"]
    # yet its references' stops engage past their fatigue limits (the thinnest shim sets
    # them): each such grasp is a cycle beyond them, listed beside the overload verdict
    from tactcad.studies.verification import FATIGUE_LIMITS, element_overload_limits_N

    fatigue = element_overload_limits_N(plan, fig, FATIGUE_LIMITS)
    beyond = {it["element"] for it in r["elements"]
              if it["element_force_N"] > fatigue[it["element"]]}
    assert beyond and beyond == {int(s.split(":")[0].split()[1])
                                 for s in r["fatigue_at_max_grasp"]}
    assert f"{len(beyond)} of {len(r['elements'])} elements past their fatigue" \
        in r["binding_words"]


@pytest.mark.slow  # a whole chain through the command line or an export
def test_verify_names_the_elements_beyond_their_overload_limit():
    from conftest import run_cli

    r = run_cli("verify", "--design", TI, "--model", "closed-form", "--set",
                "requirements.max_grasp_force_N=1")
    assert r.returncode == 1
    line = next(x for x in r.stdout.splitlines() if x.startswith("grasp at 1 N: FAIL"))
    over = _record(1.0)["over_limit"]
    assert over and all(words in line for words in over) and "3 mm slab" in line
    assert "grasp at" not in run_cli("verify", "--design", TI, "--model", "closed-form").stdout


def test_the_predicted_figure_is_a_grasp_force_as_the_target_is():
    """Target and prediction are one quantity: the grasp at which the deciding element
    reaches its overload limit (its force in proportion to the grasp), so the margin is
    prediction over target; the element's own force and limit are said apart."""
    r = _record(0.05)
    w = next(it for it in r["elements"] if it["element"] == r["binding_element"])
    assert not w["on_stop"]
    assert r["element_force_N"] == w["element_force_N"]
    assert r["overload_limit_N"] == w["overload_limit_N"]
    assert r["predicted"] == pytest.approx(0.05 * w["overload_limit_N"] / w["element_force_N"],
                                           rel=1e-9)
    assert r["margin_rel"] == pytest.approx(r["predicted"] / r["target"] - 1, rel=1e-9)
    # the same grasp limit read at another grasp force (the forces grow in proportion)
    assert _record(0.1)["predicted"] == pytest.approx(r["predicted"], rel=1e-6)


def test_an_element_on_its_stop_sets_no_largest_grasp():
    from tactcad.studies.verification import grasp_force_columns

    assert grasp_force_columns(2.0, 0.5, on_stop=True) == {"predicted": None,
                                                           "margin_rel": None}
    assert grasp_force_columns(2.0, 0.5, on_stop=False)["predicted"] == pytest.approx(3.0)
