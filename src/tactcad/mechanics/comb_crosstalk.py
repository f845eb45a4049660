"""Crosstalk of the monolithic comb: a tip force on one element strains its row's other gauges.

What couples the elements. A row's elements are cut from one sheet, each standing on its
post on a common spine (:mod:`tactcad.design.comb_plan`). A tip force on element j bends
its web and hands its post the force and its moment about the post; the post hands them to
the spine, which bends between the fasteners that hold it (two dowel pins in reamed holes,
two screws whose heads clamp it to the spacer and the other row). A neighbour's arm carries
no load whatever its base does (statics of an unloaded cantilever): its web reads the
spine's strain only as far as it reaches up the neighbour's post and along its web, and its
tip moves with the spine's deflection and rotation under its post, carried rigidly. The
stop ledges stay open (each stop gap is wider than the travel a unit force gives) and the
rows meet only through the fasteners, taken as fixed: rows do not couple here.

Levels, declared once in :data:`tactcad.mechanics.crosstalk_ladder.CROSSTALK_LEVELS`
(cheapest first):

* ``comb-beam`` (this module): the spine, of the spine's height and the sheet's
  thickness, as a Timoshenko beam along the row (two-node elements, exact for nodal
  loads; shear factor 5/6), pinned (w = 0) at each fastener's centre. Element j's unit tip
  force reaches it at its post's centre as the force and the moment (x_tip - x_post) x 1 N.
  Gauge i (i != j) reads the spine's top-face strain averaged over its post's base
  (-c theta' with c half the spine's height), times the share that reaches its grid: the
  post's self-equilibrated strain dies out up the post as exp(-K h / w) (h the post's
  height over its ledge, w its width along the row) and along the web from the post's
  front wall as exp(-K (x - x_w) / t) (t the web), averaged over the grid; K = 4.2122, the
  first symmetric Papkovich-Fadle eigenvalue of a strip with free sides (Timoshenko and
  Goodier, Theory of Elasticity, 3rd ed., section 26). The diagonal is each gauge's own
  grid strain at the closed form (:func:`tactcad.mechanics.readout_chain.grid_strain_per_N`,
  as the stack's). Tip i: its own 1 / K_i (closed form) + w(x_i) + (x_tip,i - x_post,i)
  theta(x_i). Error estimate: the spread of crosstalk_rel over the model's least known
  inputs (:data:`BEAM_BOUNDS`): the fasteners pinning the spine at their centres or holding
  it over their spans (a dowel's hole, a screw's head; w = theta = 0 there, which cuts the
  spine into spans that do not couple), and the decay at K or at Saint-Venant's pi (the
  slower, the stack model's). A fastener's hole held at its rim lies between the two: on
  the 10 mm grasper's comb the plane FE's tip matrix lies between them and its
  crosstalk_rel at or below the lowest. The beam is a screen that errs high: there 7.1e-6
  +/- 163 % against the FE's 5.4e-7 +/- 2.7 % (13 x; 21 x on a comb of wider pitch and
  longer posts), inside its stated error, which is relative to its own value as the
  stack's levels' are. ``comb-fem2d`` gives the figure; ``tactcad bench crosstalk`` both.
* ``comb-fem2d`` (:mod:`tactcad.mechanics.comb_fem2d`): the row's whole sheet, its exact
  outline with every notch, post and gauge layer, as a plane-stress solid held at its
  dowel holes' rims and under its screws' heads; two meshes, Richardson.

Units: mm, N, MPa, N/mm, s; strain dimensionless.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from tactcad.design.array_plan import Plan
from tactcad.mechanics.bonded_layer import BondedLayer
from tactcad.mechanics.crosstalk_ladder import CrosstalkInputError, CrosstalkResult, result_of

COMB_BASIS = ("each row's sheet (spine, posts, elements) held at its dowel pins' holes and "
              "under its screws' heads, the spacer and the other row rigid, the stop ledges "
              "open, rows uncoupled")


#: What a caller may change of the plan's comb (a what-if): the spine's modulus over the
#: sheet's, 1 as made (a stiffer spine, 1e6, is near rigid).
CHANGE_RANGES = {"spine_modulus_factor": (1e-2, 1e6)}


@dataclass(frozen=True)
class CombInputs:
    """What the comb's crosstalk levels read from a plan (mm, MPa, N/mm, 1/N).

    Per element (plan order): ``numbers``, ``rows``, ``columns``, ``offsets_mm`` (its
    frame's x in its sheet), ``layers`` (its gauge's glue line and carrier, element frame),
    ``width_factor`` (the plane field's grid line to the grid's area, fem2d's),
    ``stiffness_N_per_mm`` (own K, closed form), ``own_strain_per_N`` (own grid strain,
    closed form). The rows: ``sheets`` (each row's sheet, the plan's, row order). The
    material: ``youngs_modulus_MPa``, ``poisson_ratio``; ``sheet_mm``. The fasteners
    (sheet frame): ``screw_x_mm``, ``dowel_x_mm``, ``fastener_y_mm``,
    ``screw_head_diameter_mm``, ``screw_hole_mm`` (clearance), ``dowel_diameter_mm``.
    """

    numbers: tuple[int, ...]
    rows: tuple[int, ...]
    columns: tuple[int, ...]
    offsets_mm: tuple[float, ...]
    layers: tuple[BondedLayer, ...]
    width_factor: tuple[float, ...]
    stiffness_N_per_mm: tuple[float, ...]
    own_strain_per_N: tuple[float, ...]
    sheets: tuple[Any, ...]
    youngs_modulus_MPa: float
    poisson_ratio: float
    sheet_mm: float
    screw_x_mm: tuple[float, ...]
    dowel_x_mm: tuple[float, ...]
    fastener_y_mm: float
    screw_head_diameter_mm: float
    screw_hole_mm: float
    dowel_diameter_mm: float
    #: the spine's modulus over the sheet's (a what-if: 1 is the comb as made)
    spine_modulus_factor: float = 1.0
    #: the beam level's bounds (its error estimate): the fasteners hold the spine over
    #: their "spans" or pin it at their "centres"; the decay "papkovich" or "saint-venant"
    supports: str = "centres"
    decay: str = "papkovich"

    def row_elements(self, row: int) -> list[int]:
        """Indices (plan order) of ``row``'s elements, in the row's order."""
        return sorted((k for k, r in enumerate(self.rows) if r == row),
                      key=lambda k: self.columns[k])


def comb_inputs(plan: Plan, **changes: Any) -> CombInputs:
    """The plan's comb as its crosstalk levels read it.

    Raises:
        CrosstalkInputError: a change other than :data:`CHANGE_RANGES`' (the comb's
            geometry changes through its design, ``--set``), or out of its range.
        DesignError: the plan is no comb.
    """
    from tactcad.errors import DesignError
    from tactcad.mechanics.bonded_layer import chain_layer
    from tactcad.mechanics.closed_form import estimate_closed_form
    from tactcad.mechanics.gauge_strain import width_strain_factor
    from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain

    for key, value in changes.items():
        if key not in CHANGE_RANGES:
            raise CrosstalkInputError(key, value, "one of " + ", ".join(CHANGE_RANGES))
        lo, hi = CHANGE_RANGES[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value) or not lo <= value <= hi:
            raise CrosstalkInputError(key, value, f"a number in [{lo:g}, {hi:g}]")
    c = plan.comb
    if c is None:
        raise DesignError("array.construction", plan.construction, "monolithic-comb",
                          "the comb's crosstalk reads the comb's sheets")
    chain = readout_chain(plan)
    numbers, rows, cols, offs, layers, width, ks, own = [], [], [], [], [], [], [], []
    for s in plan.slots:
        g = s.geometry
        sheet = c.sheets[s.row]
        numbers.append(s.number)
        rows.append(s.row)
        cols.append(s.column)
        offs.append(sheet.offsets_mm[s.column])
        layers.append(chain_layer(g, chain))
        width.append(width_strain_factor(g.bare(), plan.material, chain.grid_width_mm).factor)
        ks.append(estimate_closed_form(g, plan.material, element=s.number).stiffness_N_per_mm)
        own.append(grid_strain_per_N(g, plan.material, chain, "closed-form")["grid"])
    return CombInputs(
        numbers=tuple(numbers), rows=tuple(rows), columns=tuple(cols), offsets_mm=tuple(offs),
        layers=tuple(layers), width_factor=tuple(width), stiffness_N_per_mm=tuple(ks),
        own_strain_per_N=tuple(own), sheets=tuple(c.sheets),
        youngs_modulus_MPa=plan.material.youngs_modulus_MPa,
        poisson_ratio=plan.material.poisson_ratio, sheet_mm=plan.sheet_thickness_mm,
        screw_x_mm=tuple(c.screw_x_mm), dowel_x_mm=tuple(c.dowel_x_mm),
        fastener_y_mm=c.fastener_y_mm, screw_head_diameter_mm=c.screw.head_diameter_mm,
        screw_hole_mm=c.screw.clearance_hole_mm, dowel_diameter_mm=c.dowel_diameter_mm,
        **{k: float(v) for k, v in changes.items()})


def comb_result(model: str, inputs: CombInputs, S: np.ndarray, C: np.ndarray, error: float,
                t0: float, basis: str = COMB_BASIS) -> CrosstalkResult:
    """The level's :class:`~tactcad.mechanics.crosstalk_ladder.CrosstalkResult`."""
    return result_of(model, inputs.numbers, S, C, error, t0, basis)


