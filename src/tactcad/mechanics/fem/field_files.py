"""An element's FEM field as a VTU file: the finest mesh of fem2d or fem3d
solved for one element and written by :func:`tactcad.mechanics.fem.fields.write_vtu`.

Apart from :mod:`tactcad.mechanics.fem.fields` (stress recovery, which the
solvers' sequences use) because it runs the solvers.

Units: mm, N, MPa.
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

from tactcad.design.array_plan import ElementGeometry
from tactcad.mechanics.fem.fields import write_vtu


class VtuOutput(NamedTuple):
    """A written VTU file and the solve behind it (mm, N, N/mm)."""

    path: Path
    force_N: float
    stiffness_N_per_mm: float


def write_element_vtu(directory: str | Path, g: ElementGeometry, material, model: str, *,
                      force_N: float = 1.0) -> VtuOutput:
    """Solve the finest mesh of ``model`` ("fem2d" plane stress or "fem3d")
    for one element and write its field to ``directory/<part>_<model>.vtu``.

    The solve is the level's default finest mesh (the one whose K the
    estimator reports) under a tip force ``force_N`` (N; fields are linear in
    it).

    Raises:
        ValueError: unknown model.
    """
    from tactcad.mechanics.fem.fem2d import solve_fem2d
    from tactcad.mechanics.fem.fem3d import solve_fem3d

    if model == "fem2d":
        sol = solve_fem2d(g, material, force_N=force_N, keep_field=True)
    elif model == "fem3d":
        sol = solve_fem3d(g, material, force_N=force_N, keep_field=True)
    else:
        raise ValueError(f"VTU output needs model fem2d or fem3d; got {model!r}")
    path = write_vtu(Path(directory) / f"{g.part_name}_{model}.vtu", sol.field)
    return VtuOutput(path, force_N, sol.stiffness_N_per_mm)
