"""``tactcad grasp``: the grasp as a virtual experiment and the leads through the shaft."""

from __future__ import annotations

import argparse
import math

from tactcad.commands import add_cache_args, add_design_arg, add_output_args, parse_overrides
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import (GRASP_OPTION_OF, grasp_option_error,
                                      keep_option_defaults, number, renamed_option)
from tactcad.mechanics.ladder import models

from tactcad.in_use.grasp_experiment import (DEFAULT_JAW_BEYOND_MM, DEFAULT_OPENING_DEG,
                                             DEFAULT_PIVOT_BEHIND_MM, DEFAULT_SLAB_MM,
                                             DEFAULT_PROFILE, LINEAR_TISSUE_STRAIN)
from tactcad.studies.grasp_report import DEFAULT_LEAD_CHANNEL_MM

#: The grasp's fields and the options that set them (an error names the option).
OPTION_OF = GRASP_OPTION_OF


def ranged(name: str):
    """The argparse type of a grasp number: its range as the API takes it
    (:data:`tactcad.studies.grasp_report.GRASP_NUMBERS`)."""
    from tactcad.studies.grasp_report import GRASP_NUMBERS

    lo, hi, unit, lo_open = GRASP_NUMBERS[name]
    return number(lo, hi, unit, lo_open=lo_open)


def register(sub: argparse._SubParsersAction) -> None:
    from tactcad.in_use.grasp_experiment import COUPLINGS, PROFILES

    p = sub.add_parser(
        "grasp", help="the grasp as a virtual experiment: a pivoting jaw closes on tissue; "
                      "each unit's radii, travels, R and K_obj read, as laid out and paired "
                      "at equal radius; the leads through the shaft",
        description="A jaw pivoting about a pin across its width closes on a tissue slab "
                    "(or a wedge thickening from the pin) at a given angle or grasp force. The "
                    "tips are rigid punches on their elements' springs, coupled through the "
                    "tissue (a layer of the slab's thickness on the opposing jaw), each "
                    "element capped by its hard stop. For every sensing unit: the two tips' "
                    "radii and their ratio (equal within 2 %), their travels, R read, K_obj "
                    "read by eq. 3 against the true one, and corrected for the travels; for "
                    "the design's layout and the units laid across the jaw's width at equal "
                    "radius, side by side; every element's force against its rating. Then "
                    "the leads (three per three-wire quarter bridge, AWG 36 PTFE 0.25 mm) "
                    "against the shaft's lead channel. On a silicon die's design file: the die's own "
                    "jaw closed on the tissue, each column read as a unit (no leads). Units: "
                    "mm, N, N/mm, degrees.")
    add_design_arg(p)
    add_cache_args(p)
    how = p.add_mutually_exclusive_group()
    # its range is the jaw's own, 0 ... its opening: checked against the jaw, one refusal
    how.add_argument("--angle-deg", type=number(unit="degrees"), default=None,
                     help="the jaw's closing angle above the opposing jaw (degrees, 0 ... the "
                          "jaw's opening)")
    how.add_argument("--force-N", dest="force_N", type=ranged("force_N"),
                     default=None, help="the grasp force the tips put on the tissue (N, "
                                        "1e-06 ... 1000: a smaller force's tip deflections "
                                        "are lost in round-off; default half the rated full-scale force on every "
                                        "element)")
    p.add_argument("--slab-thickness-mm", type=ranged("slab_thickness_mm"),
                   default=None,
                   help="the tissue's thickness (mm; default the design's [tissue_slab] with "
                        f"its [grasper_jaw], else {DEFAULT_SLAB_MM:g} mm, assumed: give "
                        "your tissue's); a wedge's at the last tip")
    p.add_argument("--profile", choices=PROFILES, default=DEFAULT_PROFILE,
                   help="the tissue between the jaws: a wedge, from nothing at the pin to "
                        "the tissue's thickness at the last tip, so every tip touches at first "
                        "contact and its travel grows with its radius, or a flat slab, pressed "
                        "near the pin first (a hinged jaw "
                        "reaches the far tips only once the near ones are on their stops; "
                        "default %(default)s)")
    p.add_argument("--kobj", type=ranged("kobj"), default=None,
                   help="the tissue's true local stiffness under one tip (N/mm, 1e-06 ... "
                        "10000: a softer tissue is lost in the elements' K, its readings "
                        "round-off; default the geometric mean of the requirements' K_obj "
                        "range)")
    p.add_argument("--pivot-mm", type=ranged("pivot_mm"), nargs=2, metavar=("X", "Y"),
                   default=None,
                   help="the pin in the insert's frame (mm): X along the rows, Y across them, "
                        "from the first element's tip centre (default the design's "
                        f"[grasper_jaw], else -{DEFAULT_PIVOT_BEHIND_MM:g} 0: "
                        f"{DEFAULT_PIVOT_BEHIND_MM:g} mm behind the first tip)")
    p.add_argument("--pin-to-tip-mm", type=ranged("pin_to_tip_mm"), default=None,
                   help="the jaw from its pin to its tip (mm; default the design's "
                        "[grasper_jaw], "
                        f"else the last tip's radius + {DEFAULT_JAW_BEYOND_MM:g} mm)")
    # the option's earlier name: refused with its new one, not as an unknown argument
    p.add_argument("--jaw-length-mm", type=renamed_option("--jaw-length-mm", "--pin-to-tip-mm",
                                                          "the jaw from its pin to its tip; "
                                                          "jaw_length_mm is the jaw's own "
                                                          "length"),
                   default=None, help=argparse.SUPPRESS)
    p.add_argument("--opening-deg", type=ranged("opening_deg"),
                   default=None,
                   help="the jaw's full opening (degrees; default the design's [grasper_jaw], "
                        f"else {DEFAULT_OPENING_DEG:g}, assumed)")
    p.add_argument("--coupling", choices=COUPLINGS, default="layer",
                   help="the tissue between the tips: a layer of the slab's thickness on the "
                        "opposing jaw (on the base the design's [tissue_slab] states, bonded "
                        "unless it says), a half-space, or none (eq. 1; default %(default)s)")
    p.add_argument("--model", choices=models(), default="closed-form",
                   help="ladder level for the elements' K (default closed-form)")
    p.add_argument("--lead-channel-mm", type=ranged("lead_channel_mm"),
                   default=None,
                   help="the shaft's lead channel diameter (mm; default the bore of the "
                        "design's [grasper_shaft] when it states its grasper, else "
                        f"{DEFAULT_LEAD_CHANNEL_MM:g} mm, assumed: give your shaft's)")
    add_output_args(p, "print one JSON object: the jaw, both layouts' tips and units, the "
                       "leads")
    keep_option_defaults(p)  # a die's design: its view refuses an array's options
    p.set_defaults(func=run)