# ---------------------------------------------------------------------------
# comb-beam: the spine as a beam on its fasteners
# ---------------------------------------------------------------------------
#: The first symmetric Papkovich-Fadle eigenvalue of a strip with free sides: a
#: self-equilibrated end load on a strip of width w dies out as exp(-K y / w),
#: K = 2 x 2.1061 (Timoshenko and Goodier, Theory of Elasticity, 3rd ed., section 26).
PAPKOVICH_DECAY = 4.2122
#: Saint-Venant's rough rate, exp(-pi y / w) (Timoshenko and Goodier, section 24; the stack
#: model's): the slower bound of the decay.
SAINT_VENANT_DECAY = math.pi


@dataclass(frozen=True)
class SpineLayout:
    """The row's spine as the beam level reads it (sheet frame, mm).

    Per element of the row (row order): ``post_mm`` ((x0, x1) of its post's base on the
    spine), ``post_height_mm`` (its ledge to its top face), ``tip_x_mm`` (its contact face's
    centre), ``hinge_x_mm``, ``web_mm``, ``notch_radius_mm``, ``grid_mm`` ((x0, x1) of its
    grid). The spine: ``length_mm``, ``height_mm``; ``clamps_mm``: the (x0, x1) spans the
    fasteners hold (each dowel's hole, each screw's head).
    """

    post_mm: tuple[tuple[float, float], ...]
    post_height_mm: tuple[float, ...]
    tip_x_mm: tuple[float, ...]
    hinge_x_mm: tuple[float, ...]
    web_mm: tuple[float, ...]
    notch_radius_mm: tuple[float, ...]
    grid_mm: tuple[tuple[float, float], ...]
    length_mm: float
    height_mm: float
    clamps_mm: tuple[tuple[float, float], ...]


