"""The die's beams in motion and checked by a finite-element model of another kind.

Closed form (:func:`first_resonance_Hz`): each cantilever with the post on its free end as
a point mass M, Rayleigh's estimate f = (1/2 pi) sqrt(K / (33/140 m + M)) with m the beam's
mass from the root to the post's centre and M the post plus the beam beyond that centre;
checked by the exact Euler-Bernoulli frequency equation of a cantilever carrying a tip
mass (:func:`exact_first_resonance_Hz`: 1 + cos l cosh l + l (M/m)(cos l sinh l -
sin l cosh l) = 0; Blevins, *Formulas for Natural Frequency and Mode Shape*, 1979,
table 8-1 case 4 (the beam with a tip mass), whose Rayleigh form is the closed form's).
K is the die's closed form on the frame (the root's give and shear,
:func:`tactcad.products.silicon_die.design.mems_die.beam_stiffness_N_per_mm`); the exact equation takes the
uniform beam of length L with that K (EI = K L^3 / 3). Against fem3d on the frame Rayleigh
reads the example's f1 4.4 % (reference) and 2 % (measuring) high: the lumped post leaves
out its rotary inertia, and the frame's give is not a massless extra length.

Finite elements (:func:`calculix_beam_check`): the beam as a brick of C3D8I hexahedra
(incompatible modes: bending without shear locking) in CalculiX, with silicon's full
anisotropic stiffness in the beam's frame (``*ELASTIC, TYPE=ANISO``: <110> along the beam
on a (100) wafer, :meth:`tactcad.vocabulary.crystal.CubicElasticity.in_frame`), the root
face fixed or the beam run into its frame block (:func:`beam_on_frame`: the die as made,
held at the handle's underside), a unit force spread over the post centre's section for K
and ``*FREQUENCY`` with the post's mass on its footprint's nodes for f1. Clamped, its K and
f1 against the clamped closed form's are that form's error from shear, the width's
anticlastic stiffening (w/t of a few) and the anisotropic Poisson coupling, none of which
K = E w t^3 / (4 L^3) carries. On its frame they add the frame's compliance at the root:
the frame turns and gives under the root's moment and shear (on the example die K_r 15 %
and K_m 7 % below the clamped beam's), which the closed form carries as extra length
behind the root (:func:`tactcad.products.silicon_die.design.mems_die.root_extension_um`).

Units: um for the die, mm, N, MPa, tonne/mm^3 and s inside CalculiX, Hz.
"""

from __future__ import annotations

import math
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

#: Single-crystal silicon's density (kg/m^3): 2329 (Hull, *Properties of Crystalline
#: Silicon*, INSPEC/IEE 1999, ch. 1).
SILICON_DENSITY_KG_M3 = 2329.0
#: The posts' density (kg/m^3): SU-8 epoxy, 1190 (MicroChem, *SU-8 2000 Permanent Epoxy
#: Negative Photoresist*, processing guidelines, physical properties), the traveller's
#: post material (an assumption: a plated post is heavier).
POST_DENSITY_KG_M3 = 1190.0
#: Rayleigh's effective fraction of a cantilever's mass at its tip (33/140).
RAYLEIGH_FRACTION = 33.0 / 140.0
#: The closed form's error estimate of a row's first resonance (relative): against the
#: die's fem3d level on the frame Rayleigh reads the example die's f1 4.3 % (reference) and
#: 2.0 % (measuring) high (the post lumped without its rotary inertia, the frame's give a
#: massless extra length), with the closed form's K within 0.5 % of fem3d's there; a K off
#: by its stated 2 % moves f1 by 1 % more. Measured on the example die only: ``tactcad modal
#: --model fem3d`` solves a die's own.
CLOSED_FORM_F1_ERROR_REL = 0.05
#: The frame block a beam's root runs into, in the FE models of one beam: it reaches this
#: many device-layer thicknesses behind the root and beside the beam (the root's stresses
#: have decayed to a few per cent there; 7.5 against 15 moves K by less than 0.1 %), and
#: down through the buried oxide and the handle to the die attach, where it is held.
FRAME_MARGIN_OVER_T = 7.5
#: The frame's element edges grow by this factor per element away from the root.
FRAME_GROWTH = 1.5


