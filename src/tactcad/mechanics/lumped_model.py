"""Lumped spring model of a stiffness sensing unit (paper eq. 1-3).

A unit is a measuring element of stiffness K_m and a reference element of
stiffness K_r > K_m, both pressed by the same displacement Δ into an object of
stiffness K_obj. Each element is a spring in series with the object spring
under it; δ_m and δ_r are the object indentations under the two elements and
Δ−δ_m, Δ−δ_r the element deflections (paper Fig. 1a):

* eq. 1: δ_m = K_m Δ/(K_obj + K_m),  δ_r = K_r Δ/(K_obj + K_r)
* eq. 2: R = (Δ−δ_m)/(Δ−δ_r) = (K_r + K_obj)/(K_m + K_obj)
* eq. 3: K_obj = (K_r − R K_m)/(R − 1)

Units: stiffness in N/mm, displacement in mm, force in N; R is dimensionless.

Domain: K_m, K_r, K_obj finite and > 0, K_r > K_m, hence 1 < R < K_r/K_m.

Calling convention (every function except :func:`simulate_unit`):

* all arguments scalar (Python or NumPy 0-d): returns a ``float`` (or a
  :class:`UnitDeflections` of floats) and raises :class:`LumpedDomainError`,
  naming the failed condition and the value, when an input is out of domain;
* any argument an array (ndim >= 1): the arguments broadcast and the call
  returns ``Masked(value, valid)``: ``value`` holds the result with NaN where
  the inputs are out of domain, ``valid`` is the boolean mask of in-domain
  entries. Nothing is raised for out-of-domain entries.

Numerics. The formulas are written in the forms with the smallest rounding
error (u = 2**-53, the unit round-off of float64):

* R − 1 = (K_r − K_m)/(K_m + K_obj) (no cancellation; relative error <= 3u),
  available as :func:`deflection_ratio_excess`; R = 1 + that (<= 4u, and
  monotonic in K_obj after rounding);
* K_obj = (K_r − K_m)/(R − 1) − K_m, the rearranged eq. 3. R − 1 is exact
  for 1 < R <= 2 (Sterbenz), K_r − K_m has relative error <= u, and the final
  subtraction is benign unless K_obj << K_m, so the relative error is at most
  (4 + 3 K_m/K_obj) u. The printed form (K_r − R K_m)/(R − 1) rounds R K_m
  before the subtraction and loses all accuracy when K_r → K_m.
* dK_obj/dR = −(K_r − K_m)/(R − 1)² (relative error <= 5u).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from tactcad.errors import TactcadError


class LumpedDomainError(TactcadError, ValueError):
    """An input of the lumped model is outside its domain.

    The message names the quantity, its value and the condition it fails, e.g.
    ``R = 0.98: must satisfy 1 < R < K_r/K_m = 2.00349``.

    Attributes:
        quantity: symbol of the offending input (``"R"``, ``"K_m"``, ...).
        value: the offending value.
        condition: the condition it fails, with bounds.
    """

    def __init__(self, quantity: str, value: object, condition: str):
        self.quantity = quantity
        self.value = value
        self.condition = condition
        super().__init__(f"{quantity} = {_fmt(value)}: must satisfy {condition}")


class Masked(NamedTuple):
    """Result of an array call.

    Attributes:
        value: the result, broadcast shape of the inputs, NaN where out of
            domain (a :class:`UnitDeflections` of such arrays for
            :func:`element_deflections`).
        valid: boolean array, same shape, True where the inputs are in domain.
    """

    value: object
    valid: np.ndarray


class UnitDeflections(NamedTuple):
    """Deflections of a sensing unit pressed by Δ into an object (eq. 1), all in mm.

    Attributes:
        delta_m: δ_m, object indentation under the measuring element.
        delta_r: δ_r, object indentation under the reference element.
        element_m: Δ − δ_m, deflection of the measuring element.
        element_r: Δ − δ_r, deflection of the reference element.
    """

    delta_m: float | np.ndarray
    delta_r: float | np.ndarray
    element_m: float | np.ndarray
    element_r: float | np.ndarray


class SimulatedUnit(NamedTuple):
    """Force-equilibrium solution of the unit's spring network (:func:`simulate_unit`).

    Attributes:
        delta_m: object indentation under the measuring element δ_m (mm).
        delta_r: object indentation under the reference element δ_r (mm).
        element_m: measuring-element deflection Δ − δ_m (mm).
        element_r: reference-element deflection Δ − δ_r (mm).
        force_m: force through the measuring element (N).
        force_r: force through the reference element (N).
        total_force: force needed to hold the displacement Δ (N).
    """

    delta_m: float
    delta_r: float
    element_m: float
    element_r: float
    force_m: float
    force_r: float
    total_force: float


# ---------------------------------------------------------------------------
# Domain checks
# ---------------------------------------------------------------------------
def _fmt(value: object) -> str:
    try:
        return repr(float(value))  # shortest repr that round-trips
    except (TypeError, ValueError):
        return repr(value)


def _fmt_bound(bound: object, value: object) -> str:
    """``bound`` to 6 significant digits, or more until it reads differently from ``value``."""
    b, v = float(bound), float(value)
    for digits in range(6, 18):
        text = f"{b:.{digits}g}"
        if b == v or text != f"{v:.{digits}g}":
            return text
    return repr(b)


@dataclass(frozen=True)
class _Check:
    """One domain condition: elementwise ``ok`` and the error to raise for a scalar."""

    ok: np.ndarray
    error: Callable[[], LumpedDomainError]


def _positive(symbol: str, x: np.ndarray, unit: str = " N/mm") -> _Check:
    with np.errstate(invalid="ignore"):
        ok = np.isfinite(x) & (x > 0)
    return _Check(ok, lambda: LumpedDomainError(symbol, x, f"{symbol} > 0{unit}, finite"))


def _non_negative(symbol: str, x: np.ndarray, unit: str) -> _Check:
    with np.errstate(invalid="ignore"):
        ok = np.isfinite(x) & (x >= 0)
    return _Check(ok, lambda: LumpedDomainError(symbol, x, f"{symbol} >= 0{unit}, finite"))


def _ordered(k_m: np.ndarray, k_r: np.ndarray) -> _Check:
    with np.errstate(invalid="ignore"):
        ok = k_r > k_m
    return _Check(ok, lambda: LumpedDomainError(
        "K_r", k_r, f"K_r > K_m = {_fmt(k_m)} N/mm (the reference element is the stiffer one)"))


def _stiffness_checks(k_m: np.ndarray, k_r: np.ndarray) -> list[_Check]:
    return [_positive("K_m", k_m), _positive("K_r", k_r), _ordered(k_m, k_r)]


def _ratio_check(symbol: str, shown: np.ndarray, s: np.ndarray, q: np.ndarray,
                 k_m: np.ndarray, k_r: np.ndarray) -> _Check:
    """R in (1, K_r/K_m), tested as s = R − 1 > 0 and q = (K_r − K_m)/s > K_m.

    Testing q > K_m rather than R < K_r/K_m guarantees that the computed
    K_obj = q − K_m is positive and finite.
    """
    with np.errstate(invalid="ignore"):
        ok = (s > 0) & np.isfinite(q) & (q > k_m)

    def error() -> LumpedDomainError:
        if symbol == "R":
            cond = f"1 < R < K_r/K_m = {_fmt_bound(k_r / k_m, shown)}"
        else:
            cond = f"0 < R - 1 < (K_r - K_m)/K_m = {_fmt_bound((k_r - k_m) / k_m, shown)}"
        if s > 0 and not np.isfinite(q):
            cond += " (K_obj overflows at this value)"
        return LumpedDomainError(symbol, shown, cond)

    return _Check(ok, error)


def _broadcast(*args: object) -> tuple[bool, list[np.ndarray]]:
    scalar = all(np.ndim(a) == 0 for a in args)
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in args))
    return scalar, arrays


def _valid(checks: list[_Check], scalar: bool) -> np.ndarray:
    """AND of the checks; for a scalar call, raise the first failed check."""
    valid = np.ones(np.shape(checks[0].ok), dtype=bool)
    for check in checks:
        if scalar and not bool(check.ok):
            raise check.error()
        valid = valid & check.ok
    return valid


def _finish(value: np.ndarray, valid: np.ndarray, scalar: bool) -> float | Masked:
    if scalar:
        return float(value)
    return Masked(np.where(valid, value, np.nan), valid)


# ---------------------------------------------------------------------------
# Eq. 2 and 3
# ---------------------------------------------------------------------------
def deflection_ratio(k_m, k_r, k_obj):
    """Deflection ratio R = (K_r + K_obj)/(K_m + K_obj), paper eq. 2.

    Evaluated as R = 1 + (K_r − K_m)/(K_m + K_obj): every step is a correctly
    rounded operation monotonic in K_obj, so the computed R never increases
    as K_obj increases (the quotient of two sums can, by one ulp).

    Args:
        k_m: measuring-element stiffness K_m (N/mm), scalar or array.
        k_r: reference-element stiffness K_r (N/mm), > K_m.
        k_obj: object stiffness K_obj (N/mm), > 0.

    Returns:
        R (dimensionless) as float, or ``Masked`` for array input (see module
        docstring). Relative rounding error <= 4u. Near R = 1, use
        :func:`deflection_ratio_excess`, which keeps R − 1 to full precision.

    Raises:
        LumpedDomainError: scalar input with a stiffness <= 0 or not finite,
            or K_r <= K_m.
    """
    scalar, (k_m, k_r, k_obj) = _broadcast(k_m, k_r, k_obj)
    valid = _valid(_stiffness_checks(k_m, k_r) + [_positive("K_obj", k_obj)], scalar)
    with np.errstate(all="ignore"):
        r = 1.0 + (k_r - k_m) / (k_m + k_obj)
    return _finish(r, valid, scalar)


def deflection_ratio_excess(k_m, k_r, k_obj):
    """R − 1 = (K_r − K_m)/(K_m + K_obj), from paper eq. 2, without forming R.

    Args and raises as :func:`deflection_ratio`. Relative rounding error <= 3u
    for any K_obj, whereas R − 1 formed from a rounded R has absolute error
    ~u, i.e. relative error ~u/(R − 1).
    """
    scalar, (k_m, k_r, k_obj) = _broadcast(k_m, k_r, k_obj)
    valid = _valid(_stiffness_checks(k_m, k_r) + [_positive("K_obj", k_obj)], scalar)
    with np.errstate(all="ignore"):
        s = (k_r - k_m) / (k_m + k_obj)
    return _finish(s, valid, scalar)


def _k_obj_from_excess(symbol, shown, s, k_m, k_r, scalar):
    with np.errstate(all="ignore"):
        q = (k_r - k_m) / s  # = K_m + K_obj
    checks = _stiffness_checks(k_m, k_r) + [_ratio_check(symbol, shown, s, q, k_m, k_r)]
    valid = _valid(checks, scalar)
    with np.errstate(all="ignore"):
        k_obj = q - k_m
    return _finish(k_obj, valid, scalar)


def object_stiffness(r, k_m, k_r):
    """Object stiffness from the deflection ratio, paper eq. 3.

    Evaluated as K_obj = (K_r − K_m)/(R − 1) − K_m, algebraically equal to
    eq. 3's (K_r − R K_m)/(R − 1) and free of its cancellation when K_r → K_m
    (relative rounding error <= (4 + 3 K_m/K_obj) u for 1 < R <= 2; see the
    module docstring).

    Args:
        r: deflection ratio R = (Δ−δ_m)/(Δ−δ_r), scalar or array.
        k_m: measuring-element stiffness K_m (N/mm).
        k_r: reference-element stiffness K_r (N/mm), > K_m.

    Returns:
        K_obj (N/mm) as float, or ``Masked`` for array input.

    Raises:
        LumpedDomainError: scalar input outside K_m, K_r > 0, K_r > K_m,
            1 < R < K_r/K_m.
    """
    scalar, (r, k_m, k_r) = _broadcast(r, k_m, k_r)
    s = r - 1.0  # exact for 0.5 <= R <= 2 (Sterbenz lemma)
    return _k_obj_from_excess("R", r, s, k_m, k_r, scalar)


def object_stiffness_from_excess(r_minus_one, k_m, k_r):
    """Object stiffness from R − 1 (paper eq. 3 rearranged): K_obj = (K_r − K_m)/(R − 1) − K_m.

    Use this when R − 1 is known more precisely than R itself (e.g. from
    :func:`deflection_ratio_excess`): the round trip K_obj -> R − 1 -> K_obj
    then has relative error <= (7 + 6 K_m/K_obj) u for every K_obj.

    Args:
        r_minus_one: R − 1 (dimensionless), scalar or array.
        k_m, k_r: element stiffnesses (N/mm), K_r > K_m.

    Returns:
        K_obj (N/mm) as float, or ``Masked`` for array input.

    Raises:
        LumpedDomainError: scalar input outside K_m, K_r > 0, K_r > K_m,
            0 < R − 1 < (K_r − K_m)/K_m.
    """
    scalar, (s, k_m, k_r) = _broadcast(r_minus_one, k_m, k_r)
    return _k_obj_from_excess("R - 1", s, s, k_m, k_r, scalar)


def sensitivity(r, k_m, k_r):
    """Sensitivity of eq. 3, dK_obj/dR (N/mm per unit R).

    Differentiating K_obj = (K_r − R K_m)/(R − 1):
    dK_obj/dR = [−K_m (R − 1) − (K_r − R K_m)]/(R − 1)² = (K_m − K_r)/(R − 1)²,
    which equals −(K_m + K_obj)²/(K_r − K_m). It is negative: K_obj falls as R
    rises, and its magnitude grows without bound as R → 1 (stiff objects).

    Args:
        r: deflection ratio R, scalar or array.
        k_m, k_r: element stiffnesses (N/mm), K_r > K_m.

    Returns:
        dK_obj/dR (N/mm) as float, or ``Masked`` for array input.

    Raises:
        LumpedDomainError: as :func:`object_stiffness`.
    """
    scalar, (r, k_m, k_r) = _broadcast(r, k_m, k_r)
    s = r - 1.0
    with np.errstate(all="ignore"):
        d = k_r - k_m
        q = d / s
    checks = _stiffness_checks(k_m, k_r) + [_ratio_check("R", r, s, q, k_m, k_r)]
    valid = _valid(checks, scalar)
    with np.errstate(all="ignore"):
        slope = -(q / s)  # −(K_r − K_m)/(R − 1)², no overflow in (R − 1)²
    return _finish(slope, valid, scalar)


def propagate_sigma(r, sigma_r, k_m, k_r):
    """Standard uncertainty of K_obj from that of R, to first order.

    ``σ_K_obj = |dK_obj/dR| σ_R`` (first-order Taylor / delta method, GUM
    section 5.1.2). The neglected second-order term, (K_r − K_m) σ_R²/(R − 1)³,
    is σ_R/(R − 1) times the first-order one, so the result holds while
    σ_R << R − 1; beyond that K_obj's distribution is skewed and wider.

    Args:
        r: deflection ratio R, scalar or array.
        sigma_r: standard uncertainty of R, σ_R >= 0 (dimensionless).
        k_m, k_r: element stiffnesses (N/mm), K_r > K_m.

    Returns:
        σ_K_obj (N/mm) as float, or ``Masked`` for array input.

    Raises:
        LumpedDomainError: as :func:`object_stiffness`, or σ_R < 0.
    """
    scalar, (r, sigma_r, k_m, k_r) = _broadcast(r, sigma_r, k_m, k_r)
    s = r - 1.0
    with np.errstate(all="ignore"):
        q = (k_r - k_m) / s
    checks = (_stiffness_checks(k_m, k_r) + [_ratio_check("R", r, s, q, k_m, k_r)]
              + [_non_negative("sigma_R", sigma_r, "")])
    valid = _valid(checks, scalar)
    with np.errstate(all="ignore"):
        sigma_k = (q / s) * sigma_r
    return _finish(sigma_k, valid, scalar)


def element_deflections(delta, k_m, k_r, k_obj):
    """Deflections of the unit pressed by Δ into the object, paper eq. 1.

    δ_m = K_m Δ/(K_obj + K_m), δ_r = K_r Δ/(K_obj + K_r); the element
    deflections are computed directly as Δ − δ = K_obj Δ/(K_obj + K), with no
    cancellation.

    Args:
        delta: displacement Δ of the unit towards the object (mm), >= 0.
        k_m, k_r, k_obj: stiffnesses (N/mm), K_r > K_m.

    Returns:
        :class:`UnitDeflections` (mm) of floats, or ``Masked`` whose value is a
        :class:`UnitDeflections` of arrays, for array input.

    Raises:
        LumpedDomainError: scalar input with a stiffness <= 0, K_r <= K_m or
            Δ < 0.
    """
    scalar, (delta, k_m, k_r, k_obj) = _broadcast(delta, k_m, k_r, k_obj)
    checks = (_stiffness_checks(k_m, k_r) + [_positive("K_obj", k_obj)]
              + [_non_negative("Delta", delta, " mm")])
    valid = _valid(checks, scalar)
    with np.errstate(all="ignore"):
        parts = (k_m * delta / (k_obj + k_m), k_r * delta / (k_obj + k_r),
                 k_obj * delta / (k_obj + k_m), k_obj * delta / (k_obj + k_r))
    if scalar:
        return UnitDeflections(*(float(p) for p in parts))
    return Masked(UnitDeflections(*(np.where(valid, p, np.nan) for p in parts)), valid)


# ---------------------------------------------------------------------------
# Independent check: the spring network solved by force equilibrium
# ---------------------------------------------------------------------------
def simulate_unit(k_m: float, k_r: float, k_obj: float, delta: float) -> SimulatedUnit:
    """Solve the unit's spring network by nodal force equilibrium (no use of eq. 1-2).

    Four nodes on one axis (displacement positive towards the object): the
    unit's base (prescribed Δ), the contact point under each element, and the
    object's fixed support (0). Springs: base–contact_m (K_m), contact_m–support
    (K_obj), base–contact_r (K_r), contact_r–support (K_obj). The 4 x 4
    stiffness matrix is assembled spring by spring and the free contact
    displacements solved from K_ff u_f = −K_fp u_p.

    Args:
        k_m, k_r, k_obj: spring stiffnesses (N/mm), finite and > 0 (any order).
        delta: prescribed base displacement Δ (mm), >= 0.

    Returns:
        :class:`SimulatedUnit` (mm, N).

    Raises:
        LumpedDomainError: a stiffness <= 0 or Δ < 0.
    """
    checks = [_positive("K_m", np.asarray(k_m, float)), _positive("K_r", np.asarray(k_r, float)),
              _positive("K_obj", np.asarray(k_obj, float)),
              _non_negative("Delta", np.asarray(delta, float), " mm")]
    _valid(checks, scalar=True)
    base, contact_m, contact_r, support = range(4)
    springs = ((base, contact_m, k_m), (contact_m, support, k_obj),
               (base, contact_r, k_r), (contact_r, support, k_obj))
    stiffness = np.zeros((4, 4))
    for i, j, k in springs:
        stiffness[np.ix_([i, j], [i, j])] += k * np.array([[1.0, -1.0], [-1.0, 1.0]])
    free, fixed = [contact_m, contact_r], [base, support]
    u = np.zeros(4)
    u[base] = delta
    u[free] = np.linalg.solve(stiffness[np.ix_(free, free)],
                              -stiffness[np.ix_(free, fixed)] @ u[fixed])
    nodal_force = stiffness @ u
    elem_m, elem_r = u[base] - u[contact_m], u[base] - u[contact_r]
    return SimulatedUnit(
        delta_m=float(u[contact_m]), delta_r=float(u[contact_r]),
        element_m=float(elem_m), element_r=float(elem_r),
        force_m=float(k_m * elem_m), force_r=float(k_r * elem_r),
        total_force=float(nodal_force[base]))
