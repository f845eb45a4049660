"""Design file -> plan: the paper's values carried over, bad input refused clearly."""

from __future__ import annotations

import csv
import math
import subprocess
import sys
from pathlib import Path

import pytest

import tactcad

from conftest import run_cli
from tactcad.design.array_plan import load_design, plan_from_dict, with_overrides
from tactcad.errors import DesignError


def test_default_plan_carries_the_paper(plan):
    assert (plan.rows, plan.columns, plan.pitch_mm) == (2, 5, 4.0)
    assert plan.sheet_thickness_mm == 3.0
    assert plan.material.youngs_modulus_MPa == 69000.0 and plan.material.poisson_ratio == 0.33
    assert all(s.geometry.web_thickness_mm == 0.25 for s in plan.slots)
    assert plan.element(1).geometry.contact_face_mm == (2.0, 3.0)
    # Every element's arm length is Table 1's flexing arm length.
    rows = csv.DictReader(open(Path(tactcad.__file__).parent / "data" / "table1_calibration.csv"))
    for row in rows:
        arm = float(row["flexing_arm_length_mm"])
        assert plan.element(int(row["element"])).geometry.arm_length_mm == arm


def test_every_assumption_names_a_real_field_and_says_why(plan):
    keys = {k for k, _ in plan.assumptions}
    for required in ("element.notch_radius_mm", "element.base_height_mm", "arms.lengths_mm[5]",
                     "clamp.bolt_size"):
        assert required in keys
    assert all(len(reason) > 20 for _, reason in plan.assumptions)


def test_tips_on_the_pitch_grid_and_in_one_plane(plan):
    tips = [s.tip_centre_world_mm for s in plan.slots]
    assert len({round(t[1], 9) for t in tips}) == 1
    xs = sorted({round(t[0], 9) for t in tips})
    zs = sorted({round(t[2], 9) for t in tips})
    assert xs[1] - xs[0] == pytest.approx(plan.pitch_mm)
    assert all(b - a == pytest.approx(plan.pitch_mm) for a, b in zip(zs, zs[1:]))


def test_plan_is_immutable(plan):
    with pytest.raises(AttributeError):
        plan.pitch_mm = 5.0  # type: ignore[misc]


@pytest.mark.parametrize("overrides, field, text", [
    ({"element.web_thickness_mm": -0.25}, "element.web_thickness_mm", "0.05"),
    ({"element.web_thickness_mm": 0.0}, "element.web_thickness_mm", "1 mm"),
    ({"element.web_thickness_mm": 1.5}, "element.web_thickness_mm", "1 mm"),
    ({"element.web_thickness_mm": "thin"}, "element.web_thickness_mm", "finite number"),
    ({"element.notch_radius_mm": 0.2}, "element.notch_radius_mm", "0.25"),  # t/R > 1
    ({"element.arm_height_mm": 0.6}, "element.arm_height_mm", "0.75"),  # web + notch > arm
    ({"array.pitch_mm": 3.0}, "array.pitch_mm", "sheet.thickness_mm"),
    ({"array.pitch_mm": 2.0}, "array.pitch_mm", "3"),
    ({"sheet.thickness_mm": -3.0}, "sheet.thickness_mm", "0.025"),  # the thinnest foil
    ({"sheet.thickness_mm": 0.3}, "sheet.thickness_mm", "0.5"),  # wire EDM's sheet
    ({"array.rows": 3}, "array.rows", "2"),
    ({"array.columns": 0}, "array.columns", "1 ... 12"),
    ({"element.inside_corner_radius_mm": 0.1}, "element.inside_corner_radius_mm", "0.15"),
    ({"clamp.bolt_size": "M7"}, "clamp.bolt_size", "M2"),
    ({"material.poisson_ratio": 0.5}, "material.poisson_ratio", "0.5"),
    ({"arms.lengths_mm": [4.0] * 9}, "arms.lengths_mm", "10 lengths"),
    ({"arms.lengths_mm": [4.0] * 9 + [21.0]}, "arms.lengths_mm[10]", "20"),
    ({"edm.start_hole_diameter_mm": 2.5}, "edm.start_hole_diameter_mm", "2.4"),
])
def test_bad_values_are_refused_naming_field_value_and_range(design_data, overrides, field, text):
    with pytest.raises(DesignError) as info:
        plan_from_dict(with_overrides(design_data, overrides))
    err = info.value
    assert err.field == field
    assert text in str(err)
    assert repr(err.value) in str(err) or str(err.value) in str(err)


