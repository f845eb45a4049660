"""The build book written by the ``instructions`` export kind."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tactcad.assembly.build_steps import tightening_torque_Nm
from tactcad.assembly.inventory import design_assemblies
from tactcad.design.project import load_project
from tactcad.export.bom import complete_kit
from tactcad.export.instructions import BOOK_DATA, BOOK_PAGE, BOOK_PDF, write_book

HARDWARE = Path(__file__).resolve().parents[2] / "hardware"


@pytest.fixture(scope="module", params=["macro_array", "ti_array_2x3"])
def book(request, tmp_path_factory):
    project = load_project(HARDWARE / request.param / f"{request.param}.toml")
    assembled = design_assemblies(project)
    out = tmp_path_factory.mktemp(request.param)
    records = write_book(project, out, lambda line: None, assembled)
    return project, complete_kit(project, assembled), out, records


def test_book_lists_every_bom_row_in_one_step(book):
    """Every BOM row in one step, its fitted count there; a nut in the steps that fit the
    bolts of its size, its counts adding up to the BOM's."""
    _, rows, out, records = book
    steps = json.loads((out / BOOK_DATA).read_text())
    assert records[0]["steps"] == len(steps)
    in_steps = [p["part"] for s in steps for p in s["parts"]]
    assert sorted(set(in_steps)) == sorted(r.part for r in rows)
    assert all(in_steps.count(p) == 1 or p.startswith("nut_") for p in in_steps)
    counted = {r.part: sum(p["quantity"] for s in steps for p in s["parts"] if p["part"] == r.part)
               for r in rows}
    assert counted == {r.part: r.quantity - r.spares for r in rows}
    page = (out / BOOK_PAGE).read_text()
    assert all(f'data-step="{s["key"]}"' in page for s in steps)
    assert "<script" not in page and "http" not in page  # nothing to fetch: opens offline


def test_wiring_names_terminals_and_bolts_a_torque(book):
    project, _, out, _ = book
    steps = {s["key"]: s for s in json.loads((out / BOOK_DATA).read_text())}
    pairs = project.rigs.library["terminal_board"].attributes["terminal_pairs"]
    assert f"terminals {2 * pairs - 1} and {2 * pairs}" in " ".join(steps["array-wiring"]["notes"])
    bolt = project.plan.bolt
    torque = f"{tightening_torque_Nm(bolt.nominal_diameter_mm, bolt.thread_pitch_mm):.2f} N m"
    assert torque in steps["array-bolts"]["notes"][0]


def test_each_rig_step_torques_the_screws_it_uses(book):
    """A rig step names each of its screw parts with its size, quantity and the
    torque of that size (ISO 4762 hex key); a step without screws names none."""
    from tactcad.assembly.build_steps import screw_notes
    from tactcad.vocabulary.standards import RIG_BOLTS

    _, _, out, _ = book
    steps = json.loads((out / BOOK_DATA).read_text())
    screws = {p["part"]: p["quantity"] for s in steps if s["key"].startswith("rig-")
              for p in s["parts"] if p["part"].startswith("bolt_")}
    assert screws  # both examples' rigs carry screws
    for s in (s for s in steps if s["key"].startswith("rig-")):
        text = " ".join(s["notes"])
        for p in (p["part"] for p in s["parts"] if p["part"] in screws):
            size = p.split("_")[1].split("x")[0].replace("p", ".")
            bolt = RIG_BOLTS[size]
            torque = tightening_torque_Nm(bolt.nominal_diameter_mm, bolt.thread_pitch_mm)
            assert f"{screws[p]:g} {size} screws ({p}) to {torque:.2f} N m" in text
        assert text.count("N m") == sum(p["part"] in screws for p in s["parts"])
    assert screw_notes([("column", 1)], {}) == ()
    assert "2.5 mm hex key" in screw_notes([("bolt_M3x10", 2)], {"bolt_M3x10": RIG_BOLTS["M3"]})[0]


