"""Rig file validation and the rig parts: solids against independent estimates,
bought parts with catalogue data, the samples' stiffness attributes."""

from __future__ import annotations

import copy
import json
import math
import re

import pytest

from tactcad.errors import DesignError
from tactcad.catalogue.rig_catalogue import RigPartSpec, rig_parts
from tactcad.design.array_plan import EXAMPLES
from tactcad.design.rig_plan import default_rigs_data, load_rigs, rigs_from_dict
from tactcad.partlib.sample import sample_name
from tactcad.vocabulary.standards import BEARINGS

PAPER_STIFFNESS = (10.01, 7.26, 6.28, 5.41, 4.51, 3.85, 3.57, 2.34)


@pytest.fixture(scope="module")
def rigs(plan):
    return load_rigs(array_plan=plan)


@pytest.fixture(scope="module")
def specs(plan, rigs):
    return rig_parts(plan, rigs)


def _with(data, dotted, value):
    out = copy.deepcopy(data)
    section, key = dotted.split(".")
    if value is None:
        del out[section][key]
    else:
        out.setdefault(section, {})[key] = value
    return out


@pytest.mark.parametrize("dotted, value, words", [
    ("cart.bearing", "608ZZ", ["cart.bearing", "608ZZ", "624ZZ"]),
    ("base_plate.groove_width_mm", 5.0, ["base_plate.groove_width_mm", "5.0", "624ZZ"]),
    ("base_plate.groove_depth_mm", 3.4, ["base_plate.groove_depth_mm", "<= 3 mm"]),
    ("weights.count", -1, ["weights.count", "0 ... 20"]),
    ("calibration.element", 11, ["calibration.element", "1 ... 10"]),
    ("sample.stiffness_N_per_mm", [3.0, 3.0], ["sample.stiffness_N_per_mm", "distinct"]),
    ("sample.stiffness_N_per_mm", [1.0, 1.0000001], ["sample.stiffness_N_per_mm", "distinct",
                                                    "sample_k<value>"]),
    ("bracket.width_mm", 30.0, ["bracket.width_mm", "clamp bolts"]),
    ("cart.thickness_mm", None, ["cart.thickness_mm", "missing"]),
    ("cart.colour", "red", ["cart.colour", "unknown key"]),
])
def test_bad_rig_values_name_field_value_and_range(plan, dotted, value, words):
    data = _with(default_rigs_data(), dotted, value)
    with pytest.raises(DesignError) as info:
        rigs_from_dict(data, plan)
    text = str(info.value)
    for w in words:
        assert w in text, text


def test_assumption_keys_must_name_rig_fields(plan):
    data = default_rigs_data()
    data["assumptions"]["cart.wheels"] = "four"
    with pytest.raises(DesignError, match="assumptions.cart.wheels"):
        rigs_from_dict(data, plan)


def test_every_unstated_value_has_a_reason(rigs):
    reasons = dict(rigs.assumptions)
    data = default_rigs_data()
    for section, table in data.items():
        if section in ("rigs", "assumptions"):
            continue
        for key in table:
            assert f"{section}.{key}" in reasons, f"{section}.{key} has no reason in [assumptions]"


def test_derived_rig_values(rigs, plan):
    cart = rigs.part("cart")
    assert cart.axle_bolt.size == "M4" and cart.axle_bolt_length_mm == 12
    assert rigs.part("base_plate").track_half_mm == pytest.approx(60 / 2 + 1.0 + 5 / 2)
    assert rigs.part("weights").height_mm * math.pi * 12.5 ** 2 == pytest.approx(100 / 7.85 * 1000)
    # the bracket bolts pass the clamp plate's two bridge holes
    assert rigs.part("bracket").hole_xs_mm == tuple(h.x_mm for h in plan.clamp.holes[-2:])
    grip = rigs.part("bracket").ear_thickness_mm + 2 * plan.clamp.thickness_mm + plan.stack_length_mm
    assert rigs.part("bracket").bolt_length_mm >= grip + plan.bolt.nut_height_mm


def test_bought_parts_carry_catalogue_data(specs):
    bought = {n: s for n, s in specs.items() if s.kind == "purchased"}
    assert {"bearing_624ZZ", "force_gauge", "z_stage_body", "xy_stage_base", "rail_MGNR12R",
            "block_MGN12H", "weight_100g", "bolt_M4x12", "bolt_M3x10"} <= set(bought)
    assert "ISO 15" in bought["bearing_624ZZ"].process and "d 4 x D 13 x B 5" in bought["bearing_624ZZ"].process
    assert "Sauter FH 5" in bought["force_gauge"].process
    assert bought["force_gauge"].attributes["stiffness_N_per_mm"] == 57.04
    assert "HIWIN MGN12H" in bought["block_MGN12H"].process
    w = bought["weight_100g"]
    assert w.expected_volume_mm3 == pytest.approx(100 / 7.85 * 1000, rel=1e-12)
    assert BEARINGS["623ZZ"].outer_diameter_mm == 10 and BEARINGS["624ZZ"].width_mm == 5


def test_samples_carry_the_papers_stiffnesses(specs):
    samples = {n: s for n, s in specs.items() if n.startswith("sample_k")}
    assert sorted(s.attributes["stiffness_N_per_mm"] for s in samples.values()) == sorted(PAPER_STIFFNESS)
    assert sample_name(3.85) == "sample_k3p85" and "sample_k3p85" in samples
    assert len({s.color for s in samples.values()}) == len(samples)


