"""A refused inverse design says what to ask instead: every binding limit, the
nearest feasible targets and the change of grade, sheet or gauge that relaxes
the limits most, each checked by designing with it."""

from __future__ import annotations

import json
import re

import pytest

from tactcad.cli import main
from tactcad.studies.design_alternatives import (design_or_alternatives, nearest_targets,
                                                 relaxing_changes)
from tactcad.studies.inverse_design import (InverseDesignError, Targets, design_for_targets,
                                            design_from_tables, with_grid)

pytestmark = pytest.mark.filterwarnings(
    "ignore::tactcad.mechanics.correction.CorrectionRangeWarning")

#: The fingertip case: 2 x 4, 17-4PH, K_r/K_m 6 over 5-50 N/mm, asked 1.5 N (too much).
TOO_MUCH = Targets(6.0, (5.0, 50.0), 1.5)


def _fingertip_tables(plan, grade="17-4PH-H900"):
    data = with_grid(plan.raw, None, 4)
    data["material"] = {"name": grade, "grade": grade}
    return data


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_refusal_names_the_force_limit_behind_the_largest_force_and_the_ways_out(plan):
    with pytest.raises(InverseDesignError) as exc:
        design_or_alternatives(plan, TOO_MUCH, grade="17-4PH-H900", columns=4)
    text = str(exc.value)
    assert "K_m within the arm range" in text  # the thick webs' soft arms exceed 20 mm
    assert re.search(r"at web 0\.\d+ mm, where the asked force misses gauge fatigue strain", text)
    force = re.search(r"--full-scale-force ([0-9.]+)", text)
    assert force and float(force[1]) < TOO_MUCH.full_scale_force_N
    assert "--kr-over-km" in text and "--kobj-range" in text
    fields = [a["field"] for a in exc.value.alternatives if a["kind"] == "change"]
    assert len(fields) == len(set(fields)) and set(fields) <= {
        "material.grade", "sheet.thickness_mm", "strength.gauge"}


@pytest.mark.slow  # a whole design search
def test_each_nearest_target_is_met_and_lies_at_the_edge_of_the_feasible(plan):
    data = _fingertip_tables(plan)
    near = {a.field: a for a in nearest_targets(data, TOO_MUCH)}
    assert set(near) == {"--full-scale-force", "--kr-over-km", "--kobj-range"}
    force = near["--full-scale-force"].value
    design_from_tables(dict(data), Targets(6.0, (5.0, 50.0), force))  # met
    with pytest.raises(InverseDesignError):  # 5 % more is not
        design_from_tables(dict(data), Targets(6.0, (5.0, 50.0), force * 1.05))
    ratio = near["--kr-over-km"].value
    assert 1.0 < ratio < TOO_MUCH.kr_over_km
    design_from_tables(dict(data), Targets(ratio, (5.0, 50.0), 1.5))
    lo, hi = near["--kobj-range"].value
    assert hi / lo == pytest.approx(10.0, rel=1e-2) and lo > 5.0  # the same width, moved up
    design_from_tables(dict(data), Targets(6.0, (lo, hi), 1.5))


@pytest.mark.slow  # a whole design search
def test_a_grade_that_meets_the_targets_is_offered_first_and_does(plan):
    """6061 cannot carry 0.7 N at these stiffnesses; 17-4PH can, and is said to."""
    data = _fingertip_tables(plan, "6061-T6")
    asked = Targets(6.0, (5.0, 50.0), 0.7)
    with pytest.raises(InverseDesignError):
        design_from_tables(dict(data), asked)
    changes = relaxing_changes(data, asked)
    first = changes[0]
    assert first.field == "material.grade" and first.meets_targets
    assert first.largest_force_N >= asked.full_scale_force_N
    d = design_for_targets(plan, asked, grade=first.value, columns=4)
    assert d.plan.material.grade == first.value


@pytest.mark.slow  # a whole chain through the command line or an export
def test_the_refusal_reaches_the_command_line_as_its_json_error(tmp_path, capsys):
    argv = ["design", "--kr-over-km", "6", "--kobj-range", "5", "50", "--full-scale-force", "1.5",
            "--material", "17-4PH", "--columns", "4", "--out", str(tmp_path / "x.toml"),
            "--verify", "none", "--json"]
    assert main(argv) == 2
    out = capsys.readouterr()
    doc = json.loads(out.out)
    err = doc["error"]
    assert "nearest feasible, to paste: --full-scale-force" in err["message"]
    assert err["exit_code"] == 2 and err["field"] == "--full-scale-force" and err["value"] == 1.5
    assert [a["option"].split()[0] for a in err["alternatives"]][0] == "--full-scale-force"
    assert not (tmp_path / "x.toml").exists()


def test_a_refusals_alternatives_judge_each_design_once(monkeypatch):
    import tactcad.studies.design_alternatives as alternatives

    calls = []

    def counted(data, targets, **kwargs):
        calls.append(targets.full_scale_force_N)
        if targets.full_scale_force_N > 1.0:
            raise InverseDesignError("too much")

    monkeypatch.setattr(alternatives, "design_from_tables", counted)
    tables = {"sheet": {"thickness_mm": 1.0}, "arms": {"lengths_mm": [2.0, 3.0]}}
    asked = [TOO_MUCH, Targets(6.0, (5.0, 50.0), 0.5), TOO_MUCH]
    assert [alternatives._feasible(tables, t, None) for t in asked] == [False, True, False]
    assert len(calls) == 3  # outside a refusal every call judges
    calls.clear()
    with alternatives.evaluations_kept():
        same = {"arms": {"lengths_mm": [2.0, 3.0]}, "sheet": {"thickness_mm": 1.0}}
        assert [alternatives._feasible(same, t, None) for t in asked] == [False, True, False]
        other = {"sheet": {"thickness_mm": 1.0}, "arms": {"lengths_mm": (2.0, 3.0)}}
        alternatives._feasible(other, TOO_MUCH, None)  # a tuple is not the list
    assert calls == [1.5, 0.5, 1.5]


def test_the_nearest_kobj_range_is_sought_only_within_the_bounds_a_design_takes(monkeypatch):
    """A range near the stiff bound, shifted stiffer on the scan, leaves what Targets takes:
    such shifts are infeasible, not an error that ends the refusal."""
    import tactcad.studies.design_alternatives as alternatives

    seen = []

    def soft_only(data, targets, **kwargs):  # meets only ranges at least 10 x softer
        seen.append(targets.k_obj_range_N_per_mm)
        if targets.k_obj_range_N_per_mm[1] > 500.0:
            raise InverseDesignError("too stiff")

    monkeypatch.setattr(alternatives, "design_from_tables", soft_only)
    monkeypatch.setattr(alternatives, "_largest_force", lambda *a: 0.0)
    tables = {"sheet": {"thickness_mm": 1.0}, "arms": {"lengths_mm": [2.0, 3.0]}}
    found = alternatives.nearest_targets(tables, Targets(6.0, (500.0, 5000.0), 0.5))
    ranges = [a.value for a in found if a.field == "--kobj-range"]
    assert len(ranges) == 1 and ranges[0][1] <= 500.0
    assert seen and all(hi <= 1e4 for _, hi in seen)
