"""Scenes: listing, building only what a scene shows, placement by joints,
interference (mesh fast path + exact confirmation), geometry sanity, exports."""

from __future__ import annotations

import dataclasses
import json
import re
import shutil
from collections import Counter

import pytest

from conftest import warm_store_copy
from tactcad import cli
from tactcad.errors import DesignError, TactcadError
from tactcad.assembly.rig_models import describe, scene_names
from tactcad.assembly.scene_solver import assemble, build_scene
from tactcad.checks.scene_checks import placed_shapes
from tactcad.design.scene_specs import load_scenes
from tactcad.errors import SceneError
from tactcad.solids.cache import PartCache

SCENES = ["wirecut", "array", "calibration-rig", "sample-stiffness-rig", "array-evaluation-rig"]


@pytest.fixture(scope="module")
def cache(plan):
    return PartCache(plan)


@pytest.fixture(scope="module")
def built(project, cache):
    """Every scene built once: name -> (scene, solids)."""
    return {n: build_scene(project, n, cache) for n in SCENES}


def _counts_during(fn) -> Counter:
    from tactcad.solids.build import BUILD_COUNTS

    before = Counter(BUILD_COUNTS)
    fn()
    return Counter(BUILD_COUNTS) - before


def test_scene_list(project, capsys):
    assert scene_names(project) == SCENES
    assert cli.main(["scenes"]) == 0
    out = capsys.readouterr().out
    for n in SCENES:
        assert re.search(rf"^{n}\s+\[", out, re.M), n
    assert "bearing_624ZZ x4 (envelope)" in out and "cart x1 (full)" in out
    assert "sample_k3p85 x1" in out  # the evaluation rig's sample


def test_unknown_scene_lists_the_scenes_and_exits_2(capsys):
    assert cli.main(["scenes", "no-such-scene"]) == 2
    err = capsys.readouterr().err
    assert "unknown scene 'no-such-scene'" in err
    for n in SCENES:
        assert n in err
    assert issubclass(SceneError, TactcadError)
    assert cli.main(["export", "--scene", "nope", "--out", "/nonexistent/x"]) == 2


def test_an_unknown_check_scene_is_refused_before_any_check_runs(monkeypatch, capsys, tmp_path):
    """`check --scene nosuch` names --scene and the scenes before the requirements run."""
    import tactcad
    from tactcad.checks import groups

    ran = []
    monkeypatch.setattr(groups, "run_groups", lambda *a, **k: ran.append(a))
    assert cli.main(["check", "--scene", "nosuch", "--out", str(tmp_path / "exports")]) == 2
    err = capsys.readouterr().err
    assert "--scene = 'nosuch'" in err and "requirements:" not in err
    for n in SCENES:
        assert n in err
    assert ran == [] and not (tmp_path / "exports").exists()
    with pytest.raises(SceneError, match="nosuch"):  # the API's check too
        tactcad.load().check(None, ["wirecut", "nosuch"], cache=False)
    assert ran == []
    assert cli.main(["export", "--scene", "nope", "--out", str(tmp_path / "ex")]) == 2
    assert "--scene = 'nope'" in capsys.readouterr().err
    assert not (tmp_path / "ex").exists()


def test_a_scene_builds_only_its_parts(plan, project):
    """A fresh cache: `wirecut` never builds the cart, `array` never a bearing."""
    wirecut = _counts_during(lambda: build_scene(project, "wirecut", PartCache(plan)))
    assert wirecut and set(wirecut) == {*plan.distinct_elements, "spacer"}
    assert "cart" not in wirecut and "clamp_plate" not in wirecut
    array = _counts_during(lambda: build_scene(project, "array", PartCache(plan)))
    assert "bearing_624ZZ" not in array and "cart" not in array and "clamp_plate" in array
    assert all(v == 1 for v in array.values())  # once each
    rig = _counts_during(lambda: build_scene(project, "sample-stiffness-rig", PartCache(plan)))
    assert rig["bearing_624ZZ"] == 1 and "element_a4mm" not in rig  # 4 wheels, one build


def test_listing_and_placing_build_no_part(plan, project):
    counts = _counts_during(lambda: (describe(project), [assemble(project, n) for n in SCENES]))
    assert not counts


def test_joints_place_the_parts(built):
    """Placements follow from the joints: contact faces meet, loops close."""
    sc, _ = built["sample-stiffness-rig"]
    ind = sc.world_point("indenter", "contact")
    top = sc.world_point("sample", "top")
    assert (ind - top).length < 1e-9
    # the cart rolled (solved slide) to put the sample under the indenter
    assert "cart_roll" in sc.slide_positions
    ev, _ = built["array-evaluation-rig"]
    assert (ev.world_point("array", "tips") - ev.world_point("sample", "top")).length < 1e-9
    # the array hangs tips down over the sample, the weights stand on the carrier
    assert ev.world_point("array", "tip_1").Y == pytest.approx(ev.world_point("sample", "top").Y)
    w1, w3 = ev.world_point("weight_1", "bottom"), ev.world_point("weight_3", "top")
    assert w3.Y > w1.Y and abs(w3.X - w1.X) < 1e-9
    cal, _ = built["calibration-rig"]
    assert (cal.world_point("indenter", "contact") - cal.world_point("array", "tip_8")).length < 1e-9


