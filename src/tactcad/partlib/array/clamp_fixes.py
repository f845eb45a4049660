"""What mends a clamp bolt too short for its stack: the changes a refusal offers.

A stacked array's clamp bolt grips both clamp plates and the element/spacer
stack (and, for the rigs' bracket bolt, the bracket ear as well) with its nut
and two thread pitches beyond it; the longest stock bolt of its size bounds
that. A refusal offers only the changes that, tried against the same rule and
the design file's other rules, pass: another bolt size, thinner clamp plates,
fewer columns. Where no bolt or plate change can clamp the columns, it says so
and names the column count that fits.
"""

from __future__ import annotations

import copy
import math
from contextvars import ContextVar
from typing import Any, Callable, Mapping

from tactcad.vocabulary.grid import STACKED_COLUMNS_RANGE
from tactcad.vocabulary.schema import LIMIT_TOLERANCE_MM, fmt
from tactcad.vocabulary.standards import BOLTS, shortest_stock_length

#: Thinnest clamp plate a design file takes (mm), ``clamp.plate_thickness_mm``.
THINNEST_PLATE_MM = 1.0

#: Plate thickness offered is rounded down to this step (mm), so that it still fits.
PLATE_STEP_MM = 0.1

#: The design file's rules, ``check(tables) -> refusals`` (falsy when none): set by
#: :mod:`tactcad.design.array_plan` (the design layer above this one) on import.
DESIGN_CHECK: list[Callable[[Mapping[str, Any]], Any]] = []

#: True while a candidate change is being tried: its own refusal searches no further.
_TRYING: ContextVar[bool] = ContextVar("clamp_fix_trying", default=False)


def bolt_needed_mm(data: Mapping[str, Any], ear_mm: float = 0.0) -> float:
    """Bolt length (mm) the clamp of the raw design tables ``data`` needs: ear
    (``ear_mm``, 0 for the array's own clamp bolts), both clamp plates, the
    element/spacer stack, the nut and two thread pitches."""
    bolt = BOLTS[data["clamp"]["bolt_size"]]
    stack = (int(data["array"]["columns"]) - 1) * float(data["array"]["pitch_mm"]) \
        + float(data["sheet"]["thickness_mm"])
    return ear_mm + 2 * float(data["clamp"]["plate_thickness_mm"]) + stack \
        + bolt.nut_height_mm + 2 * bolt.thread_pitch_mm


def clamps(data: Mapping[str, Any], ear_mm: float = 0.0) -> bool:
    """True when a stock bolt of the design's size is long enough (:func:`bolt_needed_mm`)."""
    return shortest_stock_length(BOLTS[data["clamp"]["bolt_size"]],
                                 bolt_needed_mm(data, ear_mm)) is not None


def _with(data: Mapping[str, Any], changes: Mapping[str, Any]) -> dict[str, Any]:
    out = copy.deepcopy(dict(data))
    for dotted, value in changes.items():
        section, key = dotted.split(".", 1)
        out.setdefault(section, {})[key] = value
    return out


def _fewer_columns(data: Mapping[str, Any], columns: int) -> dict[str, Any]:
    """The changes for ``columns`` columns: each row's arms cut to its first ``columns``."""
    rows = int(data["array"]["rows"])
    old = int(data["array"]["columns"])
    arms = list(data["arms"]["lengths_mm"])
    kept = [a for r in range(rows) for a in arms[r * old: r * old + columns]]
    return {"array.columns": columns, "arms.lengths_mm": kept}


def _option(changes: Mapping[str, Any]) -> str:
    def value(v: Any) -> str:
        if isinstance(v, str):
            return f'"{v}"'
        if isinstance(v, list):
            return "[" + ",".join(fmt(x) for x in v) + "]"
        return fmt(v)
    parts = []
    for key, v in changes.items():
        text = f"{key}={value(v)}"
        parts.append(f"--set '{text}'" if any(c in text for c in "\"[]") else f"--set {text}")
    return " ".join(parts)


