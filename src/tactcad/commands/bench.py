"""``tactcad bench``: speed benchmarks.

* ``bench export``: a cold ``tactcad export`` (every part and scene) in a
  fresh subprocess, the scene writer alone, and the interference check of
  the largest scene: manifold3d fast path, OpenCascade confirmation, and an
  OpenCascade-only check for comparison.
* ``bench stiffness``: the stiffness estimators, provided by
  ``tactcad.benchmarks.stiffness_bench.main(args)`` when that module is installed.
* ``bench die``: a silicon die's beams, each stiffness level's cost and K error against
  fem3d on the frame (:mod:`tactcad.products.silicon_die.benchmarks.die_bench`).
* ``bench atlas``: the design atlas on one and two workers, and its agreement with
  ``design`` (:mod:`tactcad.benchmarks.atlas_bench`).
* ``bench closed-form``, ``bench montecarlo``, ``bench sweep``: the design
  tools at scale (:mod:`tactcad.benchmarks.bench_scale`).
"""

from __future__ import annotations

import argparse
import importlib
import os

from tactcad.commands import (add_design_arg, add_output_args, plan_from_args, progress_from_args,
                               project_from_args)
from tactcad.commands.options import count, material_grade_name, number, output_file, output_folder
from tactcad.commands.finite_json import dumps
from tactcad.mechanics.ladder import models
from tactcad.mechanics.modal_ladder import modal_models

