"""A silicon die's grasp is judged along its stops' load path: the post's whole force over
its footprint and the cavity floor under the beam's end, not only the beams. A lab's 7 mm
jaw took ``--max-grasp-force 21`` (the jaw's reach, which design itself pasted) without a
word, and verify could never decide it (predicted "none", the stops' strength "not
judged"). A die file that states no ``kobj_resolution_rel`` had it judged against a 0.01
nobody stated; and diff listed the die's stated grasp force as derived."""

from __future__ import annotations

import json
import math

import pytest

from conftest import run_cli

#: The lab's 7 mm jaw the review designed its die for (its [grasper_jaw] table, mm, degrees).
JAW7 = """[grasper_jaw]
shaft_diameter_mm = 7.0
width_mm = 4.5
length_mm = 26.0
thickness_mm = 2.6
opposing_jaw_mm = 2.6
pin_diameter_mm = 1.5
pin_inset_mm = 1.6
opening_angle_deg = 40.0
"""
DESIGN7 = ("design", "--jaw", "jaw7.toml", "--kr-over-km", "8", "--kobj-range", "0.2", "4",
           "--construction", "mems-die", "--full-scale-force", "0.0103")


def _grasp(stdout: str) -> dict:
    return next(r for r in json.loads(stdout)["matrix"]
                if r["requirement"] == "max_grasp_force_N")


def test_the_stops_load_path_bounds_a_dies_grasp_and_its_paste_verifies(tmp_path):
    (tmp_path / "jaw7.toml").write_text(JAW7, encoding="utf-8")
    refused = run_cli(*DESIGN7, "--max-grasp-force", "21", "--out", "g4", "--json",
                      cwd=tmp_path)
    assert refused.returncode == 2 and not (tmp_path / "g4").exists(), refused.stdout
    error = json.loads(refused.stdout)["error"]
    assert error["field"] == "--max-grasp-force" and "post" in error["message"]
    paste = float(error["alternatives"][0]["option"].split()[-1])
    assert 0 < paste < 21
    made = run_cli(*DESIGN7, "--max-grasp-force", f"{paste:g}", "--out", "g5", cwd=tmp_path)
    assert made.returncode == 0, made.stdout + made.stderr
    assert f"grasp {paste:g} N: PASS" in made.stdout  # design says how the grasp is judged
    r = run_cli("verify", "--json", cwd=tmp_path / "g5")
    assert r.returncode == 0, r.stdout
    row = _grasp(r.stdout)
    assert row["verdict"] == "pass" and row["predicted"] > paste, row
    assert row["margin_rel"] == pytest.approx(row["predicted"] / paste - 1, rel=1e-9)
    assert {it["item"].split(":")[0].split()[0] for it in row["items"]} >= {"beam", "post"}
    assert any(it["item"].startswith("the cavity floors") for it in row["items"])
    assert "not judged" not in row["binding_words"]
    # the jaw's reach itself is past what the posts take: judged, failed, with a figure
    far = run_cli("verify", "--set", "die.max_grasp_force_N=21", "--json", cwd=tmp_path / "g5")
    row = _grasp(far.stdout)
    assert far.returncode == 1 and row["verdict"] == "fail" and row["predicted"] < 21
    assert row["binding_item"].startswith("post")


def test_the_stops_load_path_in_closed_form():
    from tactcad.products.silicon_die.design.mems_die import DESIGN_STRENGTH
    from tactcad.products.silicon_die.mechanics.die_strength import (
        bearing_area_um2, floor_edge_tension_MPa, floor_effective_area_um2,
        floors_force_scale, post_stress_MPa)

    assert post_stress_MPa(0.6, 100.0) == pytest.approx(60.0)  # N over 1e-2 mm^2
    assert bearing_area_um2(100.0, 262.5) == 1e4 and bearing_area_um2(100.0, 50.0) == 5e3
    assert floor_edge_tension_MPa(1.0, 1e4) == pytest.approx(50.0)  # half of 100 MPa
    assert floor_effective_area_um2(1e4, 5.0) == pytest.approx(2.5e3)
    # one stop on the design pair: the tension at which the ring reaches P = 1e-3
    scale = floors_force_scale([1.0], 1e4, DESIGN_STRENGTH)
    ring = 2.5e3 / DESIGN_STRENGTH.reference_area_um2
    sigma = DESIGN_STRENGTH.characteristic_MPa * (-math.log1p(-1e-3) / ring) ** 0.2
    assert scale * 50.0 == pytest.approx(sigma, rel=1e-12)
    assert floors_force_scale([0.0], 1e4, DESIGN_STRENGTH) == math.inf
    with pytest.raises(ValueError, match="post_um"):
        post_stress_MPa(1.0, 0.0)


def test_an_unstated_kobj_resolution_is_reported_not_judged():
    from tactcad.mechanics.verdicts import INFO
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.products.silicon_die.studies.die_doping import doped_die_plan
    from tactcad.products.silicon_die.studies.die_verification import die_verification
    from tactcad.studies.inverse_design import Targets

    targets, room = Targets(10.0, (0.5, 5.0), 0.006), jaw_room("5")

    def row(plan):
        return next(r for r in die_verification(plan) if r["requirement"] == "kobj_resolution_rel")

    unstated = row(doped_die_plan(targets, room))
    assert unstated["verdict"] == INFO and unstated["target"] is None
    assert unstated["margin_rel"] is None and unstated["pass"] is None
    assert unstated["reference_value"] == 0.01 and unstated["predicted"] > 0
    stated = row(doped_die_plan(targets, room, kobj_resolution_rel=0.01))
    assert stated["verdict"] == "pass" and stated["target"] == 0.01


def test_diff_lists_a_dies_stated_values_as_stated(tmp_path):
    from tactcad.export.manifest_diff import PRODUCT_STATED_KEYS, compare
    from tactcad.products.silicon_die.design.die_file import DieSection

    # every key listed as stated is one the die's file states
    assert set(PRODUCT_STATED_KEYS["die"]) <= set(DieSection.__annotations__)
    for name, grasp in (("old", None), ("new", 21.0)):
        (tmp_path / name).mkdir()
        die = {"full_scale_force_N": 0.0103, "cavity_depths_um": {"reference": 6.5},
               **({} if grasp is None else {"max_grasp_force_N": grasp})}
        (tmp_path / name / "manifest.json").write_text(json.dumps(
            {"files": [], "die": die}), encoding="utf-8")
    d = compare(tmp_path / "old", tmp_path / "new")
    assert d.derived == [] and d.changed
    assert d.stated == [{"name": "die.max_grasp_force_N", "before": None, "after": 21.0,
                         "unit": "N"}]
    assert "stated        die.max_grasp_force_N: - -> 21 N" in d.lines()
    assert not any(line.startswith("derived") for line in d.lines())
    assert d.as_json()["stated"] == d.stated