def test_each_joined_instance_has_its_joint_axis(built):
    """Joint axes (the build book's explosion): a unit vector for every
    instance placed by a joint, none for the rig's root; the weights stacked on
    the carrier of the evaluation rig explode upwards, the way they are stacked."""
    import math

    for name, (sc, _) in built.items():
        axes = sc.joint_axes()
        in_roots = {m.name for r in sc.model.roots for m in sc.model.nodes[r].members} | set(
            sc.model.roots)
        assert set(axes) == {i.name for i in sc.instances} - in_roots, name
        assert all(math.isclose(math.hypot(*a), 1.0) for a in axes.values())
    ev, _ = built["array-evaluation-rig"]
    w1, w3 = ev.world_point("weight_1", "bottom"), ev.world_point("weight_3", "top")
    up = (w3 - w1).normalized()
    assert ev.joint_axes()["weight_3"] == pytest.approx((up.X, up.Y, up.Z), abs=1e-9)


def test_declared_contacts(built):
    sc, _ = built["sample-stiffness-rig"]
    for pair in [("indenter", "sample"), ("wheel_mm", "base_plate"), ("wheel_pp", "base_plate"),
                 ("cart", "sample"), ("wheel_bolt_pm", "cart"), ("indenter", "force_gauge")]:
        assert frozenset(pair) in sc.contacts, pair
    ev, _ = built["array-evaluation-rig"]
    assert all(frozenset({f"element_{n}", "sample"}) in ev.contacts for n in range(1, 11))
    assert frozenset({"array_bracket", "clamp_plate_front"}) in ev.contacts


@pytest.mark.slow
@pytest.mark.parametrize("name", SCENES)
def test_scene_has_no_interference_and_is_sane(built, name):
    from tactcad.checks.mesh_interference import check_mesh_interference
    from tactcad.checks.scene_sanity import check_scene_sanity

    sc, solids = built[name]
    placed = placed_shapes(sc, solids)
    rep = check_mesh_interference(placed, sc.contacts, {i.name: i.part for i in sc.instances},
                                  solids, {i.name: i.location for i in sc.instances})
    bad = [r.line() for r in rep.results if not r.passed]
    assert not bad, "\n".join(bad)
    assert rep.pairs_tested >= len(sc.contacts)
    sanity = check_scene_sanity(sc, {p.name: p.shape for p in placed})
    assert all(r.passed for r in sanity), "\n".join(r.line() for r in sanity)
    expected = {"array": {"tips_coplanar", "tips_on_pitch"},
                "calibration-rig": {"tips_coplanar", "tips_on_pitch", "indenter_centred",
                                    "indenter_covers_tip"},
                "sample-stiffness-rig": {"bearing_on_base", "indenter_centred"},
                "array-evaluation-rig": {"tips_coplanar", "tips_on_pitch", "tips_on_sample",
                                         "bearing_on_base"}}.get(name, set())
    assert expected <= {r.check for r in sanity}


def test_sanity_catches_a_tip_out_of_plane(built):
    """Move one element by 0.02 mm: the tip plane and the interference see it."""
    import build123d as bd

    from tactcad.checks.scene_sanity import check_scene_sanity

    sc, solids = built["array"]
    shapes = {p.name: p.shape for p in placed_shapes(sc, solids)}
    shapes["element_3"] = shapes["element_3"].moved(bd.Location((0, 0.02, 0)))
    rows = {r.check: r for r in check_scene_sanity(sc, shapes)}
    assert not rows["tips_coplanar"].passed


def _bad_design_dir(tmp_path, edit):
    """Copy of the hardware folder with rigs.toml edited by ``edit(text)``."""
    from tactcad.design.array_plan import DEFAULT_DESIGN

    hw = DEFAULT_DESIGN.parent
    for f in ("macro_array.toml", "scenes.toml"):
        shutil.copy(hw / f, tmp_path / f)
    (tmp_path / "rigs.toml").write_text(edit((hw / "rigs.toml").read_text()))
    return tmp_path / "macro_array.toml"


def fem3d_solves_missing(design, store) -> list[str]:
    """The fem3d solves (K and peak stress, per distinct element) of ``design`` that
    ``store`` (a folder) does not hold, each as "what: element"; none solved here."""
    from tactcad.design.project import load_project
    from tactcad.store import Store, keeping_results
    from tactcad.studies.parallel_solves import PEAK_STRESS, STIFFNESS, _kept

    plan = load_project(design).plan
    with keeping_results(Store(store)):
        return [f"{what}: {name}" for name, g in plan.distinct_elements.items()
                for what in (STIFFNESS, PEAK_STRESS) if not _kept("fem3d", g, plan.material, what)]


