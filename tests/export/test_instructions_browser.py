"""The build book opens from file:// in headless Chromium with the network off."""

from __future__ import annotations

import json
from pathlib import Path

from tactcad.assembly.inventory import design_assemblies
from tactcad.design.project import load_project
from tactcad.export.instructions import BOOK_DATA, BOOK_PAGE, write_book

HARDWARE = Path(__file__).resolve().parents[2] / "hardware"


def test_book_opens_offline_in_chromium(tmp_path, browser):
    project = load_project(HARDWARE / "ti_array_2x3" / "ti_array_2x3.toml")
    write_book(project, tmp_path, lambda line: None, design_assemblies(project))
    steps = json.loads((tmp_path / BOOK_DATA).read_text())
    with browser() as page:
        page.goto((tmp_path / BOOK_PAGE).resolve().as_uri())
        assert page.errors == []
        shown = page.eval_on_selector_all("section[data-step]", "els => els.map(e => e.id)")
        assert shown == [s["key"] for s in steps]
        assert page.locator("h1").inner_text().startswith("Build book")