def test_an_exploded_part_carries_what_an_earlier_step_put_on_it():
    """A gauge (bonded in an earlier step) sitting on an element lifted in the
    stack step moves with it; a part of a later step stays; the lift is the
    element's own z times EXPLODE_FACTOR its height."""
    import numpy as np

    from tactcad.catalogue.array_catalogue import Instance
    from tactcad.design.array_plan import Placement
    from tactcad.export.instructions import EXPLODE_FACTOR, explode_offsets

    def box(x, y, z):
        v = np.array([[i * x, j * y, k * z] for i in (0, 1) for j in (0, 1) for k in (0, 1)],
                     dtype=float)
        return v, np.array([[0, 1, 2]])

    meshes = {"element": box(30, 10, 3), "gauge": box(5, 3, 0.1), "bolt": box(2, 2, 20)}
    inst = [Instance("element_1", "element", Placement(0, 0, 0)),
            Instance("gauge_1", "gauge", Placement(10, 2, 3)),        # on the element's top
            Instance("gauge_2", "gauge", Placement(10, 2, 40)),       # on nothing
            Instance("bolt_1", "bolt", Placement(-2, 0, 0))]          # a later step, touching
    off = explode_offsets(meshes, inst, {"element"}, earlier={"gauge"})
    assert np.allclose(off[0], [0, 0, EXPLODE_FACTOR * 3.0])
    assert np.allclose(off[1], off[0]) and 2 not in off and 3 not in off


def test_a_step_whose_parts_its_scene_lacks_is_drawn_where_they_are():
    from types import SimpleNamespace as NS

    from tactcad.export.instructions import drawn_scene

    step = NS(scene="array", highlight=("terminal_board",))
    assemblies = {"array": [NS(part="element_a4mm")], "wirecut": [NS(part="element_a4mm")],
                  "calibration-rig": [NS(part="base_plate"), NS(part="terminal_board")]}
    assert drawn_scene(step, assemblies) == "calibration-rig"
    assert drawn_scene(NS(scene="array", highlight=("element_a4mm",)), assemblies) == "array"
    assert drawn_scene(NS(scene="array", highlight=("daq",)), assemblies) == "array"


def test_torque_grows_with_size():
    # M3 class 8.8 with K = 0.2: about 1.3 N m (common tables 1.2-1.3 N m)
    assert 1.1 < tightening_torque_Nm(3, 0.5) < 1.4
    assert tightening_torque_Nm(2, 0.4) < tightening_torque_Nm(3, 0.5) < tightening_torque_Nm(4, 0.7)


@pytest.mark.parametrize("name", ["macro_array", "ti_array_2x3"])
@pytest.mark.slow  # a whole chain through the command line or an export
def test_step_pictures_show_their_highlighted_parts(name, tmp_path):
    """Each array step picture is non-blank and carries the highlight colour;
    the page embeds it (so it opens offline)."""
    import numpy as np
    from PIL import Image

    from conftest import run_cli

    result = run_cli("export", "--only", "instructions", "--no-cache", "--design",
                     str(HARDWARE / name / f"{name}.toml"), "--out", str(tmp_path / "ex"))
    assert result.returncode == 0, result.stderr
    book = tmp_path / "ex" / "instructions"
    pictures = sorted(book.glob("step_*.png"))
    keys = {p.stem.split("_", 2)[2] for p in pictures}
    steps = [st["key"] for st in json.loads((book / "steps.json").read_text())]
    rigs = {k for k in steps if k.startswith("rig-")}
    assert {"array-gauges", "array-wiring", "array-stack", "array-bolts",
            "samples-cast"} | rigs <= keys  # every step that places a part
    page = (book / "index.html").read_text()
    assert page.count("data:image/png;base64,") == len(pictures)
    # a step without a picture says why, naming its parts; the others keep their numbers
    numbered = {int(p.stem.split("_")[1]): p.stem.split("_", 2)[2] for p in pictures}
    said = json.loads((book / "steps.json").read_text())
    for n, st in enumerate(said, start=1):
        if n in numbered:
            assert numbered[n] == st["key"] and st["no_picture"] is None, (n, st["key"])
        else:
            assert st["no_picture"].startswith("No picture: its parts ("), st
            assert st["no_picture"] in page, st["key"]
    readout = next(st for st in said if st["title"] == "Connect the read-out chain")
    assert readout["no_picture"] and "have no 3D model" in readout["no_picture"]
    # every explosion vector names an instance of the scene its step is drawn in
    _, assemblies = design_assemblies(load_project(HARDWARE / name / f"{name}.toml"))
    for st in json.loads((book / "steps.json").read_text()):
        names = {i.name for i in assemblies[st["scene"]]}
        assert set(st["explode"]) <= names, (st["key"], set(st["explode"]) - names)
        assert all(len(v) == 3 and any(v) for v in st["explode"].values()), st["key"]
    for p in pictures:
        rgb = np.asarray(Image.open(p).convert("RGB")).astype(int)
        assert (rgb < 250).any(axis=2).mean() > 0.05, p  # a model drawn, not a blank frame
        r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
        magenta = (g < 10) & (r > 60) & (abs(r - b) < 8)
        assert magenta.sum() > 50, p  # the step's new parts, in the highlight colour
        # framed on them: not a few pixels in the whole rig (the terminal board, a
        # sample: 3 % of the picture's width when the whole rig was framed)
        rows, cols = np.nonzero(magenta)
        assert max(np.ptp(cols) / rgb.shape[1], np.ptp(rows) / rgb.shape[0]) > 0.1, p


