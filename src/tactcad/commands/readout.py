"""``tactcad readout``: signal, sensitivity and resolution of each element's gauge read-out."""

from __future__ import annotations

import argparse

from tactcad.mechanics.ladder import models
from tactcad.commands import (add_cache_args, add_design_arg, add_output_args, plan_from_args,
                              product_view, progress_from_args)
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import keep_option_defaults



def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "readout", help="per element: gauge strain over the grid, K_v, K_v/K, force and K_obj "
                        "resolution of the read-out chain",
        description="Evaluates the design's [readout] chain (gauge, quarter bridge, amplifier, "
                    "DAQ; defaults from the library gauge and the datasheets, each with its "
                    "source) for every element: the strain averaged over the gauge grid at its "
                    "bonded position over the web, the signal per newton K_v/K (V/N) and per "
                    "millimetre K_v (V/mm), the noise-limited force resolution (1 sigma) and the "
                    "K_obj resolution over the required K_obj range at the full-scale force. "
                    "closed-form and beam take the strain from bending along the profile, fem2d "
                    "and fem3d from the fem2d field. Units: V, N, mm.")
    add_design_arg(p)
    add_cache_args(p)
    p.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level for K and the strain field (default closed-form)")
    add_output_args(p, "print one JSON object: the chain, its noise and one record per element")
    p.set_defaults(func=run)
    keep_option_defaults(p)  # a die's design: its view refuses an array's options


def run(args: argparse.Namespace) -> int:
    shown = product_view("readout", args)  # a silicon die's design: its own figures
    if shown is not None:
        return shown
    from tactcad.paper.table1 import with_measured_sensitivities
    from tactcad.studies.project_reports import readout_record

    plan = plan_from_args(args)
    report = with_measured_sensitivities(
        readout_record(plan, args.model, progress_from_args(args)), plan, args.model)
    if args.json:
        print(dumps(report.as_json(), indent=1))
        return 0
    print(render(report))
    return 0


def _g(x, fmt: str = ".4g") -> str:
    return "n/a" if x is None else format(x, fmt)


def _layer_k_text(report) -> str:
    """The bonded layer's K rise over the elements, as a range in percent."""
    rel = [r["gauge_layer_k_rel"] for r in report.records]
    lo, hi = 100 * min(rel), 100 * max(rel)
    return f"{lo:.2g} %" if round(lo, 1) == round(hi, 1) else f"{lo:.2g}-{hi:.2g} %"


def _filter_text(c) -> str:
    """The anti-alias filter and the noise bandwidth it sets, in words."""
    if c.filter_order < 1:
        return f"no anti-alias filter (noise bandwidth {c.noise_bandwidth_Hz:.4g} Hz)"
    return (f"anti-alias filter {c.filter_corner_Hz:g} Hz order {c.filter_order} (noise "
            f"bandwidth {c.noise_bandwidth_Hz:.4g} Hz)")


def _assumed_text(c) -> str:
    """The filter and DAQ range choices with where they come from."""
    return "; ".join(f"{key} {getattr(c, key):g}: {c.source(key)}"
                     for key in ("filter_corner_Hz", "filter_order", "daq_range_V")
                     if c.source(key) != "design file") or "none (all stated)"


