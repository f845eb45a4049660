"""``tactcad calibrate``: fit and audit element calibrations (paper eq. 4-6, Table 1).

Examples::

    tactcad calibrate                                  # the paper's Table 1 as the measured input
    tactcad calibrate --data hardware/calibration_example.csv --json
    tactcad calibrate --simulate --write-csv /tmp/cal.csv --design my_array.toml
"""

from __future__ import annotations

import argparse

from tactcad.mechanics.ladder import models


#: Signal noise (V, one sigma) of a simulated rig read with an explicit ``--gain`` (no
#: read-out chain to take it from).
GAIN_SIGNAL_NOISE_V = 0.001


def simulated_noise(args: argparse.Namespace, project) -> tuple[tuple[float, str],
                                                                tuple[float, str]]:
    """((force noise N, its source), (signal noise V, its source)) of a simulated rig: the
    options where given, else the rigs' force gauge's resolution and one reading's noise
    of the design's read-out chain (:func:`tactcad.mechanics.readout_chain.noise_budget_V`),
    never another design's figures."""
    from tactcad.mechanics.readout_chain import noise_budget_V, readout_chain

    if args.noise_force is not None:
        force = (float(args.noise_force), "--noise-force")
    else:
        from tactcad.studies.verification import calibration_gauge

        gauge = calibration_gauge(project.plan).gauge
        force = (float(gauge.resolution_N), f"the force gauge {gauge.model}, read to "
                                            f"{gauge.resolution_N:g} N")
    if args.noise_signal is not None:
        signal = (float(args.noise_signal), "--noise-signal")
    elif args.gain is not None:
        signal = (GAIN_SIGNAL_NOISE_V, "the default with --gain (no read-out chain)")
    else:
        chain = readout_chain(project.plan)
        signal = (float(noise_budget_V(chain)["reading"]), "one reading of the design's "
                                                           "[readout] chain")
    return force, signal


#: The options a zeroing run (``--flat``) takes besides the common ones: the file.
FLAT_OPTIONS = frozenset({"flat", "encoding", "contact_um"})


