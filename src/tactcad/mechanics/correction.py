"""The fem3d-fitted correction of the closed-form stiffness: model, range, JSON.

The closed form (:mod:`tactcad.mechanics.closed_form`) is Euler-Bernoulli
(EB) with Timoshenko shear. Against fem3d it errs in two ways:

* beam theory is too stiff at a short, deep notch (plane sections do not
  stay plane; the notch's bending reaches into the arm and the base), by an
  amount that grows with s = t/R (t web thickness, R notch radius);
* a sheet much wider (b) than the hinge's bending length sqrt(t R) holds
  the web near plane strain (the thick base and arm restrain its
  anticlastic bending), stiffer than the beam's plane stress by up to
  1 / (1 - nu^2); a sheet narrower than sqrt(t R) bends in plane stress.

Model (E scales out of K; every input is dimensionless)::

    K = K_EB * (1 + g) / (1 + q (c1 s + c2 s^2) + p c6 + r c7),
    g = nu^2 / (1 - nu^2) * c3 / (1 + c4 w + c5 w^2 + c8 v),
    s = t / R,  w = sqrt(t R) / b,  v = t / b,
    q = C_notch_bending / C_EB,  p = C_notch_shear / C_EB,  r = C_arm_bending / C_EB,

where q, p and r are the notch-bending, notch-shear and arm-bending shares
of the closed form's tip compliance C_EB = 1 / K_EB and nu the Poisson
ratio. c1, c2 carry the notch-theory error (plane sections through a deep
notch); c3 = 1 would be the plane-strain limit at w -> 0, and the 3D gain
fades as the hinge's bending length sqrt(t R) and the web thickness t grow
against the sheet b. c6 rescales the notch's Timoshenko shear term and c7
the arm-bending term: they matter only for thick webs and short arms (q well
below 1), where the force-proportional compliance of the notch and the
arm-root rotation are not beam-like. c7 is an empirical term (it absorbs
how the notch and the arm root interact, not a property of the arm alone);
leave-one-out and hold-out checks in the JSON file show it generalises over
the domain.

The coefficients are least-squares fits (scipy.optimize.least_squares, relative
residuals) to fem3d over a grid of designs (:mod:`tactcad.studies.correction_sweep`,
fitted by :mod:`tactcad.studies.correction_fit`); the file ``src/tactcad/data/stiffness_correction.json`` stores them with the range
of every fitted coordinate, the max / rms residual, the hold-out check and
the points. Outside the range the closed form warns with an estimated error:
the fit's largest residual plus the change of the correction factor between
the point and its projection onto the fitted range, plus, for an arm longer
than the fitted arm / arm height (a / h_a) allows, a measured growth
k r (a / h_a - its fitted end): r the arm-bending share of the compliance (the
arm term c7 r is what extrapolates), k the slope per unit of a / h_a and of r
(``arm_aspect_extrapolation`` in the file: k and the fem3d points it bounds
with a margin, with their source).

Units: mm, N, MPa, N/mm (K), mm/N (compliance C).
"""

from __future__ import annotations

import json
import math
import warnings
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any, Iterator, Mapping

import numpy as np

from tactcad.errors import DesignError

#: The file the closed form reads.
CORRECTION_FILE = Path(__file__).resolve().parents[1] / "data" / "stiffness_correction.json"

MODEL = ("K = K_EB * (1 + g) / (1 + q*(c1*s + c2*s^2) + p*c6 + r*c7), g = nu^2/(1 - nu^2) * "
         "c3 / (1 + c4*w + c5*w^2 + c8*v), s = t/R, w = sqrt(t*R)/b, v = t/b, "
         "q = C_notch_bending / C_EB, p = C_notch_shear / C_EB, r = C_arm_bending / C_EB")

COEFFICIENT_NAMES = ("c1", "c2", "c3", "c4", "c5", "c6", "c7", "c8")
N_COEFFICIENTS = len(COEFFICIENT_NAMES)

#: Relative stiffness bias of the uncorrected closed form against fem3d per
#: unit t/R (single-sided circular notch; the error estimate of the identity).
UNCORRECTED_BIAS_PER_T_OVER_R = 0.39

#: The fitted coordinate whose range end an arm's measured error growth is counted from.
ARM_ASPECT_KEY = "arm_over_arm_height"

