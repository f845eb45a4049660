"""Fabrication drawings: SVGs parse, the PDF has a page per drawing and the
pages are not blank, every dimension reads back as the plan's value, a changed
design changes the drawing, title blocks carry quantity / hash / version."""

from __future__ import annotations

import dataclasses
import json
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from tactcad import __version__
from tactcad.assembly.inventory import design_assemblies, fabricated_parts, instance_counts
from tactcad.catalogue.array_catalogue import Method, Process, array_instances, array_parts
from tactcad.catalogue.shop import stock_size, tightening_torque_Nm
from tactcad.drawings.compose import part_hash
from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides

SVG = "{http://www.w3.org/2000/svg}"
NUMBER = re.compile(r"-?\d+(?:\.\d+)?")


from tactcad.design.tolerances import DEFAULTS as TOL_DEFAULTS  # noqa: E402


def texts_by_id(svg_text: str) -> dict[str, str]:
    root = ET.fromstring(svg_text.encode("utf-8"))
    return {el.get("id"): (el.text or "") for el in root.iter(f"{SVG}text") if el.get("id")}


def dims(svg_text: str) -> dict[str, str]:
    return {k[4:]: v for k, v in texts_by_id(svg_text).items() if k.startswith("dim-")}


def printed_equals(text: str, value: float, index: int = 0) -> bool:
    """The ``index``-th number printed in ``text`` equals ``value`` to the
    drawings' printed precision: 3 decimals with trailing zeros dropped
    (``22`` means 22.000), so the tolerance is half a unit of the 3rd decimal."""
    nums = NUMBER.findall(text)
    return abs(float(nums[index]) - value) <= 0.0005 + 1e-12


def assert_dims(found: dict[str, str], expected: dict[str, float | tuple]) -> None:
    missing = set(expected) - set(found)
    assert not missing, f"dimensions missing from the drawing: {sorted(missing)}"
    for name, want in expected.items():
        values = want if isinstance(want, tuple) else (want,)
        for k, v in enumerate(values):
            assert printed_equals(found[name], v, k), f"{name}: drawing says {found[name]!r}, plan {v}"


def element_expectations(g) -> dict:
    """Plan values of an element's dimensions, by dimension name."""
    h1, h2 = sorted(g.bolt_holes, key=lambda h: h.x_mm)
    return {
        "web_thickness": (g.web_thickness_mm, g.web_tolerance_mm),
        "notch_radius": g.notch_radius_mm,
        "arm_length": g.arm_length_mm,
        "tip_width": g.tip_width_mm,
        # width and depth, each with its [tolerances] value (the defaults here)
        "contact_face": (g.contact_face_mm[0], TOL_DEFAULTS["contact_face_mm"][0],
                         g.contact_face_mm[1], TOL_DEFAULTS["sheet_thickness_mm"][0]),
        "overall_length": g.overall_length_mm,
        "overall_height": g.tip_top_y_mm,
        "base_height": g.base_height_mm,
        "arm_height": g.arm_height_mm,
        "tip_height": g.tip_height_mm,
        "corner_radius": g.inside_corner_radius_mm,
        "hole_1_x": h1.x_mm,
        "hole_2_x": h2.x_mm,
        "hole_y": h1.y_mm,
        "hole_diameter": (2, h1.diameter_mm),
        "thickness": g.sheet_thickness_mm,
    }


@pytest.fixture(scope="module")
def drawing_files(exported):
    out, _ = exported
    man = json.loads((out / "manifest.json").read_text())
    svgs = {f["part"]: out / f["path"] for f in man["files"] if f["kind"] == "drawing-svg"}
    return out, man, svgs


def test_one_drawing_per_fabricated_part_and_every_svg_parses(drawing_files, plan, project):
    out, man, svgs = drawing_files
    specs, assemblies = design_assemblies(project)
    used = {i.part for inst in assemblies.values() for i in inst}
    placed = {n for n, s in specs.items() if s.kind == "fabricated" and n in used}
    made, _ = fabricated_parts(project)
    assert set(svgs) == {s.name for s in made} >= placed  # and the samples no scene shows
    assert {n for n, s in array_parts(plan).items() if s.kind == "fabricated"} <= set(svgs)
    for part, path in svgs.items():
        assert path.name == f"{part}.svg" and path.parent.name == "drawings"
        root = ET.parse(path).getroot()
        assert root.tag == f"{SVG}svg"
        assert root.get("viewBox") == "0 0 420 297"
        assert root.find(f".//{SVG}g[@id='view-front']/{SVG}path") is not None


