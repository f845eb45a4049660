"""A sensor project is a folder: the design file, its rigs and scenes files
(named in the design's ``[files]`` table), a README, a ``.gitignore`` and a
CI workflow. :func:`new_project` makes one (``tactcad new``, ``tactcad design
--out DIR``); :func:`companion_tables` gives a design with no rigs or scenes
file of its own ones made for it, so no design ever borrows another's.

The rigs and scenes are written from the templates in ``tactcad/data/project``:
the rig hardware is a generic starting point, the samples span the design's
own K_obj range (stated in ``[requirements]``, else derived from its elements),
and every text names the design's own grid. Nothing here reads a file outside
the project folder and the installed package.
"""

from __future__ import annotations

import functools
import json
import math
import os
import re
import shlex
import tomllib
from dataclasses import dataclass, replace
from importlib import resources
from pathlib import Path
from string import Template
from typing import Any, Iterable, Mapping

from tactcad.version import VERSION
from tactcad.atomic import in_target, remove_tree, staging_dir, warn_left_behind
from tactcad.design.array_plan import EXAMPLES, Plan
from tactcad.errors import DesignError

#: Template file -> the file it becomes in a project folder (the design's
#: rigs and scenes come from :func:`companion_texts`).
EXTRA_FILES = {"README.md": "README.md", "gitignore": ".gitignore",
               "hardware.yml": ".github/workflows/hardware.yml"}
#: Shipped with the examples and copied into every project: the bought rig parts' sources.
PURCHASED_PARTS = "purchased-parts.md"
#: The example a new project starts from when none is named (not the paper's array).
DEFAULT_EXAMPLE = "ti_array_2x3"
#: Sample stiffnesses are written to this many significant digits (N/mm).
SAMPLE_DIGITS = 3
#: The samples' stiffness range of the rigs schema (N/mm).
SAMPLE_RANGE = (0.01, 1e4)


def _template(name: str) -> Template:
    return Template((resources.files("tactcad") / "data" / "project" / name)
                    .read_text(encoding="utf-8"))


def examples() -> dict[str, Path]:
    """The shipped example projects: name -> its design file (one folder each); a silicon
    die's folder (:func:`die_examples`) is not one of them."""
    return {name: design for name, (design, die) in _shipped_designs().items() if not die}


def die_examples() -> dict[str, Path]:
    """The shipped silicon dies: name -> its die design file (a ``[die]`` table, read by
    ``tactcad die --design``)."""
    return {name: design for name, (design, die) in _shipped_designs().items() if die}


@functools.cache
def _shipped_designs() -> dict[str, tuple[Path, bool]]:
    # the package's examples, read once a process: every command's help lists them
    # (name -> (design file, whether it is a die's))
    from tactcad.products.silicon_die.design.die_file import is_die_file
    from tactcad.vocabulary.schema import read_toml

    out = {}
    for folder in sorted(p for p in EXAMPLES.iterdir() if p.is_dir()):
        design = folder / f"{folder.name}.toml"
        if design.is_file():
            out[folder.name] = (design, is_die_file(read_toml(design, "design file")))
    return out


def _significant(value: float, digits: int = SAMPLE_DIGITS) -> float:
    return float(f"{value:.{digits}g}")


def sample_stiffnesses(plan: Plan) -> tuple[list[float], str]:
    """The samples a design's rigs carry: the ends and the geometric mean of
    its K_obj range, stiffest first (N/mm, 3 significant digits), with the reason.

    The range is ``requirements.kobj_range_N_per_mm`` where the design states
    it, else the one :func:`tactcad.studies.verification.requirements_of`
    derives from the elements (closed form).
    """
    from tactcad.studies.verification import requirements_of

    req = requirements_of(plan)
    lo, hi = req.kobj_range_N_per_mm
    values = [hi, math.sqrt(lo * hi), lo]
    clipped = [min(max(_significant(v), SAMPLE_RANGE[0]), SAMPLE_RANGE[1]) for v in values]
    samples = list(dict.fromkeys(clipped))  # distinct, in order
    how = ("stated in the design file" if "kobj_range_N_per_mm" in req.stated
           else "derived from the elements' stiffness span, closed form")
    reason = (f"The ends and the geometric mean of the design's K_obj range, "
              f"{_significant(lo)} ... {_significant(hi)} N/mm ({how}).")
    return samples, reason


def _toml_list(values: list[float]) -> str:
    return "[" + ", ".join(repr(v) for v in values) + "]"


def _rigs_name(plan: Plan) -> str:
    return plan.name[:64 - len("_rigs")]


