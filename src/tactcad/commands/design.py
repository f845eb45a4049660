"""``tactcad design``: write a design file whose elements meet sensing targets."""

from __future__ import annotations

import argparse
import copy
import json
import math
import os
import shlex
from pathlib import Path
from typing import Any, Sequence

from tactcad.mechanics.ladder import is_meshed, models
from tactcad.commands import add_cache_args, add_design_arg, add_output_args, progress_from_args
from tactcad.commands.options import count, material_grade_name, number, output_file_or_folder
from tactcad.design.requirements_section import (MAX_FULL_SCALE_FORCE_N, MAX_GRASP_FORCE_N,
                                                 MAX_KOBJ_N_PER_MM, MAX_KR_OVER_KM,
                                                 MIN_FULL_SCALE_FORCE_N, MIN_KOBJ_N_PER_MM)
from tactcad.design.array_plan import (COLUMNS_RANGE, MIN_PAIRED_COLUMNS, STACKED_COLUMNS_RANGE,
                                       STACKED_COLUMNS_WHY)
from tactcad.errors import DesignError, DesignErrors, RequirementFailure
from tactcad.vocabulary.schema import NAME_ALLOWED


def check_columns(columns: int, allowed: tuple[int, int], what: str, why: str) -> None:
    """Refuse ``--columns`` outside the range of the product asked for.

    Args:
        columns: the columns asked.
        allowed: (fewest, most) columns of that product, inclusive.
        what: the product's words ("a stacked array", "a silicon die").
        why: why the range is what it is.

    Raises:
        DesignError: ``--columns`` outside ``allowed``, naming the range, the product and
            why, with the nearest count in range to paste.
    """
    lo, hi = allowed
    if lo <= columns <= hi:
        return
    nearest = min(max(columns, lo), hi)
    raise DesignError("--columns", columns, f"{lo} ... {hi} for {what}", why,
                      alternatives=[{"option": f"--columns {nearest}",
                                     "words": f"the nearest count {what} takes"}])




#: Decimal places a written design keeps of a length (mm): 1 nm, far below any tolerance,
#: so a value the search computes as 43 x 0.001 mm is written 0.043, not
#: 0.043000000000000003; the plan itself is computed unrounded.
WRITTEN_MM_PLACES = 6


def rounded_lengths(value: Any, key: str = "") -> Any:
    """``value`` (a design's tables, or one of their values under ``key``) with every float
    of a key ending in ``_mm``, alone or in a list, rounded to :data:`WRITTEN_MM_PLACES`;
    anything else as it is.

    Args:
        value: the tables (nested mappings and lists) or a value of them.
        key: the key ``value`` is under ("" at the top).

    Returns:
        A copy with the lengths rounded (mappings as dicts, lists as lists).
    """
    if isinstance(value, dict):
        return {k: rounded_lengths(v, str(k)) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [rounded_lengths(v, key) for v in value]
    if isinstance(value, float) and key.endswith("_mm") and math.isfinite(value):
        return round(value, WRITTEN_MM_PLACES)
    return value


def design_text(header: str, data: dict) -> str:
    """A design file's text: ``header`` and the tables as TOML, each length rounded to
    :data:`WRITTEN_MM_PLACES` (:func:`rounded_lengths`) where the file is written, each
    reason under ``[assumptions]`` ending with the value it is written for
    (:func:`tactcad.vocabulary.schema.with_written_values`: a later edit shows it stale)."""
    import tomli_w

    from tactcad.vocabulary.schema import with_written_values

    return header + tomli_w.dumps(with_written_values(rounded_lengths(data)))


#: How a searched design is checked (``--verify``), without ``--jaw``: ``auto`` climbs the
#: ladder only for a requirement the closed form leaves undecided, as ``verify`` does.
DEFAULT_VERIFY = "auto"


def verify_levels() -> tuple[str, ...]:
    """``--verify`` choices: auto, the ladder's levels above the closed form, dearest first,
    or none."""
    return ("auto", *reversed(models()[1:]), "none")


def jaw_classes() -> tuple[str, ...]:
    """The grasper trocar classes a jaw can be designed to (mm)."""
    from tactcad.partlib.grasper_jaw import SHAFT_CLASSES_MM

    return tuple(SHAFT_CLASSES_MM)


def jaw_of(value: str) -> tuple[str | dict, str]:
    """(a trocar class or a ``[grasper_jaw]`` table, the file it came from) of ``--jaw``.

    Raises:
        DesignError: ``--jaw`` neither a class nor a readable TOML file with a
            ``[grasper_jaw]`` table.
    """
    from tactcad.design.array_plan import read_toml

    if value in jaw_classes():
        return value, ""
    allowed = (", ".join(jaw_classes())
               + " (mm trocar class) or a TOML file with a [grasper_jaw] table")
    path = Path(value)
    if not path.is_file():  # any name: read as TOML, whose errors name it
        raise DesignError("--jaw", value, allowed, "not a class, nor an existing file")
    table = read_toml(path, "--jaw").get("grasper_jaw")
    if not isinstance(table, dict):
        raise DesignError("--jaw", value, allowed, f"{path.name} has no [grasper_jaw] table")
    return table, str(path)


def process_choices() -> tuple[str, ...]:
    from tactcad.vocabulary.process import process_names

    return process_names()


def construction_choices() -> tuple[str, ...]:
    from tactcad.design.construction_registry import construction_names

    return construction_names()


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "design", help="inverse design: K_r/K_m, K_obj range and full-scale force -> design file",
        description="Chooses the arm lengths and the web of reference and measuring "
                    "elements for a stiffness ratio K_r/K_m, an object-stiffness range and a "
                    "full-scale force, within yield / safety factor and the gauge's fatigue "
                    "strain; where the base design's layout cannot, searches the sheet, the "
                    "ISO clamp bolt, the pitch and the tip width (each fixed by a --set of it, "
                    "the pitch by --pitch), nearest the base first; checks the written design "
                    "as tactcad verify does (--verify); writes the design TOML. A refusal names "
                    "the targets that bind and the nearest feasible ones as options to paste. "
                    "Units: N/mm, N, mm.")
    p.add_argument("--kr-over-km", type=number(1, MAX_KR_OVER_KM, lo_open=True), required=True,
                   metavar="X",
                   help="stiffness ratio K_r/K_m of a sensing unit (> 1; about 10 reads soft "
                        "objects with high sensitivity)")
    p.add_argument("--kobj-range", type=number(MIN_KOBJ_N_PER_MM, MAX_KOBJ_N_PER_MM, "N/mm"),
                   nargs=2, required=True, metavar=("LO", "HI"),
                   help="object stiffnesses to read (N/mm)")
    from tactcad.products.silicon_die.design.mems_die import FULL_SCALE_FORCE_WORDS

    p.add_argument("--full-scale-force", type=number(MIN_FULL_SCALE_FORCE_N,
                                                     MAX_FULL_SCALE_FORCE_N, "N"),
                   required=True, metavar="F",
                   help="force every element must carry (N); on a silicon die "
                        f"(--construction mems-die): {FULL_SCALE_FORCE_WORDS}")
    p.add_argument("--max-grasp-force", type=number(0, MAX_GRASP_FORCE_N, "N", lo_open=True),
                   default=None,
                   metavar="F",
                   help="with --jaw: the largest grasp the insert must survive (N): every "
                        "element within its overload limit, its hard stop taking the rest "
                        "(requirements.max_grasp_force_N; not judged when left out)")
    p.add_argument("--kobj-accuracy", type=number(0, 10, "", lo_open=True), default=None,
                   metavar="REL",
                   help="the largest relative K_obj error the design may read with over its "
                        "range (0 < REL <= 10; 0.1 = 10 %%): for a metal array the root sum "
                        "square of its K_obj budget after correction "
                        "(requirements.kobj_accuracy_rel, judged by verify), for a silicon "
                        "die its budget's worst root sum square before calibration "
                        "([die] kobj_accuracy_rel); a design that misses it is refused with "
                        "the accuracy it reaches to paste (not judged when left out)")
    p.add_argument("--material", metavar="GRADE", type=material_grade_name, default=None,
                   help="material grade of the library (default: the base design's material)")
    p.add_argument("--process", choices=process_choices(), default=None,
                   help="the cut process of the elements (%(choices)s: the process registry's, each "
                        "with its rules in the documentation's Processes page; "
                        "default: the base design's); the sheet is then searched over the "
                        "stock that process cuts a flexure from, and every web, hole and slot "
                        "held to its rules (element.process; with --jaw, the comb's rows: "
                        "its slots, notch and corner radii, webs and tolerance)")
    from tactcad.products.silicon_die.design.mems_die import COLUMNS_RANGE as DIE_COLUMNS

    per_product = (f"{STACKED_COLUMNS_RANGE[0]} ... {STACKED_COLUMNS_RANGE[1]} for a stacked "
                   f"array, {COLUMNS_RANGE[0]} ... {COLUMNS_RANGE[1]} for a comb, "
                   f"{DIE_COLUMNS[0]} ... {DIE_COLUMNS[1]} for a silicon die")
    p.add_argument("--columns", type=count(1, max(COLUMNS_RANGE[1], DIE_COLUMNS[1]),
                                           f"columns: {per_product}"),
                   metavar="N", default=None,
                   help=f"columns of the new grid (2 rows x N): {per_product}; default: the "
                        "base design's")
    p.add_argument("--rows", type=count(1, 100, "rows"), metavar="2", default=None,
                   help="rows of the new grid: 2, the only value taken (the model holds two "
                        "clamped rows facing each other; any other is refused); default 2")
    p.add_argument("--pitch", type=number(0, 1000, "mm", lo_open=True), metavar="MM", default=None,
                   help="array pitch, fixed (default: searched, starting from the base "
                        "design's)")
    p.add_argument("--footprint", type=number(0, 1e4, "mm", lo_open=True), nargs=2,
                   metavar=("X", "Y"), default=None,
                   help="plan-view envelope (mm) the clamped array must fit: the design is "
                        "refused, naming the envelope it needs, when it does not; the file "
                        "states it as requirements.footprint_mm so verify and check keep it")
    p.add_argument("--out", metavar="NEW.toml|DIR", type=output_file_or_folder(".toml"),
                   required=True,
                   help="design file to write (.toml), or a sensor project folder DIR to make "
                        "as `tactcad new` does (the design DIR/<name>.toml, <name> DIR's own "
                        "with '-' made '_', with its rigs, scenes, README, .gitignore and CI "
                        "workflow); the file's or folder's name is the design's: "
                        f"{NAME_ALLOWED}; a name with another character (a space, an accent) "
                        "is refused, offering it cleaned to paste (--out pince_ete for "
                        "'pince été'); any writable folder but system folders")
    p.add_argument("--force", action="store_true",
                   help="overwrite an existing file (default: refuse); for a project folder, "
                        "the files tactcad wrote for the project it held (its design, README, "
                        ".gitignore, CI workflow, the rigs, scenes and bought-parts list or the "
                        "jaw file its design names) are replaced or removed, so the folder "
                        "holds what the new design writes; files of your own are kept")
    p.add_argument("--tissue-coupling", choices=("on", "off"), default="on",
                   help="on (default): K_r and K_m centred on the K_obj range as the units see it "
                        "through one sample under all tips (rigid flat punches of the tip faces on "
                        "an elastic half-space or layer), each unit's coupled R checked to span "
                        "the range; off: eq. 2 alone (each tip on its own object spring)")
    p.add_argument("--tissue-poisson", type=number(0, 0.5, ""), metavar="NU", default=0.5,
                   help="Poisson ratio of the tissue (0 ... 0.5; default 0.5, nearly "
                        "incompressible soft tissue and rubber)")
    p.add_argument("--tissue-thickness", type=number(0, 1e4, "mm", lo_open=True), metavar="MM",
                   default=None, help="tissue layer thickness on a rigid base (mm; default: a "
                                      "half-space)")
    p.add_argument("--jaw", default=None, metavar="CLASS|FILE",
                   help="design an insert for the jaw of a laparoscopic grasper: a trocar "
                        "class's default jaw (mm: " + ", ".join(jaw_classes()) + ") or a TOML "
                        "file whose [grasper_jaw] table states a lab's own jaw (its pocket "
                        "width and length where given, else the most its body holds); "
                        "searches every "
                        "construction that seats in a jaw (sheet, pitch, arms, webs, hard stops) "
                        "inside the jaw's pocket; writes the design and its scenes (the insert "
                        "in the jaw), or names the binding limits and the nearest force")
    p.add_argument("--construction", choices=("auto",) + construction_choices()
                   + (DIE_CONSTRUCTION,), default="auto",
                   help="construction of the array (default auto: the stacked array, or with "
                        "--jaw every construction that seats in a jaw, and a silicon die's "
                        "design file where the jaw's pocket holds none; mems-die: the die "
                        "only, with --jaw)")
    p.add_argument("--verify", choices=verify_levels(), default=None,
                   help=f"how the chosen geometry is checked (default {DEFAULT_VERIFY}: the "
                        "closed form, and a FEM level only for a requirement it leaves "
                        "undecided, as `tactcad verify`; fem3d checks each element's K at the "
                        "top of the ladder, about 1.5 min an element on two cores; not with "
                        "--jaw, whose design the checks that need no CAD kernel check: run "
                        "tactcad verify on it)")
    add_design_arg(p, design_help="base design file (TOML), or a shipped example's name "
                   "(--design macro_array: the same base in any folder); default: the one "
                   "design file of the working folder, else the shipped example macro_array; "
                   "the base is named on stderr before the search and in the file written",
                   design_word=False)
    add_cache_args(p, ".tactcad-cache in the folder the design is written to, where the "
                      "project's commands find it; for a new --out DIR, the folder DIR is "
                      "made in, copied into DIR with the project, so a refused design "
                      "makes no folder and its rerun solves nothing again")
    add_output_args(p, "print JSON")
    p.set_defaults(func=run, default_store=project_store)


#: ``--out`` names ending so are taken for a mistyped design file, not a new folder.
FILE_LIKE_SUFFIXES = (".toml", ".tml", ".tom", ".json", ".yaml", ".yml", ".txt", ".cfg", ".ini")


def check_project_folder(out: str) -> Path:
    """The resolved project folder ``--out DIR``: new, or an existing folder
    (its files are checked when the project is written), outside the system
    folders and the installed package.

    Raises:
        DesignError: naming ``--out``, the value and what is allowed.
    """
    from tactcad import __file__ as package_init
    from tactcad.atomic import refuse_system_folder
    from tactcad.errors import DesignError

    folder = Path(os.path.abspath(os.path.expanduser(out))).resolve()
    refuse_system_folder("--out", out, folder)
    if folder.is_relative_to(Path(package_init).resolve().parent):
        raise DesignError("--out", out, "a folder outside the installed package")
    if folder.exists() and not folder.is_dir():
        raise DesignError("--out", out, "a file name ending in .toml, or a project folder",
                          "it is a file without .toml")
    if not folder.exists() and folder.suffix.lower() in FILE_LIKE_SUFFIXES:
        raise DesignError("--out", out, "a file name ending in .toml (lower case), or a "
                          "project folder", f"{folder.suffix} names a file, not a folder")
    if not folder.parent.is_dir():
        raise DesignError("--out", out, "a folder in an existing folder",
                          f"{folder.parent} is not a folder")
    if not os.access(folder if folder.exists() else folder.parent, os.W_OK):
        raise DesignError("--out", out, "a writable folder")
    return folder


