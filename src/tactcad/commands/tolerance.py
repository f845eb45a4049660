"""``tactcad tolerance``: Monte Carlo of manufacturing tolerances (K, R, K_obj)."""

from __future__ import annotations

import argparse
import json

from tactcad.commands import add_design_arg, add_output_args, plan_from_args, product_view
from tactcad.commands.options import ascii_integer, count, keep_option_defaults, number
from tactcad.errors import DesignError
from tactcad.products.silicon_die.studies.die_tolerance import DIE_SAMPLES_RANGE
from tactcad.studies.tolerance_montecarlo import (
    MONTE_CARLO_SAMPLES, MONTE_CARLO_SEED, SAMPLES_RANGE)

#: ``--seed``'s range (a NumPy seed).
SEED_RANGE = (0, 2**32 - 1)
#: ``--reference``'s range (an element number; the design's reference elements checked after).
REFERENCE_RANGE = (1, 10_000)
#: ``--kobj``'s range (N/mm, 0 excluded).
KOBJ_RANGE = (0.0, 1e6)
#: The what-if options by keyword (``arm_tol`` is ``--arm-tol``): the
#: :class:`~tactcad.studies.tolerance_montecarlo.Tolerances` field each replaces, its range
#: and unit (mm, or relative: no unit).
WHAT_IF_OPTIONS = {"notch_radius_tol": ("notch_radius_mm", 0.0, 10.0, "mm"),
                   "arm_tol": ("arm_length_mm", 0.0, 10.0, "mm"),
                   "modulus_tol": ("modulus_rel", 0.0, 0.5, "")}
#: ``--samples``'s ranges, each in the words of its refusal: a metal array's
#: (:data:`~tactcad.studies.tolerance_montecarlo.SAMPLES_RANGE`) and a silicon die's
#: (:data:`~tactcad.products.silicon_die.studies.die_tolerance.DIE_SAMPLES_RANGE`).
ARRAY_SAMPLES_ALLOWED = f"an integer {SAMPLES_RANGE[0]} ... {SAMPLES_RANGE[1]} (arrays drawn)"
DIE_SAMPLES_ALLOWED = f"an integer {DIE_SAMPLES_RANGE[0]} ... {DIE_SAMPLES_RANGE[1]} (dies drawn)"


def samples_count(text: str) -> int:
    """An argparse type for ``--samples``: the integer given. Its range is the product's
    (a metal array's or a silicon die's), which the parser, reading no design, does not know:
    :func:`check_array_samples` and the die's view check it.

    Args:
        text: the option's value.

    Returns:
        The integer (:func:`~tactcad.commands.options.ascii_integer`).

    Raises:
        argparse.ArgumentTypeError: not an integer in ASCII digits, naming both products'
            ranges.
    """
    try:
        return ascii_integer(text)
    except (TypeError, ValueError):
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r}: allowed {ARRAY_SAMPLES_ALLOWED}; on a silicon die's design "
            f"{DIE_SAMPLES_ALLOWED}") from None


samples_count.__name__ = "integer"


def check_array_samples(samples: int) -> int:
    """``samples`` when a metal array's Monte Carlo takes that many arrays
    (:data:`~tactcad.studies.tolerance_montecarlo.SAMPLES_RANGE`).

    Args:
        samples: the arrays asked (``--samples``).

    Returns:
        ``samples``.

    Raises:
        DesignError: ``--samples`` outside the range, naming it.
    """
    if not SAMPLES_RANGE[0] <= samples <= SAMPLES_RANGE[1]:
        raise DesignError("--samples", samples, ARRAY_SAMPLES_ALLOWED)
    return samples