#: Coordinates whose fitted range is stored and checked (dimensionless
#: ratios and the physical sizes they come from).
RANGE_KEYS = ("t_over_R", "width_ratio", "web_over_sheet", "poisson_ratio", "web_mm",
              "notch_radius_mm", "arm_mm", "sheet_mm", "arm_over_arm_height")


#: What a range warning's estimated error is of: the correction's on the bare element, which a
#: result's `error estimate` row (K, with its bonded gauge) raises by its layer's share.
BARE_K_SAID = ("the correction's, on the bare element's K; a result's `error estimate` adds "
               "its gauge layer's share")


class CorrectionRangeWarning(UserWarning):
    """A correction is applied outside the range it was fitted over.

    A command or an API call says all of its run's such warnings as one line
    (:meth:`merged_text`, through :class:`tactcad.commands.notices.WarningLines`):
    the nominal elements and the ends of their web tolerance would otherwise say the
    same range three times.

    Attributes:
        error_rel: the estimated relative error there (dimensionless).
        left: {coordinate: (least value, largest value, fitted low, fitted high)} of the
            coordinates left (:data:`RANGE_KEYS`).
        where: what the estimate was of, when not the element as drawn (e.g. an end of its
            web tolerance); "" for the element as drawn.
        merge_as: what a run's output merges such warnings under.
    """

    merge_as = "closed-form stiffness correction used outside its fitted range"

    def __init__(self, message: str, error_rel: float = 0.0,
                 left: Mapping[str, tuple[float, float, float, float]] | None = None,
                 where: str = ""):
        super().__init__(message)
        self.error_rel = float(error_rel)
        self.left = dict(left or {})
        self.where = where

    @staticmethod
    def merged_text(said: "list[CorrectionRangeWarning]") -> str:
        """One line for every range warning of a run: each coordinate left with the values
        it took over all of them and its fitted range, and the largest estimated error with
        the values of the estimate it belongs to (the worst). One warning keeps its own
        text; one without its values (a bare text) is named by its text alone.

        Args:
            said: the warnings, in the order issued (at least one).

        Returns:
            The line (no trailing newline).
        """
        if len(said) == 1 or not all(w.left for w in said):
            return "; ".join(dict.fromkeys(str(w) for w in said))
        names = list(dict.fromkeys(k for w in said for k in w.left))
        parts = []
        for k in names:
            drawn = [w.left[k] for w in said if k in w.left and not w.where]
            spans = drawn or [w.left[k] for w in said if k in w.left]
            lo, hi = min(v[0] for v in spans), max(v[1] for v in spans)
            fit_lo, fit_hi = spans[0][2], spans[0][3]
            vals = f"{lo:.4g}" if f"{lo:.4g}" == f"{hi:.4g}" else f"{lo:.4g} ... {hi:.4g}"
            parts.append(f"{k} ({RANGE_WORDS.get(k, k)}) {vals}, fitted {fit_lo:.4g} ... "
                         f"{fit_hi:.4g}" + ("" if drawn else " (only at a web tolerance's end)"))
        worst = max(said, key=lambda w: w.error_rel)
        at = ", ".join(f"{RANGE_WORDS.get(k, k)} {v[1] if v[1] > v[3] else v[0]:.4g}"
                       for k, v in worst.left.items())
        what = ("elements as drawn and at the ends of their web tolerance, the K band "
                "`verify` reads" if any(w.where for w in said) else "elements")
        return (f"closed-form stiffness correction used outside its fitted range "
                f"({'; '.join(parts)}) by {len(said)} estimates ({what}); estimated error up "
                f"to {100 * worst.error_rel:.2g} % at the worst, {at}"
                f"{' ' + worst.where if worst.where else ''} ({BARE_K_SAID}; the correction is "
                "fitted to fem3d solves of elements inside that range; `tactcad stiffness "
                "--model fem3d` solves an element without it)")


@contextmanager
def range_warnings_unsaid() -> Iterator[None]:
    """Estimates made inside issue no :class:`CorrectionRangeWarning`: for the
    candidates a search weighs or a grid's points, which are not the design
    the user asked about (or report their range themselves)."""
    from tactcad.mechanics.gauge_strain import GaugeStrainRangeWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CorrectionRangeWarning)
        warnings.simplefilter("ignore", GaugeStrainRangeWarning)
        yield


_INF_RANGE = (0.0, math.inf)


def _as_range(name: str, value: Any) -> tuple[float, float]:
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise DesignError(name, value, "a pair [low, high]") from None
    if math.isnan(lo) or math.isnan(hi) or lo < 0 or hi < lo:
        raise DesignError(name, value, "0 <= low <= high")
    return (lo, hi)