def check_output_path(out: str, force: bool) -> Path:
    """The resolved output path: any ``.toml`` file in a writable folder, refused
    in a system folder (:func:`tactcad.atomic.refuse_system_folder`), as the default
    design or inside the installed package, or when it exists without ``--force``.

    Raises:
        DesignError: naming ``--out``, the value and what is allowed.
    """
    from tactcad import __file__ as package_init
    from tactcad.atomic import refuse_system_folder
    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.errors import DesignError

    path = Path(os.path.abspath(os.path.expanduser(out))).resolve()
    folder = path.parent
    if path.suffix != ".toml":
        raise DesignError("--out", out, "a file name ending in .toml, or a project folder")
    refuse_system_folder("--out", out, folder, "a file")
    if path == DEFAULT_DESIGN.resolve() or path.is_relative_to(Path(package_init).parent):
        raise DesignError("--out", out, "a new file, not the default design or a package file")
    if not folder.is_dir():
        raise DesignError("--out", out, "a file in an existing folder",
                          f"{folder} is not a folder")
    if path.exists() and not force:
        raise DesignError("--out", out, "a file that does not exist yet (or give --force)")
    if path.is_dir():
        raise DesignError("--out", out, "a file name, not a folder")
    if not os.access(path if path.exists() else folder, os.W_OK):
        raise DesignError("--out", out, "a writable file in a writable folder")
    return path


def project_store(args: argparse.Namespace) -> Path:
    """Where ``design`` keeps its FEM results without ``--cache``: the store of the folder
    the design is written to (an existing ``--out DIR``, or the folder of ``--out
    NEW.toml``), so ``verify`` run in that folder right after solves nothing again. A new
    ``--out DIR`` is not made for the store: its results go to the store of the folder it
    would be made in (as ``--out NEW.toml`` there), so a refused design, which makes no
    folder, leaves them where the same command run again finds them; a written project gets
    a copy in its own store (:func:`run`).

    Args:
        args: the design's options (``out``).

    Returns:
        The store folder.
    """
    from tactcad.store import STORE_FOLDER

    out = Path(os.path.expanduser(args.out))  # as check_project_folder reads it
    if args.out.endswith(".toml") or not out.is_dir():
        return out.parent / STORE_FOLDER
    return out / STORE_FOLDER


def run(args: argparse.Namespace) -> int:
    """``design``: the searched design written, or a refusal that leaves no folder it made.
    A new ``--out DIR`` is made only by the project written: the solves go to the store of
    the folder it lies in (:func:`project_store`), where a rerun of a refused design finds
    them, and a written project gets a copy of them in its own store."""
    from tactcad.atomic import refuse_too_long_name
    from tactcad.store import STORE_FOLDER, copy_block_results

    refuse_too_long_name("--out", args.out,  # before the file system is asked of it
                         "a file" if args.out.endswith(".toml") else "a folder")
    out = Path(os.path.expanduser(args.out))  # as check_project_folder reads it
    made = not out.exists() and not args.out.endswith(".toml")
    try:
        code = _run(args)
    except (DesignError, KeyboardInterrupt):
        if made and out.is_dir() and {p.name for p in out.iterdir()} <= {STORE_FOLDER}:
            import shutil

            shutil.rmtree(out, ignore_errors=True)
        raise
    if made and out.is_dir() and not getattr(args, "cache", None) \
            and not getattr(args, "no_cache", False):
        # solved into the store beside it (project_store): the project's commands read theirs
        copy_block_results(out / STORE_FOLDER)
    return code


def _run(args: argparse.Namespace) -> int:
    from tactcad.atomic import write_bytes_atomic
    from tactcad.design.project import COMPANIONS
    from tactcad.project_folder import check_project_target
    from tactcad.studies.inverse_design import Targets
    from tactcad.studies.layout_search import searched_design

    if args.rows not in (None, 2):  # said as the option, not as the file's range "2 ... 2"
        raise DesignError("--rows", args.rows, "2", "the model holds two rows facing each other")
    targets = Targets(args.kr_over_km, tuple(args.kobj_range), args.full_scale_force,
                      tissue=tissue_of(args) if args.tissue_coupling == "on" else None)
    if args.jaw is not None or args.construction not in ("auto", "stacked"):
        return run_jaw(args, targets)
    if args.max_grasp_force is not None:
        raise DesignError("--max-grasp-force", args.max_grasp_force, "only with --jaw",
                          "a grasp is judged in the jaw the design is for; state "
                          "requirements.max_grasp_force_N with the design's [grasper_jaw]")
    folder = None if args.out.endswith(".toml") else check_project_folder(args.out)
    path = check_output_path(args.out, args.force) if folder is None else \
        folder / f"{folder.name.replace('-', '_') or 'inverse_design'}.toml"
    check_design_name(args.out, folder, path)
    if folder is not None:  # an existing project is refused now, not after the search
        check_project_target(folder, path.name, args.force, companions=COMPANIONS.values())
    stacked = STACKED_COLUMNS_RANGE  # the design file's own range (array.columns)
    if args.columns is not None:
        check_columns(args.columns, stacked, "a stacked array", STACKED_COLUMNS_WHY)
    data, design = start_from_args(args, name=path.stem.replace("-", "_") or "inverse_design",
                                   out=path)
    check_columns(int(data["array"]["columns"]), stacked, "a stacked array", STACKED_COLUMNS_WHY)
    if not (args.json or args.quiet):  # the base, said before the search that starts from it
        from tactcad.commands.notices import print_heads

        print_heads()
    kwargs = {}
    if args.footprint is not None:
        from tactcad.assembly.inventory import array_envelope_mm

        kwargs = dict(footprint_mm=tuple(args.footprint), envelope_of=array_envelope_mm)
    try:
        result = searched_design(data, targets, fixed=fixed_fields(args), validate=project_check(path),
                                 name=data["design"]["name"], **kwargs)
    except DesignError as exc:
        raise as_options(exc, args, design) from None
    from dataclasses import replace

    from tactcad.studies.inverse_design import with_base_named

    label = base_label(design)
    result = replace(result, data=with_base_named(result.data, label))
    if args.kobj_accuracy is not None:
        result = with_kobj_accuracy(result, args.kobj_accuracy)
        # judged on the rigs the written project calibrates on, as verify reads the file
        result = replace(result, plan=written_plan(result.data, path))
    progress = progress_from_args(args)
    asked = args.verify or DEFAULT_VERIFY
    margins = design_margins(result.plan)
    if args.kobj_accuracy is not None:  # a miss is not written, as a failed requirement is not
        refuse_missed_accuracy(margins, args.kobj_accuracy)
    warn_coarse_reading(result.plan)
    level, records = design_verification(result.plan, asked, margins, progress)
    report = design_report(result, level or "none", progress, margins)
    report["verify"] = verification_summary(asked, level, records)
    report["tissue_coupling"] = coupling_summary(result, args)
    from tactcad.version import VERSION

    header = (f"# Written by tactcad {VERSION}: "
              f"`tactcad design {' '.join(design_options(args))}`.\n"
              f"{base_comment(label, bool(args.design), label != design.name)}"
              f"# Units: mm, N, MPa. Reasons for the chosen values are under [assumptions].\n\n")
    text = design_text(header, result.data)
    if folder is None:  # the rigs a design file alone takes are those beside it
        report["rigs"] = rigs_beside(result.data, path, args.out)
        write_bytes_atomic(path, text.encode("utf-8"))
    else:
        from tactcad.project_folder import write_project
        write_project(folder, text, path.name, result.plan, force=args.force, option="--out")
    report["out"] = str(path)
    if args.json:
        print(json.dumps(report, indent=2, allow_nan=False))
    else:
        print_report(report)
    return 0 if report["verify"]["passed"] else 1  # written, and its check fails


#: ``--construction`` of a silicon die (not an array construction: its design file is read
#: by ``tactcad die --design``).
DIE_CONSTRUCTION = "mems-die"
#: Options a die does not take: option -> (attribute, why).
DIE_IGNORES = {"--material": ("material", "the die is single-crystal silicon"),
               "--process": ("process", "the die is made by its SOI process (tactcad die)"),
               "--tissue-thickness": ("tissue_thickness", "a die's tissue coupling is not "
                                                          "computed yet")}


def die_ignored(args: argparse.Namespace) -> dict[str, str]:
    """The options given that a die does not take (:data:`DIE_IGNORES`): option -> why."""
    return {option: why for option, (attr, why) in DIE_IGNORES.items()
            if getattr(args, attr, None) is not None}


def untried_die_line(ignored: dict[str, str], designs: bool) -> str:
    """The line of a jaw refusal for the silicon die not tried for the options given that a
    die does not take (:func:`die_ignored`).

    Args:
        ignored: those options -> why a die takes none.
        designs: whether the die designs in this jaw without them (its paste follows).

    Returns:
        ``silicon die: not tried: ...`` on one line, ending without a parenthesis (it closes
        the refusal's).
    """
    options = " and ".join(ignored)
    verb = "is a metal's option" if len(ignored) == 1 else "are a metal's options"
    text = f"silicon die: not tried: {options} {verb}"
    return text + (f"; without {options} the die designs in this jaw, to paste below"
                   if designs else "")


def die_without_metal_options(args: argparse.Namespace, targets, room) -> dict | None:
    """The silicon die's paste for the lab's own jaw when options a die does not take
    (:func:`die_ignored`, such as ``--material``) kept it from being tried: the die's
    change that designs at the columns asked (:func:`die_columns_that_design`), to paste
    with those options left out.

    Args:
        args: the options asked. targets: the targets asked (N/mm, N). room: the jaw's
            room (:class:`tactcad.partlib.grasper_jaw.JawRoom`, mm).

    Returns:
        The alternative (``option``: ``--construction mems-die`` and the targets that bind;
        ``words``: the options to leave out and why; ``without``: those options), or None
        where the die does not fit the jaw at those columns or no pasted target designs it.
    """
    from tactcad.products.silicon_die.design.die_mount import die_misfit
    from tactcad.products.silicon_die.design.mems_die import COLUMNS_RANGE, DEFAULT_COLUMNS

    ignored = die_ignored(args)
    columns = args.columns or DEFAULT_COLUMNS
    if not ignored or not COLUMNS_RANGE[0] <= columns <= COLUMNS_RANGE[1] \
            or die_misfit(room, room.table or {}, columns):
        return None
    from tactcad.store import Store, keeping_results

    with keeping_results(Store(None)):  # an alternative looked at: nothing kept on disk
        whole = die_columns_that_design(columns, targets, room)
    if not whole:
        return None
    change = whole.split(maxsplit=2)[2:]  # the columns are those asked (or the default)
    left_out = ", ".join(f"{o} {getattr(args, DIE_IGNORES[o][0])}" for o in ignored)
    why = "; ".join(ignored.values())
    return {"option": " ".join(["--construction", DIE_CONSTRUCTION, *change]),
            "words": f"the silicon die in this jaw, with {left_out} left out: {why}",
            "without": list(ignored)}


def misfit_words(misfits: list[dict]) -> str:
    """A product's misfits against a jaw (:func:`tactcad.studies.comb_design.comb_misfit`,
    :func:`tactcad.products.silicon_die.design.die_mount.die_misfit`) in words: "does not
    fit: " and each dimension that binds against the jaw's key, joined by "; "."""
    return "does not fit: " + "; ".join(m["words"] for m in misfits if m.get("words"))


def misfit_alternatives(misfits: list[tuple[str, list[dict]]]) -> list[dict]:
    """The pasteable alternatives of every product's misfits (``option``, ``words``: the
    product it makes fit, or the misfit's own ``paste_words``), each once."""
    out, seen = [], set()
    for name, missed in misfits:
        for m in missed:
            if m.get("option") and m["option"] not in seen:
                seen.add(m["option"])
                out.append({"option": m["option"], "words": m.get("paste_words") or (
                    f"a jaw the {name} fits" if not m["option"].startswith("--columns")
                    else f"the most columns of the {name} the pocket holds")})
    return out


def misfit_option(misfits: list[tuple[str, list[dict]]], refusals: list,
                  args: argparse.Namespace) -> tuple[str, Any, str]:
    """The option a refusal of misfits names: ``--columns`` where one product alone was
    judged (no other refused) and only its columns make it fit (each misfit's paste is
    ``--columns``: the pocket's length), as that product's own search names them; else
    ``--jaw``.

    Args:
        misfits: (product, its misfits) (:func:`misfit_alternatives`' argument).
        refusals: the constructions searched and refused.
        args: the options asked.

    Returns:
        (field, value, allowed): the allowed range in words for ``--columns`` (the count
        to paste follows as its alternative), or "" for ``--jaw`` (the caller names the
        jaw that holds the products).
    """
    if len(misfits) == 1 and not refusals:
        options = [m.get("option") or "" for m in misfits[0][1]]
        if options and all(o.startswith("--columns ") for o in options):
            return "--columns", args.columns or 6, "no more columns than the pocket holds"
    return "--jaw", args.jaw, ""


def misfit_limit(misfits: list[tuple[str, list[dict]]], refusals: list) -> str:
    """The limit code of a refusal of misfits: the first misfit's, where one product alone
    was judged (no other refused); else "" (several products bind on their own limits)."""
    if len(misfits) == 1 and not refusals and misfits[0][1]:
        return misfits[0][1][0].get("limit", "")
    return ""


#: The target options a die's refusal pastes, and the :class:`~tactcad.studies.inverse_design.Targets`
#: field each sets.
DIE_TARGET_OPTIONS = {"--kr-over-km": "kr_over_km", "--kobj-range": "k_obj_range_N_per_mm",
                      "--full-scale-force": "full_scale_force_N"}
#: The die's refusals followed at most this many times for one pasted change (each pastes
#: a change that designs: a second is a safeguard, not the rule).
DIE_PASTE_ROUNDS = 3


def pasted_targets(option: str, targets: Any) -> tuple[Any, dict[str, str]] | None:
    """``targets`` with the target options of a pasted ``option`` set
    (:data:`DIE_TARGET_OPTIONS`), or None when it pastes any other option.

    Args:
        option: the options a refusal pastes, e.g. ``--kobj-range 0.3 3 --full-scale-force
            0.004`` (N/mm, N).
        targets: the targets asked (:class:`~tactcad.studies.inverse_design.Targets`).

    Returns:
        (the targets changed, {option: its words as pasted}), or None.
    """
    import dataclasses

    words, changed, flag = shlex.split(option), {}, None
    for word in words:
        if word.startswith("--"):
            if word not in DIE_TARGET_OPTIONS:
                return None
            flag = word
            changed[flag] = []
        elif flag is not None:
            changed[flag].append(word)
    if not changed:
        return None
    values = {DIE_TARGET_OPTIONS[f]: (tuple(float(v) for v in vs) if len(vs) > 1
                                      else float(vs[0])) for f, vs in changed.items()}
    return dataclasses.replace(targets, **values), {f: " ".join(vs) for f, vs in changed.items()}


