"""``tactcad atlas``: what fits a jaw: every product and material that seats in it judged
over a Sobol sample of targets, on Dask; a Parquet table, the Pareto front and its figure."""

from __future__ import annotations

import argparse
import io
import json
import math
import time
from pathlib import Path
from typing import Any, Mapping

from tactcad.commands import add_cache_args, add_output_args, progress_from_args, store_from_args
from tactcad.commands.design import jaw_classes, jaw_of
from tactcad.commands.options import count, material_grade_name, number, output_folder
from tactcad.commands.tolerance import add_cluster_args
from tactcad.errors import DesignError
from tactcad.stopping import stop_signals_held
from tactcad.studies.atlas_files import (  # noqa: F401  (the command's names)
    ATLAS_RENAMED, FIGURE_NAME, PROJECT_ATLAS_FOLDER, SUMMARY_NAME, TABLE_NAME, point_title,
    read_table, span, write_table)
from tactcad.studies.design_atlas import (  # noqa: F401  (the command's batch rule)
    MAX_AUTO_BATCH, TASKS_PER_WORKER, auto_batch)

#: Range options: option -> (the axis of :data:`tactcad.studies.design_atlas.AXES`, unit, type).
RANGE_OPTIONS = {"--kr-over-km-range": ("kr_over_km", ""),
                 "--kobj-centre": ("kobj_centre_N_per_mm", "N/mm"),
                 "--kobj-span": ("kobj_span", ""),
                 "--force-range": ("full_scale_force_N", "N"),
                 "--columns-range": ("columns", "")}


def register(sub: argparse._SubParsersAction) -> None:
    from tactcad.studies.design_atlas import AXIS_LIMITS, DEFAULT_RANGES

    p = sub.add_parser(
        "atlas", help="what fits a jaw: feasible targets and the Pareto front of every product "
                      "and material, on Dask",
        description="Judges a scrambled Sobol sample of targets (K_r/K_m, the K_obj range's "
                    "centre and span, the rated full-scale force, the columns) for every "
                    "product that seats in the jaw (the monolithic comb in each material of "
                    "the library, the silicon die) as `tactcad design --jaw J --construction "
                    "C` judges it: feasible or not, the limit that binds and the design's "
                    "figures (K_obj resolution, largest force, f1, sheet or device layer). "
                    "Writes atlas.parquet (kept in the store by its inputs, reused by a second "
                    "run), atlas_front.svg and atlas.json (the Pareto front of force, K_obj "
                    "span and K_obj resolution per product and material, each point with the "
                    "design command that writes it). Runs on a new local Dask cluster, or an "
                    "existing one with --scheduler. Units: N, N/mm, mm, Hz.")
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--jaw", metavar="CLASS|FILE",
                       help="the grasper's jaw: a trocar class's default jaw (mm: "
                            + ", ".join(jaw_classes()) + ") or a TOML file with a "
                            "[grasper_jaw] table, as `tactcad design --jaw` takes it")
    where.add_argument("--project", metavar="DESIGN.toml",
                       help="a sensor project's design file (or its folder): the atlas of its jaw (its "
                            "[grasper_jaw] table, or a die's jaw), written in the project's "
                            f"{PROJECT_ATLAS_FOLDER}/ folder, where `tactcad export` finds "
                            "it for the review page")
    p.add_argument("--points", type=count(1, 100_000, "target points"), default=16,
                   metavar="N", help="target points of the Sobol sample (default %(default)s; "
                                     "a comb's point costs a fraction of a CPU second per material)")
    p.add_argument("--seed", type=count(0, 2**32 - 1, "a seed"), default=0,
                   help="seed of the sample's scramble (default %(default)s)")
    p.add_argument("--material", type=material_grade_name, action="append", default=None,
                   metavar="GRADE", help="a comb material judged (repeat for more; default: "
                                         "every grade of the library)")
    for option, (axis, unit) in RANGE_OPTIONS.items():
        lo, hi = DEFAULT_RANGES[axis]
        least, most = AXIS_LIMITS[axis][2]  # the study's own limits, stated once
        # a ratio of 1 is no reference at all: the study asks LO > 1
        p.add_argument(option, type=count(int(least), int(most)) if axis == "columns" else
                       number(least, most, unit, lo_open=axis == "kr_over_km"), nargs=2, metavar=("LO", "HI"),
                       default=None, help=f"range of {axis} sampled (default {lo:g} {hi:g}"
                       + (f" {unit}" if unit else "") + ")")
    p.add_argument("--batch", type=count(1, 10_000, "points per task"), default=None,
                   metavar="N", help="target points per Dask task (default: the points over "
                   f"{TASKS_PER_WORKER} tasks a worker thread, 1 to {MAX_AUTO_BATCH})")
    p.add_argument("--out", metavar="DIR", type=output_folder, default=None,
                   help=f"folder for {TABLE_NAME}, {FIGURE_NAME} and {SUMMARY_NAME} "
                        f"(default: exports/atlas; with --project, the project's "
                        f"{PROJECT_ATLAS_FOLDER}/)")
    add_cache_args(p)
    add_cluster_args(p, local_default=True)
    add_output_args(p, "print the summary as JSON")
    p.set_defaults(func=run)