COLD_GOAL_S = 6.0  # on two cores
WARM_GOAL_S = 1.5
ONE_CHANGE_GOAL_OF_COLD = 0.5  # one changed arm: at most this fraction of the cold export
MESH_GOAL_S = 1.0
REVIEW_SIZE_GOAL_MB = 15.0  # the review page of the default design
REVIEW_FIRST_FRAME_GOAL_S = 3.0
MAX_LOAD_CLIENTS = 200  # simulated reviewers of bench watch's load test, at most
MAX_LOAD_SECONDS = 600.0  # its duration at most (s)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("bench", help="speed benchmarks (export, stiffness, modal, die, atlas, closed-form, montecarlo, sweep)",
                       description="Print timings. Goals on two cores: cold export <= 6 s, "
                                   "no-change re-export <= 1.5 s, one changed arm <= 0.5 x "
                                   "the cold export, each "
                                   "distinct part built once; interference of the largest scene "
                                   "on meshes <= 1 s; closed form >= 1e7 evaluations/s, "
                                   "10 000-sample Monte Carlo <= 1 s, fem3d sweep on two workers "
                                   ">= 1.7x one worker.")
    bsub = p.add_subparsers(dest="bench", metavar="WHAT")
    e = bsub.add_parser("export", help="cold, warm and one-change export, and the interference "
                                       "check of the largest scene (manifold3d vs OpenCascade)")
    add_design_arg(e)
    add_output_args(e, "print the figures as JSON: cold_s, warm_s, one_change_s, builds, "
                        "distinct_parts (and the job counts)")
    e.set_defaults(func=run_export)
    s = bsub.add_parser("stiffness", help="stiffness estimator benchmarks (tactcad.benchmarks.stiffness_bench)")
    add_design_arg(s)
    s.add_argument("--out", metavar="DIR", type=output_folder, default=None,
                   help="folder for the report files (default: the benchmark's own)")
    s.add_argument("--models", nargs="+", metavar="MODEL", default=None,
                   help="estimators to run (default: all)")
    add_output_args(s, "print one JSON object: throughput and the summary per level")
    s.set_defaults(func=run_stiffness)
    md = bsub.add_parser("modal", help="modal levels' cost and first-frequency error against "
                                       "fem3d (tactcad.benchmarks.modal_bench)")
    add_design_arg(md)
    md.add_argument("--designs", choices=("own", "corners", "all"), default="all",
                    help="the design's shortest and longest arm, the design domain's four "
                         "corners, or both (default %(default)s; fem3d takes 10-60 s each)")
    md.add_argument("--models", nargs="+", metavar="MODEL", choices=modal_models(), default=None,
                    help="modal levels to run (default: all; fem3d always, as the reference)")
    add_output_args(md, "print one JSON object: every design's figures and the summary per level")
    md.set_defaults(func=run_modal_bench)
    x = bsub.add_parser("crosstalk", help="cost and error of each crosstalk level "
                                          "(tactcad.benchmarks.crosstalk_bench)")
    add_design_arg(x)
    add_output_args(x, "print one JSON object: inputs_s and per level solve_s, crosstalk_rel, "
                       "error_estimate_rel, vs_last_level_rel, asymmetry_rel")
    x.set_defaults(func=run_crosstalk)
    dd = bsub.add_parser("die", help="a silicon die's beams: the cost and K error of each "
                                     "stiffness level against fem3d on the frame "
                                     "(tactcad.products.silicon_die.benchmarks.die_bench)")
    add_design_arg(dd)
    dd.add_argument("--beams", choices=("rows", "domain", "all"), default="all",
                    help="the die's two rows, four beams at the corners of the sections its "
                         "design makes, or both (default %(default)s; fem3d takes half a minute to "
                         "a minute and a half a beam)")
    add_output_args(dd, "print one JSON object: every beam's K per level and the summary per "
                        "level")
    dd.set_defaults(func=run_die_bench)
    dj = bsub.add_parser("design-jaw", help="design --jaw on the grasper case at three forces "
                                           "(goal: an answer <= 30 s)")
    add_output_args(dj, "print one JSON object: each force's seconds and answer")
    dj.set_defaults(func=run_design_jaw)
    at = bsub.add_parser("atlas", help="tactcad atlas on one worker and on two: points/s, "
                                       "the scaling (goal >= 1.7x) and the agreement with "
                                       "tactcad design on drawn records")
    at.add_argument("--jaw", default="5", metavar="CLASS|FILE",
                    help="the jaw, as `tactcad atlas --jaw` takes it (default %(default)s: the "
                         "die alone)")
    at.add_argument("--points", type=count(2, 100_000, "target points"), default=64,
                    metavar="N", help="target points of the sample (default %(default)s)")
    at.add_argument("--material", type=material_grade_name, action="append", default=None,
                    metavar="GRADE", help="a comb material judged (repeat for more; default: "
                                          "every grade of the library)")
    at.add_argument("--agree", type=count(0, 1000, "records checked"), default=4, metavar="N",
                    help="records drawn and run through `tactcad design` (default "
                         "%(default)s; each costs seconds, a comb's refusal minutes)")
    at.add_argument("--batch", type=count(1, 10_000, "points per task"), default=None,
                    metavar="N", help="target points per Dask task (default: as `tactcad "
                                      "atlas` chooses for the cluster's workers)")
    at.add_argument("--seed", type=count(0, 2**32 - 1, "a seed"), default=0,
                    help="seed of the sample and of the draw (default %(default)s)")
    add_output_args(at, "print one JSON object: seconds, points/s, scaling, agreement, goals")
    at.set_defaults(func=run_atlas_bench)
    c = bsub.add_parser("closed-form", help="corrected closed-form K evaluations/s (goal >= 1e7)")
    add_design_arg(c)
    add_output_args(c, "print one JSON object: evaluations per second and the goal")
    c.set_defaults(func=run_closed_form)
    m = bsub.add_parser("montecarlo", help="10 000-sample tolerance Monte Carlo (goal <= 1 s)")
    add_design_arg(m)
    m.add_argument("--samples", type=count(1, 10**7, "samples"), default=10_000,
                   help="Monte Carlo samples (default %(default)s)")
    add_output_args(m, "print one JSON object: first and best-of-3 seconds and the goal")
    m.set_defaults(func=run_montecarlo)
    w = bsub.add_parser("sweep", help="fem3d sweep on two Dask workers vs one (goal >= 1.7x)")
    add_design_arg(w)
    w.add_argument("--webs", type=number(0, 100, "mm", lo_open=True), nargs="+", default=[0.25, 0.4], metavar="MM",
                   help="web thicknesses of the sweep (mm; default %(default)s)")
    w.add_argument("--arms", type=number(0, 1000, "mm", lo_open=True), nargs="+", default=[4.0, 8.0], metavar="MM",
                   help="arm lengths of the sweep (mm; default %(default)s)")
    w.add_argument("--model", default="fem3d", choices=("beam", "fem2d", "fem3d"),
                   help="ladder level of every point (default %(default)s)")
    add_output_args(w, "print one JSON object: one- and two-worker seconds, speed-up, goal")
    w.set_defaults(func=run_sweep)
    r = bsub.add_parser("review", help="the review page: size and time to first frame in "
                                       "headless Chromium (goals <= 15 MB, <= 3 s)")
    add_design_arg(r)
    r.add_argument("--out", metavar="DIR", type=output_folder, default=None,
                   help="an export holding review/index.html (default: export to a temporary "
                        "folder first)")
    r.add_argument("--screenshot", metavar="PNG", type=output_file(), default=None,
                   help="also save the page's first screen as this PNG")
    add_output_args(r, "print one JSON object: bytes, first_frame_s, wall_s, goals")
    r.set_defaults(func=run_review)
    wa = bsub.add_parser("watch", help="tactcad watch: save -> 3D view shown, save -> every "
                                      "file current (goals <= 2 s, <= 4 s), then a loopback "
                                      "load of simulated reviewers during edits (goal: 0 "
                                      "errors, p99 <= 250 ms)")
    add_design_arg(wa)
    wa.add_argument("--rounds", type=count(0, 50, "one-arm edits in Chromium"), default=5,
                    metavar="N",
                    help="one-arm edits timed in headless Chromium after a warm-up edit, "
                         "0 ... 50; 0: none, no browser needed (default: 5)")
    wa.add_argument("--clients", type=count(0, MAX_LOAD_CLIENTS, "simulated reviewers"),
                    default=40, metavar="N",
                    help=f"simulated reviewers' browsers asking the watch on 127.0.0.1 at "
                         f"once during the load test, 0 ... {MAX_LOAD_CLIENTS}; 0: no load "
                         f"test (default: 40)")
    wa.add_argument("--load-seconds", type=number(0, MAX_LOAD_SECONDS, "s", lo_open=True),
                    default=30.0, metavar="S",
                    help=f"duration of the load test in seconds, > 0 ... {MAX_LOAD_SECONDS:g}, "
                         f"one-arm edits saved one after the other meanwhile (default: 30 s)")
    add_output_args(wa, "print one JSON object: first_update_s, full_update_s (medians), the "
                         "rounds, goals, load average, and under load: clients, seconds, "
                         "edits, requests, errors, p50_ms, p95_ms, p99_ms, max_ms, per route")
    wa.set_defaults(func=run_watch)
    ws = bsub.add_parser("watch-stop", help="tactcad watch stopped at random moments (Ctrl-C "
                                            "or SIGTERM; start-up, first export, an edit's "
                                            "export, serving): each must end within 2 s "
                                            "with exit 0 and no traceback")
    add_design_arg(ws)
    ws.add_argument("--rounds", type=count(1, 200, "watches stopped"), default=20, metavar="N",
                    help="watches started and stopped once each, 1 ... 200 (default: 20)")
    ws.add_argument("--latest", type=number(0, 600, "s"), default=12.0, metavar="S",
                    help="the latest moment after the start a start-up round stops at, "
                         "0 ... 600 s (default: 12 s)")
    ws.add_argument("--seed", type=count(0, 2**31 - 1, "seed"), default=0, metavar="N",
                    help="seed of the random moments (default: 0)")
    add_output_args(ws, "print one JSON object: every round (phase, signal, moment_s, "
                        "ended_s, exit_code, traceback, left_behind, good) and good of rounds")
    ws.set_defaults(func=run_watch_stop)
    v = bsub.add_parser("verify", help="verify: each ladder level's matrix timed, then "
                                       "--model auto; its seconds and verdicts against the "
                                       "top level's")
    add_design_arg(v)
    v.add_argument("--models", nargs="+", choices=models(), default=None, metavar="MODEL",
                   help="the ladder to time and climb, cheapest first (default: every level)")
    add_output_args(v, "print one JSON object: seconds and verdicts per level and of auto")
    v.set_defaults(func=run_verify)
    c = bsub.add_parser("check", help="check on a current export: whole-process seconds "
                                      "(median of --runs) and each group's (goal <= 5 s); "
                                      "the start-up, tactcad --version (goal <= 0.3 s)")
    add_design_arg(c)
    c.add_argument("--runs", type=count(1, 20, "whole-process runs"), default=3, metavar="N",
                   help="whole-process runs of tactcad check, 1 ... 20 (default: 3)")
    c.add_argument("--out", metavar="DIR", type=output_folder, default=None,
                   help="export folder to make current and check (default: a temporary one)")
    add_output_args(c, "print one JSON object: export_s, runs_s, median_s, groups, goal_s, "
                       "startup_s, startup_goal_s")
    c.set_defaults(func=run_check)
    p.set_defaults(func=lambda args: (p.print_help(), 2)[1])