def die_columns_that_design(columns: int, targets, room) -> str:
    """The change to paste that designs a die of ``columns`` in the jaw's ``room``: the
    columns and every target that binds at them, as the die's own refusals paste them (a
    lighter rating rounded down, a K_obj range that fits), so that pasting it designs.

    Args:
        columns: the columns the pocket holds.
        targets: the targets asked (:class:`~tactcad.studies.inverse_design.Targets`: N/mm, N).
        room: the jaw's room (:class:`tactcad.partlib.grasper_jaw.JawRoom`, mm).

    Returns:
        ``--columns N`` and the target options that bind there, or "" when no change the
        die's refusals paste designs it.
    """
    from tactcad.products.silicon_die.studies.die_doping import doped_die_plan

    pasted: dict[str, str] = {}
    for _ in range(DIE_PASTE_ROUNDS):
        try:
            doped_die_plan(targets, room, columns=columns)
        except DesignError as refusal:
            offered = [a["option"] for a in refusal.alternatives if a.get("option")]
            change = pasted_targets(offered[0], targets) if offered else None
            if change is None:
                return ""  # the die refuses at these columns with nothing a target helps
            targets, options = change
            pasted.update(options)
            continue
        return " ".join([f"--columns {columns}", *(f"{f} {v}" for f, v in pasted.items())])
    return ""


def die_misfits_that_design(missed: list[dict], targets, room) -> list[dict]:
    """The die's misfits (:func:`~tactcad.products.silicon_die.design.die_mount.die_misfit`)
    with each ``--columns N`` to paste widened to the change that designs at N
    (:func:`die_columns_that_design`): fewer columns that the die then refuses for its
    rating would be a paste that does not design.

    Args:
        missed: the die's misfits (``words``, ``option``).
        targets: the targets asked. room: the jaw's room (mm).

    Returns:
        The misfits, a ``--columns`` option replaced by the whole change ("" when none
        designs), its ``paste_words`` naming what else it sets.
    """
    out = []
    for m in missed:
        option = m.get("option") or ""
        if option.startswith("--columns "):
            whole = die_columns_that_design(int(option.split()[1]), targets, room)
            more = [w for w in whole.split()[2:] if w.startswith("--")]
            m = {**m, "option": whole}
            if more:
                m["paste_words"] = ("the most columns of the silicon die the pocket holds, "
                                    f"and the {', '.join(more)} they take")
        out.append(m)
    return out


def _other_classes_holding(c, args: argparse.Namespace, base, targets) -> list[dict]:
    """``--jaw CLASS`` for the first trocar class's default jaw (other than the one asked)
    that the construction ``c``'s smallest build fits (its screen finds no misfit)."""
    from tactcad.partlib.grasper_jaw import jaw_room

    for k in jaw_classes():
        if k != args.jaw and not c.jaw_screen()(jaw_room(k), args.columns or 6, base, targets,
                                                args.material, args.process):
            return [{"words": "", "option": f"--jaw {k}"}]
    return []


def one_refusal_line(construction: str, exc: DesignError | str) -> str:
    """A construction's refusal on one line: its head and every reason under it (a refusal
    of many lines lists one per sheet or limit), joined by "; " (a text: as it is)."""
    if isinstance(exc, str):
        return f"{construction}: {exc}"
    text = exc.message if hasattr(exc, "message") else str(exc)
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return f"{construction}: " + " ".join(lines[:1]) + (
        " " + "; ".join(lines[1:]) if len(lines) > 1 else "")


def paste_distance(option: str, args: argparse.Namespace) -> float:
    """How far a pasted option moves what was asked.

    Args:
        option: the options to paste (``--full-scale-force 0.14``, ``--columns 5
            --full-scale-force 0.02``); ``--construction`` in it is not counted.
        args: the options asked.

    Returns:
        The sum, over each number pasted, of ``|ln(pasted / asked)|`` (scale-free, so a
        force in N and a K_obj range in N/mm add up; for a lower force, the larger the
        nearer); ``math.inf`` where it pastes a value asked as no number or not asked at
        all (a jaw, a jaw file's key, a default's columns): nearness is not measured then.
    """
    distance, flag = 0.0, None
    pasted: dict[str, list[str]] = {}
    for word in shlex.split(option):
        if word.startswith("--"):
            flag = word
            pasted.setdefault(flag, [])
        elif flag is not None:
            pasted[flag].append(word)
    for flag, words in pasted.items():
        if flag == "--construction":
            continue
        asked = getattr(args, flag[2:].replace("-", "_"), None)
        asked = list(asked) if isinstance(asked, (list, tuple)) else [asked]
        if not all(isinstance(a, (int, float)) and not isinstance(a, bool) for a in asked):
            return math.inf  # asked as no number (a jaw's class or file), or not asked
        try:
            pairs = [(float(w), float(a)) for w, a in zip(words, asked, strict=True)]
        except ValueError:  # a word pasted, or another count of values
            return math.inf
        if not words or any(not (p > 0 and a > 0) for p, a in pairs):
            return math.inf
        distance += sum(abs(math.log(p / a)) for p, a in pairs)
    return distance if pasted else math.inf


def constructions_refusal(refused: list[tuple[str, str, DesignError]], args: argparse.Namespace,
                          after: Sequence[str] = (), more: Sequence[dict] = ()) -> DesignError:
    """The refusal of ``design --jaw`` when several constructions were tried and none designs.

    Each construction's own nearest option (the first alternative of its refusal) is offered
    with ``--construction`` so that pasting it designs that construction, the one nearest
    what was asked first (:func:`paste_distance`; for a force the largest that designs), and
    the headline is that construction's refusal (its option, value, allowed range and limit).

    Args:
        refused: (its ``--construction`` name, the name its line reads, its refusal), in the
            order tried.
        args: the options asked.
        after: lines said after the refusals (the constructions that do not fit the jaw).
        more: alternatives offered after the refusals' (a jaw that one of them fits).

    Returns:
        One :class:`~tactcad.errors.DesignError` naming every refusal, nearest first.
    """
    def nearest_of(entry: tuple[str, str, DesignError]) -> float:
        alternatives = [a for a in entry[2].alternatives if a.get("option")]
        return paste_distance(alternatives[0]["option"], args) if alternatives else math.inf

    order = sorted(refused, key=nearest_of)  # stable: tied ones in the order tried
    pasted, seen = [], set()
    for name, shown, exc in order:
        for a in exc.alternatives:
            if a.get("option"):
                option = f"--construction {name} {a['option']}"
                if option not in seen:
                    seen.add(option)
                    words = a.get("words") or ""
                    pasted.append({**a, "option": option,
                                   "words": f"the {shown}: {words}" if words else f"the {shown}"})
    _, shown, head = order[0]
    lines = [refusal_under(s, e, head) for _, s, e in order] + list(after)
    allowed = head.allowed or "a design"
    if len(order) > 1:  # one construction: its name heads its reasons, said once
        allowed += (f" ({shown}, the nearest of the {len(order)} constructions that refuse; "
                    "each one's to paste below)")
    return DesignError(head.field, head.value, allowed, each_on_its_line(lines),
                       alternatives=[*pasted, *more], limit=getattr(head, "limit", ""))


def each_on_its_line(lines: Sequence[str]) -> str:
    """A jaw refusal's reasons, one construction's a line (as the refusal of the
    constructions that do not fit the jaw says them): a single one as it is.

    Args:
        lines: each construction's ``name: ...`` line, in the order said.

    Returns:
        The refusal's parenthesis text: ``each against this jaw:`` and a line each, or the
        one line.
    """
    if len(lines) == 1:
        return lines[0]
    return "each against this jaw:\n  " + "\n  ".join(lines)


def refusal_under(construction: str, exc: DesignError, head: DesignError) -> str:
    """A construction's refusal under the headline ``head`` of :func:`constructions_refusal`,
    saying nothing the headline says: the headline's own refusal by its reasons, one of the
    same option and value by its allowed range and reasons, any other by its whole line
    (:func:`one_refusal_line`).

    Args:
        construction: the construction's name as the line reads it.
        exc: its refusal.
        head: the refusal the headline states.

    Returns:
        ``construction: ...`` on one line.
    """
    if len(getattr(exc, "errors", (exc,))) > 1 or (exc.field, exc.value) != (head.field,
                                                                             head.value):
        return one_refusal_line(construction, exc)
    if exc is head:
        return f"{construction}: {exc.why or 'refused'}"
    return f"{construction}: allowed {exc.allowed}" + (f" ({exc.why})" if exc.why else "")


def write_die_design(args: argparse.Namespace, targets, room, path: Path, folder: Path | None,
                     refusals: list, left: list[str]) -> int:
    """``design --jaw`` where only a silicon die fits (or ``--construction mems-die``): the
    die planned for the targets in the jaw's pocket (:func:`tactcad.products.silicon_die.design.mems_die.die_plan`;
    its refusal is this command's) and its design file written at ``path`` (in ``folder``
    when ``--out`` names one, with a lab's jaw file copied beside it), for ``tactcad die
    --design``.

    Raises:
        DesignError: an option a die does not take (:data:`DIE_IGNORES`), or the die's own
            refusal (what binds, with a K_obj range to paste).
    """
    from tactcad.atomic import write_bytes_atomic
    from tactcad.products.silicon_die.design.die_file import die_file_text, suggested_cell_name
    from tactcad.products.silicon_die.design.mems_die import COLUMNS_RANGE as DIE_COLUMNS
    from tactcad.products.silicon_die.design.mems_die import DEFAULT_COLUMNS
    from tactcad.products.silicon_die.studies.die_doping import doped_die_plan

    ignored = die_ignored(args)
    if ignored:  # the first option a die does not take
        option, why = next(iter(ignored.items()))
        raise DesignError(option, getattr(args, DIE_IGNORES[option][0]),
                          "only for a metal construction", why)
    name = suggested_cell_name(path.stem)  # the folder's name, as a GDS cell takes it
    columns = args.columns or DEFAULT_COLUMNS
    check_columns(columns, DIE_COLUMNS, "a silicon die", "each unit pairs a reference beam "
                  "with a measuring beam along the die (die.columns)")
    plan = doped_die_plan(targets, room, columns=columns, name=name)
    jaw, jaw_file = jaw_of(args.jaw)
    from tactcad.products.silicon_die.design.die_mount import die_mount

    die_mount(plan, {"shaft_class_mm": jaw} if isinstance(jaw, str) else jaw)  # it seats
    stated = args.jaw
    if jaw_file:  # the lab's jaw beside the die's file: a sensor folder reads only itself
        stated = f"{path.stem}_jaw.toml"
    why = [one_refusal_line(n, e) for n, e in refusals]
    reasons = {"die.jaw": (f"tactcad design --jaw {shlex.quote(Path(args.jaw).name)}: "
                           + ("; ".join(why) if why else "a silicon die asked for") + "."),
               "die.kr_over_km": "The ratio asked (--kr-over-km).",
               "die.kobj_range_N_per_mm": "The range asked (--kobj-range).",
               "die.full_scale_force_N": "The force asked (--full-scale-force).",
               "die.columns": f"{columns} units along the die"
                              + (" (--columns)." if args.columns else " (the default)."),
               "die.pitch_um": "The die command's default spacing."}
    grasp = getattr(args, "max_grasp_force", None)
    grasp_row = None
    if grasp is not None:  # judged as verify judges it, before anything is written
        grasp_row = _die_survives_grasp(plan, jaw, grasp)
        reasons["die.max_grasp_force_N"] = "Asked (--max-grasp-force)."
    accuracy = getattr(args, "kobj_accuracy", None)
    if accuracy is not None:
        _die_reads_to(plan, accuracy)
        reasons["die.kobj_accuracy_rel"] = "Asked (--kobj-accuracy)."
    text = die_file_text(stated, targets.kr_over_km, targets.k_obj_range_N_per_mm,
                         targets.full_scale_force_N, columns, plan.pitch_um, plan.name,
                         "tactcad design " + " ".join(design_options(args)), reasons,
                         max_grasp_force_N=grasp, kobj_accuracy_rel=accuracy)
    beside = {}
    if jaw_file:  # the lab's file as it wrote it: its comments say where each value comes from
        beside[stated] = Path(jaw_file).read_text(encoding="utf-8-sig")
    if folder is not None:  # a project folder, as an array's design writes one
        from tactcad.project_folder import write_die_project

        write_die_project(folder, text, path.name, plan.name, beside,
                          force=getattr(args, "force", False))
    else:
        for rel, jaw_text in beside.items():
            if (path.parent / rel).resolve() != Path(jaw_file).resolve():  # not the lab's
                write_bytes_atomic(path.parent / rel, jaw_text.encode("utf-8"))  # own file
        write_bytes_atomic(path, text.encode("utf-8"))
    report = {"construction": DIE_CONSTRUCTION, "design": str(path), "jaw": room.label,
              "left_out": [*left, *why], "die": plan.as_json(),
              **({} if grasp_row is None else {"max_grasp_force": _grasp_summary(grasp_row)}),
              "next": (f"cd {shown_path(str(folder))} && tactcad export --out exports && "
                       "tactcad check --out exports" if folder is not None else
                       f"tactcad die --design {shown_path(str(path))} --out die")}
    if args.json:
        print(json.dumps(report, indent=2, allow_nan=False))
    else:
        b_r, b_m = plan.beams[0], plan.beams[plan.columns]
        print(f"{shown_path(str(path))}: silicon die for the {room.label} "
              f"({plan.die_length_um:g} x "
              f"{plan.die_width_um:g} um, {plan.thickness_words()})")
        for line in report["left_out"]:
            print(f"  not searched: {line}")
        print(f"  SOI device layer {plan.stack.device_um:g} um, beams {b_r.width_um:g} um wide: "
              f"reference {b_r.length_um:.4g} um, measuring {b_m.length_um:.4g} um long")
        if grasp_row is not None:
            print(f"  {_grasp_line(grasp_row)}")
        print(f"  next: {report['next']} (masks, wafer, STEP, traveller, review page, "
              "KLayout DRC)")
    return 0


def _die_survives_grasp(plan, jaw, grasp_N: float) -> dict:
    """A die asked to survive the grasp ``grasp_N`` (N) in its jaw (``jaw``: a trocar class
    or a jaw table), judged by verify's own row
    (:func:`tactcad.products.silicon_die.studies.die_verification.grasp_row`: the beams, the
    posts and the cavity floors under the stops).

    Returns:
        The row (its verdict ``pass`` or ``undecided``).

    Raises:
        DesignError: ``--max-grasp-force`` the die does not survive or the jaw cannot reach,
            with a grasp that passes to paste.
    """
    from tactcad.products.silicon_die.design.die_mount import die_mount
    from tactcad.products.silicon_die.studies.die_verification import grasp_row

    stated = {"shaft_class_mm": jaw} if isinstance(jaw, str) else jaw
    mount = die_mount(plan, stated)
    row = grasp_row(plan, mount, grasp_N)
    if row["verdict"] == "fail":
        raise DesignError("--max-grasp-force", grasp_N, "a grasp the die survives in its jaw",
                          row["binding_words"],
                          alternatives=_surviving_grasp(plan, mount, row, grasp_N))
    return row


