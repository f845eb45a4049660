"""scripts/docs_images.py, what `make docs-images` runs: the pictures of the pages
made from an export (the drawing sheets found by their drawing number)."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "docs_images.py"


def load_script():
    spec = importlib.util.spec_from_file_location("docs_images", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.slow
def test_pictures_come_from_the_export(example_exported, tmp_path):
    script = load_script()
    # the atlases judge designs for minutes and are drawn by the atlas's own figure
    # function, tested with the atlas (tests/commands/test_atlas_cmd.py)
    assert script.main([str(example_exported), "--images", str(tmp_path), "--no-atlas"]) == 0
    made = {p.name for p in tmp_path.glob("*.png")}
    assert {"array.png", "cart_drawing.png", "assembly_sheet.png", "table2_models.png",
            "evaluate_fig7_halfspace.png"} <= made
    assert any(name.endswith("_drawing.png") and name != "cart_drawing.png" for name in made)
    pdf = example_exported / "drawings" / "drawings.pdf"
    design = json.loads((example_exported / "manifest.json").read_text())["design"]["name"]
    cart, array = (script.sheet_page(pdf, f"{design}-{part}") for part in ("cart", "array"))
    assert cart != array
    with pytest.raises(SystemExit, match="no page"):
        script.sheet_page(pdf, f"{design}-no_such_part")
