"""``tactcad bench modal``: the speed/accuracy trade of the modal ladder.

Designs: the design file's shortest- and longest-arm elements, and the four
corners of the design domain the closed form's correction spans (web 0.05
and 1 mm, arm 2-20 mm, notch radius t-2 mm, sheet 0.5-10 mm; other
dimensions by the grid rule of :mod:`tactcad.studies.correction_sweep`,
steel of 7.8 g/cm^3). Every level runs on every design; fem3d is the
reference. Printed per level: time per element, the largest and mean
distance of its first in-plane frequency from fem3d's, the largest error
estimate it states, and whether every distance lies within the stated
estimate.

Units: Hz, s.
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from dataclasses import replace

from tactcad.design.array_plan import Plan
from tactcad.mechanics.modal_ladder import estimate_modes, modal_models

#: (web t, arm a, notch R, sheet b) at the corners of the design domain (mm).
CORNERS = ((0.05, 20.0, 0.05, 10.0), (1.0, 3.6, 2.0, 0.5), (0.05, 2.0, 0.05, 0.5),
           (1.0, 20.0, 2.0, 10.0))
CORNER_DENSITY_G_PER_CM3 = 7.8


def designs(plan: Plan, which: str = "all") -> list[tuple[str, object, object]]:
    """(label, geometry, material) of the benchmark designs: ``own``, ``corners`` or ``all``."""
    from tactcad.studies.correction_sweep import grid_geometry

    out = []
    if which in ("own", "all"):
        arms = sorted(plan.distinct_elements.values(), key=lambda g: g.arm_length_mm)
        for g in {id(a): a for a in (arms[0], arms[-1])}.values():
            out.append((g.part_name, g, plan.material))
    if which in ("corners", "all"):
        for t, a, R, b in CORNERS:
            g, mat = grid_geometry(t, a, R, sheet_mm=b, poisson_ratio=0.27)
            out.append((f"corner_t{t:g}_a{a:g}_R{R:g}_b{b:g}", g,
                        replace(mat, density_g_per_cm3=CORNER_DENSITY_G_PER_CM3)))
    return out


def run(plan: Plan, which: str = "all", levels: tuple[str, ...] | None = None,
        progress=lambda s: None) -> list[dict]:
    """One row per (design, level): first in-plane frequency (Hz), first
    frequency of any family, error estimate, seconds and the distance to fem3d."""
    levels = tuple(levels or modal_models())
    if "fem3d" not in levels:
        levels += ("fem3d",)
    rows = []
    for label, g, mat in designs(plan, which):
        found = {}
        for level in levels:
            t0 = time.perf_counter()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # outside the correction's fit: error grows, stated
                r = estimate_modes(level, g, mat, modes=3)
            seconds = time.perf_counter() - t0
            in_plane = next(m.frequency_Hz for m in r.modes if m.family == "in-plane")
            found[level] = {"design": label, "model": level, "first_in_plane_Hz": in_plane,
                            "first_Hz": r.first_Hz, "first_family": r.modes[0].family,
                            "error_estimate_rel": r.error_estimate_rel, "seconds": seconds}
            progress(f"{label}: {level} {in_plane:.1f} Hz in-plane, {seconds:.3g} s")
        rows += against_fem3d(found, "first_in_plane_Hz")
    return rows


def against_fem3d(found: dict[str, dict], key: str) -> list[dict]:
    """One design's rows by level (level -> row), each given ``error_vs_fem3d_rel``: its
    ``key`` over fem3d's, less one."""
    ref = found["fem3d"][key]
    for row in found.values():
        row["error_vs_fem3d_rel"] = row[key] / ref - 1.0
    return list(found.values())


def summary(rows: list[dict]) -> list[dict]:
    """Per level: designs, mean and max seconds, max and mean |error vs fem3d|,
    the largest stated estimate and whether every error lies within its estimate (None for
    the reference, fem3d, and for a level that states no estimate)."""
    out = []
    for level in dict.fromkeys(r["model"] for r in rows):
        rs = [r for r in rows if r["model"] == level]
        errs = [abs(r["error_vs_fem3d_rel"]) for r in rs]
        estimates = [r["error_estimate_rel"] for r in rs if r["error_estimate_rel"] is not None]
        out.append({"model": level, "n": len(rs),
                    "time_per_element_s": sum(r["seconds"] for r in rs) / len(rs),
                    "max_time_s": max(r["seconds"] for r in rs),
                    "max_error_vs_fem3d_rel": max(errs), "mean_error_vs_fem3d_rel": sum(errs) / len(errs),
                    "max_error_estimate_rel": max(estimates) if estimates else None,
                    "within_estimate": all(abs(r["error_vs_fem3d_rel"]) <= r["error_estimate_rel"]
                                           for r in rs)
                    if level != "fem3d" and len(estimates) == len(rs) else None})
    return out


def main(args, plan: Plan) -> int:
    """Entry point of ``tactcad bench modal``."""
    as_json = getattr(args, "json", False)
    quiet = as_json or getattr(args, "quiet", False)
    progress = (lambda s: None) if quiet else (lambda s: print(s, file=sys.stderr, flush=True))
    rows = run(plan, getattr(args, "designs", "all"), tuple(getattr(args, "models", None) or ()),
               progress)
    table = summary(rows)
    if as_json:
        print(json.dumps({"designs": rows, "levels": table}, indent=2))
        return 0
    print(f"{'level':<12} {'n':>3} {'time/elem s':>12} {'max time s':>11} "
          f"{'err vs fem3d max':>17} {'mean':>8} {'est. err max':>13} {'within est.':>12}")
    for r in table:
        within = "-" if r["within_estimate"] is None else ("yes" if r["within_estimate"] else "NO")
        print(f"{r['model']:<12} {r['n']:>3} {r['time_per_element_s']:>12.4g} "
              f"{r['max_time_s']:>11.3g} {100 * r['max_error_vs_fem3d_rel']:>16.2f}% "
              f"{100 * r['mean_error_vs_fem3d_rel']:>7.2f}% {100 * r['max_error_estimate_rel']:>12.2f}% "
              f"{within:>12}")
    print("errors: first in-plane frequency against fem3d's; fem3d's column is its own "
          "Richardson estimate")
    return 0
