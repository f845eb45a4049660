"""A die's beam in 3D finite elements with silicon's full anisotropic stiffness
(scikit-fem): the die's fem3d level, a model of another kind than the closed form and than
CalculiX's brick (:func:`tactcad.products.silicon_die.mechanics.die_dynamics.calculix_beam_check`).

The beam, root to the post's far edge, is meshed with triquadratic hexahedra (27 nodes,
scikit-fem's ``ElementHex2``: bending without locking through a few layers), node planes at
the post's centre and at its footprint's edges. The stiffness is assembled from the 4th-order
tensor C_ijkl of silicon turned into the beam's frame (<110> along the beam on a (100)
wafer, :meth:`tactcad.vocabulary.crystal.CubicElasticity.in_frame`), K_ia,jb =
sum_q w g_ik C_akbl g_jl, per chunk of cells (no Python call per pair of basis functions).
The beam runs into its frame block (the die as made; :func:`tactcad.products.silicon_die.mechanics.die_dynamics.
beam_on_frame`): the device layer behind and beside the root, bonded on the buried oxide
and the handle (one silicon solid), the cavity under the beam with the handle as its floor,
held at the handle's underside. The frame turns and gives under the root's moment and shear:
on the example die that makes K_r 15 % and K_m 7 % softer than the same beams clamped at the
root (``frame=False``, the textbook cantilever K = E w t^3 / (4 L^3)); the die's closed form
carries that give as extra length behind the root
(:func:`tactcad.products.silicon_die.design.mems_die.root_extension_um`, fitted to this level).
K: a uniform shear traction of total F over the cross-section at
the post's centre (an internal plane of facets), K = F^2 / (f . u), f the consistent load
vector, so f . u / F is the section's mean deflection. f1: the lowest eigenvalue of
K u = omega^2 M u, M the silicon's consistent mass plus the post's as a surface density over
its footprint on the top face (scipy ``eigsh``, shift-invert at 0). Each at two meshes,
the second twice as fine every way, Richardson-extrapolated (order 4 for the energy of
quadratic elements on the clamped beam; :data:`FRAME_ORDER` on its frame, whose re-entrant
corner at the cavity's edge is singular); the error estimate is the extrapolation's change.
The post's footprint sides closer than :func:`sliver_tolerance_um` to the beam's sides are
snapped onto them (:func:`snapped_footprint`): a die whose 100 um post stands 1 um inside
its 102 um beam's edges would otherwise carry a 1 um layer of cells across the whole block,
the frame's cells graded from it (the reference beam's finer mesh 214 275 unknowns instead
of 105 675, the same as with the sliver closed). The footprint carries only the post's mass
(K's load is the whole section at the post's centre, which never moves), so K does not see
the snap and f1 moves by far less than its error; the distance moved is kept with the
result (:attr:`DieBeamFem.snapped_um`).
The factorisation (SuperLU under METIS's nested dissection of the node graph,
:func:`tactcad.mechanics.fem.sparse_lu.spd_lu`) serves both the static solve and the
eigenvalue's shift-invert. A mesh that is its own mirror image across the beam's axis
(y = 0 a plane of its nodes: the example's coarser meshes, not its finer, whose middle
segment across the beam takes 3 cells) is solved as its two halves, each factor about a
quarter of the whole's (:func:`half_mesh`): K and f1 are the whole's to round-off.

The root's peak stress (:func:`root_peak_fem3d`) is a model of its own: the beam root to the
post's centre, its filleted root (the plan's ``root_fillet_um``) and the frame block, half
the beam (y >= 0, a mirror plane of silicon's tensor in the beam's frame), in curved
quadratic tetrahedra meshed by gmsh and graded from the fillet's top arc; the peak is the
largest principal stress over the root's upper half, each vertex's the mean of its
elements'. It checks the closed form's K_t
(:func:`tactcad.products.silicon_die.design.mems_die.root_stress_concentration`).

Units: mm, N, MPa, tonne/mm^3 (so N/mm over tonne is 1/s^2), Hz.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

#: Elements along, across, through the beam on the coarser mesh (the finer doubles each).
DIVISIONS = (12, 2, 2)
#: The convergence order of K and f1 Richardson assumes for the clamped beam (quadratic
#: elements, energy norm squared: h^4).
ORDER = 4.0
#: The order on the beam on its frame: where the beam's underside meets the cavity's edge
#: the solid has a re-entrant 270 degree corner, whose stresses grow as r^(lambda - 1) with
#: lambda = 0.5445 (Williams, "Stress singularities resulting from various boundary
#: conditions in angular corners of plates in extension", J. Appl. Mech. 19, 1952, the
#: symmetric mode of a 3 pi / 2 wedge), so the energy, and K, converge as h^(2 lambda)
#: on a mesh refined evenly (CalculiX's C3D20 on the same block halves its change per
#: halving of the edge).
FRAME_ORDER = 2 * 0.5445
#: The quadrature order of the hexahedra's cells and facets: scikit-fem's default for
#: ``ElementHex2`` (twice its degree 6) takes 7^3 Gauss points per cell; 5 takes 3^3, exact
#: here because every cell is a box (a constant Jacobian), where the stiffness's and the
#: mass's integrands are polynomials of degree 4 in each coordinate and 3-point Gauss-Legendre
#: integrates degree 5 exactly (Abramowitz and Stegun, *Handbook of Mathematical Functions*,
#: 25.4.29). K and f1 move by round-off only; the basis and both assemblies cost a tenth.
HEX_QUADRATURE_ORDER = 5
#: The Lanczos basis of the first mode's shift-invert solve (ARPACK's ``ncv``; its default
#: is 20 for one eigenvalue, each vector a solve with the factor).
EIGEN_BASIS = 6
#: A feature edge closer to another than this fraction of the finer default mesh's edge
#: through the device layer (t / (2 x :data:`DIVISIONS`'s through-count)) is snapped onto it
#: (:func:`sliver_tolerance_um`): the thinnest layer of cells the block carries is then the
#: one its own divisions make, never a sliver of the post's footprint.
SNAP_FRACTION = 1.0
#: Voigt index of each pair of tensor indices (xx, yy, zz, yz, zx, xy).
VOIGT = ((0, 5, 4), (5, 1, 3), (4, 3, 2))


@dataclass(frozen=True)
class DieBeamFem:
    """One beam at the die's fem3d level.

    Attributes:
        role: the beam's row ("reference", "measuring").
        k_N_per_mm: K, extrapolated. f1_Hz: the first resonance with its post, extrapolated.
        k_error_rel, f1_error_rel: each extrapolation's change from the finer mesh.
        dofs: the finer mesh's degrees of freedom. wall_time_s: both meshes.
        frame: on its frame block, or clamped at its root.
        snapped_um: how far the post's footprint sides were moved onto the beam's sides
            (um; 0 when neither was closer than :func:`sliver_tolerance_um`): K does not
            see it and f1 moves by far less than its error (:func:`snapped_footprint`).
    """

    role: str
    k_N_per_mm: float
    f1_Hz: float
    k_error_rel: float
    f1_error_rel: float
    dofs: int
    wall_time_s: float
    #: on its frame block (the die as made), or clamped at its root
    frame: bool = True
    #: the largest distance a footprint edge of the post was snapped (um)
    snapped_um: float = 0.0

    def as_json(self) -> dict:
        """The row as ``tactcad die --fem3d --json`` writes it: the first resonance under
        ``modal --json``'s names (``first_Hz``, Hz; ``first_Hz_error_rel``), K (N/mm), the
        finer mesh's dofs, the wall time (s) and how far the post's footprint was snapped
        onto the beam's edges (``snapped_um``, um); the old names are the die command's to
        add (:data:`FEM3D_RENAMED`)."""
        return {"role": self.role, "K_N_per_mm": self.k_N_per_mm, "first_Hz": self.f1_Hz,
                "K_error_rel": self.k_error_rel, "first_Hz_error_rel": self.f1_error_rel,
                "dofs": self.dofs, "wall_time_s": self.wall_time_s,
                "root": "on its frame" if self.frame else "clamped",
                "snapped_um": self.snapped_um}


#: The keys of a die's fem3d rows (``tactcad die --fem3d --json``) renamed, old -> new: the
#: first resonance is ``first_Hz``, as ``modal --json`` names it. The old keys are still
#: written beside the new ones with the same values and each row lists them in its
#: ``deprecated_keys`` (:func:`tactcad.in_use.kobj_budget.with_declared_deprecated_keys`);
#: they go in a later release.
FEM3D_RENAMED = {"f1_Hz": "first_Hz", "f1_error_rel": "first_Hz_error_rel",
                 "f1_closed_form_error_rel": "first_Hz_closed_form_error_rel"}


def stiffness_tensor(voigt: np.ndarray) -> np.ndarray:
    """C_ijkl (3, 3, 3, 3) of a 6 x 6 Voigt stiffness (MPa; engineering shear strains)."""
    c = np.empty((3, 3, 3, 3))
    for i in range(3):
        for j in range(3):
            for k in range(3):
                for m in range(3):
                    c[i, j, k, m] = voigt[VOIGT[i][j], VOIGT[k][m]]
    return c


def assemble_anisotropic(sb, c: np.ndarray, chunk: int = 200):
    """The stiffness matrix of linear elasticity with the tensor ``c`` (MPa) on the vector
    space over the scalar basis ``sb`` (interleaved numbering ``3 s + a``, scikit-fem's
    ``ElementVector``'s), ``scipy.sparse.csr_matrix``, N/mm.

    The triplets' indices are 32-bit where the matrix's size allows (scipy's own choice
    for its indices): 64-bit ones were copied down to 32 bits whole, a third of the
    assembly's time on the die's finer meshes."""
    import scipy.sparse as sp

    nbf = sb.Nbfun
    grads = np.array([sb.basis[i][0].grad for i in range(nbf)])  # (nbf, 3, nel, nq)
    weights = sb.dx
    edofs = sb.element_dofs
    nel, n = edofs.shape[1], 3 * sb.N
    index = np.int32 if n < 2 ** 31 else np.int64
    rows, cols, vals = [], [], []
    for e0 in range(0, nel, chunk):
        sl = slice(e0, min(nel, e0 + chunk))
        g = grads[:, :, sl, :]
        # K[e, i, a, j, b] = sum_q w g_ik C_akbl g_jl
        k = np.einsum("ikeq,akbl,jleq,eq->eiajb", g, c, g, weights[sl], optimize=True)
        gd = (3 * edofs[:, sl].T[:, :, None]
              + np.arange(3)[None, None, :]).reshape(-1, 3 * nbf).astype(index)
        rows.append(np.broadcast_to(gd[:, :, None], k.shape[:1] + (3 * nbf, 3 * nbf)).ravel())
        cols.append(np.broadcast_to(gd[:, None, :], k.shape[:1] + (3 * nbf, 3 * nbf)).ravel())
        vals.append(k.reshape(-1))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n, n))


def _planes(lo: float, hi: float, cuts: list[float], count: int) -> np.ndarray:
    """About ``count`` divisions of [lo, hi] with node planes at every cut inside it."""
    edges = sorted({lo, hi, *[c for c in cuts if lo < c < hi]})
    out = [lo]
    for a, b in zip(edges, edges[1:]):
        parts = max(1, round(count * (b - a) / (hi - lo)))
        out += list(np.linspace(a, b, parts + 1)[1:])
    return np.array(out)


def snapped_edge(edge: float, anchors: tuple[float, ...], tolerance: float) -> float:
    """``edge`` moved onto the nearest of ``anchors`` when it lies closer to it than
    ``tolerance`` (and not on it), else ``edge`` (one unit, any: um or mm).

    Args:
        edge: a feature edge's coordinate along one axis. anchors: the edges it may merge
            into (coordinates on the same axis). tolerance: the largest sliver merged, >= 0.

    Returns:
        The edge's coordinate after the snap.

    Raises:
        ValueError: a negative tolerance.
    """
    if tolerance < 0:
        raise ValueError(f"tolerance {tolerance!r}: at least 0")
    near = [a for a in anchors if 0 < abs(edge - a) < tolerance]
    return min(near, key=lambda a: abs(edge - a)) if near else edge


def sliver_tolerance_um(beam) -> float:
    """The thinnest sliver between two feature edges the die's fem3d mesh keeps (um): a
    footprint edge of the post closer than this to the beam's edge is snapped onto it,
    :data:`SNAP_FRACTION` of the finer default mesh's edge through the device layer
    (10 um in a 40 um layer): the frame's cells grow from the thinnest layer, so a thinner
    one would set node planes across the whole block.

    Args:
        beam: the die's beam (its thickness, um).

    Returns:
        The tolerance (um).
    """
    return SNAP_FRACTION * beam.thickness_um / (2 * DIVISIONS[2])


@dataclass(frozen=True)
class PostFootprint:
    """The post's footprint on the beam's top face as the fem3d mesh carries it (mm).

    Attributes:
        start_x: its edge towards the root (x from the root). end_x: its far edge, the beam's
            end. half_y: its half width across the beam. snapped_um: how far each side was
            moved onto the beam's side (um).
    """

    start_x: float
    end_x: float
    half_y: float
    snapped_um: float

    @property
    def area_mm2(self) -> float:
        return (self.end_x - self.start_x) * 2 * self.half_y


def snapped_footprint(plan, beam) -> PostFootprint:
    """The post's footprint on ``beam`` (a square of ``plan.post_um`` centred on the
    post's centre, at most the beam's width), its sides closer than
    :func:`sliver_tolerance_um` to the beam's sides snapped onto them
    (:func:`snapped_edge`); along the beam nothing moves (the post's centre is the load,
    its far edge the beam's end, its near edge half a post from the centre, far from the
    root).

    On a die whose 100 um post stands on a 102 um beam the snap widens the footprint by
    1 um a side: the post's mass, spread over it, stays where it was along the beam, and K
    does not see the footprint at all, so on one mesh (the sliver's planes kept in both)
    K is the same and f1 moves by 2e-7 (reference beam) and 1e-8 (measuring): far below
    the extrapolation's error, which is left as it is. The mesh without the sliver is a
    coarser one, whose change the extrapolation carries: the reference beam's coarse-mesh K
    0.55 % (divisions (6, 1, 1)) and 0.23 % ((12, 2, 2)) stiffer than with the sliver's
    planes, halving as the mesh does; extrapolated, K_r 3.599 N/mm snapped against 3.600
    unsnapped (+-1.2 % and +-1.1 %), K_m 0.3615 against 0.3616.

    Args:
        plan: the die's plan. beam: one of its beams.

    Returns:
        :class:`PostFootprint` (mm; the snap in um).
    """
    at = beam.length_um * 1e-3
    half_post = plan.post_um * 1e-3 / 2
    half_width = beam.width_um * 1e-3 / 2
    tolerance = sliver_tolerance_um(beam) * 1e-3
    half_y = min(half_post, half_width)
    snapped_y = snapped_edge(half_y, (half_width,), tolerance)
    return PostFootprint(at - half_post, at + half_post, snapped_y, 1e3 * abs(snapped_y - half_y))


def _mesh(plan, beam, divisions: tuple[int, int, int], frame: bool, snap: bool = True):
    """The beam's hexahedra (its root clamped) or the beam on its frame block (the block
    held at the handle's underside; :func:`tactcad.products.silicon_die.mechanics.die_dynamics.beam_on_frame`),
    and a predicate of the held points; the post's footprint snapped
    (:func:`snapped_footprint`) unless ``snap`` is False."""
    from skfem import MeshHex

    from tactcad.products.silicon_die.mechanics.die_dynamics import beam_on_frame

    at = beam.length_um * 1e-3  # the post's centre: the force
    width, thick = beam.width_um * 1e-3, beam.thickness_um * 1e-3
    post = _footprint(plan, beam, snap)
    nx, ny, nz = divisions
    xs = _planes(0.0, post.end_x, [post.start_x, at], nx)
    ys = _planes(-width / 2, width / 2, [-post.half_y, post.half_y], ny)
    zs = np.linspace(0.0, thick, nz + 1)
    if not frame:
        return MeshHex.init_tensor(xs, ys, zs), lambda x: np.isclose(x[0], 0.0)
    block = beam_on_frame(plan, beam, xs, ys, zs)
    mesh = MeshHex.init_tensor(block.xs, block.ys, block.zs)
    centres = mesh.p[:, mesh.t].mean(axis=1)
    mesh = mesh.remove_elements(np.flatnonzero(~block.solid(*centres)))
    return mesh, lambda x: np.isclose(x[2], -block.handle_mm)


def _footprint(plan, beam, snap: bool) -> PostFootprint:
    """:func:`snapped_footprint`, or with ``snap`` False the footprint as drawn (mm)."""
    if snap:
        return snapped_footprint(plan, beam)
    at, half_post = beam.length_um * 1e-3, plan.post_um * 1e-3 / 2
    return PostFootprint(at - half_post, at + half_post,
                         min(half_post, beam.width_um * 1e-3 / 2), 0.0)


def mirror_symmetric(c: np.ndarray) -> bool:
    """Whether the plane y = 0 is a mirror plane of the elasticity tensor ``c`` (MPa):
    every component with an odd count of y indices vanishes (to 1e-12 of the largest), as
    for silicon turned into a beam's frame, <110> along it on a (100) wafer ((-110) is a
    mirror plane of the cubic crystal).

    Args:
        c: C_ijkl, shape (3, 3, 3, 3), MPa.

    Returns:
        True when reflecting y leaves ``c`` unchanged.
    """
    index = np.indices(c.shape)
    odd = (index == 1).sum(axis=0) % 2 == 1
    return bool(np.all(np.abs(c[odd]) <= 1e-12 * np.abs(c).max()))


def half_mesh(mesh):
    """The cells of ``mesh`` on y >= 0 when the mesh is its own mirror image across y = 0
    and that plane runs along cell faces; else None (mm).

    Args:
        mesh: a scikit-fem mesh (the die's hexahedra).

    Returns:
        The half mesh, or None when y = 0 crosses a cell or the node planes across y are
        not mirrored.
    """
    y = mesh.p[1]
    tolerance = 1e-9 * max(float(np.ptp(y)), 1e-30)
    planes = np.unique(np.round(y / tolerance)) * tolerance
    if not np.allclose(planes, -planes[::-1], rtol=0.0, atol=2 * tolerance):
        return None
    cell_y = y[mesh.t]
    low, high = cell_y.min(axis=0), cell_y.max(axis=0)
    if np.any((low < -tolerance) & (high > tolerance)) or not np.any(high <= tolerance):
        return None
    return mesh.remove_elements(np.flatnonzero(high <= tolerance))


def _solve(plan, beam, divisions: tuple[int, int, int],
           frame: bool = True, snap: bool = True,
           mirror: bool = True) -> tuple[float, float, int]:
    """(K N/mm, f1 Hz, dofs) of ``beam`` on one mesh, on its frame or clamped at its root.

    The beam, its post, its frame block, the load and silicon's tensor in the beam's frame
    are each their own mirror image across y = 0 (:func:`mirror_symmetric`), so when the
    mesh is too (:func:`half_mesh`) the half on y >= 0 is solved twice instead of the whole
    once: held in y on the plane (the symmetric half) for K and the lowest symmetric mode,
    held in x and z there (the antisymmetric half) for the lowest antisymmetric mode; f1 is
    the lower of the two, the whole mesh's lowest mode. Each half's factor costs about a
    quarter of the whole's (121 000 unknowns: about 45 % of the time in all); K and f1 are
    the whole mesh's to round-off. ``mirror`` False, or a mesh that is not mirrored, solves
    the whole. ``dofs`` is the whole mesh's either way.

    Everything is assembled on the scalar basis and carried to the displacement's three
    components by the interleaved numbering ``3 s + a`` (:func:`assemble_anisotropic`): the
    load is the z component's, the mass is the scalar mass on each component (one scalar
    basis instead of a vector one, whose mapping and mass kernel cost as much as the
    factorisation).

    Args:
        plan: the die's plan. beam: one of its beams. divisions: elements along, across
            and through the beam. frame: on its frame block, else clamped at its root.
        snap: snap the post's footprint (:func:`snapped_footprint`).
        mirror: solve the two halves when the mesh allows.

    Returns:
        (K N/mm, f1 Hz, the whole mesh's unknowns).
    """
    from tactcad.vocabulary.crystal import SILICON

    post = _footprint(plan, beam, snap)
    mesh, held = _mesh(plan, beam, divisions, frame, snap)
    dofs = int(3 * (mesh.nvertices + mesh.nedges + mesh.nfacets + mesh.nelements))
    c = stiffness_tensor(SILICON.in_frame((1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)))
    half = half_mesh(mesh) if mirror and mirror_symmetric(c) else None
    if half is None:
        k_N_per_mm, lam = _solve_mesh(plan, beam, post, mesh, held, c, ())
        return k_N_per_mm, _hertz(lam), dofs
    k_half, symmetric = _solve_mesh(plan, beam, post, half, held, c, (1,))
    _, antisymmetric = _solve_mesh(plan, beam, post, half, held, c, (0, 2))
    return k_half / 2.0, _hertz(min(symmetric, antisymmetric)), dofs


def _hertz(lam: float) -> float:
    """The frequency (Hz) of the eigenvalue omega^2 ``lam`` (1/s^2)."""
    return math.sqrt(lam) / (2 * math.pi)


def _solve_mesh(plan, beam, post: PostFootprint, mesh, held, c: np.ndarray,
                on_mirror: tuple[int, ...]) -> tuple[float, float]:
    """(1 / (f . u) (N/mm), the lowest eigenvalue omega^2 (1/s^2)) on ``mesh``, ``f`` the
    unit force's traction 1 / (w t) on the post centre's section, held where ``held`` is
    true and, on y = 0, in the components ``on_mirror`` (() for a whole mesh, whose
    1 / (f . u) is K; (1,) the symmetric half, whose section carries half the force and
    half the whole's f . u, so K is its 1 / (f . u) over 2; (0, 2) the
    antisymmetric half, where the symmetric load does no work: K is not solved, only its
    lowest mode, from a fixed random start)."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import LinearOperator, eigsh
    from skfem import Basis, BilinearForm, ElementHex2, FacetBasis, LinearForm, condense

    from tactcad.products.silicon_die.mechanics.die_dynamics import (POST_DENSITY_KG_M3,
                                                                     SILICON_DENSITY_KG_M3)
    at = beam.length_um * 1e-3  # the post's centre: the force
    width, thick = beam.width_um * 1e-3, beam.thickness_um * 1e-3
    scalar = Basis(mesh, ElementHex2(), intorder=HEX_QUADRATURE_ORDER)
    k = assemble_anisotropic(scalar, c)
    clamped = _components(scalar.get_dofs(held).all())
    if on_mirror:
        plane = 3 * scalar.get_dofs(lambda x: np.isclose(x[1], 0.0)).all()
        clamped = np.unique(np.concatenate([clamped] + [plane + a for a in on_mirror]))
    # whole nodes held (or one component a node on the mirror): dofs stay numbered 3 s + a
    # and METIS orders the node graph
    solving_k = on_mirror != (0, 2)
    f = np.zeros(3 * scalar.N)
    if solving_k:
        section = FacetBasis(mesh, scalar.elem, facets=mesh.facets_satisfying(
            lambda x: np.isclose(x[0], at) & (x[2] > -1e-12)
            & (np.abs(x[1]) < width / 2 + 1e-12)), intorder=HEX_QUADRATURE_ORDER)

        @LinearForm
        def spread(v, w):  # a unit force over the whole section, evenly
            return v / (width * thick)

        f[2::3] = -spread.assemble(section)  # down (-z)
    kk, ff, _, free = condense(k, f, D=clamped)
    free_mask = np.zeros(3 * scalar.N, dtype=bool)
    free_mask[free] = True
    lu = _node_ordered_lu(k, kk, free_mask)
    rho = SILICON_DENSITY_KG_M3 * 1e-12  # tonne/mm^3
    post_t = POST_DENSITY_KG_M3 * plan.post_um ** 2 * plan.post_height_um * 1e-18 * 1e-3

    @BilinearForm
    def mass(u_, v, w):
        return w.density * u_ * v

    top = FacetBasis(mesh, scalar.elem, facets=mesh.facets_satisfying(
        lambda x: np.isclose(x[2], thick) & (x[0] >= post.start_x - 1e-12)
        & (x[0] <= post.end_x + 1e-12) & (np.abs(x[1]) <= post.half_y + 1e-12)),
        intorder=HEX_QUADRATURE_ORDER)
    m_scalar = (mass.assemble(scalar, density=rho)  # the post's mass on its footprint
                + mass.assemble(top, density=post_t / post.area_mm2))
    m = sp.kron(m_scalar, sp.identity(3), format="csr")  # the same on each component
    mm = condense(k, m, D=clamped, expand=False)[1]
    inverse = LinearOperator(kk.shape, matvec=lu.solve, dtype=float)  # shift-invert at 0
    k_N_per_mm = math.nan
    if solving_k:
        u = np.zeros(3 * scalar.N)
        u[free] = lu.solve(ff)
        k_N_per_mm = 1.0 / float(f @ u)
        # started from the static deflection, close to the first mode's shape: a short
        # Lanczos basis converges in a few solves instead of ARPACK's default twenty
        start = u[free]
    else:
        start = np.random.default_rng(0).standard_normal(len(free))
    lam = eigsh(kk, k=1, M=mm, sigma=0.0, which="LM", OPinv=inverse, v0=start,
                ncv=EIGEN_BASIS, return_eigenvectors=False)
    return k_N_per_mm, float(lam[0])


def _node_ordered_lu(k, kk, free: np.ndarray):
    """:func:`tactcad.mechanics.fem.sparse_lu.spd_lu` of ``kk``, the stiffness ``k``
    (numbered ``3 s + a``) with its held dofs removed (``free``: a boolean mask over ``k``'s
    rows), in METIS's nested dissection of the node graph: of ``kk``'s own when whole nodes
    are held, else of ``k``'s restricted to the free dofs (a node held in one component on
    the mirror plane keeps the others)."""
    from tactcad.mechanics.fem.sparse_lu import graph_nested_dissection, node_dof_order, spd_lu

    per_node = free.reshape(-1, 3)
    if np.array_equal(per_node.all(axis=1), per_node.any(axis=1)):
        return spd_lu(kk, dofs_per_node=3)
    return spd_lu(kk, order=node_dof_order(graph_nested_dissection(k[::3, ::3]), 3, kept=free))


def _components(scalar_dofs: np.ndarray) -> np.ndarray:
    """The displacement's dofs ``3 s + a`` (a = x, y, z) of scalar dofs ``s``."""
    return (3 * np.asarray(scalar_dofs)[:, None] + np.arange(3)[None, :]).ravel()


#: The finer mesh's unknowns of the shipped dies' beams on their frames (the 8 mm robot
#: jaw's 67 000 ... 80 000, the 5 mm grasper's 100 000 ... 128 000), whose two meshes take
#: about 45 s a beam on two cores; the solve's time grows faster than its unknowns (a
#: sparse direct factorisation of a 3D mesh), its memory about as fast.
SHIPPED_FINE_DOFS = (67_000, 128_000)


def mesh_dofs(plan, beam, divisions: tuple[int, int, int] = DIVISIONS,
              frame: bool = True) -> tuple[int, int]:
    """The unknowns (three per node of the triquadratic hexahedra) of ``beam``'s two meshes,
    ``divisions`` and twice as fine, counted on the meshes without solving (milliseconds):
    what :func:`die_beam_fem3d`'s time and memory grow with (the post's footprint snapped
    as the solve snaps it, :func:`snapped_footprint`).

    Args:
        plan: the die's plan. beam: one of its beams. divisions, frame: as
            :func:`die_beam_fem3d`.

    Returns:
        (the coarser mesh's unknowns, the finer's).

    Raises:
        ValueError: a division below 1.
    """
    if min(divisions) < 1:
        raise ValueError(f"divisions {divisions!r}: each at least 1")

    def count(d: tuple[int, int, int]) -> int:
        mesh, _ = _mesh(plan, beam, d, frame)
        return 3 * (mesh.nvertices + mesh.nedges + mesh.nfacets + mesh.nelements)
    return count(divisions), count(tuple(2 * d for d in divisions))


def die_beam_fem3d(plan, beam, divisions: tuple[int, int, int] = DIVISIONS,
                   frame: bool = True,
                   progress: Callable[[str], None] | None = None) -> DieBeamFem:
    """``beam`` of ``plan`` at two meshes (``divisions`` and twice as fine), extrapolated
    (module doc).

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan`. beam: one of its beams.
        divisions: elements along, across and through the beam on the coarser mesh.
        frame: the beam on its frame block (the die as made); False: clamped at its root
            (the textbook cantilever, E w t^3 / (4 L^3) with shear and plate effects).
        progress: told before each mesh is solved (its unknowns) and when the coarser is
            done (its seconds); None says nothing.

    Returns:
        :class:`DieBeamFem`, its ``snapped_um`` how far the post's footprint was snapped
        onto the beam's sides (um, :func:`snapped_footprint`).

    Raises:
        ValueError: a division below 1.
    """
    if min(divisions) < 1:
        raise ValueError(f"divisions {divisions!r}: each at least 1")
    say = progress or (lambda line: None)
    snapped = snapped_footprint(plan, beam).snapped_um
    finer = tuple(2 * d for d in divisions)
    t0 = time.perf_counter()
    say(f"  {beam.role} beam, mesh 1 of 2 ...")
    coarse = _solve(plan, beam, divisions, frame)
    say(f"  {beam.role} beam, mesh 1 of 2: {coarse[2]} unknowns in "
        f"{time.perf_counter() - t0:.0f} s; mesh 2 of 2 (twice as fine) ...")
    fine = _solve(plan, beam, finer, frame)
    say(f"  {beam.role} beam, mesh 2 of 2: {fine[2]} unknowns; both in "
        f"{time.perf_counter() - t0:.0f} s")
    r = 2.0 ** (FRAME_ORDER if frame else ORDER)

    def extrapolated(a: float, b: float) -> tuple[float, float]:
        best = b + (b - a) / (r - 1.0)
        return best, abs(best / b - 1.0)

    k, k_err = extrapolated(coarse[0], fine[0])
    f1, f_err = extrapolated(coarse[1], fine[1])
    return DieBeamFem(beam.role, k, f1, k_err, f_err, fine[2], time.perf_counter() - t0, frame,
                      snapped)


# --- the root's peak stress on its fillets ----------------------------------------------------

#: The element edge on each fillet's top arc at mesh level 1, over the fillet's radius; each
#: level halves it (:func:`root_peak_fem3d`).
ROOT_ARC_EDGE_OVER_R = 0.5
#: How fast the element edge grows with the distance from the fillet's top arc (per unit
#: distance), up to :data:`ROOT_BEAM_EDGE_OVER_T` t in the beam and the root's region.
ROOT_GROWTH = 0.3
#: The element edge in the beam and around its root, over the device layer's thickness (the
#: quadratic tetrahedra carry the linear bending stress through the layer exactly).
ROOT_BEAM_EDGE_OVER_T = 0.25
#: The levels the die's check and its test solve (the arc's edge r / 4 and r / 8).
ROOT_LEVELS = (2, 3)


@dataclass(frozen=True)
class RootPeakFem:
    """A beam's root peak stress at the die's fem3d level, on its filleted root.

    Attributes:
        role: the beam's row. radius_um: the fillet's radius (um).
        nominal_MPa_per_N: 6 L / (w t^2), the root's nominal surface stress per newton.
        levels: the mesh levels solved; kt_levels: each level's K_t (peak over nominal);
            dofs: each level's degrees of freedom; seconds: each level's wall time (s).
        kt: K_t on the finest level; kt_error_rel: its change from the level before, relative
            (the mesh's error estimate: the peak converges unevenly as the vertex nearest the
            fillet's top edge moves, so it is not extrapolated).
        where_um: the peak's place on the finest mesh (x from the root line along the beam,
            y from its axis, z up from the device layer's underside; um).
    """

    role: str
    radius_um: float
    nominal_MPa_per_N: float
    levels: tuple[int, ...]
    kt_levels: tuple[float, ...]
    dofs: tuple[int, ...]
    seconds: tuple[float, ...]
    kt: float
    kt_error_rel: float
    where_um: tuple[float, float, float]

    @property
    def peak_MPa_per_N(self) -> float:
        """The root's peak stress per newton of tip force (MPa/N): K_t x the nominal."""
        return self.kt * self.nominal_MPa_per_N

    def as_json(self) -> dict:
        return {"role": self.role, "root_fillet_um": self.radius_um,
                "root_nominal_stress_MPa_per_N": self.nominal_MPa_per_N,
                "levels": list(self.levels), "kt_levels": list(self.kt_levels),
                "dofs": list(self.dofs), "wall_time_s": list(self.seconds),
                "root_stress_concentration_factor": self.kt,
                "root_stress_concentration_error_rel": self.kt_error_rel,
                "root_peak_stress_MPa_per_N": self.peak_MPa_per_N,
                "where_um": list(self.where_um)}


def _root_mesh(plan, beam, level: int):
    """The beam, root to the post's centre, its filleted root and the frame block around it
    (:data:`tactcad.products.silicon_die.mechanics.die_dynamics.FRAME_MARGIN_OVER_T`), the
    half on y >= 0, in quadratic tetrahedra meshed by gmsh (curved on the fillet), graded
    from the fillet's top arc (mm); and (t, w, L, r, handle) in mm."""
    import gmsh
    import meshio
    from skfem.io.meshio import from_meshio

    from tactcad.mechanics.fem.fem_mesh import initialize_gmsh

    from tactcad.products.silicon_die.mechanics.die_dynamics import FRAME_MARGIN_OVER_T

    t, w = beam.thickness_um * 1e-3, beam.width_um * 1e-3
    length, r = beam.length_um * 1e-3, plan.root_fillet_um * 1e-3
    cavity = plan.cavity_depth_of(beam) * 1e-3
    handle = (plan.stack.box_um + plan.stack.handle_um) * 1e-3
    margin = FRAME_MARGIN_OVER_T * t
    side = w / 2 + margin
    arc_edge = ROOT_ARC_EDGE_OVER_R * r / 2 ** (level - 1)
    beam_edge = ROOT_BEAM_EDGE_OVER_T * t
    started = gmsh.isInitialized()
    if not started:
        initialize_gmsh()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add(f"root_{beam.role}_{level}")
        occ = gmsh.model.occ
        corners = [(-margin, 0.0), (length, 0.0), (length, w / 2), (r, w / 2), (0.0, w / 2 + r),
                   (0.0, side), (-margin, side)]
        p = [occ.addPoint(x, y, 0.0) for x, y in corners]
        centre = occ.addPoint(r, w / 2 + r, 0.0)
        curves = [occ.addLine(p[0], p[1]), occ.addLine(p[1], p[2]), occ.addLine(p[2], p[3]),
                  occ.addCircleArc(p[3], centre, p[4]), occ.addLine(p[4], p[5]),
                  occ.addLine(p[5], p[6]), occ.addLine(p[6], p[0])]
        device = occ.extrude([(2, occ.addPlaneSurface([occ.addCurveLoop(curves)]))], 0, 0, t)
        below = [(3, occ.addBox(-margin, 0.0, -handle, margin, side, handle)),
                 (3, occ.addBox(0.0, 0.0, -handle, length, side, handle - cavity))]
        occ.fragment([e for e in device if e[0] == 3], below)
        occ.synchronize()
        eps = 1e-4 * t
        arcs = gmsh.model.getEntitiesInBoundingBox(-eps, w / 2 - eps, t - eps, r + eps,
                                                   w / 2 + r + eps, t + eps, 1)
        if len(arcs) != 1:
            raise RuntimeError(f"the fillet's top arc: found {len(arcs)} curves, one expected")
        field = gmsh.model.mesh.field
        distance = field.add("Distance")
        field.setNumbers(distance, "CurvesList", [arcs[0][1]])
        field.setNumber(distance, "Sampling", 100)
        graded = field.add("MathEval")
        field.setString(graded, "F", f"{arc_edge} + {ROOT_GROWTH} * F{distance}")
        box = field.add("Box")
        for key, value in (("VIn", beam_edge), ("VOut", handle / 4), ("XMin", -t),
                           ("XMax", length + eps), ("YMin", -eps), ("YMax", w / 2 + r + eps),
                           ("ZMin", -t / 2), ("ZMax", t + eps), ("Thickness", handle / 2)):
            field.setNumber(box, key, value)
        least = field.add("Min")
        field.setNumbers(least, "FieldsList", [graded, box])
        field.setAsBackgroundMesh(least)
        for key, value in (("Mesh.MeshSizeExtendFromBoundary", 0),
                           ("Mesh.MeshSizeFromPoints", 0), ("Mesh.MeshSizeFromCurvature", 0),
                           ("Mesh.MeshSizeMax", handle / 4), ("Mesh.Algorithm3D", 1)):
            gmsh.option.setNumber(key, value)
        gmsh.model.mesh.generate(3)
        gmsh.model.mesh.setOrder(2)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        _, nodes = gmsh.model.mesh.getElementsByType(11)  # 10-node tetrahedra
        gmsh.model.remove()
    finally:
        if not started:
            gmsh.finalize()
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    cells = index[nodes.astype(np.int64)].reshape(-1, 10)[:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]
    used = np.unique(cells)  # gmsh's edge order -> meshio's (VTK's): its last two swap
    renumber = np.full(len(tags), -1, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    mesh = from_meshio(meshio.Mesh(xyz.reshape(-1, 3)[used], [("tetra10", renumber[cells])]))
    return mesh, (t, w, length, r, handle)


def _root_peak(plan, beam, level: int) -> tuple[float, tuple, int]:
    """(the root's peak stress per newton of tip force (MPa/N), its place (mm), dofs) on the
    filleted root's mesh at ``level``: a unit force spread evenly over the half section at
    the post's centre (-z), the handle's underside held, y = 0 the plane of symmetry (silicon's
    tensor in the beam's frame is mirror-symmetric across it: (-110) is a mirror plane of
    the cubic crystal); the largest principal stress over the mesh's vertices on the root's
    upper half (within a layer thickness of the root line and of the fillet), each vertex's
    stress the mean of its elements' (quadratic displacements: each element's stress
    evaluated at the vertex)."""
    from skfem import Basis, ElementTetP2, FacetBasis, LinearForm, condense

    from tactcad.mechanics.fem.sparse_lu import spd_lu
    from tactcad.vocabulary.crystal import SILICON

    mesh, (t, w, length, r, handle) = _root_mesh(plan, beam, level)
    scalar = Basis(mesh, ElementTetP2())
    c = stiffness_tensor(SILICON.in_frame((1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)))
    k = assemble_anisotropic(scalar, c)
    held = _components(scalar.get_dofs(lambda x: np.isclose(x[2], -handle)).all())
    mirror = 3 * scalar.get_dofs(lambda x: np.isclose(x[1], 0.0)).all() + 1
    section = FacetBasis(mesh, scalar.elem, facets=mesh.facets_satisfying(
        lambda x: np.isclose(x[0], length) & (x[2] > -1e-12)))

    @LinearForm
    def spread(v, _):  # half of a unit force, over the half section
        return v * 0.5 / (t * w / 2)

    f = np.zeros(3 * scalar.N)
    f[2::3] = -spread.assemble(section)
    kk, ff, _, free = condense(k, f, D=np.unique(np.concatenate([held, mirror])))
    u = np.zeros(3 * scalar.N)
    # the mirror holds only y: dofs ordered one by one (nested dissection: 70 s -> 14 s at level 3)
    u[free] = spd_lu(kk, dofs_per_node=1).solve(ff)
    corners = np.array([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    at_vertices = Basis(mesh, ElementTetP2(), quadrature=(corners, np.full(4, 1 / 24)))
    grad = np.array([at_vertices.interpolate(u[a::3]).grad for a in range(3)])  # a, k, e, q
    stress = np.einsum("akbl,bleq->akeq", c, 0.5 * (grad + grad.transpose(1, 0, 2, 3)))
    total = np.zeros((3, 3, mesh.p.shape[1]))
    count = np.zeros(mesh.p.shape[1])
    for q in range(4):
        np.add.at(count, mesh.t[q], 1.0)
        for a in range(3):
            for b in range(3):
                np.add.at(total[a, b], mesh.t[q], stress[a, b, :, q])
    vertex = count > 0
    mean = total[:, :, vertex] / count[vertex]
    first = np.linalg.eigvalsh(mean.transpose(2, 0, 1))[:, -1]
    x, y, z = mesh.p[:, vertex]
    near = (np.abs(x) < t) & (z > t / 2) & (y > w / 2 - t) & (y < w / 2 + r + t)
    i = np.flatnonzero(near)[np.argmax(first[near])]
    return float(first[i]), (float(x[i]), float(y[i]), float(z[i])), 3 * scalar.N


def root_peak_fem3d(plan, beam, levels: tuple[int, ...] = ROOT_LEVELS) -> RootPeakFem:
    """``beam``'s root peak stress on its fillets at the die's fem3d level: its filleted
    root and frame block meshed at each of ``levels`` (the arc's element edge
    :data:`ROOT_ARC_EDGE_OVER_R` r / 2^(level - 1)), each level's peak over the nominal
    6 L / (w t^2) as K_t; the finest level's is the result, its change from the level before
    the error estimate (on the example die's reference beam levels 1-4 give K_t 1.86, 1.94,
    2.04, 2.06, its measuring beam 1.86, 1.93, 2.02, 2.06: level 3 within about 1 % of 4).

    The peak lies on the fillet's top edge, near its tangent with the beam's sidewall
    (tension: the beam bends down into its cavity); the re-entrant edge under the root
    (the cavity's wall, compressed, singular) is left out by taking the upper half.

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan`. beam: one of
            its beams.
        levels: increasing mesh levels, at least two, each >= 1.

    Returns:
        :class:`RootPeakFem`.

    Raises:
        ValueError: fewer than two levels, a level below 1, or levels not increasing by one.
    """
    levels = tuple(levels)
    if len(levels) < 2 or min(levels) < 1 or any(b != a + 1 for a, b in zip(levels, levels[1:])):
        raise ValueError(f"levels = {levels!r}: at least two, each >= 1, increasing by one")
    nominal = 6.0 * beam.length_um * 1e-3 / (beam.width_um * 1e-3 * (beam.thickness_um * 1e-3) ** 2)
    kts, dofs, seconds, where = [], [], [], (0.0, 0.0, 0.0)
    for level in levels:
        t0 = time.perf_counter()
        peak, where, n = _root_peak(plan, beam, level)
        kts.append(peak / nominal)
        dofs.append(n)
        seconds.append(time.perf_counter() - t0)
    return RootPeakFem(beam.role, plan.root_fillet_um, nominal, levels, tuple(kts), tuple(dofs),
                       tuple(seconds), kts[-1], abs(kts[-2] / kts[-1] - 1.0),
                       tuple(1e3 * v for v in where))
