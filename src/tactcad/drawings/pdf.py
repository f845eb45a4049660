"""All drawing sheets in one PDF, drawn straight from the sheets' SVG (reportlab's canvas).

A sheet's SVG (:class:`tactcad.drawings.sheet.Sheet`) holds a closed set of
elements: ``line``, ``path`` (``M``/``L``/``Z`` only), ``rect``, ``circle``
and ``text`` in groups, in paper millimetres with y down. Each becomes the
matching PDF path or text operator, the coordinates copied as the SVG writes
them (3 decimals), under one page transform (mm to points, y flipped). The
pages stay vector: strokes keep their ISO 128 widths and dashes, texts stay
Helvetica text a reader can search. The default design's 26 sheets take 0.2 s; a
general SVG converter (svglib) took 5.5 s.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

from reportlab.pdfgen import canvas

from tactcad.store import Store

SVG_NS = "{http://www.w3.org/2000/svg}"
POINTS_PER_MM = 72.0 / 25.4
#: The SVG's font family maps onto PDF's base Helvetica (the sheets' metrics are Helvetica's).
PDF_FONTS = {False: "Helvetica", True: "Helvetica-Bold"}
_ROTATE = re.compile(r"rotate\(\s*([-+0-9.eE]+)")
_PATH_TOKENS = re.compile(r"[MLZ]|[-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?")


class SheetSvgError(ValueError):
    """An SVG holds an element or path command a drawing sheet never writes."""


def svgs_to_pdf(svg_texts: list[str], target: Path, title: str = "",
                store: Store | None = None) -> None:
    """One PDF page per SVG drawing sheet, each page the sheet's own size.

    Written in reportlab's invariant mode (fixed creation date and document
    id), so the same SVGs give the same bytes.

    Args:
        svg_texts: the sheets' SVG texts, as :meth:`tactcad.drawings.sheet.Sheet.svg` writes them.
        target: the PDF file to write.
        title: the PDF's title.
        store: unused; kept so callers that pass the run's store need no change
            (the direct drawing costs less than reading a kept conversion back).

    Raises:
        ValueError: an SVG could not be parsed, or holds an element a drawing
            sheet never writes (its page number and the element are named).
    """
    del store
    roots = [_parsed(text, k) for k, text in enumerate(svg_texts, start=1)]
    c = canvas.Canvas(str(target), invariant=1, pageCompression=1)
    c.setTitle(title)
    c.setAuthor("tactcad")
    c.setCreator("tactcad")
    c.setProducer("tactcad (reportlab)")
    for k, root in enumerate(roots, start=1):
        width_mm, height_mm = _sheet_size_mm(root, k)
        c.setPageSize((width_mm * POINTS_PER_MM, height_mm * POINTS_PER_MM))
        # one transform for the page: paper mm with y down, as the SVG's viewBox
        c.transform(POINTS_PER_MM, 0, 0, -POINTS_PER_MM, 0, height_mm * POINTS_PER_MM)
        _draw_children(c, root, k)
        c.showPage()
    c.save()


def _parsed(text: str, page: int) -> ET.Element:
    try:
        return ET.fromstring(text.encode("utf-8"))
    except ET.ParseError as err:
        raise ValueError(f"SVG page {page} could not be parsed: {err}") from None


def _sheet_size_mm(root: ET.Element, page: int) -> tuple[float, float]:
    """The sheet's width and height (mm) from its viewBox (the SVG's user units are mm)."""
    box = (root.get("viewBox") or "").split()
    if root.tag != SVG_NS + "svg" or len(box) != 4:
        raise SheetSvgError(f"SVG page {page}: no <svg> root with a viewBox (got {root.tag!r})")
    return float(box[2]), float(box[3])


def _draw_children(c: canvas.Canvas, parent: ET.Element, page: int) -> None:
    for el in parent:
        tag = el.tag[len(SVG_NS):] if el.tag.startswith(SVG_NS) else el.tag
        if tag == "g":
            _draw_children(c, el, page)
        elif tag == "title":
            continue
        elif tag == "text":
            _draw_text(c, el)
        elif tag in _SHAPES:
            c.addLiteral(_paint(el, _SHAPES[tag](el, page)))
        else:
            raise SheetSvgError(f"SVG page {page}: element <{tag}> is not one a drawing "
                                f"sheet writes (line, path, rect, circle, text, g, title)")


def _line(el: ET.Element, page: int) -> str:
    return f"{el.get('x1')} {el.get('y1')} m {el.get('x2')} {el.get('y2')} l"


def _path(el: ET.Element, page: int) -> str:
    ops, pending = [], []
    for tok in _PATH_TOKENS.findall(el.get("d", "")):
        if tok in "MLZ":
            op = tok
            if tok == "Z":
                ops.append("h")
            continue
        pending.append(tok)
        if len(pending) == 2:
            ops.append(f"{pending[0]} {pending[1]} {'m' if op == 'M' else 'l'}")
            op, pending = "L", []  # coordinates after a moveto are linetos (SVG 1.1, 8.3.2)
    if pending or not ops:
        raise SheetSvgError(f"SVG page {page}: path d={el.get('d', '')[:60]!r} is not "
                            f"a list of M/L/Z commands with coordinate pairs")
    return " ".join(ops)


def _rect(el: ET.Element, page: int) -> str:
    return f"{el.get('x')} {el.get('y')} {el.get('width')} {el.get('height')} re"


#: A quarter circle as one cubic Bezier: the control points lie this fraction of r out.
_KAPPA = 0.5522847498307936


def _circle(el: ET.Element, page: int) -> str:
    cx, cy, r = (float(el.get(a)) for a in ("cx", "cy", "r"))
    k = _KAPPA * r
    pts = [(cx + r, cy), (cx + r, cy + k, cx + k, cy + r, cx, cy + r),
           (cx - k, cy + r, cx - r, cy + k, cx - r, cy),
           (cx - r, cy - k, cx - k, cy - r, cx, cy - r),
           (cx + k, cy - r, cx + r, cy - k, cx + r, cy)]
    out = [f"{_f(pts[0][0])} {_f(pts[0][1])} m"]
    out += [" ".join(_f(v) for v in seg) + " c" for seg in pts[1:]]
    return " ".join(out) + " h"


_SHAPES = {"line": _line, "path": _path, "rect": _rect, "circle": _circle}


def _f(v: float) -> str:
    text = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _colour(value: str | None) -> str | None:
    """An SVG colour (``#rrggbb``, ``none``) as PDF RGB components, or None for ``none``."""
    if value is None or value == "none":
        return None
    if len(value) == 7 and value.startswith("#"):
        return " ".join(_f(int(value[i:i + 2], 16) / 255.0) for i in (1, 3, 5))
    return "0 0 0"


def _paint(el: ET.Element, geometry: str) -> str:
    """PDF operators that fill and/or stroke ``geometry`` as the element's SVG attributes say
    (fill defaults to black, stroke to none, as in SVG)."""
    fill = _colour(el.get("fill", "#000000"))
    stroke = _colour(el.get("stroke"))
    ops = ["q"]
    if stroke is not None:
        ops.append(f"{stroke} RG {el.get('stroke-width', '1')} w")
        ops.append(f"{_CAPS[el.get('stroke-linecap', 'butt')]} J "
                   f"{_JOINS[el.get('stroke-linejoin', 'miter')]} j")
        dash = el.get("stroke-dasharray")
        ops.append(f"[{dash.replace(',', ' ')}] 0 d" if dash and dash != "none" else "[] 0 d")
    if fill is not None:
        ops.append(f"{fill} rg")
    ops.append(geometry)
    ops.append({(True, True): "B", (True, False): "f", (False, True): "S",
                (False, False): "n"}[(fill is not None, stroke is not None)])
    ops.append("Q")
    return "\n".join(ops)


_CAPS = {"butt": 0, "round": 1, "square": 2}
_JOINS = {"miter": 0, "round": 1, "bevel": 2}


def _draw_text(c: canvas.Canvas, el: ET.Element) -> None:
    """A text element: Helvetica (bold when the SVG says so) of the SVG's font size,
    its baseline at (x, y), anchored and rotated as the SVG says."""
    text = el.text or ""
    if not text:
        return
    x, y = float(el.get("x", "0")), float(el.get("y", "0"))
    size = float(el.get("font-size", "1"))
    font = PDF_FONTS[el.get("font-weight") == "bold"]
    c.saveState()
    c.translate(x, y)
    turn = _ROTATE.match(el.get("transform", ""))
    if turn:
        c.rotate(float(turn.group(1)))  # SVG's rotate(a x y): about the baseline point
    c.scale(1, -1)  # the page runs y down; glyphs stand upright
    c.setFillColorRGB(0, 0, 0)
    c.setFont(font, size)
    anchor = el.get("text-anchor", "start")
    draw = {"start": c.drawString, "middle": c.drawCentredString, "end": c.drawRightString}[anchor]
    draw(0, 0, text)
    c.restoreState()
