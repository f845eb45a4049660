"""The array commands on a silicon die's design file: ``modal``, ``budget``, ``readout`` and
``thermal`` print the die's own resonances, K_obj budget, piezoresistive read-out and its
temperature terms (what ``tactcad die`` prints among its files), planned as the die command
plans it and writing nothing.

An option of the array command that has no meaning for a die (a ladder level, an element,
a temperature step) is refused by name rather than ignored. ``grasp`` and ``crosstalk``
stay refused with their reason (:data:`NOT_FOR_A_DIE`).
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Callable

from tactcad.commands.finite_json import dumps
from tactcad.errors import DesignError

#: Options every view takes as the array command does: the design, its overrides, output.
SHARED_OPTIONS = frozenset({"design", "overrides", "json", "quiet", "cache", "no_cache", "func",
                            "command", "array_defaults"})


def keep_array_defaults(parser: argparse.ArgumentParser) -> None:
    """Remember the parser's option defaults on its namespace (``array_defaults``), so that a
    die's view can tell an option the user set from one left at its default."""
    parser.set_defaults(array_defaults={a.dest: a.default for a in parser._actions
                                        if a.dest != "help"})


def _refuse_array_options(args: argparse.Namespace, command: str, design: Path) -> None:
    defaults = getattr(args, "array_defaults", {}) or {}
    for dest, default in defaults.items():
        if dest in SHARED_OPTIONS:
            continue
        value = getattr(args, dest, default)
        if value != default:
            option = "--" + dest.replace("_", "-")
            raise DesignError(option, value, f"left out for a die's design ({design.name})",
                              f"`tactcad {command}` on a silicon die prints the die's own "
                              "figures; this option chooses among an array's")


def _planned(design: Path, args: argparse.Namespace):
    from tactcad.commands.die import _die_args, die_asked, plan_of

    return plan_of(die_asked(_die_args(design, args, Path("."))))


def _modal(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands.die import mode_lines, modes_json
    from tactcad.mechanics.die_dynamics import die_modes

    plan = _planned(design, args).plan
    modes = die_modes(plan)
    return ({"design": str(design), "die": plan.name, "resonance_Hz": modes_json(modes)},
            [f"die {plan.name}: each row's first bending mode, clamped at the root",
             *mode_lines(modes)])


def _budget(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands.die import budget_lines
    from tactcad.in_use.die_budget import die_budget

    plan = _planned(design, args).plan
    budget = die_budget(plan)
    return ({"design": str(design), "die": plan.name, "kobj_budget": budget.as_json()},
            [f"die {plan.name}", *budget_lines(budget)])


def _readout(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.commands.die import resistor_line
    from tactcad.mechanics.piezoresistor import die_readout

    plan = _planned(design, args).plan
    readout = die_readout(plan)
    lines = [f"die {plan.name}: one p-type resistor per beam in a quarter bridge",
             "| role | dR/R per N | V/N | force resolution N |", "| --- | --- | --- | --- |"]
    for role, r in readout["rows"].items():
        lines.append(f"| {role} | {r['resistance_change_per_N']:.4g} | "
                     f"{r['sensitivity_V_per_N']:.4g} | {r['force_resolution_N']:.3g} |")
    lines += [resistor_line(plan, readout),
              f"sensitivity temperature coefficient {100 * readout['sensitivity_tc_per_K']:+.3g}"
              f" %/K; self-heating {1e3 * readout['self_heating_K']:.3g} mK"]
    return {"design": str(design), "die": plan.name, "readout": readout}, lines


def _thermal(design: Path, args: argparse.Namespace) -> tuple[dict, list[str]]:
    from tactcad.in_use.die_budget import TEMPERATURE_STEP_K, die_budget
    from tactcad.mechanics.piezoresistor import die_readout

    plan = _planned(design, args).plan
    readout = die_readout(plan)
    budget = die_budget(plan, readout)
    tcs, heating = readout["sensitivity_tc_per_K"], readout["self_heating_K"]
    term = budget.terms["temperature"]
    zero = ("not sized: the bridge's three other arms are the same implant on the die's "
            "frame, so their TCR cancels the active arm's to first order; their mismatch and "
            "the beam's self-heating over the frame are not modelled")
    report = {"design": str(design), "die": plan.name,
              "sensitivity_tc_per_K": tcs, "self_heating_K": heating,
              "temperature_step_K": TEMPERATURE_STEP_K,
              "kobj_error_rel": {"k_obj_N_per_mm": budget.k_obj_N_per_mm.tolist(),
                                 "temperature": [float(v) for v in term],
                                 "reason": budget.reasons["temperature"]},
              "zero": zero}
    lines = [f"die {plan.name}: p-type resistors, boron {plan.acceptors_per_cm3:.2g} cm^-3",
             f"span: sensitivity {100 * tcs:+.3g} %/K (d ln P / dT, Richter et al. 2008), "
             "alike in both rows: it cancels in R at one temperature",
             f"self-heating: {1e3 * heating:.3g} mK at the root, P(N, T) moved "
             f"{100 * abs(tcs) * heating:.2g} %",
             f"K_obj error over a {TEMPERATURE_STEP_K:g} K step at K_obj "
             + ", ".join(f"{k:.3g}" for k in budget.k_obj_N_per_mm) + " N/mm: "
             + ", ".join(f"{100 * v:.3f} %" for v in term) + f" ({budget.reasons['temperature']})",
             f"zero: {zero}"]
    return report, lines


#: The array commands that print a die's own figures, and what they print.
DIE_VIEWS: dict[str, Callable[[Path, argparse.Namespace], tuple[dict, list[str]]]] = {
    "modal": _modal, "budget": _budget, "readout": _readout, "thermal": _thermal}


def die_view(command: str, args: argparse.Namespace) -> int | None:
    """Run ``command``'s view of a die when ``--design`` (or the working folder's one design
    file) is a die's; None for an array's design (the command goes on as usual).

    Raises:
        DesignError: an option of the array command set (named), or the die's own refusals.
    """
    from tactcad.commands.die import die_design_of

    design = die_design_of(args)
    if design is None:
        return None
    _refuse_array_options(args, command, design)
    report, lines = DIE_VIEWS[command](design, args)
    print(dumps(report, indent=1) if args.json else "\n".join(lines))
    return 0