def run_design_jaw(args: argparse.Namespace) -> int:
    from tactcad.benchmarks.design_jaw_bench import design_jaw_figures, design_jaw_lines
    from tactcad.design.array_plan import EXAMPLES, read_toml
    from tactcad.design.construction_registry import construction

    comb = construction("monolithic-comb")
    figures = design_jaw_figures(read_toml(EXAMPLES / comb.jaw_template, "design file"))
    print(dumps(figures) if args.json else "\n".join(design_jaw_lines(figures)))
    return 0


def run_check(args: argparse.Namespace) -> int:
    """Time ``tactcad check`` on a current export (:mod:`tactcad.benchmarks.check_bench`)."""
    from tactcad.benchmarks.check_bench import check_figures, check_table
    from tactcad.commands import load_from_args

    argv = ([] if args.design is None else ["--design", args.design]) + [
        a for item in (getattr(args, "overrides", None) or ()) for a in ("--set", item)]
    report = check_figures(argv, load_from_args(args), args.out, args.runs)
    print(dumps(report, indent=1) if args.json else check_table(report))
    return 0


def run_verify(args: argparse.Namespace) -> int:
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.benchmarks.verify_bench import trade_table, verify_trade
    from tactcad.studies.strength_studies import element_stress

    plan = plan_from_args(args)
    report = verify_trade(plan, array_envelope_mm(plan), element_stress,
                          tuple(args.models or models()))
    print(dumps(report, indent=1) if args.json else trade_table(report))
    return 0


