"""``tactcad bench die``: the cost and the error of a die beam's stiffness levels.

Beams: the die's two rows (its reference and its measuring beam) and, with ``domain``, four
beams in the die's device layer at the corners of the sections a die's design makes (beam
width over layer thickness 1 to 12, length over thickness 4.5 to 36, each at least
:data:`tactcad.products.silicon_die.design.mems_die.SLENDERNESS` widths long). Levels, each on every beam:

* ``clamped``: the textbook cantilever clamped at its root, E w t^3 / (4 L^3) (no stated
  error: it leaves out the frame's give at the root);
* ``closed-form``: the die's closed form, the root's give as extra length and Timoshenko's
  shear (:func:`tactcad.products.silicon_die.design.mems_die.beam_stiffness_N_per_mm`; stated
  :data:`tactcad.products.silicon_die.design.mems_die.CLOSED_FORM_K_ERROR_REL`);
* ``calculix``: CalculiX C3D8I on the frame block, one mesh (when ``ccx`` is installed; its
  mesh error not estimated);
* ``fem3d``: the die's fem3d level on the frame, two meshes extrapolated: the reference (its
  own column is its extrapolation's change).

Printed per level: seconds per beam, the largest and mean distance of its K from fem3d's,
the largest error it states, and whether every distance lies within it. Sets no goal.

Units: um, N/mm, s.
"""

from __future__ import annotations

import dataclasses
import json
import shutil
import sys
import time

#: (w / t, L / t) of the domain's beams: the corners of the sections the design makes.
DOMAIN = ((1.0, 4.5), (1.0, 36.0), (6.0, 18.0), (12.0, 36.0))


def beams(plan, which: str = "all") -> list[tuple[str, object, object]]:
    """(label, plan, beam) of the benchmark's beams: ``rows``, ``domain`` or ``all``; a
    domain beam carries a post as wide as the beam (at most the die's largest post)."""
    from tactcad.products.silicon_die.design.mems_die import POST_MAX_UM

    out = []
    if which in ("rows", "all"):
        out += [(f"{b.role} beam", plan, b) for b in plan.beams[:: plan.columns]]
    if which in ("domain", "all"):
        ref, t = plan.beams[0], plan.beams[0].thickness_um
        for w_over_t, l_over_t in DOMAIN:
            beam = dataclasses.replace(ref, width_um=w_over_t * t, length_um=l_over_t * t)
            out.append((f"w/t {w_over_t:g}, L/t {l_over_t:g}",
                        dataclasses.replace(plan, post_um=min(beam.width_um, POST_MAX_UM)),
                        beam))
    return out


def _levels(calculix: bool) -> dict:
    """Level name -> (plan, beam) -> (K N/mm, stated error or None)."""
    from tactcad.products.silicon_die.design.mems_die import (CLOSED_FORM_K_ERROR_REL,
                                                              beam_stiffness_N_per_mm,
                                                              clamped_beam_stiffness_N_per_mm)
    from tactcad.products.silicon_die.mechanics.die_dynamics import calculix_beam_check
    from tactcad.products.silicon_die.mechanics.die_fem3d import die_beam_fem3d

    def section(plan, beam):
        return plan.youngs_modulus_MPa, beam.width_um, beam.thickness_um, beam.length_um

    def fem3d(plan, beam):
        r = die_beam_fem3d(plan, beam)
        return r.k_N_per_mm, r.k_error_rel

    levels = {"clamped": lambda p, b: (float(clamped_beam_stiffness_N_per_mm(*section(p, b))),
                                       None),
              "closed-form": lambda p, b: (beam_stiffness_N_per_mm(*section(p, b)),
                                           CLOSED_FORM_K_ERROR_REL)}
    if calculix:
        levels["calculix"] = lambda p, b: (calculix_beam_check(p, b).k_fe_N_per_mm, None)
    levels["fem3d"] = fem3d
    return levels


def run(plan, which: str = "all", calculix: bool | None = None,
        progress=lambda s: None) -> list[dict]:
    """One row per (beam, level): K (N/mm), its stated error (or None), seconds and the
    distance to fem3d's K. ``calculix``: run CalculiX (default: when ``ccx`` is on the PATH)."""
    from tactcad.benchmarks.modal_bench import against_fem3d

    levels = _levels(shutil.which("ccx") is not None if calculix is None else calculix)
    rows = []
    for label, p, beam in beams(plan, which):
        found = {}
        for name, level in levels.items():
            t0 = time.perf_counter()
            k, error = level(p, beam)
            seconds = time.perf_counter() - t0
            found[name] = {"beam": label, "model": name, "width_um": beam.width_um,
                           "thickness_um": beam.thickness_um, "length_um": beam.length_um,
                           "K_N_per_mm": k, "error_estimate_rel": error, "seconds": seconds}
            progress(f"{label}: {name} K {k:.4g} N/mm, {seconds:.3g} s")
        rows += against_fem3d(found, "K_N_per_mm")
    return rows


def main(args, plan) -> int:
    """Entry point of ``tactcad bench die``."""
    from tactcad.benchmarks.modal_bench import summary

    as_json = getattr(args, "json", False)
    quiet = as_json or getattr(args, "quiet", False)
    progress = (lambda s: None) if quiet else (lambda s: print(s, file=sys.stderr, flush=True))
    rows = run(plan, getattr(args, "beams", "all"), progress=progress)
    table = summary(rows)
    if as_json:
        print(json.dumps({"die": plan.name, "beams": rows, "levels": table}, indent=2,
                         allow_nan=False))
        return 0
    print(f"die {plan.name}: each beam's K by level against fem3d on the frame")
    print("| level | beams | s per beam | max s | K vs fem3d, largest | mean | stated, largest "
          "| within it |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in table:
        within = "-" if r["within_estimate"] is None else ("yes" if r["within_estimate"] else "NO")
        stated = ("-" if r["max_error_estimate_rel"] is None
                  else f"{100 * r['max_error_estimate_rel']:.2f} %")
        print(f"| {r['model']} | {r['n']} | {r['time_per_element_s']:.3g} | "
              f"{r['max_time_s']:.3g} | {100 * r['max_error_vs_fem3d_rel']:.2f} % | "
              f"{100 * r['mean_error_vs_fem3d_rel']:.2f} % | {stated} | {within} |")
    print("fem3d's stated column is its own extrapolation's change; calculix is one mesh")
    return 0
