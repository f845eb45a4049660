"""The die's grasp as ``tactcad grasp`` on a die reports it, for the command (its view,
:mod:`tactcad.products.silicon_die.commands.die_views`) and the die's export (its review
page): the die's jaw closed on tissue, each post's force against its beam's rating and
breaking force.

Units: N, N/mm, mm, degrees.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

from tactcad.errors import DesignError


def default_grasp_options() -> SimpleNamespace:
    """The ``tactcad grasp`` command's options :func:`die_grasp_record` reads, at the
    command's defaults (no option given: the tissue a layer, the wedge profile, every
    figure its default), for a grasp the command line did not ask for (the export's review
    page)."""
    from tactcad.in_use.grasp_experiment import DEFAULT_PROFILE

    return SimpleNamespace(force_N=None, angle_deg=None, kobj=None, opening_deg=None,
                           slab_thickness_mm=None, coupling="layer", profile=DEFAULT_PROFILE)


def die_grasp_record(plan, mount, args, design: str | None):
    """The die's grasp as ``tactcad grasp`` on a die reports it: its jaw (``mount``) closed on
    tissue at the force, angle, K_obj, opening, coupling and profile ``args`` ask for (each
    None: its default, whose reason the record's ``reasons`` give).

    Args:
        plan: the die as planned. mount: its mount in the jaw
            (:func:`tactcad.products.silicon_die.design.die_mount.die_mount`).
        args: the grasp command's options (``force_N``, ``angle_deg``, ``kobj``,
            ``opening_deg``, ``slab_thickness_mm``, ``coupling``, ``profile``;
            :func:`default_grasp_options` for none given).
        design: the design file's name as the record names it (None: a die made from
            targets).

    Returns:
        (the record, the grasp result), N, N/mm, mm, degrees.

    Raises:
        DesignError: an option out of its range (the command names it as its option,
            :func:`tactcad.commands.options.grasp_option_error`).
    """
    from tactcad.products.silicon_die.in_use.die_grasp import (default_grasp_force_N, die_grasp,
                                                                die_jaw)
    from tactcad.in_use.grasp_experiment import (kobj_range_warning, overload_warning,
                                                 overloaded_sites, with_kobj_range)
    from tactcad.studies.grasp_report import with_grasp_deprecated_keys

    lo, hi = plan.kobj_range_N_per_mm
    k_obj = args.kobj if args.kobj is not None else math.sqrt(lo * hi)
    opening = args.opening_deg if args.opening_deg is not None else mount.opening_angle_deg
    asked = args.angle_deg is not None or args.force_N is not None
    force = args.force_N if asked else default_grasp_force_N(plan)
    rated = role_ratings_N(plan)
    force_why = ("--force-N" if args.force_N is not None else "--angle-deg"
                 if args.angle_deg is not None else
                 f"half each beam's own rated force ({rated_words(rated)}) summed over its "
                 f"{len(plan.beams)} beams")
    jaw = die_jaw(mount, opening, args.slab_thickness_mm)
    shut = dict(coupling=args.coupling, profile=args.profile)
    try:
        result = die_grasp(plan, mount, jaw, k_obj, angle_deg=args.angle_deg,
                           force_N=None if args.angle_deg is not None else force, **shut)
    except DesignError as exc:
        if asked or exc.field != "force_N":
            raise
        # the default force out of the tissue's reach: the jaw fully open or closed flat
        result = die_grasp(plan, mount, jaw, k_obj, angle_deg=jaw.opening_angle_deg, **shut)
        if result.total_force_N <= force:
            result = die_grasp(plan, mount, jaw, k_obj, angle_deg=0.0, **shut)
        force_why = (f"{force_why} ({force:g} N) is out of the tissue's reach: the jaw at "
                     f"{result.angle_deg:g} degrees takes {result.total_force_N:.4g} N")
    result = with_kobj_range(result, (lo, hi))
    warnings = [w for w in (kobj_range_warning(k_obj, (lo, hi)), overload_warning(result)) if w]
    record = {"design": design, "die": plan.name,
              "kobj_range_N_per_mm": [lo, hi], "warnings": warnings,
              # a beam past its breaking force: the grasp does not pass (exit 1)
              "passed": not overloaded_sites(result.tips),
              "jaw": {"pin_x_mm": mount.pin_x_mm, "jaw_length_mm": mount.jaw_length_mm,
                      "pin_to_tip_mm": jaw.pin_to_tip_mm,
                      "opening_angle_deg": jaw.opening_angle_deg,
                      "slab_thickness_mm": jaw.slab_thickness_mm},
              "K_obj_N_per_mm": k_obj, "coupling": args.coupling, "profile": args.profile,
              "full_scale_force_N": plan.full_scale_force_N, "rated_force_N_by_role": rated,
              "post_proud_mm": mount.post_proud_mm,
              "grasp": result.as_json(),
              "reasons": {"force_N": force_why,
                          "K_obj": "--kobj" if args.kobj is not None else
                          f"the geometric mean of the die's K_obj range {lo:g} ... {hi:g} N/mm",
                          "opening": "--opening-deg" if args.opening_deg is not None else
                          "the jaw's opening_angle_deg",
                          "rated_force_N": "each beam's own: the most it carries in use "
                                           "(the full-scale force on a reference beam, K_m "
                                           "x its rated travel on a measuring beam), as "
                                           "strength and verify rate it",
                          "overload_limit_N": "each beam's root at the mean strength of "
                                              "etched silicon bars (no Weibull modulus)",
                          "error": error_words(args.coupling)}}
    # the old name of the K_obj range beside the glossary's, as the metal grasp writes it
    record = with_grasp_deprecated_keys(record)
    return record, result


def error_words(coupling: str) -> str:
    """What the die's grasp error holds, by the tissue's ``coupling``: uncoupled (``none``,
    eq. 1) no coupling between the posts is in the read R to name."""
    caveat = ("the tissue is not coupled between the posts (--coupling none, eq. 1)"
              if coupling == "none" else
              "the tissue's coupling between neighbouring posts stays in it (the die's "
              "budget: the coupled inversion removes it)")
    return (f"eq. 3 on the read R: {caveat}; a unit's two posts share one radius, so the "
            "travel correction changes nothing")


def role_ratings_N(plan) -> dict[str, float]:
    """Each beam role's rated force (N), as :meth:`DiePlan.rated_force_N` gives it (every
    beam of a role carries one rating)."""
    return {b.role: plan.rated_force_N(b) for b in plan.beams}


def rated_words(rated: dict[str, float]) -> str:
    """The roles' ratings in words (mN), e.g. ``9 mN reference, 4.95 mN measuring``."""
    return ", ".join(f"{1e3 * f:.3g} mN {role}" for role, f in rated.items())