def _passes(data: Mapping[str, Any], ear_mm: float) -> bool:
    """True when ``data`` clamps (with ``ear_mm``) and the design file's rules pass."""
    if not clamps(data, ear_mm):
        return False
    token = _TRYING.set(True)
    try:
        refused = [check(data) for check in DESIGN_CHECK]
    except Exception:  # noqa: BLE001 - a candidate the rules cannot read mends nothing
        return False
    finally:
        _TRYING.reset(token)
    return not any(refused)


def most_columns(data: Mapping[str, Any], ear_mm: float = 0.0) -> int | None:
    """Most columns (fewer than the design's) its bolt and plates clamp, or None when
    not even the fewest a stacked array takes (:data:`STACKED_COLUMNS_RANGE`) fit."""
    for n in range(int(data["array"]["columns"]) - 1, STACKED_COLUMNS_RANGE[0] - 1, -1):
        if clamps(_with(data, {"array.columns": n}), ear_mm):
            return n
    return None


def clamp_fixes(data: Mapping[str, Any], ear_mm: float = 0.0) -> tuple[str, list[dict]]:
    """What mends a clamp bolt too short for the design ``data`` (raw tables).

    Each candidate (every other bolt size, the thickest clamp plate that
    fits, the most columns that fit) is tried against the bolt-length rule
    (with ``ear_mm``) and the design file's rules; only those that pass are
    offered.

    Args:
        data: the design file's tables (a stacked array).
        ear_mm: thickness the bolt grips besides the plates and the stack (mm):
            the rigs' bracket ear, 0 for the array's own clamp bolts.

    Returns:
        (the ``allowed`` text of the refusal, the alternatives: each a dict with
        ``option`` to paste and ``words``). The text says plainly when no bolt or
        plate change clamps the design's columns, naming the column count that fits.
    """
    if _TRYING.get():
        return "a longer stock bolt than its size has", []
    bolt = BOLTS[data["clamp"]["bolt_size"]]
    columns = int(data["array"]["columns"])
    plate = float(data["clamp"]["plate_thickness_mm"])
    words, alternatives = [], []
    for size in BOLTS:
        if size == bolt.size:
            continue
        changes = {"clamp.bolt_size": size}
        if _passes(_with(data, changes), ear_mm):
            relation = "larger" if BOLTS[size].nominal_diameter_mm > bolt.nominal_diameter_mm \
                else "smaller"
            words.append(f"a {relation} bolt, {size}")
            alternatives.append({"option": _option(changes), "words": f"{size} bolts"})
    # thickest plate that fits: the bolt's longest stock length minus all but the plates
    spare = max(bolt.catalogue_lengths_mm) + LIMIT_TOLERANCE_MM - bolt_needed_mm(
        _with(data, {"clamp.plate_thickness_mm": 0.0}), ear_mm)
    thickest = math.floor(spare / 2 / PLATE_STEP_MM + 1e-9) * PLATE_STEP_MM
    if THINNEST_PLATE_MM - 1e-9 <= thickest < plate:
        changes = {"clamp.plate_thickness_mm": round(thickest, 6)}
        if _passes(_with(data, changes), ear_mm):
            words.append(f"clamp plates {fmt(thickest)} mm thick or thinner")
            alternatives.append({"option": _option(changes),
                                 "words": f"{fmt(thickest)} mm clamp plates"})
    fits = most_columns(data, ear_mm)
    column_changes = _fewer_columns(data, fits) if fits is not None else None
    if column_changes is not None and _passes(_with(data, column_changes), ear_mm):
        alternatives.append({"option": _option(column_changes),
                             "words": f"{fits} columns, each row's first {fits} arms"})
    else:
        column_changes = None
    if words:
        text = " or ".join(words)
        if column_changes is not None:
            text = f"fewer columns ({fits}), " + text
        return text, alternatives
    if column_changes is not None:
        return (f"fewer columns ({fits}): no bolt size or clamp plate thickness clamps "
                f"{columns} columns"), alternatives
    return (f"no bolt size or clamp plate thickness clamps this stack, not even of "
            f"{STACKED_COLUMNS_RANGE[0]} columns (pitch {fmt(float(data['array']['pitch_mm']))} mm, sheet "
            f"{fmt(float(data['sheet']['thickness_mm']))} mm)"), alternatives
