"""``tactcad lumped``: deflection ratio or object stiffness of a sensing unit (paper eq. 2-3).

Examples::

    tactcad lumped --km 15.25 --kr 80.38 --kobj 3.85
    tactcad lumped --km 15.25 --kr 80.38 --r 2.283 --sigma-r 0.05 --json
    cd my_project && tactcad lumped --kobj 2     # K_m, K_r from the project's design
"""

from __future__ import annotations

import argparse
import math

from tactcad.commands.finite_json import dumps
from tactcad.errors import DesignError, TactcadError

from tactcad.commands import add_design_arg, add_output_args
from tactcad.commands.options import ascii_float, ascii_integer, number


#: The option that gives each of the lumped model's inputs (its refusals name it).
OPTION_OF_QUANTITY = {"R": "--r", "K_m": "--km", "K_r": "--kr", "K_obj": "--kobj",
                      "sigma_R": "--sigma-r"}


def register(subparsers) -> None:
    """Add the ``lumped`` sub-command to an ``argparse`` sub-parser collection."""
    p = subparsers.add_parser(
        "lumped",
        help="lumped model of a stiffness sensing unit: R from K_obj or K_obj from R",
        description="Lumped spring model of a stiffness sensing unit (paper eq. 2-3). "
                    "Given K_obj prints R = (K_r + K_obj)/(K_m + K_obj); given R prints "
                    "K_obj = (K_r - R K_m)/(R - 1). Also prints the sensitivity dK_obj/dR "
                    "and, with --sigma-r, the first-order uncertainty of K_obj. "
                    "Domain: 0 < K_m < K_r, K_obj > 0, 1 < R < K_r/K_m.")
    p.add_argument("--km", type=ascii_float, default=None, metavar="N_PER_MM",
                   help="measuring-element stiffness K_m (N/mm); default: the design's (a "
                        "project's, --design's or the DESIGN word's), as tactcad stiffness "
                        "gives it at closed-form")
    p.add_argument("--kr", type=ascii_float, default=None, metavar="N_PER_MM",
                   help="reference-element stiffness K_r (N/mm), > K_m; default: the "
                        "design's, as --km")
    given = p.add_mutually_exclusive_group(required=True)
    given.add_argument("--kobj", type=ascii_float, metavar="N_PER_MM",
                       help="object stiffness K_obj (N/mm): print R")
    given.add_argument("--r", type=ascii_float, metavar="R",
                       help="measured deflection ratio R (dimensionless): print K_obj")
    p.add_argument("--sigma-r", type=ascii_float, default=None, metavar="SIGMA",
                   help="standard uncertainty of R: print sigma of K_obj (first order)")
    p.add_argument("--coupled-design", metavar="DESIGN.toml", default=None,
                   help="also the coupled form beside eq. 2-3: every tip of this design on one "
                        "elastic half-space (nu 0.5; in_use/tissue_coupling), --km and --kr the "
                        "unit's elements, the others at the closed form")
    p.add_argument("--unit", type=ascii_integer, metavar="ELEMENT", default=None,
                   help="with --coupled-design: the measuring element (its row's reference "
                        "is the unit's other tip); without --km/--kr, the array's unit whose "
                        "K_m and K_r are taken (needed where its units differ)")
    p.add_argument("--flat", metavar="FILE", default=None,
                   help="with --coupled-design: the tips' heights read on a rigid flat (the "
                        "zeroing run of tactcad calibrate --flat, CSV element,step,"
                        "deflection_um), taken out of the coupled R or K_obj; needs --force-r")
    p.add_argument("--encoding", metavar="NAME", default=None,
                   help="with --flat: the file's text encoding (default UTF-8, or what its byte "
                        "order mark says), e.g. cp1252")
    p.add_argument("--contact-um", type=number(0, 1e4, "um"), default=0.0, metavar="UM",
                   help="with --flat: a step counts where every element's deflection exceeds "
                        "this (um, default 0), as tactcad calibrate --flat")
    p.add_argument("--force-r", type=ascii_float, metavar="N", default=None,
                   help="with --flat: the reference element's force at the reading (N, its "
                        "calibrated K_r times its deflection): a height offset is a length, so "
                        "its effect on R depends on how far the elements deflect")
    add_design_arg(p, design_help="design file (TOML) or project folder whose K_m and K_r "
                                  "are taken when --km or --kr is not given; default: the one "
                                  "design file of the working folder")
    add_output_args(p, "print one JSON object instead of text")
    p.set_defaults(func=run)


