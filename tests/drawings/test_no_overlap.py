"""Drawings never overlap: for random designs of the accepted domain
(:func:`tactcad.design.domain.draw_design`) and for the sizes that once
overlapped, the drawing sheets an export writes pass the ``drawings`` group of
``tactcad check`` (no text over a line or another text) with no failure."""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from tactcad.checks.groups import CHECK_GROUPS, CheckContext
from tactcad.design.array_plan import DEFAULT_DESIGN, with_overrides
from tactcad.design.domain import draw_design
from tactcad.design.project import project_from_data, project_of, project_with_design_data
from tactcad.design.rig_plan import default_rigs_data
from tactcad.design.scene_specs import DEFAULT_SCENES
from tactcad.vocabulary.schema import Problems, read_toml

from conftest import EXAMPLE_DESIGN
from depth import draws

#: Accepted designs drawn over the domain: 30 in ``make test-deep``, a share of them (fresh
#: seeds past the few-designs test's) in ``make test``; about 5 s each.
DOMAIN_DESIGNS = draws(6, 30)

#: The 2 x 6 titanium insert for a 10 mm grasper jaw (issue 41): the non-paper
#: example with six columns on thinner sheet, a finer pitch and a narrower tip.
GRASPER = {"array.columns": 6, "sheet.thickness_mm": 1.0, "array.pitch_mm": 2.0,
           "element.tip_width_mm": 1.0,
           "arms.lengths_mm": [19.605, 6.196, 19.605] * 4}


def drawings_check(project, folder: Path, parts: tuple[str, ...] = ()) -> tuple[int, list[str]]:
    """Draw the project's sheets as the export draws them (every fabricated
    part's, numbered as the export's BOM, and the assembly sheet; of ``parts``
    only, when given) into ``folder``/drawings and run the ``drawings`` check
    group on them: (sheets checked, the failing checks' lines). No manifest is
    written: the design studies it runs are other tests'."""
    from tactcad.assembly.inventory import design_assemblies, fabricated_parts
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.drawings.assembly import compose_assembly
    from tactcad.drawings.compose import compose
    from tactcad.export.bom import complete_kit
    from tactcad.solids.cache import PartCache

    plan, cache = project.plan, PartCache(project.plan)
    inventory = design_assemblies(project)
    specs, quantity = fabricated_parts(project, inventory)
    (folder / "drawings").mkdir(parents=True)
    sheets = {s.name: lambda s=s: compose(plan, s, cache.solid(s), quantity[s.name]).sheet
              for s in specs}
    items = {r.part: r.item for r in complete_kit(project, inventory)}
    sheets["assembly"] = lambda: compose_assembly(
        plan, {n: cache.solid(s) for n, s in array_parts(plan).items()}, items).sheet
    for name, draw in sheets.items():
        if not parts or name in parts:
            (folder / "drawings" / f"{name}.svg").write_text(draw().svg(), encoding="utf-8")
    context = CheckContext(plan, folder, cache=cache, project=project)
    results = [r for _, found in CHECK_GROUPS["drawings"].run(context) for r in found]
    return len(results), [r.line() for r in results if not r.passed]


def design_file_project(path: Path, overrides: dict):
    """The project of a design file with ``--set`` style ``overrides``."""
    return project_with_design_data(with_overrides(read_toml(path, "design file"), overrides), path)


def domain_projects(seeds):
    """(seed, project) of each accepted in-domain draw of ``seeds``, with the
    default rigs and scenes files."""
    rigs, scenes = default_rigs_data(), read_toml(DEFAULT_SCENES, "scenes file")
    for seed in seeds:
        rng = random.Random(seed)
        data = draw_design(rng.uniform, rng.choice, name=f"domain{seed}")
        problems = Problems("domain.toml")
        plan, rig_design, scene_specs = project_from_data(data, rigs, scenes, problems,
                                                          source="domain.toml")
        if not problems:  # a refused draw is the domain test's (tests/design), not this one
            yield seed, project_of(plan, rig_design, scene_specs, scenes)