def ranges_of(args: argparse.Namespace) -> dict[str, tuple[float, float]]:
    """The sampled ranges the options ask for.

    Args:
        args: the parsed options (:data:`RANGE_OPTIONS`).

    Returns:
        axis -> (low, high) of each range option given.
    """
    out = {}
    for option, (axis, _) in RANGE_OPTIONS.items():
        value = getattr(args, option.lstrip("-").replace("-", "_"))
        if value is not None:
            out[axis] = (value[0], value[1])
    return out


from tactcad.studies.comb_design import COLUMN_FREE_MISFITS  # noqa: E402 (re-exported)


def comb_misfits(room, columns: range, base: dict, targets) -> list[dict]:
    """The comb's misfits in the jaw in its height or its width across the rows (sizes its
    columns do not change), at the first column count of ``columns`` whose screen names one
    (:func:`tactcad.studies.comb_design.comb_misfit`; at few columns no sheet's comb has a
    plan and the screen names nothing); empty when none does."""
    from tactcad.studies.comb_design import comb_misfit

    for n in columns:
        missed = [m for m in comb_misfit(room, n, base, targets)
                  if m.get("words", "").startswith(COLUMN_FREE_MISFITS)]
        if missed:
            return missed
    return []


def jaw_atlas(jaw: str, materials: list[str] | None, columns: tuple[int, int]):
    """The :class:`~tactcad.studies.design_atlas.JawAtlas` of ``--jaw``: its room and the
    products that seat in it at some count of ``columns`` (low, high): the comb in each of
    ``materials`` (default every library grade) unless it stands too tall or too wide for
    the pocket (:func:`comb_misfits`), the die unless its smallest build misfits.

    Args:
        jaw: ``--jaw``: a trocar class or a jaw file's path.
        materials: the comb's grades (None: every grade of the library).
        columns: (low, high) of ``--columns-range``.

    Returns:
        The jaw's atlas; its ``left_out`` names each product left out with its misfit in
        words (as ``design --jaw`` says it: "does not fit: height 5.79 mm ...", mm).

    Raises:
        DesignError: ``--jaw`` unreadable, or no product fits it (each one's misfit named).
    """
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.commands.design import misfit_words
    from tactcad.design.array_plan import EXAMPLES, read_toml
    from tactcad.design.construction_registry import construction
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.products.silicon_die.design.die_mount import die_misfit
    from tactcad.studies.design_atlas import COMB, DIE, SILICON, JawAtlas, targets_of
    from tactcad.vocabulary.material_library import material_grades

    room = jaw_room(*jaw_of(jaw))
    comb = construction(COMB)
    base = read_toml(EXAMPLES / comb.jaw_template, "design file")
    nominal = targets_of({"kr_over_km": 10.0, "kobj_lo_N_per_mm": 0.5, "kobj_hi_N_per_mm": 5.0,
                          "full_scale_force_N": 0.1})  # a comb's size does not depend on them
    comb_miss = comb_misfits(room, range(columns[0], columns[1] + 1), base, nominal)
    die_miss = die_misfit(room, room.table or {}, columns[0])
    products = [] if comb_miss else [(COMB, g) for g in (materials or list(material_grades()))]
    products += [] if die_miss else [(DIE, SILICON)]
    if not products:
        words = "; ".join(m["words"] for m in comb_miss + die_miss if m.get("words"))
        raise DesignError("--jaw", jaw, "a jaw that holds a monolithic comb or a silicon die",
                          f"neither fits at {columns[0]} ... {columns[1]} columns: {words}")
    left_out = tuple((product, misfit_words(missed))
                     for product, missed in ((COMB, comb_miss), (DIE, die_miss)) if missed)
    return JawAtlas(jaw, room, None if comb_miss else base, array_envelope_mm, tuple(products),
                    left_out)