#: The level a design's K_m and K_r are read at: ``tactcad stiffness``'s default.
DESIGN_K_LEVEL = "closed-form"


def design_stiffness(args: argparse.Namespace) -> dict | None:
    """K_m and K_r (N/mm) of the design a command line names (the ``DESIGN`` word,
    ``--design``, else the working folder's one design file), as ``tactcad stiffness`` gives
    them at :data:`DESIGN_K_LEVEL`, for the ones of ``--km`` and ``--kr`` not given: an
    array's unit (``--unit``, or any where all its units share both), a silicon die's rows.

    Args:
        args: the parsed command line (``km``, ``kr``, ``unit``, ``design``,
            ``design_word``, ``overrides``).

    Returns:
        ``{"design", "unit", "model", "k_m_N_per_mm", "k_r_N_per_mm"}`` (unit: [measuring,
        reference] element numbers, None for a die); None when both are given.

    Raises:
        DesignError: a design (or ``--set``) given beside both --km and --kr (it would go
            unused), no design to take them from (naming --km and --kr), an array whose
            units differ without ``--unit``, or ``--unit`` no measuring element of it.
        TactcadError: ``--unit`` for a die's design.
    """
    named = getattr(args, "design_word", None) or args.design
    if args.km is not None and args.kr is not None:
        if named is not None or getattr(args, "overrides", None):
            given = "--design" if named is not None else "--set"
            raise DesignError(given, named if named is not None else
                              args.overrides[0], "no design with both --km and --kr given",
                              "the design's K_m and K_r would go unused: leave out --km and "
                              "--kr to take them from it")
        return None
    from tactcad.commands import parse_overrides, settle_design
    from tactcad.project_folder import designs_in, other_product_designs_in

    settle_design(args)
    missing = " and ".join(o for o, v in (("--km", args.km), ("--kr", args.kr)) if v is None)
    if args.design is None and not (designs_in(".") + other_product_designs_in(".")):
        raise DesignError(missing, None, "a stiffness in N/mm, or a design to take it from: "
                                         "run in a project folder, or give --design FILE or "
                                         "the DESIGN word",
                          "lumped takes K_m and K_r from the design, as tactcad stiffness "
                          "gives them, when they are not given")
    from pathlib import Path

    from tactcad.api import load
    from tactcad.project_folder import default_design

    design = str(Path(args.design) if args.design is not None else default_design())
    project = load(design, set=parse_overrides(getattr(args, "overrides", None)))
    plan = project.plan
    if hasattr(plan, "k_m_N_per_mm"):  # a silicon die: its rows' beams
        if args.unit is not None and args.coupled_design is None:
            raise TactcadError(f"--unit = {args.unit}: allowed with an array's design only "
                               f"(every unit of die {plan.name} has its rows' K_m and K_r)")
        pair, k_m, k_r = None, plan.k_m_N_per_mm, plan.k_r_N_per_mm
    else:
        pair, k_m, k_r = _array_unit(project, args.unit)
    return {"design": design, "unit": pair, "model": DESIGN_K_LEVEL,
            "k_m_N_per_mm": float(k_m), "k_r_N_per_mm": float(k_r)}


def _array_unit(project, unit: int | None) -> tuple[list[int], float, float]:
    """([measuring, reference], K_m, K_r (N/mm)) of an array's unit at
    :data:`DESIGN_K_LEVEL`: ``unit`` (its measuring element), or the first where every unit
    has the same two.

    Raises:
        DesignError: ``unit`` not a measuring element, or none given where units differ.
    """
    from tactcad.in_use.tissue_coupling import design_units

    by_part: dict[str, float] = {}
    k = {}
    for slot in project.plan.slots:
        part = slot.geometry.part_name
        if part not in by_part:
            by_part[part] = project.element(slot.number).stiffness(
                DESIGN_K_LEVEL).stiffness_N_per_mm
        k[slot.number] = by_part[part]
    pairs = dict(design_units(project.plan, k))
    if unit is None:
        if len({(k[m], k[r]) for m, r in pairs.items()}) > 1:
            raise DesignError("--unit", None, f"a measuring element of {project.plan.name}: "
                                              f"{sorted(pairs)}",
                              "its units differ in K_m or K_r: choose the one whose "
                              "stiffnesses lumped takes (or give --km and --kr)")
        unit = min(pairs)
    if unit not in pairs:
        raise DesignError("--unit", unit, f"a measuring element of {project.plan.name}: "
                                          f"{sorted(pairs)}")
    return [unit, pairs[unit]], k[unit], k[pairs[unit]]


