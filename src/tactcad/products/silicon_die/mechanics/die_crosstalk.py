"""Crosstalk of a silicon die through its handle and die attach: a force on one post
changes the other units' half bridges.

What couples the units. A post's force bends its beam; the beam's root hands the force and
its moment to the frame, and through it to the whole die, which rests on its die-attach
film. An unloaded beam carries no moment whatever its root does (statics of a free
cantilever), so a neighbour's beam resistor reads the die's strain only where its legs run
onto the frame to their contacts; its on-die reference resistor lies wholly on the frame
and reads it all. The unit's reading is the beam resistor's relative change less its
reference's (the half bridge, :func:`tactcad.products.silicon_die.mechanics.piezoresistor.die_readout`).

Model (``attach-fem3d``, the die's one crosstalk level). The die is a block of silicon, the
handle, buried oxide and device layer as one solid with silicon's full anisotropic
stiffness (the die's edges along <110>, :data:`tactcad.vocabulary.crystal.SILICON`), the
device layer cut away over the window; the shallow cavities under the beams and the 1 um
oxide are left out. Its bottom face rests on the die attach, a thin film on a rigid
carrier: Winkler springs, normal k_n = M / h (M the film's constrained modulus
E (1 - nu) / ((1 + nu)(1 - 2 nu)): a film much wider than thick cannot spread) and
tangential k_t = G / h per unit area. Each beam is replaced by what its root hands the frame
under a unit force on its post: on the frame's edge face under the beam, a uniform shear of
1 N down and the bending stress M (z - z_c) / I of the moment M = L x 1 N (Euler-Bernoulli's
root section). Triquadratic hexahedra (scikit-fem ``ElementHex2``), node planes at every
beam's and resistor's edges, one factorisation (SuperLU) per mesh for every post's load
(four meshes with the error estimate's). Each
resistor reads pi_l P sigma_l + pi_t P sigma_t on the die's top face (Smith's coefficients
turned along and across its legs, :class:`tactcad.vocabulary.crystal.PiezoCoefficients`;
P(N, T) of its implant), averaged over its footprint; a beam resistor's run onto the frame
is weighted by its share of the resistor's squares.

The diagonal is each unit's own reading, its beam resistor's bending response as the
read-out states it (:meth:`tactcad.products.silicon_die.mechanics.piezoresistor.PiezoCantilever.
resistance_change_per_N`); the model gives the rest. crosstalk_rel is the largest
|S_ij / S_ii| (i != j): unit i's reading under a force on post j over its reading under its
own.

The film is the plan's :attr:`~tactcad.products.silicon_die.design.mems_die.DiePlan.attach`: the lab's
``[attach]`` table (its data sheet's modulus, Poisson's ratio and bond line), else
:data:`~tactcad.products.silicon_die.design.mems_die.DEFAULT_DIE_ATTACH` (an assumption).

Error estimate: the change of crosstalk_rel on a mesh with half the handle's layers, plus
that mesh's largest change when the attach's modulus is divided and multiplied by
:data:`ATTACH_MODULUS_SPAN` (assumed: the film's modulus is then the least known input, a
silver-filled epoxy's is a few GPa and moves with its cure and filler; on the example die
halving it moves crosstalk_rel +67 %, doubling it -60 %) or :data:`STATED_MODULUS_SPAN`
(stated by the lab).

Units: mm, N, MPa inside the solver; um for the plan's layout; readings 1/N.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

#: The die's one crosstalk level (``tactcad crosstalk --model`` on a die's design), and what
#: it costs: its 3D FE through the handle and the die attach.
CROSSTALK_LEVEL, CROSSTALK_COST = "attach-fem3d", ("about a minute and a half for 5 "
                                                  "columns, longer with more columns")

#: An assumed attach's modulus is taken this factor either way for the error estimate.
ATTACH_MODULUS_SPAN = 2.0
#: A data sheet's modulus is taken this factor either way (assumption: a cured adhesive's
#: modulus moves by about a quarter with its cure schedule, bond line voids and the
#: temperature between 20 and 40 C, where a data sheet states one figure).
STATED_MODULUS_SPAN = 1.25
#: In the die's plane each element edge is at most this many times its neighbour's, from
#: the finest at every beam's, resistor's and window's edge (:func:`graded_planes`).
GROWTH = 1.5
#: The mesh: its finest and largest element edge in the die's plane (um) and its elements
#: through the handle (one through the device layer). On the example die, halving the
#: finest edge moved crosstalk_rel 3 %, a third handle layer 2 %, a largest edge of 250 um
#: nothing; one handle layer instead of two (the error's coarser mesh) 9 %.
MESH = (80.0, 400.0, 2)
#: The largest mesh (degrees of freedom, :func:`mesh_dofs`) a run takes: a 10-column die in
#: the 10 mm jaw's pocket (273 000) takes about 5 GB and 4 minutes on two cores.
MAX_DOFS = 300_000


@dataclass(frozen=True)
class DieCrosstalk:
    """The die's crosstalk at one level.

    Attributes:
        beams: the beams' numbers, the order of the matrix's rows and columns.
        reading_per_N: S (n x n, 1/N): unit i's half-bridge reading (the beam resistor's
            relative change less its reference's) per newton on post j.
        crosstalk_rel: the largest |S_ij / S_ii|, i != j; worst: that (i, j) as beam
            numbers.
        error_estimate_rel: the mesh's change plus the attach modulus's, relative to
            crosstalk_rel.
        dofs: the finer mesh's degrees of freedom. seconds: wall time.
        basis: the model in a sentence.
    """

    model: str
    beams: tuple[int, ...]
    reading_per_N: np.ndarray
    crosstalk_rel: float
    worst: tuple[int, int]
    error_estimate_rel: float
    dofs: int
    seconds: float
    basis: str

    def as_json(self) -> dict:
        return {"model": self.model, "beams": list(self.beams),
                "reading_per_N": self.reading_per_N.tolist(),
                "crosstalk_rel": self.crosstalk_rel,
                "worst": {"beam": self.worst[0], "loaded_post": self.worst[1]},
                "error_estimate_rel": self.error_estimate_rel, "dofs": self.dofs,
                "cost_s": self.seconds, "basis": self.basis}


@dataclass(frozen=True)
class Footprint:
    """A resistor's footprint on the die's top face (um) and its weight in its unit's
    reading: +share for the beam resistor's run, -1 for the reference."""

    beam_index: int
    x0: float
    y0: float
    x1: float
    y1: float
    weight: float