def test_arm_shorter_than_the_tip_is_refused(design_data):
    data = with_overrides(design_data, {"array.pitch_mm": 10.0, "element.tip_width_mm": 5.0})
    with pytest.raises(DesignError, match="arm shorter than the tip") as info:
        plan_from_dict(data)
    assert info.value.field == "arms.lengths_mm[1]"


def test_base_too_short_for_the_bolt_pattern_names_the_arm(design_data):
    data = with_overrides(design_data, {"element.overall_length_mm": 16.0})
    with pytest.raises(DesignError, match="bolt pattern") as info:
        plan_from_dict(data)
    assert info.value.field.startswith("arms.lengths_mm[")


def test_missing_and_unknown_keys(design_data):
    del design_data["element"]["notch_radius_mm"]
    with pytest.raises(DesignError, match="missing") as info:
        plan_from_dict(design_data)
    assert info.value.field == "element.notch_radius_mm"
    assert str(info.value).endswith(
        "element.notch_radius_mm (not given): allowed 0 < value <= 2 mm (missing)")
    del design_data["element"]
    with pytest.raises(DesignError) as info:
        plan_from_dict(design_data)
    assert info.value.field == "element" and info.value.allowed == "a [element] table"
    data = with_overrides(load_design().raw, {"element.web_thickness": 0.25})
    with pytest.raises(DesignError, match="unknown key"):
        plan_from_dict(data)
    data = dict(load_design().raw, extras={"a": 1})
    with pytest.raises(DesignError, match="unknown section"):
        plan_from_dict(data)


def test_assumption_must_name_a_field(design_data):
    design_data["assumptions"]["element.colour"] = "looks nice"
    with pytest.raises(DesignError, match="assumptions.element.colour"):
        plan_from_dict(design_data)


def test_derived_dimensions_have_reasons(plan):
    names = {d.name for d in plan.derived}
    assert {"clamp_leg_length", "bolt_length", "spacer_thickness"} <= names
    spacer = next(d for d in plan.derived if d.name == "spacer_thickness")
    assert spacer.value == pytest.approx(plan.pitch_mm - plan.sheet_thickness_mm)
    bolt = next(d for d in plan.derived if d.name == "bolt_length")
    grip = plan.stack_length_mm + 2 * plan.clamp.thickness_mm
    assert bolt.value >= grip + plan.bolt.nut_height_mm
    assert all(d.reason for d in plan.derived)


def test_cli_refuses_bad_design_with_exit_2_and_writes_nothing(tmp_path, design_data):
    bad = tmp_path / "bad.toml"
    text = (load_design().source and open(load_design().source).read())
    bad.write_text(text.replace("web_thickness_mm = 0.25", "web_thickness_mm = 1.55"))
    out = tmp_path / "out"
    proc = run_cli("export", "--design", str(bad), "--out", str(out))
    assert proc.returncode == 2
    assert "element.web_thickness_mm = 1.55" in proc.stderr
    assert "0.05 <= value <= 1 mm" in proc.stderr
    assert "Traceback" not in proc.stderr
    assert not out.exists()


def test_cli_reports_unreadable_and_invalid_toml(tmp_path):
    proc = run_cli("export", "--design", str(tmp_path / "nope.toml"), "--out", str(tmp_path / "o"))
    assert proc.returncode == 2 and "design file" in proc.stderr
    broken = tmp_path / "broken.toml"
    broken.write_text("[element\nweb = ")
    proc = run_cli("check", "--design", str(broken))
    assert proc.returncode == 2 and "valid TOML" in proc.stderr


def test_help_does_not_import_the_cad_kernel():
    code = ("import sys; from tactcad.cli import build_parser; build_parser().format_help(); "
            "print(any(m.split('.')[0] in ('build123d', 'cadquery', 'OCP') for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_hinge_estimate_in_table1_range(plan):
    """The assumption's first-order hand estimate lands inside Table 1's 5-80 N/mm."""
    g = plan.element(1).geometry
    E, b, t, R = plan.material.youngs_modulus_MPa, g.sheet_thickness_mm, g.web_thickness_mm, g.notch_radius_mm
    k_theta = 2 * E * b * t**2.5 / (9 * math.pi * math.sqrt(2 * R))
    for a in (4.0, 8.0):
        assert 5.0 < k_theta / a**2 < 80.0
