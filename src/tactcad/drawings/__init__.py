"""Fabrication drawings of every fabricated part: one SVG each and one PDF.

Writes into the export folder:

* ``drawings/<part>.svg``: A3 landscape sheet (see :mod:`tactcad.drawings.compose`),
  views projected from the part's solid, dimensions from the plan, title block;
* ``drawings/drawings.pdf``: all sheets, one page per part in catalogue order,
  converted from the SVGs (svglib + reportlab, standard PDF fonts, fixed
  creation date and document id);
* ``images/<first element>_drawing.png``: the first element's sheet rendered
  from the PDF at 150 dpi (pypdfium2).

Same design, same versions of the tools: same bytes.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Callable

DRAWING_DIR = "drawings"
PDF_NAME = f"{DRAWING_DIR}/drawings.pdf"
PNG_DPI = 150


def drawing_name(part: str) -> str:
    """Export-relative path of a part's drawing, e.g. ``drawings/spacer.svg``."""
    return f"{DRAWING_DIR}/{part}.svg"


def drawing_png_name(part: str) -> str:
    """Export-relative path of a part's rendered drawing, ``images/<part>_drawing.png``."""
    return f"images/{part}_drawing.png"


def fabricated_parts(plan, assembled=None):
    """(part specs to draw in sheet order, quantity of each counted from the
    assemblies' instances, see :func:`tactcad.export.bom.part_quantities`). Parts
    placed in no assembly are not drawn.

    Args:
        assembled: the result of :func:`tactcad.export.bom.design_assemblies`, if
            already at hand.
    """
    from tactcad.export.bom import design_assemblies, part_quantities

    specs, assemblies = assembled or design_assemblies(plan)
    qty = part_quantities(assemblies)
    return [s for s in specs.values() if s.kind == "fabricated" and qty.get(s.name, 0) > 0], qty


def svgs_to_pdf(svg_texts: list[str], target: Path, title: str = "") -> None:
    """One PDF page per SVG, each page the SVG's own size.

    The PDF is written in reportlab's invariant mode (fixed creation date and
    document id), so the same SVGs give the same bytes.

    Raises:
        ValueError: an SVG could not be parsed.
    """
    import io

    from reportlab.graphics import renderPDF
    from reportlab.pdfgen import canvas
    from svglib.svglib import svg2rlg

    drawings = []
    for k, text in enumerate(svg_texts, start=1):
        dr = svg2rlg(io.BytesIO(text.encode("utf-8")))
        if dr is None:
            raise ValueError(f"SVG page {k} could not be parsed")
        drawings.append(dr)
    c = canvas.Canvas(str(target), invariant=1, pageCompression=1)
    c.setTitle(title)
    c.setAuthor("tactcad")
    c.setCreator("tactcad")
    c.setProducer("tactcad (svglib, reportlab)")
    for dr in drawings:
        c.setPageSize((dr.width, dr.height))
        renderPDF.draw(dr, c, 0, 0)
        c.showPage()
    c.save()


def write_drawing_files(plan, staging: Path, log: Callable[[str], None]) -> list[dict]:
    """Write the drawings, the PDF and the first element's drawing PNG into
    ``staging`` (see module doc).

    Returns:
        File records ``{"path", "part", "kind", ...}``: ``drawing-svg`` (with
        ``quantity`` and ``scale``), ``drawing-pdf`` (with ``pages``) and
        ``image-png``.
    """
    from tactcad.parts.registry import PartCache
    from tactcad.export.bom import design_assemblies
    from tactcad.atomic import write_atomic, write_bytes_atomic
    from tactcad.export.render import pdf_page_png
    from tactcad.drawings.compose import compose
    from tactcad.drawings.views import scale_text

    t0 = time.perf_counter()
    assembled = design_assemblies(plan)
    cache = PartCache(plan, assembled[0])
    parts, qty = fabricated_parts(plan, assembled)
    records: list[dict] = []
    texts = []
    for k, spec in enumerate(parts, start=1):
        d = compose(plan, spec, cache.solid(spec.name), qty[spec.name], k, len(parts))
        text = d.sheet.svg()
        texts.append(text)
        rel = drawing_name(spec.name)
        write_bytes_atomic(staging / rel, text.encode("utf-8"))
        records.append({"path": rel, "part": spec.name, "kind": "drawing-svg",
                        "quantity": qty[spec.name], "scale": scale_text(d.scale),
                        "sheet": k})
    write_atomic(staging / PDF_NAME,
                 lambda tmp: svgs_to_pdf(texts, tmp, f"{plan.name} fabrication drawings"))
    records.append({"path": PDF_NAME, "part": "drawings", "kind": "drawing-pdf",
                    "pages": len(texts)})
    elements = [s for s in parts if s.builder == "element"]
    if elements:
        page = parts.index(elements[0])
        rel = drawing_png_name(elements[0].name)
        write_atomic(staging / rel, lambda tmp: pdf_page_png(staging / PDF_NAME, page, tmp, PNG_DPI))
        records.append({"path": rel, "part": elements[0].name, "kind": "image-png"})
    log(f"  wrote {len(texts)} drawings in {DRAWING_DIR}/ and {PDF_NAME} "
        f"({time.perf_counter() - t0:.1f} s)")
    return records
