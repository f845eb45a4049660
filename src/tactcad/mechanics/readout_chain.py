"""Read-out chain of a design: gauge strain, signal, noise and resolution per element.

Gauge strain. The gauge sits on the flat top face centred over the notch
centre x_h and across the sheet, and reads the strain averaged over its
grid, length L_g along x, width W across:

    eps_avg / F = (1 / (L_g W)) * integral over the grid of eps_xx / F dA.

Per level (:func:`grid_strain_per_N`):

* ``fem3d``: fem3d's own eps_xx on the top face (the P2 field of the kept
  stiffness solve, :func:`tactcad.mechanics.fem.fields.face_rectangle_average`),
  integrated exactly over the grid's rectangle; its error is the Richardson
  estimate over the three meshes.
* ``closed-form`` and ``beam``: Euler-Bernoulli bending along the real
  profile, eps(x) / F = -6 (x_F - x) / (E b h(x)^2) with the section height
  h(x) of the notch (t + R - sqrt(R^2 - (x - x_h)^2)), the base block behind
  it and the arm in front (x_F: load point; negative: the top face is in
  compression under an upward tip force), averaged over L_g, times the
  fem3d-fitted factor C of :mod:`tactcad.mechanics.gauge_strain` (the web's
  near plane strain in a wide sheet, and EB's too peaked profile); its
  error is the fit's, larger outside the fitted range (flagged).
* ``fem2d``: the plane-stress P2 field of :mod:`tactcad.mechanics.fem.fem2d`
  on the top-surface vertices (sigma_xx / E on the free surface), averaged
  over L_g, times the width part 1 - nu^2 phi of that fit.

The grid lies a glue line + carrier above the face and the layer stiffens
the web: every level's face average is multiplied by the transformed-section
read factor of web + layer (catalogue thicknesses and modulus, ``[readout]``;
:func:`tactcad.mechanics.gauge_strain.bonded_grid_factor`), taken section by
section along the grid's span and weighted by the beam's face strain there
(:func:`beam_grid_read_factor`), so the sensitivity, K_v, the force
resolution and the thermal figures read the strain the grid itself sees. A
finite-element level that meshes the layer reads the grid's plane itself.

Signal. Quarter bridge, linearised: V_out = G V_ex GF eps / 4
(Hoffmann, "An Introduction to Measurements using Strain Gages", HBM 1989,
ch. 7); the exact output V_ex GF eps / (4 + 2 GF eps) is lower by the
relative nonlinearity GF |eps| / 2 (reported at the full-scale force).
Per element: sensitivity S = G V_ex GF eps_avg / (4 F) (V/N), K_v = S K
(V/mm, eq. 4-6 of the paper's calibration).

Noise (one reading, ``samples_averaged`` samples averaged):
the amplifier's input noise density e_n over the chain's noise bandwidth
(the anti-alias filter's: pi/2 x its corner for first order, (pi/2n)/sin(pi/2n)
x the corner for a Butterworth of order n; the amplifier's single pole,
pi/2 x its -3 dB bandwidth, without one), the bridge's Johnson noise
(source resistance = gauge resistance for four equal arms), both times the
gain, the DAQ's random noise and the quantisation step / sqrt(12), summed
in quadrature; averaging divides the filtered analog part by the square root of the
effective sample count (correlated samples: :attr:`ReadoutChain.effective_samples`), the
DAQ's and the quantisation by that of the sample count. The 1/f noise of the amplifier
(its data sheet's low-band figure) and of the foil grid (Hooge) over the band from the tare
to the averaging window's bandwidth is added unaveraged (:func:`flicker_noise_V`). Force
resolution = that noise / |S| (1 sigma).

K_obj resolution: eq. 1-3 with each element's own force resolution
(:func:`tactcad.mechanics.resolution.unit_resolution`); each row's reference
reads with every element of the row softer than it (:func:`row_units`, as
``verify``), pressed until the reference carries the full-scale force.

Units: mm, N, MPa, V, N/mm, V/mm, V/N; strain dimensionless.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Collection, Mapping

import numpy as np

from tactcad.store import kept_per_process
from tactcad.design.array_plan import ElementGeometry, Material, Plan
from tactcad.design.readout_section import ReadoutChain, readout_of
from tactcad.mechanics.ladder import is_meshed
from tactcad.mechanics.notch_profile import notch_integral, notched_height_mm

#: Boltzmann constant (J/K) and the bridge temperature assumed for its Johnson noise (K).
BOLTZMANN_J_PER_K = 1.380649e-23
BRIDGE_TEMPERATURE_K = 296.0
#: Gauss-Legendre points on each smooth piece of the grid's span (the beam-theory average).
GAUSS_POINTS = 64


def readout_chain(plan: Plan) -> ReadoutChain:
    """The plan's resolved ``[readout]`` (defaults from the library gauge and datasheets)."""
    return readout_of(plan.raw, plan.strength.gauge)


# ---------------------------------------------------------------------------
# Gauge strain
# ---------------------------------------------------------------------------
def top_face_height_mm(g: ElementGeometry, x_mm) -> np.ndarray:
    """Section height under the flat top face at ``x_mm`` (element frame, mm; array-like):
    the base block behind the notch, the circular notch, the arm in front
    (:func:`tactcad.mechanics.notch_profile.notched_height_mm`)."""
    return notched_height_mm(np.asarray(x_mm, float) - g.hinge_x_mm, g.web_thickness_mm,
                             g.notch_radius_mm, g.base_height_mm, g.arm_height_mm)