def atlas_key(atlas, points: list[dict]) -> str:
    """The store's key of an atlas (:func:`tactcad.store.content_key`).

    Args:
        atlas: the jaw (its room), its products and materials.
        points: every target point (the sample's size, seed and ranges made them).

    Returns:
        The key: those inputs with the tactcad version, the table's schema
        (:data:`~tactcad.studies.atlas_files.ATLAS_SCHEMA`) and the store's code salt. The
        jaw counts by its content (its room and ``[grasper_jaw]`` table), not by the path
        of the file that holds it: the same jaw in another file, or a project's design
        stating it, has the same key (the records' design commands name the jaw of the
        run that reads them: :func:`with_commands`).
    """
    import dataclasses

    from tactcad.store import content_key
    from tactcad.studies.atlas_files import ATLAS_SCHEMA
    from tactcad.version import VERSION

    room = dataclasses.replace(atlas.room, option="")  # the file's path: no part of the jaw
    return content_key("atlas", VERSION, ATLAS_SCHEMA, room, list(atlas.products), points)


def with_commands(records: list[dict], jaw: str) -> list[dict]:
    """Records with each one's design command naming ``jaw``, the jaw of this run: a table
    kept by a run of the same jaw under another path (:func:`atlas_key`) names that path.

    Args:
        records: rows of the atlas table. jaw: ``--jaw`` of this run.

    Returns:
        New rows, their ``command`` that of
        :func:`~tactcad.studies.design_atlas.design_command`.
    """
    from tactcad.studies.design_atlas import design_command

    return [{**r, "command": design_command(jaw, r["product"], r["material"], r)}
            for r in records]


def stored_table(store, key: str) -> Path | None:
    """Where the store keeps an atlas.

    Args:
        store: the :class:`tactcad.store.Store` of the options. key: :func:`atlas_key`.

    Returns:
        The Parquet file's path; None with ``--no-cache``.
    """
    return None if store.root is None else store.root / "atlas" / key[:2] / f"{key}.parquet"


def run(args: argparse.Namespace) -> int:
    """``atlas``: the table (from the store when kept), the front, its figure and summary."""
    from tactcad.studies.design_atlas import atlas_targets, checked_ranges

    if args.project is not None and Path(args.project).is_dir():  # a project folder
        from tactcad.project_folder import design_in_folder

        args.project = str(design_in_folder(args.project, "--project"))
    ranges = ranges_of(args)
    bounds = checked_ranges(ranges)
    points = atlas_targets(args.points, ranges, args.seed)
    jaw, default_out = ((args.jaw, "exports/atlas") if args.project is None
                        else project_jaw(args.project))
    atlas = jaw_atlas(jaw, args.material, (int(bounds["columns"][0]), int(bounds["columns"][1])))
    made = first_missing(args.out or default_out)
    out = writable_folder(args.out or default_out)
    try:
        return atlas_into(out, atlas, points, bounds, jaw, args)
    except BaseException:  # a refusal or a stop after the folder was made: none is left
        remove_empty_made(out, made)
        raise


def first_missing(out: str) -> Path | None:
    """The outermost folder of ``out`` (absolute) that does not exist yet, which the run
    makes; None when ``out`` exists."""
    import os

    folder = Path(os.path.abspath(os.path.expanduser(out)))
    missing = None
    for f in (folder, *folder.parents):
        if f.exists():
            break
        missing = f
    return missing


def remove_empty_made(folder: Path, made: Path | None) -> None:
    """Remove ``folder`` and its parents up to ``made`` (the outermost this run made) while
    they are empty: a run refused after making its ``--out`` leaves nothing behind."""
    if made is None:
        return
    for f in (folder, *folder.parents):
        try:
            f.rmdir()  # only an empty folder goes
        except OSError:
            return
        if f == made:
            return