def run_watch(args: argparse.Namespace) -> int:
    """Time one-arm edits under ``tactcad watch`` and load its server (see
    :mod:`tactcad.benchmarks.bench_watch`).

    Raises:
        DesignError: ``--rounds 0`` with ``--clients 0`` (nothing to measure); a refused design.
        BrowserMissing: ``--rounds`` > 0 without Chromium or Playwright.
        TimeoutError: the watch did not answer in time.
    """
    from pathlib import Path

    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.errors import DesignError
    from tactcad.benchmarks.bench_scale import load_average
    from tactcad.benchmarks.bench_watch import watch_figures

    if args.rounds == 0 and args.clients == 0:
        raise DesignError("--rounds", 0, "1 ... 50 when --clients is 0 (nothing to measure)")
    plan_from_args(args)  # a refused design stops here, not in the watch process
    report = progress_from_args(args)
    from tactcad.commands.watch import watched_files

    figures = watch_figures(watched_files(Path(args.design) if args.design else DEFAULT_DESIGN),
                            args.rounds, log=report, clients=args.clients,
                            load_seconds=args.load_seconds)
    figures["load_average"] = load_average()
    if args.json:
        print(dumps(figures))
        return 0
    print(f"tactcad bench watch ({figures['cpus']} CPUs, load average {figures['load_average']}):")
    if args.rounds:
        print(f"  {args.rounds} one-arm edits, medians:")
        print(f"  save -> 3D view shows the edit   {figures['first_update_s']:6.2f} s   goal <= "
              f"{figures['first_goal_s']:g} s")
        print(f"  save -> every file current       {figures['full_update_s']:6.2f} s   goal <= "
              f"{figures['full_goal_s']:g} s")
    if args.clients:
        for line in load_lines(figures["load"]):
            print(line)
    return 0