def coupled_form(design: str, unit: int | None, k_m: float, k_r: float, k_obj: float | None,
                 r: float | None, flat: str | None = None, force_r_N: float | None = None,
                 encoding: str | None = None, contact_um: float = 0.0) -> dict:
    """The coupled R (eq. 2 corrected) from K_obj, or the coupled K_obj (eq. 3 corrected) from
    R, for measuring element ``unit`` of ``design`` against its row's reference, every tip on
    one half-space (:mod:`tactcad.in_use.tissue_coupling`); K_m, K_r for the unit's two
    elements, the others' K at the closed form. With ``flat`` (a zeroing run's file) the
    tips' heights read on it are taken out as well, at the reference's force ``force_r_N``
    (:func:`~tactcad.in_use.tissue_coupling.offset_object_stiffness`); the K_obj's spread
    over the unit's mismatch uncertainty is reported beside it.

    Raises:
        TactcadError: ``unit`` missing or no measuring element of the design (named);
            ``flat`` without ``force_r_N`` or a force not > 0.
        tactcad.mechanics.contact.ContactError: R outside the coupled model's range.
        tactcad.mechanics.calibration.CalibrationError, tactcad.in_use.tip_zeroing.ZeroingError:
            the flat's file cannot be read or gives no heights.
    """
    from tactcad.design.array_plan import load_design
    from tactcad.in_use.tissue_coupling import (coupled_object_stiffness, coupled_ratio, coupled_sample,
                                                design_units)
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element

    try:
        plan = load_design(design)
    except DesignError as exc:  # name the option this command reads the file by
        if exc.field != "--design":
            raise
        raise DesignError("--coupled-design", exc.value, exc.allowed, exc.why) from None
    k = ladder_stiffness_by_element(plan)
    pairs = dict(design_units(plan, k))
    if unit not in pairs:
        shown = "--unit (not given)" if unit is None else f"--unit = {unit!r}"
        raise TactcadError(f"{shown}: allowed a measuring element of {plan.name}: "
                           f"{sorted(pairs)}")
    pair = (unit, pairs[unit])
    k = {**k, pair[0]: k_m, pair[1]: k_r}
    sample = coupled_sample(plan)
    out: dict = {"unit": list(pair)}
    if r is None:
        out["r_coupled"] = float(coupled_ratio(sample, k, pair, k_obj))
    else:
        out["k_obj_coupled_N_per_mm"] = coupled_object_stiffness(sample, k, pair, r)
    if flat is not None:
        out["zeroed"] = _zeroed_form(plan, sample, k, pair, k_obj, r, flat, force_r_N,
                                     encoding, contact_um)
    return out


def _zeroed_form(plan, sample, k: dict, pair: tuple[int, int], k_obj: float | None,
                 r: float | None, flat: str, force_r_N: float | None,
                 encoding: str | None = None, contact_um: float = 0.0) -> dict:
    """The coupled R or K_obj with the tips' heights of a zeroing run taken out, and the
    K_obj (or R) at the unit's mismatch moved by +-1 sigma."""
    from tactcad.in_use.tip_zeroing import read_tip_heights
    from tactcad.in_use.tissue_coupling import offset_object_stiffness, offset_ratio

    _check_force_r(force_r_N)
    yield_N = _yield_force_N(plan, pair[1])
    if yield_N is not None and force_r_N > yield_N:
        raise DesignError("--force-r", force_r_N, f"<= {yield_N:.4g} N",
                          f"the force at which the reference element {pair[1]} yields; a force "
                          "in N, not mN or g")
    heights, _ = read_tip_heights(flat, tuple(s.number for s in plan.slots), encoding,
                                  contact_um)
    mismatch, sigma = heights.mismatch_mm(pair)
    at = dict(heights.heights_mm)

    def value(shift_mm: float) -> float:
        moved = {**at, pair[0]: at[pair[0]] + shift_mm}
        if r is None:
            return offset_ratio(sample, k, pair, float(k_obj), force_r_N, moved)
        return offset_object_stiffness(sample, k, pair, r, force_r_N, moved)

    key = "r_zeroed" if r is None else "k_obj_zeroed_N_per_mm"
    spread = sorted((value(-sigma), value(sigma)))
    return {"flat": flat, "force_r_N": force_r_N, "mismatch_um": 1e3 * mismatch,
            "mismatch_sigma_um": 1e3 * sigma, key: value(0.0),
            f"{key}_at_sigma": spread}


