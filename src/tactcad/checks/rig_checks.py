"""The test rigs against the design's rating: no rig loads an element beyond the
rated full-scale force, the force gauge reads the range the rigs need to
the resolution the rating asks (:mod:`tactcad.studies.rig_sizing`), and the
sample kit spans the design's K_obj range (what ``evaluate`` runs over)."""

from __future__ import annotations

from typing import Iterator

from tactcad.checks.check_result import CheckResult
from tactcad.checks.groups import CheckContext, Found

#: How far (relative) a sample may fall inside an end of the K_obj range and still
#: cover it: samples are stated to 3 significant digits (10.01 N/mm is cast as 10.0).
SPAN_TOLERANCE = 5e-3


def rig_group(context: CheckContext) -> Iterator[Found]:
    """``rigs``: the rigs of the design against its rating (none without the
    rigs; a project without test rigs gets one result that says so and why)."""
    from tactcad.design.project import has_test_rigs, no_test_rigs_reason

    if context.project is None:
        return
    if not has_test_rigs(context.project):
        yield "rigs", [CheckResult("test rigs", "project", True,
                                   "not checked: " + no_test_rigs_reason(context.project))]
        return
    yield "rigs", rig_checks(context.plan, context.project.rigs, context.project.scenes,
                             context.project.scenes_file)


def rig_checks(plan, rigs, scenes=None, scenes_file: str = "") -> list[CheckResult]:
    """The evaluation rig's top load, the force gauge and the sample kit against the
    design's rated full-scale force and K_obj range (each result names the rig, the part,
    the load and the rating). Where the kit fails, the gauge is sized for the kit it
    suggests, so that every suggestion of one report holds when all are pasted; ``scenes``
    (by name, from ``scenes_file``), given, are the scenes whose sample it names to set."""
    from tactcad.studies.verification import rated_full_scale_force

    rated = rated_full_scale_force(plan)
    after = kit_after_suggestion(plan, rigs)
    return [evaluation_load_check(plan, rigs, rated, samples_after=after),
            force_gauge_check(rigs, rated, samples_after=after),
            sample_kit_check(plan, rigs, rated, scenes, scenes_file)]


def kit_spans(plan, samples) -> bool:
    """True when ``samples`` (N/mm) span the design's K_obj range (stated or derived),
    within :data:`SPAN_TOLERANCE`."""
    from tactcad.studies.verification import requirements_of

    lo, hi = requirements_of(plan).kobj_range_N_per_mm
    return min(samples) <= lo * (1 + SPAN_TOLERANCE) and max(samples) >= hi * (1 - SPAN_TOLERANCE)


def suggested_kit(plan) -> list[float]:
    """The samples (N/mm, stiffest first) the sample kit check suggests: the design's own,
    those ``evaluate`` runs over."""
    from tactcad.studies.design_loads import design_samples

    return sorted(design_samples(plan), reverse=True)


def kit_after_suggestion(plan, rigs) -> list[float]:
    """The samples (N/mm) the rigs hold once check's suggestions are pasted: their own
    where they span the design's K_obj range, else :func:`suggested_kit`."""
    own = list(rigs.sample_stiffness_N_per_mm)
    return own if kit_spans(plan, own) else suggested_kit(plan)


def suggested_gauge(model: str, need):
    """The catalogue gauge a suggestion names for ``need``: the rig's own ``model`` where
    the catalogue holds it and it fits (its stated values corrected), else the catalogue's
    choice (:func:`~tactcad.vocabulary.force_gauge_catalogue.choose_force_gauge`).

    Returns:
        (the gauge, its shortfalls in words: empty when it fits).
    """
    from tactcad.vocabulary.force_gauge_catalogue import (catalogue_gauge, choose_force_gauge,
                                                          gauge_shortfalls)

    own = catalogue_gauge(model)
    if own is not None and not gauge_shortfalls(own.range_N, own.resolution_N, need):
        return own, []
    return choose_force_gauge(need)


def gauge_setting(gauge, rigs_file: str) -> str:
    """Every key a rigs file changes to carry the catalogue ``gauge``, in TOML as pasted
    under its ``[force_gauge]`` table."""
    return (f'{rigs_file} [force_gauge] model = "{gauge.model}", range_N = {gauge.range_N!r}, '
            f"resolution_N = {gauge.resolution_N!r}, "
            f"stiffness_N_per_mm = {gauge.stiffness_N_per_mm!r}")