def run_watch_stop(args: argparse.Namespace) -> int:
    """Stop ``tactcad watch`` at random moments (:mod:`tactcad.benchmarks.watch_stop`);
    exit 1 when a round was not good.

    Raises:
        TimeoutError: an edit round's first export was not current in time.
    """
    from pathlib import Path

    from tactcad.benchmarks.watch_stop import stop_figures
    from tactcad.commands.watch import watched_files
    from tactcad.design.array_plan import DEFAULT_DESIGN

    plan_from_args(args)  # a refused design stops here, not in the watch process
    files = watched_files(Path(args.design) if args.design else DEFAULT_DESIGN)
    figures = stop_figures(files, args.rounds, args.latest, args.seed,
                           log=progress_from_args(args))
    if args.json:
        print(dumps(figures))
    else:
        print(f"tactcad bench watch-stop ({figures['cpus']} CPUs): {figures['good']} of "
              f"{figures['of']} watches ended within {figures['goal_s']:g} s of the stop "
              f"with exit 0, a 'stopped' line, no traceback and no process left; slowest "
              f"{figures['slowest_s']} s")
    return 0 if figures["good"] == figures["of"] else 1


def load_lines(load: dict) -> list[str]:
    """The load test's figures (:func:`tactcad.benchmarks.watch_load.load_summary`) as lines."""
    flag = "ok" if load["met"] else "not met"
    kinds = ", ".join(f"{k} {n}" for k, n in sorted(load["error_kinds"].items()))
    lines = [f"  load: {load['clients']} clients for {load['seconds']:g} s, {load['edits']} "
             f"one-arm edits saved meanwhile: {load['requests']} requests, {load['errors']} "
             f"errors" + (f" ({kinds})" if kinds else ""),
             f"  latency p50 {load['p50_ms']:.1f} ms, p95 {load['p95_ms']:.1f} ms, p99 "
             f"{load['p99_ms']:.1f} ms, max {load['max_ms']:.1f} ms   goal: 0 errors, p99 <= "
             f"{load['p99_goal_ms']:g} ms: {flag}"]
    if load.get("watch_export_s"):
        import statistics

        own = load["watch_export_s"]
        lines.append(f"  the watch's own updates meanwhile: median {statistics.median(own):.2f} s, "
                     f"longest {max(own):.2f} s ({len(own)} finished)")
    for route, r in load["routes"].items():
        lines.append(f"    {route:<7} {r['requests']:6d} requests   p50 {r['p50_ms']:7.1f} ms   "
                     f"p99 {r['p99_ms']:7.1f} ms   max {r['max_ms']:7.1f} ms")
    return lines


def run_review(args: argparse.Namespace) -> int:
    """Open the review page from ``file://`` offline in Chromium; print its size and load time."""
    import tempfile
    from pathlib import Path

    from tactcad.checks.review_browser import measure_page
    from tactcad.export.review_page import REVIEW_PAGE
    from tactcad.benchmarks.bench_scale import load_average

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(args.out or tmp)
        if not (out / REVIEW_PAGE).is_file():
            from tactcad.export.run import export

            export(project_from_args(args), out, log=lambda s: None)
        m = measure_page(out / REVIEW_PAGE, Path(args.screenshot) if args.screenshot else None)
    mb = m.bytes / 1e6
    figures = {"bytes": m.bytes, "first_frame_s": round(m.first_frame_s, 3),
               "wall_s": round(m.wall_s, 3), "instances": m.instances,
               "size_goal_mb": REVIEW_SIZE_GOAL_MB, "first_frame_goal_s": REVIEW_FIRST_FRAME_GOAL_S,
               "met": mb <= REVIEW_SIZE_GOAL_MB and m.first_frame_s <= REVIEW_FIRST_FRAME_GOAL_S,
               "load_average": load_average()}
    if args.json:
        print(dumps(figures))
        return 0
    print(f"tactcad bench review: {REVIEW_PAGE} {mb:.1f} MB (goal <= {REVIEW_SIZE_GOAL_MB:g} MB), "
          f"first frame {m.first_frame_s:.2f} s after navigation (goal <= "
          f"{REVIEW_FIRST_FRAME_GOAL_S:g} s; {m.wall_s:.2f} s wall), {m.instances} parts in view; "
          f"headless Chromium, software WebGL; load average {load_average()}")
    return 0


