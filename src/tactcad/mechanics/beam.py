"""Level 2 of the element-stiffness ladder: 1D Timoshenko beam along the real profile.

The element is modelled as a stepped cantilever along x (element frame) from
the clamp to the load point at the contact-face centre:

* optional free base block [clamp_x, x_h - R], height = base height
  (default: clamp at the notch back wall x_h - R, base block rigid);
* the single-sided circular notch hinge, h(x) = t + R - sqrt(R^2 - (x - x_h)^2),
  split into n segments uniform in psi = arctan(q tan(theta / 2)),
  x = x_h + R sin(theta), q = sqrt((2 + s)/s), s = t/R: h is smooth in psi
  (no sqrt singularity at the notch walls, where h'(x) is unbounded) and the
  neck, of width ~ sqrt(2 s) in theta, gets the same share of segments for
  any t/R;
* the measuring arm, height h_a (one prismatic segment);
* the tip-root fillet of radius r (h = h_a + r (1 - cos phi), n/2 segments
  uniform in phi);
* the tip block, height h_a + h_tip, up to the load point (one segment).

Each segment is prismatic with its section height taken at the segment's
mid-point in psi (mid-point rule in the smooth variable) and is integrated
exactly as a Timoshenko beam (bending + shear, shear coefficient kappa =
1 / ALPHA_SHEAR = 5/6 of :mod:`tactcad.mechanics.closed_form`; Timoshenko &
Gere, "Mechanics of Materials"). The cantilever is statically
determinate, so the section forces come from equilibrium and deflection and
rotation are transferred segment by segment from the clamp to the load
point (flexibility method); this is the solution an assembly of exact
two-node Timoshenko elements gives, without the round-off of an assembled
stiffness matrix whose segments at the notch walls are orders of magnitude
shorter and stiffer than at the neck.
The stepped approximation of h converges as O(n^-2); three meshes (n/4,
n/2, n) give the observed order and a Richardson estimate of the
discretisation error (:mod:`tactcad.mechanics.richardson`). The error
estimate that :func:`estimate_beam` reports adds to it the beam-theory model
error (plane sections through a short, deep notch; plane stress against 3D),
taken from the fem3d-fitted correction of :mod:`tactcad.mechanics.correction`:
the beam is as stiff as the uncorrected closed form, so its model error is
|K_EB / K_corrected - 1| plus the correction's own error estimate e (over K_corrected /
K_EB), which grows outside the correction's fitted range (past its arm / arm height the
beam would otherwise state 22 % where fem3d reads it 32 % off).

Gauge strain: the bending moment at the notch centre, M = F a (equilibrium),
converted to the top-surface strain eps = M (t/2) / (E b t^3 / 12) (neutral
axis at the centroid of the b x t section); it carries no discretisation
error. :func:`estimate_beam` reports it times the fem3d-fitted point factor
of :mod:`tactcad.mechanics.gauge_strain`, as the closed form does (the web
of a wide sheet bends near plane strain).

Units: mm, N, MPa, N/mm.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from tactcad.design.array_plan import ElementGeometry, Material
from tactcad.mechanics.closed_form import (ALPHA_SHEAR, correction_factor_and_error,
                                          face_strain_factor)
from tactcad.mechanics.stiffness_result import StiffnessResult
from tactcad.mechanics.richardson import richardson

DEFAULT_SEGMENTS = 256
#: Formal order of the stepped (mid-point) approximation of h(x).
FORMAL_ORDER = 2.0
MODEL_NAME = "beam"


@dataclass(frozen=True, eq=False)
class BeamMesh:
    """Stepped-beam discretisation of one element (element frame, mm).

    Attributes:
        x_mm: node x positions, shape (N + 1,), increasing; node 0 is clamped,
            node N is the load point.
        height_mm: section height of each segment, shape (N,).
        hinge_node: index of the node at the notch centre x_h.
    """

    x_mm: np.ndarray
    height_mm: np.ndarray
    hinge_node: int

    @property
    def n_segments(self) -> int:
        return int(self.height_mm.size)


def beam_mesh(g: ElementGeometry, n_segments: int = DEFAULT_SEGMENTS, *,
              clamp_x_mm: float | None = None, include_fillet: bool = True) -> BeamMesh:
    """Stepped-beam mesh of the element profile.

    Args:
        g: element geometry.
        n_segments: segments over the notch (even, >= 2); the tip-root fillet
            gets n_segments / 2.
        clamp_x_mm: x of the clamp; ``None`` clamps at the notch back wall
            x_h - R (rigid base). A value below x_h - R adds the free part of
            the base block (height = base height).
        include_fillet: model the tip-root fillet (False: sharp corner).

    Raises:
        ValueError: odd or too small ``n_segments``, a clamp outside
            [0, x_h - R], or a lever too short for notch, fillet and tip.
    """
    if not isinstance(n_segments, (int, np.integer)) or n_segments < 2 or n_segments % 2:
        raise ValueError(f"n_segments must be an even integer >= 2; got {n_segments!r}")
    n = int(n_segments)
    R, t, xh = g.notch_radius_mm, g.web_thickness_mm, g.hinge_x_mm
    ha, htip = g.arm_height_mm, g.tip_height_mm
    r = g.inside_corner_radius_mm if include_fillet else 0.0
    x_tip0 = g.overall_length_mm - g.tip_width_mm      # tip block's back face
    x_fil = x_tip0 - r                                  # fillet start on the arm's top face
    x_load = g.tip_centre_x_mm
    if x_fil < xh + R:
        raise ValueError("the notch, fillet and tip overlap: arm_length_mm must be >= "
                         "notch radius + fillet radius + tip_width / 2")
    xs: list[np.ndarray] = []
    hs: list[np.ndarray] = []
    if clamp_x_mm is not None:
        cx = float(clamp_x_mm)
        if not 0.0 <= cx <= xh - R:
            raise ValueError(f"clamp_x_mm = {clamp_x_mm!r}: allowed 0 ... {xh - R:g} mm")
        if cx < xh - R:
            xs.append(np.array([cx]))
            hs.append(np.array([g.base_height_mm]))
    th, th_mid = _notch_angles(t / R, n)
    x_notch = xh + R * np.sin(th)
    x_notch[n // 2] = xh
    x_notch[0], x_notch[-1] = xh - R, xh + R
    hinge_node = sum(a.size for a in xs) + n // 2
    xs.append(x_notch[:-1])
    hs.append(t + R * (1.0 - np.cos(th_mid)))
    if x_fil > xh + R:
        xs.append(np.array([xh + R]))
        hs.append(np.array([ha]))
    if r > 0:
        nf = max(1, n // 2)
        ph = np.linspace(0.0, 0.5 * math.pi, nf + 1)
        ph_mid = 0.5 * (ph[:-1] + ph[1:])
        xf = x_fil + r * np.sin(ph)
        xf[0], xf[-1] = x_fil, x_tip0
        xs.append(xf[:-1])
        hs.append(ha + r * (1.0 - np.cos(ph_mid)))
    xs.append(np.array([x_tip0, x_load]))
    hs.append(np.array([ha + htip]))
    x = np.concatenate(xs)
    h = np.concatenate(hs)
    if not np.all(np.diff(x) > 0):
        raise ValueError("degenerate beam mesh (non-increasing nodes)")
    return BeamMesh(x_mm=x, height_mm=h, hinge_node=hinge_node)


def _notch_angles(s: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Node and mid-segment notch angles theta for n segments uniform in
    psi = arctan(q tan(theta / 2)), q = sqrt((2 + s) / s), psi in [-A, A],
    A = arctan(q). This maps the neck (width ~ sqrt(2 s) in theta) to a fixed
    share of the segments for any t/R; theta(psi) is smooth, so the mid-point
    rule keeps its O(n^-2) error."""
    q = math.sqrt((2.0 + s) / s)
    A = math.atan(q)
    psi = np.linspace(-A, A, n + 1)
    psi_mid = 0.5 * (psi[:-1] + psi[1:])
    th = 2.0 * np.arctan(np.tan(psi) / q)
    th[0], th[-1] = -0.5 * math.pi, 0.5 * math.pi
    return th, 2.0 * np.arctan(np.tan(psi_mid) / q)


