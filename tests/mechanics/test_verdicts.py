"""Verdicts: an item is judged on its own margin and error; a record of several takes
its worst item's verdict, not the verdict of the item with the smallest margin."""

from __future__ import annotations

import pytest

from tactcad.mechanics.verdicts import deciding_item, judged, verdict


@pytest.mark.parametrize("margin, error, expected", [
    (0.0, 0.01, "undecided"),  # met at exactly zero margin with an error: cannot tell
    (0.0, 0.0, "pass"),  # met exactly, nothing uncertain
    (0.01, 0.01, "pass"),
    (-0.0101, 0.01, "fail"),
])
def test_zero_margin_with_an_error_is_undecided(margin, error, expected):
    assert verdict(margin, error, 0.0, margin >= 0) == expected


def test_the_worst_verdict_decides_not_the_smallest_margin():
    wide = judged({"name": "wide", "margin_rel": -0.05, "error_estimate_rel": 0.10})
    narrow = judged({"name": "narrow", "margin_rel": -0.03, "error_estimate_rel": 0.005})
    fine = judged({"name": "fine", "margin_rel": 0.20, "error_estimate_rel": 0.01})
    assert [wide["verdict"], narrow["verdict"], fine["verdict"]] == ["undecided", "fail", "pass"]
    assert deciding_item([wide, narrow, fine])["name"] == "narrow"
    assert deciding_item([wide, fine])["name"] == "wide"
    # among equal verdicts the smallest margin; an infinite (None) margin last
    other = judged({"name": "other", "margin_rel": 0.10, "error_estimate_rel": 0.01})
    endless = judged({"name": "endless", "margin_rel": None, "error_estimate_rel": 0.01})
    assert deciding_item([fine, endless, other])["name"] == "other"
    with pytest.raises(ValueError):
        deciding_item([])


def test_a_resonance_record_fails_on_the_element_that_misses_beyond_its_error(monkeypatch):
    """The lowest frequency (closed form, wide error) is undecided; an element verified at
    fem3d (narrow error) misses the target beyond its error: the record fails on it."""
    from tactcad.design.array_plan import load_design
    from tactcad.studies import resonance

    rows = [{"part": "soft", "elements": [1], "first_Hz": 960.0, "family": "in-plane",
             "error_estimate_rel": 0.05, "model": "closed-form", "out_of_plane_unchecked": False},
            {"part": "thin", "elements": [2], "first_Hz": 980.0, "family": "out-of-plane",
             "error_estimate_rel": 0.001, "model": "fem3d", "out_of_plane_unchecked": False}]
    monkeypatch.setattr(resonance, "first_frequencies", lambda *a, **k: [dict(r) for r in rows])
    monkeypatch.setattr(resonance, "stated_requirements",
                        lambda raw: {resonance.REQUIREMENT: 1000.0})
    (record,) = resonance.resonance_records(load_design(), "closed-form")
    assert [r["verdict"] for r in record["elements"]] == ["undecided", "fail"]
    assert record["binding_element"] == 2 and record["predicted"] == 980.0
    assert verdict(record["margin_rel"], record["error_estimate_rel"], 0.0,
                   record["pass"]) == "fail"


def test_a_thermal_record_judges_every_element():
    from pathlib import Path

    from tactcad.design.array_plan import plan_from_dict, read_toml, with_overrides
    from tactcad.studies.verification import verification_matrix

    path = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
    data = with_overrides(read_toml(path, "design"),
                          {"requirements.max_thermal_drift_N_per_K": 1e-4})
    record = next(r for r in verification_matrix(plan_from_dict(data, str(path)))
                  if r["requirement"] == "max_thermal_drift_N_per_K")
    verdicts = {e["element"]: e["verdict"] for e in record["elements"]}
    assert set(verdicts) == set(range(1, 7)) and {"pass", "fail"} <= set(verdicts.values())
    assert record["verdict"] == "fail" and verdicts[record["binding_element"]] == "fail"