def run_stiffness(args: argparse.Namespace) -> int:
    try:
        module = importlib.import_module("tactcad.benchmarks.stiffness_bench")
    except ModuleNotFoundError as exc:
        if exc.name not in ("tactcad.benchmarks.stiffness_bench", "tactcad.studies"):
            raise
        print("tactcad bench stiffness: not available in this build "
              "(no tactcad.benchmarks.stiffness_bench)")
        return 0
    return int(module.main(args, plan=plan_from_args(args)) or 0)


def run_modal_bench(args: argparse.Namespace) -> int:
    from tactcad.benchmarks.modal_bench import main

    return int(main(args, plan=plan_from_args(args)) or 0)


def run_die_bench(args: argparse.Namespace) -> int:
    from tactcad.products.silicon_die.benchmarks.die_bench import main
    from tactcad.commands.die import die_design_of
    from tactcad.products.silicon_die.commands.die_views import _planned
    from tactcad.errors import DesignError

    design = die_design_of(args)
    if design is None:
        raise DesignError("--design", getattr(args, "design", None), "a silicon die's design file",
                          "bench die times a die's beams (a file with a [die] table)")
    return int(main(args, _planned(design, args).plan) or 0)


def run_crosstalk(args: argparse.Namespace) -> int:
    from tactcad.benchmarks.crosstalk_bench import main

    return int(main(args, plan_from_args(args)) or 0)


def run_atlas_bench(args: argparse.Namespace) -> int:
    """``bench atlas``: points/s on one and two workers, the scaling, the agreement with
    ``design`` (:mod:`tactcad.benchmarks.atlas_bench`)."""
    from tactcad.benchmarks.atlas_bench import atlas_bench_figures, atlas_bench_lines
    from tactcad.benchmarks.bench_scale import load_average
    from tactcad.commands.atlas import jaw_atlas
    from tactcad.studies.design_atlas import checked_ranges

    columns = checked_ranges({})["columns"]
    atlas = jaw_atlas(args.jaw, args.material, (int(columns[0]), int(columns[1])))
    figures = atlas_bench_figures(atlas, args.points, args.agree, args.batch, args.seed,
                                  say=progress_from_args(args))
    if args.json:
        print(dumps({**figures, "load_average": load_average()}))
        return 0
    print("\n".join(atlas_bench_lines(figures, load_average())))
    return 0


def run_closed_form(args: argparse.Namespace) -> int:
    import numpy as np

    from tactcad.benchmarks.bench_scale import (CLOSED_FORM_GOAL_PER_S, closed_form_rate,
                                                load_average)

    plan = plan_from_args(args)
    one, k_one = closed_form_rate(plan, threads=1)
    two, k_two = closed_form_rate(plan, threads=2)
    same = bool(np.array_equal(k_one, k_two))
    met = two >= CLOSED_FORM_GOAL_PER_S
    if args.json:
        print(dumps({"evaluations_per_s": one, "evaluations_per_s_two_threads": two,
                     "same_values": same, "goal_per_s": CLOSED_FORM_GOAL_PER_S,
                     "goal_cores": 2, "met": met, "cores": os.cpu_count(),
                     "load_average": load_average()}))
        return 0
    print(f"tactcad bench closed-form: corrected K evaluations/s (vectorised): one thread "
          f"{one:,.0f}, two threads {two:,.0f} ({two / one:.2f} x; the same K to the bit: "
          f"{'yes' if same else 'NO'})   goal >= {CLOSED_FORM_GOAL_PER_S:.0e} on two cores: "
          f"{'ok' if met else 'under goal'}   cores {os.cpu_count()}, load average "
          f"{load_average()}")
    return 0 if same else 1


