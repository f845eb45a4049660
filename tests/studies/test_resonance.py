"""``requirements.min_first_resonance_Hz``: checked when stated (verify,
verify --model auto, check), the first frequencies reported in the manifest's
requirements record either way."""

from __future__ import annotations

from pathlib import Path

import pytest

from tactcad import cli
from tactcad.design.array_plan import plan_from_dict, read_toml, with_overrides
from tactcad.errors import DesignErrors
from tactcad.studies.resonance import first_frequencies, resonance_records
from tactcad.studies.verification import requirements_record, verification_auto, verification_matrix

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def example(**overrides):
    return plan_from_dict(with_overrides(read_toml(EXAMPLE, "design"), overrides), str(EXAMPLE))


def _record(plan, model="closed-form"):
    return next(r for r in verification_matrix(plan, model)
                if r["requirement"] == "min_first_resonance_Hz")


def test_not_stated_it_is_reported_not_checked():
    plan = example()
    assert resonance_records(plan, "closed-form") == []
    summary = requirements_record(plan)["first_resonance"]
    rows = first_frequencies(plan, "closed-form")
    assert summary["lowest_first_Hz"] == rows[0]["first_Hz"] > 0
    assert summary["required_min_Hz"] is None
    # the long arms ring lowest
    assert rows[0]["part"] == max(plan.distinct_elements.values(),
                                  key=lambda g: g.arm_length_mm).part_name


def test_a_stated_minimum_passes_or_fails_with_the_lowest_element(capsys):
    low = first_frequencies(example(), "closed-form")[0]
    ok = _record(example(**{"requirements.min_first_resonance_Hz": 0.5 * low["first_Hz"]}))
    assert ok["verdict"] == "pass" and ok["stated"]
    assert ok["binding_element"] == low["elements"][0] and ok["families"] == ["in-plane"]
    bad = _record(example(**{"requirements.min_first_resonance_Hz": 2 * low["first_Hz"]}))
    assert bad["verdict"] == "fail" and bad["margin_rel"] == pytest.approx(-0.5)
    assert cli.main(["verify", "--design", str(EXAMPLE), "--model", "closed-form", "--quiet",
                     "--set", f"requirements.min_first_resonance_Hz={2 * low['first_Hz']:.1f}"]) == 1
    assert "| min_first_resonance_Hz |" in capsys.readouterr().out


def test_check_fails_on_a_resonance_below_the_minimum():
    from tactcad.checks.requirement_checks import requirement_checks

    plan = example(**{"requirements.min_first_resonance_Hz": 5000.0})
    bad = [r for r in requirement_checks(plan, "closed-form") if not r.passed]
    assert [r.subject for r in bad] == ["min_first_resonance_Hz"]
    assert "closed-form, in-plane modes" in bad[0].detail


@pytest.mark.slow  # a whole chain through the command line or an export
def test_auto_climbs_the_ladder_when_the_closed_form_cannot_decide():
    from tactcad.studies.strength_studies import element_stress

    low = first_frequencies(example(), "closed-form")[0]["first_Hz"]
    plan = example(**{"requirements.min_first_resonance_Hz": low})  # margin 0: undecided
    records, spent = verification_auto(plan, stress=element_stress,
                                       levels=("closed-form", "beam", "fem2d"))
    rec = next(r for r in records if r["requirement"] == "min_first_resonance_Hz")
    assert "fem2d" in rec["levels_tried"]
    assert rec["modal_model"] in ("fem2d", "closed-form")
    assert [s["model"] for s in spent][-1] == "fem2d"


@pytest.mark.parametrize("value", [0, -5, "fast"])
def test_a_bad_minimum_is_refused_naming_the_field(value):
    with pytest.raises(DesignErrors) as err:
        example(**{"requirements.min_first_resonance_Hz": value})
    assert err.value.field == "requirements.min_first_resonance_Hz"


@pytest.mark.slow
def test_a_thin_sheet_is_verified_at_fem3d_whatever_the_level():
    """A 0.6 mm sheet over a 0.25 mm web (under three webs): the closed form
    cannot see the out-of-plane modes, so the element is taken at fem3d; the
    manifest's summary keeps the closed form and flags it instead."""
    from tactcad.design.array_plan import default_design_data
    from tactcad.studies.resonance import out_of_plane_may_lead, resonance_summary

    plan = plan_from_dict(with_overrides(default_design_data(), {
        "sheet.thickness_mm": 0.6, "readout.grid_width_mm": 0.6, "arms.lengths_mm": [4.0] * 10,
        "requirements.min_first_resonance_Hz": 100.0}))
    (g,) = plan.distinct_elements.values()
    assert out_of_plane_may_lead(g)
    (rec,) = resonance_records(plan, "closed-form")
    assert rec["modal_model"] == "closed-form" and rec["binding_model"] == "fem3d"
    assert rec["families"] == ["in-plane", "out-of-plane"]
    (row,) = resonance_summary(plan)["elements"]
    assert row["model"] == "closed-form" and row["out_of_plane_unchecked"]
    assert not out_of_plane_may_lead(example().element(1).geometry)