def atlas_into(out: Path, atlas, points: list[dict], bounds: dict, jaw: str,
               args: argparse.Namespace) -> int:
    """:func:`run`'s work once ``out`` is made: the records judged (or read from the
    store), then the table, the figure and the summary written into ``out``."""
    key = atlas_key(atlas, points)
    kept = stored_table(store_from_args(args), key)
    inputs = {"jaw": jaw, "points": args.points, "seed": args.seed, "ranges": bounds,
              "products": [list(p) for p in atlas.products],
              "left_out": [{"product": p, "misfit": words} for p, words in atlas.left_out],
              "key": key}
    start = time.perf_counter()
    records = read_table(kept) if kept is not None and kept.is_file() else None
    reused, complete, resumed = records is not None, True, 0
    if records is None:
        records, complete, resumed = judged_on_top(atlas, points, args, kept, inputs)
    if reused or resumed:  # kept by a run that may have named the same jaw otherwise
        records = with_commands(records, atlas.jaw)
    seconds = time.perf_counter() - start
    kept_rows = printed_rows = records
    if args.project is not None:
        # the printed commands are pasted where the atlas ran; the project's atlas files
        # (its review page) name paths from the project's own folder
        printed_rows = project_records(records, args.project, jaw)
        kept_rows = project_records(records, args.project, jaw,
                                    Path(args.project).resolve().parent)
    summary = atlas_summary(kept_rows, inputs, seconds, reused, complete, out, resumed)
    printed = (summary if printed_rows is kept_rows else
               atlas_summary(printed_rows, inputs, seconds, reused, complete, out, resumed))
    # the files are one set: a stop while they are written waits for the last of them
    with stop_signals_held(block_in_children=False):
        write_atlas_files(out, kept_rows, summary, {**inputs, "complete": complete}, jaw)
        if args.json:
            print(json.dumps(printed, indent=2, allow_nan=False))
        else:
            print_summary(printed)
    return 0 if complete else 130


def partial_table(kept: Path) -> Path:
    """Where the store keeps a stopped atlas's finished points, beside its whole table."""
    return kept.with_name(kept.name.replace(".parquet", ".partial.parquet"))


def judged_on_top(atlas, points: list[dict], args: argparse.Namespace, kept: Path | None,
                  inputs: dict) -> tuple[list[dict], bool, int]:
    """The points judged, on top of what a stopped run of the same atlas kept.

    A stopped run keeps its finished points in the store (:func:`partial_table`); a run of
    the same inputs judges only the others, and a run stopped again keeps the union, so the
    kept part only grows. Once every point is judged the whole table is kept and the part
    removed.

    Args:
        atlas: the jaw. points: the targets. args: as :func:`judged`.
        kept: the whole table's place in the store (None: ``--no-cache``, nothing kept).
        inputs: the table's metadata.

    Returns:
        (the records in point order, True when every point is judged, the points read from
        the kept part).

    Raises:
        ClusterError: nothing answers at ``--scheduler``.
    """
    from tactcad.studies.design_atlas import ordered

    part = None if kept is None else partial_table(kept)
    earlier = (read_table(part) or []) if part is not None and part.is_file() else []
    wanted = {p["point"] for p in points}
    earlier = [r for r in earlier if r.get("point") in wanted]
    finished = {r["point"] for r in earlier}
    todo = [p for p in points if p["point"] not in finished]
    new, complete = judged(atlas, todo, args) if todo else ([], True)
    records = ordered(earlier + new, atlas) if earlier else new
    if kept is not None:
        # the store's files a stop must not split: the whole table or the grown part
        with stop_signals_held(block_in_children=False):
            if complete:
                write_table(kept, records, inputs, noted=False)
                part.unlink(missing_ok=True)
            elif new:
                write_table(part, records, inputs, noted=False)
    return records, complete, len(finished)


def write_atlas_files(out: Path, records: list[dict], summary: dict, inputs: dict,
                      jaw: str) -> None:
    """The atlas's table, figure and summary written into ``out``, each atomically
    (:mod:`tactcad.atomic`).

    Args:
        out: the ``--out`` folder. records: every verdict. summary: :func:`atlas_summary`.
        inputs: the table's metadata. jaw: ``--jaw``, for the figure's title.
    """
    from tactcad.atomic import write_bytes_atomic

    write_table(out / TABLE_NAME, records, inputs)
    front_figure(records, summary["front"], out / FIGURE_NAME, jaw)
    write_bytes_atomic(out / SUMMARY_NAME,
                       (json.dumps(summary, indent=2, allow_nan=False) + "\n").encode("utf-8"))


