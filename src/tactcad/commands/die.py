"""``tactcad die``: a silicon die for a grasper's jaw, from the stiffness targets to its masks:
the die's plan (:mod:`tactcad.products.silicon_die.design.mems_die`), its GDSII masks for the die and a wafer
(:mod:`tactcad.products.silicon_die.export.gds_masks`) and their read-back with KLayout against the process's
rules and the plan (:mod:`tactcad.products.silicon_die.checks.gds_drc`)."""

from __future__ import annotations

import argparse
import contextlib
import io
import math
import os
import shutil
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping

from tactcad.commands import (add_cache_args, add_design_arg, add_output_args,
                              progress_from_args)
from tactcad.commands.finite_json import dumps
from tactcad.commands.options import count, number, output_folder
from tactcad.products.silicon_die.design.mems_die import (DEFAULT_COLUMNS, DEFAULT_DIE_NAME,
                                                          DEFAULT_PITCH_UM,
                                                          FULL_SCALE_FORCE_WORDS, LEAST_PITCH_UM)
from tactcad.design.requirements_section import (MAX_FULL_SCALE_FORCE_N, MAX_KOBJ_N_PER_MM,
                                                 MIN_FULL_SCALE_FORCE_N, MIN_KOBJ_N_PER_MM)
from tactcad.errors import DesignError, DesignErrors

if TYPE_CHECKING:
    from tactcad.export.reuse import ExportState

#: The written files, by what they hold ({name}: the die's name).
DIE_FILES = {"masks": "{name}.gds", "wafer": "{name}_wafer.gds", "step": "{name}.step",
             "picture": "{name}_masks.png", "traveller": "{name}_traveller.md",
             "scene": "{name}_in_jaw.step", "scene_picture": "{name}_in_jaw.png",
             "bom": "{name}_bom.csv", "drawing": "{name}_drawing.svg",
             "record": "{name}.json", "glb": "scenes/{name}_in_jaw.glb",
             "review": "review/index.html", "manifest": "manifest.json"}
#: The files whose sha256 the manifest cannot hold: itself.
NOT_IN_MANIFEST = ("manifest",)
#: The checks ``tactcad check`` adds to the export's own, on the written files as they lie
#: in the folder (the export prints its checks before it moves its files in): each one
#: check of a fresh export (``export_file``: one per file edited by hand since, when any).
READ_BACK_CHECKS = {"die_files": "every file of the die there",
                    "export_file": "no file changed since the export, sha256 as manifest.json "
                                   "lists",
                    "die_record": "the record holds the plan the design makes"}


def on_the_files(check: str) -> bool:
    """Whether a die's check result named ``check`` is one of the files themselves
    (:data:`READ_BACK_CHECKS`, or ``export_inputs``, which ``tactcad check`` adds when the
    export it checks as it is, files edited by hand, is older than the design or jaw file),
    not one ``tactcad export`` prints.

    Args:
        check: the result's check name.

    Returns:
        True for a check of the files themselves.
    """
    from tactcad.checks.export_files import STALE_CHECK

    return check in READ_BACK_CHECKS or check == STALE_CHECK


def read_back_words() -> str:
    """The checks :data:`READ_BACK_CHECKS` names, each with what it asks, as one phrase."""
    return ", ".join(f"{k} ({v})" for k, v in READ_BACK_CHECKS.items())


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "die", help="a silicon MEMS die for a grasper's jaw: plan, GDSII masks, KLayout DRC",
        description="Sizes two rows of piezoresistive cantilevers in an SOI wafer's device "
                    "layer (reference row stiff, measuring row soft, paired across the die) "
                    "for K_r/K_m and a K_obj range in the jaw's pocket; writes the die's "
                    "masks (GDSII, one layer per mask) with their picture, a wafer of dies, "
                    "the process traveller, "
                    "the die as a STEP assembly of its layers, the die on its carrier in the "
                    "jaw's face pocket (STEP and picture) with the insert's bill of "
                    "materials, and a JSON record of the plan with every derived "
                    "dimension's reason; reads the masks back with KLayout against the "
                    "process's rules and the plan, and checks the mount's fit. Exit 1 when a "
                    "check fails, 2 when the targets cannot be met (with what binds and a "
                    "pasteable alternative). Units: um, N/mm, N, MPa.")
    add_design_arg(p, "a die design file (a [die] table: jaw, kr_over_km, kobj_range_N_per_mm, "
                      "full_scale_force_N, columns, pitch_um, name; `tactcad design --jaw 5` "
                      "writes one); in place of the options below",
                   "with --design: override one value of the die file (repeatable), e.g. --set "
                   "die.full_scale_force_N=0.03; checked like the file")
    p.add_argument("--jaw", metavar="CLASS|FILE",
                   help="the jaw the die seats in: a trocar class (5, 10) or a TOML file with "
                        "a [grasper_jaw] table (its pocket bounds the die)")
    p.add_argument("--kr-over-km", type=number(1, 1000, lo_open=True),
                   metavar="X", help="stiffness ratio K_r/K_m of a unit (> 1; about 10)")
    p.add_argument("--kobj-range", type=number(MIN_KOBJ_N_PER_MM, MAX_KOBJ_N_PER_MM, "N/mm"),
                   nargs=2, metavar=("LO", "HI"),
                   help="object stiffnesses to read (N/mm)")
    p.add_argument("--full-scale-force", type=number(MIN_FULL_SCALE_FORCE_N,
                                                     MAX_FULL_SCALE_FORCE_N, "N"),
                   metavar="F", help=f"{FULL_SCALE_FORCE_WORDS} (N)")
    p.add_argument("--columns", type=count(2, 50), default=None, metavar="N",
                   help=f"units along the die (2 ... 50; default {DEFAULT_COLUMNS})")
    p.add_argument("--pitch-um", type=number(LEAST_PITCH_UM, 5000, "um"), default=None,
                   metavar="UM",
                   help=f"the units' spacing along the die ({LEAST_PITCH_UM:g} ... 5000 um: each "
                        "beam's three bond pads and its reference resistor within one pitch; "
                        f"default {DEFAULT_PITCH_UM:g})")
    p.add_argument("--name", default=None,
                   help="the die's name: its GDS cell and file names (letters, digits, _; "
                        f"default {DEFAULT_DIE_NAME})")
    p.add_argument("--fe-check", action="store_true",
                   help="also solve each row's beam on its frame block in CalculiX with "
                        "silicon's anisotropic stiffness (C3D8I, about 15 s a beam) and give "
                        "the closed form's error in K and in the first resonance against it")
    p.add_argument("--fem3d", action="store_true",
                   help="solve each row's beam on its frame block at the die's fem3d level "
                        "(scikit-fem, silicon's anisotropic stiffness, triquadratic hexahedra, "
                        "two meshes extrapolated; about a minute and a half) and state the "
                        "closed form's K and f1 error against it")
    p.add_argument("--out", default="die", metavar="DIR", type=output_folder,
                   help="folder for the masks and the record (default ./die)")
    # the store every command reads: --fem3d's solves are kept there, so `modal --model fem3d`
    # and `stiffness --model fem3d` read them, and a second `die --fem3d` solves nothing
    add_cache_args(p)
    add_output_args(p, "print the plan and the checks as one JSON object")
    p.set_defaults(func=run_die_command)