def test_pdf_has_a_page_and_every_step_title(book):
    from pypdf import PdfReader

    _, _, out, _ = book
    steps = json.loads((out / BOOK_DATA).read_text())
    text = " ".join(page.extract_text() for page in PdfReader(out / BOOK_PDF).pages)
    for s in steps:
        assert s["title"] in text


def test_every_array_part_module_names_the_step_that_consumes_its_parts(book):
    """The array's part modules (and the terminal board's and the sample's)
    declare their build step; the book's titles, tools and notes are theirs."""
    from tactcad.assembly.build_steps import module_steps
    from tactcad.partlib.array import element, fasteners, strain_gauge
    from tactcad.partlib.registry import array_parts_lib

    assert all(part.assembly is not None for part in array_parts_lib().values())
    modules = module_steps()
    assert {b: modules[b].key for b in ("gauge", "element", "spacer", "clamp_plate", "bolt",
                                        "nut", "terminal_board", "sample")} == {
        "gauge": "array-gauges", "element": "array-stack", "spacer": "array-stack",
        "clamp_plate": "array-stack", "bolt": "array-bolts", "nut": "array-bolts",
        "terminal_board": "array-wiring", "sample": "samples-cast"}
    assert "rig_bolt" not in modules  # a rig's screws are its own step's
    _, _, out, _ = book
    steps = {s["key"]: s for s in json.loads((out / BOOK_DATA).read_text())}
    for module in (element, fasteners, strain_gauge):
        declared = module.PART.assembly
        assert steps[declared.key]["title"] == declared.title


def test_a_stack_is_spread_apart_in_its_order():
    """Layers that touch along their common axis (clamp plate, element, spacer,
    element, clamp plate) move apart in their order, a gap between every two;
    a part of the same step away from the stack is lifted on its own."""
    import numpy as np

    from tactcad.catalogue.array_catalogue import Instance
    from tactcad.design.array_plan import Placement
    from tactcad.export.instructions import EXPLODE_FACTOR, explode_offsets

    def box(x, y, z):
        v = np.array([[i * x, j * y, k * z] for i in (0, 1) for j in (0, 1) for k in (0, 1)],
                     dtype=float)
        return v, np.array([[0, 1, 2]])

    meshes = {"plate": box(30, 10, 2), "element": box(30, 10, 3), "spacer": box(30, 10, 1),
              "lone": box(5, 5, 4)}
    layers = [("plate", 0), ("element", 2), ("spacer", 5), ("element", 6), ("plate", 9)]
    inst = [Instance(f"{p}_{n}", p, Placement(0, 0, z)) for n, (p, z) in enumerate(layers)]
    inst.append(Instance("lone_1", "lone", Placement(100, 0, 0)))
    off = explode_offsets(meshes, inst, {"plate", "element", "spacer", "lone"})
    assert np.allclose(off[0], [0, 0, EXPLODE_FACTOR * 2.0])  # the first layer, as alone
    bottoms = [z + off[n][2] for n, (_, z) in enumerate(layers)]
    tops = [b + meshes[p][0][:, 2].max() for b, (p, _) in zip(bottoms, layers)]
    gaps = [lo - hi for hi, lo in zip(tops, bottoms[1:])]
    assert min(gaps) > 0.5, gaps  # in order, none touching
    assert all(np.allclose(off[n][:2], 0) for n in range(len(layers)))
    assert np.allclose(off[5], [0, 0, EXPLODE_FACTOR * 4.0])