def render(report) -> str:
    """The report as text: the chain, the noise and one table row per element."""
    from tactcad.mechanics.ladder import gauge_rise_error_rel, is_meshed

    c = report.chain
    rise_error = gauge_rise_error_rel(report.model)
    how = ("its glue line and carrier meshed with the element" if is_meshed(report.model) else
           f"the {report.model} level's layer term, within {100 * rise_error:.0f} % of itself "
           "against fem3d with the layer meshed")
    lines = [f"read-out of {report.design} ({report.model}): gauge {c.gauge_name}, GF "
             f"{c.gauge_factor:g}, {c.gauge_resistance_ohm:g} ohm, grid {c.grid_length_mm:g} x "
             f"{c.grid_width_mm:g} mm, {c.bridge} bridge at {c.excitation_V:g} V, {c.amplifier} "
             f"gain {c.amplifier_gain:g}, {_filter_text(c)}, {c.daq} +/-{c.daq_range_V:g} V "
             f"{c.daq_bits} bit, {c.samples_averaged} samples averaged",
             f"  assumed (change in [readout]): {_assumed_text(c)}",
             f"  {c.volts_per_strain:.4g} V per unit strain; noise of one reading "
             f"{1e6 * report.noise_V['reading']:.1f} uV rms, of it 1/f "
             + (f"{1e6 * report.noise_V['amplifier_flicker']:.2g} uV (amplifier)"
                if not c.source("amplifier_flicker_nV_per_rtHz_at_1Hz").startswith("not stated")
                else f"none of the {c.amplifier}'s (its 1/f density not stated: left out, the "
                     "noise is low by it)")
             + f" and {1e6 * report.noise_V['gauge_flicker']:.2g} uV (foil grid, Hooge) over "
             f"{c.flicker_band_Hz[0]:.3g}-{c.flicker_band_Hz[1]:.3g} Hz (tare to reading "
             f"{c.tare_interval_s:g} s); full-scale force "
             f"{report.full_scale_force_N:.4g} N; K_obj range {report.kobj_range_N_per_mm[0]:g}-"
             f"{report.kobj_range_N_per_mm[1]:g} N/mm",
             f"  grid {1e3 * c.grid_height_mm:.0f} um above the top face (glue line + carrier, "
             f"{c.gauge_backing_modulus_MPa:g} MPa): the grid reads the face's strain x "
             "'read'; the layer stiffens the web by 'stiff.' and raises K by "
             + _layer_k_text(report) + f" ({how}); the K below carries it, as the "
             "calibration measures K with the gauge bonded",
             "| element | role | K N/mm | face mean strain/N (as cut) | its error | read | "
             "stiff. | grid strain/N | face mean/centre (as cut) | K_v/K V/N | K_v V/mm | force res. N | "
             "K_obj res. |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in report.records:
        res = "n/a" if r["kobj_resolution_rel"] is None else f"{100 * r['kobj_resolution_rel']:.2f} %"
        flag = " (outside fit)" if r["strain_outside_fit"] else ""
        lines.append(f"| {r['element']} | {r['role']} | {r['stiffness_N_per_mm']:.4g} | "
                     f"{r['face_mean_strain_as_cut_per_N']:.4g} | {100 * r['strain_error_rel']:.2g} %"
                     f"{flag} | {r['grid_read_factor']:.3f} | "
                     f"{100 * r['gauge_stiffening_rel']:.2g} % | "
                     f"{r['grid_strain_per_N']:.4g} | {r['face_mean_over_centre_as_cut']:.3f} | "
                     f"{r['sensitivity_V_per_N']:.4g} | {r['k_v_V_per_mm']:.4g} | "
                     f"{r['force_resolution_N']:.2g} | {res} |")
    for r in report.records:
        if r["daq_range_used_rel"] > 1:
            lines.append(f"  element {r['element']}: the full-scale signal "
                         f"{r['full_scale_signal_V']:.3g} V exceeds the DAQ range "
                         f"+/-{c.daq_range_V:g} V: lower readout.amplifier_gain or raise "
                         f"readout.daq_range_V")
    lines += [f"  {note}" for note in report.fit_range_notes()]
    arr = report.array_kobj_resolution_rel
    lines.append(f"array K_obj resolution (worst over the range, best unit): "
                 f"{'n/a' if arr is None else f'{100 * arr:.2f} %'}")
    if report.table1 is not None and report.table1.get("elements"):
        t = report.table1
        lines += ["Table 1 (measured) against the prediction:",
                  "| element | K_v meas. | K_v pred. | ratio | K_v/K meas. | K_v/K pred. | ratio | "
                  "gain that reconciles |", "| --- | --- | --- | --- | --- | --- | --- | --- |"]
        for r in report.records:
            if r.get("table1_k_v_V_per_mm") is None:
                continue
            lines.append(f"| {r['element']} | {r['table1_k_v_V_per_mm']:g} | {r['k_v_V_per_mm']:.3g} "
                         f"| {r['table1_k_v_ratio']:.2f} | {r['table1_sensitivity_V_per_N']:g} | "
                         f"{r['sensitivity_V_per_N']:.3g} | {r['table1_sensitivity_ratio']:.2f} | "
                         f"{r['reconciling_gain']:.0f} |")
        lines.append(f"  fitted {_g(t['fitted_volts_per_strain'])} V per unit strain (assumed "
                     f"{t['assumed_volts_per_strain']:.4g}): gain "
                     f"{_g(t['fitted_gain_at_assumed_excitation'], '.0f')} at the assumed excitation")
        lines.append(f"  ratio spread {100 * t['sensitivity_ratio_rel_std']:.0f} % (1 sigma); at each "
                     f"element's as-built web {100 * t['as_built_web_ratio_rel_std']:.0f} %, mean "
                     f"{t['as_built_web_ratio_mean']:.2f} (gain {t['gain_at_as_built_webs']:.0f}); "
                     f"one gain through the signals there: "
                     f"{_g(t['fitted_volts_per_strain_as_built'])} V per unit strain, "
                     "as `tactcad calibrate` fits it")
    elif report.table1 is not None and report.table1.get("not_applicable"):
        lines.append(f"Table 1 comparison: not applicable ({report.table1['not_applicable']})")
    return "\n".join(lines)