def run_die_command(args: argparse.Namespace) -> int:
    """``tactcad die``: :func:`run`, its ``--out`` folder's name first held to the names
    ``design --out`` and ``tactcad new`` take
    (:func:`tactcad.project_folder.refuse_no_design_name`).

    Args:
        args: the die command's parsed options.

    Returns:
        The exit code of :func:`run` (0: the die's checks pass; 1: one fails).

    Raises:
        DesignError: ``--out`` whose folder name has a character outside the names' rule
            (a space, an accent), naming the value, the rule and a name to paste; any
            refusal of :func:`run`.
    """
    from tactcad.project_folder import refuse_no_design_name

    out = str(args.out)
    refuse_no_design_name("--out", out, Path(os.path.abspath(os.path.expanduser(out))).name)
    return run(args)


#: The targets' options, by the die design file's key; and the options with defaults.
TARGET_OPTIONS = {"jaw": "--jaw", "kr_over_km": "--kr-over-km",
                  "kobj_range": "--kobj-range", "full_scale_force": "--full-scale-force"}
DEFAULTS = {"columns": ("--columns", DEFAULT_COLUMNS), "pitch_um": ("--pitch-um", DEFAULT_PITCH_UM),
            "name": ("--name", DEFAULT_DIE_NAME)}


def die_asked(args: argparse.Namespace) -> dict:
    """The die asked for: from ``--design`` (:func:`tactcad.products.silicon_die.design.die_file.load_die_design`)
    or from the options, each left out taking its default.

    Raises:
        DesignError: a target option missing without ``--design``, or given with it.
    """
    from tactcad.commands import parse_overrides, set_sources
    from tactcad.products.silicon_die.design.die_file import load_die_design

    if args.design is None and not _any_option_given(args):
        folder_design = _folder_die_design()
        if folder_design is not None:  # the working folder's die, as every command takes
            args = argparse.Namespace(**{**vars(args), "design": str(folder_design)})
    if args.design is None:
        if args.overrides:
            raise DesignError("--set", args.overrides[0], "only with --design",
                              "it overrides a value of the die design file")
        missing = [DesignError(option, None, "a value, or --design FILE",
                               "the die's targets are the options or a die design file")
                   for key, option in TARGET_OPTIONS.items() if getattr(args, key) is None]
        if missing:
            raise DesignErrors(missing, what="the die's targets")
        return {**{k: getattr(args, k) for k in TARGET_OPTIONS},
                **{k: v if (v := getattr(args, k)) is not None else d
                   for k, (_, d) in DEFAULTS.items()}}
    given = [o for k, o in {**TARGET_OPTIONS, **{k: o for k, (o, _) in DEFAULTS.items()}}.items()
             if getattr(args, k) is not None]
    if given:
        raise DesignError(given[0], getattr(args, given[0].lstrip("-").replace("-", "_")),
                          "only without --design", f"{args.design} states it")
    overrides = parse_overrides(args.overrides, example=DIE_SET_EXAMPLE)
    try:
        d = load_die_design(args.design, overrides)
    except DesignErrors as exc:  # a refused --set value is named as typed, as an array's is
        raise exc.sourced(set_sources(args.overrides, DIE_SET_EXAMPLE)) from None
    return {"jaw": d.jaw, "kr_over_km": d.die.kr_over_km,
            "kobj_range": tuple(d.die.kobj_range_N_per_mm),
            "full_scale_force": d.die.full_scale_force_N, "columns": d.die.columns,
            "pitch_um": d.die.pitch_um, "name": d.die.name, "file": Path(args.design).name,
            "design_path": str(args.design),
            "source": _source_of(Path(args.design), overrides),
            "strength": d.strength,
            # a resolution the file leaves out is the default's, reported, not judged
            "kobj_resolution_rel": (d.die.kobj_resolution_rel
                                    if "kobj_resolution_rel" in d.stated else None),
            "attach": d.attach,
            "max_grasp_force": d.die.max_grasp_force_N,
            "kobj_accuracy": d.die.kobj_accuracy_rel,
            "root_fillet_um": d.die.root_fillet_um,
            # the file's reasons as shown, and those a hand edit left stale
            "assumptions": d.assumptions, "stale_reasons": dict(d.stale)}


def _any_option_given(args: argparse.Namespace) -> bool:
    return any(getattr(args, k, None) is not None for k in (*TARGET_OPTIONS, *DEFAULTS))


def _folder_die_design() -> Path | None:
    # the working folder's one die design file; an array's folder or none gives None
    from tactcad.design.array_plan import read_toml
    from tactcad.products.silicon_die.design.die_file import is_die_file
    from tactcad.project_folder import designs_in, other_product_designs_in

    found = designs_in(".") + other_product_designs_in(".")
    if len(found) == 1 and is_die_file(read_toml(found[0], "--design")):
        return found[0]
    return None


def _source_of(design: Path, overrides: dict | None = None) -> dict:
    """The die design file a record comes from: its name and sha256 (as an array's manifest
    names its design), so that a command run in the output folder can say where it is, and
    the ``--set`` values the die was made with over the file's (key -> value)."""
    import hashlib

    return {"source": design.name, "sha256": hashlib.sha256(design.read_bytes()).hexdigest(),
            "overrides": dict(overrides or {})}


#: A ``--set`` a refusal of a die's shows.
DIE_SET_EXAMPLE = "die.kr_over_km=10"
#: The die file's key of each target option (a refusal of a file's value names the key).
FILE_KEYS = {"--jaw": "die.jaw", "--kr-over-km": "die.kr_over_km",
             "--kobj-range": "die.kobj_range_N_per_mm",
             "--full-scale-force": "die.full_scale_force_N", "--columns": "die.columns",
             "--pitch-um": "die.pitch_um", "--name": "die.name"}


def _as_file_keys(exc: DesignError, file: str) -> DesignError:
    """``exc`` naming the die file's key instead of the option, its alternatives as
    ``--set`` values to paste (the targets came from ``file``, not from options)."""
    key = FILE_KEYS.get(exc.field)
    if key is None:
        return exc

    def as_set(alt: dict) -> dict:
        words = str(alt.get("option", "")).split()
        if len(words) == 2 and words[0] in FILE_KEYS:
            return {**alt, "option": f"--set {FILE_KEYS[words[0]]}={words[1]}"}
        return alt

    return DesignError(key, exc.value, exc.allowed, exc.why, file=file,
                       alternatives=[as_set(a) for a in exc.alternatives])


