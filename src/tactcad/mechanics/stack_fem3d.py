"""The ``stack-fem3d`` crosstalk level: each row's bonded stack as a 3D
linear-elastic solid (scikit-fem, triquadratic hexahedra on a tensor mesh).

The solid is the stack model of :mod:`tactcad.mechanics.stack_crosstalk` in
3D: the bonded block (x over the bonded width centred on the bolt pattern,
y over the section height, z between the clamp plates), the element layers
of the element's material and the spacer layers of the spacers' (bonded
interfaces: one continuous mesh; the bolts are not meshed, their preload is
what keeps the interfaces bonded). Plates: at each end face u_x = u_y = 0
(rigid in the plate's plane) and u_z on a spring bed whose moment stiffness
about x is the bridge's torsion stiffness (k = k_theta / I per area).
A unit tip force on element j is its static equivalent on the block's front
face over the element's layer: a uniform shear traction 1 / A and a linear
normal traction for the moment F d about z (d: tip to front face).

Per element i: gauge strain = mean eps_xx on the top face at the front edge
over i's layer, times the grid's Saint-Venant share (as the beam levels);
tip displacement = the work-conjugate of its own load (so the tip matrix is
symmetric by construction, f_i^T K^-1 f_j). One ``splu`` factorisation per
row serves all its loads. Two mesh levels (h, h/2) give a Richardson error
estimate of crosstalk_rel (order 2 assumed when it cannot be observed).

Units: mm, N, MPa, s.
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.sparse.linalg import splu

from tactcad.mechanics.fem.fem2d import assemble_elasticity
from tactcad.mechanics.stack_crosstalk import (BASIS, CrosstalkResult, StackInputs,
                                               bridge_torsion_stiffness_Nmm, crosstalk_of,
                                               decoupling_matrix, grid_transfer, _layers)

#: Hexahedra across x and y and per layer along z on the coarse level (the fine halves h).
#: The paper's array: (3, 3, 2) gives crosstalk_rel 1.50e-5 +/- 27 % in 9.2 s on two
#: shared cores; (2, 2, 1) gives 1.71e-5 +/- 70 % in 2 s.
COARSE_DIVISIONS = (3, 3, 2)


def _axis(lo: float, hi: float, n: int) -> np.ndarray:
    return np.linspace(lo, hi, n + 1)


def solve_row_3d(inputs: StackInputs, row: int, refine: int,
                 divisions: tuple[int, int, int] = COARSE_DIVISIONS
                 ) -> tuple[np.ndarray, np.ndarray]:
    """(stack gauge strain S (1/N), stack tip compliance C (mm/N)) of ``row``'s
    elements at mesh level ``refine`` (1 coarse, 2 fine)."""
    from skfem import (Basis, BilinearForm, ElementHex2, ElementVector, FacetBasis, LinearForm,
                       MeshHex, asm, condense)

    idx = [k for k, r in enumerate(inputs.rows) if r == row]
    w, h = inputs.bonded_width_mm, inputs.height_mm
    nx, ny, nz = (d * refine for d in divisions)
    layers = _layers(inputs, row)
    zs = np.unique(np.concatenate([_axis(a, b, nz) for a, b, _ in layers]))
    mesh = MeshHex.init_tensor(_axis(0.0, w, nx), _axis(0.0, h, ny), zs)
    el_layers = [(a, b) for a, b, is_el in layers if is_el]
    nu_e, nu_s = inputs.element_nu, inputs.spacer_nu

    def moduli(z):
        in_el = np.zeros_like(z, dtype=bool)
        for a, b in el_layers:
            in_el |= (z > a) & (z < b)
        E = np.where(in_el, inputs.element_E_MPa, inputs.spacer_E_MPa)
        nu = np.where(in_el, nu_e, nu_s)
        return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))

    # the vector basis numbers its dofs as assemble_elasticity does (3 s + c)
    basis = Basis(mesh, ElementVector(ElementHex2()), intorder=4)
    scalar = Basis(mesh, ElementHex2(), intorder=4)
    K = assemble_elasticity(scalar, *moduli(np.asarray(scalar.global_coordinates())[2]))
    z0, z1 = inputs.span_mm
    ends = mesh.facets_satisfying(lambda x: np.isclose(x[2], z0) | np.isclose(x[2], z1))
    k_bed = bridge_torsion_stiffness_Nmm(inputs) / (w * h ** 3 / 12)

    @BilinearForm
    def bed(u, v, p):
        return k_bed * u[2] * v[2]

    K = K + asm(bed, FacetBasis(mesh, basis.elem, facets=ends, intorder=4))
    fixed = basis.get_dofs(ends).all(["u^1", "u^2"])
    loads = []
    for k in idx:
        zc = inputs.z_mm[k]
        lo, hi = zc - inputs.sheet_mm / 2, zc + inputs.sheet_mm / 2
        face = mesh.facets_satisfying(lambda x, lo=lo, hi=hi: np.isclose(x[0], w)
                                      & (x[2] > lo) & (x[2] < hi))
        area, inertia = inputs.sheet_mm * h, inputs.sheet_mm * h ** 3 / 12
        arm = inputs.lever_mm[k] - w / 2  # tip to the front face (mm)

        @LinearForm
        def tip(v, p, area=area, inertia=inertia, arm=arm):
            return v[1] / area - arm * (p.x[1] - h / 2) / inertia * v[0]

        loads.append(asm(tip, FacetBasis(mesh, basis.elem, facets=face, intorder=4)))
    F = np.column_stack(loads)
    Kc, _, _, free = condense(K, F[:, 0], D=fixed)
    U = np.zeros_like(F)
    U[free] = splu(Kc.tocsc()).solve(F[free])
    C = F.T @ U  # work-conjugate tip displacements
    # eps_xx on the top face at the front edge, averaged over each element's layer
    S = np.zeros((len(idx), len(idx)))
    for a, k in enumerate(idx):
        zc = inputs.z_mm[k]
        zq = np.linspace(zc - inputs.sheet_mm / 2, zc + inputs.sheet_mm / 2, 7)[1:-1]
        pts = np.vstack([np.full_like(zq, w * (1 - 1e-9)), np.full_like(zq, h * (1 - 1e-9)), zq])
        probes = basis.probes(pts)
        dx = 1e-3 * w / nx
        probes_b = basis.probes(pts - np.array([[dx], [0.0], [0.0]]))
        ux = (probes @ U)[:len(zq)]
        uxb = (probes_b @ U)[:len(zq)]
        S[a] = grid_transfer(inputs, k) * ((ux - uxb) / dx).mean(axis=0)
    return S, C


def _matrices(inputs: StackInputs, refine: int, divisions: tuple[int, int, int]
              ) -> tuple[np.ndarray, np.ndarray]:
    n = len(inputs.numbers)
    S = np.diag(np.array(inputs.own_strain_per_N, float))
    C = np.diag(1.0 / np.array(inputs.stiffness_N_per_mm, float))
    for row in sorted(set(inputs.rows)):
        idx = [k for k, r in enumerate(inputs.rows) if r == row]
        s3, c3 = solve_row_3d(inputs, row, refine, divisions)
        S[np.ix_(idx, idx)] += s3
        C[np.ix_(idx, idx)] += c3
    assert S.shape == (n, n)
    return S, C


def estimate_stack_fem3d(inputs: StackInputs,
                         divisions: tuple[int, int, int] = COARSE_DIVISIONS) -> CrosstalkResult:
    """3D stack at two mesh levels (``divisions``: hexahedra across x, y and per
    layer on the coarse one; the fine one halves h): the fine level's
    matrices, Richardson error of crosstalk_rel.

    Raises:
        ValueError: a division below 1.
    """
    if min(divisions) < 1:
        raise ValueError(f"divisions = {divisions!r}: allowed three integers >= 1")
    t0 = time.perf_counter()
    coarse = crosstalk_of(_matrices(inputs, 1, divisions)[0])[0]
    S, C = _matrices(inputs, 2, divisions)
    rel, (i, j) = crosstalk_of(S)
    # two levels cannot observe the order: order 2 (triquadratic hexahedra in bending)
    error = abs(rel - coarse) / 3.0 / rel if rel else 0.0
    asym = float(np.max(np.abs(C - C.T)) / np.max(np.abs(C)))
    return CrosstalkResult("stack-fem3d", inputs.numbers, S, C, rel,
                           (inputs.numbers[i], inputs.numbers[j]), decoupling_matrix(S), asym,
                           error if math.isfinite(error) else math.inf,
                           time.perf_counter() - t0, BASIS + "; 3D solid of the bonded stack")