def test_views_carry_visible_and_hidden_lines(drawing_files):
    _, _, svgs = drawing_files
    root = ET.parse(svgs["element_a4mm"]).getroot()
    top = root.find(f".//{SVG}g[@id='view-top']")
    classes = [p.get("class") for p in top.iter(f"{SVG}path")]
    assert classes.count("hidden") >= 4  # the two bolt holes seen from above
    assert classes.count("visible") >= 4
    assert all(p.get("stroke-dasharray") for p in top.iter(f"{SVG}path")
               if p.get("class") == "hidden")


def test_pdf_has_one_page_per_drawing_and_no_blank_page(drawing_files):
    import pypdfium2 as pdfium
    from pypdf import PdfReader

    out, man, svgs = drawing_files
    pdf = out / "drawings/drawings.pdf"
    reader = PdfReader(pdf)
    assert len(reader.pages) == len(svgs) + 1  # the parts, then the assembly sheet
    assert "SLOT MAP" in reader.pages[len(svgs)].extract_text()
    w, h = (float(v) for v in reader.pages[0].mediabox.upper_right)
    assert abs(w - 420 / 25.4 * 72) < 1 and abs(h - 297 / 25.4 * 72) < 1  # A3 landscape
    assert "element_a4mm" in reader.pages[0].extract_text()
    order = [f["part"] for f in man["files"] if f["kind"] == "drawing-svg"]
    for k in (0, len(order) - 1):
        assert order[k] in reader.pages[k].extract_text()
    doc = pdfium.PdfDocument(str(pdf))
    try:
        for k in range(len(doc)):
            img = np.asarray(doc[k].render(scale=40 / 72).to_pil().convert("L"), dtype=float)
            dark = (img < 128).mean()
            assert img.std() > 10 and dark > 0.003, f"page {k + 1} looks blank"
    finally:
        doc.close()


def test_element_dimensions_read_back_as_plan_values(drawing_files, plan):
    _, _, svgs = drawing_files
    for name, g in plan.distinct_elements.items():
        assert_dims(dims(svgs[name].read_text()), element_expectations(g))


def test_web_thickness_carries_tolerance_and_reason(drawing_files, plan):
    _, _, svgs = drawing_files
    text = svgs["element_a4mm"].read_text()
    g = plan.distinct_elements["element_a4mm"]
    assert dims(text)["web_thickness"] == "0.25 ±0.02"
    notes = " ".join(v for k, v in texts_by_id(text).items() if k.startswith("note"))
    all_text = " ".join(el.text or "" for el in ET.fromstring(text).iter(f"{SVG}text"))
    assert "Table 1" in all_text and "40.12" in all_text and "80.38" in all_text
    assert f"1. Web thickness {g.web_thickness_mm:g} ±{g.web_tolerance_mm:g}" in notes


def test_plate_dimensions_read_back_as_plan_values(drawing_files, plan):
    _, _, svgs = drawing_files
    s = plan.spacer
    h1, h2 = sorted(s.holes, key=lambda h: h.x_mm)
    assert_dims(dims(svgs["spacer"].read_text()), {
        "overall_length": s.length_mm, "overall_height": s.height_mm, "thickness": s.thickness_mm,
        "hole_1_x": h1.x_mm, "hole_2_x": h2.x_mm, "hole_y": h1.y_mm,
        "hole_diameter": (2, h1.diameter_mm)})
    c = plan.clamp
    found = dims(svgs["clamp_plate"].read_text())
    expected = {"overall_length": 2 * c.half_length_mm, "overall_height": c.height_mm,
                "thickness": c.thickness_mm, "window_width": 2 * c.window_half_width_mm,
                "bridge_height": c.bridge_height_mm, "inside_radius": c.window_corner_radius_mm}
    for i, h in enumerate(sorted(c.holes, key=lambda h: (h.y_mm, h.x_mm)), start=1):
        expected |= {f"hole_{i}_x": h.x_mm, f"hole_{i}_y": h.y_mm, f"hole_{i}_d": h.diameter_mm}
    assert_dims(found, expected)


