"""The die's traveller is one a fab can run: its check passes on what tactcad writes and
fails, naming the step, on a traveller without a pad opening, with dicing after the release,
with an etch that has no stop, an implant after the metal, lithography over the posts, or a
mask that is not drawn."""

from __future__ import annotations

from pathlib import Path

import pytest

from tactcad.products.silicon_die.checks.traveller_check import (read_traveller,
                                                                 traveller_checks,
                                                                 traveller_results)
from tactcad.products.silicon_die.design import mems_die as md
from tactcad.products.silicon_die.export.gds_masks import die_polygons, write_die_gds
from tactcad.products.silicon_die.export.traveller import traveller_markdown
from tactcad.partlib.grasper_jaw import jaw_room
from tactcad.studies.inverse_design import Targets


@pytest.fixture(scope="module")
def plan():
    # a soft range at 1.9 mN, within the design-default strength with its model error to spare (its frontier 1.96 mN)
    return md.die_plan(Targets(10.0, (0.05, 0.5), 0.0019), jaw_room("5"))


@pytest.fixture
def written(plan, tmp_path):
    path = tmp_path / "t.md"
    path.write_text(traveller_markdown(plan, 300.0, "t.gds"), encoding="utf-8")
    return path


def _drawn(plan) -> set[str]:
    return {name for name, polys in die_polygons(plan).items() if polys}


def _failed(plan, path: Path) -> dict[str, str]:
    results = traveller_results(read_traveller(path), _drawn(plan), path.name)
    assert len(results) == 6
    return {r.check: r.detail for r in results if not r.passed}


def _rows(path: Path) -> list[str]:
    return path.read_text(encoding="utf-8").splitlines()


def _row_of(lines: list[str], step: str) -> int:
    return next(i for i, line in enumerate(lines) if line.startswith("|")
                and line.split("|")[2].strip() == step)


def test_the_written_traveller_passes_against_its_gds(plan, written, tmp_path):
    assert _failed(plan, written) == {}
    gds = write_die_gds(plan, tmp_path / "t.gds")
    results = traveller_checks(written, gds)
    assert results and all(r.passed for r in results), [r.detail for r in results]


def test_a_traveller_without_its_pad_opening_leaves_the_pads_covered(plan, written):
    lines = _rows(written)
    del lines[_row_of(lines, "pad opening")]
    written.write_text("\n".join(lines), encoding="utf-8")
    failed = _failed(plan, written)
    assert "hard mask" in failed["traveller_pads_open"]
    assert "pad_open" in failed["traveller_masks"]  # drawn, and no step uses it


def test_dicing_after_the_release_is_refused(plan, written):
    lines = _rows(written)
    i, j = _row_of(lines, "dicing"), _row_of(lines, "release")
    a, b = lines[i].split("|"), lines[j].split("|")
    a[1], b[1] = b[1], a[1]  # the numbers swapped: the release now comes first
    lines[i], lines[j] = "|".join(a), "|".join(b)
    written.write_text("\n".join(lines), encoding="utf-8")
    assert "free beams" in _failed(plan, written)["traveller_dicing"]


def test_an_etch_without_a_stop_is_refused(plan, written):
    lines = _rows(written)
    i = _row_of(lines, "front DRIE")
    cells = lines[i].split("|")
    cells[6] = " - "
    lines[i] = "|".join(cells)
    written.write_text("\n".join(lines), encoding="utf-8")
    assert "front DRIE" in _failed(plan, written)["traveller_etch_stops"]


def test_an_implant_after_the_metal_and_lithography_over_the_posts_are_refused(plan, written):
    lines = _rows(written)
    for step in ("implant", "contact"):  # both moved behind the posts (renumbered)
        i = _row_of(lines, step)
        cells = lines[i].split("|")
        cells[1] = f" {100 + len(step)} "
        lines[i] = "|".join(cells)
    written.write_text("\n".join(lines), encoding="utf-8")
    failed = _failed(plan, written)
    assert "implant" in failed["traveller_implants"]
    assert "posts" in failed["traveller_litho_order"]


def test_a_mask_no_layer_draws_is_named(plan, written):
    text = written.read_text(encoding="utf-8").replace("| posts | tip (6) |",
                                                       "| posts | bumps (12) |")
    written.write_text(text, encoding="utf-8")
    assert "bumps" in _failed(plan, written)["traveller_masks"]


def test_an_unreadable_traveller_is_one_failed_check(tmp_path, plan):
    path = tmp_path / "t.md"
    path.write_text("# no table\n", encoding="utf-8")
    gds = write_die_gds(plan, tmp_path / "t.gds")
    [result] = traveller_checks(path, gds)
    assert not result.passed and "no step table" in result.detail