def spine_layout(inputs: CombInputs, row: int) -> SpineLayout:
    """``row``'s spine, posts and grids as the beam level reads them."""
    sheet = inputs.sheets[row]
    posts, heights, tips, hinges, webs, radii, grids = [], [], [], [], [], [], []
    for k in inputs.row_elements(row):
        c = inputs.columns[k]
        g, x0 = sheet.elements[c], inputs.offsets_mm[k]
        posts.append((x0, x0 + g.hinge_x_mm - g.notch_radius_mm))
        heights.append(g.base_height_mm - sheet.ledges_mm[c])
        tips.append(x0 + g.tip_centre_x_mm)
        hinges.append(x0 + g.hinge_x_mm)
        webs.append(g.web_thickness_mm)
        radii.append(g.notch_radius_mm)
        lay = inputs.layers[k]
        grids.append((x0 + lay.grid_x0_mm, x0 + lay.grid_x1_mm))
    clamps = [(x - inputs.dowel_diameter_mm / 2, x + inputs.dowel_diameter_mm / 2)
              for x in inputs.dowel_x_mm]
    clamps += [(x - inputs.screw_head_diameter_mm / 2, x + inputs.screw_head_diameter_mm / 2)
               for x in inputs.screw_x_mm]
    return SpineLayout(tuple(posts), tuple(heights), tuple(tips), tuple(hinges), tuple(webs),
                       tuple(radii), tuple(grids), sheet.length_mm, sheet.spine_height_mm,
                       tuple(sorted(clamps)))