def test_title_blocks_carry_quantity_hash_version_material(drawing_files, plan, project):
    _, _, svgs = drawing_files
    made, largest = fabricated_parts(project)  # the largest count in an assembly, else 1
    specs = {s.name: s for s in made}
    array_counts = instance_counts(array_instances(plan))
    for part, path in svgs.items():
        tb = texts_by_id(path.read_text())
        assert tb["tb-part"] == part
        assert int(tb["tb-quantity"]) == largest[part]
        if part in array_counts:
            assert int(tb["tb-quantity"]) == array_counts[part]
        assert tb["tb-design"].endswith(part_hash(plan, specs[part])[:12])
        assert tb["tb-number"] == f"{plan.name}-{part}"
        assert tb["tb-version"] == f"tactcad {__version__}"
        assert tb["tb-tolerance"] == "ISO 2768-f"
        assert tb["tb-units"] == "mm"
        assert tb["tb-process"] == specs[part].process
        assert tb["tb-material"].startswith(specs[part].material)
        assert tb["tb-material"].endswith(stock_size(specs[part]))
        assert re.fullmatch(r"\d+:\d+(, detail \d+:\d+)?", tb["tb-scale"])
    assert texts_by_id(svgs["element_a4mm"].read_text())["tb-scale"] == "5:1, detail 50:1"


def _compose_first_element(plan):
    from tactcad.solids.cache import PartCache
    from tactcad.drawings.compose import compose

    specs = array_parts(plan)
    name = next(iter(plan.distinct_elements))
    spec = specs[name]
    solid = PartCache(plan).solid(specs[name])
    qty = instance_counts(array_instances(plan))[name]
    return name, compose(plan, spec, solid, qty).sheet.svg()


@pytest.mark.parametrize("overrides", [
    {"element.web_thickness_mm": 0.3},
    {"element.web_thickness_mm": 0.18, "element.web_tolerance_mm": 0.01,
     "element.notch_radius_mm": 0.8},
    {"arms.lengths_mm": [5.5, 7.0, 6.0, 8.0, 6.0, 8.0, 5.0, 5.5, 5.0, 7.0],
     "element.tip_width_mm": 2.5},
])
def test_changed_design_changes_the_drawing(overrides):
    plan = plan_from_dict(with_overrides(default_design_data(), overrides))
    name, svg = _compose_first_element(plan)
    found = dims(svg)
    assert_dims(found, element_expectations(plan.distinct_elements[name]))
    if "element.web_thickness_mm" in overrides:
        assert found["web_thickness"].startswith(f"{overrides['element.web_thickness_mm']:g} ±")
    assert texts_by_id(svg)["tb-design"].endswith(part_hash(plan, array_parts(plan)[name])[:12])


def test_part_hash_follows_what_shapes_the_part(plan):
    """The title block's hash covers every value that shapes the part, and no other:
    another element's arm leaves element_a4mm's hash alone, its own web does not."""
    data = default_design_data()
    other_arm = plan_from_dict(with_overrides(data, {"arms.lengths_mm": [
        4.0, 7.0, 6.0, 8.0, 6.5, 8.0, 5.0, 4.0, 5.0, 7.0]}))
    thicker = plan_from_dict(with_overrides(data, {"element.web_thickness_mm": 0.3}))
    renamed = plan_from_dict(with_overrides(data, {"design.name": "other_array"}))

    def h(p, name="element_a4mm"):
        return part_hash(p, array_parts(p)[name])

    assert h(other_arm) == h(plan)
    assert h(other_arm, "element_a6mm") != h(plan, "element_a6mm")  # used by one element now
    assert h(thicker) != h(plan) and h(renamed) != h(plan)


def test_same_plan_gives_same_svg(plan):
    assert _compose_first_element(plan) == _compose_first_element(plan)


def test_reader_rejects_a_wrong_value():
    assert printed_equals("0.25 ±0.02", 0.25) and printed_equals("0.25 ±0.02", 0.02, 1)
    assert not printed_equals("0.25 ±0.02", 0.3)
    assert not printed_equals("22", 22.6) and not printed_equals("6", 5.5)
    assert printed_equals("1.333", 4 / 3)
    with pytest.raises(AssertionError):
        assert_dims({"web_thickness": "0.25 ±0.02"}, {"web_thickness": (0.25, 0.03)})