def run_montecarlo(args: argparse.Namespace) -> int:
    from tactcad.benchmarks.bench_scale import MONTE_CARLO_GOAL_S, load_average, monte_carlo_times

    first, best = monte_carlo_times(plan_from_args(args), args.samples)
    flag = "ok" if best <= MONTE_CARLO_GOAL_S else "over goal"
    if args.json:
        print(dumps({"samples": args.samples, "first_s": first, "best_of_3_s": best,
                     "goal_s": MONTE_CARLO_GOAL_S, "met": best <= MONTE_CARLO_GOAL_S,
                     "load_average": load_average()}))
        return 0
    print(f"tactcad bench montecarlo: {args.samples} samples at the closed form: first "
          f"{first:.3f} s, best of 3 {best:.3f} s   goal <= {MONTE_CARLO_GOAL_S:g} s: {flag}   "
          f"load average {load_average()}")
    return 0


def run_sweep(args: argparse.Namespace) -> int:
    from tactcad.benchmarks.bench_scale import SWEEP_SPEEDUP_GOAL, fem3d_sweep_timing, load_average

    plan = plan_from_args(args)
    progress_from_args(args)(f"tactcad bench sweep: {args.model} on "
                             f"{len(args.webs) * len(args.arms)} designs, load average before "
                             f"{load_average()}")
    t = fem3d_sweep_timing(plan, args.webs, args.arms, args.model)
    flag = "ok" if t.speedup >= SWEEP_SPEEDUP_GOAL else "under goal"
    if args.json:
        print(dumps({"model": args.model, "designs": len(args.webs) * len(args.arms),
                     "one_worker_s": t.one_worker_s, "two_workers_s": t.two_workers_s,
                     "speedup": t.speedup, "goal": SWEEP_SPEEDUP_GOAL,
                     "met": t.speedup >= SWEEP_SPEEDUP_GOAL, "same_numbers": t.same_numbers,
                     "load_average_after": load_average()}))
        return 0
    print(f"  1 worker {t.one_worker_s:.1f} s, 2 workers {t.two_workers_s:.1f} s: speed-up "
          f"{t.speedup:.2f}x   goal >= {SWEEP_SPEEDUP_GOAL:g}x: {flag}; same K both runs: "
          f"{t.same_numbers}; load average after {load_average()}")
    return 0


def run_export(args: argparse.Namespace) -> int:
    import json
    import tempfile

    from tactcad.benchmarks.bench_scale import load_average

    project = project_from_args(args)
    plan = project.plan
    say = (lambda s: None) if args.json else print
    say(f"tactcad bench export: design {plan.name}, {os.cpu_count()} CPUs, "
        f"load average {load_average()}")
    with tempfile.TemporaryDirectory() as tmp:
        figures = export_figures(plan, args, tmp)
    if args.json:
        print(json.dumps(figures, indent=1))
        return 0
    for key, label, goal in (("cold_s", "cold (empty cache, new process)", COLD_GOAL_S),
                             ("warm_s", "warm (no change)", WARM_GOAL_S)):
        flag = "ok" if figures[key] <= goal else "over goal"
        print(f"  {label:<34} {figures[key]:6.2f} s   goal <= {goal:g} s: {flag}")
    share = figures["one_change_s"] / figures["cold_s"]
    flag = "ok" if share <= ONE_CHANGE_GOAL_OF_COLD else "over goal"
    print(f"  {'one arm length changed':<34} {figures['one_change_s']:6.2f} s   "
          f"{share:.2f} x cold, goal <= {ONE_CHANGE_GOAL_OF_COLD:g} x cold: {flag}")
    ok = "ok" if figures["builds"] == figures["distinct_parts"] else "over goal"
    print(f"  solid builds in the cold run       {figures['builds']:6d}     distinct parts "
          f"{figures['distinct_parts']}: {ok}")
    print(f"  one change: {figures['one_change_jobs_run']} of {figures['jobs']} jobs rebuilt")
    _bench_interference(project)
    return 0


