"""Refresh the pictures of README and the documentation (docs/images) from an export.

``make docs-images`` runs it after ``make export``: every picture the pages
show is made by tactcad itself, from the export folder given:

* ``array.png`` and ``element_a4mm_drawing.png``: the export's own images
  (``images/*.png``);
* ``cart_drawing.png`` and ``assembly_sheet.png``: their pages of
  ``drawings/drawings.pdf``, found by the drawing number in the title block
  (``<design>-<part>``), rasterised as the export rasterises its drawing image;
* ``review_page.png``: the review page opened offline in headless Chromium
  (``--review``; skipped with a note where no Chromium is installed);
* ``table2_models.png`` and ``evaluate_fig7_halfspace.png``: the plots of
  ``tactcad table2`` and ``tactcad evaluate`` on the paper's design;
* ``grasper_open.png`` and ``grasper_closed.png``: the grasper example's scenes
  ``grasper-open`` and ``grasper-closed`` rendered from the side (the export's renderer);
* ``die_in_jaw.png``, ``die_masks.png`` and ``die_drawing.png``: the silicon die example's
  mount in the 5 mm jaw, its masks (KLayout) and its drawing (the SVG in headless
  Chromium; skipped with a note where none is installed), from ``tactcad die``.

* ``atlas_jaw5.png`` and ``atlas_jaw10.png``: ``tactcad atlas`` of the 5 mm jaw (the die,
  :data:`ATLAS_POINTS` [5] points) and of the 10 mm jaw (the die and the titanium comb,
  :data:`ATLAS_POINTS` [10] points), drawn as the command draws its figure.

The design chart (fem3d, minutes) and the diff overlay (two exports) are made
by the commands their pages name.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IMAGES = ROOT / "docs" / "images"
PAPER = ROOT / "hardware" / "macro_array" / "macro_array.toml"
#: Sheets shown in the pages: picture name -> the part whose drawing it is.
SHEETS = {"cart_drawing.png": "cart", "assembly_sheet.png": "array"}
PNG_DPI = 110
GRASPER = ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
#: Grasper scenes shown in the pages: picture name -> scene.
GRASPER_SCENES = {"grasper_open.png": "grasper-open", "grasper_closed.png": "grasper-closed"}
DIE = ROOT / "hardware" / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml"
#: The tutorial's atlases: jaw -> (target points, the comb materials judged).
ATLAS_POINTS = {"5": (96, []), "10": (12, ["Ti-6Al-4V-annealed"])}


def sheet_page(pdf: Path, drawing_number: str) -> int:
    """The page of ``pdf`` whose title block carries ``drawing_number``."""
    import pypdfium2

    document = pypdfium2.PdfDocument(str(pdf))
    for index in range(len(document)):
        if drawing_number in document[index].get_textpage().get_text_range():
            return index
    raise SystemExit(f"docs_images: no page of {pdf} carries the drawing number {drawing_number}")


def copy_export_images(exports: Path, images: Path) -> None:
    for picture in sorted((exports / "images").glob("*.png")):  # array.png, <part>_drawing.png
        shutil.copyfile(picture, images / picture.name)


def render_sheets(exports: Path, images: Path) -> None:
    from tactcad.export.render import pdf_page_png

    design = json.loads((exports / "manifest.json").read_text(encoding="utf-8"))["design"]["name"]
    pdf = exports / "drawings" / "drawings.pdf"
    for picture, part in SHEETS.items():
        pdf_page_png(pdf, sheet_page(pdf, f"{design}-{part}"), images / picture, PNG_DPI)


def screenshot_review(exports: Path, images: Path) -> None:
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        print("docs_images: no chromium installed; review_page.png left as it was", file=sys.stderr)
        return
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium,
                                    args=["--no-sandbox", "--use-gl=swiftshader"])
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        page.goto((exports / "review" / "index.html").resolve().as_uri())
        page.wait_for_timeout(4000)  # the first frame of software WebGL, with margin
        page.screenshot(path=str(images / "review_page.png"))
        browser.close()


def paper_plots(images: Path) -> None:
    from tactcad.cli import main

    for argv in (["table2", "--plot", str(images / "table2_models.png")],
                 ["evaluate", "--stiffness", "table1", "--plot",
                  str(images / "evaluate_fig7_halfspace.png")]):
        with contextlib.redirect_stdout(io.StringIO()):  # the plot is the output wanted
            code = main([*argv, "--design", str(PAPER), "--quiet"])
        if code != 0:
            raise SystemExit(f"docs_images: tactcad {' '.join(argv)} exited {code}")


def grasper_scenes(images: Path) -> None:
    """The grasper example's jaw scenes, side-on (elevation 0), as the export renders its array."""
    from tactcad.assembly.scene_solver import build_scene
    from tactcad.design.project import load_project
    from tactcad.export.render import render_assembly_png
    from tactcad.solids.cache import PartCache

    project = load_project(GRASPER)
    cache = PartCache(project.plan)
    for name, scene_name in GRASPER_SCENES.items():
        scene, _ = build_scene(project, scene_name, cache)
        meshes = {i.part: cache.mesh(scene.specs[i.part]) for i in scene.instances}
        colors = {n: scene.specs[n].color for n in meshes}
        render_assembly_png(meshes, scene.instances, colors, images / name,
                            f"{project.plan.name}: scene {scene_name} (side view)", elev=0.0,
                            azim=0.0)