def test_any_fabricated_part_gets_a_generic_drawing_from_its_solid(plan):
    """A part with no dimension set of its own and no plan profile (as a rig
    part may be) is dimensioned from its solid: sizes and holes."""
    from tactcad.solids.cache import PartCache
    from tactcad.drawings.compose import compose
    from tactcad.drawings.part_sets import GENERIC, drawing_of

    specs = array_parts(plan)
    solid = PartCache(plan).solid(specs["spacer"])
    spec = dataclasses.replace(specs["spacer"], name="rig_test_plate", builder="rig_test_plate",
                               profile=None, thickness_mm=0.0, process=Process("milling", Method.PLATE))
    assert drawing_of(spec) is GENERIC
    svg = compose(plan, spec, solid, 3).sheet.svg()
    s = plan.spacer
    h1, h2 = sorted(s.holes, key=lambda h: h.x_mm)
    assert_dims(dims(svg), {"overall_length": s.length_mm, "overall_height": s.height_mm,
                            "thickness": s.thickness_mm, "hole_1_x": h1.x_mm,
                            "hole_2_x": h2.x_mm, "hole_y": h1.y_mm,
                            "hole_diameter": (2, h1.diameter_mm)})
    tb = texts_by_id(svg)
    assert tb["tb-part"] == "rig_test_plate" and tb["tb-quantity"] == "3"


def test_purchased_parts_are_not_drawn(plan):
    from tactcad.drawings.compose import compose

    bolt = next(s for s in array_parts(plan).values() if s.kind == "purchased")
    with pytest.raises(ValueError, match="purchased"):
        compose(plan, bolt, None, 4)


def test_pictures_exist_and_are_not_blank(exported, plan):
    from PIL import Image

    out, _ = exported
    for rel, size in (("images/element_a4mm_drawing.png", (2480, 1754)),
                      ("images/array.png", (1600, 1000))):
        img = Image.open(out / rel)
        assert abs(img.size[0] - size[0]) <= 1 and abs(img.size[1] - size[1]) <= 1
        a = np.asarray(img.convert("L"), dtype=float)
        assert a.std() > 10, rel
    # the array picture shows the parts' colours (blue clamp plates, grey elements)
    rgb = np.asarray(Image.open(out / "images/array.png").convert("RGB"), dtype=int)
    blue = (rgb[..., 2] - rgb[..., 0] > 40).mean()
    assert blue > 0.02


def test_rig_parts_are_drawn_when_the_scenes_show_them(drawing_files, plan, project):
    """Fabricated rig parts get drawings with their own dimension set
    (indenter) or the generic one (sizes from the solid)."""
    pytest.importorskip("tactcad.assembly.scene_solver")
    _, _, svgs = drawing_files
    specs = {s.name: s for s in fabricated_parts(project)[0]}
    if "indenter" in svgs:
        g = specs["indenter"].geometry
        assert_dims(dims(svgs["indenter"].read_text()), {
            "contact_width": g.contact_width_mm, "contact_depth": g.contact_depth_mm,
            "tip_length": g.tip_length_mm, "body_diameter": g.body_diameter_mm,
            "contact_face": (g.contact_width_mm, g.contact_depth_mm)})
    rig = [n for n in svgs if n not in array_parts(plan)]
    assert rig, "the scenes show fabricated rig parts"
    for name in rig:
        x0, y0, z0, x1, y1, z1 = specs[name].expected_bbox_mm
        found = dims(svgs[name].read_text())
        sizes = sorted([x1 - x0, y1 - y0, z1 - z0])
        printed = [found[k] for k in ("overall_length", "overall_height", "thickness",
                                      "outer_diameter") if k in found]
        for text in printed:
            assert any(printed_equals(text, v) for v in sizes), (name, text, sizes)


# --- shop-ready sheets: features, sections, title-block fields, no overlapping texts ----------
def _compose(plan, name, raw=None):
    from tactcad.design.project import project_for_plan
    from tactcad.drawings.compose import compose
    from tactcad.solids.build import build_part

    specs, _ = design_assemblies(project_for_plan(plan))
    if raw is not None:
        plan = dataclasses.replace(plan, raw=raw)
    return compose(plan, specs[name], build_part(specs[name]), 1), specs[name]