def compile_package_bytecode() -> None:
    """Write tactcad's bytecode cache, as installing the wheel does, so the
    timed commands read it (a shell with ``PYTHONDONTWRITEBYTECODE`` set would
    otherwise have each new process compile every module it imports, about
    0.4 s of a warm export)."""
    import compileall
    from pathlib import Path

    import tactcad

    compileall.compile_dir(Path(tactcad.__file__).parent, quiet=2)


def export_figures(plan, args: argparse.Namespace, tmp: str) -> dict:
    """Wall times of ``tactcad export`` in new processes: cold (empty store),
    warm (same design again) and after one arm length changed (one more
    ``--set``), with the cold run's solid builds and the design's distinct parts."""
    import json
    import subprocess
    import sys
    import time
    from pathlib import Path

    store, out = Path(tmp) / "store", Path(tmp) / "out"
    arms = [s.geometry.arm_length_mm for s in plan.slots]
    arms[-1] = arms[-1] + 0.5 if arms[-1] + 0.5 <= 8.0 else arms[-1] - 0.5
    given = (["--design", args.design] if args.design else []) + [
        a for text in args.overrides for a in ("--set", text)]
    one_change = ["--set", "arms.lengths_mm=[" + ", ".join(f"{a!r}" for a in arms) + "]"]

    def run(extra: list[str]) -> tuple[float, dict]:
        cmd = [sys.executable, "-m", "tactcad.cli", "export", "--json", "--cache", str(store),
               "--out", str(out), *given, *extra]
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if proc.returncode != 0:
            raise RuntimeError(f"tactcad export failed: {proc.stderr[-2000:]}")
        return wall, json.loads(proc.stdout)

    compile_package_bytecode()
    cold, first = run([])
    warm, _ = run([])
    one, last = run(one_change)
    return {"cold_s": round(cold, 3), "warm_s": round(warm, 3), "one_change_s": round(one, 3),
            "builds": first["builds"], "distinct_parts": first["distinct_parts"],
            "jobs": first["jobs_run"] + first["jobs_reused"],
            "one_change_jobs_run": last["jobs_run"], "cpus": os.cpu_count()}


def _bench_interference(project) -> None:
    import time

    from tactcad.checks.interference import check_interference
    from tactcad.checks.mesh_interference import check_mesh_interference
    from tactcad.assembly.rig_models import scene_names
    from tactcad.assembly.scene_solver import build_scene
    from tactcad.checks.scene_checks import placed_shapes
    from tactcad.solids.cache import PartCache

    cache = PartCache(project.plan)
    largest = None
    for name in scene_names(project):
        scene, solids = build_scene(project, name, cache)
        if largest is None or len(scene.instances) > len(largest[0].instances):
            largest = (scene, solids)
    scene, solids = largest
    placed = placed_shapes(scene, solids)
    part_of = {i.name: i.part for i in scene.instances}
    locs = {i.name: i.location for i in scene.instances}
    t0 = time.perf_counter()
    fast = check_mesh_interference(placed, scene.contacts, part_of, solids, locs, confirm=False)
    t_fast = time.perf_counter() - t0
    t0 = time.perf_counter()
    full = check_mesh_interference(placed, scene.contacts, part_of, solids, locs, confirm=True)
    t_full = time.perf_counter() - t0
    t0 = time.perf_counter()
    occ = check_interference(placed, scene.contacts)
    t_occ = time.perf_counter() - t0
    ok = all(r.passed for r in full.results) == all(r.passed for r in occ)
    flag = "ok" if t_fast <= MESH_GOAL_S else "over goal"
    print(f"  interference, largest scene {scene.name} ({len(placed)} parts, "
          f"{len(scene.contacts)} declared contacts):")
    print(f"    manifold3d fast path (tessellate + {fast.pairs_tested} pairs): {t_fast:6.2f} s   "
          f"goal <= {MESH_GOAL_S:g} s: {flag}")
    print(f"    + OpenCascade confirmation of {full.pairs_confirmed} pairs (contacts, near, "
          f"overlapping): {t_full:6.2f} s in all ({full.confirm_seconds:.2f} s exact)")
    print(f"    OpenCascade only (every pair with overlapping boxes): {t_occ:6.2f} s; "
          f"verdicts agree: {ok}")