def design_plan_from_args(args: argparse.Namespace):
    """The plan of ``--design`` with every ``--set``: the design file alone, since the grasp
    needs neither the test rigs nor the scenes (a construction the rigs cannot hold yet is
    still grasped); a named reference no stiffer than its measuring elements refused
    (:func:`tactcad.api.check_references_stiffer`).

    Raises:
        DesignError: unreadable file, bad ``--set``, a value out of range, a stacked array
            of one column, a soft reference.
    """
    from pathlib import Path

    from tactcad.api import check_references_stiffer
    from tactcad.design.array_plan import plan_from_dict, stacked_columns_error, with_overrides
    from tactcad.design.file_kind import read_array_tables
    from tactcad.errors import DesignErrors
    from tactcad.commands import announced_default_design

    path = Path(args.design) if getattr(args, "design", None) else announced_default_design()
    texts = getattr(args, "overrides", None) or []
    data = with_overrides(read_array_tables(path), parse_overrides(texts))
    too_few = stacked_columns_error(data, path.name)
    try:
        if too_few is not None:
            raise DesignErrors([too_few])
        plan = plan_from_dict(data, source=str(path), file=path.name)
        check_references_stiffer(plan)  # a unit that cannot read K_obj is no grasp's
        return plan
    except DesignErrors as exc:  # a refused --set value is named as typed
        from tactcad.commands import set_sources

        raise exc.sourced(set_sources(texts)) from None