def _check_force_r(force_r_N: float | None) -> None:
    """Refuse a reference force that is missing, not finite or not > 0 (with ``--flat``).

    Raises:
        TactcadError: naming ``--force-r`` and its value.
    """
    if force_r_N is None or not (math.isfinite(force_r_N) and force_r_N > 0):
        shown = "--force-r (not given)" if force_r_N is None else f"--force-r = {force_r_N!r}"
        raise TactcadError(f"{shown}: allowed > 0 N with --flat (the reference element's force "
                           "at the reading)")


def _yield_force_N(plan, element: int) -> float | None:
    """The tip force (N) at which ``element`` yields at the closed form (its yield limit
    without the safety factor), or None for a material without a yield strength."""
    from tactcad.mechanics.limits import plan_limits

    try:
        limits = plan_limits(plan, "closed-form")
    except DesignError:
        return None
    return next((lim.force_N * plan.strength.safety_factor for lim in limits
                 if lim.element == element and lim.limit == "yield"), None)


def evaluate(k_m: float, k_r: float, k_obj: float | None = None, r: float | None = None,
             sigma_r: float | None = None) -> dict:
    """The numbers the command prints, as a dict (N/mm, dimensionless R); every
    value finite.

    Exactly one of ``k_obj`` and ``r`` is given.

    Raises:
        tactcad.mechanics.lumped_model.LumpedDomainError: an input out of the model's domain.
        TactcadError: a K_obj whose R rounds onto the domain's edge, or a result that
            is not finite; the message names the inputs the user gave.
    """
    from tactcad.mechanics import lumped_model as lumped

    if (k_obj is None) == (r is None):
        raise ValueError("give exactly one of k_obj and r")
    given = {"--km": k_m, "--kr": k_r, **({"--kobj": k_obj} if r is None else {"--r": r})}
    if sigma_r is not None:
        given["--sigma-r"] = sigma_r
    try:
        out = _results(lumped, k_m, k_r, k_obj, r, sigma_r)
    except lumped.LumpedDomainError as exc:
        if exc.quantity != "R" or k_obj is None:
            option = OPTION_OF_QUANTITY.get(exc.quantity)
            if option is None:
                raise
            raise DesignError(option, float(exc.value), exc.condition) from None
        # R was computed from K_obj, not given: name what the user gave
        raise TactcadError(f"{_inputs(given)}: allowed a K_obj whose R = (K_r + K_obj)/(K_m + K_obj) "
                           f"lies strictly inside 1 ... K_r/K_m in double precision (R rounds to "
                           f"{float(exc.value):.17g})") from None
    bad = [k for k, v in out.items() if not math.isfinite(float(v))]
    if bad:
        raise TactcadError(f"{_inputs(given)}: allowed inputs whose results are finite "
                           f"({bad[0]} = {out[bad[0]]} overflows double precision)")
    return out


def _source_words(source: dict | None, args: argparse.Namespace) -> str:
    """Where K_m and K_r came from, for the text's first line: "" when both were given."""
    if source is None:
        return ""
    taken = [q for q, v, d in (("K_m", args.km, source["k_m_N_per_mm"]),
                               ("K_r", args.kr, source["k_r_N_per_mm"])) if v == d]
    unit = (f" unit {source['unit'][0]}/{source['unit'][1]}"
            if source["unit"] is not None else "")
    return (f"; {' and '.join(taken)} from {source['design']}{unit} at {source['model']}, "
            "as tactcad stiffness gives them")


def _inputs(given: dict) -> str:
    return ", ".join(f"{k} = {v:.6g}" for k, v in given.items())


def _results(lumped, k_m, k_r, k_obj, r, sigma_r) -> dict:
    if r is None:
        r = lumped.deflection_ratio(k_m, k_r, k_obj)
        r_minus_one = lumped.deflection_ratio_excess(k_m, k_r, k_obj)
    else:
        k_obj = lumped.object_stiffness(r, k_m, k_r)
        r_minus_one = r - 1.0
    out = {
        "k_m_N_per_mm": k_m,
        "k_r_N_per_mm": k_r,
        "k_r_over_k_m": k_r / k_m,
        "k_obj_N_per_mm": k_obj,
        "r": r,
        "r_minus_one": r_minus_one,
        "sensitivity_dk_obj_dr_N_per_mm": lumped.sensitivity(r, k_m, k_r),
    }
    if sigma_r is not None:
        out["sigma_r"] = sigma_r
        out["sigma_k_obj_N_per_mm"] = lumped.propagate_sigma(r, sigma_r, k_m, k_r)
    return out