@pytest.mark.slow
def test_collision_fails_check_with_names_and_volume(tmp_path, capsys, verified_store):
    """A longer cart runs into the column: `tactcad check` names both parts
    and the overlap volume, the mesh fast path and OpenCascade agree.

    Only the rig changes, so the design's elements are the default's: the check reads their
    fem3d solves (its requirement group climbs to fem3d) from a copy of the verified store
    rather than solving them again for a claim about a scene."""
    design = _bad_design_dir(tmp_path, lambda t: t.replace("[cart]\nlength_mm = 80.0",
                                                           "[cart]\nlength_mm = 140.0"))
    store = warm_store_copy(verified_store, tmp_path / "store")
    # verify climbs only the elements its full-scale force leaves undecided: the store
    # holds those; the check, deciding the same, solves no fem3d beside them
    held_back = fem3d_solves_missing(design, store)
    code = cli.main(["check", "--design", str(design), "--scene", "sample-stiffness-rig",
                     "--failures-only", "--cache", str(store)])
    out = capsys.readouterr().out
    assert code == 1
    assert fem3d_solves_missing(design, store) == held_back
    m = re.search(r"FAIL\s+interference\s+sample-stiffness-rig: (column / cart|cart / column) "
                  r"overlap ([0-9.e+]+) mm3 \(mesh ([0-9.e+]+) mm3\)", out)
    assert m, out
    exact, mesh = float(m.group(2)), float(m.group(3))
    assert exact > 1000 and mesh == pytest.approx(exact, rel=0.05)


def test_slide_out_of_range_is_a_scene_error(tmp_path):
    """Stages too short for the array: refused up front naming the rig field; a
    rig plan built past the validator still fails at the slide, not silently."""

    from tactcad.design.project import load_project

    design = _bad_design_dir(tmp_path, lambda t: t.replace("table_height_mm = 8.0\n",
                                                           "table_height_mm = 8.0\ntravel_mm = 2.0\n"))
    with pytest.raises(DesignError) as info:
        load_project(design)
    assert info.value.field == "xy_stage.travel_mm" and "every element" in str(info.value)
    project = load_project()
    rigs = project.rigs
    stage = rigs.library["xy_stage"]
    stage = dataclasses.replace(stage, geometry=dataclasses.replace(stage.geometry, travel_mm=2.0))
    short = dataclasses.replace(rigs, library={**rigs.library, "xy_stage": stage})
    with pytest.raises(SceneError, match=r"slide stage_\w+ .* range is -1 \.\.\. 1 mm"):
        assemble(dataclasses.replace(project, rigs=short), "calibration-rig")


def test_bad_scenes_file(tmp_path, plan, project):
    text = (tmp_path / "s.toml")
    text.write_text('[scene.x]\nrig = "array"\ndescription = "d"\ngroups = ["array"]\n'
                    'detail = { purchased = "full" }\n')
    with pytest.raises(DesignError, match=r'scene.x.detail.purchased = .full.: allowed "envelope"'):
        load_scenes(text)
    text.write_text('[scene.x]\nrig = "trolley"\ndescription = "d"\ngroups = ["array"]\n')
    with pytest.raises(DesignError, match="scene.x.rig"):
        load_scenes(text)
    from tactcad.assembly.scene_solver import SceneSpec, scene_model

    spec = SceneSpec("x", "sample-stiffness", "d", ("cart", "trolley"), {"fabricated": "full",
                                                                         "purchased": "envelope"})
    with pytest.raises(SceneError, match="unknown group.*trolley.*has groups.*base_plate"):
        scene_model(plan, spec, project.rigs)


def test_manifest_records_every_scene(exported):
    out, _ = exported
    man = json.loads((out / "manifest.json").read_text())
    recs = {f["path"]: f for f in man["files"]}
    for n in SCENES:
        step, glb = recs[f"scenes/{n}.step"], recs[f"scenes/{n}.glb"]
        assert step["kind"] == "step-scene" and glb["kind"] == "glb-scene"
        assert step["solids"] == step["instances"] == glb["nodes"]
        assert len(step["bbox_mm"]) == 6 and step["volume_mm3"] > 0 and step["labels"]
    ev = recs["scenes/array-evaluation-rig.step"]
    assert ev["parts"]["sample_k3p85"]["stiffness_N_per_mm"] == 3.85
    assert ev["parts"]["weight_100g"]["quantity"] == 3
    assert ev["parts"]["bearing_624ZZ"]["level"] == "envelope"
    assert ev["parts"]["cart"]["level"] == "full"


