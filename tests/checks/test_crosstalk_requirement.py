"""``max_crosstalk_rel`` reaches ``tactcad check`` and the design file refuses a bad value."""

import pytest

import tactcad
from tactcad.checks.requirement_checks import requirement_checks
from tactcad.errors import TactcadError

SMALL = {"array.columns": 2, "arms.lengths_mm": [4, 6, 5, 7]}


@pytest.mark.parametrize("target, passed", [(1e-9, False), (0.5, True)])
def test_check_reports_the_stated_crosstalk(target, passed):
    plan = tactcad.load(None, {**SMALL, "requirements.max_crosstalk_rel": target}).plan
    (found,) = [r for r in requirement_checks(plan, "closed-form")
                if r.subject == "max_crosstalk_rel"]
    assert found.passed is passed


def test_unstated_crosstalk_is_not_checked():
    plan = tactcad.load(None, SMALL).plan
    assert not [r for r in requirement_checks(plan, "closed-form")
                if r.subject == "max_crosstalk_rel"]


def test_out_of_range_value_is_refused():
    with pytest.raises(TactcadError, match=r"max_crosstalk_rel.*1\.5"):
        tactcad.load(None, {"requirements.max_crosstalk_rel": 1.5})