def beam_surface_strain_per_N(g: ElementGeometry, material: Material, x_mm) -> np.ndarray:
    """Top-face strain per newton of tip force, Euler-Bernoulli (1/N; negative: compression).

    eps / F = -6 (x_F - x) / (E b h(x)^2), x_F the load point (contact-face centre).
    """
    x = np.asarray(x_mm, float)
    h = top_face_height_mm(g, x)
    b = g.sheet_thickness_mm
    return -6.0 * (g.tip_centre_x_mm - x) / (material.youngs_modulus_MPa * b * h * h)


def grid_span_mm(g: ElementGeometry, grid_length_mm: float) -> tuple[float, float]:
    """x range the grid covers, centred over the notch centre (mm)."""
    return g.hinge_x_mm - grid_length_mm / 2, g.hinge_x_mm + grid_length_mm / 2


def beam_face_mean_strain_per_N(g: ElementGeometry, material: Material,
                                grid_length_mm: float) -> float:
    """Top-face strain per newton averaged over the grid's span, beam theory (1/N, signed;
    :func:`eb_face_mean_strain_per_N` on ``g``'s dimensions)."""
    return float(eb_face_mean_strain_per_N(g.web_thickness_mm, g.notch_radius_mm,
                                           g.arm_length_mm, grid_length_mm,
                                           g.sheet_thickness_mm, material.youngs_modulus_MPa,
                                           g.base_height_mm, g.arm_height_mm))


def eb_face_mean_strain_per_N(web_mm, notch_radius_mm, arm_length_mm, grid_length_mm,
                              sheet_mm, youngs_modulus_MPa, base_height_mm, arm_height_mm) -> np.ndarray:
    """Euler-Bernoulli top-face strain per newton averaged over a grid centred over the
    notch, broadcast over arrays of element dimensions (mm, MPa; 1/N, negative:
    compression): eps / F = -6 (a - u) / (E b h(u)^2), u from the notch centre, h the
    section under the flat top face (:func:`top_face_height_mm`); Gauss-Legendre on each
    smooth piece (the notch walls u = +-R are break points). ``grid_length_mm`` > 0."""
    a, L, b, E = np.broadcast_arrays(*(np.asarray(v, float) for v in (
        arm_length_mm, grid_length_mm, sheet_mm, youngs_modulus_MPa)))

    def strain(u, h):  # eps / F = -6 (a - u) / (E b h^2)
        return -6.0 * (a[..., None] - u) / (E[..., None] * b[..., None] * h * h)

    return notch_integral(-L / 2, L / 2, web_mm, notch_radius_mm, base_height_mm,
                          arm_height_mm, strain, GAUSS_POINTS) / L


def eb_grid_plane_mean_strain_per_N(web_mm, notch_radius_mm, arm_length_mm, grid_length_mm,
                                    sheet_mm, youngs_modulus_MPa, base_height_mm, arm_height_mm,
                                    grid_height_mm, layer_modulus_MPa, layer_width_mm
                                    ) -> np.ndarray:
    """Euler-Bernoulli strain per newton on the grid's plane, a bonded layer's height above
    the top face, averaged over the grid's span (1/N, negative: compression; broadcast
    over arrays of element dimensions, mm and MPa, like :func:`eb_face_mean_strain_per_N`).

    At each point of the span the face strain -6 (a - u) / (E b h(u)^2) is scaled by the
    transformed section's read factor of the section there, web h(u) + layer
    (:func:`tactcad.mechanics.gauge_strain.transformed_section`): the layer lifts the grid
    further, relative to the section's half height, where the section is thin. Applying the
    web's factor to the whole span instead reads 5-7 % more than fem3d with the layer
    meshed on a 0.1-0.17 mm web under a grid as long as the notch.
    """
    from tactcad.mechanics.gauge_strain import transformed_section

    a, L, b, E, hg, El, Wl = np.broadcast_arrays(*(np.asarray(v, float) for v in (
        arm_length_mm, grid_length_mm, sheet_mm, youngs_modulus_MPa, grid_height_mm,
        layer_modulus_MPa, layer_width_mm)))

    def strain_on_grid_plane(u, h):
        bb, EE = b[..., None], E[..., None]
        read = transformed_section(h, bb, EE, hg[..., None], El[..., None], Wl[..., None])[0]
        return -6.0 * (a[..., None] - u) / (EE * bb * h * h) * read

    return notch_integral(-L / 2, L / 2, web_mm, notch_radius_mm, base_height_mm,
                          arm_height_mm, strain_on_grid_plane, GAUSS_POINTS) / L


def beam_grid_read_factor(g: ElementGeometry, material: Material, chain: ReadoutChain) -> float:
    """The bonded layer's read factor over the grid's span at the beam levels: the grid
    plane's Euler-Bernoulli mean strain over the face's (:func:`eb_grid_plane_mean_strain_per_N`
    over :func:`eb_face_mean_strain_per_N`; dimensionless, > 1 for a layer of any height).
    """
    from tactcad.design.readout_section import carrier_width_mm

    b = g.sheet_thickness_mm
    plane = eb_grid_plane_mean_strain_per_N(
        g.web_thickness_mm, g.notch_radius_mm, g.arm_length_mm, chain.grid_length_mm, b,
        material.youngs_modulus_MPa, g.base_height_mm, g.arm_height_mm, chain.grid_height_mm,
        chain.gauge_backing_modulus_MPa, carrier_width_mm(chain.grid_width_mm, b))
    return float(plane / beam_face_mean_strain_per_N(g, material, chain.grid_length_mm))