def rig_sizing_words(plan: Plan, samples: list[float]) -> dict[str, str]:
    """The rigs template's force gauge and weights, sized to ``plan``'s rated
    full-scale force and its ``samples`` (N/mm) by :mod:`tactcad.studies.rig_sizing`,
    with their reasons.

    Raises:
        DesignError: no weight of the 1-2-5 series fits the rating.
    """
    from tactcad.studies.rig_sizing import element_loads_per_newton, gauge_need, weights_for
    from tactcad.studies.verification import rated_full_scale_force
    from tactcad.vocabulary.force_gauge_catalogue import choose_force_gauge

    rated = rated_full_scale_force(plan)
    need = gauge_need(rated, samples)
    gauge, short = choose_force_gauge(need)
    w = weights_for(element_loads_per_newton(plan, samples), rated)
    quote = lambda text: text.replace('"', "'")  # noqa: E731 - TOML basic strings
    return {
        "gauge_model": gauge.model, "gauge_range": repr(gauge.range_N),
        "gauge_resolution": repr(gauge.resolution_N),
        "gauge_stiffness": repr(gauge.stiffness_N_per_mm), "gauge_length": repr(gauge.length_mm),
        "gauge_width": repr(gauge.width_mm), "gauge_depth": repr(gauge.depth_mm),
        "gauge_shaft_diameter": repr(gauge.shaft_diameter_mm),
        "gauge_shaft_length": repr(gauge.shaft_length_mm),
        "gauge_reason": quote(
            f"The catalogue gauge of smallest range for this design: {need.words()}; replace "
            f"it with the gauge your lab uses if that fits too." if not short else
            f"No catalogue gauge fits this design ({need.words()}); the nearest misses it "
            f"({'; '.join(short)}): write the gauge your lab uses here (check: rigs fails "
            f"until one fits)."),
        "gauge_source": quote(gauge.source),
        "weight_mass": repr(w.mass_g), "weight_diameter": repr(w.diameter_mm),
        "weight_count": f"{w.count}",
        "weight_preload": repr(math.floor(w.preload_N * 1e6) / 1e6),  # rounded down: within the rating
        "weights_reason": quote(
            f"{w.mass_g:g} g calibration weights (1-2-5 series) added one at a time: the "
            f"preload and all {w.count} give {w.top_load_N:.3g} N, which puts "
            f"{w.element_load_N:.3g} N on element {w.element}, the most loaded, within the "
            f"rated full-scale force {rated:g} N."),
        "weights_count_reason": quote(f"As many {w.mass_g:g} g weights as the rating allows "
                                      f"after the preload, {w.count} load steps."),
    }


def scenes_without_rigs_text(plan_name: str, grid: str) -> str:
    """The scenes file of a design whose construction has no mount for the test
    rigs (TOML text): the insert, and the insert in its grasper's jaw, open and
    closed on a tissue slab; ``grid`` like ``"2 x 6"``."""
    return _template("scenes-without-rigs.toml").substitute(name=plan_name, grid=grid)


def _has_test_rigs(plan: Plan) -> bool:
    from tactcad.design.construction_registry import construction_of

    return construction_of(plan).test_rigs


