"""Sub-commands of the ``tactcad`` CLI; see :mod:`tactcad.cli`.

Every command that reads a design gets it from :func:`load_from_args` (the
:class:`tactcad.api.Project`), :func:`project_from_args` (its validated
:class:`tactcad.design.project.Project`) or :func:`plan_from_args` (its
plan): all go through :func:`tactcad.api.load`, the one place where the
design file and the rigs and scenes files beside it are read, ``--set``
overrides applied and the result validated, for the command line and the
Python API alike. Nothing below the commands opens those files again: the
validated project is carried to the last writer.
"""

from __future__ import annotations

import argparse
import re
import sys
import tomllib
from pathlib import Path
from typing import Any, Callable

from tactcad.commands.options import output_folder
from tactcad.commands.notices import print_heads
# one rule for where the store may be kept: the commands' --cache and the API's cache
from tactcad.store import CACHE_ALLOWED, usable_cache_folder  # noqa: F401 (re-exported)

SET_EXAMPLE = "element.web_thickness_mm=0.3"


DESIGN_HELP = ("design file (TOML), a project folder or a shipped example's name (e.g. "
               "macro_array, read where no file or folder of that name is); default: the one "
               "design file of the working folder (a "
               "project made by tactcad new), else the shipped example macro_array (the "
               "paper's 2 x 5 array)")
SET_HELP = ("override one value of the design file (repeatable): a dotted key and a TOML value, "
            f"e.g. --set {SET_EXAMPLE} or --set 'arms.lengths_mm=[4,5,6,7,8,4,5,6,7,8]'; "
            "checked like the file")


DESIGN_WORD_HELP = ("the design, as --design gives it: a design file (TOML), a project "
                    "folder holding one or a shipped example's name (e.g. macro_array)")


def add_design_arg(p: argparse.ArgumentParser, design_help: str = DESIGN_HELP,
                   set_help: str = SET_HELP, design_word: bool = True) -> None:
    """The ``--design FILE`` and ``--set KEY=VALUE`` options every command that reads a
    design shares (a command whose file is another kind says so in its own help texts),
    and with ``design_word`` the design as the command's one word (``tactcad strength
    d/d.toml``; :func:`settle_design` reads it); a command with a word of its own
    (``scenes NAME``) takes ``--design`` only."""
    p.add_argument("--design", metavar="FILE", default=None, help=design_help)
    if design_word:
        p.add_argument("design_word", metavar="DESIGN", nargs="?", default=None,
                       help=DESIGN_WORD_HELP)
    p.add_argument("--set", metavar="KEY=VALUE", action="append", default=[], dest="overrides",
                   help=set_help)


def settle_design(args: argparse.Namespace) -> None:
    """The design a parsed command line names, in ``args.design``, in place: the command's
    ``DESIGN`` word is ``--design``'s value, and a project folder given either way is its
    one design file (:func:`tactcad.project_folder.design_in_folder`).

    Raises:
        DesignError: the word and ``--design`` name two designs, or a folder that holds
            no design file or several.
    """
    from tactcad.errors import DesignError

    word = getattr(args, "design_word", None)
    if word is not None:
        given = getattr(args, "design", None)
        if given is not None and Path(given) != Path(word):
            raise DesignError("--design", given, f"one design: the command's word names {word}",
                              "a command works on one design; give it once")
        args.design = word
        args.design_word = None  # one design, read from --design by every command from here
    design = getattr(args, "design", None)
    if design is not None and _is_folder(design):
        from tactcad.project_folder import design_in_folder

        args.design = str(design_in_folder(design))
    elif design is not None:
        args.design = file_or_shipped_example(design)