def register(subparsers) -> None:
    """Add the ``calibrate`` sub-command."""
    from tactcad.commands import add_cache_args, add_design_arg, add_output_args
    from tactcad.commands.options import (PLOT_SUFFIXES, ascii_float, count,
                                          keep_option_defaults, number, output_file)

    p = subparsers.add_parser(
        "calibrate", help="fit K, K_v, V0 from calibration readings and audit them against the design",
        description="The paper's calibration procedure (Z steps against a force gauge in series, "
                    "eq. 4-6). Fits K, K_v, V0 and linearity per element from a CSV, LVM or TDMS "
                    "file (columns element,run,z_um,force_N,signal_V), or simulates the rig for "
                    "the design, or takes the paper's Table 1 (a design that cites the paper "
                    "only); then audits each element: as-built web, signal per newton against the "
                    "predicted gauge strain with one common gauge gain, twins of equal geometry, "
                    "series-spring error amplification. The force gauge's stiffness (N/mm) is the "
                    "data file's k_sensor_N_per_mm, else the design's rigs "
                    "(force_gauge.stiffness_N_per_mm); the paper's linearity limit applies only "
                    "to a design that cites the paper.")
    add_design_arg(p)
    add_cache_args(p)
    source = p.add_mutually_exclusive_group()
    source.add_argument("--data", metavar="FILE", default=None,
                        help="measured calibration readings: CSV (comma, semicolon or tab; decimal "
                             "point or comma; with or without a byte order mark), LabVIEW .lvm "
                             "or .tdms")
    source.add_argument("--simulate", action="store_true",
                        help="simulate the rig for the design (K and gauge strain from the ladder)")
    source.add_argument("--flat", metavar="FILE", default=None,
                        help="a zeroing run instead: each element's deflection (um) at each step "
                             "of a rigid flat pressed on every tip, CSV element,step,"
                             "deflection_um; prints each tip's height about the array's mean tip "
                             "and each unit's mismatch, which tactcad lumped --flat takes out of "
                             "K_obj")
    p.add_argument("--contact-um", type=number(0, 1e4, "um"), default=0.0, metavar="UM",
                   help="with --flat: a step counts where every element's deflection exceeds "
                        "this (um, default 0: every tip touching the flat)")
    p.add_argument("--encoding", metavar="NAME", default=None,
                   help="text encoding of a CSV or LVM --data file (default UTF-8, or what its "
                        "byte order mark says), e.g. cp1252 or latin-1")
    p.add_argument("--map", metavar="COLUMN=CHANNEL", action="append", default=[],
                   help="read a column from a CSV header, LVM or TDMS channel of another name "
                        "(repeatable, or comma-separated), e.g. "
                        "--map force_N=Dev1/ai0,signal_V=Dev1/ai1; TDMS channels as group/channel")
    p.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level for the as-built web and gauge strain (default closed-form)")
    p.add_argument("--gain", type=ascii_float, default=None, metavar="V_PER_STRAIN",
                   help="gauge gain of the simulated rig (V per unit strain of the grid's "
                        "strain, as the audit fits G); default: the design's [readout] chain's, "
                        "as tactcad readout")
    p.add_argument("--noise-force", type=number(0, 100, "N"), default=None, metavar="N",
                   help="force noise of the simulated rig (N, one sigma; default: the "
                        "resolution of the rigs' force gauge)")
    p.add_argument("--noise-signal", type=number(0, 100, "V"), default=None, metavar="V",
                   help="signal noise of the simulated rig (V, one sigma; default: the noise of "
                        f"one reading of the design's read-out chain, or {GAIN_SIGNAL_NOISE_V:g} "
                        "V with --gain)")
    p.add_argument("--seed", type=count(0, 2**32 - 1, "a seed"), default=0,
                   help="random seed of the simulated rig (default %(default)s)")
    p.add_argument("--write-csv", metavar="CSV", type=output_file(".csv"), default=None,
                   help="with --simulate: also write the readings in the calibration CSV format")
    p.add_argument("--gain-tolerance", type=number(0, 10, lo_open=True), default=0.25,
                   help="relative disagreement of signal and force data that is flagged (default 0.25)")
    p.add_argument("--plot", metavar="PNG", type=output_file(*PLOT_SUFFIXES), default=None,
                   help="with --data or --simulate: write force and signal against deflection (Fig. 4)")
    add_output_args(p, "print one JSON object")
    p.set_defaults(func=run)
    keep_option_defaults(p)  # --flat refuses the fit's and the simulation's options


def _fit_record(element: int, c) -> dict:
    from tactcad.mechanics import calibration as cal

    amp = cal.series_error_amplification(c.K_N_per_mm, c.k_sensor_N_per_mm) if c.K_N_per_mm > 0 else None
    return {"element": element, "K_N_per_mm": c.K_N_per_mm, "stderr_K_N_per_mm": c.stderr_K_N_per_mm,
            "K_v_V_per_mm": c.K_v_V_per_mm, "stderr_K_v_V_per_mm": c.stderr_K_v_V_per_mm,
            "V0_V": c.V0_V, "stderr_V0_V": c.stderr_V0_V, "F0_N": c.F0_N,
            "K_v_over_K_V_per_N": c.K_v_over_K_V_per_N,
            "linearity_force_pct": c.linearity_force_pct,
            "linearity_signal_pct": c.linearity_signal_pct,
            "max_deflection_um": float(1e3 * c.deflection_mm.max()),
            "series_amplification": None if amp is None else amp.from_k_apparent}


