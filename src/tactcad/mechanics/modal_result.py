"""The common result every modal level returns, and the density it needs.

Units: Hz, s; densities in g/cm^3 (the material library's) or t/mm^3 (the
consistent unit of the mm-N-s system: 1 g/cm^3 = 1e-9 t/mm^3).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from tactcad.design.array_plan import Material
from tactcad.errors import DesignError

#: t/mm^3 per g/cm^3.
T_PER_MM3_PER_G_PER_CM3 = 1e-9


def density_t_per_mm3(material: Material) -> float:
    """The material's density in t/mm^3 (from ``density_g_per_cm3``).

    Raises:
        DesignError: the material has no density (neither a library grade
            nor ``material.density_g_per_cm3``).
    """
    rho = material.density_g_per_cm3
    if rho is None or not rho > 0:
        raise DesignError("material.density_g_per_cm3", rho,
                          "a density in g/cm^3 (or a library grade that has one)",
                          "natural frequencies need the element's mass")
    return float(rho) * T_PER_MM3_PER_G_PER_CM3


@dataclass(frozen=True)
class Mode:
    """One natural mode: its number (1 = lowest), frequency (Hz) and family
    ("in-plane": bending in the sheet's plane, the sensing direction;
    "out-of-plane": bending out of it or twisting)."""

    number: int
    frequency_Hz: float
    family: str


@dataclass(frozen=True)
class ModalResult:
    """Natural frequencies of one element as clamped in the stiffness model.

    Attributes:
        element: paper element number (None for a bare geometry).
        model: modal level name (:mod:`tactcad.mechanics.modal_ladder`).
        modes: the lowest modes found, ascending.
        error_estimate_rel: estimated relative error of the first frequency.
        wall_time_s: wall-clock time of the evaluation (s).
        basis: how the level got them, in words.
    """

    element: int | None
    model: str
    modes: tuple[Mode, ...]
    error_estimate_rel: float
    wall_time_s: float
    basis: str = ""
    #: a FEM level's finest solve, when asked for (mode shapes to VTU)
    solve: object = field(default=None, repr=False, compare=False)

    @property
    def first_Hz(self) -> float:
        """The lowest natural frequency (Hz)."""
        return self.modes[0].frequency_Hz

    def as_json(self) -> dict:
        return {"element": self.element, "model": self.model, "first_Hz": self.first_Hz,
                "modes": [{"mode": m.number, "frequency_Hz": m.frequency_Hz,
                           "family": m.family} for m in self.modes],
                "error_estimate_rel": self.error_estimate_rel, "wall_time_s": self.wall_time_s,
                "basis": self.basis}