def file_or_shipped_example(design: str) -> str:
    """The design file a ``--design`` value names: the path given where a file (or anything)
    of that name is, else the shipped example of that name (``macro_array``, a die's
    ``grasper_jaw_5mm_mems``), so an example is named the same way in any folder and by
    every command; a local file of that name wins.

    Args:
        design: ``--design``'s value (or the command's DESIGN word), a path or a name.

    Returns:
        The path to read: ``design`` itself, or the shipped example's design file (a
        missing file is named by the reader).
    """
    from tactcad.project_folder import die_examples, examples

    try:
        if Path(design).exists():
            return design
        if Path(design).suffix == "" and Path(f"{design}.toml").is_file():
            return f"{design}.toml"  # the local file of that name wins over the example
    except OSError:  # a name the system cannot look up (too long): its reader names it
        return design
    shipped = {**examples(), **die_examples()}
    if design in shipped:
        return str(shipped[design])
    refuse_a_misspelt_example(design, sorted(shipped))
    return design


def refuse_a_misspelt_example(design: str, names: list[str]) -> None:
    """Refuse a bare word (no folder, no suffix) close to a shipped example's name, naming
    the examples; anything else is left to the design file's reader to name.

    Args:
        design: ``--design``'s value, naming no file. names: the shipped examples' names.

    Raises:
        DesignError: ``design`` is a bare word close to an example's name.
    """
    import difflib

    from tactcad.errors import DesignError

    if "/" in design or Path(design).suffix:
        return
    close = difflib.get_close_matches(design, names, n=1, cutoff=0.75)
    if close:
        raise DesignError("design file", design,
                          f"a readable TOML file, or a shipped example's name (did you mean "
                          f"{close[0]}? the examples: {', '.join(names)})")


def _is_folder(path: str) -> bool:
    """Whether ``path`` names a folder; a name the system cannot look up (too long) is
    none, and reading it as a file names its fault."""
    try:
        return Path(path).is_dir()
    except OSError:
        return False


def add_output_args(p: argparse.ArgumentParser, json_help: str = "print one JSON object") -> None:
    """``--json`` (results and errors as JSON on stdout) and ``--quiet`` (no progress)."""
    p.add_argument("--json", action="store_true",
                   help=json_help + "; an error is printed as {\"error\": {...}} on stdout")
    p.add_argument("--quiet", action="store_true", help="print no progress on stderr")


def progress_from_args(args: argparse.Namespace) -> Callable[[str], None]:
    """Where progress lines go: stderr, flushed at once; nowhere with ``--json`` or ``--quiet``."""
    if getattr(args, "json", False) or getattr(args, "quiet", False):
        return lambda line: None

    def report(line: str) -> None:
        print_heads()
        print(line, file=sys.stderr, flush=True)
    return report


def parse_override(text: str, example: str = SET_EXAMPLE) -> tuple[str, Any]:
    """``"section.key=VALUE"`` -> ``("section.key", value)``, VALUE read as a TOML value;
    ``example``: a key=value of the file's kind a refusal shows.

    Raises:
        DesignError: no ``=``, a key that is not ``section.key``, or a value
            that is not a TOML value (a number, a quoted string, true/false, a list).
    """
    from tactcad.errors import DesignError

    key, sep, raw = text.partition("=")
    key = key.strip()
    section, dot, name = key.partition(".")
    if not sep or not dot or not section or not name:
        raise DesignError("--set", text, f"KEY=VALUE with a dotted key of the design file, "
                                         f"e.g. {example}")
    try:
        value = tomllib.loads(f"value = {raw.strip()}")["value"]
    except tomllib.TOMLDecodeError as exc:
        number = number_key_error(key, raw.strip(), text) if _BARE_WORD.fullmatch(
            raw.strip()) else None
        if number is not None:
            raise number from None
        raise DesignError(key, raw.strip(), "a TOML value: a number, a quoted string, true or "
                                            "false, or a list such as [4, 5, 6]",
                          f"--set {text}: {exc}",
                          alternatives=quoted_word(key, raw.strip())) from None
    return key, value


def _file_models() -> tuple:
    """The design file models a ``--set`` key may name (the array's, the comb's, the
    die's), imported only when a refusal asks for them."""
    from tactcad.design.array_plan import DesignFile
    from tactcad.design.comb_plan import CombFile
    from tactcad.products.silicon_die.design.die_file import DieFile

    return DesignFile, CombFile, DieFile


