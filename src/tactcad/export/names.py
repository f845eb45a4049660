"""Export-relative paths of every file a run writes (one place, so writers,
the BOM, the manifest and the checks agree)."""

from __future__ import annotations

DRAWING_DIR = "drawings"
PDF_NAME = f"{DRAWING_DIR}/drawings.pdf"
ARRAY_PNG = "images/array.png"
ARRAY_STEP = "step/array.step"
MANIFEST = "manifest.json"


def part_step_name(part: str) -> str:
    """``step/<part>.step``."""
    return f"step/{part}.step"


def element_dxf_name(number: int) -> str:
    """``dxf/element_<n>.dxf``: the wire-EDM profile of array element ``n``."""
    return f"dxf/element_{number}.dxf"


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