def test_a_step_fits_what_the_array_uses_and_says_the_spares_stay_in_the_kit(book):
    project, rows, out, _ = book
    steps = json.loads((out / BOOK_DATA).read_text())
    gauge_row = next(r for r in rows if r.part == "strain_gauge")
    assert gauge_row.spares > 0  # the BOM buys spares (bom.spares)
    step = next(s for s in steps if any(p["part"] == "strain_gauge" for p in s["parts"]))
    fitted = next(p["quantity"] for p in step["parts"] if p["part"] == "strain_gauge")
    assert fitted == len(project.plan.slots) == gauge_row.quantity - gauge_row.spares
    assert any(f"{gauge_row.spares} spare strain_gauge beyond the {fitted} fitted" in n
               for n in step["notes"])


def test_a_step_picture_is_drawn_again_only_when_what_it_shows_changed(tmp_path):
    """A build-book picture is kept by the parts it shows and their places: the same
    picture asked again in another run reads the kept one (no part meshed); a changed
    arm length draws it again."""
    from dataclasses import replace

    import numpy as np

    from tactcad.catalogue.array_catalogue import array_instances, array_parts
    from tactcad.export.instructions import step_picture_kept
    from tactcad.store import Store, keeping_results

    plan = load_project(HARDWARE / "ti_array_2x3" / "ti_array_2x3.toml").plan
    meshed: list[str] = []

    def mesh(spec):
        meshed.append(spec.name)
        vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
        return vertices, np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])

    def picture(p, store_dir):
        specs, instances = array_parts(p), array_instances(p)
        new = {next(iter(specs))}
        with keeping_results(Store(store_dir)):
            return step_picture_kept(instances, specs, {}, new, set(), "Step 1: test", mesh)

    first = picture(plan, tmp_path / "store")
    assert first[0].startswith(b"\x89PNG") and meshed
    meshed.clear()
    assert picture(plan, tmp_path / "store") == first and not meshed
    arms = [s.geometry.arm_length_mm for s in plan.slots]
    arms[-1] += 0.5
    changed = replace(plan, slots=tuple(replace(s, geometry=replace(s.geometry, arm_length_mm=a))
                                        for s, a in zip(plan.slots, arms)))
    picture(changed, tmp_path / "store")
    assert meshed


def test_a_step_without_a_picture_says_why_on_its_page():
    """The read-out chain's parts have no 3D model: its page and PDF entry say so, naming
    them, instead of leaving its picture's number out unsaid."""
    from types import SimpleNamespace

    from tactcad.export.instructions import book_html, no_picture_said

    step = SimpleNamespace(key="readout", title="Connect the read-out chain",
                           sub_assembly="read-out", scene="array", tools=(), consumables=(),
                           notes=(), parts=(("amplifier", 1), ("daq", 1), ("cable", 2)))
    why = no_picture_said(step, {"element", "cable"})
    assert why == "No picture: its parts (amplifier, daq) have no 3D model."
    assert no_picture_said(step, None) == \
        "No picture: its parts (amplifier, daq, cable) have no 3D model."
    page = book_html("d", [step], [], {}, {"readout": why})
    assert '<p class="no-picture">No picture: its parts (amplifier, daq) have no 3D ' \
           'model.</p>' in page