def _section(h: np.ndarray, E: float, nu: float, b: float) -> tuple[np.ndarray, np.ndarray]:
    EI = E * b * h**3 / 12.0
    kGA = E / (2.0 * (1.0 + nu)) * b * h / ALPHA_SHEAR
    return EI, kGA


@dataclass(frozen=True, eq=False)
class BeamSolution:
    """Static solution of a stepped cantilever for a unit tip force.

    Attributes:
        compliance_mm_per_N: tip deflection along +y per newton.
        hinge_moment_Nmm_per_N: bending moment at the notch centre per newton.
        face_strain_as_cut_per_N: top-surface strain over the thinnest section per newton, of the
            bare section (1/N; :func:`estimate_beam` carries it under the gauge's layer).
        deflection_mm_per_N: nodal deflections, shape (N + 1,).
        rotation_rad_per_N: nodal section rotations, shape (N + 1,).
    """

    compliance_mm_per_N: float
    hinge_moment_Nmm_per_N: float
    face_strain_as_cut_per_N: float
    deflection_mm_per_N: np.ndarray
    rotation_rad_per_N: np.ndarray

    @property
    def stiffness_N_per_mm(self) -> float:
        return 1.0 / self.compliance_mm_per_N


def solve_beam(mesh: BeamMesh, E: float, nu: float, b: float, web_mm: float) -> BeamSolution:
    """Solve the Timoshenko stepped cantilever for a unit tip force.

    Section forces are known from equilibrium (V = 1, M(x) = x_load - x); each
    prismatic segment [x_i, x_i + L] (lever e = x_load - x_i - L at its far
    end) is integrated exactly from the clamp outwards (transfer of
    deflection and rotation, Timoshenko & Gere):

        rotation   th_{i+1} = th_i + L (2e + L) / (2 EI)
        deflection w_{i+1}  = w_i + th_i L + (e L^2 / 2 + L^3 / 3) / EI + L / (kappa G A)

    written in L and e (not as differences of cubes) so that short segments
    lose no digits. The tip deflection equals the unit-load sum of
    :func:`unit_load_compliance`.

    Args:
        mesh: :func:`beam_mesh` output. E (MPa), nu, b (mm): material and width.
        web_mm: section height at the hinge node (for the gauge strain).
    """
    x, h = mesh.x_mm, mesh.height_mm
    EI, kGA = _section(h, E, nu, b)
    L = np.diff(x)
    e = x[-1] - x[1:]
    rot = np.concatenate([[0.0], np.cumsum(L * (2.0 * e + L) / (2.0 * EI))])
    dw = rot[:-1] * L + (0.5 * e * L * L + L**3 / 3.0) / EI + L / kGA
    w = np.concatenate([[0.0], np.cumsum(dw)])
    moment = float(x[-1] - x[mesh.hinge_node])
    eps = moment * (web_mm / 2.0) / (E * b * web_mm**3 / 12.0)
    return BeamSolution(compliance_mm_per_N=float(w[-1]), hinge_moment_Nmm_per_N=moment,
                        face_strain_as_cut_per_N=eps, deflection_mm_per_N=w, rotation_rad_per_N=rot)