def _grasp_summary(row: dict) -> dict:
    """What design reports of a die's grasp row: its verdict, target and predicted grasp (N),
    margin and error (relative) and the item that decides it."""
    return {k: row.get(k) for k in ("verdict", "target", "predicted", "margin_rel",
                                    "error_estimate_rel", "binding_item")}


def _grasp_line(row: dict) -> str:
    """The line design prints for a die's grasp row (N, %): judged as verify judges it; an
    undecided one says why."""
    head = (f"grasp {row['target']:g} N: {row['verdict'].upper()}, deciding "
            f"{row.get('binding_item') or 'none'}")
    if row.get("margin_rel") is not None:
        head += (f", margin {100 * row['margin_rel']:+.3g} % (error "
                 f"{100 * row['error_estimate_rel']:.2g} %)")
    if row["verdict"] == "undecided":
        head += ": the margin is inside the model's error, so verify cannot decide it"
    return head


def _surviving_grasp(plan, mount, row: dict, grasp_N: float) -> list[dict]:
    """The grasp to paste for a refused ``--max-grasp-force``: one whose verify row passes
    (:func:`tactcad.products.silicon_die.studies.die_verification.surviving_grasp_N`), from
    at most the jaw's reach closed flat on the default tissue (:func:`_jaw_reach_N`) and the
    grasp the refused row predicts less its error, two digits rounded down; none when no
    grasp passes."""
    from tactcad.products.silicon_die.studies.die_verification import (grasp_row,
                                                                       surviving_grasp_N)

    reach = _jaw_reach_N(plan, mount)
    start = min(grasp_N, reach)
    if row.get("predicted") is None and reach < grasp_N:  # out of reach: judged at the reach
        row = grasp_row(plan, mount, start)
        if row["verdict"] == "pass":
            start = min(start, row["predicted"] or start)
    if row.get("predicted"):
        start = min(start, row["predicted"] / (1.0 + row["error_estimate_rel"]))
    paste = surviving_grasp_N(plan, mount, start)
    if paste is None:
        return []
    return [{"option": f"--max-grasp-force {paste:g}",
             "words": f"a grasp this die survives in its jaw, its beams, posts and cavity "
                      f"floors judged as verify judges them: the grasp the row predicts less "
                      f"its error, two digits rounded down (the jaw reaches {reach:.4g} N "
                      f"closed flat on the default tissue)"}]


def _jaw_reach_N(plan, mount) -> float:
    """The grasp force of the die's jaw closed flat on the default tissue (N)."""
    import math

    from tactcad.products.silicon_die.in_use.die_grasp import die_grasp, die_jaw

    lo, hi = plan.kobj_range_N_per_mm
    return die_grasp(plan, mount, die_jaw(mount, mount.opening_angle_deg), math.sqrt(lo * hi),
                     angle_deg=0.0).total_force_N


def _die_reads_to(plan, accuracy_rel: float) -> None:
    """A die asked to read K_obj to ``accuracy_rel`` (relative), judged by verify's own row
    (:func:`tactcad.products.silicon_die.studies.die_verification.accuracy_row`: its K_obj
    budget's worst root sum square over the range).

    Raises:
        DesignError: ``--kobj-accuracy`` tighter than the die's budget reaches, with the
            accuracy it does reach (rounded up to two digits) to paste.
    """
    from dataclasses import replace

    from tactcad.products.silicon_die.studies.die_verification import accuracy_row

    row = accuracy_row(replace(plan, kobj_accuracy_rel=float(accuracy_rel)))
    if row["verdict"] == "fail":
        raise accuracy_refusal(accuracy_rel, row["predicted"], "this die",
                               row["binding_words"])


def _up2(value: float) -> str:
    """``value`` rounded up to two significant digits, as text ("inf" stays)."""
    if not math.isfinite(value) or value <= 0:
        return f"{value:g}"
    step = 10 ** (math.floor(math.log10(value)) - 1)
    return f"{math.ceil(value / step - 1e-9) * step:.2g}"


def _percent(rel: float) -> str:
    """A relative accuracy as ``0.069 (6.9 %)`` ("inf" when nothing reads K_obj)."""
    if not math.isfinite(rel):
        return f"{rel:g} (no unit reads K_obj)"
    return f"{rel:.3g} ({100 * rel:.3g} %)"


def accuracy_refusal(asked_rel: float, reached_rel: float, what: str,
                     basis: str, error_rel: float | None = None) -> DesignError:
    """The refusal of a ``--kobj-accuracy`` tighter than a design reaches: the accuracy
    asked, the best one reached (relative and in %) and the option to paste, so that it
    never names a force or contradicts itself. The option pasted is the accuracy the design
    meets beyond the figure's own error estimate (:func:`decided_accuracy`), so that the
    level that judged it decides it (a figure inside its error would be left to ``verify``'s
    ladder).

    Args:
        asked_rel: ``--kobj-accuracy`` (relative).
        reached_rel: the best accuracy the design reaches (relative; inf when none).
        what: the design's words ("this design", "this die").
        basis: what the accuracy is (the budget's words).
        error_rel: the relative error estimate of ``reached_rel`` (None: none, exact).

    Returns:
        The :class:`DesignError` naming ``--kobj-accuracy``.
    """
    decided = decided_accuracy(reached_rel, error_rel)
    allowed = (f">= {_up2(decided)} for {what}" if math.isfinite(reached_rel)
               else f"none for {what}")
    return DesignError("--kobj-accuracy", asked_rel, allowed,
                       f"asked {_percent(asked_rel)}; the best {what} reaches is "
                       f"{_percent(reached_rel)}{_error_words(error_rel)}: {basis}",
                       alternatives=_accuracy_paste(reached_rel, error_rel))


def decided_accuracy(reached_rel: float, error_rel: float | None) -> float:
    """The least accuracy (relative) a design is judged to meet beyond the error estimate
    of what it reaches: ``reached_rel`` x (1 + ``error_rel``), a hair beyond
    (:data:`tactcad.studies.verification.ROOM_BEYOND_ERROR`), as a derived requirement is
    padded; ``reached_rel`` itself without an error.

    Args:
        reached_rel: the accuracy reached (relative; inf when none).
        error_rel: its relative error estimate, or None.

    Returns:
        The relative accuracy (inf stays inf).
    """
    from tactcad.studies.verification import ROOM_BEYOND_ERROR

    if error_rel is None or not math.isfinite(error_rel) or error_rel <= 0:
        return reached_rel
    return reached_rel * (1.0 + error_rel) * (1.0 + ROOM_BEYOND_ERROR)


def _error_words(error_rel: float | None) -> str:
    """`` +- 4.49 % of it (the budget's own uncertainty)`` for an error estimate, else ""."""
    if error_rel is None or not math.isfinite(error_rel) or error_rel <= 0:
        return ""
    return f" +- {100 * error_rel:.3g} % of it (the budget's own uncertainty)"


def accuracy_words(asked_rel: float | None, reached_rel: float | None,
                   error_rel: float | None = None) -> str:
    """A missed ``--kobj-accuracy`` in words: the accuracy asked, the best one reached (in
    %, with its error estimate ``error_rel`` where given) and the option to paste (none
    when nothing reads K_obj)."""
    reached = math.inf if reached_rel is None else float(reached_rel)
    paste = _accuracy_paste(reached, error_rel)
    return (f"--kobj-accuracy asked {_percent(asked_rel) if asked_rel is not None else '?'}; "
            f"the best this design reaches is {_percent(reached)}{_error_words(error_rel)}"
            + (f"; to paste: {paste[0]['option']}" if paste else ""))


def _accuracy_paste(reached: float, error_rel: float | None = None) -> list[dict]:
    """``--kobj-accuracy`` at what a design reaches beyond its error estimate
    (:func:`decided_accuracy`, rounded up), when finite and <= 10."""
    decided = decided_accuracy(reached, error_rel)
    if not (math.isfinite(decided) and 0 < decided <= 10):
        return []
    beyond = ("" if decided == reached else
              ", beyond its error estimate, so that the closed form decides it")
    return [{"option": f"--kobj-accuracy {_up2(decided)}",
             "words": f"the accuracy this design reaches over the K_obj range{beyond}"}]


def with_kobj_accuracy(result, accuracy_rel: float, refuse: bool = False):
    """A searched metal design (:class:`~tactcad.studies.inverse_design.InverseDesign` or a
    jaw's comb design) stating ``requirements.kobj_accuracy_rel`` = ``accuracy_rel``, its
    plan made anew, so that its verification judges it (the K_obj budget after correction,
    :func:`tactcad.studies.verification.kobj_accuracy_record`); with ``refuse``, judged
    here at the closed form.

    Args:
        result: the searched design (its ``data`` and ``plan``).
        accuracy_rel: ``--kobj-accuracy`` (relative).
        refuse: judge it now and refuse a miss (a design to a jaw), else leave it to the
            design's verification.

    Returns:
        The design with the requirement stated and its plan made anew.

    Raises:
        DesignError: with ``refuse``, an accuracy the design does not reach, naming
            ``--kobj-accuracy`` and the accuracy it reaches to paste.
    """
    from dataclasses import replace

    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies.verification import verification_matrix

    data = copy.deepcopy(dict(result.data))
    data.setdefault("requirements", {})["kobj_accuracy_rel"] = float(accuracy_rel)
    data.setdefault("assumptions", {})["requirements.kobj_accuracy_rel"] = \
        "Asked (--kobj-accuracy)."
    plan = plan_from_dict(data, source="<inverse design>")
    if refuse:
        from tactcad.assembly.inventory import array_envelope_mm

        refuse_missed_accuracy(verification_matrix(plan, "closed-form",
                                                   envelope_mm=array_envelope_mm(plan)),
                               accuracy_rel)
    return replace(result, data=data, plan=plan)


def written_plan(data, path: Path):
    """The plan of the design tables ``data`` as its file at ``path`` loads, with the rigs
    its project gets (their force gauge calibrates its elements, so the K_obj budget reads
    the calibration ``verify`` reads on the written file).

    Args:
        data: the design's tables. path: where its file is written.

    Returns:
        The :class:`~tactcad.design.array_plan.Plan`.

    Raises:
        DesignErrors: the tables or the companions made for them are refused.
    """
    from tactcad.design.project import project_with_design_data
    from tactcad.project_folder import companion_tables

    return project_with_design_data(copy.deepcopy(dict(data)), path,
                                    companions=companion_tables).plan


#: Above this relative K_obj resolution a reading no longer tells K_obj from twice or half
#: of it (eq. 3's resolution over the object's own stiffness).
COARSE_RESOLUTION_REL = 1.0


def warn_coarse_reading(plan) -> None:
    """Warn when the K_obj resolution a written design derives for itself (its file states
    none) is over :data:`COARSE_RESOLUTION_REL`: the design is written, as the lab asked,
    and the lab is told that it reads K_obj only to within more than its own size.

    Args:
        plan: the written design's :class:`~tactcad.design.array_plan.Plan` (a stacked array
            or a comb; nothing is said for another plan).
    """
    import warnings

    from tactcad.design.array_plan import Plan
    from tactcad.errors import CoarseReadingWarning
    from tactcad.studies.verification import requirements_of

    if not isinstance(plan, Plan):
        return
    req = requirements_of(plan)
    if "kobj_resolution_rel" in req.stated or req.kobj_resolution_rel <= COARSE_RESOLUTION_REL:
        return
    lo, hi = req.kobj_range_N_per_mm
    warnings.warn(
        f"this design's K_obj resolution over {lo:.4g}-{hi:.4g} N/mm is written as "
        f"{100 * req.kobj_resolution_rel:.4g} % (requirements.kobj_resolution_rel = "
        f"{req.kobj_resolution_rel:.4g}; {req.reasons['kobj_resolution_rel']}): over "
        f"{100 * COARSE_RESOLUTION_REL:g} % a reading does not tell a tissue from one twice or "
        f"half as stiff; a K_r/K_m further from 1 (--kr-over-km), a larger --full-scale-force "
        f"or --kobj-accuracy reads finer", CoarseReadingWarning, stacklevel=2)


def refuse_missed_accuracy(records: list[dict], accuracy_rel: float) -> None:
    """Refuse a metal design whose ``kobj_accuracy_rel`` row fails at the closed form, as a
    base design's requirement the closed form fails is refused (:func:`failed_requirements`):
    the file is not written.

    Args:
        records: the closed form's verification records (or :func:`design_margins`), each
            with ``requirement``, ``verdict`` and ``predicted``.
        accuracy_rel: ``--kobj-accuracy`` (relative).

    Raises:
        DesignError: the row fails, naming ``--kobj-accuracy``, the accuracy asked and the
            one reached (the worst root sum square over the K_obj range) to paste.
    """
    row = next((r for r in records if r["requirement"] == "kobj_accuracy_rel"), None)
    if row is None or row["verdict"] != "fail":
        return
    reached = row.get("predicted")
    raise accuracy_refusal(accuracy_rel, math.inf if reached is None else float(reached),
                           "this design", "the root sum square of its K_obj error budget "
                           "after correction, worst over the K_obj range (tactcad budget)",
                           row.get("error_estimate_rel"))


def closed_form_accuracy_row(plan) -> dict | None:
    """The ``kobj_accuracy_rel`` record of a plan's closed-form verification matrix (the
    level a design to a jaw is judged at), or None when the plan states no accuracy.

    Args:
        plan: the design's plan, ``requirements.kobj_accuracy_rel`` stated.

    Returns:
        The record (``verdict``, ``predicted``: relative, ``error_estimate_rel``), or None.
    """
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.verification import verification_matrix

    records = verification_matrix(plan, "closed-form", envelope_mm=array_envelope_mm(plan))
    return next((r for r in records if r["requirement"] == "kobj_accuracy_rel"), None)


def jaw_designs_in_preference(result, targets, room, args: argparse.Namespace, name: str):
    """The designs a jaw's search offers for a requirement judged after it: a comb search's
    every comb that counts in its order of preference
    (:func:`tactcad.studies.comb_design.designs_in_preference`), any other design alone.

    Args:
        result: the search's answer. targets: the targets searched (N/mm, N).
        room: the jaw's room (mm). args: the options asked. name: the design's name.

    Returns:
        An iterable of designs, the search's own first.
    """
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.comb_design import CombDesign, designs_in_preference

    if not isinstance(result, CombDesign):
        return [result]
    return designs_in_preference(result, targets, room, args.columns or 6, name=name,
                                 envelope_of=array_envelope_mm,
                                 max_grasp_force_N=args.max_grasp_force)


def accuracy_reached(row: dict) -> float:
    """The accuracy (relative) a ``kobj_accuracy_rel`` record reaches beyond its error
    estimate (:func:`decided_accuracy`; inf when nothing reads K_obj)."""
    reached = row.get("predicted")
    return decided_accuracy(math.inf if reached is None else float(reached),
                            row.get("error_estimate_rel"))


