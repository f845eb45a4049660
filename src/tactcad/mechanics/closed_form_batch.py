"""The corrected closed-form stiffness over arrays of designs: the kernel the tolerance
Monte Carlo, the design search, the atlas and ``tactcad bench closed-form`` run.

It gives the numbers of the element-level path, composed of
:func:`~tactcad.mechanics.closed_form.closed_form_compliance`, the fem3d-fitted
correction (:meth:`~tactcad.mechanics.correction.Correction.factor`) and the bonded
gauge's layer (:func:`~tactcad.mechanics.bonded_layer.with_gauge_layer`), to rounding
(relative 1e-13 over the design domain, tests/mechanics/test_closed_form_batch.py), in
about half the time:

* no array is allocated per step: the designs go through in blocks of :data:`BLOCK`
  with every intermediate in a reused work buffer (a fresh 128 kB temporary per step
  costs the allocator's page faults, which under load took half the time);
* the correction is applied to the compliance sum, K = (1 + g) / (C + C_nb (c1 s + c2 s^2)
  + C_ns c6 + C_ab c7), not through the shares C_nb / C and so on;
* arctan, which numpy evaluates element by element in libm, is a Cephes rational on a
  half-angle-reduced argument (:func:`arctan_unit`), within 3 ulp of it;
* the layer's notch quadrature (:func:`~tactcad.mechanics.bonded_layer._layer_moments`,
  the same nodes and weights) takes the section height at a node as h = t (1 + X)^2 / D
  (X = sigma^2, D = (1 - X)^2 + 4 k^2 X), shares k^2 = t / (t + 2 R) with the notch
  integrals' s / (2 + s), and sums g (a^2 + u^2) dtheta once instead of two moments,
  its five nodes as the rows of one (5, n) array (:func:`_notch_quadrature`) and its
  constants once a call: about 160 ufunc calls a block instead of 290, each of which
  holds the GIL while numpy parses it, so two threads wait less for each other;
* inputs are checked by two reductions each (min > 0, max < inf).

Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

import math
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np

from tactcad.design.array_plan import ElementGeometry
from tactcad.mechanics.correction import Correction

#: Designs per pass of the kernel: its 18 work buffers of 128 kB and the notch
#: quadrature's four of 640 kB (about 5 MB a thread) stay in the last-level cache, and
#: the per-step call overhead is small against the step.
BLOCK = 16_384
_N_BUFFERS = 18
_N_NODE_BUFFERS = 4
# The ufuncs take their output as the third argument where numpy allows it: parsed
# about 0.4 us faster than out=, some 160 calls a block.

#: Cephes atan.c (S. L. Moshier, "Methods and Programs for Mathematical Functions", 1989):
#: arctan(x) = x + x z P(z) / Q(z), z = x^2, for |x| <= 0.66 (relative error about 2e-16).
_ATAN_P = (-8.750608600031904122785e-1, -1.615753718733365076637e1,
           -7.500855792314704667340e1, -1.228866684490136173410e2,
           -6.485021904942025371773e1)
_ATAN_Q = (2.485846490142306297962e1, 1.650270098316988542046e2, 4.328810604912902668951e2,
           4.853903996359136964868e2, 1.945506571482613964425e2)


def arctan_unit(x2) -> np.ndarray:
    """arctan(sqrt(x2)) for x2 in [0, 1] (radians), within 3 ulp of numpy's arctan.

    Args:
        x2: the squared argument, 0 <= x2 <= 1 (not checked: the kernel's s / (2 + s)).

    Returns:
        arctan(sqrt(x2)), in [0, pi/4], an array of ``x2``'s shape.

    Source: the half-angle identity arctan(x) = 2 arctan(x / (1 + sqrt(1 + x^2))) takes the
    argument below tan(pi/8); Cephes atan.c's rational P/Q there (Moshier 1989).
    """
    x2 = np.array(x2, dtype=float, ndmin=1)
    out, r, z, q = (np.empty_like(x2) for _ in range(4))
    return _atan_half(np.sqrt(x2), x2, out, r, z, q)


def _atan_half(x, x2, out, r, z, q):
    """arctan(x) into ``out`` (:func:`arctan_unit`) for x = sqrt(x2), with work buffers
    r, z, q."""
    np.add(x2, 1.0, r)
    np.sqrt(r, r)
    r += 1.0
    np.divide(x, r, out)  # the half angle's tangent, <= tan(pi/8)
    np.multiply(out, out, z)
    np.multiply(z, _ATAN_P[0], r)
    for c in _ATAN_P[1:]:
        r += c
        r *= z
    np.add(z, _ATAN_Q[0], q)
    for c in _ATAN_Q[1:]:
        q *= z
        q += c
    r /= q
    r *= out
    out += r
    out *= 2.0
    return out


_local = threading.local()

#: The most threads :func:`corrected_stiffness_batch` takes.
MAX_THREADS = 64
_POOLS: dict[tuple[int, int], ThreadPoolExecutor] = {}
_POOLS_LOCK = threading.Lock()


def _pool(threads: int) -> ThreadPoolExecutor:
    """The process's pool of ``threads`` threads, made on first use and kept (keyed by
    the process id too: a forked child has none of its parent's threads)."""
    key = (os.getpid(), threads)
    with _POOLS_LOCK:
        if key not in _POOLS:
            _POOLS[key] = ThreadPoolExecutor(threads, thread_name_prefix="closed-form")
        return _POOLS[key]


def _work_buffers(n: int) -> list[np.ndarray]:
    """:data:`_N_BUFFERS` arrays of ``n`` <= :data:`BLOCK` floats, kept per thread and
    reused by every call (views of the thread's block-sized buffers)."""
    bufs = getattr(_local, "buffers", None)
    if bufs is None:
        bufs = _local.buffers = [np.empty(BLOCK) for _ in range(_N_BUFFERS)]
    return [b[:n] for b in bufs]


def _node_buffers(rows: int, n: int) -> list[np.ndarray]:
    """:data:`_N_NODE_BUFFERS` C-contiguous (rows, n) arrays, n <= :data:`BLOCK`, kept per
    thread: the layer's quadrature, one row per node."""
    bufs = getattr(_local, "node_buffers", None)
    if bufs is None or bufs[0].size < rows * BLOCK:
        bufs = _local.node_buffers = [np.empty(rows * BLOCK)
                                      for _ in range(_N_NODE_BUFFERS)]
    return [b[:rows * n].reshape(rows, n) for b in bufs]


def _checked(name: str, value) -> np.ndarray:
    """``value`` as floats, refused unless every element is finite and > 0."""
    if isinstance(value, float) and 0 < value < math.inf:  # one number: no reductions
        return np.asarray(value)
    arr = np.asarray(value, dtype=float)
    if not arr.size or (arr.min() > 0 and arr.max() < math.inf):  # NaN fails min > 0
        return arr
    bad = np.ravel(arr[~((arr > 0) & (arr < math.inf))])[:3].tolist()
    raise ValueError(f"{name} must be finite and > 0; got {bad}")


def _flexibility_change_scaled(h, beta, layer_term, d, tmp):
    """-g(h) ea_l / 4 of :func:`~tactcad.mechanics.bonded_layer._section_flexibility_change`
    into ``d`` (mm^-2 over the layer's E A); ``h`` is overwritten, ``tmp`` a work buffer.
    With u = E b h / (3 EA_l) = beta h, D' = (EI_c - EI_0) 4 / EA_l
    = (h + h_l)^2 u / (u + 1/3) + 4 EI_l / EA_l and E' = 4 EI_0 / EA_l = h^2 u:
    g = -(4 / EA_l) D' / (E' (E' + D'))."""
    np.multiply(h, beta, tmp)  # u
    np.add(h, layer_term[0], d)
    d *= d
    d *= tmp
    h *= h
    h *= tmp  # E'
    tmp += 1.0 / 3.0
    d /= tmp
    d += layer_term[1]
    np.add(h, d, tmp)
    tmp *= h
    d /= tmp
    return d


def _flat_flexibility_change(h: float, eb, ea_layer, ei_layer, layer_height_mm):
    """g(h) of a flat piece of height ``h`` (1/(N mm^2), <= 0; ``eb`` scalar or array)."""
    ebh = eb * h
    d12 = (h + layer_height_mm) ** 2 * ebh / (ebh + ea_layer) * (3.0 * ea_layer) \
        + 12.0 * ei_layer
    e12 = ebh * h * h
    return -12.0 * d12 / (e12 * (e12 + d12))


@dataclass(frozen=True)
class _Layer:
    """What the layer term takes from the element, worked out once a call: the carrier's
    half length c (mm), the layer's height h_l (mm), E A (N) and E I (N mm^2), and the
    notch quadrature's positive nodes squared and doubled weights as (nodes, 1) columns."""
    half_length_mm: float
    height_mm: float
    ea_N: float
    ei_N_mm2: float
    nodes2: np.ndarray
    weights: np.ndarray


def _layer_setup(g: ElementGeometry) -> _Layer | None:
    """The :class:`_Layer` of ``g``'s bonded gauge, None for a bare element."""
    from tactcad.design.readout_section import CARRIER_SIDE_MM, carrier_width_mm
    from tactcad.mechanics.bonded_layer import NOTCH_POINTS
    from tactcad.mechanics.notch_profile import gauss_legendre

    st = g.gauge
    if st is None:
        return None
    hl = st.height_mm
    ea = st.modulus_MPa * carrier_width_mm(st.grid_width_mm, g.sheet_thickness_mm) * hl
    nodes, weights = gauss_legendre(NOTCH_POINTS)
    keep = nodes > 0  # the integrand is even in sigma: the positive nodes, twice weighted
    return _Layer(st.grid_length_mm / 2 + CARRIER_SIDE_MM, hl, ea, ea * hl * hl / 12.0,
                  (nodes[keep] * nodes[keep])[:, None], (2.0 * weights[keep])[:, None])


def _notch_quadrature(S, KS, t, rt, two_rt, c0, beta, lay: _Layer, acc):
    """The notch's Gauss sum of g (a^2 + u^2) du / dz, scaled as
    :func:`_flexibility_change_scaled`, into ``acc`` for up to :data:`BLOCK` designs:
    S = sigma_1^2, KS = 4 k^2 S, rt = R + t, two_rt = 2 rt, c0 = a^2 - t (t + 2 R)."""
    hl, ea_layer, ei_layer = lay.height_mm, lay.ea_N, lay.ei_N_mm2
    xn, d, h, jac = _node_buffers(lay.nodes2.shape[0], t.shape[0])
    np.multiply(S, lay.nodes2, xn)
    np.multiply(KS, lay.nodes2, h)
    np.subtract(1.0, xn, d)
    d *= d
    d += h
    xn += 1.0
    a1 = np.divide(xn, d, jac)
    np.multiply(xn, a1, h)
    h *= t
    tmp = np.subtract(rt, h, d)
    tmp *= a1
    jac = tmp  # (R + t - h) A
    np.subtract(two_rt, h, xn)
    xn *= h
    xn += c0  # a^2 + u^2
    jac *= xn
    term = _flexibility_change_scaled(h, beta, (hl, 4.0 * ei_layer / ea_layer), xn, a1)
    term *= jac
    term *= lay.weights
    np.add.reduce(term, axis=0, out=acc)  # the nodes in order, as a running sum
    return acc


def _layer_compliance_change(t, R, a, a2, k, k2, eb, g: ElementGeometry, lay: _Layer,
                              w: list[np.ndarray]):
    """The compliance the gauge's layer takes away (mm/N, <= 0), as
    :func:`~tactcad.mechanics.bonded_layer.layer_compliance_change` with the carrier
    centred over the notch, into ``w[0]``; k2 = t / (t + 2 R), k its root, a2 = a^2; ``w`` holds
    eight free work buffers. The notch's nodes go as the rows of (nodes, n) arrays: the
    quadrature makes five times fewer ufunc calls, each over five times the elements."""
    acc, scale, S, KS, rt, t2r, x, p = w[:8]
    c, hl, ea_layer, ei_layer = lay.half_length_mm, lay.height_mm, lay.ea_N, lay.ei_N_mm2
    # the carrier's end on the notch in sigma = tan(psi / 2) (bonded_layer._sigma)
    sn = np.divide(c, R, x)
    np.minimum(sn, 1.0, out=sn)
    tan_psi = np.multiply(sn, sn, p)
    np.subtract(1.0, tan_psi, tan_psi)
    np.sqrt(tan_psi, tan_psi)
    tan_psi += 1.0
    tan_psi *= k
    np.divide(sn, tan_psi, tan_psi)
    s1 = np.multiply(tan_psi, tan_psi, x)
    s1 += 1.0
    np.sqrt(s1, s1)
    s1 += 1.0
    np.divide(tan_psi, s1, s1)
    np.multiply(s1, s1, S)
    np.multiply(k2, S, KS)
    KS *= 4.0
    np.multiply(k, s1, scale)
    scale *= -16.0 / ea_layer  # -4 / EA_l of the scaled g, 4 k sigma_1 of du / dsigma / R
    np.add(R, t, rt)
    two_rt = np.add(rt, rt, t2r)
    c0 = np.add(rt, R, p)  # t + 2 R
    np.multiply(c0, t, c0)
    np.subtract(a2, c0, c0)  # a^2 - t (t + 2 R): a^2 + u^2 = c0 + h (2 (R + t) - h)
    beta = eb / (3.0 * ea_layer)
    # at a node X = sigma^2, D = (1 - X)^2 + 4 k^2 X, A = (1 + X) / D: the height
    # h = t + 2 R sin^2(theta / 2) = t (1 + X) A, u^2 = (h - t) (t + 2 R - h), and
    # du = R cos(theta) dtheta = (R + t - h) A 4 k sigma_1 dz
    _notch_quadrature(S, KS, t, rt, two_rt, c0, beta, lay, acc)
    acc *= scale
    # the flat pieces, g constant: behind the notch (-c ... -wn), in front (wn ... c)
    gb = _flat_flexibility_change(g.base_height_mm, eb, ea_layer, ei_layer, hl)
    ga = _flat_flexibility_change(g.arm_height_mm, eb, ea_layer, ei_layer, hl)
    wn = np.minimum(R, c, out=x)
    wn2 = np.multiply(wn, wn, p)
    i0 = np.subtract(c, wn, S)
    i0 *= gb + ga
    i0 *= a2
    i1 = np.subtract(c * c, wn2, KS)
    i1 *= a
    i1 *= ga - gb  # 2 a I1 = 2 a (ga - gb) (c^2 - wn^2) / 2
    i0 -= i1
    wn2 *= wn
    i2 = np.subtract(c * c * c, wn2, rt)
    i2 *= (gb + ga) / 3.0
    i0 += i2
    acc += i0
    return acc


def _kernel(t, R, a, E, nu, g: ElementGeometry, correction: Correction, out: np.ndarray,
            layer: _Layer | None = None):
    """:func:`corrected_stiffness_batch` of one block: 1-d t, R, a of one length n <=
    :data:`BLOCK`, E and nu scalars or of that length; K (N/mm) into ``out``; ``layer``
    the :func:`_layer_setup` of ``g`` (worked out here when not given)."""
    w = _work_buffers(t.shape[0])
    s, k2, a2, nb, ns, ab, den, gain = w[:8]
    x1, x2, x3, x4, x5, x6, x7, x8 = w[8:16]
    ha, htip, b = g.arm_height_mm, g.tip_height_mm, g.sheet_thickness_mm
    d2 = 0.5 * g.tip_width_mm
    d1 = np.subtract(a, R, x8)  # lever at the arm root (notch front wall)
    if d1.min() < d2:
        raise ValueError("arm_length_mm must be >= notch_radius_mm + tip_width_mm / 2 "
                         "(the lever must reach past the notch and the tip root)")
    eb = E * b
    # notch integrals (closed_form._notch_integrals); k^2 = s / (2 + s) = t / (t + 2 R)
    np.divide(t, R, s)
    q = np.add(s, 2.0, x1)
    np.divide(s, q, k2)
    m2 = np.multiply(s, q, w[17])
    m = np.sqrt(m2, x2)
    k = np.divide(m, q, w[16])  # sqrt(s / q) = sqrt(s q) / q
    pa = _atan_half(k, k2, x3, x4, x5, x6)
    np.subtract(0.5 * np.pi, pa, pa)  # arctan(sqrt((2 + s) / s))
    p = np.add(s, 1.0, x4)
    pa *= p
    pp = np.multiply(p, p, x5)
    pm2 = np.multiply(p, m2, x4)
    m3 = np.multiply(m2, m, x6)
    inv_h3 = np.multiply(pp, 2.0, x7)
    inv_h3 += 1.0
    np.multiply(pm2, m2, nb)
    inv_h3 /= nb
    np.multiply(m2, m3, nb)
    np.divide(pa, nb, nb)
    nb *= 6.0
    inv_h3 += nb
    np.multiply(R, R, nb)
    inv_h3 /= nb
    u2_h3 = np.multiply(pp, -4.0, x1)
    u2_h3 += 6.0
    u2_h3 *= pa
    u2_h3 /= m3
    pp *= 2.0
    pp -= 1.0
    pp /= pm2
    u2_h3 += pp
    u2_h3 += np.pi
    inv_h = np.divide(pa, m, x3)
    inv_h *= 4.0
    inv_h -= np.pi
    # the correction on the compliance sum (correction.py): K = (1 + g) / (C + C_nb (c1 s
    # + c2 s^2) + C_ns c6 + C_ab c7), each part's factor folded into its coefficient, the
    # lever's two parts (C_ab = 4 / (E b) ((d1^3 - d2^3) / ha^3 + d2^3 / ht^3) and the arm's
    # shear ((d1 - d2) / ha + d2 / ht) shear) as d1 (A d1^2 + B) and one constant
    c1, c2, c3, c4, c5, c6, c7, c8 = correction.coefficients
    shear = 2.4 * (1.0 + nu) / eb  # ALPHA_SHEAR / (G b), G = E / (2 (1 + nu))
    ht = ha + htip
    d2c = d2 * d2 * d2
    ab_scale = 4.0 * (1.0 + c7) / eb
    np.multiply(a, a, a2)
    np.multiply(s, c2, den)
    den += c1
    den *= s
    den += 1.0
    den *= 12.0 / eb
    np.multiply(a2, inv_h3, nb)
    nb += u2_h3
    den *= nb  # C_nb (1 + c1 s + c2 s^2)
    den += np.multiply(inv_h, shear * (1.0 + c6), ns)  # C_ns (1 + c6)
    np.multiply(d1, d1, ab)
    ab *= ab_scale / (ha * ha * ha)
    ab += shear / ha
    ab *= d1
    den += ab
    den += shear * (d2 / ht - d2 / ha) + ab_scale * d2c * (1.0 / (ht * ht * ht)
                                                          - 1.0 / (ha * ha * ha))
    if not den.min() > 0:
        raise ValueError("correction factor not positive at t/R = "
                         f"{np.ravel(s[~(den > 0)])[:3].tolist()}")
    if c3:
        wr = np.multiply(t, R, x1)
        np.sqrt(wr, wr)  # sqrt(t R), b of the width ratio sqrt(t R) / b in c4 and c5
        np.multiply(wr, c5 / (b * b), gain)
        gain += c4 / b
        gain *= wr
        gain += 1.0
        if c8:
            gain += np.multiply(t, c8 / b, x1)
        np.divide(nu * nu / (1.0 - nu * nu) * c3, gain, gain)
        gain += 1.0
        if not gain.min() > 0:
            raise ValueError("correction factor not positive at width ratio sqrt(t R) / b = "
                             f"{np.ravel(np.sqrt(t * R) / b)[:3].tolist()}")
    else:
        gain[...] = 1.0
    if g.gauge is not None:
        lay = layer if layer is not None else _layer_setup(g)
        dc = _layer_compliance_change(t, R, a, a2, k, k2, eb, g, lay, [x1, x2, x3, x4, x5, x6,
                                                                     x7, x8])
        dc *= gain
        den += dc  # K = 1 / (1 / K_bare + dC) = (1 + g) / (den + (1 + g) dC)
    np.divide(gain, den, out)
    return out


def corrected_stiffness_batch(web_mm, notch_radius_mm, arm_length_mm, youngs_modulus_MPa,
                              g: ElementGeometry, poisson_ratio, correction: Correction,
                              out: np.ndarray | None = None, threads: int = 1):
    """Corrected closed-form tip stiffness K (N/mm) of many designs, vectorised.

    Args:
        web_mm, notch_radius_mm, arm_length_mm: web thickness t, notch radius R and lever a
            (mm); youngs_modulus_MPa: E (MPa); poisson_ratio: nu, in (-1, 0.5); array-like,
            broadcast together.
        g: the element supplying the other dimensions (arm and tip height, tip width,
            sheet thickness, base height) and the bonded gauge.
        correction: the fem3d-fitted correction, applied without the range check.
        out: optional float array of the broadcast shape, C-contiguous, to write K into.
        threads: blocks of :data:`BLOCK` designs worked on at once, 1 to :data:`MAX_THREADS`
            (numpy's ufuncs release the GIL, so two threads use two cores; each thread
            keeps its own work buffers). Leave it 1 inside a process pool or a Dask worker
            that already fills the cores.

    Returns:
        K of the broadcast shape (N/mm; a numpy float for scalar inputs), with the
        gauge's layer when ``g`` carries one.

    Raises:
        ValueError: a non-finite or non-positive t, R, a or E (the field and the first
            values named), nu outside (-1, 0.5), a lever too short for notch and tip
            (a < R + w/2), a correction factor not positive, or ``threads`` not an
            integer from 1 to :data:`MAX_THREADS`.

    Source: the closed form of :mod:`tactcad.mechanics.closed_form` (Paros & Weisbord 1965;
    Lobontiu 2002, ch. 2; Timoshenko shear), its correction
    (:mod:`tactcad.mechanics.correction`) and the layer term of
    :mod:`tactcad.mechanics.bonded_layer`; the module docstring lists what is saved.
    """
    if isinstance(threads, bool) or not isinstance(threads, int) \
            or not 1 <= threads <= MAX_THREADS:
        raise ValueError(f"threads = {threads!r}: allowed an integer from 1 to {MAX_THREADS}")
    t = _checked("web_mm", web_mm)
    R = _checked("notch_radius_mm", notch_radius_mm)
    a = _checked("arm_length_mm", arm_length_mm)
    E = _checked("E", youngs_modulus_MPa)
    nu = np.asarray(poisson_ratio, dtype=float)
    if nu.size and not (nu.min() > -1.0 and nu.max() < 0.5):
        raise ValueError(f"nu = {np.ravel(nu)[:3].tolist()}: allowed -1 < nu < 0.5")
    for name, v in (("arm_height_mm", g.arm_height_mm), ("tip_width_mm", g.tip_width_mm),
                    ("tip_height_mm", g.tip_height_mm), ("b", g.sheet_thickness_mm)):
        _checked(name, float(v))
    shape = np.broadcast_shapes(t.shape, R.shape, a.shape, E.shape, nu.shape)
    n = math.prod(shape)

    def flat(v):  # one value stays a scalar; arrays go flat and contiguous, one per design
        return float(v.reshape(-1)[0]) if v.size == 1 else \
            np.ascontiguousarray(np.broadcast_to(v, shape)).reshape(-1)

    t, R, a = (v.reshape(-1) if v.shape == shape and v.flags.c_contiguous else
               np.ascontiguousarray(np.broadcast_to(v, shape)).reshape(-1) for v in (t, R, a))
    E, nu = flat(E), flat(nu)
    k = np.empty(n) if out is None else out.reshape(-1)
    layer = _layer_setup(g)

    def block(i: int) -> None:
        j = min(i + BLOCK, n)
        _kernel(t[i:j], R[i:j], a[i:j], E if isinstance(E, float) else E[i:j],
                nu if isinstance(nu, float) else nu[i:j], g, correction, k[i:j], layer)

    starts = range(0, n, BLOCK)
    if threads > 1 and len(starts) > 1:
        for done in _pool(threads).map(block, starts):  # a block's error is raised here
            pass
    else:
        for i in starts:
            block(i)
    if out is not None:
        return out
    return k.reshape(shape) if shape else k[0]