def attach_springs_N_per_mm3(modulus_MPa: float, poisson: float,
                             thickness_mm: float) -> tuple[float, float]:
    """A thin bonded film's stiffness per unit area (N/mm^3): (normal, tangential) =
    (E (1 - nu) / ((1 + nu)(1 - 2 nu)) / h, E / (2 (1 + nu)) / h).

    Raises:
        ValueError: a modulus or thickness not > 0, nu outside 0 ... 0.5.
    """
    if not (math.isfinite(modulus_MPa) and modulus_MPa > 0):
        raise ValueError(f"modulus_MPa = {modulus_MPa!r}: > 0")
    if not (math.isfinite(thickness_mm) and thickness_mm > 0):
        raise ValueError(f"thickness_mm = {thickness_mm!r}: > 0")
    if not 0.0 <= poisson < 0.5:
        raise ValueError(f"poisson = {poisson!r}: 0 ... 0.5")
    constrained = modulus_MPa * (1 - poisson) / ((1 + poisson) * (1 - 2 * poisson))
    return constrained / thickness_mm, modulus_MPa / (2 * (1 + poisson)) / thickness_mm


def graded_planes(lo: float, hi: float, cuts, finest: float, coarsest: float,
                  growth: float = GROWTH) -> np.ndarray:
    """Node planes from ``lo`` to ``hi`` through every cut inside: gaps of ``finest`` at
    each cut, growing by about ``growth`` per gap away from it, at most ``coarsest``
    (each interval between cuts marched from its nearer end and stretched to fit).

    Raises:
        ValueError: ``finest`` not in (0, coarsest], ``growth`` not > 1.
    """
    if not (0 < finest <= coarsest and growth > 1):
        raise ValueError(f"finest {finest!r}, coarsest {coarsest!r}, growth {growth!r}: "
                         "0 < finest <= coarsest, growth > 1")
    edges = sorted({lo, hi, *[c for c in cuts if lo < c < hi]})
    out = [lo]
    for a, b in zip(edges, edges[1:]):
        x, steps = a, []
        while x < b:
            gap = min(coarsest, finest + (growth - 1) * min(x - a, b - x))
            steps.append(gap)
            x += gap
        cumulative = np.cumsum(steps) * (b - a) / sum(steps)
        out += list(a + cumulative)
        out[-1] = b
    return np.array(out)


