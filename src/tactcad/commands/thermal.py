"""``tactcad thermal``: thermal drift of each element's gauge read-out, per kelvin."""

from __future__ import annotations

import argparse

from tactcad.commands import add_cache_args, add_design_arg, add_output_args, plan_from_args
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import count
from tactcad.errors import DesignError
from tactcad.mechanics.ladder import models


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "thermal", help="per element: apparent strain, equivalent tip force and K_obj error per "
                        "kelvin, self-heating, what a half-bridge dummy gauge cancels",
        description="Thermal drift of the design's [readout] gauge on each element: the "
                    "apparent strain per kelvin from the mismatch of the element's CTE and the "
                    "gauge's STC number (Micro-Measurements TN-504 relation), the gauge factor's "
                    "temperature coefficient at full scale, the equivalent tip force per kelvin "
                    "(apparent strain / grid strain per newton at the ladder level), the K_obj "
                    "error per kelvin (eq. 1-3), the self-heating at the excitation and what a "
                    "half-bridge dummy gauge would cancel. Units: K, N/K, ppm/K, W.")
    add_design_arg(p)
    add_cache_args(p)
    p.add_argument("--element", type=count(1, 10_000, "an element number"), default=None,
                   help="only this element (default: every element)")
    p.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level for K and the strain per newton (default closed-form)")
    add_output_args(p, "print one JSON object: the thermal inputs and one record per element")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from dataclasses import replace

    from tactcad.mechanics.thermal_drift import thermal_report
    from tactcad.studies.verification import requirements_of

    plan = plan_from_args(args)
    report = thermal_report(plan, requirements_of(plan), args.model)
    if args.element is not None:
        chosen = [r for r in report.records if r["element"] == args.element]
        if not chosen:
            raise DesignError("--element", args.element, f"1 ... {len(report.records)}",
                              "an element number of the design")
        report = replace(report, records=chosen)
    if args.json:
        print(dumps(report.as_json(), indent=1))
        return 0
    print(render(report))
    return 0


def render(report) -> str:
    """The report as text: the inputs with their sources and one table row per element."""
    s = report.setting
    lines = [f"thermal drift of {report.design} ({report.model}): element CTE "
             f"{s.substrate_cte_ppm_per_K:g} ppm/K, gauge STC {s.stc_ppm_per_K:.3g} ppm/K, "
             f"apparent strain {1e6 * report.apparent_strain_per_K:+.3g} microstrain/K, gauge "
             f"factor TC {1e6 * s.gf_tc_per_K:+.3g} ppm/K, dummy gauge "
             f"{'half-bridge' if s.dummy else 'none'}",
             f"  self-heating: {1e3 * report.grid_power_W:.3g} mW in the grid, "
             f"+{report.self_heating_K:.3g} K above the element",
             "| element | role | apparent N/K | GF term N/K | drift N/K | dummy cancels | "
             "self-heating offset N | K_obj error %/K |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in report.records:
        k = "n/a" if r["kobj_error_rel_per_K"] is None else f"{100 * r['kobj_error_rel_per_K']:.3g}"
        lines.append(f"| {r['element']} | {r['role']} | {r['apparent_force_N_per_K']:+.3g} | "
                     f"{r['gauge_factor_force_N_per_K']:.3g} | {r['drift_N_per_K']:.3g} | "
                     f"{100 * r['half_bridge_cancels_rel']:.0f} % | "
                     f"{r['self_heating_offset_N']:+.3g} | {k} |")
    lines += [f"  {k}: {v}" for k, v in s.sources.items()]
    return "\n".join(lines)