def _name(value: str) -> str:
    from tactcad.products.silicon_die.design.die_file import CELL_NAME_WORDS, is_cell_name

    if not is_cell_name(value):
        raise DesignError("--name", value, CELL_NAME_WORDS)
    return value


@dataclass(frozen=True)
class PlannedDie:
    """A die planned from what was asked: the plan, the jaw's room it fits and the jaw as
    the mount takes it (a trocar class or a lab's jaw file's table)."""

    plan: Any
    room: Any
    jaw_stated: Any
    #: the die design file's name and sha256, or None for a die asked by options
    source: dict | None = None
    #: what its export is made from, the manifest's ``inputs``: the design file and the
    #: jaw file, each with its sha256
    #: (:func:`tactcad.products.silicon_die.export.die_inputs.die_inputs`)
    inputs: dict | None = None
    #: the design file's ``[assumptions]`` as shown, (key, text) pairs
    #: (:func:`tactcad.products.silicon_die.design.die_file.die_assumptions`)
    assumptions: tuple = ()
    #: those of them that no longer apply (a value edited since), key -> text
    stale_reasons: Mapping[str, str] = field(default_factory=dict)


def plan_of(asked: dict) -> PlannedDie:
    """The die's plan for ``asked`` (:func:`die_asked`): one planning for the die command,
    a die folder's check and the array commands' views of a die.

    Raises:
        DesignError: a bad name, jaw or targets the die cannot meet (named).
    """
    from tactcad.commands.design import jaw_of
    from tactcad.products.silicon_die.export.die_inputs import die_inputs
    from tactcad.products.silicon_die.studies.die_doping import doped_die_plan
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.studies.inverse_design import Targets

    name = _name(asked["name"])
    targets = Targets(asked["kr_over_km"], tuple(asked["kobj_range"]), asked["full_scale_force"])
    try:
        jaw, jaw_file = jaw_of(asked["jaw"])
        room = jaw_room(jaw, jaw_file)
    except DesignError as exc:  # a jaw the die's file states is named by its key
        if asked.get("file"):
            raise _as_file_keys(exc, asked["file"]) from None
        raise
    try:
        plan = doped_die_plan(targets, room, asked.get("kobj_resolution_rel"),
                              columns=asked["columns"], pitch_um=asked["pitch_um"], name=name,
                              weibull=asked.get("strength"),
                              **({} if asked.get("root_fillet_um") is None
                                 else {"root_fillet_um": asked["root_fillet_um"]}))
    except DesignError as exc:
        if asked.get("file"):
            raise _as_file_keys(exc, asked["file"]) from None
        raise
    if asked.get("strength") is not None:
        plan = with_weibull(plan, asked["strength"])
    if asked.get("attach") is not None:
        plan = with_attach(plan, asked["attach"])
    if asked.get("max_grasp_force") is not None:
        from dataclasses import replace

        plan = replace(plan, max_grasp_force_N=float(asked["max_grasp_force"]))
    if asked.get("kobj_accuracy") is not None:
        from dataclasses import replace

        plan = replace(plan, kobj_accuracy_rel=float(asked["kobj_accuracy"]))
    return PlannedDie(plan, room, {"shaft_class_mm": jaw} if isinstance(jaw, str) else jaw,
                      asked.get("source"), die_inputs(asked.get("design_path"), jaw_file),
                      tuple(asked.get("assumptions") or ()),
                      dict(asked.get("stale_reasons") or {}))


def with_weibull(plan, pair):
    """``plan`` judged by the lab's Weibull ``pair`` (its design file's ``[strength]``): the
    plan with the pair and its strength reason."""
    from dataclasses import replace

    from tactcad.products.silicon_die.mechanics.die_strength import die_failure_probability

    judged = replace(plan, weibull=pair)
    p_rated = die_failure_probability(judged, judged.rated_force_N)
    reasons = {**plan.reasons,
               "strength": f"the die's failure probability with every beam at its rated force, "
                           f"{p_rated:.3g}, from the lab's Weibull pair (m {pair.modulus:g}, "
                           f"sigma_0 {pair.characteristic_MPa:g} MPa on {pair.reference_area_um2:g} "
                           f"um^2; {pair.source}) over each beam's tensile face and sidewalls; "
                           f"accepted up to {pair.failure_probability_max:g}"}
    return replace(plan, weibull=pair, reasons=reasons)


def with_attach(plan, attach):
    """``plan`` bonded by the lab's die ``attach`` (its design file's ``[attach]``): the
    plan with the film and its reason."""
    from dataclasses import replace

    reasons = {**plan.reasons,
               "die_attach": f"{attach.material}, {attach.thickness_um:g} um, E "
                             f"{attach.modulus_MPa:g} MPa, nu {attach.poisson:g} "
                             f"({attach.source})"}
    return replace(plan, attach=attach, reasons=reasons)


def run(args: argparse.Namespace) -> int:
    from tactcad.atomic import (carry_over, leftover_staging, publish_dir, remove_tree,
                                staging_dir, warn_left_behind, writing_lock)
    from tactcad.checks.check_result import counts_text
    from tactcad.export.export_owner import written_by_tactcad
    from tactcad.products.silicon_die.design.die_mount import die_mount

    started = time.perf_counter()
    planned = plan_of(die_asked(args))
    plan, room, name = planned.plan, planned.room, planned.plan.name
    mount = die_mount(plan, planned.jaw_stated)
    if getattr(args, "fe_check", False) and shutil.which("ccx") is None:  # before any file
        raise DesignError("--fe-check", True, "CalculiX's ccx on the PATH",
                          "the check solves each beam in CalculiX (apt-get install calculix-ccx)")
    out = Path(args.out)
    files = {k: out / v.format(name=name) for k, v in DIE_FILES.items()}
    refuse_a_foreign_folder(out, name)
    held = contextlib.ExitStack()
    held.enter_context(writing_lock(out, "--out"))  # one run at a time moves its files in
    # every file made in a staging folder beside OUT, then moved in: a failed or
    # interrupted run leaves OUT's previous files as they were
    staging = None
    try:
        # a killed run's staging folder (or an old export not yet removed): an array's rule
        warn_left_behind([p for old in leftover_staging(out) for p in remove_tree(old)])
        staging = staging_dir(out)
        made = {k: staging / p.relative_to(out) for k, p in files.items()}
        # --fe-check and --fem3d solve outside the store's key (CalculiX, meshes): made afresh
        reusable = not (args.fe_check or getattr(args, "fem3d", False))
        key = die_export_key(planned, mount, getattr(args, "design", None)) if reusable else None
        kept = fetch_die_export(key, staging) if key else None
        if kept is not None:  # every job of the kept export reused
            jobs = {"jobs_run": 0, "jobs_reused": kept["jobs_run"] + kept["jobs_reused"]}
        else:
            for path in made.values():
                path.parent.mkdir(parents=True, exist_ok=True)
            kept = _build_die_export(args, planned, mount, files, made, staging)
            jobs = {k: kept[k] for k in ("jobs_run", "jobs_reused")}
            if key:
                keep_die_export(key, staging, kept)
        record, checks, counts = kept["record"], kept["checks"], kept["counts"]
        readout, dies, modes, fe, budget = (kept[k] for k in ("readout", "dies", "modes", "fe",
                                                              "budget"))
        if out.is_dir():  # the lab's own files in the folder stay; the old export's go
            ours = written_by_tactcad(out)
            carry_over(out, staging, lambda rel: rel not in ours)
        os.chmod(staging, 0o755)  # mkdtemp makes it private; an export folder is for sharing
        # the folder swapped whole, as an array's export: a run stopped at any moment
        # leaves the old set or the new one, never a mix
        publish_dir(staging, out)
        staging = None  # it held the old export, which publish_dir removed
    finally:
        if staging is not None:
            shutil.rmtree(staging, ignore_errors=True)
        held.close()
    if args.json:  # with the run's seconds and job counts, as an array's export --json
        print(dumps({**record, "seconds": round(time.perf_counter() - started, 3), **jobs,
                     "stale_reasons": stale_rows(planned.stale_reasons)}, indent=1))
    else:  # `--quiet` says nothing on stderr; the summary is the same, as an array's
        print(render(plan, readout, room.label, dies, files, checks, counts_text(counts),
                     modes, fe, budget, mount, record["fem3d"], planned.stale_reasons))
    return 1 if counts["failed"] else 0