def first_accurate_design(designs, accuracy_rel: float):
    """The first of ``designs`` whose closed form meets ``--kobj-accuracy`` (the
    requirement stated, :func:`with_kobj_accuracy`), or the refusal naming the best
    accuracy any of them reaches.

    Args:
        designs: the designs in the search's order of preference (a comb's every comb that
            counts, :func:`jaw_designs_in_preference`).
        accuracy_rel: ``--kobj-accuracy`` (relative, > 0).

    Returns:
        That design, the requirement stated and its plan made anew.

    Raises:
        DesignError: none meets it, naming ``--kobj-accuracy`` and the best accuracy
            reached beyond its error estimate to paste.
    """
    missed = []
    for design in designs:
        stated = with_kobj_accuracy(design, accuracy_rel)
        row = closed_form_accuracy_row(stated.plan)
        if row is None or row["verdict"] != "fail":
            return stated
        missed.append(row)
    if len(missed) <= 1:
        refuse_missed_accuracy(missed, accuracy_rel)
    best = min(missed, key=accuracy_reached)
    reached = best.get("predicted")
    raise accuracy_refusal(accuracy_rel, math.inf if reached is None else float(reached),
                           f"the {len(missed)} combs that count",
                           "the root sum square of each comb's K_obj error budget after "
                           "correction, worst over the K_obj range (tactcad budget)",
                           best.get("error_estimate_rel"))


def jaw_constructions(args: argparse.Namespace) -> tuple[list, list[str]]:
    """The constructions a jaw design searches (``--construction``, else every one whose
    registry entry has a search to a jaw) and a line for each one left out.

    Raises:
        DesignError: ``--jaw`` missing, or a construction asked for that does not seat in a jaw.
    """
    from tactcad.design.construction_registry import construction, construction_names

    if args.jaw is None:
        raise DesignError("--jaw", None, "a trocar class: " + ", ".join(jaw_classes()),
                          f"the {args.construction} construction is designed to a grasper's jaw")
    if args.construction == DIE_CONSTRUCTION:
        return [], []
    names = construction_names() if args.construction == "auto" else (args.construction,)
    chosen, left = [], []
    for name in names:
        c = construction(name)
        if c.jaw_search() is not None:
            chosen.append(c)
        elif args.construction == "auto":
            left.append(f"{name}: does not seat in a jaw ({c.scales_to_mm})")
        else:
            raise DesignError("--construction", name,
                              "auto or a construction that seats in a jaw",
                              f"{name} does not seat in a jaw ({c.scales_to_mm})")
    return chosen, left


#: Options of the stacked search that a jaw decides: option -> (its attribute, why).
JAW_DECIDES = {
    "--footprint": ("footprint", "the jaw's pocket (its outline, else its width and length) "
                                 "is the envelope"),
    "--pitch": ("pitch", "the pitch is searched inside the jaw's pocket"),
    "--design": ("design", "the base design is the construction's own jaw example"),
    "--set": ("overrides", "the base design is the construction's own jaw example"),
}


def refuse_options_a_jaw_sets(args: argparse.Namespace) -> None:
    """Refuse an option that ``--jaw`` decides itself (:data:`JAW_DECIDES`), so none
    is dropped unsaid.

    Raises:
        DesignError: naming the option, its value and why the jaw decides it.
    """
    for flag, (attr, why) in JAW_DECIDES.items():
        value = getattr(args, attr, None)
        if value not in (None, [], ()):
            shown = " ".join(f"{v:g}" for v in value) if attr == "footprint" else \
                (" ".join(value) if isinstance(value, list) else value)
            raise DesignError(flag, shown, "only without --jaw", why)
    if getattr(args, "verify", None) is not None:
        raise DesignError("--verify", args.verify, "only without --jaw",
                          "a design to a jaw is checked by the checks that run without the "
                          "CAD kernel; run `tactcad verify` on the written design")


#: The stated targets a pasted line's refusal may add to an offer, so that the offer
#: designs: an offered force then refused for its accuracy, columns then refused for
#: their force.
PASTE_WIDENS = ("--full-scale-force", "--kobj-accuracy")
#: The options whose offers are pasted and judged before they are offered.
PASTE_CHECKED = ("--full-scale-force", "--columns")
#: How many times an offer is widened by the refusal of the line it makes (each round adds
#: the next target that binds: the force, then the accuracy).
PASTE_ROUNDS = 3


def option_pairs(words: Sequence[str]) -> list[tuple[str, list[str]]]:
    """A command line's words as (option, its values), in order.

    Args:
        words: the words (``--full-scale-force``, ``0.144``, ...).

    Returns:
        The pairs; words before any option are left out.
    """
    pairs: list[tuple[str, list[str]]] = []
    for word in words:
        if word.startswith("--"):
            pairs.append((word, []))
        elif pairs:
            pairs[-1][1].append(word)
    return pairs


def pasted_line(words: Sequence[str], option: str) -> list[str]:
    """The command line ``words`` with ``option`` pasted: each option it names set to its
    values where it first stood (once), the others added at the end in their order.

    Args:
        words: the command's words. option: the options to paste (``--columns 6
            --full-scale-force 0.144``).

    Returns:
        The words of the pasted line.
    """
    pasted = dict(option_pairs(shlex.split(option)))
    out: list[tuple[str, list[str]]] = []
    for flag, values in option_pairs(words):
        if flag not in pasted:
            out.append((flag, values))
        elif flag not in {f for f, _ in out}:
            out.append((flag, pasted[flag]))
    given = {f for f, _ in out}
    out += [(f, vs) for f, vs in pasted.items() if f not in given]
    return [w for f, vs in out for w in (f, *vs)]


def pasted_refusal(args: argparse.Namespace, option: str) -> Exception | None:
    """The refusal of the command ``args`` with ``option`` pasted, run as that command
    runs (:func:`design_options`' line, parsed and checked) into a folder removed after it,
    nothing printed; None when it designs.

    Args:
        args: the options asked. option: the options an offer pastes.

    Returns:
        The refusal (a :class:`DesignError`, or the line's usage error), or None.
    """
    import contextlib
    import io
    import tempfile
    import warnings

    from tactcad.errors import TactcadError

    with tempfile.TemporaryDirectory() as tmp:
        words = pasted_line(shlex.split(" ".join(design_options(args))),
                            f"{option} --out {shlex.quote(str(Path(tmp) / 'pasted'))}")
        try:
            with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
                warnings.simplefilter("ignore")
                pasted = parsed_design_line(words)
                pasted.pasted_check = True  # its own offers are not pasted again
                _run(pasted)
        except TactcadError as exc:
            return exc
        except (OSError, ValueError):  # no room to try it, or a line the parser refuses:
            return None  # offered as it was
    return None


class _LineParser(argparse.ArgumentParser):
    """A parser that raises ValueError where argparse would print and exit."""

    def error(self, message: str):  # argparse's hook; it must not return
        raise ValueError(message)


def parsed_design_line(words: Sequence[str]) -> argparse.Namespace:
    """``tactcad design WORDS`` parsed and checked as the command line is
    (:func:`tactcad.commands.options.validate_options`), without the program's parser (the
    command reads no module above it).

    Args:
        words: the command's options.

    Returns:
        The parsed options.

    Raises:
        ValueError: argparse refuses the line. DesignError: a value the option rules refuse.
    """
    from tactcad.commands import settle_design
    from tactcad.commands.options import validate_options

    parser = _LineParser(prog="tactcad", allow_abbrev=False)
    register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["design", *words])
    validate_options(parser, args)
    settle_design(args)
    return args


def widened_paste(option: str, refusal: Exception) -> str | None:
    """``option`` with the paste of ``refusal`` added, where the line it makes is refused
    on another stated target (:data:`PASTE_WIDENS`) whose first offer (of the same
    construction, when both name one) sets only targets.

    Args:
        option: the options offered. refusal: the refusal of the line they make.

    Returns:
        The widened options, or None when the refusal offers no such target.
    """
    if getattr(refusal, "field", None) not in PASTE_WIDENS:
        return None
    own = dict(option_pairs(shlex.split(option))).get("--construction")
    for a in getattr(refusal, "alternatives", ()):
        pairs = option_pairs(shlex.split(a.get("option") or ""))
        flags = {f for f, _ in pairs}
        if not flags or not flags <= {*PASTE_WIDENS, "--construction"}:
            continue
        theirs = dict(pairs).get("--construction")
        if own and theirs and own != theirs:
            continue
        return " ".join(pasted_line(shlex.split(option), a["option"]))
    return None


def designing_paste(args: argparse.Namespace, option: str) -> str | None:
    """The offer ``option`` widened until the line it makes designs: each round pastes it
    (:func:`pasted_refusal`) and adds the target its refusal offers (:func:`widened_paste`),
    at most :data:`PASTE_ROUNDS` times.

    Args:
        args: the options asked. option: the options offered.

    Returns:
        The options that design (``option`` itself when it does), or None when no round
        designs.
    """
    for _ in range(PASTE_ROUNDS):
        refusal = pasted_refusal(args, option)
        if refusal is None:
            return option
        option = widened_paste(option, refusal)
        if option is None:
            return None
    return None


def designing_alternatives(alternatives: Sequence[dict], args: argparse.Namespace) -> list[dict]:
    """A jaw refusal's offers, each that pastes a force or columns (:data:`PASTE_CHECKED`)
    widened by the other targets the pasted line then needs (:func:`designing_paste`), so
    that pasting it designs; an offer no widening makes design is left as it was.

    Args:
        alternatives: the refusal's offers (``option``, ``words``).
        args: the options asked.

    Returns:
        The offers, in the same order.
    """
    out = []
    for a in alternatives:
        option = a.get("option") or ""
        flags = {f for f, _ in option_pairs(shlex.split(option))}
        if not flags & set(PASTE_CHECKED):
            out.append(a)
            continue
        mended = designing_paste(args, option)
        if mended is None or mended == option:
            out.append(a)
            continue
        added = [f for f, _ in option_pairs(shlex.split(mended))
                 if f not in flags and f != "--construction"]
        words = a.get("words") or ""
        out.append({**a, "option": mended,
                    "words": f"{words}; with the {' and '.join(added)} the pasted line then "
                             f"needs (judged as it runs: it designs)"})
    return out


def run_jaw(args: argparse.Namespace, targets) -> int:
    """``design --jaw``: :func:`searched_jaw`, a refusal's offers widened so that each
    designs when pasted (:func:`designing_alternatives`)."""
    try:
        return searched_jaw(args, targets)
    except DesignError as exc:
        if getattr(args, "pasted_check", False) or not exc.alternatives:
            raise
        exc.alternatives = designing_alternatives(exc.alternatives, args)
        raise


def searched_jaw(args: argparse.Namespace, targets) -> int:
    """``design --jaw``: every construction that seats in the jaw searched; the design of
    the one that counts (written with its scenes), or every binding limit."""
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.atomic import write_bytes_atomic
    from tactcad.design.project import COMPANIONS
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.project_folder import (check_project_target, scenes_without_rigs_text,
                                        write_project)

    refuse_options_a_jaw_sets(args)
    chosen, left = jaw_constructions(args)
    room = jaw_room(*jaw_of(args.jaw))  # the inputs first: a bad jaw file before the folder
    folder = None if args.out.endswith(".toml") else check_project_folder(args.out)
    path = check_output_path(args.out, args.force) if folder is None else \
        folder / f"{folder.name.replace('-', '_') or 'grasper_insert'}.toml"
    check_design_name(args.out, folder, path)
    if folder is not None:  # an existing project is refused now, not after the search
        # an array in the jaw writes its scenes (a die does not: refused the safer way)
        check_project_target(folder, path.name, args.force,
                             companions=[COMPANIONS["scenes"]] if chosen else [])
    name = path.stem.replace("-", "_") or "grasper_insert"
    from tactcad.design.array_plan import EXAMPLES, read_toml

    refusals, result, used = [], None, None
    misfits = []  # (product, its misfits): not searched, each dimension that binds said
    for c in chosen:
        base = read_toml(EXAMPLES / c.jaw_template, "design file")
        screen = c.jaw_screen()  # asked by name too: a product the jaw cannot hold is said so
        missed = screen(room, args.columns or 6, base, targets, args.material,
                        args.process) if screen else []
        if args.construction != "auto":  # asked by name: what no column count mends; the
            from tactcad.studies.comb_design import COLUMN_FREE_MISFITS  # search says the rest

            missed = [m for m in missed if m.get("words", "").startswith(COLUMN_FREE_MISFITS)]
        if missed:
            misfits.append((c.name, missed + _other_classes_holding(c, args, base, targets)))
            continue
        try:
            result = c.jaw_search()(targets, room, args.columns or 6, base, grade=args.material,
                                    name=name, envelope_of=array_envelope_mm,
                                    other_rooms={k: jaw_room(k) for k in jaw_classes()
                                                 if k != args.jaw},
                                    max_grasp_force_N=args.max_grasp_force,
                                    process=args.process)
            used = c.name
            break
        except DesignError as exc:
            refusals.append((c.name, exc))
    die_on = args.construction == DIE_CONSTRUCTION or (
        args.construction == "auto" and not die_ignored(args))
    if result is None and die_on:
        from tactcad.products.silicon_die.design.die_mount import die_misfit
        from tactcad.products.silicon_die.design.mems_die import DEFAULT_COLUMNS

        missed = die_misfit(room, room.table or {}, args.columns or DEFAULT_COLUMNS)
        if missed:
            missed = die_misfits_that_design(missed, targets, room)
            misfits.append(("silicon die", missed))
            die_on = False
    told = refusals + [(n, misfit_words(m)) for n, m in misfits]
    if result is None and die_on and args.construction == DIE_CONSTRUCTION:
        return write_die_design(args, targets, room, path, folder, told, left)
    if result is None and die_on:
        # no metal construction meets the targets in this jaw (its pocket, its height, or a
        # limit): a silicon die lies flat in the pocket, where one meets them; else both
        # refusals stand, each with what binds and what to paste
        try:
            return write_die_design(args, targets, room, path, folder, told, left)
        except DesignError as die_refusal:  # neither designs: each says why, the nearest first
            if die_refusal.field in ("--out", "--max-grasp-force", "--kobj-accuracy"):
                raise  # the die fits the targets: its folder or a requirement is refused
            raise constructions_refusal(
                [(n, n, e) for n, e in refusals] + [(DIE_CONSTRUCTION, "silicon die",
                                                     die_refusal)], args,
                after=[one_refusal_line(n, misfit_words(m)) for n, m in misfits],
                more=misfit_alternatives(misfits)) from None
    if result is None and misfits:  # nothing fits the jaw: each product's binding size
        field, value, allowed = misfit_option(misfits, refusals, args)
        ignored = die_ignored(args) if args.construction == "auto" else {}
        # the lab's own jaw kept: the die, where it designs there without a metal's options
        die_paste = die_without_metal_options(args, targets, room) \
            if ignored and field == "--jaw" else None
        fits = misfit_alternatives(misfits)  # the jaw file's keys before another jaw
        own = [a for a in fits if not a["option"].startswith("--jaw ")]
        pasted = [*own, *([die_paste] if die_paste else []), *(a for a in fits if a not in own),
                  *(a for _, e in refusals for a in e.alternatives)]
        untried = [untried_die_line(ignored, die_paste is not None)] if ignored else []
        raise DesignError(
            field, value, allowed or "a jaw that holds " + " or ".join(
                ["a " + n for n, _ in misfits] + [n for n, _ in refusals]),
            "each against this jaw:\n  " + "\n  ".join(
                [one_refusal_line(n, misfit_words(m)) for n, m in misfits]
                + [one_refusal_line(n, e) for n, e in refusals] + untried
                + ([] if pasted else ["none to paste: no option or jaw file key "
                                      "makes one of them fit this jaw"])),
            alternatives=pasted, limit=misfit_limit(misfits, refusals))
    if result is None:
        if len(refusals) == 1:
            raise refusals[0][1]
        if refusals:
            raise constructions_refusal([(n, n, e) for n, e in refusals], args)
        raise DesignError("--jaw", args.jaw, "a jaw some construction fits",
                          "no construction seats in a jaw")
    if args.kobj_accuracy is not None:
        result = first_accurate_design(
            jaw_designs_in_preference(result, targets, room, args, name), args.kobj_accuracy)
    warn_coarse_reading(result.plan)
    data = dict(result.data)
    data["grasper_jaw"] = dict(room.table or {})  # the jaw it was designed for, in its scenes
    from tactcad.version import VERSION

    header = (f"# Written by tactcad {VERSION}: "
              f"`tactcad design {' '.join(design_options(args))}`.\n"
              f"# Units: mm, N, MPa. Reasons for the chosen values are under [assumptions].\n\n")
    grid = f"{result.plan.rows} x {result.plan.columns}"
    scenes = scenes_without_rigs_text(name, grid)
    if folder is not None:  # a project folder, as `tactcad new` makes (its [files] table added)
        write_project(folder, design_text(header, data), path.name, result.plan,
                      companions={"scenes": scenes}, force=args.force, option="--out")
    else:
        scenes_path = path.parent / f"{path.stem}-scenes.toml"
        data["files"] = {"scenes": scenes_path.name}
        if scenes_path.exists() and not args.force:
            raise DesignError("--out", str(scenes_path), "a path with no file (or --force)",
                              "the design's scenes file would be overwritten")
        # the scenes first, the design last: a set cut short has no design file
        write_bytes_atomic(scenes_path, scenes.encode("utf-8"))
        write_bytes_atomic(path, design_text(header, data).encode("utf-8"))
    report = jaw_report(result, used, left, path)
    if args.json:
        print(json.dumps(report, indent=2, allow_nan=False))
    else:
        print_jaw_report(report)
    return 0