def companion_texts(plan: Plan) -> dict[str, str]:
    """The rigs and scenes files made for ``plan`` (TOML text): kind -> text.
    The force gauge and the weights are sized to the design (:func:`rig_sizing_words`).
    A construction without a mount for the test rigs gets no rigs file, and
    scenes of the insert and its grasper only (:func:`scenes_without_rigs_text`)."""
    if not _has_test_rigs(plan):
        return {"scenes": scenes_without_rigs_text(plan.name, f"{plan.rows} x {plan.columns}")}
    samples, reason = sample_stiffnesses(plan)
    count = len(plan.slots)
    tip = plan.distinct_elements[plan.slots[0].geometry.part_name]
    words = {
        "name": _rigs_name(plan), "grid": f"{plan.rows} x {plan.columns}",
        "samples": _toml_list(samples), "samples_reason": reason.replace('"', "'"),
        "n_elements": f"{count}", "n_spacers": f"{len(plan.spacer_placements)}",
        "indenter": f"{tip.tip_width_mm:g} x {plan.sheet_thickness_mm:g}",
        "sample_stiff": repr(samples[0]), "sample_mid": repr(samples[len(samples) // 2]),
        **rig_sizing_words(plan, samples),
    }
    return {"rigs": _template("rigs.toml").substitute(words),
            "scenes": _template("scenes.toml").substitute(words)}


def companion_tables(plan: Plan) -> dict[str, Mapping[str, Any]]:
    """The raw tables of :func:`companion_texts` (the ``companions`` maker of
    :func:`tactcad.design.project.project_with_design_data`)."""
    return {kind: tomllib.loads(text) for kind, text in companion_texts(plan).items()}


# --- a new project folder -----------------------------------------------------------------
@dataclass(frozen=True)
class NewProject:
    """What :func:`new_project` wrote: the folder, its design file and every file (relative),
    the files of the project the folder held that it removed (``--force``), and notes for
    the user (rigs made anew because the design's own did not fit it)."""

    folder: Path
    design: Path
    files: tuple[str, ...]
    removed: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()


_FILES_TABLE = re.compile(r"^\s*\[files\]\s*(#.*)?$", re.MULTILINE)


def _with_files_table(text: str, named: Mapping[str, str]) -> str:
    """The design text with a ``[files]`` table naming its companions (kind ->
    relative path: its rigs, where it has test rigs, and scenes; kept when it has one)."""
    if _FILES_TABLE.search(text):
        return text
    lines = "".join(f'{kind} = "{path}"\n' for kind, path in named.items())
    return (text.rstrip("\n") + "\n\n# The project's other files, relative to this one.\n"
            f"[files]\n{lines}")


def _check_target(folder: Path, names: list[str], force: bool, option: str = "DIR") -> None:
    if folder.exists() and not folder.is_dir():
        raise DesignError(option, str(folder), "a new or existing folder", "it is a file")
    parent = folder.resolve().parent
    if not parent.is_dir() or not os.access(parent, os.W_OK | os.X_OK) \
            or (folder.exists() and not os.access(folder, os.W_OK | os.X_OK)):
        raise DesignError(option, str(folder), "a folder this user can write, in an existing folder",
                          f"{parent} is not one")
    # another design file first: --force replaces this design's files, never another's, so
    # offering it first sent a lab to a second refusal
    others = sorted(p.name for p in (designs_in(folder) + other_product_designs_in(folder)
                                     if folder.is_dir() else []) if p.name not in names)
    if others:  # two design files: every command without --design would refuse the folder
        raise DesignError(option, str(folder), "a folder without another design file",
                          f"it holds {', '.join(others)}; a project folder holds one design "
                          "(move it away, or choose another folder; --force replaces this "
                          "design's own files only)")
    clashes = [n for n in names if (folder / n).exists()]
    if clashes and not force:
        raise DesignError(option, str(folder), "a folder without the project's files, or --force",
                          f"it has {', '.join(sorted(clashes))} already")


def check_project_target(folder: Path, design_name: str, force: bool,
                         option: str = "--out", companions: Iterable[str] = ()) -> None:
    """Refuse, before a design is searched for it, a project folder that
    :func:`write_project` would refuse: one holding the design file, its README, .gitignore,
    CI workflow, bought-parts list or one of ``companions`` (without ``force``), or another
    design file. Whatever else the design to come names is checked again when it is written.

    Args:
        folder: the project folder asked for.
        design_name: the design file's name in it (``NAME.toml``).
        force: the project's files may be replaced.
        option: the argument named by a refusal.
        companions: the rigs and scenes files the design to come will write (names
            relative to ``folder``), so that a refusal lists every file ``force`` replaces.

    Raises:
        DesignError: as :func:`write_project`'s, naming ``option``.
    """
    _check_target(folder, [design_name, *EXTRA_FILES.values(), PURCHASED_PARTS, *companions],
                  force, option)


def _named_files(plan: Plan) -> dict[str, str]:
    """kind -> the path relative to the project folder that the design's
    ``[files]`` table gives (else the default name)."""
    from tactcad.design.project import companion_paths

    return {kind: path.as_posix()
            for kind, path in companion_paths(Path("design.toml"), plan.raw).items()}


def _project_files(design_text: str, design_name: str, plan: Plan,
                   companions: Mapping[str, str | None] | None,
                   purchased_parts: str | None = None) -> dict[str, str]:
    """Relative path -> text of every file of the project (the design's last)."""
    made = companion_texts(plan)  # a construction without test rigs: scenes only
    texts = {k: (companions or {}).get(k) or made[k] for k in made}
    names = {kind: path for kind, path in _named_files(plan).items() if kind in made}
    files = {names[kind]: texts[kind] for kind in made}
    words = {"name": plan.name, "description": plan.description, "design": design_name,
             "companions": (f"with its test rigs `{names['rigs']}` and the scenes `{names['scenes']}` "
                            "(named in the design's `[files]` table)" if "rigs" in names else
                            f"and the scenes `{names['scenes']}` (named in the design's "
                            f"`[files]` table; the construction {plan.construction} has no "
                            "mount for the test rigs)"),
             "version": VERSION}
    for template, target in EXTRA_FILES.items():
        files[target] = _template(template).substitute(words)
    if purchased_parts is not None:
        files[PURCHASED_PARTS] = purchased_parts
    files[design_name] = _with_files_table(design_text, names)
    return files


def _write_text(path: Path, text: str) -> None:
    """``path`` written with ``text`` (UTF-8, the user's umask); an error names it
    (a failed write() names no file)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        path.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise exc if exc.filename else OSError(exc.errno, exc.strerror, str(path)) from exc


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def purchased_parts_of(design: Path) -> str:
    """``purchased-parts.md`` for the project of ``design`` (its bought parts from its BOM:
    :func:`tactcad.export.bom.purchased_parts_markdown`)."""
    from tactcad.design.project import load_project
    from tactcad.export.bom import purchased_parts_markdown

    return purchased_parts_markdown(load_project(design))


def _move_in(staging: Path, folder: Path, rels: list[str], stale: list[str] = ()) -> None:
    """Move each of ``rels`` from ``staging`` into the existing ``folder``, the last
    (the design file) last, then take the ``stale`` files out of it; a move that fails puts
    the folder back as it was (the files it held restored, the files and folders made
    removed) and raises.

    Raises:
        OSError: a file could not be moved in (the folder is as it was).
    """
    kept = staging_dir(folder)  # the files replaced, until every move has gone through
    placed: list[tuple[Path, bool]] = []
    made_dirs: list[Path] = []
    try:
        for rel in rels:
            target = folder / rel
            made_dirs += _missing_parents(target, folder)
            target.parent.mkdir(parents=True, exist_ok=True)
            had = target.exists()
            if had:
                (kept / rel).parent.mkdir(parents=True, exist_ok=True)
                os.replace(target, kept / rel)
            placed.append((Path(rel), had))
            os.replace(staging / rel, target)
        for rel in stale:  # kept until every move has gone through, as a replaced file is
            (kept / rel).parent.mkdir(parents=True, exist_ok=True)
            os.replace(folder / rel, kept / rel)
            placed.append((Path(rel), True))
    except OSError:
        _put_back(folder, kept, placed, made_dirs)
        raise
    finally:
        warn_left_behind(remove_tree(kept))


def _missing_parents(target: Path, folder: Path) -> list[Path]:
    """The folders between ``folder`` and ``target`` that do not exist yet (outermost first)."""
    missing = [p for p in target.relative_to(folder).parents if p != Path(".")]
    return [folder / p for p in reversed(missing) if not (folder / p).exists()]


def _put_back(folder: Path, kept: Path, placed: list[tuple[Path, bool]],
              made_dirs: list[Path]) -> None:
    """Undo :func:`_move_in`'s moves: the new files removed, the old ones restored,
    the folders it made removed (innermost first)."""
    for rel, had in reversed(placed):
        (folder / rel).unlink(missing_ok=True)
        if had:
            os.replace(kept / rel, folder / rel)
    for made in reversed(made_dirs):
        try:
            made.rmdir()
        except OSError:
            pass  # not empty or gone: leave it


def write_project(folder: str | Path, design_text: str, design_name: str, plan: Plan, *,
                  companions: Mapping[str, str | None] | None = None,
                  purchased_parts: str | None = None, force: bool = False,
                  option: str = "DIR") -> NewProject:
    """Write a project folder around a validated design.

    Args:
        folder: the project folder; created when missing. An existing one
            must hold none of the files written (else ``force``).
        design_text: the design file's TOML text (a ``[files]`` table is
            added when it has none).
        design_name: the design file's name in the folder (``NAME.toml``).
        plan: the design's validated plan (for the rigs' samples and texts).
        companions: the rigs and scenes texts (kind -> text, or None) to
            write instead of those made for ``plan`` (the design's own files);
            a construction without test rigs gets no rigs file.
        purchased_parts: the text of ``purchased-parts.md`` (an example's own);
            None: generated from the project's BOM (its bought parts and consumables).
        force: overwrite the files the folder holds already.
        option: the command's name of the folder, named by a refusal (``new``'s ``DIR``,
            ``design``'s ``--out``).

    Returns:
        :class:`NewProject`.

    Raises:
        DesignError: ``option`` is a file, or holds one of the files (without ``force``).
        OSError: the folder cannot be written (nothing is left half-written:
            the files are made in a staging folder beside it first).
    """
    folder = Path(folder)
    files = _project_files(design_text, design_name, plan, companions, purchased_parts)
    return _write_files(folder, files, force, option, purchased_parts_of)


def _write_files(folder: Path, files: dict[str, str], force: bool, option: str,
                 parts_of=None) -> NewProject:
    # the project's files made in a staging folder, then moved in (the design file, last
    # in ``files``, last); ``parts_of`` makes the bought-parts list from the staged design
    design_name = list(files)[-1]
    listed = [PURCHASED_PARTS, *files] if parts_of is not None else list(files)
    _check_target(folder, list(dict.fromkeys(listed)), force, option)
    # --force: the files tactcad wrote for the project the folder held go, those it keeps
    # writing are replaced; files of the user's own are kept
    stale = sorted(set(old_project_files(folder / design_name)) - set(listed)) if force else []
    staging = staging_dir(folder)
    os.chmod(staging, 0o777 & ~_umask())  # a project folder, not a private temporary one
    try:
        for rel, text in files.items():
            _write_text(staging / rel, text)
        if parts_of is not None and PURCHASED_PARTS not in files:  # its own, from its BOM
            text = parts_of(staging / design_name)
            _write_text(staging / PURCHASED_PARTS, text)
            files = {PURCHASED_PARTS: text, **files}  # the design file stays the last moved
        if not folder.exists():
            os.rename(staging, folder)
        else:
            _move_in(staging, folder, list(files), stale)
    except OSError as exc:  # name the file in the folder asked for, not in the staging one
        raise in_target(exc, staging, folder) from exc
    finally:
        if staging.exists():
            warn_left_behind(remove_tree(staging))
    return NewProject(folder, folder / design_name, tuple(files), tuple(stale))


def old_project_files(design: Path) -> list[str]:
    """The files tactcad wrote for the project of the design file ``design`` as its writer
    recorded them: the design file, the README, .gitignore and CI workflow, and the files
    the design names (an array's ``[files]`` table: its rigs and scenes, with its
    ``purchased-parts.md``; a die's jaw file), each relative to the design's folder and
    present there.

    Args:
        design: a design file in a project folder (need not exist).

    Returns:
        Relative paths (POSIX) of the files present; none when ``design`` is no readable
        design file.
    """
    from tactcad.design.file_kind import DIE_TABLE

    try:
        tables = tomllib.loads(design.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return []
    named = [design.name, *EXTRA_FILES.values()]
    die = tables.get(DIE_TABLE)
    if isinstance(die, Mapping):
        named.append(die.get("jaw"))
    else:
        files = tables.get("files")
        named += [PURCHASED_PARTS, *(files.values() if isinstance(files, Mapping) else ())]
    return [rel for rel in dict.fromkeys(n for n in named if isinstance(n, str) and n)
            if _inside_folder(design.parent, rel) and (design.parent / rel).is_file()]


def _inside_folder(folder: Path, rel: str) -> bool:
    """True when ``rel`` names a path inside ``folder`` (not absolute, no way out of it)."""
    return not Path(rel).is_absolute() and \
        (folder / rel).resolve().is_relative_to(folder.resolve())


_TABLE_HEAD = re.compile(r"^\[", re.MULTILINE)


def _string_line(key: str) -> re.Pattern:
    """``key = "..."`` in a TOML table (a basic or literal string, a comment after it)."""
    return re.compile(rf"""^(\s*{re.escape(key)}\s*=\s*)("[^"\\\n]*"|'[^'\n]*')(\s*(#.*)?)$""",
                      re.MULTILINE)


#: ``name = "..."`` in a TOML table.
_NAME_LINE = _string_line("name")


def project_design_name(folder_name: str) -> str | None:
    """The design name a project folder gives its design (``palp-strip`` -> ``palp_strip``),
    or None when the folder's name is no design name (:data:`NAME_PATTERN`)."""
    from tactcad.vocabulary.schema import NAME_PATTERN

    name = folder_name.removesuffix(".toml").replace("-", "_")
    return name if re.fullmatch(NAME_PATTERN, name) else None


def suggested_design_name(text: str, fallback: str = "sensor") -> str:
    """A design name (:data:`~tactcad.vocabulary.schema.NAME_PATTERN`) close to ``text``
    for a user to paste (:func:`~tactcad.vocabulary.schema.suggested_name`: accents dropped,
    ``ü`` -> ``u``, every other character outside the allowed ones an ``_``).

    Args:
        text: the name asked for (a folder or file name; a ``.toml`` suffix is not kept).
        fallback: the name when nothing of ``text`` is left.

    Returns:
        A name :func:`project_design_name` accepts.
    """
    from tactcad.vocabulary.schema import suggested_name

    name = suggested_name(text.removesuffix(".toml"), fallback)
    return name if project_design_name(name) is not None else fallback


def refuse_no_design_name(option: str, value: str, folder_name: str) -> None:
    """Refuse a project folder (or design file) whose name names no design: the project's
    design takes its name, which ends up in file names, DXF headers and drawings.

    Args:
        option: the argument named in the refusal (``DIR``, ``--out``).
        value: the value as given.
        folder_name: the folder's (or file's) own name, the design's name to be.

    Raises:
        DesignError: naming ``option``, the value, the characters allowed and a name to
            paste (:func:`suggested_design_name`).
    """
    from tactcad.vocabulary.schema import NAME_ALLOWED

    if project_design_name(folder_name) is not None:
        return
    parent = os.path.dirname(value.rstrip("/"))
    suggestion = os.path.join(parent, suggested_design_name(folder_name)
                              + (".toml" if folder_name.endswith(".toml") else ""))
    paste = f"{option} {shlex.quote(suggestion)}" if option.startswith("-") else \
        shlex.quote(suggestion)  # a positional argument is pasted alone
    raise DesignError(option, value, NAME_ALLOWED + " (its file or folder name is the design's "
                      f"name), e.g. {paste}", "names end up in file names, DXF headers and "
                      "drawings", alternatives=[{"option": paste, "words": "the name with "
                                                 "accents dropped and other characters as _"}])


def named_for_project(design_text: str, folder_name: str, table: str = "design"
                      ) -> tuple[str, str | None]:
    """(text, name): the design file's text with its ``[design]`` (or a die's ``[die]``,
    ``table``) name set to the project folder's (:func:`project_design_name`), and that
    name; the text unchanged and None when the folder's name is no design name or the
    file states its name otherwise than on a ``name = "..."`` line of that table (an
    inline table, say)."""
    name = project_design_name(folder_name)
    if name is None:
        return design_text, None
    head = re.search(rf"^\[{table}\]\s*$", design_text, re.MULTILINE)
    if head is None:
        return design_text, None
    nxt = _TABLE_HEAD.search(design_text, head.end())
    line = _NAME_LINE.search(design_text, head.end(), nxt.start() if nxt else len(design_text))
    if line is None:
        return design_text, None
    text = (design_text[:line.start(2)] + json.dumps(name) + design_text[line.end(2):])
    if tomllib.loads(text).get(table, {}).get("name") != name:
        return design_text, None
    return text, name


#: The opening comment of a rigs file copied into a project named otherwise than its source.
RIGS_HEADER = """# Test rigs of {name}, started from those of {source}: calibration on micro-stages
# under a force gauge, object-stiffness rig on a wheeled cart, array evaluation rig
# on a vertical linear axis with added weights. The rig hardware is a starting point
# to adapt to your lab. `tactcad check` (rigs) judges the force gauge and the weights
# against the design's rating, and fails while the samples do not span its K_obj range.
# Units: mm, N, g. Every value is listed under [assumptions] with its reason.
"""
_OPENING_COMMENT = re.compile(r"\A(?:#[^\n]*\n)+")


def _with_table_string(text: str, table: str, key: str, value: str) -> str:
    """``text`` with the string ``key = "..."`` of TOML table ``table`` set to ``value``
    (unchanged where the table states it otherwise than on such a line)."""
    head = re.search(rf"^\[{table}\]\s*$", text, re.MULTILINE)
    if head is None:
        return text
    nxt = _TABLE_HEAD.search(text, head.end())
    line = _string_line(key).search(text, head.end(), nxt.start() if nxt else len(text))
    if line is None:
        return text
    return text[:line.start(2)] + json.dumps(value) + text[line.end(2):]


def rigs_named_for_project(rigs_text: str, name: str, source: str) -> str:
    """The rigs file's text of the design ``source`` (an example's) for the project ``name``
    started from it: its ``[rigs]`` name and description and its opening comment name the
    project, not ``source``; the rig hardware is kept.

    Args:
        rigs_text: the rigs file's TOML text.
        name: the project's design name.
        source: the design the rigs were written for (named in the comment).

    Returns:
        The text (unchanged where its ``[rigs]`` table is no ``name = "..."`` line).
    """
    text = _with_table_string(rigs_text, "rigs", "name", f"{name[:64 - len('_rigs')]}_rigs")
    if text == rigs_text:
        return rigs_text
    text = _with_table_string(text, "rigs", "description",
                              f"Calibration, sample-stiffness and array-evaluation rigs of {name}")
    header = RIGS_HEADER.format(name=name, source=source)
    return _OPENING_COMMENT.sub(lambda _: header, text, count=1)


def new_project(folder: str | Path, *, example: str | None = None,
                from_design: str | Path | None = None, force: bool = False) -> NewProject:
    """Make a sensor project folder (``tactcad new``).

    Args:
        folder: the folder to make (or an existing one without the project's files).
        example: a shipped example to start from (:func:`examples`; default
            ``ti_array_2x3``); its own rigs and scenes are copied, the rigs named for
            the project (:func:`rigs_named_for_project`).
        from_design: a design file to start from instead; its own rigs and scenes
            (named in its ``[files]`` table, else beside it) are copied where the rigs fit
            it (:func:`rigs_misfits`), else both are made for it (samples over its K_obj
            range, force gauge and weights sized to its rating), a note saying so.
        force: overwrite the project's files in an existing folder.

    Returns:
        :class:`NewProject`.

    Raises:
        DesignError: both or an unknown ``example``; a folder whose name names no
            design (:func:`refuse_no_design_name`); a design that does not validate (every
            refusal); ``folder`` unusable.
        OSError: the folder cannot be written.
    """
    from tactcad.design.array_plan import read_toml
    from tactcad.products.silicon_die.design.die_file import is_die_file
    from tactcad.design.project import companion_files, project_with_design_data
    from tactcad.vocabulary.schema import Problems

    if example is not None and from_design is not None:
        raise DesignError("--example", example, "either --example or --from-design, not both")
    # the design takes the folder's name: refused here, not swapped for the example's
    refuse_no_design_name("DIR", str(folder), Path(folder).resolve().name)
    if from_design is None:
        name = example or DEFAULT_EXAMPLE
        if name in die_examples():
            return new_die_project(folder, die_examples()[name], force=force)
        known = examples()
        if name not in known:
            raise DesignError("--example", name, "one of " + ", ".join([*known, *die_examples()]))
        source = known[name]
    else:
        source = Path(from_design)
    data = read_toml(source, "design file")
    if from_design is not None and is_die_file(data):
        return new_die_project(folder, source, force=force)
    if from_design is not None and not isinstance(data.get("design"), dict):
        # a companion (rigs, scenes) or another TOML: not a design to start from
        raise DesignError("--from-design", str(from_design), "a design file (a [design] "
                          "table, or a die's [die])", f"{source.name} has no [design] table")
    # the design named for the project (``new palp`` writes palp.toml), where its text allows
    text, name = named_for_project(source.read_text(encoding="utf-8"),
                                   Path(folder).resolve().name)
    if name is not None:
        data = {**data, "design": {**data["design"], "name": name}}
    validated = project_with_design_data(data, source, companions=companion_tables)
    # the design's own rigs and scenes where it has them (validated above)
    own = companion_files(source, data, Problems(source.name))
    companions = {kind: f.read_text(encoding="utf-8") if f is not None else None
                  for kind, f in own.items()}
    if name is not None and companions.get("rigs"):  # the rigs name the project, not the example
        companions["rigs"] = rigs_named_for_project(companions["rigs"], name, source.stem)
    notes: tuple[str, ...] = ()
    misfits = rigs_misfits(validated) if from_design is not None and companions.get("rigs") else []
    if misfits:  # rigs sized for another design (a folder's rigs.toml): made for this one
        companions = {}  # the scenes too: they name the samples the rigs carry
        notes = (rigs_remade_note(validated.rigs.source or "rigs.toml", source.name, misfits),)
    own_parts = source.parent / PURCHASED_PARTS if from_design is None else None
    made = write_project(folder, text, f"{name}.toml" if name else source.name, validated.plan,
                         companions=companions, force=force,
                         purchased_parts=own_parts.read_text(encoding="utf-8")
                         if own_parts is not None and own_parts.is_file() else None)
    return replace(made, notes=notes)


def rigs_misfits(project) -> list[str]:
    """The rig checks (:func:`tactcad.checks.rig_checks.rig_checks`) a project's rigs fail,
    by name ("rig force gauge", "rig sample kit"); empty when they fit or it has no rigs.

    Args:
        project: a validated :class:`~tactcad.design.project.Project`.
    """
    from tactcad.checks.rig_checks import rig_checks

    if project.rigs is None:
        return []
    return [r.check for r in rig_checks(project.plan, project.rigs) if not r.passed]


def rigs_remade_note(rigs_file: str, design_file: str, misfits: list[str]) -> str:
    """The note of ``new --from-design`` when the design's rigs did not fit it and the
    project's rigs and scenes were made for it instead."""
    return (f"the rigs {rigs_file} of {design_file} do not fit it ({', '.join(misfits)} fail): "
            "the project's rigs and scenes are made for it instead (samples over its K_obj "
            "range, the force gauge and weights sized to its rated full-scale force)")


def new_die_project(folder: str | Path, source: Path, *, force: bool = False) -> NewProject:
    """A silicon die's project folder (``tactcad new --example`` of a shipped die): its die
    design file named for the folder where the folder's name may name the die, a README and
    a .gitignore (a die has no rigs, scenes or bought-parts list).

    Raises:
        DesignError: ``folder`` a file, or holding one of the files (without ``force``).
        OSError: the folder cannot be written (nothing is left half-written).
    """
    from tactcad.products.silicon_die.design.die_file import (DIE_TABLE, is_cell_name,
                                                              load_die_design)

    original = source.read_text(encoding="utf-8")
    text, name = named_for_project(original, Path(folder).resolve().name, DIE_TABLE)
    if name is None or not is_cell_name(name):
        text, name = original, None
    design_name = f"{name}.toml" if name else source.name
    text = text.replace(source.name, design_name)  # its comments name the file they are in
    design = load_die_design(source)
    jaw = Path(design.jaw)
    jaw_text = (jaw.read_text(encoding="utf-8")  # a lab's jaw file, kept beside it
                if jaw.suffix.lower() == ".toml" and jaw.is_file() else None)
    files = die_project_files(text, design_name, name or design.die.name,
                              {design.die.jaw: jaw_text} if jaw_text is not None else {})
    return _write_files(Path(folder), files, force, "DIR")


def die_project_files(design_text: str, design_name: str, name: str,
                      beside: Mapping[str, str] | None = None) -> dict[str, str]:
    """Relative path -> text of a silicon die's project folder: a README, a .gitignore, the
    CI workflow (export, check with a JUnit report, the diff on a pull request, as an
    array's project has), the files ``beside`` it (a lab's jaw file) and the die's design
    file (last: it is moved in last)."""
    words = {"name": name, "design": design_name, "version": VERSION}
    files = {"README.md": _template("README-die.md").substitute(words),
             ".gitignore": _template("gitignore").substitute(words),
             EXTRA_FILES["hardware.yml"]: _template("hardware.yml").substitute(words),
             **dict(beside or {})}
    files[design_name] = design_text
    return files


def write_die_project(folder: str | Path, design_text: str, design_name: str, name: str,
                      beside: Mapping[str, str] | None = None, *, force: bool = False,
                      option: str = "--out") -> NewProject:
    """A silicon die's project folder around a design file's text (``tactcad design
    --jaw ... --out DIR`` when a die is what fits): :func:`die_project_files`, made in a
    staging folder and moved in.

    Raises:
        DesignError: ``option`` is a file, or holds one of the files (without ``force``).
        OSError: the folder cannot be written (nothing is left half-written).
    """
    return _write_files(Path(folder), die_project_files(design_text, design_name, name, beside),
                        force, option)


# --- which design a command works on ---------------------------------------------------------
def product_of(design: Path):
    """The product (:class:`tactcad.products.Product`) of the design file ``design``, read
    as TOML (:func:`tactcad.products.product_of_tables`).

    Raises:
        DesignError: the file is unreadable or not TOML (named).
    """
    from tactcad.products import product_of_tables
    from tactcad.vocabulary.schema import read_toml

    return product_of_tables(read_toml(design, "design file"))


def designs_in(folder: str | Path) -> list[Path]:
    """The design files of a project folder: its ``*.toml`` files with a
    ``[design]`` and an ``[arms]`` table (unreadable files are passed over)."""
    return _tomls_where(folder, lambda t: isinstance(t.get("design"), dict)
                        and isinstance(t.get("arms"), dict))


def other_product_designs_in(folder: str | Path) -> list[Path]:
    """The design files of a folder that another product than the array claims (a silicon
    die's ``[die]`` file, :func:`tactcad.products.product_of_tables`): its ``*.toml`` files
    a registered product owns (unreadable files passed over)."""
    from tactcad.products import product_of_tables

    return _tomls_where(folder, lambda tables: not product_of_tables(tables).is_default)


def _tomls_where(folder: str | Path, holds) -> list[Path]:
    """The ``*.toml`` files of ``folder`` whose tables ``holds`` (unreadable ones passed over)."""
    found = []
    for path in sorted(Path(folder).glob("*.toml")):
        try:
            tables = tomllib.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
            continue
        if holds(tables):
            found.append(path)
    return found


def design_in_folder(folder: str | Path, field: str = "--design") -> Path:
    """The design file a project folder names by holding it: its one design file (an
    array's, a comb's or a silicon die's), so that ``--design FOLDER``, a command's
    ``DESIGN`` word and ``tactcad.load(FOLDER)`` read the project as its file would.

    Args:
        folder: a project folder (as ``tactcad new`` or ``design --out`` writes one).
        field: the option or keyword the folder was given as, for the refusal.

    Returns:
        The path of the folder's design file.

    Raises:
        DesignError: the folder holds no design file (a ``*.toml`` that cannot be read is
            named with its fault) or several (each named: the file must be chosen).
    """
    folder = Path(folder)
    found = designs_in(folder) + other_product_designs_in(folder)
    if len(found) == 1:
        return found[0]
    if found:
        raise DesignError(field, str(folder), "one of its design files: "
                          + ", ".join(str(folder / p.name) for p in found),
                          f"the folder holds {len(found)} design files")
    unreadable = unreadable_tomls(folder)
    why = (f"{unreadable[0].value}: {unreadable[0].why or unreadable[0].allowed}"
           if unreadable else "it holds no *.toml with a [design] or [die] table")
    raise DesignError(field, str(folder),
                      "a design file (TOML) or a project folder holding one", why)


def default_design(folder: str | Path = ".", refuse_unreadable: bool = True) -> Path:
    """The design a command works on when none is named: the one design file
    of the project folder ``folder`` (the working folder; an array's or a silicon
    die's), else the shipped example ``macro_array`` (the paper's 2 x 5 array).

    Args:
        folder: the working folder.
        refuse_unreadable: refuse a folder with no design file and a ``*.toml`` file that
            cannot be read (:func:`refuse_unreadable_tomls`); False passes such files over
            (``design``, which writes a new file and names its base on stderr).

    Returns:
        The design file's path.

    Raises:
        DesignError: the folder holds several design files (``--design`` must choose), or
            none and a ``*.toml`` file that cannot be read (with ``refuse_unreadable``).
    """
    from tactcad.design.array_plan import DEFAULT_DESIGN

    found = designs_in(folder) + other_product_designs_in(folder)
    if len(found) > 1:
        raise DesignError("--design", None, "one of " + ", ".join(p.name for p in found),
                          f"{len(found)} design files in {Path(folder).resolve().name or '/'}")
    if not found:
        if refuse_unreadable:
            refuse_unreadable_tomls(Path(folder))
        for where in _export_folders(Path(folder)):
            if (export := export_in(where)) is not None:
                raise _not_in_an_export(Path(folder), where, *export)
    return found[0] if found else DEFAULT_DESIGN


#: Tables only a design file holds: a ``*.toml`` with one of them that is no design is a
#: design with a slip in it (a table renamed or lost), not another tool's file.
DESIGN_ONLY_TABLES = ("design", "arms", "element", "array", "die")
#: What a design file holds, as a refusal says it.
DESIGN_FILE_WORDS = "a design file: a [design] and an [arms] table, or a silicon die's [die] table"


def hollow_design_fault(tables: dict[str, Any]) -> str:
    """Why a ``*.toml`` that reads as TOML may be a project's design file gone wrong rather
    than another tool's file: empty (a write the disk cut short leaves one), no table at all,
    or a design's own table (:data:`DESIGN_ONLY_TABLES`) without being a design.

    Args:
        tables: the file's parsed TOML.

    Returns:
        The fault in words, "" when the file is a design or plainly another kind of file.
    """
    from tactcad.products import product_of_tables

    if not tables:
        return "it is empty: no table and no key"
    if not any(isinstance(v, dict) for v in tables.values()):
        return "it has no table, only the keys " + ", ".join(sorted(tables)[:4])
    if isinstance(tables.get("design"), dict) and isinstance(tables.get("arms"), dict):
        return ""
    if not product_of_tables(tables).is_default:
        return ""
    held = [f"[{t}]" for t in DESIGN_ONLY_TABLES if isinstance(tables.get(t), dict)]
    if held:
        return f"it has a design's {', '.join(held)} but not what a design needs"
    return ""


def unreadable_tomls(folder: Path) -> list[DesignError]:
    """The ``*.toml`` files of ``folder`` that cannot be read as TOML, or that read but may
    be the project's design file gone wrong (:func:`hollow_design_fault`: empty, no table,
    a design's table without being one), each as a refusal naming the file and its fault.

    Args:
        folder: the working folder.

    Returns:
        One :class:`DesignError` per such file, in name order (empty: all read).
    """
    from tactcad.vocabulary.schema import read_toml

    found = []
    for path in sorted(folder.glob("*.toml")):
        if path.is_file():
            try:
                fault = hollow_design_fault(read_toml(path, "design file"))
            except DesignError as exc:
                found.append(exc)
                continue
            if fault:
                found.append(DesignError("design file", str(path), DESIGN_FILE_WORDS, fault))
    return found


def refuse_unreadable_tomls(folder: Path) -> None:
    """Refuse a folder whose ``*.toml`` files include one that cannot be read as TOML: it
    may be the project's design file with a slip in it, and a command must not work on the
    shipped example in its place (and overwrite the project's exports with it).

    Args:
        folder: the working folder, where no design file was found.

    Raises:
        DesignError: the first such file, named with its fault, saying it was read because
            no ``--design`` was given and that ``--design FILE`` chooses the design.
    """
    for exc in unreadable_tomls(folder)[:1]:
        name = Path(str(exc.value)).name
        raise DesignError(
            "design file", name, exc.allowed,
            f"{exc.why}; read as this folder's design file could be, because no --design "
            f"was given: name the design with --design FILE, or mend or move {name}",
            alternatives=[{"option": "--design FILE",
                           "words": "the design to work on; the folder's *.toml files are "
                                    "then not read"}])


#: How far up from the working folder an export is looked for (``exports/step`` is two).
EXPORT_DEPTH = 3


def _export_folders(folder: Path) -> list[Path]:
    # the working folder and its parents up to EXPORT_DEPTH, stopping at a project folder
    out, here = [], folder.resolve()
    for _ in range(EXPORT_DEPTH + 1):
        out.append(here)
        if here.parent == here or designs_in(here.parent) or other_product_designs_in(here.parent):
            break
        here = here.parent
    return out


def export_in(folder: str | Path) -> tuple[str, str] | None:
    """(the record's file name, the design file it was made from) where ``folder`` holds an
    export (an array's ``manifest.json``, a die's record) rather than a design; else None."""
    for path in sorted(Path(folder).glob("*.json")):
        try:
            record = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, ValueError):
            continue
        if not isinstance(record, dict) or "files" not in record:
            continue
        design = record.get("design")
        if isinstance(design, dict) and "source" in design:
            return path.name, str(design["source"] or "")
        if "die" in record:  # a die's record written before it named its design
            return path.name, ""
    return None


def _not_in_an_export(folder: Path, export: Path, record: str, source: str) -> DesignError:
    # a command run among an export's files must not quietly work on the shipped example
    design = next((p / source for p in export.parents[:EXPORT_DEPTH]
                   if source and (p / source).is_file()), None)
    where = (f"--design {shlex.quote(os.path.relpath(design, folder))}" if design is not None
             else f"--design PATH/{source}" if source else "--design FILE")
    inside = "" if export == folder.resolve() else f", and this folder lies inside it"
    return DesignError("--design", None, f"a design file ({where})",
                       f"{export.name or '/'} holds an export ({record}), not a design"
                       f"{inside}: run the command in its project's folder or name the design",
                       alternatives=[{"option": where, "words": "the design this export "
                                                                 "was made from"}])