@dataclass(frozen=True)
class FitRange:
    """Closed intervals a correction was fitted over (unbounded by default).

    Attributes:
        t_over_R: web thickness over notch radius.
        width_ratio: w = sqrt(t R) / b, hinge bending length over sheet thickness.
        web_over_sheet: v = t / b.
        poisson_ratio: nu.
        web_mm, notch_radius_mm, arm_mm, sheet_mm: t, R, lever a, sheet b (mm).
        arm_over_arm_height: a / h_a.
    """

    t_over_R: tuple[float, float] = _INF_RANGE
    width_ratio: tuple[float, float] = _INF_RANGE
    web_over_sheet: tuple[float, float] = _INF_RANGE
    poisson_ratio: tuple[float, float] = _INF_RANGE
    web_mm: tuple[float, float] = _INF_RANGE
    notch_radius_mm: tuple[float, float] = _INF_RANGE
    arm_mm: tuple[float, float] = _INF_RANGE
    sheet_mm: tuple[float, float] = _INF_RANGE
    arm_over_arm_height: tuple[float, float] = _INF_RANGE

    def __post_init__(self):
        for name in RANGE_KEYS:
            object.__setattr__(self, name, _as_range(f"fit_range.{name}", getattr(self, name)))

    def outside(self, **coords) -> dict[str, np.ndarray]:
        """{name: mask} of the given coordinates that leave their range.

        A relative slack of 1e-9 absorbs rounding at the range ends; ``None``
        values are not checked.
        """
        out = {}
        for name, v in coords.items():
            if v is None:
                continue
            lo, hi = getattr(self, name)
            v = np.asarray(v, dtype=float)
            tol = 1e-9 * max(abs(lo), abs(hi) if math.isfinite(hi) else abs(lo), 1e-300)
            mask = (v < lo - tol) | (v > hi + tol)
            if np.any(mask):
                out[name] = mask
        return out

    def clip(self, name: str, value) -> np.ndarray:
        """``value`` projected onto the range of ``name``."""
        lo, hi = getattr(self, name)
        return np.clip(np.asarray(value, dtype=float), lo, hi)

    def as_json(self) -> dict:
        return {k: list(getattr(self, k)) for k in RANGE_KEYS
                if getattr(self, k) != _INF_RANGE}


def _gain_and_denominator(c, s, w, nu, q, p, r, v) -> tuple[np.ndarray, np.ndarray]:
    """(1 + g, 1 + q (c1 s + c2 s^2) + p c6 + r c7) of the model (module doc)."""
    s, w, nu, q, p, r, v = (np.asarray(x, dtype=float) for x in (s, w, nu, q, p, r, v))
    gain = 1.0 + nu * nu / (1.0 - nu * nu) * c[2] / (1.0 + c[3] * w + c[4] * w * w + c[7] * v)
    den = 1.0 + q * (c[0] * s + c[1] * s * s) + p * c[5] + r * c[6]
    return gain, den


