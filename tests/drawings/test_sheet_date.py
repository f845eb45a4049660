"""The date every sheet prints (tactcad.drawings.frame.sheet_date): SOURCE_DATE_EPOCH,
else the design's stated date, else undated; never the clock."""

from __future__ import annotations

import copy

import pytest

from tactcad.design.array_plan import plan_from_dict
from tactcad.drawings.frame import revision_and_date, sheet_date
from tactcad.errors import DesignError


def _plan(design_data, **design):
    data = copy.deepcopy(design_data)
    data["design"].update(design)
    return plan_from_dict(data)


def test_epoch_beats_the_stated_date_and_is_utc(design_data):
    plan = _plan(design_data, date="2026-03-01", revision="C")
    assert sheet_date(plan, {"SOURCE_DATE_EPOCH": "1700000000"}) == "2023-11-14"
    assert sheet_date(plan, {"SOURCE_DATE_EPOCH": "86399"}) == "1970-01-01"   # 23:59:59 UTC
    assert sheet_date(plan, {}) == "2026-03-01"


def test_undated_design_prints_a_dash(design_data, monkeypatch):
    monkeypatch.delenv("SOURCE_DATE_EPOCH", raising=False)
    assert revision_and_date(_plan(design_data)) == ("A", "—")


@pytest.mark.parametrize("bad", ["-1", "1.5", "soon", "999999999999"])
def test_a_bad_epoch_is_one_clear_error(design_data, bad):
    with pytest.raises(DesignError, match="SOURCE_DATE_EPOCH = .*whole number of seconds"):
        sheet_date(_plan(design_data), {"SOURCE_DATE_EPOCH": bad})


@pytest.mark.parametrize("bad", ["2026-13-01", "1 March 2026", "2026-3-1"])
def test_the_schema_refuses_a_date_not_iso(design_data, bad):
    with pytest.raises(DesignError, match=r"design\.date = .*YYYY-MM-DD"):
        _plan(design_data, date=bad)


def test_the_cli_refuses_a_bad_epoch_in_one_line(monkeypatch):
    from tests.conftest import run_cli

    monkeypatch.setenv("SOURCE_DATE_EPOCH", "next week")
    done = run_cli("verify", "--model", "closed_form")
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        "tactcad: error: SOURCE_DATE_EPOCH = 'next week': allowed a whole number of seconds "
        "since 1970-01-01 UTC, 0 .. 253402300799"]