def _build_die_export(args: argparse.Namespace, planned, mount, files: dict, made: dict,
                      staging: Path) -> dict:
    """Every file of a die's export written into ``staging`` (``made``: the same names as
    ``files``, under it) and what the command prints of them.

    Returns:
        ``{"record", "checks", "counts", "readout", "dies", "modes", "fe", "budget"}``.
    """
    from tactcad.checks.check_result import status_counts
    from tactcad.checks.sheet_overlap import sheet_file_results
    from tactcad.export.run import run_jobs
    from tactcad.products.silicon_die.checks.gds_drc import gds_checks
    from tactcad.products.silicon_die.checks.traveller_check import traveller_checks
    from tactcad.products.silicon_die.export.die_jobs import DieRun, die_jobs
    from tactcad.in_use.kobj_budget import with_declared_deprecated_keys
    from tactcad.products.silicon_die.mechanics.die_dynamics import (FE_CHECK_RENAMED,
                                                                     calculix_beam_check,
                                                                     closed_form_k_N_per_mm,
                                                                     die_modes, first_resonance_Hz)
    from tactcad.products.silicon_die.mechanics.die_fem3d import FEM3D_RENAMED
    from tactcad.products.silicon_die.studies.die_reports import die_beam_fem3d_kept
    from tactcad.store import Store, active_store

    plan, room, name, out = planned.plan, planned.room, planned.plan.name, Path(args.out)
    run = DieRun(plan, mount, room.label, staging,
                 {k: p.relative_to(staging).as_posix() for k, p in made.items()},
                 active_store() or Store(None), log=progress_from_args(args))
    # each file a job of the store, as an array's: a change rebuilds only what it shapes
    jobs = die_jobs(run)
    records, jobs_run = run_jobs(run, jobs, run.store)
    dies = next(r["dies"] for r in records if "dies" in r)
    readout, budget = run.readout, run.budget
    checks = (gds_checks(made["masks"], plan)
              + traveller_checks(made["traveller"], made["masks"])
              + _mount_checks(run)
              + sheet_file_results(made["drawing"]) + die_requirement_checks(plan, mount))
    counts = status_counts(checks)
    modes = die_modes(plan)
    fe = [calculix_beam_check(plan, b) for b in plan.beams[:: plan.columns]] \
        if args.fe_check else []
    fem3d = [die_beam_fem3d_kept(plan, b) for b in plan.beams[:: plan.columns]] \
        if getattr(args, "fem3d", False) else []
    record = {"design": {"name": name, **(planned.source or {"source": None})},
              "die": plan.as_json(), "readout": readout, "jaw": room.label,
              "mount": mount.as_json(),
              "resonance_Hz": modes_json(modes),
              # each row's first resonance named as modal's; the old keys declared in it
              "fe_check": [with_declared_deprecated_keys(c.as_json(), FE_CHECK_RENAMED)
                           for c in fe],
              "fem3d": [with_declared_deprecated_keys(dict(
                  r.as_json(), K_closed_form_error_rel=closed_form_k_N_per_mm(
                      plan, _beam_of(plan, r.role), r.frame) / r.k_N_per_mm - 1.0,
                  first_Hz_closed_form_error_rel=first_resonance_Hz(
                      plan, _beam_of(plan, r.role), r.frame) / r.f1_Hz - 1.0), FEM3D_RENAMED)
                        for r in fem3d],
              "kobj_budget": budget.as_json(),
              "wafer_dies": dies, "files": {k: p.relative_to(out).as_posix() for k, p in files.items()},
              "checks": [{"check": c.check, "subject": c.subject, "status": c.status,
                          "detail": c.detail} for c in checks], "counts": counts}
    made["record"].write_text(dumps(record, indent=1) + "\n", encoding="utf-8")
    _write_review_and_manifest(plan, planned.source, made, files, budget, staging,
                               mount, getattr(args, "design", None), readout, planned.inputs,
                               planned.assumptions)
    return {"record": record, "checks": checks, "counts": counts, "readout": readout,
            "dies": dies, "modes": modes, "fe": fe, "budget": budget,
            "jobs_run": jobs_run, "jobs_reused": len(jobs) - jobs_run}


def _mount_checks(run) -> list:
    """The mount's checks on its solids (:func:`~tactcad.products.silicon_die.checks.die_mount_fit.mount_checks`),
    kept in the store by the scene's inputs: a run that fetched the scene's files builds no
    solid for them."""
    from tactcad.products.silicon_die.checks.die_mount_fit import mount_checks
    from tactcad.store import kept_result

    return kept_result("die-mount-checks",
                       lambda: mount_checks(run.solids, run.mount, f"{run.plan.name}_posts"),
                       run.scene_inputs)


def die_export_key(planned, mount, design_file: str | None) -> str:
    """The store's name for a die's whole export: what every file of it is made from (the
    plan, its mount in the jaw, the design's source and ``--set`` values, its input files
    (the design and jaw files' sha256, the manifest's ``inputs``), the project's atlas
    files, the review page's scripts, the file names; the store's own salt adds tactcad's
    code and the CAD stack).

    Args:
        planned: the die as planned (:func:`plan_of`). mount: its mount in the jaw.
        design_file: the design file (None: a die made from targets).

    Returns:
        A content key (:func:`tactcad.store.content_key`).
    """
    from tactcad.export.atlas_view import atlas_identity
    from tactcad.export.review_assets import assets_identity
    from tactcad.store import content_key

    return content_key("die-export", planned.plan.as_json(), mount.as_json(),
                       planned.room.label, planned.source, planned.inputs,
                       [list(pair) for pair in planned.assumptions], DIE_FILES,
                       NOT_IN_MANIFEST,
                       atlas_identity(design_file), assets_identity())