def resistor_footprints(plan) -> list[Footprint]:
    """Every unit's resistors where they lie on the frame (um): the beam resistor's run to
    its contacts (weighted by the run's share of its squares) and the on-die reference
    resistor (weight -1: it is the half bridge's other arm)."""
    from tactcad.products.silicon_die.design import mems_die as md
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_squares

    half = md.LEG_GAP_UM / 2 + md.LEG_UM
    squares = die_squares(plan)
    run_share = (2 * md.RESISTOR_RUN_UM / md.LEG_UM) / squares["total"]
    v0 = md.reference_resistor_v0_um(plan)
    out = []
    for i, b in enumerate(plan.beams):
        y0, y1 = _across_root(b, -md.RESISTOR_RUN_UM, 0.0)
        out.append(Footprint(i, b.x_um - half, y0, b.x_um + half, y1, run_share))
        y0, y1 = _across_root(b, v0 - md.RESISTOR_RUN_UM, v0 + plan.reference_resistor_length_um)
        xr = b.x_um + md.REFERENCE_AXIS_UM
        out.append(Footprint(i, xr - half, y0, xr + half, y1, -1.0))
    return out


def _across_root(beam, v_lo: float, v_hi: float) -> tuple[float, float]:
    """The die's y span (low, high; um) of beam-local v_lo ... v_hi from its root line (v > 0
    along the beam, v < 0 into the frame)."""
    a, b = (beam.y_root_um + beam.direction * v for v in (v_lo, v_hi))
    return min(a, b), max(a, b)


def _cuts(plan, footprints) -> tuple[list[float], list[float]]:
    """The node planes every mesh of the die passes through (um): the window's, every
    beam's and every resistor footprint's edges."""
    x0, y0, x1, y1 = plan.window_um
    xs, ys = [x0, x1], [y0, y1]
    for b in plan.beams:
        xs += [b.x_um - b.width_um / 2, b.x_um + b.width_um / 2]
    for f in footprints:
        xs += [f.x0, f.x1]
        ys += [f.y0, f.y1]
    return xs, ys


def _mesh(plan, sizes: tuple[float, float, int], footprints):
    """The die's block (mm), the device layer cut away over the window; ``sizes``: the
    finest and largest edge in the plane (um) and the elements through the handle."""
    from skfem import MeshHex

    x0, y0, x1, y1 = plan.window_um
    xs, ys = _cuts(plan, footprints)
    t = plan.stack.device_um
    h = plan.stack.total_um
    mm = 1e-3
    finest, largest, handle_layers = sizes
    mesh = MeshHex.init_tensor(graded_planes(0.0, plan.die_length_um, xs, finest, largest) * mm,
                               graded_planes(0.0, plan.die_width_um, ys, finest, largest) * mm,
                               np.concatenate([np.linspace(0.0, h - t, handle_layers + 1),
                                               [h]]) * mm)
    mid = mesh.p[:, mesh.t].mean(axis=1)
    window = ((mid[2] > (h - t) * mm) & (mid[0] > x0 * mm) & (mid[0] < x1 * mm)
              & (mid[1] > y0 * mm) & (mid[1] < y1 * mm))
    return mesh.remove_elements(np.nonzero(window)[0])