@pytest.mark.parametrize("overrides, parts", [
    ({"element.tip_height_mm": 1.783}, ("element_a4mm",)),       # '2 ±0.02' over '1.783'
    ({"element.notch_radius_mm": 1.339}, ("element_a4mm",)),     # 'R1.339 ±0.01' on detail A
], ids=["tip_height_1.783", "notch_radius_1.339"])
def test_the_paper_designs_element_sizes_that_overlapped_draw_clear(overrides, parts, tmp_path):
    n, failed = drawings_check(design_file_project(DEFAULT_DESIGN, overrides), tmp_path, parts)
    assert n == len(parts) and failed == []


#: Names of the name rule's most characters (64): one that breaks at its underscores, one of
#: its widest letter that fits on no two lines of the drawing number's cell.
LONGEST_NAMES = {"underscores": "abcdefghij_" * 5 + "abcdefghi", "widest": "W" * 64}
#: The comb example (issue: a 42-character atlas name failed check on every sheet).
COMB_EXAMPLE = DEFAULT_DESIGN.parents[1] / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.mark.parametrize("kind", sorted(LONGEST_NAMES))
@pytest.mark.parametrize("design, parts", [
    (EXAMPLE_DESIGN, ("terminal_board", "assembly")),
    (COMB_EXAMPLE, ("comb_row1", "comb_spacer", "assembly")),
], ids=["example", "comb"])
def test_a_design_name_of_the_rules_64_characters_fits_every_title_block(design, parts, kind,
                                                                         tmp_path):
    """The drawing number (``<name>-<part>``) ran 3 mm past its cell and the frame at 42
    characters: it is set smaller, then on two lines, then shortened in its middle, the
    sheet's SVG title keeping the name whole."""
    import xml.etree.ElementTree as ET

    name = LONGEST_NAMES[kind]
    assert len(name) == 64
    project = design_file_project(design, {"design.name": name})
    n, failed = drawings_check(project, tmp_path, parts)
    assert n == len(parts) and failed == []
    for part in parts:
        svg = (tmp_path / "drawings" / f"{part}.svg").read_text(encoding="utf-8")
        root = ET.fromstring(svg)
        texts = {el.get("id"): el.text for el in root.iter("{http://www.w3.org/2000/svg}text")}
        number = texts["tb-number"] + texts["tb-number-2"]
        if kind == "underscores":
            assert number == f"{name}-{part}"
        else:
            head, tail = number.split("…")
            assert name.startswith(head) and f"{name}-{part}".endswith(tail)
            assert tail.endswith(f"W-{part}") and len(head) > 10
        assert name in root.findtext("{http://www.w3.org/2000/svg}title")


@pytest.mark.slow  # a whole chain through the command line or an export
def test_the_2x6_titanium_grasper_insert_draws_clear(tmp_path):
    """Every sheet of the grasper insert: both element sheets (0.09 mm over a
    line), the indenter (2.64 mm) and the terminal board (14 overlaps, H16 on
    H17 among them, its 24 holes at 2:1) once failed."""
    project = design_file_project(EXAMPLE_DESIGN, GRASPER)
    n, failed = drawings_check(project, tmp_path)
    assert n >= 15 and failed == []
    board = (tmp_path / "drawings" / "terminal_board.svg").read_text(encoding="utf-8")
    assert "5:1" in board          # its hole table beside the views lets the board be drawn larger


#: The 2 x 8 palpation strip (a lab's design): 32 terminal holes and a 17-row slot map.
PALPATION_STRIP = {"array.columns": 8, "sheet.thickness_mm": 0.8, "readout.grid_width_mm": 0.8,
                   "array.pitch_mm": 1.0,
                   "element.tip_width_mm": 0.8, "clamp.bolt_size": "M1.6",
                   "element.arm_height_mm": 4.9, "element.overall_length_mm": 31.0,
                   "arms.lengths_mm": [19.543] * 3 + [6.905] + [19.543] * 7 + [6.905]
                   + [19.543] * 4, "arms.reference_elements": [4, 12]}