def sample_kit_check(plan, rigs, rated_N: float | None = None, scenes=None,
                     scenes_file: str = "") -> CheckResult:
    """Fails when the rigs' samples (``[sample] stiffness_N_per_mm``, N/mm) do not span the
    design's K_obj range (``requirements.kobj_range_N_per_mm``, stated or derived, N/mm):
    the lab's kit would not test the stiffnesses ``evaluate`` and the design claim.

    Args:
        plan: the design's plan.
        rigs: its :class:`~tactcad.design.rig_plan.RigDesign`.
        rated_N: the design's rated full-scale force (N); given, a failure also names the
            force gauge the suggested samples need where the rig's own misses them.
        scenes: the project's scenes by name (:class:`~tactcad.design.scene_specs.SceneSpec`);
            given, a failure names each scene's ``sample_stiffness_N_per_mm`` to set
            (:func:`scene_samples_setting`). scenes_file: the file they were read from.

    Returns:
        The result, naming the samples, the range and, on a failure, samples over it.
    """
    from tactcad.partlib.sample import sample_name
    from tactcad.studies.verification import requirements_of

    req = requirements_of(plan)
    lo, hi = req.kobj_range_N_per_mm
    kit = rigs.sample_stiffness_N_per_mm
    subject = "sample-stiffness and evaluation rigs: " + ", ".join(sample_name(k) for k in kit)
    how = "stated" if "kobj_range_N_per_mm" in req.stated else "derived from the elements"
    text = (f"samples {min(kit):g} ... {max(kit):g} N/mm against the design's K_obj range "
            f"{lo:.4g} ... {hi:.4g} N/mm ({how})")
    if kit_spans(plan, kit):
        return CheckResult("rig sample kit", subject, True, text)
    suggested = suggested_kit(plan)
    rigs_file = rigs.source or "rigs.toml"
    gauge = "" if rated_N is None else (gauge_for_samples(rigs, rated_N, suggested)
                                        + weights_for_samples(plan, rigs, rated_N, suggested))
    return CheckResult("rig sample kit", subject, False,
                       f"{text}: the kit does not span it; state samples that do in "
                       f"{rigs_file} [sample] stiffness_N_per_mm, e.g. "
                       f"[{', '.join(f'{k:g}' for k in suggested)}] (the design's own samples, "
                       "those evaluate runs over), and each scene's sample_stiffness_N_per_mm "
                       f"one of them{scene_samples_setting(scenes, scenes_file, suggested)}"
                       f"{gauge}")


def scene_samples_setting(scenes, scenes_file: str, samples) -> str:
    """Words for the sample kit's suggestion: each scene that states a
    ``sample_stiffness_N_per_mm`` the kit ``samples`` (N/mm) does not hold, with the sample
    of the kit nearest its own (log scale) to paste, as ``scenes.toml
    [scene.NAME] sample_stiffness_N_per_mm = V`` ("" where no scene states one: a scene
    that states none shows the kit's first)."""
    import math
    from pathlib import Path

    settings = [f"[scene.{name}] sample_stiffness_N_per_mm = "
                f"{min(samples, key=lambda k: abs(math.log(k / s.sample_stiffness_N_per_mm))):g}"
                for name, s in (scenes or {}).items()
                if s.sample_stiffness_N_per_mm is not None
                and s.sample_stiffness_N_per_mm not in samples]
    if not settings:
        return ""
    return f": set {Path(scenes_file).name or 'scenes.toml'} " + ", ".join(settings)


def gauge_for_samples(rigs, rated_N: float, samples) -> str:
    """Words for the sample kit's suggestion: the force gauge ``samples`` (N/mm) need at
    ``rated_N`` (N) where the rig's own misses them ("" where it fits)."""
    from tactcad.studies.rig_sizing import gauge_need
    from tactcad.vocabulary.force_gauge_catalogue import gauge_shortfalls

    g = rigs.part("force_gauge")
    need = gauge_need(rated_N, samples)
    if not gauge_shortfalls(g.range_N, g.resolution_N, need):
        return ""
    fit, misses = suggested_gauge(g.model, need)
    if misses:
        return f"; with them the force gauge needs {need.words()}, which no catalogue gauge meets"
    return (f"; with them the force gauge needs {need.words()}: set "
            f"{gauge_setting(fit, rigs.source or 'rigs.toml')}")


