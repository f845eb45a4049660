"""The section of a circular-notch flexure along its length, and integrals over it.

Under the flat top face the section's height is the base block's behind the notch, the
notch's t + R - sqrt(R^2 - u^2) across it (t the web, R the notch radius, u from the notch
centre) and the arm's in front. The height has kinks at the notch walls u = -R and +R, so an
integral over a span is taken on each smooth piece with Gauss-Legendre
(:func:`notch_integral`): the beam-theory grid strain and the bonded layer's compliance
both integrate over it.

Units: mm (heights, positions).
"""

from __future__ import annotations

import functools
from typing import Callable

import numpy as np


@functools.cache
def gauss_legendre(points: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on [-1, 1], shape (points,) each (numpy's
    ``leggauss``, formed once per count: a 64-point rule costs a millisecond, and the
    grid strain is evaluated thousands of times in a design search). Read-only arrays."""
    nodes, weights = np.polynomial.legendre.leggauss(points)
    nodes.flags.writeable = weights.flags.writeable = False
    return nodes, weights


def notched_height_mm(u_mm, web_mm, notch_radius_mm, base_height_mm, arm_height_mm):
    """The section's height under the flat top face at ``u_mm`` from the notch centre (mm;
    all broadcast): the base behind the notch, the circular notch, the arm in front."""
    u, t, R = (np.asarray(v, float) for v in (u_mm, web_mm, notch_radius_mm))
    notch = t + R - np.sqrt(np.maximum(R * R - u * u, 0.0))
    return np.where(u < -R, base_height_mm, np.where(u > R, arm_height_mm, notch))


def notch_integral(lo_mm, hi_mm, web_mm, notch_radius_mm, base_height_mm, arm_height_mm,
                   integrand: Callable[[np.ndarray, np.ndarray], np.ndarray],
                   points: int) -> np.ndarray:
    """The integral of ``integrand(u, h)`` over u in [lo, hi] (u from the notch centre, h the
    section's height there, :func:`notched_height_mm`), Gauss-Legendre with ``points`` on
    each smooth piece (behind the notch, across it, in front: each clipped to the span).

    Args:
        lo_mm, hi_mm: the span (mm; lo <= hi), broadcast with the element's dimensions.
        web_mm, notch_radius_mm, base_height_mm, arm_height_mm: the element (mm, broadcast).
        integrand: f(u, h) on arrays of shape (..., points) (u and h with a trailing node
            axis; the caller's own arrays take ``[..., None]``), returning that shape, or
            that shape behind leading axes of its own (several integrands at once).
        points: Gauss-Legendre nodes per piece.

    Returns:
        The integral, shape of the broadcast inputs (behind the integrand's own leading
        axes).
    """
    lo, hi, t, R, hb, ha = np.broadcast_arrays(*(np.asarray(v, float) for v in (
        lo_mm, hi_mm, web_mm, notch_radius_mm, base_height_mm, arm_height_mm)))
    nodes, weights = gauss_legendre(points)
    wall_lo, wall_hi = np.clip(-R, lo, hi), np.clip(R, lo, hi)
    total = np.zeros(t.shape)
    for a, b in ((lo, wall_lo), (wall_lo, wall_hi), (wall_hi, hi)):
        half = 0.5 * (b - a)
        u = half[..., None] * nodes + (0.5 * (a + b))[..., None]
        h = notched_height_mm(u, t[..., None], R[..., None], hb[..., None], ha[..., None])
        total = total + half * (integrand(u, h) @ weights)
    return total