def _svg_text_boxes(svg_text: str) -> list[tuple[str, tuple]]:
    """Text boxes of an SVG as :func:`tactcad.drawings.sheet.text_box` computes them,
    read back from the file's attributes."""
    from tactcad.drawings.sheet import CAP_HEIGHT_EM, text_box

    out = []
    for el in ET.fromstring(svg_text.encode("utf-8")).iter(f"{SVG}text"):
        at = (float(el.get("x")), float(el.get("y")))
        rot = re.search(r"rotate\((-?[\d.]+)", el.get("transform") or "")
        out.append((el.text or "", text_box(at, el.text or "", float(el.get("font-size")) * CAP_HEIGHT_EM,
                                          el.get("text-anchor") or "start",
                                          float(rot.group(1)) if rot else 0.0)))
    return out


def test_no_two_texts_of_a_sheet_overlap(drawing_files):
    """Every exported sheet, the assembly sheet included: no two text boxes overlap."""
    out, _, svgs = drawing_files
    for path in [*svgs.values(), out / "drawings/assembly.svg"]:
        boxes = _svg_text_boxes(path.read_text())
        for i, (ta, a) in enumerate(boxes):
            for tb, b in boxes[i + 1:]:
                ox = min(a[2], b[2]) - max(a[0], b[0])
                oy = min(a[3], b[3]) - max(a[1], b[1])
                assert ox <= 0.05 or oy <= 0.05, f"{path.name}: {ta!r} overlaps {tb!r}"


def test_overlap_finder_sees_overlapping_texts():
    from tactcad.drawings.sheet import Sheet, overlapping_texts

    sh = Sheet("A3")
    sh.text("g", (10.0, 10.0), "H4")
    sh.text("g", (12.0, 10.5), "H5")
    sh.text("g", (50.0, 10.0), "far")
    assert overlapping_texts(sh) == [("H4", "H5")]


@pytest.mark.slow
def test_cart_features_and_section(plan):
    """The cart's pocket, holder and axle threads, hose port, channel and
    suction holes carry the rigs file's values; section A-A is hatched and labelled."""
    from tactcad.catalogue.shop import coarse_pitch_mm

    d, spec = _compose(plan, "cart")
    g = spec.geometry
    svg = d.sheet.svg()
    found = dims(svg)
    assert_dims(found, {
        "overall_length": g.length_mm, "overall_height": g.width_mm, "thickness": g.thickness_mm,
        "pocket_length": g.pocket_length_mm, "pocket_width": g.pocket_width_mm,
        "pocket_depth": g.pocket_depth_mm, "holder_screw_spacing": 2 * g.holder_screw_y_mm,
        "axle_spacing": 2 * g.axle_x_mm, "axle_height": g.axle_height_mm,
        "port_depth": g.port_depth_mm, "channel_length": g.channel_end_x_mm + g.length_mm / 2,
        "channel_height": g.thickness_mm / 2, "channel_diameter": g.channel_diameter_mm,
        "suction_hole_pitch": g.suction_hole_xs_mm[1] - g.suction_hole_xs_mm[0],
        "suction_hole_first_x": g.suction_hole_xs_mm[0] + g.length_mm / 2,
        "suction_holes": (len(g.suction_hole_xs_mm), g.suction_hole_diameter_mm),
        "holder_thread": (2, g.holder_screw_diameter_mm,
                          coarse_pitch_mm(g.holder_screw_diameter_mm), g.holder_tapped_depth_mm),
        "axle_thread": (4, g.axle_bolt.nominal_diameter_mm, g.axle_bolt.thread_pitch_mm,
                        g.axle_hole_depth_mm),
        "port_thread": (g.port_diameter_mm, coarse_pitch_mm(g.port_diameter_mm), g.port_depth_mm)})
    root = ET.fromstring(svg.encode("utf-8"))
    section = root.find(f".//{SVG}g[@id='view-section']")
    hatch = [p for p in section.iter(f"{SVG}path") if p.get("class") == "hatch"]
    assert len(hatch) > 20
    assert not [p for p in section.iter(f"{SVG}path") if p.get("class") == "hidden"]
    tb = texts_by_id(svg)
    assert tb["section-label"].startswith("A-A (")
    assert tb["section-letter-l"] == tb["section-letter-r"] == "A"
    assert "hole-label-1" not in tb  # no crowded hole table on the cart