def number_key_error(key: str, raw: str, text: str):
    """The refusal of a ``--set`` whose key takes a number (or an integer) in every design
    file that names it and whose value is no number: the key's kind and allowed range (with
    its unit, mm, N, Hz...), and no paste (quoting the word as a TOML string would be
    refused again as not a number).

    Args:
        key: the dotted key. raw: its value as typed. text: the whole ``--set`` text.

    Returns:
        The :class:`tactcad.errors.DesignError`; None when no model names the key, or one
        names it as a text, list or choice (the string paste stands then).
    """
    from tactcad.errors import DesignError
    from tactcad.vocabulary.schema import field_limits

    found = [field_limits(m, key) for m in _file_models()]
    limits = [f for f in found if f is not None]
    if not limits or any(f.kind not in ("number", "integer") for f in limits):
        return None
    first = limits[0]
    allowed = (f"an integer {first.lo} ... {first.hi}" if first.kind == "integer" else
               f"a number ({first.unit}), {first.text()}" if first.unit else
               f"a number, {first.text()}")
    why = f"{first.why}; " if first.why else ""
    kind = "an integer" if first.kind == "integer" else "a number"
    return DesignError(key, raw, allowed, f"{why}--set {text}: the key takes {kind}, and "
                                          f"{raw} is none: no paste quotes it as a string")


#: A value typed without TOML's quotes (the shell ate them: ``--set design.name="Zélé"``
#: reaches tactcad as ``design.name=Zélé``): no quote, bracket, brace, comma or control
#: character in it.
_WORD = r"[^\s\"'\[\]{},=#\x00-\x1f\x7f]+"
_BARE_WORD = re.compile(f"{_WORD}(?: {_WORD})*")


def quoted_word(key: str, raw: str) -> list[dict]:
    """The paste of a ``--set`` whose value is a bare word that is not a TOML value: the
    word as a TOML string, the whole option quoted against the shell (``--set
    'design.name="Zele"'``); a name the key's own rule refuses (``design.name``, ``die.name``)
    cleaned as that rule's refusal cleans it; none for any other value.

    Args:
        key: the dotted key. raw: its value as typed.

    Returns:
        The alternatives (``option``, ``words``) to paste, or none.
    """
    import shlex

    if not _BARE_WORD.fullmatch(raw):
        return []
    word, words = raw, "the value as a TOML string, its quotes kept from the shell"
    if key in NAME_RULES:
        allowed, cleaned, how = NAME_RULES[key]()
        if not allowed(raw):
            word, words = cleaned(raw), f"{words}: {how}"
    quoted = '"' + word.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return [{"option": "--set " + shlex.quote(f"{key}={quoted}"), "words": words}]


NameRule = tuple[Callable[[str], bool], Callable[[str], str], str]


def _design_name_rule() -> NameRule:
    from tactcad.vocabulary.schema import NAME_PATTERN, suggested_name

    return ((lambda t: re.fullmatch(NAME_PATTERN, t) is not None), suggested_name,
            "the name with accents dropped and other characters as _")


def _die_name_rule() -> NameRule:
    from tactcad.products.silicon_die.design.die_file import (CLEANED_CELL_NAME_WORDS,
                                                              is_cell_name, suggested_cell_name)

    return is_cell_name, suggested_cell_name, CLEANED_CELL_NAME_WORDS


#: Keys whose value is a name a rule refuses: key -> (the rule, the name it offers instead,
#: that name in words), each imported when a refusal asks for it.
NAME_RULES: dict[str, Callable[[], NameRule]] = {"design.name": _design_name_rule,
                                                 "die.name": _die_name_rule}