def unit_load_compliance(mesh: BeamMesh, E: float, nu: float, b: float,
                         ei_factor=1.0) -> float:
    """Tip compliance (mm/N) of the same stepped beam by the unit-load method:
    sum over segments of integral M^2/(EI) + V^2/(kappa G A) with M = d, V = 1,
    i.e. L (d_a^2 + d_a d_b + d_b^2) / (3 EI) + L / (kappa G A), d = lever to
    the load point. Equal to :func:`solve_beam` (a cross-check). ``ei_factor``
    (scalar or one per segment) multiplies EI: a layer bonded on some segments."""
    x, h = mesh.x_mm, mesh.height_mm
    EI, kGA = _section(h, E, nu, b)
    EI = EI * np.asarray(ei_factor, float)
    L = np.diff(x)
    db = x[-1] - x[1:]
    da = db + L
    return float(np.sum(L * (da * da + da * db + db * db) / (3.0 * EI) + L / kGA))


@dataclass(frozen=True)
class BeamConvergence:
    """Mesh-refinement study of the beam level (notch segments n/4, n/2, n).

    Attributes:
        n_segments: the three notch segment counts.
        stiffness_N_per_mm: K on each mesh.
        observed_order: log2((K1 - K2)/(K2 - K3)); NaN when the differences are
            at round-off.
        extrapolated_N_per_mm: Richardson extrapolation
            (:func:`tactcad.mechanics.richardson.richardson`: the observed order
            if in [1, 3], else the formal order 2).
        error_estimate_rel: |K3 - K_extrapolated| / K_extrapolated, the
            discretisation error of the finest mesh.
        face_strain_as_cut_per_N: top-surface strain over the web per newton (finest mesh), of
            the bare section (1/N).
    """

    n_segments: tuple[int, int, int]
    stiffness_N_per_mm: tuple[float, float, float]
    observed_order: float
    extrapolated_N_per_mm: float
    error_estimate_rel: float
    face_strain_as_cut_per_N: float


