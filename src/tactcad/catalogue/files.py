"""Export-relative paths of every file a run writes (one place, so writers,
the BOM, the manifest and the checks agree)."""

from __future__ import annotations

from typing import Sequence

from tactcad.vocabulary.schema import name_number

DRAWING_DIR = "drawings"
PDF_NAME = f"{DRAWING_DIR}/drawings.pdf"
ARRAY_PNG = "images/array.png"
ASSEMBLY_DRAWING = "drawings/assembly.svg"  # the array's assembly sheet
ARRAY_STEP = "step/array.step"
MANIFEST = "manifest.json"


def part_step_name(part: str) -> str:
    """``step/<part>.step``."""
    return f"step/{part}.step"


def profile_dxf_name(part: str, quantity: int) -> str:
    """``dxf/<part>_qty<n>.dxf``."""
    return f"dxf/{part}_qty{quantity}.dxf"


def sheet_dxf_name(material: str, thickness_mm: float) -> str:
    """``dxf/sheet_<material>_<t>mm.dxf`` (decimal point written ``p``)."""
    return f"dxf/sheet_{material.replace(' ', '_')}_{name_number(thickness_mm)}mm.dxf"


def sheet_material_names(cuts: Sequence[tuple[str, str, float]]) -> list[str]:
    """The material each cut's nested sheet is named by, from ``(material
    family, grade designation, thickness mm)`` per cut: the family
    (``aluminium``) while one grade of it is cut at that thickness, else the
    designation (``aluminium EN AW-6061-T6``), so that two grades of one family
    never share a sheet nor a file name."""
    grades: dict[tuple[str, float], set[str]] = {}
    for family, grade, t in cuts:
        grades.setdefault((family, t), set()).add(grade or family)
    return [family if len(grades[(family, t)]) == 1 else (grade or family)
            for family, grade, t in cuts]


def sheet_names_by_process(cuts: Sequence[tuple[str, str, float, str]]) -> list[str]:
    """:func:`sheet_material_names` of ``(family, grade, thickness mm, process)``
    per cut, one process per sheet: where one sheet would be cut by two
    processes, the cuts of every process after the first are named with it
    (``Ti-6Al-4V-annealed-laser-cutting``), so a shop file is one process's."""
    names = sheet_material_names([(family, grade, t) for family, grade, t, _ in cuts])
    first: dict[tuple[str, float], str] = {}
    out = []
    for name, (_, _, t, process) in zip(names, cuts):
        kept = first.setdefault((name, t), process)
        out.append(name if kept == process else f"{name}-{process}")
    return out


def scene_step_name(name: str) -> str:
    """``scenes/<scene>.step``."""
    return f"scenes/{name}.step"


def scene_glb_name(name: str) -> str:
    """``scenes/<scene>.glb``."""
    return f"scenes/{name}.glb"


def drawing_name(part: str) -> str:
    """``drawings/<part>.svg``."""
    return f"{DRAWING_DIR}/{part}.svg"


def drawing_png_name(part: str) -> str:
    """``images/<part>_drawing.png``: a part's drawing rendered to PNG."""
    return f"images/{part}_drawing.png"