@pytest.mark.slow
def test_base_plate_grooves_and_sample_holder_window(plan):
    d, spec = _compose(plan, "base_plate")
    g = spec.geometry
    assert_dims(dims(d.sheet.svg()), {"groove_width": g.groove_width_mm,
                                      "groove_depth": g.groove_depth_mm,
                                      "groove_spacing": 2 * g.track_half_mm})
    d, spec = _compose(plan, "sample_holder")
    h = spec.geometry
    found = dims(d.sheet.svg())
    assert_dims(found, {"window_length": h.window_length_mm, "window_width": h.window_width_mm,
                        "window_corner": (4, h.corner_radius_mm),
                        "hole_1_d": h.screw.clearance_hole_mm, "hole_2_d": h.screw.clearance_hole_mm})
    assert "hole_3_d" not in found  # window fillets are not holes


@pytest.mark.slow
def test_indenter_has_its_mounting_thread(plan, project):
    from tactcad.partlib.indenter import INDENTER_THREAD_DIAMETER_MM, indenter_thread_depth_mm
    from tactcad.solids.build import build_part

    specs, _ = design_assemblies(project)
    spec = specs["indenter"]
    solid = build_part(spec)
    assert abs(solid.volume - spec.expected_volume_mm3) < 1e-3 * spec.expected_volume_mm3
    d, _ = _compose(plan, "indenter")
    depth = indenter_thread_depth_mm(spec.geometry)
    assert 0 < depth < spec.geometry.body_length_mm
    svg = d.sheet.svg()
    assert_dims(dims(svg), {"mount_thread": (INDENTER_THREAD_DIAMETER_MM, 1.0, depth),
                            "thread_depth": depth})
    # the blind tapped hole is shown in a hatched section through the axis
    assert texts_by_id(svg)["section-label"].startswith("A-A (")
    section = ET.fromstring(svg.encode("utf-8")).find(f".//{SVG}g[@id='view-section']")
    assert any(p.get("class") == "hatch" for p in section.iter(f"{SVG}path"))


@pytest.mark.slow
def test_title_block_revision_date_material_and_finish(plan):
    d, spec = _compose(plan, "element_a4mm")
    tb = texts_by_id(d.sheet.svg())
    assert tb["tb-revision"] == "A" and tb["tb-date"] == "—"
    assert f"EN AW-{plan.material.grade}" in tb["tb-material"]
    assert "Ra 1.6 general" in tb["tb-finish"] and "Ra 0.8: contact face" in tb["tb-finish"]
    assert tb["finish-general"] == "Ra 1.6"
    raw = {**plan.raw, "design": {**plan.raw["design"], "revision": "C", "date": "2026-01-15"}}
    d2, _ = _compose(plan, "element_a4mm", raw=raw)
    tb2 = texts_by_id(d2.sheet.svg())
    assert tb2["tb-revision"] == "C" and tb2["tb-date"] == "2026-01-15"
    assert tb2["tb-design"] != tb["tb-design"]  # the part hash covers revision and date
    d3, _ = _compose(plan, "cart")
    tb3 = texts_by_id(d3.sheet.svg())
    assert "EN AW-6082-T651" in tb3["tb-material"] and "plate" in tb3["tb-material"]
    assert "Ra 0.8" not in tb3["tb-finish"]


def test_assembly_sheet_content(drawing_files, plan):
    """Slot map: one row per element with its arm and DXF, row 2 turned; stack
    order; balloons numbered as the BOM; bolts with their torque."""
    from tactcad.catalogue.files import profile_dxf_name
    from tactcad.drawings.assembly import slot_map, stack_order

    out, man, _ = drawing_files
    tb = texts_by_id((out / "drawings/assembly.svg").read_text())
    rows = slot_map(plan)
    assert len(rows) == len(plan.slots)
    dxf = {f["path"].split("/")[-1] for f in man["files"]}
    for s in plan.slots:
        assert tb[f"slot-{s.number}-part"] == s.geometry.part_name
        assert printed_equals(tb[f"slot-{s.number}-arm_mm"], s.geometry.arm_length_mm)
        assert tb[f"slot-{s.number}-dxf"] in dxf
        assert tb[f"slot-{s.number}-dxf"] == profile_dxf_name(
            s.geometry.part_name, sum(t.geometry.part_name == s.geometry.part_name
                                      for t in plan.slots)).split("/")[-1]
        assert ("turned" in tb[f"slot-{s.number}-orientation"]) == (s.row == 1)
    order = stack_order(plan)
    for r, names in order.items():
        assert names[0] == "clamp_plate_front" and names[-1] == "clamp_plate_back"
        inner = names[1:-1]
        assert [n.split("_")[0] for n in inner] == ["element", "spacer"] * (plan.columns - 1) + ["element"]
        assert {int(n.split("_")[1]) for n in inner[::2]} == {s.number for s in plan.slots if s.row == r}
    notes = " ".join(v for k, v in tb.items() if k.startswith("note"))
    assert ", ".join(order[0][:3]) in notes
    bom = {r["part"]: r["item"] for r in
           __import__("csv").DictReader((out / "bom.csv").open(encoding="utf-8-sig"))}
    for part in array_parts(plan):
        assert tb[f"balloon-{part}"] == bom[part]
    torque = tightening_torque_Nm(plan.bolt)
    assert 0.2 < torque < 0.6  # M2 8.8 tables give about 0.35 to 0.4 N·m
    assert f"{torque:.2f} N·m" in notes and "VDI 2230" in notes


