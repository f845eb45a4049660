"""Numbers a user pastes: rounded to a few significant digits toward the safe side.

A largest feasible force or ratio printed to paste must be feasible itself, so it is
rounded down; a band or tolerance that must hold is rounded up.
"""

from __future__ import annotations

import math


def round_down(x: float, digits: int = 2) -> float:
    """``x`` rounded down to ``digits`` significant digits.

    Args:
        x: the value (x > 0; zero, a negative or a non-finite x is returned as it is).
        digits: significant digits kept (>= 1).

    Returns:
        The largest number of ``digits`` significant digits not above ``x`` (up to a
        1e-9 relative snap, so 0.29999999999 gives 0.3), as six-digit clean float.
    """
    if x <= 0 or not math.isfinite(x):
        return x
    e = math.floor(math.log10(x)) - digits + 1
    return clean(math.floor(x / 10 ** e + 1e-9) * 10 ** e)


def round_up(x: float, digits: int = 2) -> float:
    """``x`` rounded up to ``digits`` significant digits (x > 0; any other x as it is);
    see :func:`round_down`."""
    if x <= 0 or not math.isfinite(x):
        return x
    e = math.floor(math.log10(x)) - digits + 1
    return clean(math.ceil(x / 10 ** e - 1e-9) * 10 ** e)


def clean(x: float) -> float:
    """``x`` to six significant digits, as a design file writes it (no binary tail)."""
    return float(f"{x:.6g}")
