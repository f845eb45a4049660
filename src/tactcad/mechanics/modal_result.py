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
class PointMass:
    """A mass carried by the element that is not of its sheet (gauge, adhesive, lead,
    solder pad, a tip cover): the modal levels add it at its place.

    Attributes:
        name: what it is. mass_g: its mass (g).
        x_mm, y_mm: where it sits in the element frame (mm; the sheet's plane, on its
            mid-plane across the sheet).
        source: where the figure comes from (a data sheet, or an estimate stated as such).
    """

    name: str
    mass_g: float
    x_mm: float
    y_mm: float
    source: str = ""

    @property
    def mass_t(self) -> float:
        """The mass in t (the mm-N-s system's unit; 1 g = 1e-6 t)."""
        return self.mass_g * 1e-6


@dataclass(frozen=True)
class Mode:
    """One natural mode: its number (1 = lowest), frequency (Hz) and family
    ("in-plane": bending in the sheet's plane, the sensing direction;
    "out-of-plane": bending out of it or twisting)."""

    number: int
    frequency_Hz: float
    family: str
    #: this mode's own relative error estimate, where the level gives each mode one (the
    #: closed form: its two families are estimated each its own way); None: only the
    #: first's, :attr:`ModalResult.error_estimate_rel`
    error_estimate_rel: float | None = None
    #: (lower, upper) bounds on this mode's frequency (Hz), where the level estimates it
    #: between two (the closed form's out-of-plane mode); None: none given
    bounds_Hz: tuple[float, float] | None = None

    def as_json(self) -> dict:
        out = {"mode": self.number, "frequency_Hz": self.frequency_Hz, "family": self.family}
        if self.error_estimate_rel is not None:
            out["frequency_Hz_error_rel"] = self.error_estimate_rel
        if self.bounds_Hz is not None:
            out["frequency_Hz_bounds"] = list(self.bounds_Hz)
        return out


#: The largest relative error a frequency is said as +/- with (1: the lower end reaches
#: 0 Hz); above it only the mode's bounds mean anything (:func:`error_words`).
PLUS_MINUS_LIMIT_REL = 1.0


def error_words(error_rel: float | None, bounds_Hz: list[float] | None) -> str:
    """A mode's error in words, for the modal tables: ``+/- 3.8 %``, or where the error
    estimate is above :data:`PLUS_MINUS_LIMIT_REL` and the level gives bounds, the bounds
    (an error of 161 % is their ratio, not a +/-: the frequency cannot be 61 % below 0).

    Args:
        error_rel: the mode's relative error estimate (None: none given).
        bounds_Hz: its (lower, upper) bounds (Hz), or None.

    Returns:
        The words ("" when the mode has no error estimate).
    """
    if error_rel is None:
        return ""
    if error_rel > PLUS_MINUS_LIMIT_REL and bounds_Hz is not None:
        lo, hi = bounds_Hz
        return (f" between {lo:.1f} and {hi:.1f} Hz: the closed form's bounds, a factor "
                f"{hi / lo:.3g} apart; its {100 * error_rel:.0f} % error estimate, a formula "
                "made for close bounds, is no +/- here; --model fem3d computes this mode")
    return f" +/- {100 * error_rel:.1f} %"


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
        added_mass_g: the point masses counted (g, total; 0: the bare element).
        bare_first_Hz: the first frequency without them (Hz; None when none are counted).
    """

    element: int | None
    model: str
    modes: tuple[Mode, ...]
    error_estimate_rel: float
    wall_time_s: float
    basis: str = ""
    added_mass_g: float = 0.0
    bare_first_Hz: float | None = None
    #: a FEM level's finest solve, when asked for (mode shapes to VTU)
    solve: object = field(default=None, repr=False, compare=False)

    @property
    def first_Hz(self) -> float:
        """The lowest natural frequency (Hz)."""
        return self.modes[0].frequency_Hz

    def first_of(self, family: str) -> float | None:
        """The lowest frequency of ``family`` (Hz), None when the level found none."""
        return next((m.frequency_Hz for m in self.modes if m.family == family), None)

    def as_json(self) -> dict:
        return {"element": self.element, "model": self.model, "first_Hz": self.first_Hz,
                "first_in_plane_Hz": self.first_of("in-plane"),
                "first_out_of_plane_Hz": self.first_of("out-of-plane"),
                "modes": [m.as_json() for m in self.modes],
                "added_mass_g": self.added_mass_g, "bare_first_Hz": self.bare_first_Hz,
                "first_Hz_error_rel": self.error_estimate_rel, "wall_time_s": self.wall_time_s,
                "basis": self.basis}