@pytest.mark.slow  # a whole design's drawings
def test_the_2x8_palpation_strip_draws_clear(tmp_path):
    """The strip's slot map once covered the view along the bolts (41 overlaps) and its
    terminal board's 32 hole labels crowded a 2:1 view under a one-block table (51)."""
    project = design_file_project(EXAMPLE_DESIGN, PALPATION_STRIP)
    n, failed = drawings_check(project, tmp_path, ("terminal_board", "assembly"))
    assert n == 2 and failed == []
    board = (tmp_path / "drawings" / "terminal_board.svg").read_text(encoding="utf-8")
    assert "5:1" in board  # its table in two blocks under the views, the notes over the title


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_few_random_designs_of_the_domain_draw_clear(tmp_path):
    checked = 0
    for seed, project in domain_projects(range(3)):
        n, failed = drawings_check(project, tmp_path / str(seed))
        assert failed == [], f"design seed {seed}"
        checked += n
    assert checked >= 45


@pytest.mark.slow
def test_thirty_random_designs_of_the_domain_draw_clear(tmp_path):
    """N accepted designs drawn over the whole domain (seeds from 1000): every sheet of
    each passes the drawings check. N is :data:`DOMAIN_DESIGNS`: the first 6 of the
    same seeds in ``make test``, all 30 in ``make test-deep`` (nightly)."""
    designs = sheets = 0
    failures = {}
    for seed, project in domain_projects(range(1000, 1040)):
        n, failed = drawings_check(project, tmp_path / str(seed))
        designs, sheets = designs + 1, sheets + n
        if failed:
            failures[seed] = failed
        if designs == DOMAIN_DESIGNS:
            break
    print(f"drawings check: N = {designs} random in-domain designs, {sheets} sheets, "
          f"{len(failures)} with overlaps")
    assert designs == DOMAIN_DESIGNS and failures == {}


def test_balloon_leaders_are_ordered_so_that_none_crosses_its_neighbour():
    """Two parts seen at one x, one over the other, their balloons in a row to
    the right: the left balloon takes the upper part, or the leaders cross and
    one runs through the other's number."""
    from tactcad.drawings.assembly import segments_cross, uncrossed

    row = [(100.0, 20.0), (111.0, 20.0)]
    anchors = {"lower": (80.0, 80.0), "upper": (80.0, 40.0)}
    assert segments_cross(row[0], anchors["lower"], row[1], anchors["upper"])
    order = uncrossed(["lower", "upper"], row, anchors)
    assert order == ["upper", "lower"]
    assert not segments_cross(row[0], anchors[order[0]], row[1], anchors[order[1]])


#: A stacked array the inverse design writes for a thin copper-beryllium sheet (``tactcad
#: design --material CuBe-C17200-TF00 --columns 12``: M3 bolts, 2 mm sheet, 2.2 mm pitch),
#: which holds every stacked column count; its terminal board has 4 x columns holes.
THIN_SHEET_M3 = {"sheet.thickness_mm": 2.0, "array.pitch_mm": 2.2, "clamp.bolt_size": "M3",
                 "clamp.bolt_spacing_mm": 6.6, "clamp.bridge_height_mm": 4.4,
                 "element.arm_height_mm": 5.0, "element.base_height_mm": 10.4,
                 "element.overall_length_mm": 34.0}