def closed_form_grid_read_per_N(web_mm, notch_radius_mm, arm_length_mm, g: ElementGeometry,
                                material: Material, chain: ReadoutChain) -> np.ndarray:
    """What the grid of ``chain`` reads per newton at the closed-form level on elements
    like ``g`` with the given webs, notch radii and arm lengths (mm; broadcast; 1/N,
    signed): the fem3d-fitted grid factor x the EB mean on the grid's plane
    (:func:`eb_grid_plane_mean_strain_per_N`), as :func:`grid_strain_per_N` gives it for one
    element, without its error estimate and range check (for design searches, whose
    candidates are not the design)."""
    from tactcad.design.readout_section import carrier_width_mm
    from tactcad.mechanics.gauge_strain import load_strain_correction

    t, R, a = (np.asarray(v, float) for v in (web_mm, notch_radius_mm, arm_length_mm))
    b, L, W = g.sheet_thickness_mm, chain.grid_length_mm, chain.grid_width_mm
    corr = load_strain_correction()
    factor = corr.factor(t / R, np.sqrt(t * R) / b, material.poisson_ratio, L / (2.0 * R),
                         min(W, b) / b)
    plane = eb_grid_plane_mean_strain_per_N(
        t, R, a, L, b, material.youngs_modulus_MPa, g.base_height_mm, g.arm_height_mm,
        chain.grid_height_mm, chain.gauge_backing_modulus_MPa, carrier_width_mm(W, b))
    return factor * plane


def fem2d_surface_strain_per_N(g: ElementGeometry, material: Material
                               ) -> tuple[np.ndarray, np.ndarray]:
    """(x, eps/F) on the top-face vertices of the default fem2d mesh (plane stress, unit force):
    eps = sigma_xx / E on the free surface (sigma_yy = sigma_zz = 0). Sorted by x.
    Kept in the result store (:func:`tactcad.store.kept_result`) for the same element."""
    from tactcad.store import kept_result

    return kept_result("fem2d surface strain", lambda: _surface_strain(g, material), g, material)


def _surface_strain(g: ElementGeometry, material: Material) -> tuple[np.ndarray, np.ndarray]:
    from tactcad.mechanics.fem.fem2d import solve_fem2d
    from tactcad.mechanics.fem.fields import vertex_stress

    sol = solve_fem2d(g, material, plane="stress", force_N=1.0, keep_field=True)
    mesh = sol.field.basis.mesh
    p = mesh.p
    corners = np.unique(mesh.t[:3])  # a quadratic mesh also lists its mid-side nodes in p
    top = corners[np.abs(p[1, corners] - g.base_height_mm) < 1e-7]
    sxx = vertex_stress(sol.field)[top, 0, 0]
    order = np.argsort(p[0, top])
    return p[0, top][order], sxx[order] / material.youngs_modulus_MPa


def field_face_mean_strain_per_N(x: np.ndarray, eps: np.ndarray,
                                 span: tuple[float, float]) -> float:
    """Average of a sampled strain profile over ``span`` (linear between samples)."""
    a, b = span
    inside = x[(x > a) & (x < b)]
    xs = np.concatenate([[a], inside, [b]])
    ys = np.interp(xs, x, eps)
    return float(np.trapezoid(ys, xs) / (b - a)) if hasattr(np, "trapezoid") else \
        float(np.trapz(ys, xs) / (b - a))


def fem3d_face_mean_strain_per_N(g: ElementGeometry, material: Material,
                                 grid_length_mm: float, grid_width_mm: float) -> dict:
    """fem3d's own top-face strain per newton averaged over the grid (centred over the notch
    and across the sheet; a grid wider than the sheet covers the sheet), from the
    stiffness level's kept solves (:func:`~tactcad.mechanics.fem.fem3d.fem3d_convergence`
    with its defaults: no solve of its own when ``stiffness --model fem3d`` ran).

    Returns:
        ``{"surface": grid average (1/N, signed), "peak": eps/F at the notch centre,
        mid-width, "error_rel": Richardson error of the grid average}``.
    """
    from tactcad.mechanics.fem.fem2d import REFINEMENT_RATIO
    from tactcad.mechanics.fem.fem3d import fem3d_convergence
    from tactcad.mechanics.fem.fields import face_rectangle_average
    from tactcad.mechanics.richardson import richardson

    conv = fem3d_convergence(g, material)
    b = g.sheet_thickness_mm
    w = min(grid_width_mm, b)
    span, across = grid_span_mm(g, grid_length_mm), (b / 2 - w / 2, b / 2 + w / 2)
    vals = [face_rectangle_average(f, span, across) for f in conv.top_face_strains]
    fin = conv.finest
    return {"surface": vals[-1], "peak": fin.gauge_strain / fin.force_N,
            "error_rel": richardson(vals, REFINEMENT_RATIO).error_rel}