def run(args: argparse.Namespace) -> int:
    """Handler of ``tactcad calibrate``; returns the exit code."""
    from pathlib import Path

    from tactcad.errors import TactcadError
    from tactcad.mechanics import calibration as cal
    from tactcad.paper import calibration_audit as ca
    from tactcad.commands.finite_json import dumps

    if args.write_csv and not args.simulate:
        raise TactcadError("--write-csv = given without --simulate: allowed only with --simulate")
    if args.map and not args.data:
        raise TactcadError("--map = given without --data: allowed only with --data")
    if args.encoding and not (args.data or args.flat):
        raise TactcadError("--encoding = given without --data or --flat: allowed only with a "
                           "data file")
    if args.contact_um and not args.flat:
        raise TactcadError(f"--contact-um = {args.contact_um:g}: allowed only with --flat")
    if args.flat:
        from tactcad.commands.options import COMMON_OPTIONS, options_given

        given = options_given(args, COMMON_OPTIONS | FLAT_OPTIONS)
        if given:
            raise TactcadError(f"{given[0][0]} = {given[0][1]!r}: allowed only without --flat "
                               "(a zeroing run reads deflections; it fits and simulates "
                               "nothing)")
    if args.plot and not (args.simulate or args.data):
        raise TactcadError("--plot = given without --data or --simulate: allowed only with readings")
    from tactcad.commands import project_from_args
    from tactcad.design.requirements_section import cites_paper

    project = project_from_args(args)
    plan = project.plan
    if args.flat:
        return _run_flat(args, plan)
    # the force gauge in series: the data file's (its k_sensor comment), else the rigs'
    from tactcad.studies.verification import calibration_gauge

    rig = calibration_gauge(project.plan)
    gauge, source = rig.gauge, rig.source
    k_sensor = float(gauge.stiffness_N_per_mm)
    report: dict = {"design": plan.name, "model": args.model,
                    "force_gauge": {"model": gauge.model, "stiffness_N_per_mm": k_sensor,
                                    "source": source}}
    if args.data or args.simulate:
        if args.simulate:
            gain = args.gain
            # the paper's Z steps for its design; any other is loaded to its full-scale force
            # (the rig's, as the K_obj budget's calibration term takes it)
            force = rig.full_scale_force_N
            noise_force, noise_signal = simulated_noise(args, project)
            report["simulated_noise"] = {"force_N": noise_force[0], "force_source": noise_force[1],
                                         "signal_V": noise_signal[0],
                                         "signal_source": noise_signal[1]}
            data = ca.simulate_design_calibration(plan, args.model, gain, noise_force[0],
                                                  noise_signal[0], args.seed,
                                                  full_scale_force_N=force,
                                                  k_sensor_N_per_mm=k_sensor)
            if force is not None:
                report["full_scale_force_N"] = force
            report["input"] = "simulated"
            if gain is None:
                from tactcad.mechanics.readout_chain import readout_chain

                report["simulated_readout"] = "the design's [readout] chain, grid-averaged strain"
                report["simulated_gauge_gain_V_per_strain"] = readout_chain(plan).volts_per_strain
            else:
                report["simulated_gauge_gain_V_per_strain"] = gain
            if args.write_csv:
                Path(args.write_csv).parent.mkdir(parents=True, exist_ok=True)
                Path(args.write_csv).write_text(cal.format_calibration_csv(
                    data, (f"simulated calibration of design {plan.name}, ladder {args.model}, "
                           f"gauge gain {report['simulated_gauge_gain_V_per_strain']:g} V/strain"
                           f"{'' if gain is not None else ' (read-out chain, grid strain)'}, "
                           f"noise {noise_force[0]:g} N, "
                           f"{noise_signal[0]:g} V, seed {args.seed}",)), encoding="utf-8")
                report["written_csv"] = args.write_csv
        else:
            from tactcad.mechanics.calibration_file import read_calibration
            from tactcad.mechanics.measured_io import parse_mapping

            read = read_calibration(args.data, "--data", args.encoding,
                                    parse_mapping(args.map), k_sensor,
                                    [slot.number for slot in plan.slots])
            data, fits, info = read
            k_sensor = next(iter(data.values())).k_sensor_N_per_mm
            if k_sensor != float(gauge.stiffness_N_per_mm):  # the file states its own gauge
                report["force_gauge"] = {"model": None, "stiffness_N_per_mm": k_sensor,
                                         "source": "the data file's k_sensor_N_per_mm"}
            report["input"] = f"{info.format}:{args.data}"
            report["data_file"] = {**info.as_dict(), "read_as": info.describe()}
        if args.simulate:
            fits = ca.fit_all(data)
        report["fig4"] = [{"element": e, "z_um": d.z_travel_um.tolist(),
                           "deflection_um": (1e3 * fits[e].deflection_mm).tolist(),
                           "force_N": d.force_N.tolist(), "signal_V": d.signal_V.tolist()}
                          for e, d in data.items()]
        report["fits"] = [_fit_record(e, c) for e, c in fits.items()]
        bad = [f for f in report["fits"] if not f["K_N_per_mm"] > 0]
        if bad:
            raise cal.CalibrationError(
                f"element {bad[0]['element']}: fitted K = {bad[0]['K_N_per_mm']:.4g} N/mm: "
                "allowed > 0 (force must rise with Z travel)")
        calibrations = ca.from_fits(fits, "simulated" if args.simulate else "csv")
    else:
        if not cites_paper(plan.raw):  # Table 1's measurements belong to the paper's design
            raise TactcadError("--data (not given): allowed a data file (--data FILE) or --simulate "
                               f"for {plan.name}, which does not cite the paper (only the "
                               "paper's design is audited against its Table 1)")
        report["input"] = "table1"
        report["table1_consistency"] = ca.table1_consistency(k_sensor)
        present = {slot.number for slot in plan.slots}
        calibrations = [c for c in ca.from_table1() if c.element in present]
        report["skipped_elements"] = sorted({c.element for c in ca.from_table1()} - present)
    if args.data:  # the file's audit, as budget --calibration gives it: one function
        report["audit"] = ca.audit_file(plan, read, args.data, args.model, args.gain_tolerance)
        # a reading file that leaves out an element of the design says so
        report["elements_without_readings"] = report["audit"].pop("elements_without_readings")
    else:
        report["audit"] = ca.audit(plan, calibrations, args.model, args.gain_tolerance,
                                   k_sensor, paper_criteria=cites_paper(plan.raw))
    if args.plot:
        from tactcad.paper.figures import plot_calibration

        report["plot"] = str(plot_calibration(report["fig4"], args.plot,
                                              f"{plan.name}: calibration readings"))
    if args.json:
        print(dumps(report))
        return 0
    _print_text(report)
    return 0


