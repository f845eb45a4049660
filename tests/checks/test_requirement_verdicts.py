"""``tactcad check`` judges the requirements with the verdicts ``tactcad verify`` gives by
default: a requirement the closed form leaves undecided and a higher level fails fails the
check too (a lab's CI on ``check --junit`` goes red where verify does), and one undecided at
the ladder's top stays undecided."""

from __future__ import annotations

import copy

import pytest

import tactcad
from tactcad.checks.check_result import status_of
from tactcad.checks.groups import CheckContext
from tactcad.checks.requirement_checks import requirement_checks, requirement_group
from tactcad.studies import verification

FORCE = "full_scale_force_N"


@pytest.fixture(scope="module")
def small():
    return tactcad.load(None, {"array.columns": 2, "arms.lengths_mm": [4, 6, 5, 7]})


@pytest.fixture(scope="module")
def closed_form(small):
    return verification.verification_matrix(small.plan, "closed-form")


def _ladder(monkeypatch, closed_form, verdicts: dict[str, str]) -> list[str]:
    """Each level's matrix: the closed form's records, the full-scale force given the
    level's verdict in ``verdicts`` (computed at that level); the levels asked, in order."""
    asked = []

    def matrix(plan, model="closed-form", *args, **kwargs):
        asked.append(model)
        records = copy.deepcopy(closed_form)
        force = next(r for r in records if r["requirement"] == FORCE)
        force.update(verdict=verdicts[model], model=model, level_fixed=False,
                     **{"pass": verdicts[model] != "fail"})
        return records

    monkeypatch.setattr(verification, "verification_matrix", matrix)
    monkeypatch.setattr(verification, "prefetch_top_level", lambda *a, **k: 0)
    return asked


def _force_check(results):
    return next(r for r in results if r.subject == FORCE)


def test_a_requirement_undecided_at_the_closed_form_and_failed_above_fails_the_check(
        monkeypatch, small, closed_form):
    asked = _ladder(monkeypatch, closed_form, {"closed-form": "undecided", "beam": "undecided",
                                               "fem2d": "fail", "fem3d": "pass"})
    verified = small.verify()  # verify's default: auto
    (label, found), = requirement_group(CheckContext(small.plan, None, None))
    force = _force_check(found)
    assert label == "requirements"
    assert not force.passed and status_of(force) == "fail", force.detail
    assert "fem2d" in force.detail
    assert not verified.passed
    assert {r["requirement"]: r["verdict"] for r in verified.records} == \
        {r.subject: status_of(r) for r in found}
    # no more solved than verify's default: fem3d is never asked, the climb stops at fem2d
    assert "fem3d" not in asked


def test_a_requirement_undecided_at_the_ladders_top_stays_undecided(monkeypatch, small,
                                                                    closed_form):
    _ladder(monkeypatch, closed_form, dict.fromkeys(("closed-form", "beam", "fem2d", "fem3d"),
                                                    "undecided"))
    force = _force_check(requirement_checks(small.plan))
    assert force.passed and status_of(force) == "undecided"
    assert "undecided up to the ladder's top (fem3d)" in force.detail


def test_design_jaw_keeps_the_closed_form_alone(monkeypatch, small, closed_form):
    asked = _ladder(monkeypatch, closed_form, {"closed-form": "undecided", "beam": "fail",
                                               "fem2d": "fail", "fem3d": "fail"})
    context = CheckContext(small.plan, None, None, requirements_model="closed-form")
    (_, found), = requirement_group(context)
    assert status_of(_force_check(found)) == "undecided" and asked == ["closed-form"]


def test_the_fem2d_grid_strain_is_kept_so_a_second_command_solves_nothing(monkeypatch,
                                                                          tmp_path):
    """verify and then check (two processes, one store): the grid strain's three fem2d
    solves of an element are read back, not solved again."""
    from tactcad.design.array_plan import load_design
    from tactcad.mechanics.fem import fem2d
    from tactcad.mechanics.readout_chain import meshed_grid_strain_per_N, readout_chain
    from tactcad.store import Store, keeping_results

    plan = load_design()
    g, chain = plan.element(1).geometry, readout_chain(plan)
    real, solved = fem2d.fem2d_convergence, []
    monkeypatch.setattr(fem2d, "fem2d_convergence",
                        lambda *a, **k: solved.append(a) or real(*a, **k))
    found = []
    for _ in range(2):  # each block as one command: its memory dropped at the end
        with keeping_results(Store(tmp_path / "store")):
            found.append(meshed_grid_strain_per_N(g, plan.material, chain, "fem2d"))
    assert len(solved) == 1 and found[0] == found[1] and found[0]["grid"] < 0