def test_every_rig_part_is_a_valid_solid_of_the_expected_size(plan, specs):
    from tactcad.checks.solids import check_solid
    from tactcad.solids.build import build_part

    failed = []
    for name, spec in specs.items():
        assert isinstance(spec, RigPartSpec)
        solid = build_part(spec)
        failed += [r.line() for r in check_solid(spec, solid) if not r.passed]
    assert not failed, "\n".join(failed)


def test_cart_has_its_vacuum_clamping_features(plan, specs):
    """Removing the pocket, port, channel or suction holes changes the volume
    the formula expects: each feature is really cut."""
    from tactcad.kernel.inspect import common_volume
    from tactcad.solids.build import build_part

    spec = specs["cart"]
    g = spec.geometry
    solid = build_part(spec)
    block = g.length_mm * g.width_mm * g.thickness_mm
    assert block - solid.volume > 0.9 * (g.pocket_length_mm * g.pocket_width_mm * g.pocket_depth_mm)
    # a ray along the channel axis from the port face meets no material up to the channel end
    import build123d as bd
    probe = bd.Solid.make_cylinder(0.2, g.channel_end_x_mm + g.length_mm / 2 - 0.5,
                                   bd.Plane(origin=(-g.length_mm / 2, 0, g.thickness_mm / 2),
                                            z_dir=(1, 0, 0)))
    assert common_volume(solid, probe) == pytest.approx(0.0, abs=1e-9)
    # and a suction hole opens from the pocket floor into the channel
    hole = bd.Solid.make_cylinder(0.2, g.thickness_mm / 2 - g.pocket_depth_mm,
                                  bd.Plane(origin=(g.suction_hole_xs_mm[0], 0, g.thickness_mm / 2)))
    assert common_volume(solid, hole) == pytest.approx(0.0, abs=1e-9)
    # while the same probe beside the channel runs through material
    beside = probe.moved(bd.Location((0, 0, g.channel_diameter_mm)))
    assert common_volume(solid, beside) > 1.0


@pytest.mark.parametrize("tip_width_mm", [1.5, 2.0])
def test_the_indenter_drawing_note_gives_the_designs_own_face(tip_width_mm):
    """The note names the indenter's face, the element's contact face (tip
    width x sheet thickness), not the paper's 2 x 3 mm."""
    import tactcad
    from tactcad.drawings.part_sets import PEN
    from tactcad.partlib.indenter import notes_after

    design = EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml"
    project = tactcad.load(design, set={"element.tip_width_mm": tip_width_mm,
                                        "sheet.thickness_mm": 2.5})
    g = rig_parts(project.plan, project.validated.rigs)["indenter"].geometry
    note = " ".join(notes_after(g, PEN))
    assert f"the {tip_width_mm:g} x 2.5 mm face lies flat" in note and "2 x 3 mm" not in note


@pytest.mark.parametrize("ear", ["2.5", "6"])
def test_a_clamp_bolt_too_short_offers_what_also_clamps_the_rigs_own_ear(tmp_path, ear):
    """The array's own clamp bolt too short for 10 mm plates: the plates offered are tried
    with the bracket ear of the project's own rigs file (not the default rigs' 2.5 mm), so
    that pasting them loads the project, rigs and all."""
    import shlex
    import shutil

    from conftest import run_cli
    from tactcad.design.array_plan import EXAMPLES

    folder = tmp_path / "ti"
    shutil.copytree(EXAMPLES / "ti_array_2x3", folder)
    rigs = folder / "rigs.toml"
    rigs.write_text(re.sub(r"(?m)^ear_thickness_mm = .*$", f"ear_thickness_mm = {ear}",
                           rigs.read_text(encoding="utf-8")), encoding="utf-8")
    r = run_cli("scenes", "--set", "clamp.plate_thickness_mm=10", "--json", cwd=folder)
    assert r.returncode == 2, r.stdout
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "array.columns" and "bolt needs" in error["message"], error
    plates = [a["option"] for a in error["alternatives"] if "plate_thickness" in a["option"]]
    assert plates == [{"2.5": "--set clamp.plate_thickness_mm=7",
                       "6": "--set clamp.plate_thickness_mm=5.3"}[ear]], error["alternatives"]
    pasted = run_cli("scenes", *shlex.split(plates[0]), cwd=folder)
    assert pasted.returncode == 0, pasted.stderr


@pytest.mark.parametrize("columns, arms, fewer", [
    (3, None, False),  # 2 columns with 6 mm plates still need too long a bolt
    (2, "[19.605, 6.196, 19.605, 6.196]", False),  # a stacked array's fewest columns
])
def test_the_bracket_bolt_refusal_offers_fewer_columns_only_above_the_fewest(
        tmp_path, columns, arms, fewer):
    """A bracket ear too thick for any stock bolt is refused on the design's columns; it
    offers fewer columns only where the stacked array may have fewer (2 pair one reference
    with one measuring element) and they mend it."""
    import shutil

    from conftest import run_cli
    from tactcad.design.array_plan import EXAMPLES

    folder = tmp_path / "ti"
    shutil.copytree(EXAMPLES / "ti_array_2x3", folder)
    rigs = folder / "rigs.toml"
    rigs.write_text(re.sub(r"(?m)^ear_thickness_mm = .*$", "ear_thickness_mm = 12",
                           rigs.read_text(encoding="utf-8")), encoding="utf-8")
    sets = ["--set", "clamp.plate_thickness_mm=6"] + (
        ["--set", f"array.columns={columns}", "--set", f"arms.lengths_mm={arms}"] if arms else [])
    r = run_cli("verify", *sets, cwd=folder)
    assert r.returncode == 2 and "the bracket bolt through ear 12 mm" in r.stderr, r.stderr
    assert f"array.columns = {columns}" in r.stderr
    assert ("fewer columns" in r.stderr) is fewer
