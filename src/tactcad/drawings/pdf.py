"""All drawing sheets in one PDF (svglib + reportlab)."""

from __future__ import annotations

import io
from pathlib import Path

import reportlab.rl_config

# reportlab checks every attribute set on every shape (a developer's aid that costs a third
# of a sheet's conversion); svglib's shapes need no checking. Set before reportlab.graphics
# is first imported, which reads it when its classes are made.
reportlab.rl_config.shapeChecking = 0

from reportlab.graphics import renderPDF  # noqa: E402 - after the setting above
from reportlab.pdfgen import canvas  # noqa: E402
from svglib.svglib import svg2rlg  # noqa: E402

from tactcad.store import Store, content_key


def svgs_to_pdf(svg_texts: list[str], target: Path, title: str = "",
                store: Store | None = None) -> None:
    """One PDF page per SVG, each page the SVG's own size.

    The PDF is written in reportlab's invariant mode (fixed creation date and
    document id), so the same SVGs give the same bytes.

    Args:
        store: where each sheet's conversion (svglib) is kept for the next
            run; a PDF with one changed sheet then converts only that one.

    Raises:
        ValueError: an SVG could not be parsed.
    """
    store = store or Store(None)
    drawings = []
    for k, text in enumerate(svg_texts, start=1):
        dr = store.memo(content_key("svg2rlg", text),
                        lambda: svg2rlg(io.BytesIO(text.encode("utf-8"))))
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