def strains_on_springs(mesh, c: np.ndarray, springs_N_per_mm3: tuple[float, float],
                       loads, windows) -> tuple[np.ndarray, int]:
    """A solid on a Winkler bed: each load's mean strain over each window of its top face.

    One scalar basis (triquadratic hexahedra) carries the three displacement components,
    interleaved (3 s + a, as :func:`~tactcad.products.silicon_die.mechanics.die_fem3d.assemble_anisotropic`
    numbers them); K is factorised once (SuperLU, minimum degree on its symmetric pattern:
    a tenth of COLAMD's fill) for every load.

    Args:
        mesh: a ``skfem.MeshHex`` (mm), its bottom face at z = 0 on the bed, its top face at
            its largest z.
        c: the stiffness tensor C_ijkl (3, 3, 3, 3), MPa, in the mesh's axes.
        springs_N_per_mm3: the bed's stiffness per unit area (normal, tangential), N/mm^3.
        loads: (facets, traction) pairs: boundary facets and a function of the points x
            (3, ...) giving the traction (3, ...) on them (MPa).
        windows: rectangles (x0, y0, x1, y1) of the top face (mm), each on node planes.

    Returns:
        (strains (windows, loads, 3, 3), degrees of freedom): each window's mean strain.
    """
    import scipy.sparse as sp
    from skfem import Basis, BilinearForm, ElementHex2, FacetBasis, LinearForm

    from tactcad.products.silicon_die.mechanics.die_fem3d import (HEX_QUADRATURE_ORDER,
                                                                   assemble_anisotropic)
    from tactcad.mechanics.fem.sparse_lu import spd_lu

    # the block's cells are boxes and its loads linear in x: 3 x 3 x 3 Gauss points
    # integrate the stiffness, the bed and the loads exactly (see HEX_QUADRATURE_ORDER)
    order = HEX_QUADRATURE_ORDER
    element = ElementHex2()
    scalar = Basis(mesh, element, intorder=order)
    k_n, k_t = springs_N_per_mm3
    bottom = FacetBasis(mesh, element, facets=mesh.facets_satisfying(
        lambda x: np.isclose(x[2], 0.0), boundaries_only=True), intorder=order)

    @BilinearForm
    def area(u, v, w):
        return u * v

    bed = sp.kron(area.assemble(bottom), sp.diags([k_t, k_t, k_n]))
    lu = spd_lu(assemble_anisotropic(scalar, c) + bed, dofs_per_node=3)
    rhs = np.zeros((3 * scalar.N, len(loads)))
    for j, (facets, traction) in enumerate(loads):
        fb = FacetBasis(mesh, element, facets=facets, intorder=order)
        for a in range(3):
            @LinearForm
            def component(v, p, a=a):
                return traction(p.x)[a] * v

            rhs[a::3, j] = component.assemble(fb)
    u = lu.solve(rhs)
    top_z = float(mesh.p[2].max())
    out = np.zeros((len(windows), len(loads), 3, 3))
    eps_ = 1e-9
    for w_index, (x0, y0, x1, y1) in enumerate(windows):
        fb = FacetBasis(mesh, element, facets=mesh.facets_satisfying(
            lambda x: np.isclose(x[2], top_z) & (x[0] > x0 - eps_) & (x[0] < x1 + eps_)
            & (x[1] > y0 - eps_) & (x[1] < y1 + eps_), boundaries_only=True), intorder=order)
        out[w_index] = mean_strains(fb, u)
    return out, 3 * scalar.N


def mean_strains(fb, u: np.ndarray) -> np.ndarray:
    """Each load's mean strain over the facets of ``fb``, weighted by their area.

    The gradients are summed from the basis functions' at the quadrature points for every
    load and component at once: ``fb.interpolate`` per load and component split the whole
    vector's dofs each time (a sort of every dof: 2400 of them took a quarter of a die's
    crosstalk solve).

    Args:
        fb: a ``skfem.FacetBasis`` of the scalar element (the window's facets).
        u: displacements (3 N, loads), numbered ``3 s + a`` (mm per the loads' units).

    Returns:
        The mean strains, shape (loads, 3, 3) (dimensionless per the loads' units).
    """
    weights = fb.dx / np.sum(fb.dx)
    grads = np.array([fb.basis[i][0].grad for i in range(fb.Nbfun)])  # (i, k, f, q)
    values = u.reshape(-1, 3, u.shape[1])[fb.element_dofs]  # (i, f, a, loads)
    grad = np.einsum("ifal,ikfq->lakfq", values, grads)
    strain = 0.5 * (grad + np.swapaxes(grad, 1, 2))  # (loads, 3, 3, facets, points)
    return np.einsum("lijfq,fq->lij", strain, weights)