def project_records(records: list[dict], design: str, jaw: str,
                    pasted_in: Path | None = None) -> list[dict]:
    """``records`` with each design command writing a new project folder beside the
    project's, its jaw file and that folder named from ``pasted_in``
    (:func:`~tactcad.studies.design_atlas.command_beside_project`).

    Args:
        records: the atlas table's rows. design: ``--project``. jaw: the atlas's ``--jaw``.
        pasted_in: the folder the commands are to be pasted in (None: the working folder,
            where the atlas command runs).

    Returns:
        New rows; the kept table in the store is left as the jaw's.
    """
    from tactcad.studies.design_atlas import command_beside_project

    here = (Path.cwd() if pasted_in is None else pasted_in).resolve()
    folder = Path(design).resolve().parent
    jaw_file = Path(jaw)
    jaw_here = (named_from(jaw_file.resolve(), here)
                if jaw_file.suffix.lower() == ".toml" and jaw_file.is_file() else "")
    beside = named_from(folder.parent, here)
    return [{**r, "command": command_beside_project(r["command"], folder.name, jaw, jaw_here,
                                                    beside)}
            for r in records]


def named_from(path: Path, here: Path) -> str:
    """``path`` as a command pasted in ``here`` names it: relative to ``here``, or absolute
    where no relative path leads there (another drive on Windows).

    Args:
        path, here: absolute paths.

    Returns:
        The path, with ``/`` between its names.
    """
    import os

    try:
        return Path(os.path.relpath(path, here)).as_posix()
    except ValueError:
        return path.as_posix()


def project_jaw(design: str) -> tuple[str, str]:
    """The jaw of a sensor project, as ``--jaw`` takes it, and its atlas folder.

    Args:
        design: ``--project``: a design file with a ``[grasper_jaw]`` table (a metal insert
            for a grasper: a trocar class's jaw where the table describes the class's default
            jaw, else the lab's jaw the table states) or a die design file (its ``die.jaw``: a
            trocar class, or a jaw file beside it).

    Returns:
        (``--jaw``'s value: the trocar class, or the file holding the jaw's table, named
        as ``--project`` was or from the working folder, never as an absolute path where a
        relative one leads there; the folder ``PROJECT_ATLAS_FOLDER`` beside the design
        file).

    Raises:
        DesignError: naming ``--project``: no such file, not TOML, or a design with no jaw.
    """
    from tactcad.design.array_plan import read_toml
    from tactcad.products.silicon_die.design.die_file import is_die_file, load_die_design

    path = Path(design)
    if not path.is_file():
        raise DesignError("--project", design, "an existing design file (.toml)",
                          "a folder, not a file" if path.is_dir() else "no such file")
    table = read_toml(path, "--project")
    folder = str(path.parent / PROJECT_ATLAS_FOLDER)
    if is_die_file(table):
        jaw = load_die_design(path).jaw  # a jaw file's path resolved beside the design
        return (jaw if not Path(jaw).is_absolute()
                else named_from(Path(jaw), Path.cwd().resolve())), folder
    jaw = table.get("grasper_jaw")
    if isinstance(jaw, dict):
        return class_of_default_jaw(jaw) or str(path), folder
    raise DesignError("--project", design, "a design with a jaw: a [grasper_jaw] table or a "
                      "die's jaw", "this design names no grasper jaw; give --jaw CLASS|FILE")


def class_of_default_jaw(table: dict) -> str | None:
    """The trocar class whose default jaw a design's ``[grasper_jaw]`` table describes (it
    states the class and at most values equal to the class's own: ``design --jaw 10``
    writes it so), or None: a lab's own jaw, which the atlas reads as a jaw file.

    Args:
        table: the design's ``[grasper_jaw]`` table as read.

    Returns:
        the class (a key of :data:`tactcad.partlib.grasper_jaw.SHAFT_CLASSES_MM`) or None
        (also for a table that does not validate: the jaw file's reading names its faults).
    """
    from tactcad.partlib.grasper_jaw import GrasperJawSection, with_class_defaults

    try:
        stated = with_class_defaults(GrasperJawSection(**table))
    except (ValueError, TypeError):  # pydantic's ValidationError is a ValueError
        return None
    default = with_class_defaults(GrasperJawSection(shaft_class_mm=stated.shaft_class_mm))
    return stated.shaft_class_mm if stated == default else None


