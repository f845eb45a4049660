"""The review page's verification section shows the first natural
frequencies, and a stated minimum as a row naming the lowest element."""

from __future__ import annotations

from pathlib import Path

from tactcad.design.array_plan import plan_from_dict, read_toml, with_overrides
from tactcad.export.review_page import verification_view
from tactcad.studies.verification import requirements_record

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def test_first_frequencies_and_a_stated_minimum_show_on_the_page():
    raw = read_toml(EXAMPLE, "design")
    plan = plan_from_dict(raw, str(EXAMPLE))
    view = verification_view(requirements_record(plan))
    (key,) = [k for k in view if k.startswith("first natural frequencies")]
    lowest = view[key][0]
    assert lowest["first_Hz"] > 0 and lowest["elements"][0] == 1
    strict = plan_from_dict(with_overrides(raw, {"requirements.min_first_resonance_Hz": 1000.0}),
                            str(EXAMPLE))
    view = verification_view(requirements_record(strict))
    row = next(r for r in view[next(iter(view))] if r["requirement"] == "min_first_resonance_Hz")
    assert row["verdict"] == "FAIL" and row["binds"].startswith(f"element 1 ({lowest['part']}, closed-form")
    assert "min_first_resonance_Hz" in view["requirements not met"]


def test_the_thermal_figures_show_on_the_page_with_the_span_and_the_kobj_force_range():
    from tactcad.export.review_page import THERMAL_VIEW_KEY
    from tactcad.mechanics.thermal_drift import thermal_report
    from tactcad.studies.verification import requirements_of

    data = read_toml(EXAMPLE, "design")
    data["material"] = {"name": "7075-T6", "grade": "7075-T6"}  # 6061's figure stands in
    plan = plan_from_dict(data, str(EXAMPLE))
    rep = thermal_report(plan, requirements_of(plan)).as_json()
    view = verification_view(requirements_record(plan), rep)[THERMAL_VIEW_KEY]
    assert "1/F" in THERMAL_VIEW_KEY
    assert float(view["span per kelvin (ppm/K)"]["total"]) == \
        float(f"{1e6 * rep['span_rel_per_K']:.4g}")
    assert view["modulus coefficient sourced"] is False  # 7075's is a stand-in
    assert [r["element"] for r in view["elements"]] == [r["element"] for r in rep["elements"]]
    assert view["worst K_obj error"].startswith(f"element {rep['worst_kobj_element']}:")
    assert "at 10 % of full scale" in view["worst K_obj error"]