def _solve(plan, sizes: tuple[float, float, int], attach_modulus_MPa: float,
           footprints) -> tuple[np.ndarray, int]:
    """The frame's reading F (n x n, 1/N): unit i's frame share per newton on post j; and
    the degrees of freedom (the plan's attach at ``attach_modulus_MPa``)."""
    from tactcad.products.silicon_die.mechanics.die_fem3d import stiffness_tensor
    from tactcad.products.silicon_die.mechanics.piezoresistor import piezoresistance_factor
    from tactcad.vocabulary.crystal import SILICON, SILICON_P_TYPE

    mesh = _mesh(plan, sizes, footprints)
    c = stiffness_tensor(SILICON.in_frame((-1.0, 1.0, 0.0), (1.0, 1.0, 0.0)))
    mm = 1e-3
    t, h = plan.stack.device_um * mm, plan.stack.total_um * mm
    loads = [_root_load(mesh, b, t, h) for b in plan.beams]
    windows = [(f.x0 * mm, f.y0 * mm, f.x1 * mm, f.y1 * mm) for f in footprints]
    springs = attach_springs_N_per_mm3(attach_modulus_MPa, plan.attach.poisson,
                                       plan.attach.thickness_um * mm)
    strains, dofs = strains_on_springs(mesh, c, springs, loads, windows)
    stresses = np.einsum("ijkl,wnkl->wnij", c, strains)
    p_factor = piezoresistance_factor(plan.acceptors_per_cm3)
    along, across = (1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)
    pi_l = SILICON_P_TYPE.longitudinal(along) * 1e-11 * p_factor
    pi_t = SILICON_P_TYPE.transverse(along, across) * 1e-11 * p_factor
    response = (pi_l * stresses[:, :, 1, 1] + pi_t * stresses[:, :, 0, 0]) * 1e6  # MPa -> Pa
    frame = np.zeros((len(plan.beams), len(plan.beams)))
    for f, row in zip(footprints, response):
        frame[f.beam_index] += f.weight * row
    return frame, dofs


def _root_load(mesh, beam, t: float, h: float):
    """What ``beam``'s root hands the frame under 1 N down on its post (mm, MPa): on the
    device layer's edge face under the beam, the shear -1 / (w t) and the bending stress
    M (z - z_c) / I, M = L x 1 N, pulling the top towards the beam."""
    mm = 1e-3
    w, arm = beam.width_um * mm, beam.length_um * mm
    inertia, zc = w * t ** 3 / 12, h - t / 2
    y_root, x_axis = beam.y_root_um * mm, beam.x_um * mm
    facets = mesh.facets_satisfying(
        lambda x: np.isclose(x[1], y_root) & (x[2] > h - t - 1e-9)
        & (np.abs(x[0] - x_axis) < w / 2 + 1e-9), boundaries_only=True)

    def traction(x):
        return np.array([np.zeros_like(x[0]),
                         beam.direction * arm * (x[2] - zc) / inertia,
                         np.full_like(x[0], -1.0 / (w * t))])

    return facets, traction


def mesh_dofs(plan, mesh: tuple[float, float, int] = MESH) -> int:
    """The degrees of freedom of ``plan``'s block on ``mesh`` before the window's elements are
    cut away (an upper bound, from the node planes alone: no mesh is built)."""
    finest, largest, layers = mesh
    xs, ys = _cuts(plan, resistor_footprints(plan))
    nx = len(graded_planes(0.0, plan.die_length_um, xs, finest, largest)) - 1
    ny = len(graded_planes(0.0, plan.die_width_um, ys, finest, largest)) - 1
    return 3 * (2 * nx + 1) * (2 * ny + 1) * (2 * (layers + 1) + 1)