def weights_setting(plan, rated_N: float, samples, rigs_file: str) -> str:
    """The ``[weights]`` and ``[evaluation]`` keys that keep the evaluation rig within
    ``rated_N`` (N) over ``samples`` (N/mm), as pasted into ``rigs_file``
    (:func:`tactcad.studies.rig_sizing.weights_for`), or why none do."""
    import math

    from tactcad.errors import DesignError
    from tactcad.studies.rig_sizing import element_loads_per_newton, weights_for

    try:
        w = weights_for(element_loads_per_newton(plan, samples), rated_N)
    except DesignError as exc:
        return f"no stack of calibration weights fits ({exc})"
    preload = math.floor(w.preload_N * 1e6) / 1e6  # rounded down: within the rating
    return (f"set {rigs_file} [weights] mass_g = {w.mass_g!r}, diameter_mm = "
            f"{w.diameter_mm!r}, count = {w.count}, [evaluation] preload_N = {preload!r}")


def weights_for_samples(plan, rigs, rated_N: float, samples) -> str:
    """Words for the sample kit's suggestion: the weights ``samples`` (N/mm) need where the
    rig's own top load would put more than ``rated_N`` (N) on an element over them ("" where
    it stays within, states no preload, or is kept beyond the rating by a reason)."""
    from tactcad.studies.rig_sizing import element_loads_per_newton, evaluation_rig_steps

    steps = evaluation_rig_steps(rigs)
    if steps is None or rigs.beyond_rating_reason:
        return ""  # the load check says what to state
    top = steps[0][-1] * max(element_loads_per_newton(plan, samples).values())
    if top <= rated_N * (1 + 1e-9):
        return ""
    return (f"; with them the evaluation rig's top load puts {top:.3g} N on an element, "
            f"beyond the rated {rated_N:g} N: "
            f"{weights_setting(plan, rated_N, samples, rigs.source or 'rigs.toml')}")


#: Slack on a waiver's recorded values: they are stated to 3 significant digits.
WAIVER_SLACK = 0.005


def stale_waiver(rigs, element_load_N: float, rated_N: float) -> str:
    """Why the rigs' ``[evaluation] beyond_rating_reason`` no longer keeps the rig ("" where
    it does): the reason keeps only the overload it was judged for, its
    ``beyond_rating_load_N`` (N, the most loaded element's tip force) and
    ``beyond_rating_rated_N`` (N, the rating then); a load above the one or a rating below
    the other (0.5 % allowed for values stated to 3 digits), or a reason without them, fails.

    Args:
        rigs: the design's :class:`~tactcad.design.rig_plan.RigDesign`.
        element_load_N: the most loaded element's tip force now (N).
        rated_N: the design's rated full-scale force now (N).

    Returns:
        The words naming the reason, the values it accepted, the values now and what to do.
    """
    from pathlib import Path

    file = Path(rigs.source or "rigs.toml").name
    todo = (f"judge the overload for this design again, then state [evaluation] "
            f"beyond_rating_load_N = {element_load_N:.3g}, beyond_rating_rated_N = "
            f"{rated_N:.3g} in {file}, or lighter weights and no beyond_rating_reason")
    accepted_load, accepted_rating = rigs.beyond_rating_load_N, rigs.beyond_rating_rated_N
    if accepted_load is None or accepted_rating is None:
        return ("[evaluation] beyond_rating_reason is bound to no load (it states no "
                "beyond_rating_load_N and beyond_rating_rated_N it was judged for), so it "
                f"cannot keep this rig: {todo}")
    changes = []
    if element_load_N > accepted_load * (1 + WAIVER_SLACK):
        changes.append(f"the load on an element is {element_load_N:.3g} N now, "
                       f"beyond the {accepted_load:g} N it accepted")
    if rated_N < accepted_rating * (1 - WAIVER_SLACK):
        changes.append(f"the rating is {rated_N:g} N now, below the {accepted_rating:g} N "
                       "it was judged against")
    if not changes:
        return ""
    return (f"[evaluation] beyond_rating_reason of {file} (judged for {accepted_load:g} N on "
            f"an element, rated {accepted_rating:g} N) no longer keeps this rig: "
            f"{' and '.join(changes)}; {todo}")