def shown_path(path: str) -> str:
    """``path`` as a user reads it: relative to the working folder when inside it (the JSON
    report keeps it whole)."""
    try:
        return os.path.relpath(path) if Path(path).resolve().is_relative_to(Path.cwd()) else path
    except (OSError, ValueError):
        return path


def check_design_name(out: str, folder: Path | None, path: Path) -> None:
    """Refuse, before any search, an ``--out`` whose file or folder name is no design name
    (:func:`tactcad.project_folder.refuse_no_design_name`, the rule ``tactcad new`` keeps).

    Args:
        out: ``--out`` as given.
        folder: the project folder asked for, or None for a design file.
        path: the design file to write.

    Raises:
        DesignError: naming ``--out``, its value, the names allowed and one to paste.
    """
    from tactcad.project_folder import refuse_no_design_name

    refuse_no_design_name("--out", out, folder.name if folder is not None else path.name)


def jaw_report(result, construction: str, left: list[str], path: Path) -> dict:
    """What ``design --jaw`` found: the room, the chosen design, every candidate, the checks
    that run without the CAD kernel on the written design (each group's
    :func:`check_group_summary`)."""
    from tactcad.design.project import load_project
    from tactcad.checks.groups import CheckContext, groups_to_run, run_groups

    project = load_project(path)
    groups = [g for g in groups_to_run() if not g.on_export]
    checks = {}

    def done(label: str, results: list) -> None:
        checks[label] = check_group_summary(results)

    # the closed form alone: a search reports in seconds, verify climbs the ladder after
    run_groups(groups, CheckContext(project.plan, path.parent, None, project,
                                    requirements_model="closed-form"), done)
    d, room = rounded_lengths(dict(result.data)), result.room  # as the file has them
    processes = row_process_verdicts(project.plan)
    return {
        "out": str(path), "construction": construction, "left_out": left,
        "jaw": {"jaw": room.label, "shaft_class_mm": room.shaft_class_mm,  # to 1 µm
                "pocket_across_mm": round(room.across_mm, 6),
                "pocket_along_mm": round(room.along_mm, 6), "height_mm": round(room.height_mm, 6)},
        "sheet_mm": d["sheet"]["thickness_mm"], "pitch_mm": d["array"]["pitch_mm"],
        **distinct_elements_lengths(d),
        "candidates": [{"sheet_mm": c.sheet_mm, "km_scale": c.km_scale,
                        "counts": c.plan is not None and not c.failures,
                        "force_margin_rel": None if math.isinf(c.force_margin_rel) else c.force_margin_rel,
                        "binding": list(c.failures[:1])} for c in result.candidates],
        "fasteners": [{"screw_size": f.screw_size, "dowel_diameter_mm": f.dowel_diameter_mm,
                       "counts": not f.failures, "binding": list(f.failures[:1])}
                      for f in result.fasteners],
        "processes": processes, "checks": checks,
        # the largest force the search designs at, as a refusal offers it (a comb's)
        "max_full_scale_force_N": getattr(result, "max_full_scale_force_N", None)}


def comb_largest_force_line(force_N: float) -> str:
    """A jaw design's largest feasible full-scale force as its text says it (the stacked
    design's words, :func:`largest_force_line`).

    Args:
        force_N: the search's frontier (N; :func:`tactcad.studies.comb_design.frontier_of`).

    Returns:
        The line.
    """
    from tactcad.studies.comb_design import FRONTIER_TOLERANCE_REL

    return (f"largest feasible full-scale force for these stiffness targets: {force_N:g} N "
            f"in this jaw (the search's frontier to {100 * FRONTIER_TOLERANCE_REL:g} %, "
            f"rounded down to three digits; to paste: --full-scale-force {force_N:g})")


def check_group_summary(results: list) -> dict:
    """One check group's results as ``check`` counts them: an undecided result (a requirement
    whose margin lies inside its error estimate) is no pass and no failure.

    Args:
        results: the group's :class:`~tactcad.checks.check_result.CheckResult`.

    Returns:
        ``passed`` and ``info`` (how many passed, how many were reported, not judged),
        ``undecided`` and ``failed`` (each one's line, as ``check`` prints it).
    """
    from tactcad.checks.check_result import status_of

    found = [(status_of(r), r.line()) for r in results]
    return {"passed": sum(status == "pass" for status, _ in found),
            "info": sum(status == "info" for status, _ in found),
            "undecided": [line for status, line in found if status == "undecided"],
            "failed": [line for status, line in found if status == "fail"]}


def row_process_verdicts(plan) -> dict[str, list[str]]:
    """Each cut process (:data:`tactcad.vocabulary.process.CUT_PROCESSES`) against the
    written comb's row sheets: the rules it breaks (``process`` check group's lines; empty
    when it cuts them). A flexure's web, far thinner than its sheet, is what wire EDM cuts
    and etching and laser cutting (min web about the sheet's thickness) do not."""
    from dataclasses import replace

    from tactcad.checks.process_rules import part_rule_checks
    from tactcad.export.dxf_sheet import shop_profiles
    from tactcad.partlib.array.comb_sheet import CombSheet
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.vocabulary.process import process_names

    specs = array_parts(plan, ("comb_sheet",))
    rows = [sp for sp in shop_profiles(plan)
            if sp.part in specs and isinstance(specs[sp.part].geometry, CombSheet)]
    return {name: [r.detail for sp in rows for r in part_rule_checks(replace(sp, process=name))
                   if not r.passed] for name in process_names()}


def counted_words(counted: int) -> str:
    """How many of a jaw's candidates count, as a clause: ``2 of them count``, ``1 of them
    counts``, ``none of them counts``."""
    if counted == 0:
        return "none of them counts"
    return f"{counted} of them count" + ("s" if counted == 1 else "")


def print_jaw_report(r: dict) -> None:
    from tactcad.checks.check_result import counts_text

    j = r["jaw"]
    print(f"{shown_path(r['out'])}: {r['construction']} for the {j['jaw']} (pocket "
          f"{j['pocket_across_mm']:g} x {j['pocket_along_mm']:g} mm, {j['height_mm']:g} mm high)")
    for line in r["left_out"]:
        print(f"  not searched: {line}")
    print(f"  sheet {r['sheet_mm']:g} mm, pitch {r['pitch_mm']:g} mm, arms "
          f"{', '.join(f'{a:g}' for a in r['arms_mm'])} mm, webs "
          f"{', '.join(f'{w:g}' for w in r['webs_mm'])} mm, stop gaps "
          f"{', '.join(f'{g:g}' for g in r['stop_gaps_mm'])} mm")
    counted = sum(c["counts"] for c in r["candidates"])
    print(f"  {len(r['candidates'])} candidates, {counted_words(counted)}")
    if r["fasteners"]:
        got, before = r["fasteners"][-1], r["fasteners"][:-1]
        print(f"  fasteners: {got['screw_size']} screws, {got['dowel_diameter_mm']:g} mm dowels"
              + (f" ({len(before)} larger pairs tried first; the first binds on "
                 f"{before[0]['binding'][0]})" if before else " (the largest)"))
    for name, broken in r["processes"].items():
        # a rule's line without its process (the line's head) and its figure and source
        first = broken[0].split("; rule:")[0].removeprefix(f"{name}: ") if broken else ""
        print(f"  rows by {name}: " + ("its rules hold" if not broken else
                                       f"{len(broken)} rules broken (first: {first})"))
    if r.get("max_full_scale_force_N") is not None:
        print("  " + comb_largest_force_line(r["max_full_scale_force_N"]))
    for label, c in r["checks"].items():
        print(f"  check {label}: " + counts_text({"passed": c["passed"],
                                                  "undecided": len(c["undecided"]),
                                                  "failed": len(c["failed"]),
                                                  "info": c.get("info", 0)}))
        for line in c["failed"] + c["undecided"]:  # as check prints them
            print(f"    {line}")


def tissue_of(args: argparse.Namespace):
    """The tissue model the options ask for (:class:`tactcad.in_use.tissue_coupling.Tissue`)."""
    from tactcad.in_use.tissue_coupling import Tissue

    return Tissue(poisson_ratio=args.tissue_poisson, thickness_mm=args.tissue_thickness)


def coupling_summary(result, args: argparse.Namespace) -> dict:
    """The coupling figures of the written design (per unit κ and eq. 3's K_obj bias, before and
    after the coupled correction), with the model used or eq. 2's choice."""
    from tactcad.in_use.tissue_coupling import coupling_report
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element
    from tactcad.studies.inverse_design import report_points, sensing_unit_numbers

    plan = result.plan
    rep = coupling_report(plan, ladder_stiffness_by_element(plan), sensing_unit_numbers(plan),
                          report_points(result.targets), tissue_of(args))
    return {"mode": args.tissue_coupling,
            "kobj_seen_factor": result.coupling_seen_factor,
            "centred_on_factor": result.targets.kobj_seen_factor,
            "assumption": result.data.get("assumptions", {}).get("requirements.kobj_range_N_per_mm"),
            **rep}


#: Design fields the command's options write (the option named in their errors).
OPTION_FIELDS = {"array.rows": "--rows", "array.columns": "--columns", "array.pitch_mm": "--pitch",
                 "material.grade": "--material", "material.name": "--material",
                 "design.name": "--out", "requirements.footprint_mm": "--footprint",
                 "requirements.kr_over_km": "--kr-over-km",
                 "requirements.kobj_range_N_per_mm": "--kobj-range",
                 "requirements.full_scale_force_N": "--full-scale-force",
                 "requirements.max_grasp_force_N": "--max-grasp-force",
                 "requirements.kobj_accuracy_rel": "--kobj-accuracy"}


def set_keys(args: argparse.Namespace) -> dict[str, Any]:
    """The ``--set`` overrides, by key."""
    from tactcad.commands import parse_overrides

    keys = parse_overrides(getattr(args, "overrides", None))
    if getattr(args, "process", None) is not None:  # --process NAME is element.process=NAME
        keys["element.process"] = args.process
    return keys


def fixed_fields(args: argparse.Namespace) -> set[str]:
    """The free layout's fields the user fixed: by ``--set`` or ``--pitch``."""
    from tactcad.studies.layout_search import FREE_FIELDS

    fixed = set(set_keys(args)) & set(FREE_FIELDS)
    if args.pitch is not None:
        fixed.add("array.pitch_mm")
    return fixed


def base_design(out: Path | None) -> Path:
    """The design a search without ``--design`` starts from, named on stderr: the working
    folder's design, or the shipped example where the folder has none, its design is
    ``out``, the file this run replaces (``--force``), or another product's (a die's).
    A folder's design is picked as every command picks it (docs/reference/cli.md), so the
    same command gives other hardware in another folder: the line says which ``--design``
    gives either answer in any folder (:func:`shipped_or_file` reads an example's name)."""
    from tactcad.commands.notices import announce
    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.project_folder import default_design, product_of, unreadable_tomls

    shipped = DEFAULT_DESIGN.stem
    # a design needs no file of the folder: an unreadable *.toml is passed over, named
    found = default_design(refuse_unreadable=False)  # the folder scanned once
    if found != DEFAULT_DESIGN and out is not None and found.resolve() == out.resolve():
        announce(f"design: starts from the shipped example {shipped}, not "
                 f"{found.name}, the file this run replaces; --design names a base")
        return DEFAULT_DESIGN
    if found != DEFAULT_DESIGN and not product_of(found).is_default:
        # a die's design has no stack to search: the array starts from the shipped one
        announce(f"design: starts from the shipped example {shipped}, not "
                 f"{found.name}, this folder's {product_of(found).name} design (a stacked "
                 "array is not made from it); --design names a base")
        return DEFAULT_DESIGN
    if found != DEFAULT_DESIGN:
        announce(f"design: starts from {found.name}, this folder's design, picked because no "
                 f"--design was given: the same command in another folder starts from another "
                 f"base and gives other hardware; --design {shlex.quote(found.name)} keeps this "
                 f"base, --design {shipped} starts from the shipped example (the base of a "
                 f"folder with no design file), in any folder")
        return found
    announce(f"design: starts from the shipped example {shipped} (the paper's 2 x 5 array): "
             f"no design file in this folder and no --design; a folder holding a design file "
             f"starts from that one, --design {shipped} from this one in any folder; "
             f"`tactcad new NAME` makes a project of your own")
    passed = unreadable_tomls(Path("."))
    if passed:
        announce("design: passed over " + ", ".join(
            f"{Path(str(e.value)).name} (not {e.allowed}: {e.why})" for e in passed)
            + ", no design file can be read from them; --design FILE names a base")
    return DEFAULT_DESIGN


