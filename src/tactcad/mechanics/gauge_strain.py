"""The strain a bonded gauge reads over the web, beyond plane-stress beam theory.

Two corrections turn the Euler-Bernoulli (EB) top-face strain of the closed
form and beam levels into what a gauge on the real element reads:

**Width and profile (fem3d-fitted).** A sheet much wider (b) than the
hinge's bending length sqrt(t R) holds the web near plane strain: the thick
base and arm on either side of a short notch restrain its anticlastic
bending, so the surface strain under a given moment is lower than plane
stress's by up to 1 - nu^2 (at b/t = 12, nu = 0.33, 11 %). This is a
restraint by the blocks, not the large-curvature anticlastic effect of
Searle's parameter b^2 / (R_c t) (Ashwell 1950, J. R. Aeronaut. Soc. 54,
708): at the read-out's tiny curvatures that parameter is near zero and a
free plate would bend in plane stress. And EB's 1/h(x)^2 profile is more
peaked than the top face's real strain, which diffuses from the thin web
into the thicker sections beside it, so a grid of length L_g reads more,
relative to EB, the more of the notch it covers. Model::

    eps_grid = eps_EB_grid * C,
    C = (1 - nu^2 phi) * (1 + c3 s + c4 xi^2 (1 + c5 s) + c6 xi^4),
    phi = 1 / (1 + c1 w^2 + c2 (W / b)^2),
    s = t / R,  w = sqrt(t R) / b,  xi = L_g / (2 R),  W = grid width (<= b),

phi the plane-strain share of the web under the grid (1 for a wide sheet,
a grid across the whole sheet reaches the free edges' plane stress), the
second factor the profile's (and the deep notch's, c3 s) departure from EB.
At a point over the notch centre (xi = 0, W = 0) C is the surface strain's
correction (:func:`point_strain_factor`). The coefficients are least-squares
fits (relative residuals) of the grid average of fem3d's own top-face
strain (:func:`tactcad.mechanics.fem.fields.face_rectangle_average`) to
fem3d over a Sobol set of designs (:mod:`tactcad.studies.gauge_strain_sweep`);
``src/tactcad/data/gauge_strain_correction.json`` holds them with the range
of every coordinate, the residuals, a hold-out check and the points. The
error estimate is the largest fit or hold-out residual, plus, outside the
range, the change of C between the point and its projection onto the range
(the design is then flagged; beyond xi = 1 the grid leaves the notch for
the blocks, where EB's step in section height misreads the profile).

**The grid above the surface, and the layer's stiffening.** The foil grid
lies on its carrier, on the glue line, a height h_g above the top face; on
a thin web in bending it is further from the neutral axis than the surface
and reads more (Perry & Lissner, "The Strain Gage Primer", 2nd ed., 1962;
Micro-Measurements Tech Note TN-505, thin specimens in bending). Glue line
and carrier (modulus E_l, width W_c) also stiffen the web. Both follow from
the transformed section of web + layer (Timoshenko & Gere, "Mechanics of
Materials", composite beams): neutral axis e above the web's mid-plane,
bending stiffness EI_c, grid strain per moment (t/2 + h_g - e) / EI_c
against the bare web's (t/2) / EI_0 (:func:`bonded_grid_factor`). With
E_l -> 0 the factor is (t/2 + h_g) / (t/2). The face itself, under the layer,
strains (t/2 - e) / EI_c per moment: the web's stiffening and the neutral axis's
rise both lower it (:func:`face_under_layer_factor`; about 0.89 on a 0.25 mm
aluminium or a 0.165 mm titanium web under the default 55 um gauge).

Units: mm, MPa; strains and factors dimensionless.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material

#: The file the fitted coefficients come from.
GAUGE_STRAIN_FILE = Path(__file__).resolve().parents[1] / "data" / "gauge_strain_correction.json"

MODEL = ("C = (1 - nu^2 phi) * (1 + c3 s + c4 xi^2 (1 + c5 s) + c6 xi^4), "
         "phi = 1 / (1 + c1 w^2 + c2 (W/b)^2), s = t/R, w = sqrt(t R)/b, xi = L_g/(2R), "
         "W = grid width")
COEFFICIENT_NAMES = ("c1", "c2", "c3", "c4", "c5", "c6")
#: The coordinates of the model and their fitted range (JSON ``fit_range``).
RANGE_KEYS = ("t_over_R", "width_ratio", "poisson_ratio", "grid_over_notch",
              "grid_width_over_sheet", "sheet_over_web")
#: Each coordinate of :data:`RANGE_KEYS` in words, with its symbol (for the user's eyes).
COORDINATE_WORDS = {
    "t_over_R": "the web thickness over the notch radius, t/R",
    "width_ratio": "sqrt(web x notch radius) over the sheet thickness, sqrt(t R)/b",
    "poisson_ratio": "the material's Poisson ratio, nu",
    "grid_over_notch": "the gauge grid's length over the notch diameter, L_g/(2R)",
    "grid_width_over_sheet": "the gauge grid's width over the sheet thickness, W/b",
    "sheet_over_web": "the sheet over the web thickness, b/t"}


def coordinate_words(names) -> str:
    """The coordinates ``names`` (keys of :data:`RANGE_KEYS`) in words, joined with "and".

    Args:
        names: coordinate keys, e.g. ``("sheet_over_web",)``.

    Returns:
        e.g. ``"the sheet over the web thickness, b/t"``; an unknown key as itself.
    """
    return " and ".join(COORDINATE_WORDS.get(n, n) for n in names)


class GaugeStrainRangeWarning(UserWarning):
    """The gauge-strain factor is applied outside the range it was fitted over.

    Attributes:
        error_rel: the estimated relative error of the factor there.
        detail: the message without the element's name ("" when not given).
        fold_as: what a run's output folds such warnings into (one per element geometry).
    """

    fold_as = "gauge strain outside the fem3d fit of the plane-strain factor"

    def __init__(self, message: str, error_rel: float = 0.0, detail: str = ""):
        """Args:
            message: the whole text. error_rel: as the attribute (dimensionless).
            detail: the text after the element's name (what is outside which fit), for a
                caller that names the element its own way; "" when none.
        """
        super().__init__(message)
        self.error_rel = error_rel
        self.detail = detail


@dataclass(frozen=True)
class StrainCorrection:
    """The fitted model (module doc): coefficients, fitted range, error.

    Attributes:
        coefficients: c1 ... c6.
        fit_range: {coordinate: (low, high)} for :data:`RANGE_KEYS`.
        error_rel: the largest relative residual of fit and hold-out.
        source: the reference and the set of designs.
    """

    coefficients: tuple[float, ...]
    fit_range: dict
    error_rel: float
    source: str

    def factor(self, t_over_R: float, width_ratio: float, poisson_ratio: float,
               grid_over_notch: float, grid_width_over_sheet: float) -> float:
        """C at the given coordinates (module doc)."""
        c1, c2, c3, c4, c5, c6 = self.coefficients
        s, xi = t_over_R, grid_over_notch
        phi = 1.0 / (1.0 + c1 * width_ratio ** 2 + c2 * grid_width_over_sheet ** 2)
        return ((1.0 - poisson_ratio ** 2 * phi)
                * (1.0 + c3 * s + c4 * xi * xi * (1.0 + c5 * s) + c6 * xi ** 4))

    def plane_strain_factor(self, width_ratio: float, poisson_ratio: float,
                            grid_width_over_sheet: float) -> float:
        """1 - nu^2 phi: the width part of C alone (for a plane-stress field that has
        the profile along x right, such as fem2d's)."""
        c1, c2 = self.coefficients[:2]
        return 1.0 - poisson_ratio ** 2 / (1.0 + c1 * width_ratio ** 2
                                           + c2 * grid_width_over_sheet ** 2)

    def outside(self, coords: dict) -> tuple[str, ...]:
        """Names of the coordinates outside the fitted range (relative slack 1e-9)."""
        out = []
        for k, v in coords.items():
            lo, hi = self.fit_range[k]
            if v < lo - 1e-9 * abs(lo) or v > hi + 1e-9 * abs(hi):
                out.append(k)
        return tuple(out)

    def clipped(self, coords: dict) -> dict:
        """``coords`` projected onto the fitted range."""
        return {k: min(max(v, self.fit_range[k][0]), self.fit_range[k][1])
                for k, v in coords.items()}


@lru_cache(maxsize=1)
def load_strain_correction(path: Path = GAUGE_STRAIN_FILE) -> StrainCorrection:
    """The fitted model of ``path`` (:data:`GAUGE_STRAIN_FILE`).

    Raises:
        FileNotFoundError: the file is missing.
        KeyError, ValueError: the file lacks a coefficient or a range.
    """
    doc = json.loads(Path(path).read_text(encoding="utf-8"))
    coeffs = tuple(float(doc["coefficients"][k]) for k in COEFFICIENT_NAMES)
    rng = {k: tuple(float(v) for v in doc["fit_range"][k]) for k in RANGE_KEYS}
    err = max(float(doc["fit"]["max"]), float(doc.get("holdout", {}).get("max", 0.0)))
    return StrainCorrection(coeffs, rng, err, str(doc["source"]))


@dataclass(frozen=True)
class StrainFactor:
    """C of one element and grid, with its error estimate and range flags.

    Attributes:
        factor: C (dimensionless).
        error_rel: estimated relative error of the corrected strain.
        outside: coordinates outside the fitted range (empty inside it).
        coordinates: the model's coordinates at this element and grid.
    """

    factor: float
    error_rel: float
    outside: tuple[str, ...]
    coordinates: dict


def model_coordinates(g: ElementGeometry, material: Material, grid_length_mm: float,
                      grid_width_mm: float) -> dict:
    """The model's coordinates (module doc) of an element and a grid (0, 0: a point
    over the notch centre); a grid wider than the sheet counts as the sheet."""
    t, R, b = g.web_thickness_mm, g.notch_radius_mm, g.sheet_thickness_mm
    return {"t_over_R": t / R, "width_ratio": math.sqrt(t * R) / b,
            "poisson_ratio": material.poisson_ratio,
            "grid_over_notch": grid_length_mm / (2.0 * R),
            "grid_width_over_sheet": min(grid_width_mm, b) / b, "sheet_over_web": b / t}


def _rated(corr: StrainCorrection, coords: dict, value) -> StrainFactor:
    """``value(coords)`` with the error estimate: the fit's, plus outside the range the
    change from the range's nearest point."""
    f = value(coords)
    out = corr.outside(coords)
    err = corr.error_rel + (abs(f / value(corr.clipped(coords)) - 1.0) if out else 0.0)
    return StrainFactor(f, err, out, coords)


def _model_args(coords: dict) -> dict:
    return {k: v for k, v in coords.items() if k != "sheet_over_web"}


def grid_strain_factor(g: ElementGeometry, material: Material, grid_length_mm: float,
                       grid_width_mm: float,
                       correction: StrainCorrection | None = None) -> StrainFactor:
    """C for the EB grid average of a grid ``grid_length_mm`` x ``grid_width_mm`` centred
    over the notch (mm); ``correction`` defaults to the fitted file's.

    Returns:
        :class:`StrainFactor` (error: the fit's, plus the extrapolation change outside).
    """
    corr = correction or load_strain_correction()
    coords = model_coordinates(g, material, grid_length_mm, grid_width_mm)
    return _rated(corr, coords, lambda c: corr.factor(**_model_args(c)))


def point_strain_factor(g: ElementGeometry, material: Material,
                        correction: StrainCorrection | None = None) -> StrainFactor:
    """C for the EB surface strain at the notch centre, mid-width (xi = 0, W = 0)."""
    return grid_strain_factor(g, material, 0.0, 0.0, correction)


def point_factor(web_mm, notch_radius_mm, sheet_mm, poisson_ratio,
                 correction: StrainCorrection | None = None):
    """C at the notch centre, mid-width, for arrays of webs, notch radii and sheets (mm;
    broadcast, no range check: for design searches, whose candidates are not the design)."""
    import numpy as np

    corr = correction or load_strain_correction()
    t, R, b = (np.asarray(v, float) for v in (web_mm, notch_radius_mm, sheet_mm))
    return corr.factor(t / R, np.sqrt(t * R) / b, poisson_ratio, 0.0, 0.0)


def width_strain_factor(g: ElementGeometry, material: Material, grid_width_mm: float,
                        correction: StrainCorrection | None = None) -> StrainFactor:
    """1 - nu^2 phi alone, for a plane-stress field whose profile along x is its own
    (fem2d); error as :func:`grid_strain_factor`."""
    corr = correction or load_strain_correction()
    coords = model_coordinates(g, material, 0.0, grid_width_mm)
    return _rated(corr, coords, lambda c: corr.plane_strain_factor(
        c["width_ratio"], c["poisson_ratio"], c["grid_width_over_sheet"]))


@dataclass(frozen=True)
class BondedGrid:
    """What the bonded layer does at the web (module doc, transformed section).

    Attributes:
        read_factor: grid strain / bare surface strain under the same moment.
        height_factor: (t/2 + h_g) / (t/2), the layer without stiffness.
        stiffening_rel: EI_c / EI_0 - 1 at the web (the hinge's bending stiffness
            rises by at most this; the layer covers only the gauge's length).
        neutral_axis_shift_mm: e, the neutral axis above the web's mid-plane (mm).
    """

    read_factor: float
    height_factor: float
    stiffening_rel: float
    neutral_axis_shift_mm: float


def bonded_grid_factor(web_mm: float, sheet_mm: float, youngs_modulus_MPa: float,
                       grid_height_mm: float, layer_modulus_MPa: float,
                       layer_width_mm: float) -> BondedGrid:
    """Grid strain over bare surface strain of a web with a bonded gauge layer.

    Args:
        web_mm: web thickness t. sheet_mm: web width b. youngs_modulus_MPa: E of the web.
        grid_height_mm: glue line + carrier under the grid, h_g (>= 0).
        layer_modulus_MPa: E_l of carrier and glue line (>= 0).
        layer_width_mm: the carrier's width across the sheet (<= b).

    Returns:
        :class:`BondedGrid`.

    Raises:
        ValueError: t, b or E not > 0, or h_g, E_l or the width < 0.
    """
    t, b, E, h, El, Wl = (float(v) for v in (web_mm, sheet_mm, youngs_modulus_MPa,
                                              grid_height_mm, layer_modulus_MPa, layer_width_mm))
    if not (t > 0 and b > 0 and E > 0) or min(h, El, Wl) < 0:
        raise ValueError(f"bonded_grid_factor: web {t!r}, sheet {b!r} mm and E {E!r} MPa must be "
                         f"> 0; grid height {h!r} mm, layer modulus {El!r} MPa and width {Wl!r} "
                         "mm >= 0")
    read, stiffening, e = transformed_section(t, b, E, h, El, Wl)
    return BondedGrid(float(read), (t / 2 + h) / (t / 2), float(stiffening), float(e))


def transformed_section(web_mm, sheet_mm, youngs_modulus_MPa, grid_height_mm,
                        layer_modulus_MPa, layer_width_mm):
    """(read factor, EI_c / EI_0 - 1, neutral-axis shift e (mm)) of a web with a bonded
    layer, broadcast over arrays, unchecked (:func:`bonded_grid_factor` checks one)."""
    t, b, E, h, El, Wl = (np.asarray(v, float) for v in (
        web_mm, sheet_mm, youngs_modulus_MPa, grid_height_mm, layer_modulus_MPa,
        layer_width_mm))
    # heights from the web's mid-plane; the layer spans t/2 ... t/2 + h
    ea_web, ea_layer = E * b * t, El * Wl * h
    e = ea_layer * (t / 2 + h / 2) / (ea_web + ea_layer)
    ei_0 = E * b * t ** 3 / 12.0
    ei_c = (ei_0 + ea_web * e * e + El * Wl * h ** 3 / 12.0
            + ea_layer * (t / 2 + h / 2 - e) ** 2)
    read = ((t / 2 + h - e) / ei_c) / ((t / 2) / ei_0)
    return read, ei_c / ei_0 - 1.0, e


def face_under_layer_factor(web_mm, sheet_mm, youngs_modulus_MPa, grid_height_mm,
                            layer_modulus_MPa, layer_width_mm):
    """The face strain under a bonded layer over the bare face's, under the same moment
    (dimensionless, <= 1; broadcast over arrays, unchecked): the transformed section's
    (t/2 - e) / EI_c against the bare web's (t/2) / EI_0, i.e.
    (1 - 2 e / t) / (EI_c / EI_0), e and EI_c of :func:`transformed_section` (the same
    section as the grid's read factor). 1 for a layer of no modulus or no height.

    Args: as :func:`bonded_grid_factor` (mm, MPa).

    Source: the transformed (composite) section, e.g. Gere and Goodno, Mechanics of
    Materials, sec. 6.2; Timoshenko and Gere, Mechanics of Materials (composite beams).
    """
    t = np.asarray(web_mm, float)
    _, stiffening, e = transformed_section(web_mm, sheet_mm, youngs_modulus_MPa,
                                           grid_height_mm, layer_modulus_MPa, layer_width_mm)
    return (1.0 - 2.0 * e / t) / (1.0 + stiffening)