def test_scene_step_is_flat_labelled_instanced(exported):
    out, _ = exported
    text = (out / "scenes/sample-stiffness-rig.step").read_text()
    assert "SI_UNIT(.MILLI.,.METRE.)" in text and "AUTOMOTIVE_DESIGN" in text
    assert text.count("NEXT_ASSEMBLY_USAGE_OCCURRENCE") == 24  # placed 24 times
    assert text.count("MANIFOLD_SOLID_BREP") == 14  # 14 distinct parts stored once
    for label in ("'wheel_mp'", "'sample_holder'", "'sample_k10p01'", "'bearing_624ZZ'"):
        assert label in text


def test_glb_content(exported):
    from tactcad.export.glb import read_glb

    out, _ = exported
    doc = read_glb(out / "scenes/sample-stiffness-rig.glb")
    root = doc["nodes"][0]
    assert root["scale"] == [0.001] * 3 and len(root["children"]) == 24
    nodes = {n["name"]: n for n in doc["nodes"][1:]}
    assert nodes["push_in_fitting"]["extras"]["part"] == "push_in_fitting_M5"
    assert nodes["sample"]["extras"]["stiffness_N_per_mm"] == 10.01
    assert nodes["wheel_mm"]["extras"]["part"] == "bearing_624ZZ"
    assert {m["name"] for m in doc["meshes"]} >= {"cart", "bearing_624ZZ", "sample_k10p01"}
    assert doc["_bin_length"] == doc["buffers"][0]["byteLength"]


@pytest.mark.slow
def test_export_single_scene(tmp_path, project):
    from tactcad.export.freecad_review import freecadcmd
    from tactcad.export.run import export_scenes

    res = export_scenes(project, tmp_path, ["array"], log=lambda s: None)
    review = ["review/array.FCStd"] if freecadcmd() else []  # written when FreeCAD is installed
    assert sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*") if p.is_file()) \
        == review + ["scenes/array.glb", "scenes/array.step"]
    assert res.files[0]["solids"] == 38  # 28 parts and 10 gauges
    with pytest.raises(SceneError):
        export_scenes(project, tmp_path / "other", ["array", "nope"])
    assert not (tmp_path / "other").exists()  # an unknown name writes nothing


def test_changed_rig_dimensions_assemble_or_fail_clearly(plan, project):
    """Any rig file either fails validation (DesignError naming the field) or
    assembles every rig with all loops closed (SceneError if a slide would
    leave its range); nothing else goes wrong."""
    from hypothesis import HealthCheck, Phase, given, settings
    from hypothesis import strategies as st

    from tactcad.design.rig_plan import default_rigs_data, rigs_from_dict

    base = default_rigs_data()

    @settings(max_examples=12, deadline=None, suppress_health_check=list(HealthCheck),
              phases=[Phase.explicit, Phase.reuse, Phase.generate])  # no slow shrinking
    @given(cart_l=st.floats(40, 160), s_h=st.floats(2, 30), holder=st.floats(1, 12),
           bar=st.floats(10, 200), rail=st.floats(0, 80), weights=st.integers(0, 6),
           z_pos=st.floats(0, 13), element=st.integers(1, 10))
    def check(cart_l, s_h, holder, bar, rail, weights, z_pos, element):
        data = json.loads(json.dumps(base))
        data["cart"]["length_mm"] = cart_l
        data["sample"]["height_mm"] = s_h
        data["sample_holder"]["thickness_mm"] = holder
        data["hanger_bar"]["length_mm"] = bar
        data["linear_axis"]["rail_mount_height_mm"] = rail
        data["weights"]["count"] = weights
        data["z_axis"]["position_mm"] = z_pos
        data.setdefault("calibration", {})["element"] = element
        try:
            rigs = rigs_from_dict(data, plan)
        except DesignError as exc:
            assert exc.field and exc.allowed
            return
        for name in SCENES[2:]:
            try:
                sc = assemble(dataclasses.replace(project, rigs=rigs), name)
            except SceneError as exc:
                assert "range is" in str(exc)
                continue
            assert sc.instances and sc.contacts

    check()


def test_bench_stiffness_delegates_or_says_unavailable(monkeypatch, capsys):
    import sys
    import types

    calls = []
    fake = types.ModuleType("tactcad.benchmarks.stiffness_bench")
    fake.main = lambda args, plan=None: calls.append(args) or 0
    monkeypatch.setitem(sys.modules, "tactcad.benchmarks.stiffness_bench", fake)
    assert cli.main(["bench", "stiffness", "--models", "beam"]) == 0
    assert calls and calls[0].models == ["beam"]
    monkeypatch.setitem(sys.modules, "tactcad.benchmarks.stiffness_bench", None)
    assert cli.main(["bench", "stiffness"]) == 0
    assert "not available" in capsys.readouterr().out