def fetch_die_export(key: str, staging: Path) -> dict | None:
    """A die's export kept under ``key`` by an earlier run, copied into ``staging``, and what
    the command prints of it; None when the active store keeps none (or no store is open).

    Args:
        key: :func:`die_export_key`. staging: the run's empty staging folder.
    """
    from tactcad.store import active_store

    store = active_store()
    if store is None:
        return None
    found, kept = store.recall(key + "-report")
    if found and isinstance(kept, dict) and store.fetch(key, staging) is not None:
        return kept
    for leftover in staging.iterdir():  # a copy cut short leaves nothing for the build
        shutil.rmtree(leftover) if leftover.is_dir() else leftover.unlink()
    return None


def keep_die_export(key: str, staging: Path, kept: dict) -> None:
    """Keep a die's export (every file in ``staging``) and what the command prints of it in
    the active store, for :func:`fetch_die_export`. Best effort, as the store's."""
    from tactcad.store import active_store

    store = active_store()
    if store is None:
        return
    rel = sorted(p.relative_to(staging).as_posix() for p in staging.rglob("*") if p.is_file())
    store.keep(key, staging, [{"path": r} for r in rel])
    store.remember(key + "-report", kept)


def _write_review_and_manifest(plan, source: dict | None, made: dict, files: dict,
                               budget, staging: Path, mount, design_file: str | None,
                               readout: dict, inputs: dict | None = None,
                               assumptions: tuple = ()) -> None:
    """The die's review page and manifest, from the files made before them in
    ``staging`` (:mod:`tactcad.products.silicon_die.export.die_review`); the page shows the
    atlas of the jaw when the design's folder has one (:mod:`tactcad.export.atlas_view`),
    and, as an array's, the grasp (``tactcad grasp``'s record at its defaults), the tissue
    coupling and the build book (the die's traveller, ``readout``'s sheet resistance). The
    manifest holds ``inputs`` (the design and jaw files with their sha256) right after its
    ``design`` when given, as an array's (:func:`tactcad.export.run.with_inputs`), and, as
    an array's, the design file's reasons (``assumptions``: (key, text) pairs, a reason a
    hand edit left stale marked so) in its ``assumptions`` section, which the page carries."""
    from tactcad.commands.finite_json import finite
    from tactcad.export.atlas_view import atlas_view
    from tactcad.products.silicon_die.studies.die_reports import (stiffness_report,
                                                                  strength_report)
    from tactcad.export.review_assets import import_map
    from tactcad.export.review_page import write_review_page
    from tactcad.products.silicon_die.export.die_review import (
        beam_elements, design_head, die_manifest, die_manifest_sections, manifest_text,
        review_contents_of_die)
    from tactcad.products.silicon_die.studies.die_verification import die_verification
    from tactcad.products.silicon_die.export.die_review import traveller_book
    from tactcad.products.silicon_die.export.traveller import traveller_steps
    from tactcad.products.silicon_die.studies.die_grasp_report import (default_grasp_options,
                                                                       die_grasp_record)
    from tactcad.products.silicon_die.studies.die_verification import (
        die_tissue_coupling_record)

    from tactcad.products.silicon_die.export.die_review import assumptions_section

    head = {**design_head(plan.name, source), **assumptions_section(assumptions)}
    from tactcad.errors import DesignError

    try:
        grasp, _ = die_grasp_record(plan, mount, default_grasp_options(),
                                    Path(design_file).name if design_file else None)
    except DesignError as exc:  # shown on the page as why, never a failed export
        grasp = {"not_applicable": f"the grasp at tactcad grasp's defaults has no answer: {exc}"}
    book = traveller_book(traveller_steps(plan, readout["sheet_resistance_ohm_per_sq"]))
    elements = beam_elements(strength_report(plan)[0], stiffness_report(plan)[0])
    verification = die_verification(plan, mount)
    contents = review_contents_of_die(
        head, verification,
        (files["drawing"].name, made["drawing"].read_text(encoding="utf-8")),
        made["glb"].read_bytes(), made["bom"].read_text(encoding="utf-8-sig"), elements,
        budget.as_json(), atlas_view(design_file, (plan.full_scale_force_N,
                                                    *plan.kobj_range_N_per_mm)),
        full_scale_force_N=plan.full_scale_force_N, grasp=grasp,
        tissue_coupling=die_tissue_coupling_record(plan), book=book)
    write_review_page(made["review"], contents, import_map())
    listed = {k: made[k].relative_to(staging).as_posix() for k in made
              if k not in NOT_IN_MANIFEST}
    manifest = die_manifest(head, staging, listed,
                            {"die": plan.as_json(), "rows": elements,
                             # an unbounded figure (a margin, an unreadable K_obj) as null
                             **finite(die_manifest_sections(plan, verification,
                                                            budget.as_json()))})
    if inputs is not None:  # what a check compares with the files now
        from tactcad.export.run import with_inputs

        manifest = with_inputs(manifest, inputs)
    made["manifest"].write_text(manifest_text(manifest), encoding="utf-8")


def die_requirement_checks(plan, mount=None) -> list:
    """The die's verification matrix (:func:`tactcad.products.silicon_die.commands.die_views.die_verification`)
    as check results, one per requirement: failed when its verdict is ``fail``; an
    ``undecided`` one (a margin inside its model's error estimate, or a mean strength
    without a Weibull pair) passes, marked undecided; an ``info`` one (reported, not judged)
    is marked info, as an array's (:func:`tactcad.checks.requirement_checks.requirement_check`)."""
    from tactcad.checks.check_result import CheckResult
    from tactcad.checks.requirement_checks import requirement_check
    from tactcad.mechanics.verdicts import INFO
    from tactcad.products.silicon_die.studies.die_verification import die_verification
    from tactcad.studies.verification import binding_text, margin_text, value_text

    out = []
    for r in die_verification(plan, mount):
        if r["verdict"] == INFO:  # the one convention: no target, no margin, not a pass
            out.append(requirement_check(r))
            continue
        detail = (f"{r['verdict']}: target {value_text(r['target'])}, predicted "
                  f"{value_text(r['predicted'])}, margin {margin_text(r)} ({r['model']})")
        if binding_text(r):
            detail += f", binds: {binding_text(r)}"
        out.append(CheckResult("requirement", r["requirement"], r["verdict"] != "fail", detail,
                               undecided=r["verdict"] == "undecided"))
    return out