def graded_from(start: float, stop: float, finest: float, cuts=(),
                growth: float = FRAME_GROWTH) -> np.ndarray:
    """Node planes from ``start`` to ``stop`` (either way), the first gap ``finest`` and
    each next ``growth`` times the last, through every cut between (a last gap under a third
    of its due merged into the one before)."""
    sign = 1.0 if stop >= start else -1.0
    span = abs(stop - start)
    inner = sorted(abs(c - start) for c in cuts if 0 < abs(c - start) < span
                   and (c - start) * sign > 0)
    out, x, gap = [0.0], 0.0, finest
    while x < span - 1e-12:
        nxt = min(x + gap, span)
        nxt = next((c for c in inner if x + 1e-12 < c < nxt - 1e-12), nxt)
        if span - nxt < gap * growth / 3:
            nxt = span
        out.append(nxt)
        x, gap = nxt, gap * growth
    return start + sign * np.array(out)


@dataclass(frozen=True)
class BeamOnFrame:
    """A beam and the frame block around its root, as node planes (mm; x along the beam
    from its root, y across it from its axis, z up from the device layer's underside) and
    which cells are solid.

    Attributes:
        xs, ys, zs: the planes. cavity_mm: the cavity's depth under the beam (its floor, the
            handle, is solid below it). width_mm, thick_mm, handle_mm: the beam's width and
            thickness and the buried oxide and handle under the frame (held at its bottom).
    """

    xs: np.ndarray
    ys: np.ndarray
    zs: np.ndarray
    width_mm: float
    thick_mm: float
    cavity_mm: float
    handle_mm: float

    def solid(self, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Whether points (cell centres) lie in the die: the frame behind the root, the
        handle under the cavity, the beam."""
        beam = (x > 0) & (np.abs(y) < self.width_mm / 2) & (z > 0)
        return (x < 0) | (z < -self.cavity_mm) | beam


def beam_on_frame(plan, beam, xs: np.ndarray, ys: np.ndarray, zs: np.ndarray) -> BeamOnFrame:
    """The beam's own planes ``xs`` (root 0 to its end), ``ys`` (across its width) and
    ``zs`` (its thickness from 0) carried into the frame block (:data:`FRAME_MARGIN_OVER_T`,
    graded from the beam's finest edge by :data:`FRAME_GROWTH`), with a plane at the
    cavity's floor (mm)."""
    w, t = beam.width_um * 1e-3, beam.thickness_um * 1e-3
    cavity = plan.cavity_depths_um[0 if beam.role == "reference" else 1] * 1e-3
    handle = (plan.stack.box_um + plan.stack.handle_um) * 1e-3
    margin = FRAME_MARGIN_OVER_T * t
    finest_x, finest_y, finest_z = (float(np.diff(v).min()) for v in (xs, ys, zs))
    behind = graded_from(0.0, -margin, finest_x)[::-1]
    side = graded_from(w / 2, w / 2 + margin, finest_y)
    under = graded_from(0.0, -handle, finest_z, cuts=(-cavity,))[::-1]
    return BeamOnFrame(np.concatenate([behind[:-1], xs]),
                       np.concatenate([-side[::-1], ys[1:-1], side]),
                       np.concatenate([under[:-1], zs]), w, t, cavity, handle)


@dataclass(frozen=True)
class BeamModes:
    """One beam's first resonance (Hz) by Rayleigh and by the exact frequency equation,
    and the masses they use (kg)."""

    role: str
    rayleigh_Hz: float
    exact_Hz: float
    beam_mass_kg: float
    tip_mass_kg: float

    @property
    def rayleigh_error_rel(self) -> float:
        return self.rayleigh_Hz / self.exact_Hz - 1.0


def _masses_kg(plan, beam) -> tuple[float, float]:
    """(the beam's mass root to post centre, the post's plus the beam's beyond it) (kg)."""
    um3 = 1e-18  # m^3 per um^3
    m = SILICON_DENSITY_KG_M3 * beam.length_um * beam.width_um * beam.thickness_um * um3
    overhang = SILICON_DENSITY_KG_M3 * plan.post_um / 2 * beam.width_um * beam.thickness_um * um3
    post = POST_DENSITY_KG_M3 * plan.post_um ** 2 * plan.post_height_um * um3
    return m, post + overhang


def closed_form_k_N_per_mm(plan, beam, frame: bool = True) -> float:
    """The closed form's K of ``beam`` (N/mm): on its frame, the plan's (the root's give as
    extra length, :func:`tactcad.products.silicon_die.design.mems_die.beam_stiffness_N_per_mm`), or clamped at
    its root (E w t^3 / (4 L^3), the textbook cantilever an FE model with a fixed root
    face is)."""
    from tactcad.products.silicon_die.design.mems_die import clamped_beam_stiffness_N_per_mm

    if frame:
        return plan.k_r_N_per_mm if beam.role == "reference" else plan.k_m_N_per_mm
    return float(clamped_beam_stiffness_N_per_mm(plan.youngs_modulus_MPa, beam.width_um,
                                                 beam.thickness_um, beam.length_um))


def _k_N_per_m(plan, beam) -> float:
    return closed_form_k_N_per_mm(plan, beam) * 1e3


def first_resonance_Hz(plan, beam, frame: bool = True) -> float:
    """Rayleigh's first resonance of ``beam`` with its post (Hz), see the module doc: with
    its K on its frame or, ``frame`` False, clamped at its root."""
    m, tip = _masses_kg(plan, beam)
    k = closed_form_k_N_per_mm(plan, beam, frame) * 1e3
    return math.sqrt(k / (RAYLEIGH_FRACTION * m + tip)) / (2 * math.pi)


def exact_first_resonance_Hz(plan, beam) -> float:
    """The first root of the Euler-Bernoulli cantilever with a tip mass (Hz), the beam's
    EI from its K (EI = K L^3 / 3)."""
    from scipy.optimize import brentq

    m, tip = _masses_kg(plan, beam)
    ratio = tip / m

    def f(lam: float) -> float:
        return (1 + math.cos(lam) * math.cosh(lam)
                + lam * ratio * (math.cos(lam) * math.sinh(lam) - math.sin(lam) * math.cosh(lam)))

    lam = brentq(f, 1e-6, 1.8751041)  # the tip mass lowers it below the bare beam's root
    length_m = beam.length_um * 1e-6
    ei = _k_N_per_m(plan, beam) * length_m ** 3 / 3
    return lam ** 2 * math.sqrt(ei / (m / length_m * length_m ** 4)) / (2 * math.pi)


def beam_modes(plan, beam) -> BeamModes:
    """``beam``'s first resonance by Rayleigh and by the exact frequency equation, with its
    masses (Hz, kg)."""
    m, tip = _masses_kg(plan, beam)
    return BeamModes(beam.role, first_resonance_Hz(plan, beam),
                     exact_first_resonance_Hz(plan, beam), m, tip)


def die_modes(plan) -> dict[str, BeamModes]:
    """Each row's first resonance (the reference's and the measuring beam's), by role."""
    return {beam.role: beam_modes(plan, beam) for beam in plan.beams[:: plan.columns]}


# --- the CalculiX check ------------------------------------------------------------------
#: Elements along, across and through the beam (C3D8I).
FE_DIVISIONS = (48, 6, 4)


@dataclass(frozen=True)
class FeCheck:
    """One beam in CalculiX against the closed form: K (N/mm) and f1 (Hz) each way."""

    role: str
    k_fe_N_per_mm: float
    k_closed_N_per_mm: float
    f1_fe_Hz: float
    f1_closed_Hz: float

    @property
    def k_error_rel(self) -> float:
        """The closed form's K over the FE model's, minus 1."""
        return self.k_closed_N_per_mm / self.k_fe_N_per_mm - 1.0

    @property
    def f1_error_rel(self) -> float:
        return self.f1_closed_Hz / self.f1_fe_Hz - 1.0

    def as_json(self) -> dict:
        """The check as ``tactcad die --fe-check --json`` writes it: K (N/mm) and the first
        resonance (Hz) by CalculiX and by the closed form, and the closed form's error
        against CalculiX of each (relative, a measured difference, not an estimate of
        CalculiX's own error): the first resonance under ``modal --json``'s name,
        ``first_Hz``, each closed form's error as the fem3d row names it
        (``K_closed_form_error_rel``, ``first_Hz_closed_form_error_rel``; the old names are
        the die command's to add, :data:`FE_CHECK_RENAMED`)."""
        return {"role": self.role, "K_fe_N_per_mm": self.k_fe_N_per_mm,
                "K_closed_form_N_per_mm": self.k_closed_N_per_mm,
                "K_closed_form_error_rel": self.k_error_rel, "fe_first_Hz": self.f1_fe_Hz,
                "closed_form_first_Hz": self.f1_closed_Hz,
                "first_Hz_closed_form_error_rel": self.f1_error_rel}


#: The keys of a die's CalculiX check (``tactcad die --fe-check --json``) renamed, old ->
#: new, as :data:`tactcad.products.silicon_die.mechanics.die_fem3d.FEM3D_RENAMED`: the old
#: keys are still written beside the new ones and listed in the row's ``deprecated_keys``.
#: ``K_error_rel`` was the closed form's K against CalculiX's, where a fem3d row's
#: ``K_error_rel`` is fem3d's own error estimate: it is ``K_closed_form_error_rel``, as the
#: fem3d row names the closed form's.
FE_CHECK_RENAMED = {"f1_fe_Hz": "fe_first_Hz", "f1_closed_form_Hz": "closed_form_first_Hz",
                    "f1_error_rel": "first_Hz_closed_form_error_rel",
                    "K_error_rel": "K_closed_form_error_rel"}


def _brick(length: float, width: float, thick: float, div: tuple[int, int, int],
           load_x: float):
    """Nodes (n, 3) mm and C3D8 connectivity (1-based) of a structured brick: x along the
    beam from the root (x = 0), a plane of nodes at ``load_x`` (the post's centre, where
    the force acts), y across its width (centred), z through its thickness."""
    nx, ny, nz = div
    xs, ys, zs = _brick_planes(length, width, thick, div, load_x)
    idx = lambda i, j, k: 1 + i + (nx + 1) * (j + (ny + 1) * k)  # noqa: E731
    nodes = np.array([(x, y, z) for z in zs for y in ys for x in xs])
    elems = [(idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
              idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1),
              idx(i, j + 1, k + 1))
             for k in range(nz) for j in range(ny) for i in range(nx)]
    return nodes, np.array(elems)


def _brick_planes(length: float, width: float, thick: float, div: tuple[int, int, int],
                  load_x: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The node planes of :func:`_brick` (mm): x evenly on each side of ``load_x``, y and
    z evenly."""
    nx, ny, nz = div
    n1 = max(1, min(nx - 1, round(nx * load_x / length)))
    xs = np.concatenate([np.linspace(0, load_x, n1 + 1),
                         np.linspace(load_x, length, nx - n1 + 1)[1:]])
    return xs, np.linspace(-width / 2, width / 2, ny + 1), np.linspace(0, thick, nz + 1)


def _structured(xs: np.ndarray, ys: np.ndarray, zs: np.ndarray, solid) -> tuple:
    """Nodes (n, 3) and C3D8 connectivity (1-based) of the cells of the grid ``xs`` x ``ys``
    x ``zs`` whose centres are ``solid(x, y, z)``; only their nodes, renumbered."""
    nx, ny = len(xs) - 1, len(ys) - 1
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(len(zs) - 1), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    keep = solid((xs[i] + xs[i + 1]) / 2, (ys[j] + ys[j + 1]) / 2, (zs[k] + zs[k + 1]) / 2)
    i, j, k = i[keep], j[keep], k[keep]

    def idx(a, b, c):
        return a + (nx + 1) * (b + (ny + 1) * c)

    corners = np.stack([idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
                        idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1),
                        idx(i, j + 1, k + 1)], axis=1)
    used, elems = np.unique(corners, return_inverse=True)
    a = used % (nx + 1)
    b = (used // (nx + 1)) % (ny + 1)
    c = used // ((nx + 1) * (ny + 1))
    nodes = np.column_stack([xs[a], ys[b], zs[c]])
    return nodes, elems.reshape(corners.shape) + 1


def _section_weights(nodes: np.ndarray, x: float,
                     on_beam: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(node ids, consistent weights summing to 1) of the cross-section at ``x``: each
    cell's share split to its four corners (``on_beam``: the nodes that may be in it)."""
    at = np.isclose(nodes[:, 0], x)
    on = np.flatnonzero(at if on_beam is None else at & on_beam)
    ys, zs = np.unique(nodes[on, 1]), np.unique(nodes[on, 2])
    wy = np.diff(ys)
    wz = np.diff(zs)
    cy = np.zeros(len(ys))
    cz = np.zeros(len(zs))
    cy[:-1] += wy / 2
    cy[1:] += wy / 2
    cz[:-1] += wz / 2
    cz[1:] += wz / 2
    w = np.array([cy[np.searchsorted(ys, nodes[n, 1])] * cz[np.searchsorted(zs, nodes[n, 2])]
                  for n in on])
    return on + 1, w / w.sum()


def _deck(nodes, elems, stiffness_MPa: np.ndarray, density_t_mm3: float, step: str,
          held: np.ndarray | None = None) -> str:
    c = stiffness_MPa
    voigt = {(1, 1): 0, (2, 2): 1, (3, 3): 2, (2, 3): 3, (1, 3): 4, (1, 2): 5}
    order = ((1, 1, 1, 1), (1, 1, 2, 2), (2, 2, 2, 2), (1, 1, 3, 3), (2, 2, 3, 3), (3, 3, 3, 3),
             (1, 1, 1, 2), (2, 2, 1, 2), (3, 3, 1, 2), (1, 2, 1, 2), (1, 1, 1, 3), (2, 2, 1, 3),
             (3, 3, 1, 3), (1, 2, 1, 3), (1, 3, 1, 3), (1, 1, 2, 3), (2, 2, 2, 3), (3, 3, 2, 3),
             (1, 2, 2, 3), (1, 3, 2, 3), (2, 3, 2, 3))
    values = [c[voigt[(i, j)], voigt[(k, l)]] for i, j, k, l in order]
    lines = ["*NODE"] + [f"{n + 1}, {x:.9g}, {y:.9g}, {z:.9g}" for n, (x, y, z) in enumerate(nodes)]
    lines += ["*ELEMENT, TYPE=C3D8I, ELSET=BEAM"]
    lines += [f"{e + 1}, " + ", ".join(str(v) for v in conn) for e, conn in enumerate(elems)]
    root = (np.flatnonzero(np.isclose(nodes[:, 0], 0.0)) if held is None else held) + 1
    lines += ["*NSET, NSET=ROOT"] + [", ".join(str(v) for v in root[i:i + 12])
                                     for i in range(0, len(root), 12)]
    lines += ["*MATERIAL, NAME=SI", "*ELASTIC, TYPE=ANISO"]
    lines += [", ".join(f"{v:.9g}" for v in values[i:i + 8]) for i in range(0, 21, 8)]
    lines += ["*DENSITY", f"{density_t_mm3:.9g}", "*SOLID SECTION, ELSET=BEAM, MATERIAL=SI",
              "*BOUNDARY", "ROOT, 1, 3, 0.0"]
    return "\n".join(lines) + "\n" + step


def _run(deck: str, folder: Path, name: str) -> str:
    (folder / f"{name}.inp").write_text(deck, encoding="ascii")
    subprocess.run(["ccx", name], cwd=folder, capture_output=True, text=True, timeout=600,
                   check=True)
    return (folder / f"{name}.dat").read_text(encoding="ascii", errors="replace")


def _first_frequency_Hz(dat: str) -> float:
    """The first mode's frequency (cycles/time) of a CalculiX .dat's eigenvalue output."""
    lines = dat.splitlines()
    start = next(i for i, line in enumerate(lines) if "E I G E N V A L U E" in line
                 and "O U T P U T" in line)
    for line in lines[start:]:
        parts = line.split()
        if len(parts) >= 4 and parts[0] == "1":
            return float(parts[3])
    raise ValueError("no first mode in the CalculiX output")


def calculix_beam_check(plan, beam, divisions: tuple[int, int, int] = FE_DIVISIONS,
                        frame: bool = True) -> FeCheck:
    """``beam`` of ``plan`` in CalculiX (see the module doc): K from the post centre's
    section's mean deflection under a unit force spread over it, f1 with the post's mass on
    the nodes of its footprint on the beam's top face; ``divisions``: elements along,
    across, through the beam; ``frame``: the beam on its frame block
    (:func:`beam_on_frame`, held at the handle's underside), else clamped at its root.

    Raises:
        RuntimeError: no ``ccx`` on the PATH (install ``calculix-ccx``).
        subprocess.CalledProcessError: CalculiX failed.
    """
    from tactcad.vocabulary.crystal import SILICON

    if shutil.which("ccx") is None:
        raise RuntimeError("the FE check needs CalculiX's ccx on the PATH (apt-get install "
                           "calculix-ccx)")
    length = (beam.length_um + plan.post_um / 2) * 1e-3  # the beam runs to the post's end
    width, thick = beam.width_um * 1e-3, beam.thickness_um * 1e-3
    at = beam.length_um * 1e-3  # the post's centre, where the force acts
    held, on_beam = None, None
    if frame:
        block = beam_on_frame(plan, beam, *_brick_planes(length, width, thick, divisions, at))
        nodes, elems = _structured(block.xs, block.ys, block.zs, block.solid)
        held = np.flatnonzero(np.isclose(nodes[:, 2], -block.handle_mm))
        on_beam = (nodes[:, 2] > -1e-12) & (np.abs(nodes[:, 1]) <= width / 2 + 1e-12)
    else:
        nodes, elems = _brick(length, width, thick, divisions, at)
    # <110> along the beam, <-110> across it, [001] through the thickness
    c = SILICON.in_frame((1.0, 1.0, 0.0), (-1.0, 1.0, 0.0))
    rho = SILICON_DENSITY_KG_M3 * 1e-12  # kg/m^3 -> tonne/mm^3
    with tempfile.TemporaryDirectory(prefix="tactcad-die-fe-") as tmp:
        folder = Path(tmp)
        # the force at the post's centre: a unit force over the nodes of that section
        ids, w = _section_weights(nodes, at, on_beam)
        loads = "\n".join(f"{n}, 3, {-wi:.12g}" for n, wi in zip(ids, w))
        loaded = "*NSET, NSET=LOADED\n" + "\n".join(
            ", ".join(str(n) for n in ids[i:i + 12]) for i in range(0, len(ids), 12))
        static = _run(_deck(nodes, elems, c, rho,
                            loaded + "\n*STEP\n*STATIC\n*CLOAD\n" + loads
                            + "\n*NODE PRINT, NSET=LOADED\nU\n*END STEP\n", held), folder,
                      "static")
        u = _displacements(static)
        k_fe = 1.0 / float(sum(wi * -u[n][2] for n, wi in zip(ids, w)))
        post_kg = POST_DENSITY_KG_M3 * plan.post_um ** 2 * plan.post_height_um * 1e-18
        top = np.flatnonzero(np.isclose(nodes[:, 2], thick)
                             & (np.abs(nodes[:, 0] - at) <= plan.post_um * 1e-3 / 2 + 1e-12)
                             & (np.abs(nodes[:, 1]) <= min(plan.post_um, beam.width_um) * 1e-3 / 2
                                + 1e-12)) + 1
        each = post_kg * 1e-3 / len(top)  # kg -> tonne
        masses = ("*ELEMENT, TYPE=MASS, ELSET=POST\n"
                  + "\n".join(f"{len(elems) + i + 1}, {n}" for i, n in enumerate(top))
                  + f"\n*MASS, ELSET=POST\n{each:.9g}\n")
        modal = _run(_deck(nodes, elems, c, rho, masses + "*STEP\n*FREQUENCY\n1\n*END STEP\n",
                           held), folder, "modal")
        f_fe = _first_frequency_Hz(modal)
    return FeCheck(beam.role, k_fe, closed_form_k_N_per_mm(plan, beam, frame), f_fe,
                   first_resonance_Hz(plan, beam, frame))


def _displacements(dat: str) -> dict[int, tuple[float, float, float]]:
    out = {}
    for line in dat.splitlines():
        parts = line.split()
        if len(parts) == 4:
            try:
                out[int(parts[0])] = tuple(float(v) for v in parts[1:])
            except ValueError:
                continue
    return out