def grid_share(lay: SpineLayout, i: int, rate: float) -> float:
    """The share of element ``i``'s spine strain its grid reads: the post's self-equilibrated
    strain dies out up the post, exp(-rate h / w) (h its height, w its width), then along
    the web from the post's front wall, exp(-rate (x - x_w) / t) (t the web), averaged over
    the grid (dimensionless)."""
    x0, x1 = lay.post_mm[i]
    up = math.exp(-rate * lay.post_height_mm[i] / (x1 - x0))
    t = lay.web_mm[i]
    g0, g1 = lay.grid_mm[i]
    a, b = max(g0, x1) - x1, max(g1, x1) - x1  # the grid beyond the post's front wall
    on_post = max(0.0, min(g1, x1) - g0)  # and over the post's top (its strain as it is)
    along = on_post + t / rate * (math.exp(-rate * a / t) - math.exp(-rate * b / t))
    return up * along / (g1 - g0)


def solve_spine(inputs: CombInputs, lay: SpineLayout, shear: bool, held_spans: bool = True
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The row's spine under a unit tip force on each element in turn: per load j (columns)
    and element i (rows) the spine's deflection w and rotation theta at i's post centre
    (mm/N, rad/N) and its top face's strain averaged over i's post base (1/N).

    The spine is a beam along x of the spine's height and the sheet's thickness (the
    Timoshenko beam's two-node element when ``shear``, Euler-Bernoulli otherwise: exact for
    nodal loads), held (w = theta = 0) over every fastener's span; element j's tip force F
    reaches it at its post's centre as F and the moment F (x_tip - x_post).
    """
    import scipy.linalg

    from tactcad.mechanics.stack_crosstalk import SHEAR_FACTOR, _beam_element

    n_el = len(lay.post_mm)
    centres = [(a + b) / 2 for a, b in lay.post_mm]
    xs = {0.0, lay.length_mm, *centres, *((a + c) / 2 for a, c in lay.clamps_mm)}
    for a, b in (*lay.post_mm, *lay.clamps_mm):
        xs |= {a, b}
    z = np.array(sorted(x for x in xs if -1e-9 <= x <= lay.length_mm + 1e-9))
    z = z[np.concatenate([[True], np.diff(z) > 1e-9])]
    n = len(z)
    E = inputs.youngs_modulus_MPa * inputs.spine_modulus_factor
    nu, b, h = inputs.poisson_ratio, inputs.sheet_mm, lay.height_mm
    EI, kGA = E * b * h ** 3 / 12, SHEAR_FACTOR * E / (2 * (1 + nu)) * b * h
    K = np.zeros((2 * n, 2 * n))
    for e in range(n - 1):
        d = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3]
        K[np.ix_(d, d)] += _beam_element(EI, kGA if shear else None, z[e + 1] - z[e])
    if held_spans:  # w = theta = 0 over every fastener's span
        held = {d for k, x in enumerate(z) for d in (2 * k, 2 * k + 1)
                if any(a - 1e-9 <= x <= c + 1e-9 for a, c in lay.clamps_mm)}
    else:  # pinned at each fastener's centre: w = 0 there, theta free
        held = {2 * int(np.argmin(abs(z - (a + c) / 2))) for a, c in lay.clamps_mm}
    free = np.array([d for d in range(2 * n) if d not in held])
    at = [int(np.argmin(abs(z - x))) for x in centres]
    F = np.zeros((2 * n, n_el))
    for j, node in enumerate(at):
        F[2 * node, j] = 1.0
        F[2 * node + 1, j] = lay.tip_x_mm[j] - centres[j]
    U = np.zeros_like(F)
    U[free] = scipy.linalg.solve(K[np.ix_(free, free)], F[free], assume_a="pos")
    w, theta = U[[2 * k for k in at]], U[[2 * k + 1 for k in at]]
    # the top face's strain, -c kappa, averaged over each post's base: the curvature is
    # the rotation's change over the base (mean of theta' = (theta(x1) - theta(x0)) / w)
    strain = np.zeros((n_el, n_el))
    for i, (a, c) in enumerate(lay.post_mm):
        ka, kc = int(np.argmin(abs(z - a))), int(np.argmin(abs(z - c)))
        strain[i] = -(h / 2) * (U[2 * kc + 1] - U[2 * ka + 1]) / (c - a)
    return w, theta, strain


def matrices(inputs: CombInputs) -> tuple[np.ndarray, np.ndarray]:
    """(sensitivity S (1/N), tip compliance C (mm/N)), n x n in the plan's element order,
    at the beam level's ``supports`` and ``decay``."""
    n = len(inputs.numbers)
    S = np.diag(np.array(inputs.own_strain_per_N, float))
    C = np.diag(1.0 / np.array(inputs.stiffness_N_per_mm, float))
    rate = PAPKOVICH_DECAY if inputs.decay == "papkovich" else SAINT_VENANT_DECAY
    for row in sorted(set(inputs.rows)):
        idx = inputs.row_elements(row)
        lay = spine_layout(inputs, row)
        w, theta, strain = solve_spine(inputs, lay, True, inputs.supports == "spans")
        lever = np.array(lay.tip_x_mm) - np.array([(a + b) / 2 for a, b in lay.post_mm])
        share = np.array([grid_share(lay, i, rate) for i in range(len(idx))])
        off = share[:, None] * strain
        np.fill_diagonal(off, 0.0)  # the loaded gauge's own strain is the closed form's
        S[np.ix_(idx, idx)] += off
        C[np.ix_(idx, idx)] += w + lever[:, None] * theta
    return S, C


#: The beam level's bounds: (supports, decay) of each; the first is its own value.
BEAM_BOUNDS = (("centres", "papkovich"), ("centres", "saint-venant"), ("spans", "papkovich"),
               ("spans", "saint-venant"))


def estimate_comb_beam(inputs: CombInputs) -> CrosstalkResult:
    """The spine as a Timoshenko beam on its fasteners (module doc); error estimate: the
    spread of crosstalk_rel over :data:`BEAM_BOUNDS`."""
    from dataclasses import replace

    from tactcad.mechanics.crosstalk_ladder import crosstalk_of

    t0 = time.perf_counter()
    own = replace(inputs, supports=BEAM_BOUNDS[0][0], decay=BEAM_BOUNDS[0][1])
    S, C = matrices(own)
    rel = crosstalk_of(S)[0]
    spread = max((abs(crosstalk_of(matrices(replace(inputs, supports=a, decay=d))[0])[0] - rel)
                  for a, d in BEAM_BOUNDS[1:]), default=0.0)
    return comb_result("comb-beam", inputs, S, C, spread / rel if rel else 0.0, t0,
                       COMB_BASIS + "; the spine a Timoshenko beam pinned at its fasteners, a "
                       "neighbour's gauge reading the spine's strain under its post, dying out "
                       "up the post and along the web (Papkovich-Fadle)")