def render(plan, readout: dict, jaw: str, dies: int, files: dict, checks, counts: str,
           modes: dict | None = None, fe: list | None = None, budget=None, mount=None,
           fem3d: list | None = None, stale: Mapping[str, str] | None = None) -> str:
    """The die, its beams, their read-out, resonances and FE check, and the checks as text;
    after the plan's reasons, a note for each reason of the design file that no longer
    applies (``stale``: key -> text, :func:`stale_notes`)."""
    d = plan
    ref, meas = d.beams[0], d.beams[d.columns]
    rows = readout["rows"]
    lines = [f"die {d.name} for the {jaw}: {d.die_length_um:g} x {d.die_width_um:g} x "
             f"{d.thickness_um:g} um (with its posts), 2 x {d.columns} beams at {d.pitch_um:g} um",
             f"SOI: device {d.stack.device_um:g} um (+-{d.stack.device_tolerance_um:g}), "
             f"oxide {d.stack.box_um:g} um, handle {d.stack.handle_um:g} um; cavities under "
             f"the rows (their hard stops) {d.cavity_depths_um[0]:g} um (reference) and "
             f"{d.cavity_depths_um[1]:g} um (measuring) deep",
             "| row | role | L um | w um | t um | K N/mm | target N/mm | rated force mN | "
             "root peak stress there MPa | dR/R per N | V/N | force resolution N |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for b, k, target in ((ref, d.k_r_N_per_mm, d.targets[0]),
                         (meas, d.k_m_N_per_mm, d.targets[1])):
        r = rows[b.role]
        lines.append(f"| {b.row} | {b.role} | {b.length_um:.4g} | {b.width_um:g} | "
                     f"{b.thickness_um:g} | {k:.4g} | {target:.4g} | "
                     f"{1e3 * d.rated_force_N(b):.3g} | "
                     f"{d.root_peak_stress_MPa_at_rated_force(b):.4g}"
                     f" | {r['resistance_change_per_N']:.4g} | "
                     f"{r['sensitivity_V_per_N']:.4g} | {r['force_resolution_N']:.3g} |")
    lines.append(resistor_line(plan, readout))
    lines += mode_lines(modes or {})
    for r in fem3d or []:
        lines.append(f"fem3d (scikit-fem, anisotropic, triquadratic hexahedra), {r['role']} beam "
                     f"{r['root']}: "
                     f"K {r['K_N_per_mm']:.4g} N/mm (+-{100 * r['K_error_rel']:.2g} %; closed "
                     f"form {100 * r['K_closed_form_error_rel']:+.2f} %), f1 "
                     f"{r['first_Hz'] / 1e3:.4g} kHz (+-{100 * r['first_Hz_error_rel']:.2g} %; "
                     f"closed form {100 * r['first_Hz_closed_form_error_rel']:+.2f} %), "
                     f"{r['wall_time_s']:.1f} s")
    for c in fe or []:
        lines.append(f"CalculiX, anisotropic C3D8I, {c.role} beam on its frame: K "
                     f"{c.k_fe_N_per_mm:.4g} N/mm "
                     f"(closed form {100 * c.k_error_rel:+.2f} %), f1 {c.f1_fe_Hz / 1e3:.4g} kHz "
                     f"(closed form {100 * c.f1_error_rel:+.2f} %); one mesh, its error not "
                     "estimated (on the frame about 2 % stiff in K: --fem3d extrapolates two)")
    if budget is not None:
        lines += ["", *budget_lines(budget)]
    lines += ["", "reasons:"] + [f"  {k}: {v}" for k, v in d.reasons.items()]
    lines += stale_notes(stale or {})
    if mount is not None:
        lines += ["", f"in the {jaw}:"] + [f"  {k}: {v}" for k, v in mount.reasons.items()]
    lines += ["", f"wrote {', '.join(str(p) for p in files.values())} ({dies} dies on the "
                  "wafer)", "", *[c.line() for c in checks], "", counts,
              f"`tactcad check` prints these {len(checks)} checks read back from the written "
              f"files and {len(READ_BACK_CHECKS)} of the files themselves: "
              f"{read_back_words()}"]
    return "\n".join(lines)


def stale_notes(stale: Mapping[str, str]) -> list[str]:
    """A line for each reason of a die file that no longer applies, worded as ``verify``
    words an array's (``note: [assumptions] KEY: TEXT``).

    Args:
        stale: key -> the reason as shown
            (:func:`tactcad.vocabulary.schema.stale_reasons`).

    Returns:
        The lines (none where every reason applies).
    """
    return [f"note: [assumptions] {key}: {why}" for key, why in stale.items()]


def stale_rows(stale: Mapping[str, str]) -> list[dict[str, str]]:
    """The reasons of a die file that no longer apply as ``--json`` lists them: one
    ``{"field", "reason"}`` each, the manifest's ``assumptions`` rows
    (:func:`tactcad.products.silicon_die.export.die_review.assumptions_section`), the reason
    as shown (``(written for 5; the file now states 7: the reason no longer applies)``).

    Args:
        stale: key -> the reason as shown
            (:func:`tactcad.vocabulary.schema.stale_reasons`).

    Returns:
        The rows (empty where every reason applies).
    """
    return [{"field": key, "reason": why} for key, why in stale.items()]


def resistor_line(plan, readout: dict) -> str:
    """The resistors, their bridge and noise, and the read-out's assumptions, as one line."""
    return (f"resistors: {readout['resistance_ohm']:.4g} ohm "
            f"({readout['sheet_resistance_ohm_per_sq']:.4g} ohm/sq, boron "
            f"{plan.acceptors_per_cm3:.2g} cm^-3), half bridge with its on-die reference "
            f"({readout['reference_resistance_ohm']:.4g} ohm) at {readout['bias_V']:g} V, "
            f"noise {1e9 * readout['noise_V']['total']:.3g} nV rms over "
            f"{readout['band_Hz'][0]:g}-{readout['band_Hz'][1]:g} Hz; "
            + "; ".join(readout["assumptions"]))


def mode_lines(modes: dict) -> list[str]:
    """Each row's first resonance (:func:`tactcad.products.silicon_die.mechanics.die_dynamics.die_modes`), a line
    each."""
    return [f"first resonance, {role} beam with its post: {m.rayleigh_Hz / 1e3:.4g} kHz "
            f"(Rayleigh; the exact Euler-Bernoulli root {m.exact_Hz / 1e3:.4g} kHz, "
            f"{100 * m.rayleigh_error_rel:+.2f} %)" for role, m in modes.items()]


def budget_lines(budget) -> list[str]:
    """The die's K_obj budget (:func:`tactcad.products.silicon_die.in_use.die_budget.die_budget`) as a table."""
    ks = budget.k_obj_N_per_mm
    lines = ["K_obj budget of the middle unit, relative, 1 sigma, at K_obj "
             + ", ".join(f"{k:.3g}" for k in ks) + " N/mm:"]
    def pct(v: float) -> str:
        return f"{100 * v:7.3f} %" if math.isfinite(v) else "unreadable"

    for term, values in budget.terms.items():
        lines.append(f"  {term:<46} " + "  ".join(pct(v) for v in values)
                     + f"   ({budget.reasons[term]})")
    lines.append(f"  {'root sum square (shown-only terms left out)':<46} "
                 + "  ".join(pct(v) for v in budget.total_rel))
    return lines