def parse_overrides(texts: list[str] | None, example: str = SET_EXAMPLE) -> dict[str, Any]:
    """Every ``--set`` in order (a later one for the same key wins, as a repeated option's
    last value does, and is said the same way); ``example`` as :func:`parse_override`
    takes it.

    Warns:
        RepeatedOptionWarning: a key set more than once, naming every value and the one taken.
    """
    import warnings

    from tactcad.errors import RepeatedOptionWarning

    pairs = [parse_override(t, example) for t in texts or ()]
    for key in dict.fromkeys(k for k, _ in pairs):
        given = [text.partition("=")[2].strip() for text, (k, _) in zip(texts or (), pairs)
                 if k == key]
        if len(given) > 1:
            warnings.warn(RepeatedOptionWarning(
                f"--set {key} given {len(given)} times ({', '.join(given)}): the last, "
                f"{given[-1]}, is taken"))
    return dict(pairs)


def set_sources(texts: list[str] | None, example: str = SET_EXAMPLE) -> dict[str, str]:
    """Key -> ``--set KEY=VALUE`` as typed (the last of a key), for
    :meth:`tactcad.errors.DesignErrors.sourced`: a refused value is named as the user gave it,
    not as the design file's.

    Args:
        texts: the ``--set`` texts, in order.
        example: as :func:`parse_override` takes it.

    Returns:
        The source of each key set.
    """
    return {parse_override(t, example)[0]: f"--set {t}" for t in texts or ()}


def plan_from_args(args: argparse.Namespace):
    """The validated :class:`~tactcad.design.array_plan.Plan` of ``--design`` with every ``--set``.

    The overrides are checked by the design validator itself, so an unknown
    key or a value out of range is refused with the field, the value and the
    allowed keys or range, as in the file. The rigs and scenes files beside
    the design are validated with it, before any geometry is built, and every
    refusal of the three files is reported at once.

    Raises:
        DesignError: unreadable file, bad ``--set``, unknown key, value out of range
            (:class:`~tactcad.errors.DesignErrors` lists every one).
    """
    return load_from_args(args).plan


def project_from_args(args: argparse.Namespace):
    """The validated :class:`~tactcad.design.project.Project` (plan, rigs,
    scenes and the three files' hashes) of :func:`load_from_args`.

    Raises:
        DesignError: as :func:`plan_from_args`.
    """
    return load_from_args(args).validated


def refuse_unknown_scenes(project, names) -> None:
    """Refuse ``--scene`` names the project has no scene of, before any work (a check's
    requirements, an export's jobs): the scenes are the design's scenes file's
    (:attr:`tactcad.api.Project.scenes`).

    Args:
        project: the loaded :class:`tactcad.api.Project` or its validated project.
        names: the ``--scene`` values given (``None`` or empty: nothing to check).

    Raises:
        DesignError: naming ``--scene``, the first unknown name and the project's scenes.
    """
    from tactcad.errors import DesignError

    known = list(project.scenes)
    unknown = [n for n in names or () if n not in known]
    if unknown:
        raise DesignError("--scene", unknown[0],
                          "one of the project's scenes: " + ", ".join(known),
                          (f"{len(unknown)} unknown scene names ({', '.join(unknown)}); "
                           if len(unknown) > 1 else "")
                          + "`tactcad scenes` lists each scene with its parts")


def announced_default_design() -> Path:
    """The design a command without ``--design`` works on
    (:func:`tactcad.project_folder.default_design`); where that is the shipped example,
    the run's stderr is headed by a line naming it and how to start a project of one's
    own (:func:`tactcad.commands.notices.announce`): a lab must not read the paper's
    array's numbers as its own.

    Raises:
        DesignError: the working folder holds several design files.
    """
    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.project_folder import default_design

    design = default_design()
    if design == DEFAULT_DESIGN:
        announce_shipped_example()
    return design


def announce_shipped_example() -> None:
    """Head the run's stderr with the line saying it works on the shipped example."""
    from tactcad.commands.notices import announce
    from tactcad.design.array_plan import DEFAULT_DESIGN

    announce(f"design: the shipped example {DEFAULT_DESIGN.stem} (the paper's 2 x 5 "
             f"array): no design file in this folder and no --design; `tactcad new NAME` "
             f"makes a project of your own")


