"""The sheet every drawing stands on: the A3 frame with its centring marks
(ISO 5457), the title-block cells (ISO 7200), the first-angle projection
symbol (ISO 128-30), the general tolerance and the revision of a design.
Used by the part drawings and the assembly drawing alike."""

from __future__ import annotations

import datetime
import os
from typing import TYPE_CHECKING, Mapping

from tactcad.errors import DesignError
from tactcad.drawings.sheet import Sheet, text_width
from tactcad.drawings.source_date import epoch_date  # noqa: F401 (its name here too)

if TYPE_CHECKING:  # the design model costs a second to import; the CLI reads epoch_date first
    from tactcad.design.array_plan import Plan

GENERAL_TOLERANCE = "ISO 2768-f"


def general_tolerance(plan) -> str:
    """The design's general tolerance class (``[tolerances] general``), e.g. ``ISO 2768-f``."""
    from tactcad.design.tolerances import tolerances_of

    return tolerances_of(plan.raw).general_text
FRAME = (20.0, 10.0, 410.0, 287.0)  # left, top, right, bottom (A3, ISO 5457)
TITLE_W, TITLE_H = 180.0, 63.0        # seven rows of 9 mm


def sheet_date(plan: Plan, environ: Mapping[str, str] | None = None) -> str:
    """The date every sheet prints (ISO 8601, ``YYYY-MM-DD``, UTC): from
    ``SOURCE_DATE_EPOCH`` (seconds since 1970, the reproducible-builds
    convention) when set, else the design file's ``[design] date``, else
    ``—`` (undated: the signer writes it). Never the clock: the same input
    writes the same bytes.

    Raises:
        DesignError: ``SOURCE_DATE_EPOCH`` is not a whole number of seconds in
            0 .. 253402300799 (year 9999), or ``[design] date`` is not a date
            ``YYYY-MM-DD``.
    """
    epoch = epoch_date(os.environ if environ is None else environ)
    if epoch is not None:
        return epoch
    table = plan.raw.get("design", {}) if isinstance(plan.raw, dict) else {}
    stated = str(table.get("date", "") or "")
    if not stated:
        return "—"
    try:
        return datetime.date.fromisoformat(stated).isoformat()
    except ValueError:
        raise DesignError("design.date", stated, "a date YYYY-MM-DD (ISO 8601)") from None


def revision_and_date(plan: Plan) -> tuple[str, str]:
    """(revision, date) of the drawing: the design file's ``[design]``
    ``revision`` (else ``A``) and :func:`sheet_date`."""
    table = plan.raw.get("design", {}) if isinstance(plan.raw, dict) else {}
    rev = str(table.get("revision", "") or "A")
    return rev, sheet_date(plan)


def wrap_text(text: str, width: float, h: float) -> list[str]:
    """``text`` broken into lines no wider than ``width`` paper mm at text height ``h`` (mm)."""
    words = text.split()
    lines, cur = [], ""
    for w in words:
        trial = f"{cur} {w}".strip()
        if text_width(trial, h) <= width or not cur:
            cur = trial
        else:
            lines.append(cur)
            cur = w
    if cur:
        lines.append(cur)
    return lines


def sheet_frame(sh: Sheet) -> None:
    """ISO 5457 frame and centring marks of an A3 sheet; the sheet's labels
    stay inside the frame."""
    x0, y0, x1, y1 = FRAME
    sh.rect("frame", x0, y0, x1 - x0, y1 - y0, "frame")
    sh.room = FRAME
    # centring marks (ISO 5457)
    w, h = sh.width_mm, sh.height_mm
    for p, q in (((w / 2, 0.0), (w / 2, y0 + 5)), ((w / 2, h), (w / 2, y1 - 5)),
                 ((0.0, h / 2), (x0 + 5, h / 2)), ((w, h / 2), (x1 - 5, h / 2))):
        sh.line("frame", p, q, "frame")


#: Smallest value height a title block sets (mm): ISO 3098's smallest nominal height.
MIN_VALUE_MM = 1.8
#: Step a value too wide for its cell is set smaller by (mm).
VALUE_STEP_MM = 0.25
#: Characters a value may be broken after onto a second line, in order of preference: a
#: space, then a name's separators.
BREAKS = (" ", "_-.")