@dataclass(frozen=True)
class Correction:
    """fem3d-fitted correction of the closed-form stiffness (model in the module doc).

    Attributes:
        coefficients: (c1, c2, c3[, ..., c8]); missing trailing ones are 0.
        fit_range: :class:`FitRange` of the fit.
        residual_rel: largest relative residual |K_fit / K_fem3d - 1| of the
            fit (``None`` for the identity).
        source: what the reference was (model, meshes, grid).
        arm_aspect_slope_rel: k of the error estimate's growth k r (a / h_a - end) past
            the fitted arm / arm height's upper end (relative error per unit of a / h_a
            and of the arm-bending share r, >= 0; the JSON's
            ``arm_aspect_extrapolation.slope_rel_per_unit``, measured against fem3d past
            the range; 0: no growth counted).

    Raises:
        DesignError: non-finite coefficients, a negative residual or slope, or a
            denominator 1 + c1 s + c2 s^2 <= 0 over a finite t/R range.
    """

    coefficients: tuple[float, ...] = (0.0,) * N_COEFFICIENTS
    fit_range: FitRange = field(default_factory=FitRange)
    residual_rel: float | None = None
    source: str = "none: uncorrected Euler-Bernoulli"
    arm_aspect_slope_rel: float = 0.0

    def __post_init__(self):
        try:
            coeffs = tuple(float(c) for c in self.coefficients)
        except (TypeError, ValueError):
            raise DesignError("coefficients", self.coefficients, "numbers c1 ... c8") from None
        if not 3 <= len(coeffs) <= N_COEFFICIENTS or not all(math.isfinite(c) for c in coeffs):
            raise DesignError("coefficients", self.coefficients, "3 to 8 finite numbers c1 ... c8")
        coeffs = coeffs + (0.0,) * (N_COEFFICIENTS - len(coeffs))
        object.__setattr__(self, "coefficients", coeffs)
        if not isinstance(self.fit_range, FitRange):
            raise DesignError("fit_range", self.fit_range, "a FitRange")
        if self.residual_rel is not None:
            r = float(self.residual_rel)
            if not math.isfinite(r) or r < 0:
                raise DesignError("residual_rel", self.residual_rel, "a finite number >= 0")
            object.__setattr__(self, "residual_rel", r)
        try:
            slope = float(self.arm_aspect_slope_rel)
        except (TypeError, ValueError):
            slope = math.nan
        if not math.isfinite(slope) or slope < 0:
            raise DesignError("arm_aspect_extrapolation.slope_rel_per_unit",
                              self.arm_aspect_slope_rel, "a finite number >= 0")
        object.__setattr__(self, "arm_aspect_slope_rel", slope)
        lo, hi = self.fit_range.t_over_R
        if math.isfinite(hi) and np.any(self._notch_term(np.linspace(lo, hi, 65)) <= -1):
            raise DesignError("coefficients", coeffs,
                              "1 + c1 s + c2 s^2 > 0 over the t/R fit range")

    @property
    def is_identity(self) -> bool:
        return not any(self.coefficients)

    def _notch_term(self, s) -> np.ndarray:
        return _gain_and_denominator(self.coefficients, s, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)[1] - 1.0

    def factor(self, t_over_R, width_ratio=0.0, poisson_ratio=0.33, notch_share=1.0,
               shear_share=0.0, arm_share=0.0, web_over_sheet=0.0) -> np.ndarray:
        """K / K_EB at s = t/R, w = sqrt(t R)/b, nu, q, p, r and v = t/b
        (array-like, broadcast; module doc).

        Raises:
            ValueError: a denominator <= 0 (far outside the fitted range).
        """
        gain, den = _gain_and_denominator(self.coefficients, t_over_R, width_ratio, poisson_ratio,
                                          notch_share, shear_share, arm_share, web_over_sheet)
        if np.any(den <= 0) or np.any(gain <= 0):
            raise ValueError("correction factor not positive at t/R = "
                             f"{np.ravel(np.asarray(t_over_R, float))[:3].tolist()}, w = "
                             f"{np.ravel(np.asarray(width_ratio, float))[:3].tolist()}")
        return gain / den

    def error_estimate_rel(self, t_over_R, width_ratio=0.0, poisson_ratio=0.33,
                           notch_share=1.0, shear_share=0.0, arm_share=0.0,
                           web_over_sheet=0.0, arm_over_arm_height=None) -> np.ndarray:
        """Estimated relative error of the corrected closed form.

        Identity: 0.39 t/R (the uncorrected bias). Fitted: the largest fit
        residual, plus, outside the fitted t/R, w or nu range, the change of
        the factor between the point and its projection onto the range, plus,
        past the fitted arm / arm height's upper end, k r (a / h_a - end) with k
        :attr:`arm_aspect_slope_rel` and r the arm-bending share (the growth
        measured against fem3d there: it grows with the distance from the range).

        Args:
            t_over_R, width_ratio, poisson_ratio, notch_share, shear_share, arm_share,
                web_over_sheet: the model's coordinates (module doc; dimensionless).
            arm_over_arm_height: a / h_a (dimensionless), or None: not counted.

        Returns:
            The relative error (dimensionless), broadcast over the arguments.
        """
        s = np.asarray(t_over_R, dtype=float)
        if self.is_identity or self.residual_rel is None:
            return UNCORRECTED_BIAS_PER_T_OVER_R * s
        fr = self.fit_range
        f = self.factor(s, width_ratio, poisson_ratio, notch_share, shear_share, arm_share,
                        web_over_sheet)
        f_in = self.factor(fr.clip("t_over_R", s), fr.clip("width_ratio", width_ratio),
                           fr.clip("poisson_ratio", poisson_ratio), notch_share, shear_share,
                           arm_share, fr.clip("web_over_sheet", web_over_sheet))
        err = self.residual_rel + np.abs(f / f_in - 1.0)
        hi = fr.arm_over_arm_height[1]
        if arm_over_arm_height is not None and self.arm_aspect_slope_rel and math.isfinite(hi):
            beyond = np.maximum(np.asarray(arm_over_arm_height, dtype=float) - hi, 0.0)
            err = err + self.arm_aspect_slope_rel * np.asarray(arm_share, dtype=float) * beyond
        return err

    def as_json(self) -> dict:
        """The part of the JSON document :func:`load_correction` reads."""
        doc = {"model": MODEL,
               "coefficients": dict(zip(COEFFICIENT_NAMES, self.coefficients)),
               "fit_range": self.fit_range.as_json(),
               "residual_rel_max": self.residual_rel, "source": self.source}
        if self.arm_aspect_slope_rel:
            doc["arm_aspect_extrapolation"] = {"slope_rel_per_unit": self.arm_aspect_slope_rel}
        return doc

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> "Correction":
        """Inverse of :meth:`as_json` (extra keys are ignored).

        Raises:
            DesignError: missing keys or invalid values (field named).
        """
        if not isinstance(data, Mapping):
            raise DesignError("stiffness_correction", type(data).__name__, "a JSON object")
        try:
            co = data["coefficients"]
            coeffs = tuple(co.get(k, 0.0) for k in COEFFICIENT_NAMES)
            fr = data["fit_range"]
            unknown = set(fr) - set(RANGE_KEYS)
            if unknown:
                raise DesignError("stiffness_correction.fit_range", sorted(unknown),
                                  "keys " + ", ".join(RANGE_KEYS))
            rng = FitRange(**{k: fr[k] for k in RANGE_KEYS if k in fr})
            residual = data["residual_rel_max"]
            source = data["source"]
            slope = (data.get("arm_aspect_extrapolation") or {}).get("slope_rel_per_unit", 0.0)
        except (KeyError, TypeError, AttributeError) as exc:
            raise DesignError(f"stiffness_correction.{exc.args[0] if exc.args else '?'}", None,
                              "keys model, coefficients{c1..c8}, fit_range, residual_rel_max, "
                              "source") from None
        if data.get("model", MODEL) != MODEL:
            raise DesignError("stiffness_correction.model", data.get("model"), MODEL)
        if not isinstance(source, str) or not source.strip():
            raise DesignError("stiffness_correction.source", source, "a non-empty string")
        return cls(coefficients=coeffs, fit_range=rng, residual_rel=residual, source=source,
                   arm_aspect_slope_rel=slope)