def modes_json(modes: dict) -> dict:
    """Each row's first resonance (Hz) as the die's record holds it."""
    return {r: {"rayleigh": m.rayleigh_Hz, "exact": m.exact_Hz,
                "rayleigh_error_rel": m.rayleigh_error_rel} for r, m in modes.items()}


# --- a die's folder: export and check ---------------------------------------------------------
def die_design_of(args: argparse.Namespace) -> Path | None:
    """The die design file ``export`` or ``check`` works on, or None for an array's:
    ``--design``, else the working folder's one design file
    (:func:`tactcad.project_folder.default_design`), when it holds a ``[die]`` table.

    Raises:
        DesignError: the folder holds several design files.
    """
    from tactcad.design.array_plan import read_toml
    from tactcad.products.silicon_die.design.die_file import is_die_file
    from tactcad.project_folder import default_design

    design = Path(args.design) if getattr(args, "design", None) else default_design()
    if design.suffix.lower() != ".toml" or not design.is_file():
        return None  # the array's loader names what is wrong with it
    return design if is_die_file(read_toml(design, "--design")) else None


def _die_args(design: Path, args: argparse.Namespace, out: Path) -> argparse.Namespace:
    return argparse.Namespace(design=str(design), overrides=getattr(args, "overrides", []),
                              out=str(out), json=getattr(args, "json", False),
                              quiet=getattr(args, "quiet", False), fe_check=False,
                              fem3d=False,
                              **{k: None for k in (*TARGET_OPTIONS, *DEFAULTS)})


def die_export_words(name: str) -> str:
    """What a die's export writes, by the file names :data:`DIE_FILES` gives the die
    ``name``: what a refusal of an array's choice of files says instead."""
    f = {k: v.format(name=name) for k, v in DIE_FILES.items()}
    return (f"its masks {f['masks']} and wafer {f['wafer']} (GDSII: the die is etched, no "
            f"part of it is cut from sheet, so it has no DXF), the die {f['step']}, its one "
            f"scene {name}_in_jaw ({f['scene']}, {f['glb']}, {f['scene_picture']}), "
            f"{f['drawing']}, {f['bom']}, {f['traveller']}, {f['record']}, {f['review']} and "
            f"{f['manifest']}, all at once")


def whole_export_command(args: argparse.Namespace) -> str:
    """The ``tactcad export`` to paste for a die: the design and ``--set`` values asked,
    ``--out`` as given, no choice of files."""
    import shlex

    words = ["tactcad", "export"]
    if getattr(args, "design", None):
        words += ["--design", str(args.design)]
    for text in getattr(args, "overrides", None) or ():
        words += ["--set", text]
    return shlex.join([*words, "--out", str(args.out)])


def export_die(design: Path, args: argparse.Namespace) -> int:
    """``tactcad export`` of a die's design file: the die command's files into ``--out``.

    Raises:
        DesignError: ``--scene``, ``--only`` or ``--part`` (an array's choice of files),
            saying what the die's export writes and pasting the export that writes it.
    """
    die_args = _die_args(design, args, Path(args.out))
    for option in ("scene", "only", "part"):
        if getattr(args, option, None):
            name = die_asked(die_args)["name"]
            raise DesignError(f"--{option}", getattr(args, option),
                              "left out for a die: its export is whole",
                              f"{design.name} is a silicon die's design; its export writes "
                              + die_export_words(name),
                              alternatives=[{"option": whole_export_command(args),
                                             "words": "the die's whole export, its scene "
                                                      f"{name}_in_jaw with it"}])
    return run(die_args)


@dataclass(frozen=True)
class DieCheck:
    """A die's check: the die's name, the folder checked (a temporary one, gone since,
    without ``--out``), why the export in ``--out`` was not reused (None: it was, or no
    ``--out`` was given: a temporary folder holds no export to refuse), every result in
    order, their counts by status and whether the export was checked as it was."""

    name: str
    out: str
    export_refusal: str | None
    checks: tuple
    counts: dict
    reused_export: bool = False


def check_die(design: Path, args: argparse.Namespace) -> int:
    """``tactcad check`` of a die's design file (:func:`die_check`), printed as text or,
    with ``--json``, as one JSON object.

    Returns:
        0, or 1 when a check fails.

    Raises:
        DesignError: ``--scene`` given, or ``--out`` holding another design's export.
    """
    from tactcad.checks.check_result import counts_text

    found = die_check(design, args, progress_from_args(args))
    checks, counts, out = found.checks, found.counts, found.out
    if args.json:
        print(dumps({"design": str(design), "out": out, "junit": getattr(args, "junit", None),
                     "reused_export": found.reused_export,
                     "export_refusal": found.export_refusal,
                     "checks": [{"check": c.check, "subject": c.subject,
                                 "status": c.status, "detail": c.detail} for c in checks],
                     "counts": counts,
                     # the export's own checks and those on the files (READ_BACK_CHECKS)
                     "checks_on_the_files": sum(on_the_files(c.check) for c in checks),
                     "checks_export_prints": sum(not on_the_files(c.check)
                                                 for c in checks)}, indent=1))
    else:
        shown = [c for c in checks if not (args.failures_only and c.status in ("pass", "info"))]
        print("\n".join([f"checking the die {found.name} in {out}",
                         *[c.line() for c in shown], counts_text(counts),
                         read_back_said(checks)]))
    return 1 if counts["failed"] else 0


def read_back_said(checks) -> str:
    """How a die's check's count differs from its export's: the checks of the files
    themselves (:data:`READ_BACK_CHECKS`) it adds, the rest those ``tactcad export``
    prints.

    Args:
        checks: the die's check's results, in order.

    Returns:
        One line, e.g. ``3 of them on the files themselves (die_files, ...); the other 50
        are the checks `tactcad export` prints``.
    """
    own = [c for c in checks if on_the_files(c.check)]
    names = ", ".join(dict.fromkeys(c.check for c in own))
    return (f"{len(own)} of them on the files themselves ({names}); the other "
            f"{len(checks) - len(own)} are the checks `tactcad export` prints")


