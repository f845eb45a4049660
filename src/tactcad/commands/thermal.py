"""``tactcad thermal``: thermal drift of each element's gauge read-out, per kelvin."""

from __future__ import annotations

import argparse

from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              product_view)
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import check_element_option, element_number, keep_option_defaults
from tactcad.mechanics.ladder import models


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "thermal", help="per element: zero and span drift per kelvin, self-heating offset, K_obj "
                        "error per kelvin across the force range, what a dummy gauge cancels",
        description="Thermal drift of the design's [readout] gauge on each element, zero and "
                    "span apart. Zero (offset, N/K): the thermal output from the mismatch of the "
                    "element's CTE and the gauge's STC number (Micro-Measurements TN-504) and, "
                    "with two-wire leads, the leads' copper (TT-612), over the grid strain per "
                    "newton at the ladder level. Span (relative, 1/K): the element's modulus "
                    "coefficient (1/E) dE/dT, its expansion, the gauge factor's coefficient and "
                    "the leads' desensitisation. Self-heating: the grid's power density against "
                    "TN-502 and the offset of a grid warmer than its substrate (-alpha_STC "
                    "dT_grid). K_obj error per kelvin (eq. 1-3) at full scale and at 10 % of it "
                    "(the zero part scales as 1/F), and what a half-bridge dummy gauge would "
                    "cancel. Units: K, N/K, 1/K, ppm/K, W.")
    add_design_arg(p)
    add_cache_args(p)
    p.add_argument("--element", type=element_number, default=None,
                   help="only this element (default: every element)")
    p.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level for K and the strain per newton (default closed-form)")
    add_output_args(p, "print one JSON object: the thermal inputs and one record per element")
    p.set_defaults(func=run)
    keep_option_defaults(p)  # a die's design: its view refuses an array's options


def run(args: argparse.Namespace) -> int:
    shown = product_view("thermal", args)  # a silicon die's design: its own figures
    if shown is not None:
        return shown
    from tactcad.studies.project_reports import thermal_record

    plan = plan_from_args(args)
    if args.element is not None:
        check_element_option(args.element, plan)
    report = thermal_record(plan, args.model, args.element)
    if args.json:
        print(dumps(report.as_json(), indent=1))
        return 0
    print(render(report))
    return 0


def render(report) -> str:
    """The report as text: the terms with their sources and one table row per element."""
    s = report.setting
    span = report.span_terms_per_K
    low, high = min(report.force_fractions), max(report.force_fractions)
    wk = report.worst_kobj
    unsourced = "" if s.modulus_tc_sourced else " (UNSOURCED: a stand-in, see its source)"
    from tactcad.design.readout_section import TN502_THIN_SECTION_W_PER_MM2

    density = 645.16 * report.grid_power_density_W_per_mm2
    above = (" ABOVE TN-502's guidance" if report.grid_power_density_W_per_mm2
             > TN502_THIN_SECTION_W_PER_MM2[1] * (1 + 1e-9) else "")
    lines = [f"thermal drift of {report.design} ({report.model}): element CTE "
             f"{s.substrate_cte_ppm_per_K:g} ppm/K, gauge STC {s.stc_ppm_per_K:.3g} ppm/K, "
             f"{report.lead_wires['leads_in_gauge_arm']} lead(s) in the gauge's arm "
             f"({s.lead_wires}), dummy gauge {'half-bridge' if s.dummy else 'none'}",
             f"  zero per K: thermal output {1e6 * report.apparent_strain_per_K:+.3g} "
             f"microstrain/K, leads {1e6 * report.lead_wires['zero_strain_per_K']:+.3g} "
             f"microstrain/K" + (" (cancelled by the dummy gauge)" if s.dummy else ""),
             f"  span per K: {1e6 * report.span_rel_per_K:+.4g} ppm/K = modulus "
             f"{1e6 * span['modulus']:+.4g}{unsourced} + expansion {1e6 * span['expansion']:+.3g} "
             f"+ gauge factor {1e6 * span['gauge_factor']:+.3g} + leads "
             f"{1e6 * span['lead_wires']:+.3g}; a dummy gauge does not cancel it",
             f"  self-heating: {1e3 * report.grid_power_W:.3g} mW in the grid "
             f"({density:.3g} W/in^2{above}; TN-502 thin sections 1-2 W/in^2), grid "
             f"+{report.self_heating_K:.3g} K above the element: an offset at switch-on "
             f"(-alpha_STC dT_grid), removed by the tare" + _against_resolution(report.records),
             f"  K_obj error per K: worst |zero| + |span| over the K_obj range with the reference "
             f"at {100 * high:g} % and at {100 * low:g} % of full scale; the zero part scales as "
             f"1/F, so full scale is the best case"
             + (f"; worst: element {wk['element']}, {100 * wk['kobj_error_rel_per_K']:.3g} %/K at "
                f"{100 * low:g} %" if wk else ""),
             f"| element | role | zero N/K | span N/K (full scale) | drift N/K | dummy cancels | "
             f"self-heating offset N | K_obj %/K at {100 * high:g} % | "
             f"K_obj %/K at {100 * low:g} % |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in report.records:
        lines.append(f"| {r['element']} | {r['role']} | {r['zero_drift_N_per_K']:+.3g} | "
                     f"{r['span_drift_N_per_K']:.3g} | {r['drift_N_per_K']:.3g} | "
                     f"{100 * r['half_bridge_cancels_rel']:.0f} % | "
                     f"{r['self_heating_offset_N']:+.3g} | "
                     f"{_pct(r['kobj_error_rel_per_K_at_full_scale'])} | "
                     f"{_pct(r['kobj_error_rel_per_K'])} |")
    lines += [f"  {k}: {v}" for k, v in s.sources.items()]
    return "\n".join(lines)


def _pct(rel: float | None) -> str:
    return "n/a" if rel is None else f"{100 * rel:.3g}"


def _against_resolution(records: list[dict]) -> str:
    """The largest self-heating offset against its element's force resolution (N), the
    figure a lab compares it with: an offset many resolutions wide must be tared warm."""
    worst = max(records, key=lambda r: abs(r["self_heating_offset_N"]))
    offset = abs(worst["self_heating_offset_N"])
    if offset == 0.0:
        return ""
    return (f"; largest {offset:.3g} N (element {worst['element']}), "
            f"{offset / worst['force_resolution_N']:.3g} x its force resolution "
            f"{worst['force_resolution_N']:.3g} N: tare after warm-up")