def writable_folder(out: str) -> Path:
    """``--out`` made a folder, before anything is judged.

    Args:
        out: the folder asked for (new or existing).

    Returns:
        Its path.

    Raises:
        DesignError: naming ``--out``: a system folder, a file, or one that cannot be made
            or written.
    """
    import os

    from tactcad.atomic import refuse_output_path, unmakeable_folder

    folder = refuse_output_path("--out", out, "a folder")  # its default too (a file refused)
    reason = None if folder.is_dir() else unmakeable_folder(folder)
    if reason is not None:  # said in words, before anything is made
        raise DesignError("--out", out, "a folder that can be made", reason)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise DesignError("--out", out, "a folder that can be made",
                          exc.strerror or type(exc).__name__) from None
    if not os.access(folder, os.W_OK):
        raise DesignError("--out", out, "a writable folder")
    return folder


def judged(atlas, points: list[dict], args: argparse.Namespace) -> tuple[list[dict], bool]:
    """Every point judged on Dask.

    Args:
        atlas: the jaw. points: the targets.
        args: ``--scheduler`` (else a new local cluster of ``--workers``, default two,
            single-threaded), ``--batch`` and the progress options.

    Returns:
        (records, True when every batch ran; False when a stop (Ctrl-C, SIGTERM) came
        while the cluster started, judged or closed: the records that finished, none
        when it came before the first).

    Raises:
        ClusterError: nothing answers at ``--scheduler``.
    """
    from tactcad.studies.design_atlas import run_atlas
    from tactcad.studies.sweeps import LOCAL_WORKERS, dask_client

    say = progress_from_args(args)
    finished: tuple[list[dict], bool] = ([], False)
    try:
        with dask_client(args.scheduler, args.workers or LOCAL_WORKERS) as client:
            size = args.batch or auto_batch(len(points), sum(client.nthreads().values()))
            finished = run_atlas(atlas, points, client, size, progress=lambda done, total:
                                 say(f"atlas: {done}/{total} batches"))
    except KeyboardInterrupt:  # raised once the cluster is closed: a stopped atlas
        return finished[0], False
    return finished


def atlas_summary(records: list[dict], inputs: dict, seconds: float, reused: bool,
                  complete: bool, out: Path, resumed: int = 0) -> dict:
    """The run's summary (``atlas.json``, ``--json``).

    Args:
        records: every verdict. inputs: the run's inputs (jaw, points, seed, ranges, key).
        seconds: the run's wall time (s). reused: read from the store. complete: every
            batch ran. out: the ``--out`` folder. resumed: the points read from what a
            stopped run kept (not judged by this run, nor counted in its rate).

    Returns:
        Per product and material the points, the feasible ones, the binding limits counted,
        the feasible region's boundary (the largest feasible force, N, in each step of the
        K_obj span; :func:`tactcad.studies.design_atlas.feasible_boundary`) and the Pareto
        front (:func:`tactcad.studies.design_atlas.pareto_front`, each point
        with its design command); the points judged per second; the files; the front
        points' renamed keys, old -> new (``deprecated_keys``); each product left out of
        the atlas, none of its points judged, with its misfit in the jaw in words
        (``left_out``: ``product``, ``misfit``; mm).
    """
    from collections import Counter

    from tactcad.studies.design_atlas import FRONT_OBJECTIVES, feasible_boundary, pareto_front

    groups: dict[tuple[str, str], list[dict]] = {}
    for r in records:
        groups.setdefault((r["product"], r["material"]), []).append(r)
    per = []
    front_rows = []
    for (product, material), rows in groups.items():
        feasible = [r for r in rows if r["feasible"]]
        front = pareto_front(feasible, FRONT_OBJECTIVES)
        front_rows += front
        per.append({"product": product, "material": material, "points": len(rows),
                    "feasible": len(feasible),
                    "binding_limits": dict(Counter(r["binding_limit"] for r in rows
                                                   if not r["feasible"])),
                    "front": [front_point(r) for r in front],
                    "boundary": [{"span_low": round(lo, 6), "span_high": round(hi, 6),
                                  "largest_feasible_force_N": force}
                                 for lo, hi, force in feasible_boundary(rows)]})
    return {"jaw": inputs["jaw"], "points": inputs["points"], "seed": inputs["seed"],
            "ranges": inputs["ranges"], "left_out": list(inputs.get("left_out", [])),
            "records": len(records), "complete": complete,
            "reused": reused, "seconds": round(seconds, 3),
            "resumed_points": resumed,
            "points_per_s": (None if reused or seconds <= 0 else
                             round(max(len({r["point"] for r in records}) - resumed, 0)
                                   / seconds, 4)),
            "key": inputs["key"], "products": per,
            "front": [front_point(r) for r in front_rows],
            "deprecated_keys": dict(ATLAS_RENAMED),
            "files": {"table": str(out / TABLE_NAME), "figure": str(out / FIGURE_NAME),
                      "summary": str(out / SUMMARY_NAME)}}