def beam_convergence(g: ElementGeometry, material: Material, n_segments: int = DEFAULT_SEGMENTS,
                     *, clamp_x_mm: float | None = None,
                     include_fillet: bool = True) -> BeamConvergence:
    """Solve on n/4, n/2 and n notch segments and estimate the discretisation error.

    Raises:
        ValueError: ``n_segments`` not a multiple of 8 or below 16; see :func:`beam_mesh`.
    """
    if not isinstance(n_segments, (int, np.integer)) or n_segments < 16 or n_segments % 8:
        raise ValueError(f"n_segments must be a multiple of 8, >= 16; got {n_segments!r}")
    E, nu, b = material.youngs_modulus_MPa, material.poisson_ratio, g.sheet_thickness_mm
    ns = (int(n_segments) // 4, int(n_segments) // 2, int(n_segments))
    sols = [solve_beam(beam_mesh(g, n, clamp_x_mm=clamp_x_mm, include_fillet=include_fillet),
                       E, nu, b, g.web_thickness_mm) for n in ns]
    ks = tuple(s.stiffness_N_per_mm for s in sols)
    rk = richardson(ks, 2.0, formal_order=FORMAL_ORDER)
    return BeamConvergence(n_segments=ns, stiffness_N_per_mm=ks, observed_order=rk.order,
                           extrapolated_N_per_mm=rk.extrapolated,
                           error_estimate_rel=rk.error_rel,
                           face_strain_as_cut_per_N=sols[-1].face_strain_as_cut_per_N)


def beam_layer_rise(g: ElementGeometry, youngs_modulus_MPa: float, poisson_ratio: float,
                    layer, n_segments: int | None = None) -> float:
    """The layer's K rise at the beam level, relative: the stepped beam's unit-load tip
    compliance (:func:`unit_load_compliance`) with EI raised by the
    layer's transformed section on the segments under the carrier, over the same bare."""
    from tactcad.mechanics.gauge_strain import transformed_section

    b, E = g.sheet_thickness_mm, youngs_modulus_MPa
    mesh = beam_mesh(g, n_segments or DEFAULT_SEGMENTS)
    middle = 0.5 * (mesh.x_mm[1:] + mesh.x_mm[:-1])
    stiff = transformed_section(mesh.height_mm, b, E, layer.height_mm, layer.modulus_MPa,
                                layer.width_mm)[1]
    covered = (middle >= layer.x0_mm) & (middle <= layer.x1_mm)
    bare = unit_load_compliance(mesh, E, poisson_ratio, b)
    return bare / unit_load_compliance(mesh, E, poisson_ratio, b,
                                       np.where(covered, 1.0 + stiff, 1.0)) - 1.0


def estimate_beam(g: ElementGeometry, material: Material, *, element: int | None = None,
                  n_segments: int = DEFAULT_SEGMENTS, clamp_x_mm: float | None = None,
                  include_fillet: bool = True) -> StiffnessResult:
    """Timoshenko stepped-beam stiffness and gauge strain of one flexure element.

    Args:
        g: element geometry. material: plan material.
        element: paper element number to carry in the result.
        n_segments: notch segments of the finest mesh (multiple of 8, >= 16).
        clamp_x_mm, include_fillet: see :func:`beam_mesh`.

    The bonded gauge ``g`` carries (:attr:`~tactcad.partlib.array.element.ElementGeometry.
    gauge`) raises EI by its layer's transformed section on the segments under the carrier
    (:func:`beam_layer_rise`); the error estimate adds
    :data:`~tactcad.mechanics.bonded_layer.BEAM_LAYER_ERROR_REL` of the rise.

    Returns:
        :class:`StiffnessResult` with model ``beam``: K of the finest mesh, the
        ``face_strain_per_N`` (1/N: the face strain at the grid's centre under the
        gauge's layer, the bare section's times
        :func:`~tactcad.mechanics.closed_form.face_strain_factor`, as the closed form's),
        and an error estimate that adds the Richardson
        discretisation error to the model error of beam theory at the notch:
        |1/f - 1| + e/f, f = K_corrected / K_EB of the fem3d-fitted correction and e
        its own error estimate there, grown outside its fitted range
        (:func:`tactcad.mechanics.closed_form.correction_factor_and_error`; beam theory
        is as stiff as K_EB: the two levels share their sections).

    Raises:
        ValueError: invalid ``n_segments`` or geometry (see :func:`beam_mesh`).
    """
    start = time.perf_counter()
    conv = beam_convergence(g, material, n_segments, clamp_x_mm=clamp_x_mm,
                            include_fillet=include_fillet)
    # beam theory is as stiff as the uncorrected closed form, f off the corrected one, and
    # that is itself off fem3d by up to e (more past its fitted range): the bound adds e / f
    f, e = correction_factor_and_error(g, material)
    model_error = abs(1.0 / f - 1.0) + e / f
    k = conv.stiffness_N_per_mm[-1]
    from tactcad.mechanics.bonded_layer import BEAM_LAYER_ERROR_REL, layer_of

    layer = layer_of(g)
    if layer is not None:

        rise = beam_layer_rise(g, material.youngs_modulus_MPa, material.poisson_ratio, layer,
                               n_segments)
        k, model_error = k * (1.0 + rise), model_error + BEAM_LAYER_ERROR_REL * rise
    return StiffnessResult(element=element, model=MODEL_NAME,
                           stiffness_N_per_mm=k,
                           face_strain_per_N=conv.face_strain_as_cut_per_N
                           * face_strain_factor(g, material),
                           error_estimate_rel=conv.error_estimate_rel + model_error,
                           wall_time_s=time.perf_counter() - start)