def title_cells(sh: Sheet, x0: float, y0: float, rh: float, cells: list[tuple]) -> None:
    """Title-block cells (ISO 7200): each ``(row, x offset, width, label,
    value, id, value height)`` in paper mm from the block's corner
    ``(x0, y0)``, rows ``rh`` high. A value too wide for its cell is set smaller, down to
    :data:`MIN_VALUE_MM`, then on two lines (its second text's id ``<id>-2``), and beyond
    that its middle is left out for an ellipsis (:func:`value_lines`; the sheet's SVG title
    and its Design cell keep the design's name whole). Widths are
    :func:`~tactcad.drawings.sheet.text_width`'s, the measure ``tactcad check`` takes."""
    for row, dx, w, label, value, id, vh in cells:
        x, y = x0 + dx, y0 + row * rh
        sh.rect("title-block", x, y, w, rh, "table")
        sh.text("title-block", (x + 1.2, y + 2.4), label, 1.6)
        if value:
            h, lines = value_lines(value, vh, 0.9 * (w - 3))
            base = y + rh - 1.6
            baselines = [base - (len(lines) - 1 - k) * (1.25 * h + 0.3) for k in range(len(lines))]
            for k, (line, at) in enumerate(zip(lines, baselines)):
                sh.text("title-block", (x + 1.5, at), line, h, id=id if k == 0 else f"{id}-2")


def value_lines(value: str, height_mm: float, room_mm: float) -> tuple[float, list[str]]:
    """How a title-block value is set in ``room_mm`` of paper: on one line at the largest
    height down to :data:`MIN_VALUE_MM` (steps of :data:`VALUE_STEP_MM`) that fits, else
    on two lines at :data:`MIN_VALUE_MM` (:func:`two_lines`), else as
    :func:`abbreviated_lines`.

    Args:
        value: the text. height_mm: its nominal height when it fits (mm).
        room_mm: the width a line may take (mm).

    Returns:
        (height mm, one or two lines).
    """
    h = height_mm
    while text_width(value, h) > room_mm and h > MIN_VALUE_MM:
        h = max(MIN_VALUE_MM, h - VALUE_STEP_MM)
    if text_width(value, h) <= room_mm:
        return h, [value]
    return MIN_VALUE_MM, (two_lines(value, MIN_VALUE_MM, room_mm)
                          or abbreviated_lines(value, MIN_VALUE_MM, room_mm))


def two_lines(value: str, height_mm: float, room_mm: float) -> list[str] | None:
    """``value`` broken onto two lines no wider than ``room_mm`` at ``height_mm`` (mm):
    after a space where one fits, else after a ``_``, ``-`` or ``.`` (:data:`BREAKS`), else
    between any two characters; of the breaks that fit, the one whose longer line is
    shortest.

    Returns:
        The two lines (a space at the break dropped), or None when no break fits.
    """
    def split(k: int) -> list[str]:
        return [value[:k].rstrip(" "), value[k:].lstrip(" ")]

    tiers = [[k for k in range(1, len(value)) if value[k - 1] in chars] for chars in BREAKS]
    for candidates in (*tiers, range(1, len(value))):
        fits = [(max(text_width(t, height_mm) for t in split(k)), k) for k in candidates
                if all(text_width(t, height_mm) <= room_mm for t in split(k))]
        if fits:
            return split(min(fits)[1])
    return None


def abbreviated_lines(value: str, height_mm: float, room_mm: float) -> list[str]:
    """``value`` on two lines of ``room_mm`` at ``height_mm`` (mm) with its middle left
    out: the longest start that fits, then an ellipsis and the longest end that fits (a
    drawing number keeps its design's first characters and its part's name).

    Returns:
        The two lines.
    """
    head = value
    while len(head) > 1 and text_width(head, height_mm) > room_mm:
        head = head[:-1]
    rest = value[len(head):]
    tail = rest
    while len(tail) > 1 and text_width("…" + tail, height_mm) > room_mm:
        tail = tail[1:]
    return [head, "…" + tail]


def projection_symbol(sh: Sheet, px: float, py: float) -> None:
    """The first-angle projection symbol (ISO 128-30) centred at paper ``(px, py)`` (mm)."""
    sh.polyline("title-block", [(px - 12, py - 1.4), (px - 4, py - 3.0), (px - 4, py + 3.0),
                                (px - 12, py + 1.4)], "thin", closed=True)
    sh.line("title-block", (px - 14, py), (px - 2, py), "centre")
    sh.circle("title-block", (px + 6, py), 3.0)
    sh.circle("title-block", (px + 6, py), 1.4)
    sh.line("title-block", (px + 2, py), (px + 10, py), "centre")
    sh.line("title-block", (px + 6, py - 4), (px + 6, py + 4), "centre")