def front_point(r: dict) -> dict:
    """A front point for the summary.

    Args:
        r: its record.

    Returns:
        Its targets, its finite figures and its design command; a renamed figure also under
        its old name (:data:`~tactcad.studies.atlas_files.ATLAS_RENAMED`, the summary's
        ``deprecated_keys``).
    """
    from tactcad.in_use.kobj_budget import with_deprecated_keys

    keys = ("product", "material", "point", "kr_over_km", "kobj_lo_N_per_mm",
            "kobj_hi_N_per_mm", "full_scale_force_N", "columns", "kobj_resolution_rel",
            "max_force_N", "lowest_first_Hz", "sheet_mm", "layer_um", "command")
    return with_deprecated_keys({k: r[k] for k in keys
                                 if not (isinstance(r[k], float) and not math.isfinite(r[k]))},
                                ATLAS_RENAMED)


def front_figure(records: list[dict], front: list[dict], path: Path, jaw: str) -> None:
    """The atlas drawn (matplotlib, SVG or PNG).

    Args:
        records: every verdict. front: the front's points. path: the figure's file (SVG,
            or PNG by its suffix).
        jaw: ``--jaw``, for the title.

    Each feasible point's K_obj span against its rated force, coloured by product and
    material; the front ringed; the refused points grey crosses; each product and
    material's feasible region bounded above by a dashed step line in its colour
    (:func:`tactcad.studies.design_atlas.feasible_boundary`). With no feasible point (a
    stopped run's) the figure says so (:func:`empty_figure_note`); with no point at all
    its axes are linear. Written atomically.
    """
    from matplotlib.figure import Figure

    from tactcad.atomic import write_atomic, write_bytes_atomic
    from tactcad.studies.design_atlas import feasible_boundary

    fig = Figure(figsize=(7.0, 4.8))
    ax = fig.add_subplot()
    refused = [r for r in records if not r["feasible"]]
    hover: dict[str, list[dict]] = {"atlas-refused": refused}
    ax.scatter([r["full_scale_force_N"] for r in refused], [span(r) for r in refused],
               marker="x", s=12, color="0.75", label="refused", gid="atlas-refused")
    for k, label in enumerate(sorted({(r["product"], r["material"]) for r in records
                                      if r["feasible"]})):
        rows = [r for r in records if r["feasible"] and (r["product"], r["material"]) == label]
        hover[f"atlas-feasible-{k}"] = rows
        dots = ax.scatter([r["full_scale_force_N"] for r in rows], [span(r) for r in rows],
                          s=18, label=f"{label[0]} {label[1]}", gid=f"atlas-feasible-{k}")
        group = [r for r in records if (r["product"], r["material"]) == label]
        edge = boundary_path(feasible_boundary(group))
        ax.plot(edge[0], edge[1], linestyle="--", linewidth=1.0,
                color=dots.get_facecolor()[0], label=f"feasible boundary, {label[1]}")
    ax.scatter([r["full_scale_force_N"] for r in front], [span(r) for r in front], s=70,
               facecolors="none", edgecolors="k", label="Pareto front")
    if records:  # a log axis of nothing is refused (a run stopped before any point)
        ax.set_xscale("log")
        ax.set_yscale("log")
    note = empty_figure_note(records)
    if note:
        ax.text(0.5, 0.5, note, transform=ax.transAxes, ha="center", va="center")
    ax.set_xlabel("rated full-scale force (N)")
    ax.set_ylabel("K_obj span, high / low")
    ax.set_title(f"design atlas of the jaw {Path(jaw).name}")
    ax.legend(fontsize=7, loc="best")
    path.parent.mkdir(parents=True, exist_ok=True)
    kind = path.suffix.lstrip(".").lower() or "svg"
    if kind != "svg":
        write_atomic(path, lambda tmp: fig.savefig(tmp, format=kind, dpi=110))
        return
    buffer = io.StringIO()
    fig.savefig(buffer, format="svg")
    write_bytes_atomic(path, with_point_titles(buffer.getvalue(), hover).encode("utf-8"))


