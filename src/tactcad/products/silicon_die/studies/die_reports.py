"""The die's strength and stiffness as the commands and the API report them: each row's
beam root against the strength of etched silicon, each row's K on its frame at the closed
form or fem3d (the solve kept in the result store). One computation for ``tactcad strength``
and ``stiffness`` on a die's file, the die's export (its review page and manifest) and
:class:`tactcad.api.DieProject`.

Units: um, N/mm, N, MPa, s.
"""

from __future__ import annotations

import json
import time
from typing import Callable

from tactcad.products.silicon_die.studies.die_verification import die_verification
from tactcad.studies.verification import matrix_table


def fem3d_solving_line(plan, beam) -> str:
    """What is about to be solved at fem3d for ``beam`` and what it costs: the finer mesh's
    unknowns (counted without solving, :func:`~tactcad.products.silicon_die.mechanics.
    die_fem3d.mesh_dofs`) against the shipped dies' (about 45 s a beam on two cores), and
    the sliver between the post's edge and the beam's when the mesh snaps the post's sides
    onto the beam's (thinner than :func:`~tactcad.products.silicon_die.mechanics.die_fem3d.
    sliver_tolerance_um`, um): kept, it would set the finest edge across the beam, from
    which the frame's cells grow.

    Args:
        plan: the die's plan. beam: one of its beams.

    Returns:
        One progress line.
    """
    from tactcad.products.silicon_die.mechanics.die_fem3d import (SHIPPED_FINE_DOFS, mesh_dofs,
                                                                  sliver_tolerance_um,
                                                                  snapped_footprint)

    fine = mesh_dofs(plan, beam)[1]
    lo, hi = SHIPPED_FINE_DOFS
    line = (f"fem3d of die {plan.name}'s {beam.role} beam on its frame: two meshes, "
            f"extrapolated; the finer {fine:,} unknowns (the shipped dies' {lo:,} ... "
            f"{hi:,}: about 45 s a beam on two cores; the time grows faster than the unknowns)")
    snapped = snapped_footprint(plan, beam).snapped_um
    if snapped > 0:  # a sliver the whole block would carry: merged into the beam's edge
        line += (f"; the post's sides {snapped:.3g} um inside the beam's snapped onto them "
                 f"(under {sliver_tolerance_um(beam):.3g} um: no sliver of cells across the "
                 "block; K does not see the post's footprint)")
    return line


def die_beam_fem3d_kept(plan, beam, reused: Callable[[str], None] | None = None,
                        solving: Callable[[], None] | None = None,
                        progress: Callable[[str], None] | None = None):
    """:func:`tactcad.products.silicon_die.mechanics.die_fem3d.die_beam_fem3d`, kept in the result store for the
    same plan and beam (a second run of the same die solves nothing).

    Args:
        plan: the die's plan. beam: one of its beams.
        reused: called once, with where it came from, when the solve is a kept one
            (:func:`tactcad.store.kept_result`).
        solving: called once before the beam is solved (not when a kept solve is reused).
        progress: told each mesh's solve as it goes (:func:`~tactcad.products.silicon_die.
            mechanics.die_fem3d.die_beam_fem3d`); None says nothing.

    Returns:
        :class:`tactcad.products.silicon_die.mechanics.die_fem3d.DieBeamFem` (N/mm, Hz, s).
    """
    from tactcad.products.silicon_die.mechanics.die_fem3d import die_beam_fem3d
    from tactcad.store import kept_result

    def solve():
        if solving is not None:
            solving()
        return die_beam_fem3d(plan, beam, progress=progress)

    return kept_result("die beam fem3d", solve,
                       json.dumps(plan.as_json(), sort_keys=True, default=str), beam,
                       reused=reused)


