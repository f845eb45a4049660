"""Richardson extrapolation over a mesh sequence, for every level of the ladder.

The beam level (notch segments n/4, n/2, n), fem2d and fem3d (element sizes
h r^2, h r, h) all estimate their discretisation error here. With values
f1, f2, f3 on meshes refined by the ratio r > 1, the observed order is

    p = ln((f1 - f2) / (f2 - f3)) / ln r,

the extrapolated value f_ext = f3 + (f3 - f2) / (r^p - 1) and the error
estimate of the finest mesh |f3 - f_ext| / |f_ext|.

Sources: L. F. Richardson, "The deferred approach to the limit" (1927);
P. J. Roache, "Verification and Validation in Computational Science and
Engineering" (1998), ch. 5 (observed order, grid convergence index).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

#: Differences below this fraction of the finest value are round-off: the
#: observed order is then undefined.
ROUND_OFF_REL = 1e-13


@dataclass(frozen=True)
class Richardson:
    """Richardson extrapolation of a quantity over a mesh sequence.

    Attributes:
        values: the quantity on each mesh, coarsest first.
        ratio: element-size ratio between successive meshes (> 1).
        order: observed order of convergence p (NaN if the last three values
            do not converge monotonically or differ only by round-off).
        extrapolated: the extrapolated value (the finest value if no order
            could be used).
        error_rel: |finest - extrapolated| / |extrapolated|; if no order could
            be used, the last difference |f3 - f2| / |f3| (a conservative
            stand-in).
    """

    values: tuple[float, ...]
    ratio: float
    order: float
    extrapolated: float
    error_rel: float


def observed_order(values: Sequence[float], ratio: float) -> float:
    """Observed convergence order of the last three values (NaN if undefined)."""
    f1, f2, f3 = (float(v) for v in values[-3:])
    d12, d23 = f1 - f2, f2 - f3
    if abs(d23) <= ROUND_OFF_REL * abs(f3) or d12 / d23 <= 1.0:
        return float("nan")
    return math.log(d12 / d23) / math.log(ratio)


def richardson(values: Sequence[float], ratio: float, order: float | None = None, *,
               formal_order: float | None = None) -> Richardson:
    """Richardson extrapolation from the last three values of a mesh sequence.

    Args:
        values: quantity on meshes of element size h r^(k), ..., h r, h (at
            least 3, coarsest first; the last three are used).
        ratio: refinement ratio r > 1.
        order: assumed order p; ``None`` uses the observed order.
        formal_order: the method's formal order. When given, an observed
            order that is undefined or outside [formal / 2, 1.5 formal] (an
            unreliable estimate, e.g. from round-off) is replaced by it.

    Returns:
        :class:`Richardson`; ``order`` is the observed (or given) order.

    Raises:
        ValueError: fewer than three values or ratio <= 1.
    """
    if len(values) < 3:
        raise ValueError("Richardson extrapolation needs at least three meshes")
    if not ratio > 1:
        raise ValueError(f"refinement ratio must be > 1, got {ratio!r}")
    p = float(order) if order is not None else observed_order(values, ratio)
    used = p
    if formal_order is not None and not (0.5 * formal_order <= p <= 1.5 * formal_order):
        used = float(formal_order)
    f2, f3 = float(values[-2]), float(values[-1])
    if math.isfinite(used) and used > 0:
        ext = f3 + (f3 - f2) / (ratio**used - 1.0)
        err = abs(f3 - ext) / abs(ext)
    else:
        ext = f3
        err = abs(f3 - f2) / abs(f3)
    return Richardson(tuple(float(v) for v in values), float(ratio), p, ext, err)