def empty_figure_note(records: list[dict]) -> str | None:
    """What the atlas's figure says when it has no feasible point to draw (a run stopped
    before any point finished, or before a feasible one did), else None.

    Args:
        records: every verdict drawn.

    Returns:
        The note, or None when some point is feasible.
    """
    if not records:
        return "no target point was judged"
    if not any(r["feasible"] for r in records):
        return f"no feasible design among the {len(records)} verdicts"
    return None


def with_point_titles(svg: str, hover: Mapping[str, list[dict]]) -> str:
    """``svg`` (matplotlib's) with a <title> on every marker of the scatters named in
    ``hover`` (gid -> the records drawn, in order): a browser shows it on hover.

    Raises:
        ValueError: a scatter's markers and its records differ in number (matplotlib
            wrote it otherwise than one <use> per point).
    """
    import xml.etree.ElementTree as ET

    ns = {"svg": "http://www.w3.org/2000/svg", "xlink": "http://www.w3.org/1999/xlink"}
    for prefix, uri in ns.items():
        ET.register_namespace("" if prefix == "svg" else prefix, uri)
    # keep matplotlib's comments: they carry the texts it draws as paths
    root = ET.fromstring(svg, ET.XMLParser(target=ET.TreeBuilder(insert_comments=True)))
    for group in root.iter(f"{{{ns['svg']}}}g"):
        rows = hover.get(group.get("id", ""))
        if rows is None:
            continue
        marks = list(group.iter(f"{{{ns['svg']}}}use"))
        if len(marks) != len(rows):
            raise ValueError(f"scatter {group.get('id')}: {len(marks)} markers drawn for "
                             f"{len(rows)} points")
        for mark, r in zip(marks, rows):
            ET.SubElement(mark, f"{{{ns['svg']}}}title").text = point_title(r)
    return ET.tostring(root, encoding="unicode", xml_declaration=True)


def boundary_path(steps: list[tuple[float, float, float]]) -> tuple[list[float], list[float]]:
    """The feasible boundary's steps as a line in the figure's axes (force along x, span
    along y): each step a vertical run at its largest force over its spans.

    Args:
        steps: (lowest span, highest span, largest feasible force N) per step.

    Returns:
        (forces, spans) of the line's vertices.
    """
    xs: list[float] = []
    ys: list[float] = []
    for low, high, force in steps:
        xs += [force, force]
        ys += [low, high]
    return xs, ys


def print_summary(s: dict) -> None:
    rate = "" if s["points_per_s"] is None else f", {s['points_per_s']:.3g} points/s"
    print(f"atlas of the jaw {s['jaw']}: {s['points']} target points, {s['records']} verdicts "
          + ("(reused from the store)" if s["reused"] else f"in {s['seconds']:.1f} s{rate}")
          + (f" ({s['resumed_points']} points kept by a stopped run, not judged again)"
             if s.get("resumed_points") else "")
          + ("" if s["complete"] else " (stopped: the points that finished are kept)"))
    for g in s["products"]:
        limits = ", ".join(f"{k} {v}" for k, v in sorted(g["binding_limits"].items()))
        print(f"  {g['product']} {g['material']}: {g['feasible']}/{g['points']} feasible"
              + (f"; refused by {limits}" if limits else ""))
        for f in g["front"]:
            print(f"    front: {f['full_scale_force_N']:g} N, K_obj {f['kobj_lo_N_per_mm']:g}-"
                  f"{f['kobj_hi_N_per_mm']:g} N/mm, resolution "
                  f"{100 * f['kobj_resolution_rel']:.2g} %: {f['command']}")
    for g in s.get("left_out", []):
        print(f"  not searched: {g['product']}: {g['misfit']}")
    for name, path in s["files"].items():
        print(f"  wrote {name}: {path}")