def run(args: argparse.Namespace) -> int:
    from tactcad.errors import DesignError
    from tactcad.studies.grasp_report import grasp_record
    from tactcad.commands import product_view

    shown = product_view("grasp", args)  # a silicon die's design: the grasp in its jaw
    if shown is not None:
        return shown
    plan = design_plan_from_args(args)
    try:
        record = grasp_record(plan, asked_of(args))
    except DesignError as exc:
        raise grasp_option_error(exc, args) from None
    print(dumps(record, indent=1) if args.json else render(record))
    # an element past its overload limit in the design's own layout, or leads the shaft
    # cannot take: exit 1, as a failed check
    return 0 if record["passed"] else 1


def asked_of(args: argparse.Namespace):
    """The grasp the command line asks for (:class:`tactcad.studies.grasp_report.GraspAsked`)."""
    from tactcad.studies.grasp_report import GraspAsked

    return GraspAsked(model=args.model, force_N=args.force_N, angle_deg=args.angle_deg,
                      kobj=args.kobj, coupling=args.coupling, profile=args.profile,
                      pivot_mm=tuple(args.pivot_mm) if args.pivot_mm else None,
                      pin_to_tip_mm=args.pin_to_tip_mm, opening_deg=args.opening_deg,
                      slab_thickness_mm=args.slab_thickness_mm,
                      lead_channel_mm=args.lead_channel_mm)


def _f(x, digits: int = 4) -> str:
    return "-" if x is None else f"{x:.{digits}g}"


def _pct(x) -> str:
    return "-" if x is None or not math.isfinite(x) else f"{100 * x:+.3g} %"


#: What a unit's R and K_obj cells say where an element of it is past its overload limit.
OVERLOADED_CELL = "overloaded"


def unit_table(layout: dict) -> list[str]:
    """One layout's units as a Markdown table."""
    lines = ["| unit | r_r mm | r_m mm | r_m/r_r | tissue mm | Δ_r mm | Δ_m mm | K_obj true | "
             "R true | R read | K_obj read | error | K_obj corrected | error | note |",
             "| --- |" + " --- |" * 14]
    for u in layout["units"]:
        t_r, t_m = u.get("tissue_thickness_reference_mm"), u.get("tissue_thickness_measuring_mm")
        tissue = "-" if t_r is None else (_f(t_r, 3) if t_r == t_m
                                          else f"{_f(t_r, 3)} / {_f(t_m, 3)}")
        if u.get("overloaded"):  # an overloaded element reads nothing: said in each cell
            read = " | ".join([OVERLOADED_CELL] * 5)
        else:
            read = (f"{_f(u['R_read'])} | {_f(u['K_obj_read_N_per_mm'])} | "
                    f"{_pct(u['error_rel'])} | {_f(u['K_obj_corrected_N_per_mm'])} | "
                    f"{_pct(u['error_corrected_rel'])}")
        lines.append(
            f"| {u['unit']} | {_f(u['r_reference_mm'])} | {_f(u['r_measuring_mm'])} | "
            f"{_f(u['radius_ratio'])} | {tissue} | {_f(u['travel_reference_mm'])} | "
            f"{_f(u['travel_measuring_mm'])} | {_f(u['K_obj_true_N_per_mm'])} | "
            f"{_f(u['R_true'])} | {read} | {unit_note(u)} |")
    return lines


def residual_line(layout: dict) -> str | None:
    """The line that says what the correction leaves in a layout's readings.

    Args:
        layout: one layout's JSON (:meth:`tactcad.in_use.grasp_experiment.LayoutGrasp.as_json`).

    Returns:
        Its ``correction_residual`` in words: the range and largest error, the unit, the
        cause and the units read further off corrected than raw; None where it leaves
        nothing.
    """
    left = layout.get("correction_residual")
    if not left:
        return None
    lo, hi = left["range_rel"]
    worse = left["worse_than_read"]
    return (f"{layout['layout']}: the corrected K_obj is still off by {_pct(lo)} ... "
            f"{_pct(hi)} (largest {_pct(left['largest_rel'])}, unit {left['unit']}): "
            f"{left['cause']}"
            + (f"; the correction leaves units {', '.join(worse)} further off than read"
               if worse else ""))