#: The identity correction (uncorrected closed form).
IDENTITY = Correction()


def load_correction(path: str | Path | None = None) -> Correction:
    """Read the fitted correction; the identity when the file does not exist.

    File (JSON, default ``src/tactcad/data/stiffness_correction.json``): the
    keys of :meth:`Correction.as_json` (``model`` must be :data:`MODEL`),
    plus the fit's points and statistics, which are not read here.

    Raises:
        DesignError: unreadable JSON or invalid content (the field is named).
    """
    p = Path(path) if path is not None else CORRECTION_FILE
    try:
        st = p.stat()
    except FileNotFoundError:
        return IDENTITY
    except OSError as exc:
        raise DesignError("stiffness_correction", str(p), "a readable JSON file",
                          str(exc)) from None
    # every closed-form estimate asks for the file (an inverse design or a sweep
    # many thousand times); it is read again only when it changed
    return _read_correction(str(p), (st.st_dev, st.st_ino), st.st_mtime_ns, st.st_size)


@lru_cache(maxsize=8)
def _read_correction(path: str, file_id: tuple[int, int], mtime_ns: int, size: int) -> Correction:
    # the path as given (named in errors) with the file's identity (device,
    # inode): a refit that writes the file anew changes the inode, one in place
    # its time or size
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise DesignError("stiffness_correction", path, "a readable JSON file", str(exc)) from None
    return Correction.from_json(data)