def flat_report(plan, path: str, encoding: str | None, contact_um: float) -> dict:
    """What ``calibrate --flat`` reports: each tip's height about the array's mean tip
    (:func:`tactcad.in_use.tip_zeroing.tip_heights_on_flat`) and each sensing unit's
    mismatch (measuring - reference, um) with its uncertainty.

    Raises:
        tactcad.mechanics.calibration.CalibrationError: the file cannot be read (named).
        tactcad.in_use.tip_zeroing.ZeroingError: its steps give no heights (named).
    """
    from tactcad.in_use.tissue_coupling import design_units, unit_label
    from tactcad.in_use.tip_zeroing import read_tip_heights
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element

    heights, info = read_tip_heights(path, tuple(slot.number for slot in plan.slots), encoding,
                                     contact_um)
    units = []
    for unit in design_units(plan, ladder_stiffness_by_element(plan)):
        d, s = heights.mismatch_mm(unit)
        units.append({"unit": unit_label(unit), "measuring": unit[0], "reference": unit[1],
                      "mismatch_um": 1e3 * d, "sigma_um": 1e3 * s})
    return {"design": plan.name, "input": f"flat:{path}",
            "data_file": {**info.as_dict(), "read_as": info.describe()},
            "tip_heights": heights.as_json(), "units": units,
            "next": f"tactcad lumped --coupled-design DESIGN --unit M --r R --force-r F "
                    f"--flat {path}: K_obj with these heights taken out"}