def strength_report(plan) -> tuple[dict, list[str]]:
    """Each row's beam root at the force it carries in use against the mean strength of
    etched silicon (and the lab's Weibull pair's failure probability, when stated), with the
    rated-force requirement and the largest rating the die verifies (``largest_rating_N``,
    :func:`~tactcad.products.silicon_die.design.mems_die.largest_verified_rating`: each limit
    with its model error's room, with what binds it: the rating ``design`` refuses past, and
    the design atlas's ``max_force_N``; ``largest_rating_nominal_N`` the least limit without
    that room): (report, text lines). MPa, N, um."""
    from tactcad.products.silicon_die.design.mems_die import (BOSCH_MEAN_STRENGTH_MPA,
                                                              BOSCH_STRENGTH_SOURCE,
                                                              ROOT_KT_SOURCE,
                                                              largest_verified_rating)
    from tactcad.products.silicon_die.mechanics.die_strength import beam_failure_probability

    rated = next(r for r in die_verification(plan) if r["requirement"] == "full_scale_force_N")
    rows = []
    for beam in plan.beams[:: plan.columns]:
        force = plan.rated_force_N(beam)
        nominal_per_N = plan.stress_MPa_at_rating(beam) / plan.full_scale_force_N
        kt = plan.root_stress_concentration(beam)
        per_N = kt * nominal_per_N
        stress = per_N * force
        rows.append({"role": beam.role, "row": beam.row, "length_um": beam.length_um,
                     "width_um": beam.width_um, "thickness_um": beam.thickness_um,
                     "root_fillet_um": plan.root_fillet_um,
                     "root_nominal_stress_MPa_per_N": nominal_per_N,
                     "root_stress_concentration_factor": kt,
                     "root_peak_stress_MPa_per_N": per_N, "rated_force_N": force,
                     "root_peak_stress_MPa_at_rated_force": stress,
                     "fracture_force_N": BOSCH_MEAN_STRENGTH_MPA / per_N,
                     "strength_over_stress": BOSCH_MEAN_STRENGTH_MPA / stress,
                     "failure_probability_at_rated_force":
                         None if plan.weibull is None
                         else beam_failure_probability(plan, beam, force)})
    largest, binds, nominal = largest_verified_rating(plan)
    report = {"die": plan.name, "model": "closed-form",
              "strength_MPa": BOSCH_MEAN_STRENGTH_MPA, "strength_source": BOSCH_STRENGTH_SOURCE,
              "rows": rows, "requirement": rated, "passed": rated["verdict"] != "fail",
              "largest_rating_N": largest, "largest_rating_binds": binds,
              "largest_rating_nominal_N": nominal,
              "reasons": {"root_stress": "the root's peak on its fillets' top edge: K_t x "
                                         "6 F L / (w t^2), the beam's nominal surface "
                                         f"bending stress at the root, K_t of its "
                                         f"{plan.root_fillet_um:g} um fillets "
                                         f"({ROOT_KT_SOURCE})",
                          "strength": "the mean tensile strength of Bosch-etched silicon "
                                      "bars" + ("" if plan.weibull is None else
                                                "; the failure probability from "
                                                f"{plan.weibull.whose}")}}
    lines = [f"die {plan.name}, model closed-form: each row's beam root at the force it "
             f"carries in use; strength {BOSCH_MEAN_STRENGTH_MPA:g} MPa ({BOSCH_STRENGTH_SOURCE})",
             "| row | role | L um | w um | t um | K_t | peak MPa/N | rated force mN | "
             "root peak MPa there | fracture force mN | strength / stress | P_f at rating |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        p_f = r["failure_probability_at_rated_force"]
        lines.append(f"| {r['row']} | {r['role']} | {r['length_um']:.4g} | {r['width_um']:g} | "
                     f"{r['thickness_um']:g} | {r['root_stress_concentration_factor']:.3g} | "
                     f"{r['root_peak_stress_MPa_per_N']:.4g} | "
                     f"{1e3 * r['rated_force_N']:.3g} | "
                     f"{r['root_peak_stress_MPa_at_rated_force']:.4g}"
                     f" | {1e3 * r['fracture_force_N']:.3g} | {r['strength_over_stress']:.3g} | "
                     + ("n/a (no Weibull pair: state [strength])" if p_f is None
                        else f"{p_f:.3g}") + " |")
    lines += [report["reasons"]["root_stress"], matrix_table([rated]),
              f"largest rating within every limit of the die by its model error: "
              f"{largest:.4g} N ({largest / plan.full_scale_force_N:.3g} x the rating; bound "
              f"by {binds}; {nominal:.4g} N at the limit itself)"]
    return report, lines


#: The keys of a die's ``stiffness --model fem3d --json`` rows renamed, old -> new: the
#: closed form's K and its error against fem3d under the names the die's FE check and
#: ``tactcad die --fem3d`` give them (docs/reference/glossary.md); the old keys are still
#: written beside them and listed in each row's ``deprecated_keys``.
STIFFNESS_RENAMED = {"closed_form_N_per_mm": "K_closed_form_N_per_mm",
                     "closed_form_error_rel": "K_closed_form_error_rel"}


def stiffness_report(plan, model: str = "closed-form",
                     progress: Callable[[str], None] | None = None) -> tuple[dict, list[str]]:
    """Each row's beam K on its frame at ``model`` (``closed-form``, or ``fem3d`` with the
    closed form's K and its error against fem3d, ``K_closed_form_N_per_mm`` and
    ``K_closed_form_error_rel``, old names beside them, :data:`STIFFNESS_RENAMED`, and how
    far the mesh snapped the post's sides onto the beam's, ``snapped_um``; the fem3d solve
    kept in the result store): (report, text lines). N/mm, um, s.

    ``progress`` (fem3d) is told, before each beam is solved, its finer mesh's unknowns
    against the shipped dies' (:func:`fem3d_solving_line`), then each mesh as it is solved,
    or where a kept solve came from; None says nothing."""
    say = progress or (lambda line: None)
    from tactcad.in_use.kobj_budget import with_declared_deprecated_keys
    from tactcad.products.silicon_die.design.mems_die import (CLOSED_FORM_K_ERROR_REL,
                                                              root_extension_um)

    rows = []
    for beam, k, target in zip(plan.beams[:: plan.columns], (plan.k_r_N_per_mm, plan.k_m_N_per_mm),
                               plan.targets):
        row = {"role": beam.role, "row": beam.row, "length_um": beam.length_um,
               "width_um": beam.width_um, "thickness_um": beam.thickness_um,
               "root_extension_um": root_extension_um(beam.width_um, beam.thickness_um),
               "target_N_per_mm": target, "model": "closed-form", "stiffness_N_per_mm": k,
               "error_estimate_rel": CLOSED_FORM_K_ERROR_REL}
        if model == "fem3d":
            fem = die_beam_fem3d_kept(
                plan, beam, reused=lambda where, role=beam.role: say(
                    f"fem3d of die {plan.name}'s {role} beam: {where} (the same die)"),
                solving=lambda b=beam: say(fem3d_solving_line(plan, b)), progress=say)
            row.update(model="fem3d", stiffness_N_per_mm=fem.k_N_per_mm,
                       error_estimate_rel=fem.k_error_rel, K_closed_form_N_per_mm=k,
                       K_closed_form_error_rel=k / fem.k_N_per_mm - 1.0,
                       wall_time_s=fem.wall_time_s, dofs=fem.dofs,
                       snapped_um=fem.snapped_um)
            row = with_declared_deprecated_keys(row, STIFFNESS_RENAMED)
        rows.append(row)
    report = {"die": plan.name, "model": model, "rows": rows,
              "K_r_over_K_m": rows[0]["stiffness_N_per_mm"] / rows[1]["stiffness_N_per_mm"]}
    lines = [f"die {plan.name}, model {model}: each row's beam on its frame (the device layer "
             "on the handle, the cavity under the beam)",
             "| row | role | L um | w um | t um | K N/mm | error | target N/mm |"
             + (" closed form | s |" if model == "fem3d" else ""),
             "| --- | --- | --- | --- | --- | --- | --- | --- |"
             + (" --- | --- |" if model == "fem3d" else "")]
    for r in rows:
        lines.append(f"| {r['row']} | {r['role']} | {r['length_um']:.4g} | {r['width_um']:g} | "
                     f"{r['thickness_um']:g} | {r['stiffness_N_per_mm']:.4g} | "
                     f"+-{100 * r['error_estimate_rel']:.2g} % | {r['target_N_per_mm']:.4g} |"
                     + (f" {100 * r['K_closed_form_error_rel']:+.2f} % | {r['wall_time_s']:.1f} |"
                        if model == "fem3d" else ""))
    lines.append(f"K_r / K_m {report['K_r_over_K_m']:.4g}; closed form: bending over L + dL "
                 "(the frame's give at the root) and Timoshenko shear over L")
    snapped = max((r.get("snapped_um", 0.0) for r in rows), default=0.0)
    if snapped > 0:
        lines.append(f"fem3d: the posts' sides snapped {snapped:.3g} um onto the beams' sides "
                     "(a sliver thinner than the mesh's edge); K does not see the post's "
                     "footprint, and the coarser mesh this leaves is in the error estimate")
    return report, lines


#: The die's modal levels: the closed form (Rayleigh with the post as a tip mass) and fem3d
#: (each row's beam on its frame, :func:`die_beam_fem3d_kept`: the solve ``tactcad die
#: --fem3d`` and ``stiffness --model fem3d`` make and keep).
DIE_MODAL_LEVELS = ("closed-form", "fem3d")


#: The keys of a die's ``modal --json`` rows renamed, old -> new: the closed form's first
#: resonance and its error against the row's level under the names the die's record gives
#: them (``tactcad die --fe-check``'s ``closed_form_first_Hz``, ``--fem3d``'s
#: ``first_Hz_closed_form_error_rel``; docs/reference/glossary.md). The old keys are still
#: written beside the new ones with the same values and each row lists them in its
#: ``deprecated_keys`` (:func:`tactcad.in_use.kobj_budget.with_declared_deprecated_keys`);
#: they go in a later release.
MODAL_RENAMED = {"closed_form_Hz": "closed_form_first_Hz",
                 "closed_form_error_rel": "first_Hz_closed_form_error_rel"}


def modes_report(plan, model: str = "closed-form",
                 progress: Callable[[str], None] | None = None) -> tuple[dict, list[str]]:
    """Each row's first resonance, its beam with its post on the frame, at ``model``, with
    the level's error estimate and cost: one record of the same keys at every level, for
    ``tactcad modal`` on a die's file and :meth:`tactcad.api.DieProject.modes`.

    At ``closed-form`` a row's first frequency is Rayleigh's
    (:func:`tactcad.products.silicon_die.mechanics.die_dynamics.beam_modes`), its error
    estimate :data:`~tactcad.products.silicon_die.mechanics.die_dynamics.CLOSED_FORM_F1_ERROR_REL`;
    at ``fem3d`` it is the die's fem3d solve (:func:`die_beam_fem3d_kept`, the one ``tactcad
    die --fem3d`` makes: kept in the result store, so a second run solves nothing), its
    error estimate the extrapolation's change, with the closed form's error against it.

    Args:
        plan: the die's plan. model: ``closed-form`` or ``fem3d``.
        progress: told what is solved or reused (fem3d); None says nothing.

    Returns:
        (report, text lines): the report's ``rows`` hold, per row, ``first_Hz`` (Hz),
        ``first_Hz_error_rel``, ``wall_time_s`` (s; a reused solve's the run's that kept it),
        ``reused``, ``dofs`` (None at the closed form), ``closed_form_first_Hz`` (Hz) and
        ``first_Hz_closed_form_error_rel`` (the closed form's against this level; None at
        the closed form), the names ``tactcad die --fem3d`` and ``--fe-check`` give them,
        with their old names (:data:`MODAL_RENAMED`) beside them, listed in the row's
        ``deprecated_keys``; ``resonance_Hz`` the closed form's Rayleigh and exact figures,
        as the die's record holds them.

    Raises:
        ValueError: ``model`` is not one of :data:`DIE_MODAL_LEVELS`.
    """
    from tactcad.in_use.kobj_budget import with_declared_deprecated_keys
    from tactcad.products.silicon_die.mechanics.die_dynamics import (CLOSED_FORM_F1_ERROR_REL,
                                                                     beam_modes)

    if model not in DIE_MODAL_LEVELS:
        raise ValueError(f"model {model!r}: one of {', '.join(DIE_MODAL_LEVELS)} for a die")
    say = progress or (lambda line: None)
    rows, closed = [], {}
    for beam in plan.beams[:: plan.columns]:
        t0 = time.perf_counter()
        modes = closed[beam.role] = beam_modes(plan, beam)
        row = {"role": beam.role, "row": beam.row, "model": "closed-form",
               "first_Hz": modes.rayleigh_Hz, "first_Hz_error_rel": CLOSED_FORM_F1_ERROR_REL,
               "wall_time_s": time.perf_counter() - t0, "reused": False, "dofs": None,
               "closed_form_first_Hz": modes.rayleigh_Hz,
               "first_Hz_closed_form_error_rel": None}
        if model == "fem3d":
            kept, role = [], beam.role

            def on_reuse(where: str) -> None:
                kept.append(True)
                say(f"fem3d of die {plan.name}'s {role} beam: {where} (the same die)")

            def on_solve(b=beam) -> None:
                say(fem3d_solving_line(plan, b))

            fem = die_beam_fem3d_kept(plan, beam, reused=on_reuse, solving=on_solve,
                                      progress=say)
            row.update(model="fem3d", first_Hz=fem.f1_Hz, first_Hz_error_rel=fem.f1_error_rel,
                       wall_time_s=fem.wall_time_s, reused=bool(kept), dofs=fem.dofs,
                       first_Hz_closed_form_error_rel=modes.rayleigh_Hz / fem.f1_Hz - 1.0)
        rows.append(with_declared_deprecated_keys(row, MODAL_RENAMED))
    lowest = min(rows, key=lambda r: r["first_Hz"])
    report = {"die": plan.name, "model": model, "rows": rows,
              "lowest_first_Hz": lowest["first_Hz"], "lowest_role": lowest["role"],
              "reused": all(r["reused"] for r in rows),
              "resonance_Hz": {role: {"rayleigh": m.rayleigh_Hz, "exact": m.exact_Hz,
                                      "rayleigh_error_rel": m.rayleigh_error_rel}
                               for role, m in closed.items()}}
    basis = ("Rayleigh with the post as a tip mass on the closed form's K"
             if model == "closed-form" else
             "scikit-fem, silicon's anisotropic stiffness, triquadratic hexahedra, two meshes "
             "extrapolated")
    lines = [f"die {plan.name}, model {model}: each row's first bending mode, its beam with "
             f"its post on the frame ({basis})"]
    for r in rows:
        m = closed[r["role"]]
        versus = (f"Rayleigh; the exact Euler-Bernoulli root {m.exact_Hz / 1e3:.4g} kHz, "
                  f"{100 * m.rayleigh_error_rel:+.2f} %" if model == "closed-form" else
                  f"closed form {r['closed_form_first_Hz'] / 1e3:.4g} kHz, "
                  f"{100 * r['first_Hz_closed_form_error_rel']:+.2f} %")
        cost = (f"solved in {r['wall_time_s']:.3g} s by an earlier run, reused" if r["reused"]
                else f"{r['wall_time_s']:.3g} s")
        lines.append(f"  {r['role']} beam (row {r['row']}): f1 {r['first_Hz'] / 1e3:.4g} kHz "
                     f"+/- {100 * r['first_Hz_error_rel']:.2g} % ({versus}); {cost}"
                     + (f", {r['dofs']} dofs" if r["dofs"] is not None else ""))
    lines.append(f"lowest first resonance: {lowest['first_Hz'] / 1e3:.4g} kHz "
                 f"({lowest['role']} beam)")
    return report, lines