def base_comment(label: str, named: bool, shipped: bool) -> str:
    """The written file's header line naming its base design (``label``, :func:`base_label`)
    and, where no ``--design`` named it, how the folder picked it.

    Args:
        label: the words naming the base. named: ``--design`` named it. shipped: it is a
            shipped example.

    Returns:
        The comment line, newline included.
    """
    if named:
        how = "named by --design"
    elif shipped:
        how = "picked without --design, the working folder holding no other array design"
    else:
        how = "picked without --design, the working folder's design file"
    return f"# Base design: {label}, {how}.\n"


def shipped_or_file(given: str) -> Path:
    """The base design ``--design`` names: the file (or folder's design) given, else, where
    no such file is, the shipped example of that name (``--design macro_array``), so a base
    is named the same way in any folder.

    Args:
        given: ``--design``'s value.

    Returns:
        The design file's path (not checked to exist: reading it names a missing file).
    """
    from tactcad.project_folder import examples

    path = Path(given)
    if path.exists():
        return path
    return examples().get(given, path)


def base_label(design: Path) -> str:
    """The base design as the written file names it: the shipped default example as such
    ("the shipped default example": a lab's design file never names the paper's design,
    :func:`tactcad.studies.inverse_design.neutral_assumptions`), another shipped example by
    its name ("ti_array_2x3, the shipped example"), any other by its file's name
    ("paste264.toml").

    Args:
        design: the base design file.

    Returns:
        The words naming it.
    """
    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.project_folder import examples

    if design.resolve() == DEFAULT_DESIGN.resolve():
        return "the shipped default example"
    for name, path in examples().items():
        if path.resolve() == design.resolve():
            return f"{name}, the shipped example"
    return design.name


def start_from_args(args: argparse.Namespace, name: str, out: Path | None = None
                    ) -> tuple[dict, Path]:
    """The raw tables the search starts from: the base design (``--design``,
    else the working folder's or the shipped one; never ``out``, the file the run
    replaces, whose last search would otherwise start this one) with every ``--set``, the
    grade, grid and pitch asked for, and the new design's name. Its values are
    checked field by field (types and ranges); the rules between fields are
    left to the search, which may change the layout that breaks them.

    Raises:
        DesignError: a value out of its range, named as the user wrote it (the
            ``--set`` key or the option) or, for the base file's own, with the file.
    """
    from tactcad.design.array_plan import read_toml, validate_design, with_overrides
    from tactcad.errors import DesignErrors
    from tactcad.commands import announced_default_design
    from tactcad.studies.inverse_design import start_tables

    def check(tables):
        model, problems = validate_design(tables, design.name)
        if model is None and problems.errors:
            # the user's own values first: a wrong --rows also breaks the arms list made for it
            own = [e for e in problems.errors if written_by_user(e.field, args)]
            raise as_options(DesignErrors(own or problems.errors), args, design)
        return model

    design = shipped_or_file(args.design) if args.design else base_design(out)
    raw = with_overrides(read_toml(design, "design file"), set_keys(args))
    refuse_another_products_base(raw, design)
    base = check(raw)  # the base's own tables first: the start is made from them
    from tactcad.design.construction_registry import DEFAULT_CONSTRUCTION, construction_name

    construction = construction_name(raw)
    if construction != DEFAULT_CONSTRUCTION:  # the layout search varies the stack's bolts
        raise DesignError("--design", str(design), "a stacked design as the base of the "
                          "layout search",
                          f"it is a {construction} design: a comb is designed to a jaw with "
                          f"--jaw 5, 10 or a file whose [grasper_jaw] table is the jaw (this "
                          f"design's own: --jaw {shlex.quote(str(design))})")
    data = start_tables(raw, base.design.name, grade=args.material, pitch_mm=args.pitch,
                        rows=args.rows, columns=args.columns, kept=frozenset(set_keys(args)))
    data["design"] = {**data["design"], "name": name}
    check(data)
    return data, design


def refuse_another_products_base(tables: dict, design: Path) -> None:
    """Refuse, in one line, a base design file of another product (a silicon die's, read
    as an array's, listed every array table as missing).

    Raises:
        DesignError: ``--design`` is another product's design file, or a jaw file.
    """
    from tactcad.design.file_kind import refuse_jaw_file
    from tactcad.products import products

    refuse_jaw_file(tables, design, "--design")
    other = next((p for p in products() if not p.is_default and p.owns(tables)), None)
    if other is not None:
        raise DesignError("--design", str(design), "a stacked design as the base of the "
                          "layout search", f"it is a {other.name}'s design "
                          f"([{other.design_table}]): a die is designed to a jaw with --jaw 5 "
                          "or a jaw file")


def written_by_user(field: str, args: argparse.Namespace) -> bool:
    """True when the user wrote ``field``: by an option, or by a ``--set`` of it,
    of a key inside it (a section) or of the list it indexes."""
    return field in OPTION_FIELDS or _set_key_of(field, args) is not None


def _set_key_of(field: str, args: argparse.Namespace) -> str | None:
    """The ``--set`` key that wrote ``field``, or None."""
    for key in set_keys(args):
        if field == key or key.startswith(field + ".") or field.startswith(key + "["):
            return key
    return None


def as_options(exc: DesignError, args: argparse.Namespace, design: Path) -> DesignError:
    """``exc`` with each error named as the user wrote it: a field an option
    writes by the option, a ``--set`` key as ``--set``; the base file's own
    fields keep the file. The alternatives are kept."""
    from tactcad.errors import DesignError as Error, DesignErrors

    errors = getattr(exc, "errors", None) or (exc,)

    def renamed(e):
        if _set_key_of(e.field, args) is not None:
            return Error(e.field, e.value, e.allowed, e.why, "--set", e.alternatives)
        option = OPTION_FIELDS.get(e.field)
        if option is not None:
            return Error(option, e.value, e.allowed, e.why, "", e.alternatives)
        return e

    if not any(renamed(e) is not e for e in errors):
        return exc
    if hasattr(exc, "message") and len(errors) > 1:  # a refusal: its own words, fields renamed
        exc.errors = tuple(renamed(e) for e in errors)
        return exc
    out = DesignErrors([renamed(e) for e in errors], exc.alternatives, what="the options")
    return out


def project_check(path: Path):
    """raw tables -> the project that would be written at ``path``, validated
    with the rigs and scenes made for it (:func:`tactcad.project_folder.companion_tables`)
    and its cut parts held to their processes' rules (the ``process`` check group's,
    :func:`tactcad.checks.process_rules.process_rule_errors`); raises
    :class:`DesignError` where the written design would be refused or fail that check."""
    from tactcad.checks.process_rules import process_rule_errors
    from tactcad.design.project import project_with_design_data
    from tactcad.project_folder import companion_tables

    def check(data):
        project = project_with_design_data(copy.deepcopy(dict(data)), path,
                                           companions=companion_tables)
        broken = process_rule_errors(project.plan) or failed_requirements(project.plan)
        if broken:
            raise DesignErrors(broken, what="the design's own checks")
        return project
    return check


def _figure(value) -> str:
    return f"{value:.4g}" if isinstance(value, float) else str(value)


def failed_requirements(plan) -> list[DesignError]:
    """Each requirement the closed form fails on ``plan`` by more than its error estimate
    (:func:`design_margins`), as a refusal naming ``requirements.<name>``: a design that
    would fail its own ``check`` is not written."""
    return [RequirementFailure(f"requirements.{m['requirement']}", m["target"],
                        f"a target the design meets (predicted {_figure(m['predicted'])}, margin "
                        f"{100 * m['margin_rel']:+.1f} % beyond the closed form's error "
                        f"{100 * (m['error_estimate_rel'] or 0):.2f} %)",
                        "the base design's requirement, which this design fails at the closed "
                        "form: loosen it with --set or change the targets")
            for m in design_margins(plan)
            if m["verdict"] == "fail"]


def design_options(args: argparse.Namespace) -> list[str]:
    """The command line that made the design (for its header), every option
    as typed so that running it again makes the same file: the targets, the
    grid, grade, pitch and footprint where given, the jaw and construction,
    the tissue options that differ from their defaults, the base design, every
    ``--set``, the verification level and ``--out`` (not ``--force``: run again, it
    refuses to overwrite)."""
    words = [f"--kr-over-km {args.kr_over_km:g}",
             f"--kobj-range {args.kobj_range[0]:g} {args.kobj_range[1]:g}",
             f"--full-scale-force {args.full_scale_force:g}"]
    if getattr(args, "footprint", None) is not None:
        words.append(f"--footprint {args.footprint[0]:g} {args.footprint[1]:g}")
    if getattr(args, "process", None) is not None:
        words.append(f"--process {args.process}")
    for flag, value in (("--material", args.material), ("--rows", args.rows),
                        ("--columns", args.columns), ("--pitch", args.pitch)):
        if value is not None:
            words.append(f"{flag} {value:g}" if isinstance(value, float) else f"{flag} {value}")
    if getattr(args, "jaw", None) is not None:
        words.append(f"--jaw {shlex.quote(args.jaw)}")
    if getattr(args, "max_grasp_force", None) is not None:
        words.append(f"--max-grasp-force {args.max_grasp_force:g}")
    if getattr(args, "kobj_accuracy", None) is not None:
        words.append(f"--kobj-accuracy {args.kobj_accuracy:g}")
    if getattr(args, "construction", "auto") != "auto":
        words.append(f"--construction {args.construction}")
    if getattr(args, "tissue_coupling", "on") == "off":
        words.append("--tissue-coupling off")
    else:
        if getattr(args, "tissue_poisson", 0.5) != 0.5:
            words.append(f"--tissue-poisson {args.tissue_poisson:g}")
        if getattr(args, "tissue_thickness", None) is not None:
            words.append(f"--tissue-thickness {args.tissue_thickness:g}")
    if getattr(args, "design", None):
        words.append(f"--design {shlex.quote(args.design)}")
    words += [f"--set {shlex.quote(item)}" for item in getattr(args, "overrides", None) or ()]
    verify = getattr(args, "verify", None)
    if verify is not None and verify != DEFAULT_VERIFY:
        words.append(f"--verify {verify}")
    words.append(f"--out {shlex.quote(args.out)}")
    return words  # no --force: the header's command, run again, refuses to overwrite


def design_verification(plan, asked: str, margins: list[dict], progress=None
                        ) -> tuple[str | None, list[dict]]:
    """The written design's verification as ``tactcad verify --model <asked>`` makes it:
    (the level it ended at, its records), (None, []) for ``none``.

    ``auto``: the closed form's records (``margins``, :func:`design_margins`) when they
    decide every requirement, else :func:`tactcad.studies.verification.verification_auto`
    (each record at the level that decided it); a ladder level: the matrix at that level.
    Solves at the ladder's top go side by side and into the store, so ``verify`` after
    ``design`` reads them back."""
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.strength_studies import element_stress
    from tactcad.studies.verification import (prefetch_top_level, verification_auto,
                                                verification_matrix)

    if asked == "none":
        return None, []
    if asked == "auto" and all(m["verdict"] != "undecided" for m in margins):
        return "closed-form", margins
    envelope = array_envelope_mm(plan)
    if asked == "auto":
        records, levels = verification_auto(plan, progress, stress=element_stress,
                                            envelope_mm=envelope)
        return levels[-1]["model"], records
    prefetch_top_level(plan, asked, progress, peak_stress=True)
    return asked, verification_matrix(plan, asked, progress, stress=element_stress,
                                      envelope_mm=envelope)


def distinct_elements_lengths(d: dict) -> dict[str, list[float]]:
    """A comb's distinct elements in element order, as three lists paired by position:
    ``arms_mm``, ``webs_mm``, ``stop_gaps_mm`` (mm; the i-th of each is one kind of
    element's), so a report line reads each arm with its own web and stop gap.

    Args:
        d: the comb's tables (``[arms] lengths_mm``, ``[comb] web_thicknesses_mm`` and
            ``stop_gaps_mm``, one value per element).
    """
    kinds = list(dict.fromkeys(zip(d["arms"]["lengths_mm"], d["comb"]["web_thicknesses_mm"],
                                   d["comb"]["stop_gaps_mm"])))
    return {"arms_mm": [k[0] for k in kinds], "webs_mm": [k[1] for k in kinds],
            "stop_gaps_mm": [k[2] for k in kinds]}


def verification_summary(asked: str, level: str | None, records: list[dict]) -> dict:
    """The report's ``verify`` record: what was asked, the level reached, whether the matrix
    passed (no requirement fails; an undecided one does not fail it) and each requirement's
    verdict with its margin and the level that decided it."""
    from tactcad.studies.verification import matrix_passed

    return {"asked": asked, "level": level, "passed": matrix_passed(records),
            "requirements": [{"requirement": r["requirement"], "verdict": r["verdict"],
                              "margin_rel": r.get("margin_rel"),
                              "decided_by": r.get("decided_by", r.get("model", level)),
                              "target": r.get("target"), "predicted": r.get("predicted"),
                              "error_estimate_rel": r.get("error_estimate_rel"),
                              **({"informational": True} if r.get("informational") else {})}
                             for r in records],
            "notes": list(dict.fromkeys(r["note"] for r in records if r.get("note")))}


