"""FreeCAD review files: each ``review/<scene>.FCStd`` opened with
``freecadcmd`` shows the scene's group tree, every instance by name, one
colour per part (a distinct one per element variant) and stands Z up."""

from __future__ import annotations

import itertools
import json

import pytest

from tactcad.checks.freecad_fcstd import check_review_files, part_colours
from tactcad.export import freecad_review
from tactcad.assembly.z_up import z_up_bbox, z_up_location, z_up_point
from tactcad.export.glb import read_glb


@pytest.fixture(scope="module")
def review(freecad, exported):
    out, _ = exported
    rows, found = check_review_files(out)
    return out, rows, {k.rsplit("/review/", 1)[1]: v for k, v in found["files"].items()}


@pytest.mark.slow
def test_every_review_file_matches_its_records(review, plan):
    out, rows, found = review
    man = json.loads((out / "manifest.json").read_text())
    scenes = [f["part"] for f in man["files"] if f["kind"] == "step-scene"]
    assert sorted(found) == sorted(f"{s}.FCStd" for s in scenes)
    bad = [r.line() for r in rows if not r.passed]
    assert not bad, "\n".join(bad)
    assert {r.check for r in rows} == {"fcstd_tree", "fcstd_solids", "fcstd_z_up_bbox",
                                       "fcstd_parts", "fcstd_colours"}


@pytest.mark.slow
def test_array_tree_names_every_instance(review, plan):
    _, _, found = review
    array = found["array.FCStd"]
    assert array["roots"] == ["array", "parts"]
    assert list(array["tree"]) == ["array"]
    names = array["tree"]["array"]
    assert names[:10] == [f"element_{n}" for n in range(1, 11)]
    assert {"clamp_plate_front", "clamp_plate_back", "spacer_1", "bolt_1", "nut_1"} <= set(names)
    for slot in plan.slots:
        assert array["linked"][f"element_{slot.number}"] == slot.geometry.part_name


@pytest.mark.slow
def test_rigs_are_z_up_with_their_sub_assemblies(review):
    _, _, found = review
    rig = found["array-evaluation-rig.FCStd"]
    assert {"array", "cart", "sample", "base_plate", "column"} <= set(rig["tree"])
    box = rig["group_bbox_mm"]
    zmin, zmax = 2, 5
    # the array's tips rest on the sample, which lies on the cart on the base plate
    assert box["array"][zmin] == pytest.approx(box["sample"][zmax], abs=1e-6)
    assert box["sample"][zmin] > box["cart"][zmin] > box["base_plate"][zmin]
    assert box["array"][zmin] > box["cart"][zmax]
    assert rig["bbox_mm"][zmin] == pytest.approx(0.0, abs=1e-9)  # base plate on the floor
    calib = found["calibration-rig.FCStd"]["group_bbox_mm"]
    assert calib["force_gauge"][zmin] > calib["array"][zmin] > calib["xy_stage"][zmin]


@pytest.mark.slow
def test_element_variants_have_distinct_colours_in_fcstd_and_glb(review, plan):
    out, _, _ = review
    fc = part_colours(out / "review/array.FCStd")
    glb = {m["name"]: m["pbrMetallicRoughness"]["baseColorFactor"][:3]
           for m in read_glb(out / "scenes/array.glb")["materials"]}
    variants = list(plan.distinct_elements)
    for a, b in itertools.combinations(variants, 2):
        assert max(abs(x - y) for x, y in zip(fc[a], fc[b])) > 0.2, (a, b)
    for v in variants:
        assert fc[v] == pytest.approx(glb[v], abs=1 / 255)


def test_glb_stays_y_up(exported):
    out, _ = exported
    root = read_glb(out / "scenes/array-evaluation-rig.glb")["nodes"][0]
    assert set(root) == {"name", "scale", "children", "extras"}  # no turn: glTF is y up


def test_z_up_turns_scene_y_into_z():
    import build123d as bd

    p = (1.0, 2.0, 3.0)
    q = (z_up_location() * bd.Location(p)).position
    assert (q.X, q.Y, q.Z) == pytest.approx(z_up_point(p))
    assert z_up_bbox([0, 1, 2, 10, 11, 12]) == [0, -12, 1, 10, -2, 11]


def test_review_files_are_skipped_with_a_note_without_freecad(tmp_path, monkeypatch):
    monkeypatch.setattr(freecad_review, "freecadcmd", lambda: None)
    notes = []
    a = freecad_review.ReviewAssembly("array", "scenes/array.step", (), ())
    assert freecad_review.write_review_files(tmp_path, [a], notes.append) == []
    assert "freecadcmd not found" in notes[0]
    assert not (tmp_path / "review").exists()