def run(args: argparse.Namespace) -> int:
    """Handler of ``tactcad lumped``; returns the exit code (0)."""
    source = design_stiffness(args)
    if source is not None:  # the ones not given, from the design
        args.km = source["k_m_N_per_mm"] if args.km is None else args.km
        args.kr = source["k_r_N_per_mm"] if args.kr is None else args.kr
    result = evaluate(args.km, args.kr, k_obj=args.kobj, r=args.r, sigma_r=args.sigma_r)
    if source is not None:
        result["stiffness_source"] = source
    if (args.flat or args.force_r is not None) and args.coupled_design is None:
        raise TactcadError(f"--{'flat' if args.flat else 'force-r'} = given without "
                           "--coupled-design: allowed only with it (the heights act through "
                           "the coupled model)")
    if args.force_r is not None and not args.flat:
        raise TactcadError("--force-r = given without --flat: allowed only with --flat")
    if (args.encoding or args.contact_um) and not args.flat:
        raise TactcadError(f"--{'encoding' if args.encoding else 'contact-um'} = "
                           f"{args.encoding or args.contact_um}: allowed only with --flat")
    if args.flat:
        _check_force_r(args.force_r)  # before the design is loaded: a quick refusal
    if args.coupled_design is not None:
        result["coupled"] = coupled_form(args.coupled_design, args.unit, args.km, args.kr,
                                         args.kobj, args.r, args.flat, args.force_r,
                                         args.encoding, args.contact_um)
    if args.json:
        print(dumps(result))
        return 0
    given_r = args.r is not None
    print(f"K_m = {result['k_m_N_per_mm']:.6g} N/mm, K_r = {result['k_r_N_per_mm']:.6g} N/mm "
          f"(K_r/K_m = {result['k_r_over_k_m']:.6g})" + _source_words(result.get(
              "stiffness_source"), args))
    if given_r:
        print(f"R = {result['r']:.6g} (given)")
        print(f"K_obj = {result['k_obj_N_per_mm']:.6g} N/mm (eq. 3)")
    else:
        print(f"K_obj = {result['k_obj_N_per_mm']:.6g} N/mm (given)")
        print(f"R = {result['r']:.6g} (eq. 2), R - 1 = {result['r_minus_one']:.6g}")
    print(f"dK_obj/dR = {result['sensitivity_dk_obj_dr_N_per_mm']:.6g} N/mm")
    from tactcad.in_use.tissue_coupling import unit_label

    c = result.get("coupled")
    if c and "r_coupled" in c:
        print(f"R = {c['r_coupled']:.6g} (eq. 2 corrected: unit {unit_label(c['unit'])} "
              f"of {args.coupled_design}, every tip on one half-space)")
    elif c:
        print(f"K_obj = {c['k_obj_coupled_N_per_mm']:.6g} N/mm (eq. 3 corrected: unit "
              f"{unit_label(c['unit'])} of {args.coupled_design}, every tip on one half-space)")
    z = (c or {}).get("zeroed")
    if z and "k_obj_zeroed_N_per_mm" in z:
        lo, hi = z["k_obj_zeroed_N_per_mm_at_sigma"]
        print(f"K_obj = {z['k_obj_zeroed_N_per_mm']:.6g} N/mm (and the tips' heights of {z['flat']}"
              f" taken out: mismatch {z['mismatch_um']:.3g} +- {z['mismatch_sigma_um']:.2g} um at "
              f"F_r {z['force_r_N']:.4g} N; {lo:.6g} ... {hi:.6g} N/mm over +-1 sigma)")
    elif z:
        lo, hi = z["r_zeroed_at_sigma"]
        print(f"R = {z['r_zeroed']:.6g} (and the tips' heights of {z['flat']}: mismatch "
              f"{z['mismatch_um']:.3g} +- {z['mismatch_sigma_um']:.2g} um at F_r "
              f"{z['force_r_N']:.4g} N; {lo:.6g} ... {hi:.6g} over +-1 sigma)")
    if "sigma_k_obj_N_per_mm" in result:
        print(f"sigma_K_obj = {result['sigma_k_obj_N_per_mm']:.6g} N/mm "
              f"(first order, sigma_R = {result['sigma_r']:.6g})")
    return 0
