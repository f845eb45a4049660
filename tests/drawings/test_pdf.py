"""The sheets' PDF drawn straight from their SVG: every element a sheet writes lands where
the SVG puts it, text stays text, the bytes repeat, and a foreign element is refused."""

from __future__ import annotations

import numpy as np
import pytest

from tactcad.drawings.pdf import SheetSvgError, svgs_to_pdf
from tactcad.drawings.sheet import Sheet

DPI = 100
PX_PER_MM = DPI / 25.4


def _sheet() -> Sheet:
    sh = Sheet(size="A4", title="probe")
    sh.line("lines", (20.0, 20.0), (120.0, 20.0), "visible")
    sh.polyline("lines", [(20.0, 60.0), (60.0, 100.0), (100.0, 60.0)], "hidden", closed=True)
    sh.rect("lines", 150.0, 30.0, 40.0, 20.0, "frame")
    sh.circle("lines", (230.0, 120.0), 15.0, "visible")
    sh.arrow("lines", (200.0, 180.0), (1.0, 0.0))
    sh.text("texts", (20.0, 150.0), "WEB 0.25 ±0.02", 5.0, bold=True)
    sh.text("texts", (260.0, 60.0), "UPWARDS", 3.5, rotate=-90.0)
    return sh


def _pixels(pdf_path) -> np.ndarray:
    import pypdfium2 as pdfium

    doc = pdfium.PdfDocument(str(pdf_path))
    try:
        return np.asarray(doc[0].render(scale=DPI / 72).to_pil().convert("L"), dtype=float)
    finally:
        doc.close()


def _dark_at(img: np.ndarray, x_mm: float, y_mm: float, reach_mm: float = 0.6) -> bool:
    r = int(round(reach_mm * PX_PER_MM))
    x, y = int(round(x_mm * PX_PER_MM)), int(round(y_mm * PX_PER_MM))
    return bool((img[y - r:y + r + 1, x - r:x + r + 1] < 128).any())


def test_every_sheet_element_lands_where_the_svg_puts_it(tmp_path):
    from pypdf import PdfReader

    target = tmp_path / "sheet.pdf"
    svgs_to_pdf([_sheet().svg()], target, "probe")
    page = PdfReader(target).pages[0]
    w, h = (float(v) for v in page.mediabox.upper_right)
    assert abs(w - 297 / 25.4 * 72) < 0.01 and abs(h - 210 / 25.4 * 72) < 0.01
    text = page.extract_text()
    assert "WEB 0.25 ±0.02" in text and "UPWARDS" in text
    img = _pixels(target)
    for x, y in [(70.0, 20.0), (40.0, 80.0), (170.0, 30.0), (190.0, 40.0), (245.0, 120.0),
                 (230.0, 105.0), (198.5, 180.0)]:
        assert _dark_at(img, x, y), (x, y)
    for x, y in [(70.0, 40.0), (230.0, 120.0), (170.0, 40.0), (10.0, 200.0)]:
        assert not _dark_at(img, x, y), (x, y)
    # the rotated text reads upwards: its ink stands in a narrow, tall column left of x = 260
    col = img[:, int(255 * PX_PER_MM):int(261 * PX_PER_MM)] < 128
    rows = np.nonzero(col.any(axis=1))[0]
    assert rows.min() < 60 * PX_PER_MM - 15 * PX_PER_MM and rows.max() <= 61 * PX_PER_MM


def test_same_sheets_give_the_same_bytes(tmp_path):
    a, b = tmp_path / "a.pdf", tmp_path / "b.pdf"
    texts = [_sheet().svg(), Sheet(size="A3").svg()]
    svgs_to_pdf(texts, a, "twice")
    svgs_to_pdf(texts, b, "twice")
    assert a.read_bytes() == b.read_bytes()


def test_an_element_no_sheet_writes_is_refused_with_its_page(tmp_path):
    text = _sheet().svg().replace("</svg>", '<ellipse cx="1" cy="1" rx="2" ry="1"/></svg>')
    with pytest.raises(SheetSvgError, match=r"page 2: element <ellipse>"):
        svgs_to_pdf([Sheet(size="A3").svg(), text], tmp_path / "x.pdf")


def test_an_unparsable_svg_is_a_value_error_naming_its_page(tmp_path):
    with pytest.raises(ValueError, match="SVG page 1 could not be parsed"):
        svgs_to_pdf(["<svg"], tmp_path / "x.pdf")