def test_holes_read_from_a_solid_know_through_from_blind(plan):
    """A hole with a flat floor is blind (its depth printed), one open at
    both ends is through; quarter-cylinder fillets are no holes."""
    import build123d as bd

    from tactcad.drawings.drawing import holes_seen

    spec = dataclasses.replace(array_parts(plan)["spacer"], profile=None)
    block = bd.Solid.make_box(20, 10, 5)
    blind = bd.Solid.make_cylinder(1.0, 3.0, bd.Plane(origin=(5, 5, 2), z_dir=(0, 0, 1)))
    through = bd.Solid.make_cylinder(1.5, 5.0, bd.Plane(origin=(15, 5, 0), z_dir=(0, 0, 1)))
    holes = {h.x: h for h in holes_seen(spec, block.cut(blind, through))}
    assert holes[5.0].depth == pytest.approx(3.0) and holes[5.0].depth_text == "depth 3"
    assert holes[15.0].depth is None and holes[15.0].depth_text == "through"
    tool = bd.Solid.make_box(8, 6, 2, bd.Plane(origin=(6, 2, 3)))
    pocket = tool.fillet(1.0, tool.edges().filter_by(bd.Axis.Z))  # concave corners in the part
    assert holes_seen(spec, bd.Solid.make_box(20, 10, 5).cut(pocket)) == []


def test_assembly_sheet_dimensions_the_envelope(drawing_files, plan):
    """X, Y and Z of the clamped array, as the inventory computes them."""
    from tactcad.assembly.inventory import array_envelope_mm

    out, _, _ = drawing_files
    d = dims((out / "drawings/assembly.svg").read_text())
    env = array_envelope_mm(plan)
    for axis, value in zip("xyz", env):
        assert printed_equals(d[f"envelope_{axis}"], value)


def test_envelope_note_gives_the_footprint_margin(plan):
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.design.array_plan import plan_from_dict
    from tactcad.drawings.assembly import envelope_note
    from tactcad.drawings.sheet import fmt_mm

    env = array_envelope_mm(plan)
    assert "footprint" not in envelope_note(plan) and fmt_mm(env[2], 2) in envelope_note(plan)
    raw = {**plan.raw, "requirements": {**plan.raw.get("requirements", {}),
                                        "footprint_mm": [env[0] + 2.0, env[1] + 0.5]}}
    note = envelope_note(plan_from_dict(raw))
    assert "required footprint" in note and "margin X 2, Y 0.5 mm" in note


def test_a_combs_slot_map_names_the_row_sheets_dxf_the_export_writes():
    # the slot map named element_a2mm_qty5.dxf; the shop cuts a comb's elements from the
    # row sheet's DXF (comb_row1_qty1.dxf), the file the export writes
    from tactcad.catalogue.files import profile_dxf_name
    from tactcad.design.array_plan import EXAMPLES
    from tactcad.design.project import load_project
    from tactcad.drawings.assembly import slot_map

    comb_plan = load_project(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml").plan
    written = {profile_dxf_name(sh.part_name, 1).split("/")[-1] for sh in comb_plan.comb.sheets}
    rows = slot_map(comb_plan)
    assert {r["dxf"] for r in rows} == written
    assert all(r["part"] == f"comb_row{r['row']}" for r in rows)