def load_from_args(args: argparse.Namespace):
    """The :class:`tactcad.api.Project` of ``--design`` with every ``--set``
    (:func:`tactcad.api.load`, which the Python API's users call too): an array's, the
    command's own; another product's design file is refused naming the commands that answer
    for it (:meth:`tactcad.products.Product.refusal`).

    Raises:
        DesignError: as :func:`plan_from_args`, or another product's design file.
    """
    from tactcad.api import load
    from tactcad.errors import DesignErrors

    from tactcad.project_folder import product_of

    texts = getattr(args, "overrides", None) or []
    design = getattr(args, "design", None)
    if design is None:
        design = announced_default_design()
    if Path(design).suffix.lower() == ".toml" and Path(design).is_file():
        product = product_of(Path(design))
        if not product.is_default:  # an array command on another product's file
            raise product.refusal(getattr(args, "command", None), Path(design))
    try:
        return load(design, set=parse_overrides(texts))
    except DesignErrors as exc:  # a refused --set value is named as typed (the last of a key)
        raise exc.sourced(set_sources(texts)) from None


def add_cache_args(p: argparse.ArgumentParser,
                   default_words: str = ".tactcad-cache in the working folder") -> None:
    """``--cache DIR`` and ``--no-cache``: the store of finished export jobs and
    of the estimators' heavy results (FEM solves, :func:`tactcad.store.kept_result`),
    for a command that exports or runs the estimators (not ``bench``, which
    measures what each solve costs)."""
    p.add_argument("--cache", metavar="DIR", type=output_folder, default=None,
                   help="store of finished export jobs and FEM results, reused when nothing "
                        f"that shapes them changed (default: {default_words})")
    p.add_argument("--no-cache", action="store_true",
                   help="build, write and solve everything afresh; read and write no store")


def store_from_args(args: argparse.Namespace):
    """The :class:`tactcad.store.Store` the options ask for: ``--cache DIR``, none with
    ``--no-cache``, else the command's own default (``args.default_store(args)``: the
    project folder ``design --out DIR`` writes) or :data:`tactcad.store.DEFAULT_STORE`."""
    from tactcad.store import DEFAULT_STORE, Store

    if args.no_cache:
        return Store(None)
    if args.cache:
        return Store(usable_cache_folder(args.cache))
    # a command that writes a project keeps its results where the project's commands look
    default = getattr(args, "default_store", None)
    return Store(default(args) if default is not None else DEFAULT_STORE)


def design_and_product(args: argparse.Namespace):
    """(design file, :class:`~tactcad.products.Product`) a command works on: ``--design``,
    else the working folder's one design file
    (:func:`tactcad.project_folder.default_design`); None when that is no readable TOML
    file (the array's loader then names what is wrong with it).

    Raises:
        DesignError: the folder holds several design files, or the file is not TOML.
    """
    from tactcad.project_folder import default_design, product_of

    design = Path(args.design) if getattr(args, "design", None) else default_design()
    if design.suffix.lower() != ".toml" or not design.is_file():
        return None
    return design, product_of(design)


def product_view(command: str, args: argparse.Namespace) -> int | None:
    """Run the product's answer to ``command`` when the design a command works on is not the
    default product's (:func:`design_and_product`); None for the default product's design
    (the command goes on with its own code).

    Returns:
        The exit code: 0, or 1 when the report says it did not pass.

    Raises:
        DesignError: the product has no answer to ``command`` (the refusal names those it
            has), or the product's own refusals.
    """
    from tactcad.commands.finite_json import dumps

    found = design_and_product(args)
    if found is None or found[1].is_default:
        return None
    design, product = found
    view = product.view(command)
    if view is None:
        raise product.refusal(command, design)
    report, lines = view(design, args)
    print(dumps(report, indent=1) if getattr(args, "json", False) else "\n".join(lines))
    return 0 if report.get("passed", True) else 1