def terminal_board_overlaps(columns: int, pitch_mm: float) -> list[str]:
    """The overlaps on the terminal board's sheet alone (composed as the export composes
    it, measured as ``tactcad check`` measures it) for :data:`THIN_SHEET_M3` at
    ``columns`` columns and a board of terminal pitch ``pitch_mm``."""
    from tactcad.catalogue.rig_catalogue import rig_parts
    from tactcad.checks.sheet_overlap import layout_of_svg, sheet_overlaps
    from tactcad.drawings.compose import compose
    from tactcad.solids.build import build_part

    overrides = {**THIN_SHEET_M3, "array.columns": columns,
                 "arms.lengths_mm": [19.847] * 2 * columns}
    rigs = default_rigs_data()
    rigs["terminal_board"]["pitch_mm"] = pitch_mm
    problems = Problems("board.toml")
    plan, rig_design, _ = project_from_data(with_overrides(read_toml(DEFAULT_DESIGN, "design file"),
                                                           overrides),
                                            rigs, read_toml(DEFAULT_SCENES, "scenes file"),
                                            problems, source="board.toml")
    assert not problems
    spec = rig_parts(plan, rig_design)["terminal_board"]
    svg = compose(plan, spec, build_part(spec), 1).sheet.svg()
    return [o.text() for o in sheet_overlaps(layout_of_svg(svg, "terminal_board.svg"))]


@pytest.mark.parametrize("columns, pitch_mm", [(12, 1.7), (11, 2.54), (2, 2.54)],
                         ids=["12_columns_finest_pitch", "11_columns", "2_columns"])
def test_the_terminal_board_labels_its_holes_clear_at_every_stacked_column_count(columns, pitch_mm):
    """A 2 x 12 array's board (48 holes at 2:1, a pitch narrower than a hole label) once
    put five labels under other labels' leaders and failed its own drawings check. The
    most columns at the finest pitch (the 2.54 mm pitch's labels sit wider apart), an odd
    count and the fewest."""
    assert terminal_board_overlaps(columns, pitch_mm) == []


@pytest.mark.parametrize("pitch_mm, scale", [(2.54, 2.0), (1.7, 2.0), (2.54, 5.0)])
def test_hole_labels_of_a_close_row_stand_a_label_apart_with_both_ends_labelled(pitch_mm, scale):
    from tactcad.drawings.dimensioning import labelled_holes
    from tactcad.drawings.drawing import Hole2D
    from tactcad.drawings.sheet import DIM_TEXT_MM, text_width

    ordered = [Hole2D(k * pitch_mm, y, 1.0) for y in (0.0, pitch_mm) for k in range(24)]
    numbers = labelled_holes(ordered, scale)
    label_mm = text_width("H48", DIM_TEXT_MM)
    for row in (range(1, 25), range(25, 49)):
        shown = [i for i in numbers if i in row]
        assert shown[0] == row[0] and shown[-1] == row[-1]
        gaps = [(ordered[b - 1].x - ordered[a - 1].x) * scale for a, b in zip(shown, shown[1:])]
        assert min(gaps) > label_mm
        # no stretch left bare that had room for another label
        assert max(gaps) < 2 * (label_mm + pitch_mm * scale)
    if pitch_mm * scale > label_mm + 1.0:
        assert numbers == list(range(1, 49))


def test_a_board_that_labels_some_holes_says_how_the_numbers_run():
    """Where the view labels only some holes, the table's title says the numbers run along
    each row, so H2 is found between H1 and H3; a board with every hole labelled says
    nothing more."""
    import re

    from tactcad.catalogue.rig_catalogue import rig_parts
    from tactcad.drawings.compose import compose
    from tactcad.solids.build import build_part

    def board_svg(columns: int) -> str:
        overrides = {**THIN_SHEET_M3, "array.columns": columns,
                     "arms.lengths_mm": [19.847] * 2 * columns}
        problems = Problems("board.toml")
        plan, rig_design, _ = project_from_data(
            with_overrides(read_toml(DEFAULT_DESIGN, "design file"), overrides),
            default_rigs_data(), read_toml(DEFAULT_SCENES, "scenes file"), problems,
            source="board.toml")
        spec = rig_parts(plan, rig_design)["terminal_board"]
        return compose(plan, spec, build_part(spec), 1).sheet.svg()

    def labels(svg: str) -> int:
        return len(re.findall(r'id="hole-label-\d+"', svg))

    close, roomy = board_svg(12), board_svg(2)
    assert labels(close) < 48 and "numbers run along each row" in close
    assert labels(roomy) == 8 and "numbers run along each row" not in roomy