def evaluation_load_check(plan, rigs, rated_N: float, samples_after=None) -> CheckResult:
    """Fails when the evaluation rig's top load puts more than ``rated_N`` (N)
    on an element, or states no preload; a rig kept beyond the rating
    (``[evaluation] beyond_rating_reason``) passes, saying so, while the overload is
    within what the reason was judged for (:func:`stale_waiver`), else fails naming it. A failure names the weights
    to set, sized for ``samples_after`` (N/mm: the samples once check's suggestions are
    pasted, :func:`kit_after_suggestion`; None: the rigs' own)."""
    from tactcad.studies.rig_sizing import evaluation_rig_load

    subject = f"array evaluation rig: {rigs.library['weights'].name}"
    load = evaluation_rig_load(plan, rigs, rated_N)
    if load is None:
        return CheckResult("rig load", subject, False,
                           "[evaluation] preload_N is not stated: the moving axis's weight on the "
                           f"sample is unknown, so the load on the elements (rated {rated_N:g} N) "
                           "is too")
    text = (f"{load.how} = {load.load_N:.4g} N puts {load.element_load_N:.3g} N on element "
            f"{load.element}, rated full-scale force {rated_N:g} N")
    if load.within_rating:
        return CheckResult("rig load", subject, True, text)
    text += f" (EXCEEDS the rating by {100 * (load.element_load_N / rated_N - 1):.0f} %)"
    reason = rigs.beyond_rating_reason
    if reason:
        stale = stale_waiver(rigs, load.element_load_N, rated_N)
        if stale:
            return CheckResult("rig load", subject, False, f"{text}; {stale}")
        return CheckResult("rig load", subject, True, f"{text}; kept: {reason}")
    samples = list(samples_after) if samples_after is not None else \
        list(rigs.sample_stiffness_N_per_mm)
    return CheckResult("rig load", subject, False,
                       f"{text}; lighter weights or a counterbalanced axis: "
                       f"{weights_setting(plan, rated_N, samples, rigs.source or 'rigs.toml')}"
                       ", or state [evaluation] beyond_rating_reason")


def force_gauge_check(rigs, rated_N: float, samples_after=None) -> CheckResult:
    """Fails when the force gauge's range or resolution misses what the
    calibration and sample rigs read at ``rated_N`` (N) and the rig's stiffest
    sample, or when a catalogue model's stated range or resolution is not the
    catalogue's (each such key named). Undecided (not failed) where only the resolution
    misses and the rig already holds the catalogue's finest gauge of that range: no gauge
    of the catalogue does better, so whether the calibration resolves the rating
    is left to the lab (a finer instrument, or calibration by dead weights);
    a range that is short always fails (the gauge would be overloaded).

    Args:
        rigs: the design's :class:`~tactcad.design.rig_plan.RigDesign`.
        rated_N: the design's rated full-scale force (N).
        samples_after: the samples (N/mm) the rigs will hold once check's suggestions are
            pasted (:func:`kit_after_suggestion`); the gauge a failure suggests is sized for
            them. None: the rigs' own.

    Returns:
        The result; a failure names every ``[force_gauge]`` key to set.
    """
    from tactcad.studies.rig_sizing import gauge_need
    from tactcad.vocabulary.force_gauge_catalogue import catalogue_mismatches, gauge_shortfalls

    g = rigs.part("force_gauge")
    own = list(rigs.sample_stiffness_N_per_mm)
    after = list(samples_after) if samples_after is not None else own
    need = gauge_need(rated_N, own)
    short = gauge_shortfalls(g.range_N, g.resolution_N, need)
    stale = catalogue_mismatches(g.model, g.range_N, g.resolution_N)
    subject = "calibration and sample rigs: force_gauge"
    text = f"{g.model} ({g.range_N:g} N, {g.resolution_N:g} N) against {need.words()}"
    if not short and not stale:
        return CheckResult("rig force gauge", subject, True, text)
    fit, misses = suggested_gauge(g.model, gauge_need(rated_N, after))
    only_resolution = g.range_N >= need.range_N * (1 - 1e-9)
    if short and not stale and misses and fit.model == g.model and only_resolution:
        return CheckResult("rig force gauge", subject, True,
                           f"{text}: {'; '.join(short)}; the catalogue's finest gauge of that "
                           "range: a finer instrument or dead-weight calibration would resolve "
                           "the rating", undecided=True)
    faults = short + [f"{words} (state the catalogue's value, or the model your lab's gauge is)"
                      for words in stale]
    kit = ("" if after == own else
           f" for the samples the sample kit check suggests ({gauge_need(rated_N, after).words()})")
    hint = (f"; no catalogue gauge fits{kit}" if misses else
            f"; the catalogue's {fit.model} fits{kit}: set {gauge_setting(fit, rigs.source or 'rigs.toml')}")
    return CheckResult("rig force gauge", subject, False, f"{text}: {'; '.join(faults)}{hint}")