def apply_correction(K_eb, t_over_R, correction: Correction = IDENTITY, *, width_ratio=0.0,
                     poisson_ratio=0.33, notch_share=1.0, shear_share=0.0, arm_share=0.0,
                     web_over_sheet=0.0, web_mm=None, notch_radius_mm=None,
                     arm_mm=None, sheet_mm=None, arm_over_arm_height=None,
                     warn: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Corrected stiffness and the mask of points inside the fitted range.

    Args:
        K_eb: uncorrected closed-form stiffness (N/mm), array-like.
        t_over_R, width_ratio, poisson_ratio, notch_share, shear_share, arm_share,
            web_over_sheet: the model's coordinates s, w, nu, q, p, r, v (module
            doc), broadcast with ``K_eb``.
        correction: the correction (default: identity).
        web_mm, notch_radius_mm, arm_mm, sheet_mm, arm_over_arm_height:
            optional, also checked against the fitted range.
        warn: emit :class:`CorrectionRangeWarning` (with the estimated
            error) when any point lies outside.

    Returns:
        (K, inside): corrected K (N/mm) and a boolean mask, True where every
        given coordinate lies in the fitted range.

    Raises:
        ValueError: the correction factor is not positive somewhere.
    """
    shares = (notch_share, shear_share, arm_share, web_over_sheet)
    K = np.asarray(K_eb, dtype=float) * correction.factor(t_over_R, width_ratio, poisson_ratio,
                                                           *shares)
    coords = dict(t_over_R=t_over_R, width_ratio=width_ratio, web_over_sheet=web_over_sheet,
                  poisson_ratio=poisson_ratio,
                  web_mm=web_mm, notch_radius_mm=notch_radius_mm, arm_mm=arm_mm,
                  sheet_mm=sheet_mm, arm_over_arm_height=arm_over_arm_height)
    out = correction.fit_range.outside(**coords)
    outside = np.zeros(K.shape, dtype=bool)
    for mask in out.values():
        outside |= np.broadcast_to(mask, K.shape)
    if warn and out:
        err = correction.error_estimate_rel(t_over_R, width_ratio, poisson_ratio, *shares,
                                            arm_over_arm_height=arm_over_arm_height)
        warn_outside(correction, out, int(np.count_nonzero(outside)), int(K.size),
                     float(np.max(np.broadcast_to(err, K.shape)[outside])),
                     values={k: np.asarray(coords[k], float)[mask] for k, mask in out.items()})
    return K, ~outside


#: Each coordinate of :class:`FitRange` in a user's words (the element's own dimensions).
RANGE_WORDS = {"t_over_R": "web thickness / notch radius",
               "width_ratio": "hinge bending length / sheet thickness",
               "web_over_sheet": "web thickness / sheet thickness",
               "poisson_ratio": "the material's Poisson's ratio",
               "web_mm": "web thickness, mm", "notch_radius_mm": "notch radius, mm",
               "arm_mm": "lever arm, mm", "sheet_mm": "sheet thickness, mm",
               "arm_over_arm_height": "arm length / arm height"}


def _values_said(values: np.ndarray) -> str:
    """The values a coordinate took outside its range: one, or the span of several."""
    lo, hi = float(np.min(values)), float(np.max(values))
    return f"{lo:.4g}" if f"{lo:.4g}" == f"{hi:.4g}" else f"{lo:.4g} ... {hi:.4g}"


def warn_outside(correction: Correction, out: Mapping[str, np.ndarray], n_out: int, n: int,
                 error_rel: float, values: Mapping[str, np.ndarray] | None = None) -> None:
    """Warn that ``n_out`` of ``n`` points leave the fitted range: each coordinate left by
    name, in words (:data:`RANGE_WORDS`), with the values it took outside (``values``, by
    name; a point just past an end reads as that end when only the range is said) and its
    range, the estimated error and how to solve without the correction. The fit's own
    record (``correction.source``) stays in the data file: it names the studies that made
    it, not what a user acts on."""
    fr = correction.fit_range
    values = values or {}
    which = ", ".join(f"{k} ({RANGE_WORDS.get(k, k)}) "
                      + (f"{_values_said(values[k])}, fitted " if np.size(values.get(k)) else "")
                      + f"{getattr(fr, k)[0]:.4g} ... {getattr(fr, k)[1]:.4g}" for k in out)
    left = {k: (float(np.min(values[k])), float(np.max(values[k])), *getattr(fr, k))
            for k in out if np.size(values.get(k))}
    warnings.warn(CorrectionRangeWarning(
        f"closed-form stiffness correction used outside its fitted range at {n_out} of {n} "
        f"points ({which}); estimated error up to {100 * error_rel:.2g} % ({BARE_K_SAID}; the "
        "correction is fitted to fem3d solves of elements inside that range; `tactcad "
        "stiffness --model fem3d` solves an element without it)", error_rel,
        left if len(left) == len(out) else None), stacklevel=3)