def add_cluster_args(p: argparse.ArgumentParser, local_default: bool = False) -> None:
    """``--scheduler ADDR`` and ``--workers N``, shared by the commands that run on Dask."""
    p.add_argument("--scheduler", metavar="ADDR", default=None,
                   help="run on an existing Dask cluster, e.g. tcp://127.0.0.1:8786 (its workers "
                        "must import tactcad)" + ("" if local_default else
                                                  "; default: in this process"))
    p.add_argument("--workers", type=count(1, 256, "worker processes"), default=None, metavar="N",
                   help="run on a new local Dask cluster of N single-threaded worker processes")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "tolerance", help="Monte Carlo of the tolerances: K per element, R per unit, K_obj band",
        description="Draws web thickness, notch radius, arm length (per element), sheet "
                    "thickness and Young's modulus (per array) from the design's [tolerances] "
                    "(the table the drawings print; options override it as what-if), evaluates K with the "
                    "corrected closed form, R per sensing unit (eq. 2) and the K_obj a unit "
                    "reports with its nominal K_m, K_r (eq. 3): mean, standard deviation and "
                    "95 % interval. Also the web tolerance that keeps K within +/-5 % (for "
                    "the paper's design next to its measured spread of equal-arm elements), "
                    "whether the K band holds [requirements] k_tolerance_rel and which "
                    "tolerance to tighten to what. On a silicon die's design file: the die's "
                    "process tolerances (device layer thickness, cavity alignment) as its "
                    "budget states them, each row's beam K by its closed form, each unit's "
                    "coupled R and the K_obj it reads, and the spread against the budget's "
                    "terms. Units: mm, N/mm (um for a die's features).")
    add_design_arg(p)
    p.add_argument("--samples", type=samples_count, default=MONTE_CARLO_SAMPLES,
                   help=f"as-built arrays drawn, {SAMPLES_RANGE[0]} ... {SAMPLES_RANGE[1]} "
                        f"(default %(default)s, as verify draws); on a silicon die's design the "
                        f"dies drawn, {DIE_SAMPLES_RANGE[0]} ... {DIE_SAMPLES_RANGE[1]}")
    p.add_argument("--seed", type=count(*SEED_RANGE, "a seed"), default=MONTE_CARLO_SEED,
                   help="seed of the draw (default %(default)s, as verify)")
    p.add_argument("--kobj", type=number(*KOBJ_RANGE, "N/mm", lo_open=True), nargs="+",
                   metavar="N_PER_MM", default=None,
                   help="true object stiffnesses to report (default: the ends and middle of "
                        "the design's required K_obj range; the paper's design: its 2.34, "
                        "5.41, 10.01 N/mm samples)")
    p.add_argument("--reference", type=count(*REFERENCE_RANGE, "an element number"),
                   default=None, metavar="ELEMENT",
                   help="one reference element for every unit, one of the design's reference "
                        "elements (the nominally stiffest; default: each unit the nearest "
                        "one)")
    p.add_argument("--distribution", choices=("normal", "uniform"), default=None,
                   help="normal with tolerance = 3 sigma or uniform over +/-tolerance "
                        "(default: normal for an array; uniform for a silicon die, as its "
                        "budget takes a +- bound)")
    p.add_argument("--notch-radius-tol", type=number(*WHAT_IF_OPTIONS["notch_radius_tol"][1:]),
                   default=None, metavar="MM",
                   help="what-if: +/- notch radius instead of the design's "
                        "[tolerances] notch_radius_mm")
    p.add_argument("--arm-tol", type=number(*WHAT_IF_OPTIONS["arm_tol"][1:]), default=None,
                   metavar="MM",
                   help="what-if: +/- arm length instead of [tolerances] arm_length_mm")
    p.add_argument("--modulus-tol", type=number(*WHAT_IF_OPTIONS["modulus_tol"][1:]),
                   default=None, metavar="REL",
                   help="what-if: +/- relative Young's modulus instead of [tolerances] "
                        "youngs_modulus_rel")
    add_output_args(p, "print JSON")
    add_cluster_args(p)
    keep_option_defaults(p)  # a die's design: its view refuses an array's options
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    shown = product_view("tolerance", args)  # a silicon die's design: its process tolerances
    if shown is not None:
        return shown
    from tactcad.paper.table1 import with_equal_arm_spread
    from tactcad.studies.project_reports import tolerance_record

    check_array_samples(args.samples)  # before the design is planned: a refusal at once
    plan = plan_from_args(args)
    what_if = {field: getattr(args, option) for option, (field, *_) in WHAT_IF_OPTIONS.items()}
    asked = dict(kobj=args.kobj, reference=args.reference, distribution=args.distribution,
                 what_if=what_if)
    if args.scheduler or args.workers:
        from tactcad.studies.sweeps import LOCAL_WORKERS, dask_client, dask_mapper

        with dask_client(args.scheduler, args.workers or LOCAL_WORKERS) as client:
            bar = not (args.json or args.quiet)
            report, fields, wall = tolerance_record(plan, args.samples, args.seed, **asked,
                                                    mapper=dask_mapper(client, progress=bar))
    else:
        report, fields, wall = tolerance_record(plan, args.samples, args.seed, **asked)
    # the paper's measured spread belongs to the paper's design
    report = with_equal_arm_spread(report, plan)
    if args.json:
        out = report.as_json()
        out.update(fields)
        print(json.dumps(out, indent=2, allow_nan=False))
        return 0
    print_report(report, plan.name, wall)
    print_check(fields["tolerances_used"], fields["k_tolerance_check"])
    for warning in fields["warnings"]:  # a --kobj outside the design's range, as a die's says
        print(warning)
    return 0


