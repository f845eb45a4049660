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
    _, rows, out, records = book
    steps = json.loads((out / BOOK_DATA).read_text())
    assert records[0]["steps"] == len(steps)
    in_steps = [p["part"] for s in steps for p in s["parts"]]
    assert sorted(in_steps) == sorted(r.part for r in rows)
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


def test_torque_grows_with_size():
    # M3 class 8.8 with K = 0.2: about 1.3 N m (common tables 1.2-1.3 N m)
    assert 1.1 < tightening_torque_Nm(3, 0.5) < 1.4
    assert tightening_torque_Nm(2, 0.4) < tightening_torque_Nm(3, 0.5) < tightening_torque_Nm(4, 0.7)


@pytest.mark.parametrize("name", ["macro_array", "ti_array_2x3"])
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
    assert {"array-gauges", "array-stack", "array-bolts"} <= keys
    page = (book / "index.html").read_text()
    assert page.count("data:image/png;base64,") == len(pictures)
    for p in pictures:
        rgb = np.asarray(Image.open(p).convert("RGB")).astype(int)
        assert (rgb < 250).any(axis=2).mean() > 0.05, p  # a model drawn, not a blank frame
        r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
        magenta = (g < 10) & (r > 60) & (abs(r - b) < 8)
        assert magenta.sum() > 50, p  # the step's new parts, in the highlight colour


def test_pdf_has_a_page_and_every_step_title(book):
    from pypdf import PdfReader

    _, _, out, _ = book
    steps = json.loads((out / BOOK_DATA).read_text())
    text = " ".join(page.extract_text() for page in PdfReader(out / BOOK_PDF).pages)
    for s in steps:
        assert s["title"] in text