def die_check(design: Path, args: argparse.Namespace,
              report: Callable[[str], None]) -> DieCheck:
    """A die's export in ``args.out`` (exported there first, said in one line to ``report``,
    unless the export is the one the design writes now, as an array's check decides it:
    :func:`_die_export_state`; a temporary folder without ``--out``) read back: the
    masks against the process's rules and the plan, the mount's solids, the drawing, and the
    record's plan against the design's; the results written to the export's review page and
    to ``args.junit`` where given.

    Args:
        design: the die's design file.
        args: the check's options (``out``, ``junit``, ``overrides``, ``scene``).
        report: told the export's reuse or refusal.

    Returns:
        :class:`DieCheck`.

    Raises:
        DesignError: ``--scene`` given, or ``--out`` holding another design's export.
    """
    import json as json_module
    import tempfile

    from tactcad.checks.check_result import CheckResult, status_counts
    from tactcad.checks.export_files import edited_results, stale_results
    from tactcad.commands.check import say_the_export_left_unread
    from tactcad.products.silicon_die.checks.die_mount_fit import mount_checks
    from tactcad.products.silicon_die.checks.gds_drc import gds_checks
    from tactcad.products.silicon_die.checks.traveller_check import traveller_checks
    from tactcad.checks.sheet_overlap import sheet_file_results
    from tactcad.products.silicon_die.design.die_mount import die_mount
    from tactcad.products.silicon_die.export.die_scene import mount_solids

    if getattr(args, "scene", None):
        raise DesignError("--scene", args.scene, "left out for a die",
                          f"{design.name} is a silicon die's design: it has no scenes to choose")
    junit = getattr(args, "junit", None)  # its path refused before, by check's own rule
    planned = plan_of(die_asked(_die_args(design, args, Path("."))))
    plan, name = planned.plan, planned.plan.name
    with tempfile.TemporaryDirectory(prefix="tactcad-die-check-") as temp:
        out = Path(args.out) if args.out else Path(temp)
        files = {k: out / v.format(name=name) for k, v in DIE_FILES.items()}
        state = _die_export_state(out, planned, files["record"])
        refusal = state.refusal
        say_the_export_left_unread(args, report)
        if refusal is None:  # hand edits are left as they are, each a failing check
            from tactcad.export.reuse import stale_said

            report(f"checking the export in {out} as it is"
                   + (f" ({len(state.edited)} file(s) changed or removed by hand since)"
                      if state.edited else " (same design, every file as listed)")
                   + (f"; it is {stale_said(state.stale)}" if state.stale else ""))
        else:  # as an array's check does: exported there first, said in one line
            if args.out:  # another design's export is refused as export refuses it
                refuse_a_foreign_folder(out, name)
            report(f"exporting to {out} first: {refusal}" if args.out else
                   f"exporting to the temporary folder {out} first (no --out)")
            quiet = argparse.Namespace(**{**vars(args), "json": True})
            with contextlib.redirect_stdout(io.StringIO()):
                run(_die_args(design, quiet, out))
        record = _record_of(files["record"])
        missing = [p.name for p in files.values() if not p.is_file()]
        mount = die_mount(plan, planned.jaw_stated)
        # the requirements first, as the array's check and the die's export order them
        checks = die_requirement_checks(plan, mount) + [CheckResult("die_files", str(out), not missing,
                              f"missing: {', '.join(missing)}" if missing
                              else f"{len(files)} files of {name}")]
        # the array's rule: one for every product (and one when the export checked as it is
        # is older than its inputs; one exported first is not)
        checks += edited_results(out, state.edited) + stale_results(
            out, state.stale if refusal is None else ())
        if not missing:
            same = record.get("die") == json_module.loads(dumps(plan.as_json()))
            checks.append(CheckResult("die_record", files["record"].name, same,
                                      "the plan the design makes" if same else
                                      "another plan than the design makes: export again"))
            checks += (gds_checks(files["masks"], plan)
                       + traveller_checks(files["traveller"], files["masks"])
                       + mount_checks(mount_solids(plan, mount), mount, f"{name}_posts")
                       + sheet_file_results(files["drawing"]))
        counts = status_counts(checks)
        if not missing and args.out:  # the results on the export's review page, as an array's
            from tactcad.checks.review_results import update_checks_script

            sha = (json_module.loads(files["manifest"].read_text(encoding="utf-8"))
                   .get("design", {}).get("sha256", ""))
            update_checks_script(out, sha, [(f"die {name}", checks)])
        if junit is not None:  # one suite, the die's: for a lab's CI as an array's check gives
            from tactcad.checks.junit import write_junit

            write_junit(junit, [(name, checks)], [name])
        return DieCheck(name, str(out), refusal if args.out else None, tuple(checks), counts,
                        reused_export=refusal is None)


def _die_export_state(out: Path, planned: PlannedDie, record: Path) -> "ExportState":
    """What the die's check finds in ``out``, by the array's rule
    (:func:`tactcad.export.reuse.export_state`: the manifest's design file sha256 and
    ``--set`` values, versions, every listed file's sha256, and its ``inputs``, the design
    and jaw files, against those files now: an export older than an edit of the jaw file is
    exported again; files changed by hand in an export of the same design are left as they
    are and listed, with what it is older than); a record of another plan is exported
    again, unless the record itself was edited."""
    import json as json_module

    from tactcad.export.reuse import ExportState, export_state
    from tactcad.products.silicon_die.export.die_inputs import changed_die_inputs

    source = planned.source or {}
    now = planned.inputs or {"files": []}
    state = export_state(out, {"sha256": source.get("sha256"),
                               "overrides": source.get("overrides", {})},
                         lambda recorded: changed_die_inputs(recorded, now))
    if state.refusal is None and record.relative_to(out).as_posix() not in state.edited \
            and (_record_of(record) or {}).get("die") != \
            json_module.loads(dumps(planned.plan.as_json())):
        return ExportState(f"{record.name} holds another plan than the design makes")
    return state


def refuse_a_foreign_folder(out: Path, name: str) -> None:
    """A die's files go into an empty or new folder, or one holding this die's own export:
    never beside another design's export (an array's, another die's), a mixed set; the rule
    every product's export keeps (:mod:`tactcad.export.export_owner`).

    Raises:
        DesignError: ``--out`` in a system folder (:func:`tactcad.atomic.refuse_system_folder`),
            a file, a folder with files but no export of this die, or a folder that cannot be
            made (:func:`tactcad.atomic.unmakeable_folder`).
        ExportPathError: a folder an export cannot replace as a whole (the home or working
            folder, a mount point, another user's export: the array's rule,
            :func:`tactcad.export.run.check_out_dir`).
    """
    from tactcad.atomic import refuse_output_path, unmakeable_folder
    from tactcad.export.export_owner import refuse_another_designs_export
    from tactcad.export.run import check_out_dir
    from tactcad.products.silicon_die.export.die_review import PRODUCT_NAME

    refuse_output_path("--out", out, "a folder")  # its default too: the rule of every output
    refuse_another_designs_export(out, PRODUCT_NAME, name)
    reason = None if out.is_dir() else unmakeable_folder(out)
    if reason is not None:  # before the staging folder beside it is made
        raise DesignError("--out", str(out), "a folder that can be made", reason)
    check_out_dir(out)  # the folder is swapped whole, as an array's export is


def _record_of(path: Path) -> dict | None:
    import json as json_module

    try:
        return json_module.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def _beam_of(plan, role: str):
    return next(b for b in plan.beams if b.role == role)