def die_crosstalk(plan, mesh: tuple[float, float, int] = MESH) -> DieCrosstalk:
    """The die's crosstalk through its handle and its attach (module doc).

    Args:
        plan: :class:`tactcad.products.silicon_die.design.mems_die.DiePlan` (its ``attach``: the film).
        mesh: the finest and largest element edge in the die's plane (um) and the
            elements through the handle (even, at least 2: the error's coarser mesh has
            half as many).

    Returns:
        :class:`DieCrosstalk`.

    Raises:
        ValueError: edges not 0 < finest <= largest, handle layers not an even integer
            >= 2, an attach's modulus or thickness not > 0.
    """
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_resistor

    finest, largest, layers = mesh
    if not (math.isfinite(finest) and math.isfinite(largest) and 0 < finest <= largest):
        raise ValueError(f"mesh edges {finest!r}, {largest!r} um: 0 < finest <= largest")
    if not (isinstance(layers, int) and layers >= 2 and layers % 2 == 0):
        raise ValueError(f"handle layers {layers!r}: an even integer, at least 2")
    t0 = time.perf_counter()
    footprints = resistor_footprints(plan)
    own = np.diag([die_resistor(plan, b).resistance_change_per_N() for b in plan.beams])
    attach = plan.attach
    span = STATED_MODULUS_SPAN if attach.stated else ATTACH_MODULUS_SPAN
    frame, dofs = _solve(plan, mesh, attach.modulus_MPa, footprints)
    coarser = (finest, largest, layers // 2)
    at_coarser = [worst_crosstalk(own + _off_diagonal(
        _solve(plan, coarser, attach.modulus_MPa * f, footprints)[0]))[0]
        for f in (1.0, 1 / span, span)]
    reading = own + _off_diagonal(frame)
    rel, worst = worst_crosstalk(reading)
    change = abs(rel - at_coarser[0]) + max(abs(at_coarser[0] - x) for x in at_coarser[1:])
    numbers = tuple(b.number for b in plan.beams)
    return DieCrosstalk(CROSSTALK_LEVEL, numbers, reading, rel,
                        (numbers[worst[0]], numbers[worst[1]]),
                        change / rel if rel > 0 else 0.0, dofs, time.perf_counter() - t0,
                        "the die a silicon block on its die-attach film (Winkler springs: "
                        f"{attach.material}, {attach.thickness_um:g} um, E "
                        f"{attach.modulus_MPa:g} MPa x/ {span:g} in the error, nu "
                        f"{attach.poisson:g}; {attach.source}), "
                        "each beam's root section as its load, each resistor's "
                        "piezoresistive response over its footprint on the frame")


def _off_diagonal(frame: np.ndarray) -> np.ndarray:
    """The frame's readings less each unit's own: a unit's own reading is its beam
    resistor's bending, as the read-out states it."""
    out = frame.copy()
    np.fill_diagonal(out, 0.0)
    return out


def worst_crosstalk(reading: np.ndarray) -> tuple[float, tuple[int, int]]:
    """The largest |S_ij / S_ii|, i != j, and its (i, j) (matrix indices)."""
    ratio = np.abs(reading / np.diag(reading)[:, None])
    np.fill_diagonal(ratio, 0.0)
    i, j = np.unravel_index(int(np.argmax(ratio)), ratio.shape)
    return float(ratio[i, j]), (int(i), int(j))


def crosstalk_in_force(plan, result: DieCrosstalk, resolution_N: dict[str, float]) -> dict:
    """The worst crosstalk in newtons: over every pair, the force unit i reads when post j
    carries the most it carries in use (:meth:`~tactcad.products.silicon_die.design.mems_die.DiePlan.
    rated_force_N`), S_ij F_j / S_ii, against unit i's force resolution.

    Args:
        plan: the die's plan; result: its :class:`DieCrosstalk`.
        resolution_N: each row's force resolution (N) by role ("reference",
            "measuring"; :func:`tactcad.products.silicon_die.mechanics.piezoresistor.die_readout`'s rows).

    Returns:
        ``{"loaded_beam", "beam", "rated_force_N", "crosstalk_force_N",
        "force_resolution_N", "force_resolution_steps"}`` of the pair with the most steps.
    """
    s = result.reading_per_N
    best = None
    for i, bi in enumerate(plan.beams):
        for j, bj in enumerate(plan.beams):
            if i == j:
                continue
            force = abs(s[i, j] / s[i, i]) * plan.rated_force_N(bj)
            steps = force / resolution_N[bi.role]
            if best is None or steps > best["force_resolution_steps"]:
                best = {"loaded_beam": bj.number, "beam": bi.number,
                        "rated_force_N": plan.rated_force_N(bj), "crosstalk_force_N": force,
                        "force_resolution_N": resolution_N[bi.role],
                        "force_resolution_steps": steps}
    return best
