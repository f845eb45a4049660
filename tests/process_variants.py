"""Design overrides that cut the element by another process: the web's drawn tolerance
what that process holds on the sheet (the validator refuses a finer one), and the web
at least twice it (a tolerance may not exceed half its feature)."""

from __future__ import annotations

from tactcad.design.array_plan import EdmRules
from tactcad.design.readout_section import DEFAULTS
from tactcad.vocabulary.process import cut_process

#: wire settings (mm) to ask a process for its limits; the tolerance reads none of them
_WIRE = EdmRules(0.25, 0.03, 1.0)


def held_tolerance_mm(process: str, sheet_mm: float, material: str = "") -> float:
    """+/- mm the process holds on a sheet of ``sheet_mm`` (mm)."""
    return cut_process(process).limits(sheet_mm, _WIRE, material).tolerance_mm.value_mm


def cut_by(process: str, sheet_mm: float, web_mm: float = 0.165, **more) -> dict:
    """Overrides (dotted keys) that cut the element by ``process`` from ``sheet_mm``; on a
    sheet thinner than the library default's gauge grid, a grid as wide as the sheet (the
    grid must fit the element's top face)."""
    tol = held_tolerance_mm(process, sheet_mm)
    grid = {} if sheet_mm >= DEFAULTS["grid_width_mm"][0] else {"readout.grid_width_mm": sheet_mm}
    return {"element.process": process, "sheet.thickness_mm": sheet_mm,
            "element.web_tolerance_mm": round(tol, 6),
            "element.web_thickness_mm": max(web_mm, round(2 * tol, 6)), **grid, **more}