def die_pictures(images: Path) -> None:
    """The die example's jaw scene, masks and drawing, from a ``tactcad die`` run."""
    import subprocess
    import tempfile

    from tactcad.cli import main

    with tempfile.TemporaryDirectory() as tmp:
        with contextlib.redirect_stdout(io.StringIO()):
            code = main(["die", "--design", str(DIE), "--out", tmp, "--quiet"])
        if code != 0:
            raise SystemExit(f"docs_images: tactcad die exited {code}")
        name = DIE.stem
        shutil.copyfile(Path(tmp) / f"{name}_in_jaw.png", images / "die_in_jaw.png")
        shutil.copyfile(Path(tmp) / f"{name}_masks.png", images / "die_masks.png")
        chromium = shutil.which("chromium") or shutil.which("chromium-browser")
        if chromium is None:
            print("docs_images: no Chromium: die_drawing.png left as it was")
            return
        subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                        f"--screenshot={images / 'die_drawing.png'}", "--window-size=1600,1130",
                        (Path(tmp) / f"{name}_drawing.svg").as_uri()],
                       check=True, capture_output=True, timeout=120)


def atlas_pictures(images: Path) -> None:
    """The atlases of the 5 and 10 mm jaws (:data:`ATLAS_POINTS`), each run by ``tactcad
    atlas`` on two local workers and drawn to PNG by the command's own figure function; the
    run's summary printed, for the tutorial's figures."""
    import tempfile

    from tactcad.cli import main
    from tactcad.commands.atlas import front_figure, read_table

    for jaw, (points, materials) in ATLAS_POINTS.items():
        with tempfile.TemporaryDirectory() as tmp:
            argv = ["atlas", "--jaw", jaw, "--points", str(points), "--no-cache", "--out",
                    tmp, "--quiet"] + [w for m in materials for w in ("--material", m)]
            code = main(argv)
            if code != 0:
                raise SystemExit(f"docs_images: tactcad {' '.join(argv)} exited {code}")
            summary = json.loads((Path(tmp) / "atlas.json").read_text(encoding="utf-8"))
            records = read_table(Path(tmp) / "atlas.parquet") or []
            front_figure(records, summary["front"], images / f"atlas_jaw{jaw}.png", jaw)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("exports", type=Path, help="an export folder of the paper's design")
    parser.add_argument("--images", type=Path, default=IMAGES,
                        help="the folder the pictures go to (default docs/images)")
    parser.add_argument("--review", action="store_true",
                        help="also screenshot the review page (needs Chromium)")
    parser.add_argument("--no-atlas", action="store_true",
                        help="leave the two jaws' atlases (minutes of design judging) as they are")
    args = parser.parse_args(argv)
    copy_export_images(args.exports, args.images)
    render_sheets(args.exports, args.images)
    if args.review:
        screenshot_review(args.exports, args.images)
    paper_plots(args.images)
    grasper_scenes(args.images)
    die_pictures(args.images)
    if not args.no_atlas:
        atlas_pictures(args.images)
    print(f"docs_images: refreshed {args.images}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