def print_check(used: dict, check: dict) -> None:
    """The tolerances used and the K band check, as text."""
    print("tolerances used (source: the design's [tolerances]; what-if overrides marked):")
    for key, u in used.items():
        print(f"  {key} = {u['value']}  ({u['source']})")
    if check.get("verdict") == "info":  # the design's own spread, padded: nothing to hold
        print(f"K band: worst element {check['worst_element']}, 95 % interval "
              f"+/-{100 * check['predicted_band_rel']:.2f} % (k_tolerance_rel not stated: "
              f"reported, not judged; the design's own web band, padded, is "
              f"{100 * check['reference_value']:.3g} %)")
        return
    verdict = "holds" if check["pass"] else "does not hold"
    print(f"K band: worst element {check['worst_element']}, 95 % interval "
          f"+/-{100 * check['predicted_band_rel']:.2f} % against k_tolerance_rel "
          f"{100 * check['target']:.3g} %: the toleranced design {verdict} it")
    for t in check["tighten"]:
        if t["to"] is None:
            print(f"  {t['note']}")
            continue
        print(f"  tighten {t['tolerance']} from {t['from']:g} to {t['to']:g}"
              + (f" ({t['note']})" if t.get("note") else ""))


def print_report(report, name: str, wall_s: float) -> None:
    """Text form of a :class:`~tactcad.studies.tolerance_montecarlo.ToleranceReport`."""
    print(f"tolerance Monte Carlo of {name}: {report.samples} samples, seed {report.seed}, "
          f"{wall_s:.2f} s")
    print(f"  {report.tolerances.describe()}")
    print("K per element (N/mm): nominal, mean, std, 95 % interval")
    for e in report.elements:
        print(f"  {e['element']:>3} a={e['arm_length_mm']:<5g} {e['K_nominal_N_per_mm']:8.3f} "
              f"{e['K_mean_N_per_mm']:8.3f} {e['K_std_N_per_mm']:7.3f} "
              f"({100 * e['K_rel_std']:4.1f} %)  [{e['K_p2_5_N_per_mm']:.3f}, "
              f"{e['K_p97_5_N_per_mm']:.3f}]")
    print("units (reference/measuring): R and reported K_obj at each true K_obj "
          "(eq. 3 with nominal K_m, K_r)")
    print(f"  {'unit':>6} {'K_obj':>6} {'R nom':>7} {'R mean':>7} {'R std':>6}  "
          f"{'K_obj mean':>10} {'std':>6} {'95 % interval':>17} {'out of eq.3':>11}")
    from tactcad.in_use.tissue_coupling import unit_label

    for u in report.units:
        r, k = u["R"], u["K_obj_reported_N_per_mm"]
        interval = (f"[{k['p2_5']:.2f}, {k['p97_5']:.2f}]" if k["mean"] is not None
                    else "n/a")
        mean = f"{k['mean']:10.3f} {k['std']:6.3f}" if k["mean"] is not None else f"{'n/a':>17}"
        label = unit_label((u["measuring"], u["reference"]))  # as every command names it
        print(f"  {label:>6} {u['K_obj_true_N_per_mm']:6.2f} "
              f"{u['R_nominal']:7.4f} {r['mean']:7.4f} {r['std']:6.4f}  {mean} {interval:>17} "
              f"{100 * u['fraction_outside_eq3_domain']:10.1f}%")
    print("web tolerance that keeps K within +/-5 % (design tolerance in brackets):")
    for w in report.web_tolerance:
        print(f"  {w['part']:<16} web {w['web_mm']:g} mm: +/-{1000 * w['web_tolerance_for_5pct_K_mm']:.1f}"
              f" um  (design +/-{1000 * w['design_web_tolerance_mm']:.0f} um)")
    if report.table1_spread:
        print("Table 1, elements with equal arms (measured K, N/mm):")
    for s in report.table1_spread:
        ks = ", ".join(f"{e}: {k:g}" for e, k in zip(s["elements"], s["measured_N_per_mm"]))
        webs = ", ".join(f"{w:.3f}" for w in s["as_built_web_mm"])
        print(f"  arm {s['arm_length_mm']:g} mm: {ks}  -> {s['ratio_max_over_min']:.2f}x "
              f"(as-built webs {webs} mm)")