def _run_flat(args: argparse.Namespace, plan) -> int:
    from tactcad.commands.finite_json import dumps

    report = flat_report(plan, args.flat, args.encoding, args.contact_um)
    if args.json:
        print(dumps(report))
        return 0
    tips = report["tip_heights"]
    print(f"design {report['design']}, zeroing on a rigid flat: {args.flat} "
          f"({report['data_file']['read_as']})")
    print(f"steps used {tips['steps_used']}, skipped {tips['steps_skipped']} (a tip out of "
          f"contact); flat flatness {tips['flatness_um']:g} um in the uncertainty")
    print("  elem  height um (+ proud)   +-")
    for e, h in tips["heights_um"].items():
        print(f"  {int(e):4d} {h:12.3f} {tips['sigma_um'][e]:13.3f}")
    print("  unit   mismatch um (measuring - reference)   +-")
    for u in report["units"]:
        print(f"  {u['unit']:>6} {u['mismatch_um']:12.3f} {u['sigma_um']:30.3f}")
    print(f"next: {report['next']}")
    return 0


def _fmt(x, spec: str) -> str:
    return "-" if x is None else format(x, spec)


def _print_text(report: dict) -> None:
    audit = report["audit"]
    print(f"design {report['design']}, input {report['input']}, ladder {report['model']}")
    if "data_file" in report:
        print(f"read as {report['data_file']['read_as']}")
    gauge = report["force_gauge"]
    print(f"force gauge in series: {gauge['model'] or 'stated'}, "
          f"{gauge['stiffness_N_per_mm']:g} N/mm ({gauge['source']})")
    if "fits" in report:
        print("fits (eq. 4-5, deflection = Z - F/K_s):")
        print("  elem     K N/mm   ±       K_v V/mm   V0 V     lin F %  lin V %  amplif.")
        for f in report["fits"]:
            print(f"  {f['element']:4d} {f['K_N_per_mm']:9.3f} {f['stderr_K_N_per_mm']:6.3f} "
                  f"{f['K_v_V_per_mm']:9.3f} {f['V0_V']:8.3f} {f['linearity_force_pct']:8.2f} "
                  f"{f['linearity_signal_pct']:8.2f} {f['series_amplification']:8.2f}")
    print(f"common gauge gain G = {_fmt(audit['gauge_gain_V_per_strain'], '.4g')} V per unit strain")
    print("  elem  K N/mm  web mm  S V/N    eps/N     S/(G eps)  K from S  amplif.")
    for r in audit["elements"]:
        print(f"  {r['element']:4d} {r['K_N_per_mm']:7.2f} {_fmt(r['web_as_built_mm'], '7.3f')} "
              f"{r['signal_per_N_V_per_N']:7.3f} {_fmt(r['grid_strain_per_N'], '9.2e')} "
              f"{_fmt(r.get('signal_ratio'), '9.2f')} {_fmt(r.get('K_implied_by_signal_N_per_mm'), '9.2f')} "
              f"{r['series_amplification']:7.2f}")
    for c in report.get("table1_consistency", []):
        if abs(c["secant_over_K"] - 1) > 0.05 or abs(c["z_travel_implied_um"] - 150) > 10:
            print(f"  Table 1 element {c['element']}: F_max/δ_max = "
                  f"{c['secant_F_max_over_delta_max_N_per_mm']:.2f} N/mm vs K {c['K_N_per_mm']}; "
                  f"Z travel implied {c['z_travel_implied_um']:.1f} um vs 150 um")
    if "plot" in report:
        print(f"plot: {report['plot']}")
    print(f"flags ({len(audit['flags'])}):")
    for f in audit["flags"]:
        print(f"  - {f['text']}")