def design_report(result, verify: str, progress=None, margins: list[dict] | None = None) -> dict:
    """Figures of an :class:`~tactcad.studies.inverse_design.InverseDesign`: K per
    element (closed form and ``verify`` level; none at ``none`` or ``closed-form``), strength
    at full scale, and R, dR/dK_obj and the K_obj resolution over the K_obj range.
    ``progress`` gets a line per FEM mesh level of the verification; ``margins`` are
    :func:`design_margins` of the design when already formed."""
    import math

    from tactcad.studies.inverse_design import WEB_RULE, report_points, unit_resolution
    from tactcad.mechanics.ladder import estimate
    from tactcad.mechanics.readout_chain import element_force_resolution_N
    from tactcad.studies.reference_loads import strength_summary

    plan, t = result.plan, result.targets
    strength = {r["element"]: r for r in strength_summary(plan)}
    if verify != "none" and is_meshed(verify):  # one core per element, read back below
        from tactcad.studies.parallel_solves import solve_side_by_side

        solve_side_by_side(verify, list(plan.distinct_elements.values()), plan.material,
                           progress)
    cache: dict[str, dict] = {}
    elements = []
    for slot in plan.slots:
        g = slot.geometry
        if g.part_name not in cache:
            cf = estimate("closed-form", g, plan.material)
            levels = {"progress": progress} if progress and is_meshed(verify) else {}
            ver = None if verify in ("none", "closed-form") else \
                estimate(verify, g, plan.material, **levels)
            cache[g.part_name] = {
                "K_closed_form_N_per_mm": cf.stiffness_N_per_mm,
                "K_verified_N_per_mm": None if ver is None else ver.stiffness_N_per_mm,
                "verify_error_estimate_rel": None if ver is None else ver.error_estimate_rel,
                "closed_form_vs_verified_rel": None if ver is None else
                cf.stiffness_N_per_mm / ver.stiffness_N_per_mm - 1.0}
        s = strength[slot.number]
        role = "reference" if slot.number in result.references else "measuring"
        elements.append({"element": slot.number, "role": role, "part": g.part_name,
                         "arm_length_mm": g.arm_length_mm,
                         "K_target_N_per_mm": t.k_r if role == "reference" else t.k_m,
                         **cache[g.part_name], "verify_model": verify,
                         "yield_limited_force_N": s["yield_limited_force_N"],
                         "yield_safety_factor_at_target_force":
                             s["yield_safety_factor_at_full_scale"] * s["full_scale_force_N"]
                             / t.full_scale_force_N,
                         "gauge_strain_at_target_force":
                             s["gauge_strain_at_full_scale"] * t.full_scale_force_N
                             / s["full_scale_force_N"],
                         "gauge_fatigue_force_N": s["gauge_fatigue_force_N"]})
    ref = next(e for e in elements if e["role"] == "reference")
    meas = next(e for e in elements if e["role"] == "measuring")
    # each force read to the design's own read-out chain's resolution (as readout and verify)
    chain = element_force_resolution_N(plan)
    df_ref, df_meas = chain[ref["part"]]["dF"], chain[meas["part"]]["dF"]
    units = []
    for key in ("K_closed_form_N_per_mm", "K_verified_N_per_mm"):
        if meas[key] is None:
            continue
        res = unit_resolution(meas[key], ref[key], report_points(t), t.full_scale_force_N,
                              df_meas, force_resolution_reference_N=df_ref)
        for i in range(len(res["R"])):
            units.append({"stiffness_from": "closed-form" if key.startswith("K_closed") else verify,
                          **{k: float(v[i]) for k, v in res.items()}})
    g = plan.element(1).geometry
    lo, hi = t.k_obj_range_N_per_mm
    return {"targets": {"kr_over_km": t.kr_over_km, "kobj_range_N_per_mm": [lo, hi],
                        "full_scale_force_N": t.full_scale_force_N,
                        "K_m_N_per_mm": t.k_m, "K_r_N_per_mm": t.k_r},
            "material": plan.material.grade or plan.material.name,
            "web_thickness_mm": g.web_thickness_mm, "web_changed": result.web_changed,
            "notch_radius_mm": g.notch_radius_mm, "notch_radius_changed": result.notch_changed,
            "overall_length_mm": g.overall_length_mm,
            "pitch_mm": plan.pitch_mm, "references": list(result.references),
            "layout_changes": [{"field": f, "base": a, "chosen": b}
                               for f, a, b in result.layout_changes],
            "K_r_over_K_m": {"closed-form": ref["K_closed_form_N_per_mm"]
                             / meas["K_closed_form_N_per_mm"],
                             **({} if ref["K_verified_N_per_mm"] is None else
                                {verify: ref["K_verified_N_per_mm"]
                                 / meas["K_verified_N_per_mm"]})},
            "elements": elements, "units": units,
            "force_resolution_N": {"reference": df_ref, "measuring": df_meas},
            "max_full_scale_force_N": result.max_full_scale_force_N,
            "max_full_scale_force_basis": MAX_FORCE_BASIS,
            "max_full_scale_force_layout": getattr(result, "layout_words", ""),
            "across_layouts_force_N": getattr(result, "across_layouts_force_N", None),
            "across_layouts_layout": getattr(result, "across_layouts_layout", ""),
            "binding_limits": list(result.binding_limits),
            "web_rule": WEB_RULE,
            "margins": design_margins(plan) if margins is None else margins,
            "all_finite": all(math.isfinite(u["K_obj_resolution_N_per_mm"]) for u in units)}


def design_margins(plan, keys: tuple[str, ...] = ()) -> list[dict]:
    """Each requirement's margin against the closed form's error on the written
    design (the level ``verify --model auto`` starts at): requirement, target, predicted,
    margin_rel, error_estimate_rel, verdict and, where undecided, whether climbing the
    ladder can decide it (``level_fixed``: the same at every level, so it cannot). With
    ``auto`` they are the design's verification records, so they carry the target and the
    prediction its report words a failure with."""
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.verification import verification_matrix

    return [{**{k: r[k] for k in ("requirement", "target", "predicted", "margin_rel",
                                  "error_estimate_rel", "verdict", "level_fixed", *keys)},
             **{k: r[k] for k in ("informational", "note") if k in r}}
            for r in verification_matrix(plan, "closed-form",
                                         envelope_mm=array_envelope_mm(plan))]


#: Why design's largest force sits below the force limits `verify` and `strength` quote.
MAX_FORCE_BASIS = ("each gauge limit less the closed form's error on the grid's strain, so "
                   "that the closed form decides it; `verify` and `strength` quote the limits "
                   "themselves, higher by up to that error")


def margin_lines(margins: list[dict]) -> list[str]:
    """The report's words on :func:`design_margins`: one line when every margin
    clears its error, else a line per requirement that does not, saying what decides it;
    then each record's note (the K spread over the web tolerance, not judged)."""
    notes = [f"note: {note}" for note in dict.fromkeys(m["note"] for m in margins
                                                        if m.get("note"))]
    open_ = [m for m in margins if m["verdict"] not in ("pass", "info")]  # info: not judged
    if not open_:
        return ["margins: every requirement passes at the closed form by more than its error "
                "estimate, so `verify --model auto` decides it there", *notes]
    out = []
    for m in open_:
        margin = "n/a" if m["margin_rel"] is None else f"{100 * m['margin_rel']:+.1f} %"
        err = "n/a" if m["error_estimate_rel"] is None else f"{100 * m['error_estimate_rel']:.2f} %"
        then = ("no level decides it anew (the same at every level): the design cannot leave "
                "it more margin" if m["level_fixed"] else
                "`verify --model auto` climbs the ladder to decide it")
        out.append(f"margin: {m['requirement']} {m['verdict']} at the closed form (margin "
                   f"{margin}, error {err}); {then}")
    return out + notes


def verification_lines(v: dict | None) -> list[str]:
    """The report's words on :func:`verification_summary`: how the design was checked, and
    each requirement that was not passed at the closed form or that a FEM level decided."""
    if not v or v["level"] is None:
        return ["verify: none (`tactcad verify` checks the written design)"]
    head = (f"verify: {v['asked']}: " + (
        "the closed form decides every requirement, so no FEM level ran (`--verify fem3d` "
        "checks each element's K at the top of the ladder)" if v["level"] == "closed-form"
        else f"the matrix at {v['level']}" if v["asked"] != "auto"
        else f"the ladder climbed to {v['level']} for what the closed form left undecided"))
    out = [head]
    for q in v["requirements"]:
        if q["verdict"] == "info":  # reported, not judged: no verdict to tell
            continue
        if q["verdict"] != "pass" or q["decided_by"] != "closed-form":
            margin = "" if q["margin_rel"] is None else f" {100 * q['margin_rel']:+.1f} %"
            out.append(f"  {q['requirement']}: {q['verdict'].upper()}{margin} "
                       f"({q['decided_by'] or 'no level decides it'})")
            if q["requirement"] == "kobj_accuracy_rel" and q["verdict"] == "fail":
                out.append("    " + accuracy_words(q.get("target"), q.get("predicted"),
                                                       q.get("error_estimate_rel")))
    out.append("verify: no requirement fails" if v["passed"] else
               "verify: a requirement FAILS: the design is written, and `tactcad verify` "
               "reports the same")
    return out


def print_report(r: dict) -> None:
    t = r["targets"]
    print(f"targets: K_r/K_m = {t['kr_over_km']:g}, K_obj {t['kobj_range_N_per_mm'][0]:g}-"
          f"{t['kobj_range_N_per_mm'][1]:g} N/mm, full-scale force {t['full_scale_force_N']:g} N"
          f" -> K_r {t['K_r_N_per_mm']:.4g}, K_m {t['K_m_N_per_mm']:.4g} N/mm")
    print(f"material {r['material']}, web {r['web_thickness_mm']:g} mm"
          f"{' (changed)' if r['web_changed'] else ' (kept)'}, notch radius "
          f"{r['notch_radius_mm']:g} mm{' (changed)' if r.get('notch_radius_changed') else ''}"
          f", overall length {r['overall_length_mm']:g} mm, pitch "
          f"{r['pitch_mm']:g} mm; references: elements {', '.join(map(str, r['references']))}")
    if r["layout_changes"]:
        print("layout searched, changed from the base design: " + ", ".join(
            f"{c['field']} {c['base']:g} -> {c['chosen']:g}" if isinstance(c["base"], float)
            else f"{c['field']} {c['base']} -> {c['chosen']}" for c in r["layout_changes"]))
    seen = set()
    print(f"{'role':<10} {'elements':<16} {'arm mm':>7} {'target':>8} {'closed form':>12} "
          f"{'verified':>10} {'diff':>7} {'F_yield N':>9} {'SF@F':>5} {'ustrain@F':>9}")
    for e in r["elements"]:
        if e["part"] in seen:
            continue
        seen.add(e["part"])
        same = [x["element"] for x in r["elements"] if x["part"] == e["part"]]
        ver = "n/a" if e["K_verified_N_per_mm"] is None else f"{e['K_verified_N_per_mm']:.4g}"
        diff = "" if e["closed_form_vs_verified_rel"] is None else \
            f"{100 * e['closed_form_vs_verified_rel']:+.1f}%"
        print(f"{e['role']:<10} {','.join(map(str, same)):<16} {e['arm_length_mm']:>7g} "
              f"{e['K_target_N_per_mm']:>8.4g} {e['K_closed_form_N_per_mm']:>12.4g} "
              f"{ver + ' (' + e['verify_model'] + ')':>10} {diff:>7} "
              f"{e['yield_limited_force_N']:>9.3g} "
              f"{e['yield_safety_factor_at_target_force']:>5.2f} "
              f"{1e6 * e['gauge_strain_at_target_force']:>9.0f}")
    df = r["force_resolution_N"]
    print(f"K_obj resolution with the read-out chain's force resolution (reference "
          f"{df['reference']:.3g} N, measuring {df['measuring']:.3g} N; tactcad readout):")
    print("K_obj N/mm      R   dR/dK_obj mm/N   dK_obj N/mm       relative   [K from]")
    for u in r["units"]:
        print(f"{u['K_obj_N_per_mm']:>10.3g} {u['R']:>6.3f} {u['dR_dKobj_per_N_per_mm']:>16.4f} "
              f"{u['K_obj_resolution_N_per_mm']:>17.3g} {100 * u['K_obj_resolution_rel']:>9.2f}%"
              f"   {u['stiffness_from']}")
    c = r.get("tissue_coupling")
    if c:
        # mirrored units tie to round-off: verify's rule names the first in the array's order
        from tactcad.in_use.tissue_coupling import unit_label, worst_unit

        worst = worst_unit(c["units"], lambda u: u["worst_eq3_rel"])
        if c["mode"] == "off":
            head = "eq. 2 alone (--tissue-coupling off)"
        elif "eq. 2's centring" not in (c["assumption"] or ""):
            head = "K_r, K_m centred on the range as the coupled units see it"
        else:
            head = ("every unit's coupled R spans the range; K_r, K_m at eq. 2's centring (x1, "
                    "see [assumptions])")
        eq3 = worst["worst_eq3_rel"]
        print(f"tissue coupling: {head} (K_obj seen x{c['kobj_seen_factor']:.3g}); coupling "
              f"{min(u['coupling'] for u in c['units']):.3f}-{max(u['coupling'] for u in c['units']):.3f}; "
              f"eq. 3's K_obj bias worst "
              + ("unreadable" if eq3 is None else f"{100 * eq3:+.1f} %")
              + f" (unit {unit_label(worst['unit'])}), coupled inversion "
              + corrected_worst_text([u["worst_corrected_rel"] for u in c["units"]]))
    print(f"web rule: {r['web_rule']}")
    for line in margin_lines(r["margins"]):
        print(line)
    for line in verification_lines(r.get("verify")):
        print(line)
    if r.get("rigs") and not r["rigs"]["fits"]:
        print(rigs_misfit_line(r["rigs"]))
    print(largest_force_line(r))
    print(f"wrote {shown_path(r['out'])}")


def largest_force_line(r: dict) -> str:
    """The report's largest feasible full-scale force: across the layouts the search tried,
    the figure its refusal names (``across_layouts_force_N``, a force the search designs at,
    so it designs when pasted), and this design's layout's own estimate (rounded down) where
    another layout carries more.

    Args:
        r: :func:`design_report`'s dict.

    Returns:
        The line.
    """
    from tactcad.vocabulary.rounding import round_down

    own = round_down(r["max_full_scale_force_N"], 4)
    bound = "; ".join(r["binding_limits"]) + f" ({MAX_FORCE_BASIS})"
    across, layout = r.get("across_layouts_force_N"), r.get("max_full_scale_force_layout")
    head = "largest feasible full-scale force for these stiffness targets: "
    if across is None or not layout:  # one layout's design (a footprint): its own figure
        where = f" for this layout ({layout})" if layout else ""
        return f"{head}{own:.4g} N{where}, bound by {bound}"
    if r["across_layouts_layout"] == layout:  # the refusal's figure, not the layout's estimate
        return (f"{head}{across:g} N across the layouts searched, at this design's ({layout}), "
                f"bound by {bound}")
    return (f"{head}{across:g} N across the layouts searched, at {r['across_layouts_layout']} "
            f"(to paste: --full-scale-force {across:g}); this design's layout ({layout}) "
            f"carries {own:.4g} N, bound by {bound}")


def rigs_beside(data: dict, path: Path, out: str) -> dict | None:
    """Whether the rigs file a design written to ``path`` takes (named in its ``[files]``
    table, else the folder's ``rigs.toml``, perhaps another design's) fits it: check's rigs
    group, closed form.

    Args:
        data: the design's tables as written.
        path: the design file to be written (``--out NEW.toml``).
        out: ``--out`` as given (the suggested command names it so).

    Returns:
        None where the folder holds no rigs file for it (rigs are made for it when read);
        else ``file``, ``fits``, ``fail`` (the failing checks' names) and ``next`` (the
        ``tactcad new`` command that makes a project with rigs sized for it).
    """
    from tactcad.design.project import companion_files, project_with_design_data
    from tactcad.project_folder import companion_tables, rigs_misfits
    from tactcad.vocabulary.schema import Problems

    rigs_file = companion_files(path, data, Problems(path.name))["rigs"]
    if rigs_file is None:
        return None
    misfits = rigs_misfits(project_with_design_data(data, path, companions=companion_tables))
    name = shlex.quote(out.removesuffix(".toml"))
    return {"file": shown_path(str(rigs_file)), "fits": not misfits, "fail": misfits,
            "next": f"tactcad new {name} --from-design {shlex.quote(out)}"}


def rigs_misfit_line(rigs: dict) -> str:
    """The report's warning on rigs that do not fit the design (:func:`rigs_beside`)."""
    return (f"warning: rigs: {rigs['file']}, which the design file takes, does not fit it "
            f"({', '.join(rigs['fail'])} fail), so `tactcad check` fails; a project with "
            f"rigs sized for it: {rigs['next']}")


def corrected_worst_text(biases: list) -> str:
    """The coupled inversion's worst bias over the units (%), or "unreadable" where one has
    no answer (its coupled R leaves the range the model spans)."""
    if any(b is None for b in biases):
        return "unreadable for some K_obj"
    return f"{100 * max(abs(b) for b in biases):.1g} %"