def face_mean_strain_as_cut_per_N(g: ElementGeometry, material: Material,
                                  grid_length_mm: float, grid_width_mm: float,
                                  model: str) -> dict:
    """The top face's strain per newton averaged over the grid's span at ladder level
    ``model`` (module doc), on the element as cut (without the gauge's layer).

    Returns:
        ``{"surface"}``: that mean, ``{"peak"}``: the face as cut at the grid's centre
        (notch centre, mid-width) (1/N, signed), ``"error_rel"`` (estimated relative error of
        "surface"), ``"outside_fit"`` (coordinates of the fitted factor outside its range,
        empty for fem3d), ``"source"`` (text).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    from tactcad.mechanics.gauge_strain import (grid_strain_factor, point_strain_factor,
                                                width_strain_factor)
    from tactcad.mechanics.ladder import LADDER

    LADDER.estimator(model)  # an unknown level is refused here
    g = g.bare()  # the face as cut: the gauge's layer is the read factor's (or its own model's)
    if model == "fem3d":
        return {**fem3d_face_mean_strain_per_N(g, material, grid_length_mm, grid_width_mm),
                "outside_fit": (),
                "source": "fem3d's own top-face field averaged over the grid's area"}
    if is_meshed(model):
        x, eps = fem2d_surface_strain_per_N(g, material)
        grid, point = (width_strain_factor(g, material, grid_width_mm),
                       width_strain_factor(g, material, 0.0))
        return {"surface": grid.factor * field_face_mean_strain_per_N(
                    x, eps, grid_span_mm(g, grid_length_mm)),
                "peak": point.factor * float(np.interp(g.hinge_x_mm, x, eps)),
                "error_rel": grid.error_rel, "outside_fit": grid.outside,
                "source": "fem2d plane-stress field on the top face x (1 - nu^2 phi), "
                          "fem3d-fitted width factor"}
    grid = grid_strain_factor(g, material, grid_length_mm, grid_width_mm)
    point = point_strain_factor(g, material)
    return {"surface": grid.factor * beam_face_mean_strain_per_N(g, material, grid_length_mm),
            "peak": point.factor * float(beam_surface_strain_per_N(g, material, g.hinge_x_mm)),
            "error_rel": grid.error_rel, "outside_fit": grid.outside,
            "source": "Euler-Bernoulli bending along the profile x the fem3d-fitted "
                      "width and profile factor"}


def grid_strain_per_N(g: ElementGeometry, material: Material, chain: ReadoutChain,
                      model: str) -> dict:
    """The strain per newton the gauge of ``chain`` reads on one element at ``model``: the
    mean strain on the grid's plane over the grid (``"grid"``; the read-out's, strength's
    and the budgets' ``grid_strain_per_N``), with the face figures as cut it comes from.

    Args:
        g: the element. material: its material.
        chain: the design's read-out (grid length and width, glue line, carrier).
        model: ladder level (module doc).

    Returns:
        ``{"grid": what the grid reads (1/N, signed; the surface average times the bonded
        layer's read factor), "surface": the top face's mean over the grid's span as cut
        (the read-out's ``face_mean_strain_as_cut_per_N``), "peak": the face's strain as
        cut at the notch centre, mid-width (``face_strain_as_cut_per_N``), "error_rel":
        estimated relative error of
        "surface", "outside_fit": flagged coordinates (module doc), "read_factor",
        "height_factor", "stiffening_rel" (:class:`~tactcad.mechanics.gauge_strain.BondedGrid`),
        "source": str}``.

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    from tactcad.design.readout_section import carrier_width_mm
    from tactcad.mechanics.gauge_strain import bonded_grid_factor

    face = face_mean_strain_as_cut_per_N(g, material, chain.grid_length_mm,
                                         chain.grid_width_mm, model)
    b = g.sheet_thickness_mm
    layer = bonded_grid_factor(g.web_thickness_mm, b, material.youngs_modulus_MPa,
                               chain.grid_height_mm, chain.gauge_backing_modulus_MPa,
                               carrier_width_mm(chain.grid_width_mm, b))
    out = {**face, "height_factor": layer.height_factor, "stiffening_rel": layer.stiffening_rel}
    meshed = meshed_grid_strain_per_N(g, material, chain, model)
    if meshed is not None:  # the layer meshed: the grid's own plane, not the section's factor
        return {**out, **meshed, "read_factor": meshed["grid"] / face["surface"]}
    read = beam_grid_read_factor(g, material, chain)
    return {**out, "grid": face["surface"] * read, "read_factor": read}


def meshed_grid_strain_per_N(g: ElementGeometry, material: Material, chain: ReadoutChain,
                             model: str) -> dict | None:
    """At a finite-element level, of an element carrying the gauge of ``chain``: the strain
    on the grid's plane (the layer's top) averaged over the grid, from the solves that give
    its K (fem3d: over the grid's area; fem2d: along it, times the fem3d-fitted width
    factor of the face). None at the other levels or for another gauge than ``g``'s.

    Returns:
        ``{"grid": 1/N (signed), "grid_error_rel": its estimated relative error,
        "grid_source": text}``.
    """
    from tactcad.mechanics.bonded_layer import chain_layer, layer_of
    from tactcad.mechanics.fem.fem2d import REFINEMENT_RATIO
    from tactcad.mechanics.richardson import richardson

    layer = layer_of(g)
    if not is_meshed(model) or layer is None or layer != chain_layer(g, chain):
        return None
    if model == "fem3d":
        from tactcad.mechanics.fem.fem3d import fem3d_convergence, grid_area_strains_per_N

        vals = grid_area_strains_per_N(fem3d_convergence(g, material), g, chain.grid_width_mm)
        return {"grid": vals[-1], "grid_error_rel": richardson(vals, REFINEMENT_RATIO).error_rel,
                "grid_source": "fem3d with the glue line and carrier meshed: the grid's "
                               "plane averaged over its area"}
    from tactcad.mechanics.fem.fem2d import fem2d_convergence, grid_plane_strain_per_N
    from tactcad.store import kept_result

    # three plane-stress solves an element: kept, so verify and check after it solve none
    return kept_result("fem2d grid strain",
                       lambda: grid_plane_strain_per_N(fem2d_convergence(g, material), g,
                                                       material, chain.grid_width_mm),
                       g, material, chain.grid_width_mm)


# ---------------------------------------------------------------------------
# Signal and noise
# ---------------------------------------------------------------------------
#: Hooge's 1/f parameter of a metal (Hooge, "1/f noise is no surface effect", Phys. Lett. A
#: 29, 139 (1969): alpha_H about 2e-3).
HOOGE_ALPHA_METAL = 2e-3
#: The foil grid's conductor (assumptions): constantan foil 5 um thick (foil gauges are
#: etched from foil of a few um), covering half the grid's area, one conduction electron per
#: atom of Cu55Ni45 (8.9 g/cm^3 over 61.4 g/mol: 8.7e22 cm^-3).
FOIL_THICKNESS_UM, GRID_FILL, FOIL_ELECTRONS_PER_CM3 = 5.0, 0.5, 8.7e22


def grid_carriers(chain: ReadoutChain) -> float:
    """The conduction electrons in the gauge's foil grid (:data:`FOIL_ELECTRONS_PER_CM3` over
    the grid's area x :data:`GRID_FILL` x :data:`FOIL_THICKNESS_UM`)."""
    volume_cm3 = (GRID_FILL * chain.grid_length_mm * chain.grid_width_mm * 1e-2
                  * FOIL_THICKNESS_UM * 1e-4)
    return FOIL_ELECTRONS_PER_CM3 * volume_cm3


def flicker_noise_V(chain: ReadoutChain) -> dict[str, float]:
    """A reading's 1/f noise at the DAQ (V rms) over :attr:`ReadoutChain.flicker_band_Hz`:
    the amplifier's, G e_f sqrt(ln(f_hi / f_lo)) (e_f: its 1/f density at 1 Hz), and the
    foil grid's Hooge noise, G (V_ex / 4) sqrt(alpha_H / N ln(f_hi / f_lo)) (a quarter bridge
    puts V_ex / 4 of each relative change of the gauge's resistance at its output). Averaging
    the samples does not reduce it: the band ends at the averaging window's bandwidth.

    Returns:
        ``{"amplifier": V, "gauge": V}``.
    """
    from tactcad.products.silicon_die.mechanics.piezoresistor import hooge_noise_V

    f_lo, f_hi = chain.flicker_band_Hz
    decades = math.log(f_hi / f_lo)
    amp = chain.amplifier_gain * chain.amplifier_flicker_nV_per_rtHz_at_1Hz * 1e-9 * math.sqrt(
        decades)
    gauge = chain.amplifier_gain * hooge_noise_V(HOOGE_ALPHA_METAL, chain.excitation_V / 4.0,
                                                 grid_carriers(chain), f_lo, f_hi)
    return {"amplifier": amp, "gauge": gauge}


def noise_budget_V(chain: ReadoutChain) -> dict[str, float]:
    """Noise of one reading at the DAQ (V rms), by source and in total.

    Keys: ``amplifier``, ``bridge_johnson``, ``daq``, ``quantisation`` (one
    sample each), ``per_sample`` (their quadrature sum), ``amplifier_flicker`` and
    ``gauge_flicker`` (the reading's 1/f noise, :func:`flicker_noise_V`), ``reading``: the
    mean of ``samples_averaged`` samples, the filtered white analog noise (amplifier,
    Johnson) over the chain's effective sample count (:attr:`ReadoutChain.effective_samples`:
    its samples are correlated), the DAQ's noise and the quantisation (independent from
    sample to sample) over the sample count, and the 1/f noise, which averaging does not
    reduce, in quadrature.
    """
    bw_noise = chain.noise_bandwidth_Hz  # anti-alias filter or the amplifier's pole
    amp = chain.amplifier_gain * chain.amplifier_noise_nV_per_rtHz * 1e-9 * math.sqrt(bw_noise)
    johnson = chain.amplifier_gain * math.sqrt(4 * BOLTZMANN_J_PER_K * BRIDGE_TEMPERATURE_K
                                               * chain.gauge_resistance_ohm * bw_noise)
    daq = chain.daq_noise_uV_rms * 1e-6
    quant = chain.lsb_V / math.sqrt(12.0)
    flicker = flicker_noise_V(chain)
    per_sample = math.sqrt(amp ** 2 + johnson ** 2 + daq ** 2 + quant ** 2)
    return {"amplifier": amp, "bridge_johnson": johnson, "daq": daq, "quantisation": quant,
            "per_sample": per_sample, "amplifier_flicker": flicker["amplifier"],
            "gauge_flicker": flicker["gauge"],
            "reading": math.sqrt((amp ** 2 + johnson ** 2) / chain.effective_samples
                                 + (daq ** 2 + quant ** 2) / chain.samples_averaged
                                 + flicker["amplifier"] ** 2 + flicker["gauge"] ** 2)}


def bridge_nonlinearity_rel(gauge_factor: float, strain: float) -> float:
    """Relative shortfall of the exact quarter-bridge output against the linear
    V_ex GF eps / 4: 1 - 1 / (1 + GF eps / 2) (for compression the exact output is larger:
    negative)."""
    return 1.0 - 1.0 / (1.0 + gauge_factor * strain / 2.0)


# ---------------------------------------------------------------------------
# Per element
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class ReadoutReport:
    """What ``tactcad readout`` prints; :meth:`as_json` is its JSON."""

    design: str
    model: str
    chain: ReadoutChain
    noise_V: dict
    full_scale_force_N: float
    kobj_range_N_per_mm: tuple[float, float]
    records: list[dict]
    array_kobj_resolution_rel: float | None
    table1: dict | None = None

    def fit_range_notes(self) -> list[str]:
        """One note per element whose gauge-strain factor is outside its fitted range."""
        return [f"element {r['element']}: the gauge-strain factor is outside its fitted "
                f"range ({', '.join(r['strain_outside_fit'])}); estimated error "
                f"{100 * r['strain_error_rel']:.1f} % (extrapolated)"
                for r in self.records if r.get("strain_outside_fit")]

    def as_json(self) -> dict:
        out = {"design": self.design, "model": self.model, "chain": self.chain.as_json(),
               "noise_V_rms": self.noise_V, "full_scale_force_N": self.full_scale_force_N,
               "kobj_range_N_per_mm": list(self.kobj_range_N_per_mm),
               "array_kobj_resolution_rel": self.array_kobj_resolution_rel,
               "elements": self.records,
               "notes": [
                   "V_out = G V_ex GF eps / 4 (quarter bridge, linearised); the exact output "
                   "differs by bridge_nonlinearity_rel at the full-scale force.",
                   "force_resolution_N: noise of one averaged reading / |sensitivity| (1 sigma).",
                   "kobj_resolution_rel: worst over the required K_obj range at the full-scale "
                   "force, each element read to its own force resolution (eq. 1-3).",
                   "full_scale_signal_V does not include the bridge's offset V0.",
                   "grid_strain_per_N: what the grid reads (the mean strain on the grid's "
                   "plane over the grid), face_mean_strain_as_cut_per_N (the top face as cut, "
                   "without the gauge's layer, averaged over the grid's span at the model "
                   "level, strain_error_rel its estimated error) x grid_read_factor (the grid "
                   "a glue line + carrier above the face, with the layer's stiffening "
                   "gauge_stiffening_rel of the web).",
                   "face_strain_as_cut_per_N: the top face as cut at the grid's centre (notch "
                   "centre, mid-width); face_mean_over_centre_as_cut: "
                   "face_mean_strain_as_cut_per_N / face_strain_as_cut_per_N. The face strain "
                   "under the gauge's layer at the grid's centre is stiffness's "
                   "face_strain_per_N."]
               + self.fit_range_notes()}
        if self.table1 is not None:
            out["table1"] = self.table1
        return out


def array_resolution_rel(units: list, rng: tuple[float, float], force_N: float) -> float | None:
    """Worst relative K_obj resolution over the range of the array's best unit at each K_obj;
    ``units``: :class:`~tactcad.mechanics.resolution.ReadUnit` (or (K_r, force resolution of
    the row's reference, K_m, force resolution of the measuring element) tuples; N/mm, N),
    one per measuring element; None without a unit."""
    from tactcad.mechanics.resolution import ReadUnit, worst_resolution_rel

    if not units:
        return None
    return worst_resolution_rel([ReadUnit(*u) for u in units], rng, force_N)


def row_units(plan: Plan, k: dict[str, float]) -> list[tuple]:
    """(reference slot, measuring slot) of every sensing unit of ``plan``, in element order:
    each element softer than its reference (:meth:`Plan.reference_for`: its row's, or its
    column's with ``pairing`` "column") measures against it; ``k``: K per distinct part (N/mm)."""
    out = []
    for slot in plan.slots:
        ref = plan.reference_for(slot)
        if k[slot.geometry.part_name] < k[ref.geometry.part_name] * (1 - 1e-9):
            out.append((ref, slot))
    return out


def soft_reference_errors(plan: Plan, k: dict[int, float]) -> list:
    """The references a design file names that are not stiffer than every element read
    against them (:meth:`Plan.reference_for`): such a unit cannot read K_obj, since eq. 2,
    R = (K_r + K_obj) / (K_m + K_obj), spans 1 ... K_r / K_m and eq. 3 inverts it only for
    K_r > K_m (paper eq. 2-3, :mod:`tactcad.mechanics.lumped_model`). References the file
    leaves out are each row's stiffest: refused only where another element of the row is
    as stiff (a row of equal elements has no reference).

    Args:
        plan: the design.
        k: element number -> K (N/mm), e.g.
            :func:`tactcad.mechanics.evaluation.ladder_stiffness_by_element`.

    Returns:
        One :class:`~tactcad.errors.DesignError` per named reference refused, naming
        ``arms.reference_elements[i]``, the reference, its K and the K of each element
        no softer than it; empty when every named reference is the stiffer.
    """
    from pathlib import Path

    from tactcad.errors import DesignError

    named = (plan.raw.get("arms") or {}).get("reference_elements")
    errors = []
    for i, ref in enumerate(plan.references):
        against = [s.number for s in plan.slots
                   if s.number != ref and plan.reference_for(s).number == ref]
        stiffer = [n for n in against if k[n] >= k[ref] * (1 - 1e-9)]
        if not stiffer:
            continue
        where = "column" if plan.pairing == "column" else "row"
        if not named:  # the row's stiffest is its reference: another as stiff leaves R = 1
            errors.append(DesignError(
                "arms.lengths_mm", [s.geometry.arm_length_mm for s in plan.slots],
                f"a {where} whose stiffest element, its reference (the file names none), is "
                f"stiffer than every other: element {ref} has K = {k[ref]:.4g} N/mm, "
                + ", ".join(f"element {n} {k[n]:.4g} N/mm" for n in stiffer)
                + "; give its reference a shorter arm (or a thicker web), or name one in "
                "arms.reference_elements",
                "the method reads K_obj from R = (K_r + K_obj) / (K_m + K_obj) (eq. 2-3), "
                "which is 1 for every K_obj when K_r = K_m", file=Path(plan.source).name))
            continue
        stiffest = max(against + [ref], key=lambda n: (k[n], -n))
        errors.append(DesignError(
            f"arms.reference_elements[{i + 1}]", ref,
            f"an element stiffer than every element read against it (K_r > K_m): element "
            f"{ref} has K = {k[ref]:.4g} N/mm, "
            + ", ".join(f"element {n} {k[n]:.4g} N/mm" for n in stiffer)
            + f"; the stiffest of its {where} is element {stiffest} ({k[stiffest]:.4g} N/mm)",
            "the method reads K_obj from R = (K_r + K_obj) / (K_m + K_obj) (eq. 2-3), which "
            "needs the reference stiffer than its measuring elements; no softer element "
            "measures against it", file=Path(plan.source).name))
    return errors


def force_resolution_N(chain: ReadoutChain, grid_strain_per_N: float,
                       reading_noise_V: float | None = None) -> float:
    """Force resolution (N, 1 sigma): the noise of one averaged reading over the
    sensitivity |V/strain x grid strain per N|. ``reading_noise_V``: the chain's
    (:func:`noise_budget_V`, ``"reading"``) when not given."""
    noise = noise_budget_V(chain)["reading"] if reading_noise_V is None else reading_noise_V
    return noise / abs(chain.volts_per_strain * grid_strain_per_N)


def element_force_resolution_N(plan: Plan, model: str = "closed-form",
                               progress: Callable[[str], None] | None = None,
                               chain: ReadoutChain | None = None,
                               parts: Collection[str] | None = None) -> dict[str, dict]:
    """Per distinct part of ``plan``: its grid strain per newton (:func:`grid_strain_per_N`,
    ``"eps"``), sensitivity (V/N, ``"S"``) and force resolution (N, ``"dF"``: the noise of one
    averaged reading over |S|, 1 sigma) through the design's read-out chain at ``model``.

    Args:
        parts: the part names to read (default every distinct part); the others are
            neither solved nor returned.

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    chain = chain or readout_chain(plan)
    noise = noise_budget_V(chain)["reading"]
    out = {}
    for name, g in plan.distinct_elements.items():
        if parts is not None and name not in parts:
            continue
        if progress:
            progress(f"readout {model}: {name}")
        eps = grid_strain_per_N(g, plan.material, chain, model)
        s = chain.volts_per_strain * eps["grid"]
        out[name] = {"eps": eps, "S": s, "dF": force_resolution_N(chain, eps["grid"], noise)}
    return out


def grid_strain_error_rel(read: Mapping[str, Any]) -> float:
    """The estimated relative error of the grid strain a :func:`grid_strain_per_N` answer
    gives: the meshed grid's own (``"grid_error_rel"``: Richardson over the meshes, plus the
    fem2d width factor's) where the level meshes the layer, else the face figure's
    (``"error_rel"``, the fitted width and profile factor's), which the layer's read factor
    carries over. ``stiffness --json``'s ``grid_strain_error_rel``, ``thermal``'s and the
    K_obj records' strain term are this one figure.

    Args:
        read: a :func:`grid_strain_per_N` answer.

    Returns:
        The relative error (dimensionless, >= 0).
    """
    return float(read.get("grid_error_rel", read["error_rel"]))


@kept_per_process(maxsize=1024)
def unmeshed_grid_read(g: ElementGeometry, material: Material, chain,
                       model: str) -> tuple[float, float]:
    """(unsigned strain per newton (1/N), its relative error) the gauge grid of ``chain``
    reads on ``g`` at a level that meshes nothing (closed form, beam):
    :func:`grid_strain_per_N`'s ``"grid"`` and :func:`grid_strain_error_rel`, kept per
    process on their (frozen) inputs, since a search reads the same element's grid strain
    for its stops, its limits and its verification matrix.

    Args:
        g: the element (mm). material: its material (MPa). chain: the design's read-out
            (:class:`tactcad.design.readout_section.ReadoutChain`). model: the level's name.

    Returns:
        (the strain per newton (1/N, unsigned), its relative error).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.

    Source: :func:`grid_strain_per_N`.
    """
    read = grid_strain_per_N(g, material, chain, model)
    return abs(float(read["grid"])), grid_strain_error_rel(read)


def unmeshed_grid_strain_per_N(g: ElementGeometry, material: Material, chain,
                               model: str) -> float:
    """The unsigned strain per newton (1/N) of :func:`unmeshed_grid_read`.

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    return unmeshed_grid_read(g, material, chain, model)[0]


def unmeshed_force_resolution_N(plan: Plan, model: str = "closed-form") -> dict[str, float]:
    """:func:`element_force_resolution_N`'s ``"dF"`` per distinct part at a level that meshes
    nothing (closed form, beam): the same numbers, from each part's unsigned grid strain
    kept per process (:func:`unmeshed_grid_strain_per_N`;
    the strain's sign drops out of |S|).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    return {name: d["dF"] for name, d in force_resolution_reads(plan, model).items()}


def force_resolution_reads(plan: Plan, model: str = "closed-form",
                           progress: Callable[[str], None] | None = None,
                           parts: Collection[str] | None = None
                           ) -> dict[str, dict[str, float]]:
    """Per distinct part: its force resolution through the read-out chain at ``model``
    (``"dF"``, N, 1 sigma) and the relative error of the grid strain it divides by
    (``"strain_error_rel"``, :func:`grid_strain_error_rel`): the read-out's share of the
    K_obj records' error. A level that meshes nothing reads each part's kept grid strain
    (:func:`unmeshed_grid_read`); a finite-element level reads its solves
    (:func:`element_force_resolution_N`).

    Args:
        plan: the design. model: the ladder level. progress: one line per part solved (the
            finite-element levels).
        parts: the part names to read (default every distinct part): a level that keeps
            some parts' figures from below (:attr:`tactcad.studies.verification.Figures.
            kept_from`) reads those there and solves none of them.

    Returns:
        ``{part name: {"dF": N, "strain_error_rel": dimensionless}}``, the parts asked for.

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
    """
    if is_meshed(model):
        return {name: {"dF": d["dF"], "strain_error_rel": grid_strain_error_rel(d["eps"])}
                for name, d in element_force_resolution_N(plan, model, progress,
                                                          parts=parts).items()}
    chain = readout_chain(plan)
    noise = noise_budget_V(chain)["reading"]
    out = {}
    for name, g in plan.distinct_elements.items():
        if parts is not None and name not in parts:
            continue
        eps, error = unmeshed_grid_read(g, plan.material, chain, model)
        out[name] = {"dF": force_resolution_N(chain, eps, noise), "strain_error_rel": error}
    return out


def readout_report(plan: Plan, requirements, model: str = "closed-form",
                   progress: Callable[[str], None] | None = None,
                   stiffness: dict[str, float] | None = None) -> ReadoutReport:
    """Per element: gauge strain over the grid, K_v, sensitivity, force and K_obj resolution.

    Args:
        plan: the design.
        model: ladder level for K and the strain field.
        progress: gets one line per distinct element.
        stiffness: K per distinct part (N/mm) already computed at ``model``
            (``verify`` passes its own); ``None`` estimates them.
        requirements: the design's :class:`~tactcad.studies.verification.Requirements`
            (full-scale force and K_obj range).

    Raises:
        UnknownModelError: ``model`` is not a ladder level.
        DesignError: the material has no yield strength (the full-scale force needs it).
    """
    from tactcad.mechanics.ladder import estimate, gauge_k_rise, gauge_rise_error_rel

    chain = readout_chain(plan)
    noise = noise_budget_V(chain)
    F, rng = requirements.full_scale_force_N, requirements.kobj_range_N_per_mm
    per_part = element_force_resolution_N(plan, model, progress, chain)
    for name, g in plan.distinct_elements.items():
        per_part[name]["K"] = stiffness[name] if stiffness is not None else \
            estimate(model, g, plan.material).stiffness_N_per_mm
        per_part[name]["K_layer_rel"] = gauge_k_rise(model, g, plan.material)
        per_part[name]["K_layer_error_rel"] = gauge_rise_error_rel(model)
    measuring = {m.number for _, m in row_units(plan, {n: d["K"] for n, d in per_part.items()})}
    records, units = [], []
    for slot in plan.slots:
        d = per_part[slot.geometry.part_name]
        ref = plan.reference_for(slot)
        r = per_part[ref.geometry.part_name]
        is_ref = slot.number == ref.number
        kobj_res = None
        if slot.number in measuring:
            units.append((r["K"], r["dF"], d["K"], d["dF"]))
            kobj_res = array_resolution_rel(units[-1:], rng, F)
        records.append(_element_record(slot, d, is_ref, ref.number, kobj_res, chain, F))
    return ReadoutReport(plan.name, model, chain, noise, F, rng, records,
                         array_resolution_rel(units, rng, F))


def _element_record(slot, d: dict, is_ref: bool, ref: int, kobj_res: float | None,
                    chain: ReadoutChain, F: float) -> dict:
    eps_fs = d["eps"]["grid"] * F
    return {"element": slot.number, "part": slot.geometry.part_name,
            "arm_length_mm": slot.geometry.arm_length_mm,
            "role": "reference" if is_ref else "measuring",
            "stiffness_N_per_mm": d["K"],
            "grid_strain_per_N": d["eps"]["grid"],
            "face_mean_strain_as_cut_per_N": d["eps"]["surface"],
            "face_strain_as_cut_per_N": d["eps"]["peak"],
            "face_mean_over_centre_as_cut": d["eps"]["surface"] / d["eps"]["peak"],
            "strain_source": d["eps"]["source"],
            "strain_error_rel": d["eps"]["error_rel"],
            "strain_outside_fit": list(d["eps"]["outside_fit"]),
            "grid_read_factor": d["eps"]["read_factor"],
            "grid_height_factor": d["eps"]["height_factor"],
            "gauge_stiffening_rel": d["eps"]["stiffening_rel"],
            "gauge_layer_k_rel": d["K_layer_rel"],
            "gauge_layer_k_error_rel": d["K_layer_error_rel"],
            "sensitivity_V_per_N": d["S"],
            "k_v_V_per_mm": d["S"] * d["K"],
            "force_resolution_N": d["dF"],
            "full_scale_signal_V": d["S"] * F,
            "daq_range_used_rel": abs(d["S"] * F) / chain.daq_range_V,
            "bridge_nonlinearity_rel": bridge_nonlinearity_rel(chain.gauge_factor, eps_fs),
            "kobj_resolution_rel": kobj_res,
            "reference_element": None if is_ref else ref}


def rel_std(x: list[float]) -> float:
    """Sample standard deviation over the mean (0 for a single value)."""
    return float(np.std(x, ddof=1) / abs(np.mean(x))) if len(x) > 1 else 0.0