def unit_note(unit: dict) -> str:
    """A unit's note: why it does not read (its tips, or a true K_obj outside the design's
    range), else whether its radii are equal (within 2 %)."""
    why = "; ".join(filter(None, [unit["why"], unit.get("out_of_range")]))
    radius = "equal radius" if abs(unit["radius_ratio"] - 1) <= 0.02 else "radii differ"
    return why or radius + ("; corrected further off than read" if unit.get("correction_worse")
                            else "")


def render(record: dict) -> str:
    """The grasp and the leads as text."""
    from tactcad.in_use.grasp_experiment import overloaded_sites

    j = record["jaw"]
    lines = [f"Grasp of {record['design']} ({record['model']}): pin at "
             f"({j['pivot_u_mm']:g}, {j['pivot_v_mm']:g}) mm, pin to tip "
             f"{j['pin_to_tip_mm']:.4g} mm, "
             f"{record['profile']} {j['slab_thickness_mm']:g} mm, K_obj "
             f"{record['K_obj_N_per_mm']:.4g} N/mm, {record['coupling']} coupling"
             + (f" on a {record['tissue_base']} base" if record.get("tissue_base") else "")
             + ", rated "
             f"{record['rated_force_N']:g} N per element", *record.get("warnings", [])]
    for key in ("as_laid_out", "paired", "along_rows"):
        lay = record[key]
        if lay is None:
            continue
        if key != "as_laid_out" and record[f"{key}_layout"]["as_laid_out"]:
            lines += ["", f"{lay['layout']}: the design's own layout (as laid out, above)"]
            continue
        over = [t["site"] for t in lay["tips"] if t["over_rating"]]
        damaged = overloaded_sites(lay["tips"])
        stops = [t["site"] for t in lay["tips"] if t["on_stop"]]
        crushed = [t["site"] for t in lay["tips"] if t.get("past_linear_tissue")]
        if crushed:
            lines += ["", f"{lay['layout']}: the tissue is compressed past "
                          f"{100 * LINEAR_TISSUE_STRAIN:g} % under tips "
                          f"{', '.join(map(str, crushed))}: past the linear tissue model"]
        lines += ["", f"{lay['layout']}: angle {lay['angle_deg']:.4g} degrees, grasp force "
                      f"{lay['total_force_N']:.4g} N; largest element force "
                      f"{max(t['element_force_N'] for t in lay['tips']):.4g} N; over the "
                      f"rating (reading past full scale): {', '.join(map(str, over)) or 'none'}; "
                      f"over the overload limit: {', '.join(map(str, damaged)) or 'none'}; "
                      f"on a stop: {', '.join(map(str, stops)) or 'none'}", *unit_table(lay)]
        residual = residual_line(lay)
        if residual:
            lines.append(residual)
    for key, words in (("paired_layout", "paired layout"),
                       ("along_rows_layout", "along the rows")):
        pl = record.get(key)
        if pl and pl["reason"]:  # units a layout has no sites for, said, not dropped
            lines += ["", f"{words}: {pl['reason']} (not laid: "
                          f"{', '.join(pl['unplaced']) or 'none'})"]
    from tactcad.design.readout_section import LEAD_WIRE

    ld = record["leads"]
    lines += ["", f"leads: {ld['bridges']} {ld['connection']} quarter bridges, {ld['leads']} "
                  f"leads of {ld['wire_diameter_mm']:g} mm (AWG {LEAD_WIRE['awg']} PTFE), packing "
                  f"{ld['packing_factor']:g}: bundle {ld['bundle_diameter_mm']:.3g} mm in a "
                  f"{ld['channel_diameter_mm']:g} mm channel: "
                  f"{'fits' if ld['fits'] else 'does NOT fit'}"]
    lines += [""] + [f"  {k}: {v}" for k, v in {**record["notes"], **record["reasons"]}.items()]
    return "\n".join(lines)
