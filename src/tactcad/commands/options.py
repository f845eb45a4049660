"""Every option of every command checked before a command runs, as the design file is.

Two layers:

* **per-option types** (``type=`` of ``add_argument``): :func:`number` (a
  finite number in a range, with its unit), :func:`count` (an integer in a
  range) and :func:`material_grade_name` (a grade of the library, matched
  without regard to case where that is unambiguous). argparse calls them, so
  a bad value is refused naming the option, the value and what is allowed.
* **rules for every option** (:func:`validate_options`, run on the parsed
  command line by introspecting the parser, so an option added later is
  covered without being listed anywhere): numbers finite, ``-0`` read as 0,
  text values (paths, names) not empty, without NUL or other control
  characters or bytes that are not UTF-8; an option whose type names a file
  or folder the command writes (:func:`output_file`, :func:`output_folder`,
  :func:`output_file_or_folder`) kept to the output rule
  (:func:`tactcad.atomic.refuse_output_path`).
"""

from __future__ import annotations

import argparse
import math
import unicodedata
from typing import Any, Callable, Iterator, Sequence

from tactcad.errors import DesignError


#: File types a ``--plot`` option writes (matplotlib chooses the format by suffix).
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def _fmt(x: float) -> str:
    return f"{x:g}"


def renamed_option(old: str, new: str, meaning: str) -> Callable[[str], Any]:
    """An argparse type for an option's earlier name: every value is refused, naming the
    option it was renamed to and what that one means.

    Raises (when called by argparse):
        argparse.ArgumentTypeError: always.
    """
    def parse(text: str) -> Any:
        # the value pasted shell-quoted: a drawn or pasted one may hold spaces or newlines
        raise argparse.ArgumentTypeError(f"{text[:40]!r}: {old} is now {new} ({meaning}); "
                                         f"give {new} {pasted_value(text[:40])}")

    return parse


def pasted_value(text: str) -> str:
    """``text`` as one shell word on one line: quoted where it needs it (:func:`shlex.quote`),
    its control characters (a newline, a tab) written as Python escapes."""
    import shlex

    one_line = text if text.isprintable() else repr(text)[1:-1]
    return shlex.quote(one_line)


class RenamedOption(argparse.Action):
    """An option's earlier name, still taken (:func:`add_renamed_option`): hidden from
    ``--help``, it stores its value where the option's new name does and says once that
    the option was renamed and to which name, as a warning of the run
    (:class:`tactcad.errors.RenamedOptionWarning`, :mod:`tactcad.commands.notices`): one
    line on stderr, none with ``--quiet``, and with ``--json`` an entry of the output's
    ``warnings`` list instead of a line.

    Attributes:
        renamed_to: the option's new name (``--force-N``).
    """

    def __init__(self, option_strings: Sequence[str], dest: str, renamed_to: str = "",
                 **kwargs: Any):
        super().__init__(option_strings, dest, **kwargs)
        self.renamed_to = renamed_to
        self.said = False  # the parser is built anew for every run: once per run

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: Any, option_string: str | None = None) -> None:
        import warnings

        from tactcad.errors import RenamedOptionWarning

        setattr(namespace, self.dest, values)
        if not self.said:
            self.said = True
            old = option_string or self.option_strings[0]
            warnings.warn(RenamedOptionWarning(
                f"{old} was renamed {self.renamed_to}; {old} is deprecated and will be "
                f"removed: give {self.renamed_to}"))


def add_renamed_option(parser: argparse.ArgumentParser, old: str,
                       new: argparse.Action) -> argparse.Action:
    """Keep ``old``, an option's earlier name, working as a deprecated alias of ``new``:
    the same dest, type (so the same refusals), default and metavar, hidden from
    ``--help``, and a warning of the run when it is given (:class:`RenamedOption`: a line
    on stderr, none with ``--quiet``, in the ``warnings`` of ``--json``).

    Args:
        parser: the command's parser. old: the earlier name (``--force``).
        new: the action of the option's new name (what ``add_argument`` returned).

    Returns:
        The alias's action.
    """
    return parser.add_argument(old, dest=new.dest, type=new.type, default=new.default,
                               metavar=new.metavar, action=RenamedOption,
                               renamed_to=option_name(new), help=argparse.SUPPRESS)


def number(lo: float | None = None, hi: float | None = None, unit: str = "", *,
           lo_open: bool = False) -> Callable[[str], float]:
    """An argparse type: a finite number ``lo <= x <= hi`` (``lo < x`` with
    ``lo_open``), in ``unit``; ``-0`` is read as 0.

    Raises (when called by argparse):
        argparse.ArgumentTypeError: not a number, not finite, or out of range.
    """
    lo_text = "" if lo is None else f"{'>' if lo_open else '>='} {_fmt(lo)}"
    hi_text = "" if hi is None else f"<= {_fmt(hi)}"
    allowed = "a finite number" + "".join(f" {t}" for t in (lo_text, hi_text) if t) + \
        (f" ({unit})" if unit else "")
    if lo is not None and hi is not None:
        allowed = f"a number {'>' if lo_open else ''}{_fmt(lo)} ... {_fmt(hi)}" + \
            (f" ({unit})" if unit else "")

    def parse(text: str) -> float:
        try:
            x = ascii_float(text)
        except (TypeError, ValueError):
            raise argparse.ArgumentTypeError(f"{text[:40]!r}: allowed {allowed}") from None
        if not math.isfinite(x) or (lo is not None and (x <= lo if lo_open else x < lo)) \
                or (hi is not None and x > hi):
            raise argparse.ArgumentTypeError(f"{text[:40]!r}: allowed {allowed}")
        return x + 0.0  # -0.0 + 0.0 == +0.0

    parse.__name__ = "number"  # argparse names the type in its own messages
    return parse


def ascii_integer(text: str) -> int:
    """An option's integer, in ASCII digits as a design file's TOML takes it (``int`` alone
    reads any script's digits: a full-width ``３`` as 3, which ``--set`` refuses).

    Args:
        text: the option's value.

    Returns:
        The integer (an optional sign, ``_`` between digits as Python and TOML allow).

    Raises:
        ValueError: not an integer, or a character outside ASCII in it.
    """
    if not isinstance(text, str) or not text.isascii():
        raise ValueError(f"{text!r} is no integer in ASCII digits")
    return int(text)


ascii_integer.__name__ = "int"  # argparse names the type in its own messages


def ascii_float(text: str) -> float:
    """An option's number, in ASCII as a design file's TOML takes it (``float`` alone reads
    any script's digits: a full-width ``０.５`` as 0.5, which ``--set`` refuses).

    Args:
        text: the option's value.

    Returns:
        The number (``nan`` and ``inf`` included: a caller bounds it).

    Raises:
        ValueError: not a number, or a character outside ASCII in it.
    """
    if not isinstance(text, str) or not text.isascii():
        raise ValueError(f"{text!r} is no number in ASCII digits")
    return float(text)


ascii_float.__name__ = "float"  # argparse names the type in its own messages


def count(lo: int = 0, hi: int = 2**31 - 1, what: str = "") -> Callable[[str], int]:
    """An argparse type: an integer ``lo <= n <= hi`` (``what`` says of what)."""
    allowed = f"an integer {lo} ... {hi}" + (f" ({what})" if what else "")

    def parse(text: str) -> int:
        try:
            n = ascii_integer(text)
        except (TypeError, ValueError):
            raise argparse.ArgumentTypeError(f"{text[:40]!r}: allowed {allowed}") from None
        if not lo <= n <= hi:
            raise argparse.ArgumentTypeError(f"{text[:40]!r}: allowed {allowed}")
        return n

    parse.__name__ = "integer"
    return parse


def element_number(text: str) -> int | str:
    """An argparse type for ``--element``: the integer given, or the text as given where it is
    none, for :func:`check_element_option` to refuse with the design's own element numbers
    (which the parser, reading no design, does not know).

    Args:
        text: the option's value.

    Returns:
        :func:`ascii_integer` of the text where it is an integer in ASCII digits, else the
        text (at most 40 characters).
    """
    try:
        return ascii_integer(text)
    except (TypeError, ValueError):
        return text[:40]


element_number.__name__ = "element number"


def output_file(*suffixes: str) -> Callable[[str], str]:
    """An argparse type: a file to write, its name ending in one of ``suffixes``
    (any case; any name without them), not an existing folder; the output rule
    (:func:`validate_options`) applies to it."""
    allowed = "a file name" + (" ending in " + " or ".join(suffixes) if suffixes else "")

    def parse(text: str) -> str:
        import os

        if not text.strip() or os.path.isdir(text) or (
                suffixes and not text.lower().endswith(tuple(s.lower() for s in suffixes))):
            raise argparse.ArgumentTypeError(f"{text[:80]!r}: allowed {allowed}")
        return text

    parse.__name__ = "file name"
    parse.writes = lambda text: "a file"  # the output rule (validate_options) applies
    return parse


def output_folder(text: str) -> str:
    """An argparse type: a folder a command writes, or writes into (``--out DIR``, ``--vtk
    DIR``); the output rule (:func:`validate_options`) applies to it."""
    return text


output_folder.__name__ = "folder"
output_folder.writes = lambda text: "a folder"


def output_file_or_folder(*suffixes: str) -> Callable[[str], str]:
    """An argparse type: a file to write where its name ends in one of ``suffixes`` (as
    typed), else a folder to write into (``design --out NEW.toml|DIR``); the output rule
    (:func:`validate_options`) applies to it."""
    allowed = "a file name ending in " + " or ".join(suffixes) + ", or a project folder"

    def parse(text: str) -> str:
        import os

        # an existing file of another kind is neither: said as the option's own choice
        if os.path.isfile(text) and not text.endswith(suffixes):
            raise argparse.ArgumentTypeError(f"{text[:80]!r}: allowed {allowed}")
        return text

    parse.__name__ = "file or folder"
    parse.writes = lambda text: "a file" if text.endswith(suffixes) else "a folder"
    return parse


def material_grade_name(text: str) -> str:
    """An argparse type: a material grade of the library, exact or matched
    without regard to case (or by a prefix or description word only one grade has;
    :func:`tactcad.vocabulary.material_library.match_name`, the matching a design file gets).

    Raises (when called by argparse):
        argparse.ArgumentTypeError: naming the value and listing the grades.
    """
    from tactcad.vocabulary.material_library import candidates, match_name, material_grades

    grades = material_grades()
    found = match_name(grades, text)
    if found is not None:
        return found
    several = candidates(grades, text)
    raise argparse.ArgumentTypeError(f"{text[:40]!r}: allowed one of {', '.join(grades)}"
                                     + (" (ambiguous)" if len(several) > 1 else ""))


material_grade_name.__name__ = "grade"


# ---------------------------------------------------------------------------
# Rules for every option, by introspection of the parser
# ---------------------------------------------------------------------------
def chosen_parsers(parser: argparse.ArgumentParser,
                   args: argparse.Namespace) -> Iterator[argparse.ArgumentParser]:
    """The parser and each sub-command parser the command line chose (``bench export``: three)."""
    yield parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            chosen = getattr(args, action.dest, None)
            if chosen in action.choices:
                yield from chosen_parsers(action.choices[chosen], args)


def option_name(action: argparse.Action) -> str:
    """``--sigma-r`` (the longest option string), or the positional's name."""
    return max(action.option_strings, key=len) if action.option_strings else \
        (action.metavar if isinstance(action.metavar, str) else action.dest)


def _checked_value(name: str, value):
    """``value`` with ``-0.0`` made 0.0; raises for a non-finite number or bad text."""
    if isinstance(value, float):
        if not math.isfinite(value):
            raise DesignError(name, value, "a finite number")
        return value + 0.0
    if isinstance(value, str):
        if not value.strip():
            raise DesignError(name, value, "a non-empty value")
        bad = next((c for c in value if unicodedata.category(c) in ("Cc", "Cs")
                    and c not in "\t"), None)
        if bad is not None and 0xDC80 <= ord(bad) <= 0xDCFF:  # os.fsdecode's surrogateescape
            raise DesignError(name, value, "text in UTF-8 (found a byte that is not UTF-8 "
                                           f"(0x{ord(bad) - 0xDC00:02X}))")
        if bad is not None:
            raise DesignError(name, value, f"text without control characters (found "
                                           f"U+{ord(bad):04X})")
    return value


def _output_rule(action: argparse.Action, name: str, value) -> None:
    """The output rule (:func:`tactcad.atomic.refuse_output_path`) for an option whose type
    names a file or folder the command writes (its ``writes``), before any work."""
    writes = getattr(action.type, "writes", None)
    if writes is None or not isinstance(value, str):
        return
    from tactcad.atomic import refuse_output_path

    refuse_output_path(name, value, writes(value))


def validate_options(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Apply the rules for every option (module doc) to a parsed command line,
    in place (``-0`` becomes 0).

    Raises:
        DesignError: naming the option, the value and what is allowed.
    """
    for p in chosen_parsers(parser, args):
        for action in p._actions:
            if isinstance(action, (argparse._SubParsersAction, argparse._HelpAction,
                                   argparse._VersionAction)) or not hasattr(args, action.dest):
                continue
            value = getattr(args, action.dest)
            if value is None or value is action.default and action.option_strings:
                continue
            name = option_name(action)
            if isinstance(value, list):
                setattr(args, action.dest, [_checked_value(name, v) for v in value])
            elif isinstance(value, tuple):
                setattr(args, action.dest, tuple(_checked_value(name, v) for v in value))
            else:
                setattr(args, action.dest, _checked_value(name, value))
                _output_rule(action, name, value)


def warn_repeated(parser: argparse.ArgumentParser, args: argparse.Namespace,
                  argv: Sequence[str]) -> None:
    """Say which value is taken when an option of one value is given twice
    (``--verify fem3d --verify auto``): the last, as argparse takes it, so that an
    alternative a refusal names can be pasted at the end of the command line. Options that
    gather (``--set``: a key it sets twice is said by :func:`tactcad.commands.parse_overrides`)
    and flags may repeat without a word.

    Warns:
        RepeatedOptionWarning: naming the option, every value given and the one taken.
    """
    import warnings

    from tactcad.errors import RepeatedOptionWarning

    given = list(argv[:argv.index("--")] if "--" in argv else argv)
    for p in chosen_parsers(parser, args):
        for action in p._actions:
            if type(action) is not argparse._StoreAction or not action.option_strings:
                continue
            # an earlier name (RenamedOption) sets the same value: said as one option
            names = (*action.option_strings,
                     *(s for a in p._actions if isinstance(a, RenamedOption)
                       and a.dest == action.dest for s in a.option_strings))
            spots = [i for i, token in enumerate(given)
                     if token in names or token.startswith(tuple(f"{o}=" for o in names))]
            if len(spots) > 1:
                values = [given[i].split("=", 1)[1] if "=" in given[i] else
                          " ".join(given[i + 1:i + 1 + _arity(action)]) for i in spots]
                warnings.warn(RepeatedOptionWarning(
                    f"{option_name(action)} given {len(spots)} times ({', '.join(values)}): "
                    f"the last, {values[-1]}, is taken"))


def _arity(action: argparse.Action) -> int:
    """How many words an option's value takes (1 unless ``nargs`` is a count)."""
    return action.nargs if isinstance(action.nargs, int) else 1


def options_of(parser: argparse.ArgumentParser,
               path: Sequence[str] = ()) -> Iterator[tuple[tuple[str, ...], argparse.ArgumentParser]]:
    """Every command (``("bench", "export")``) and its parser, for tests and fuzzing."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if path and not subs:
        yield tuple(path), parser
    for action in subs:
        for name, sub in action.choices.items():
            yield from options_of(sub, (*path, name))


#: The options a command's every mode takes alike: the design and its overrides, the result
#: store and the output (their dests), with argparse's own ``func``/``command``.
#: The grasp's fields and the options that set them (an error names the option).
GRASP_OPTION_OF = {"force_N": "--force-N", "angle_deg": "--angle-deg",
                   "jaw.pivot_u_mm": "--pivot-mm", "jaw.pivot_v_mm": "--pivot-mm",
                   "jaw.pin_to_tip_mm": "--pin-to-tip-mm",
                   "jaw.opening_angle_deg": "--opening-deg",
                   "jaw.slab_thickness_mm": "--slab-thickness-mm", "k_obj_N_per_mm": "--kobj",
                   "channel_diameter_mm": "--lead-channel-mm"}

def grasp_option_error(exc, args: Any):
    """A grasp error re-worded to name the command-line option that set its field
    (:data:`GRASP_OPTION_OF`); an option of several values (``--pivot-mm X Y``) is said with
    all of them as given, not with the one coordinate its field holds.

    Args:
        exc: the :class:`~tactcad.errors.DesignError` of a grasp field.
        args: the command line whose option gave the value, or anything with the same
            attributes (the API's :class:`~tactcad.studies.grasp_report.GraspAsked`).

    Returns:
        The error naming the option, or ``exc`` when no option sets its field.
    """
    from tactcad.errors import DesignError
    from tactcad.in_use.grasp_experiment import UnsettledContact

    if isinstance(exc, UnsettledContact):
        return unsettled_slab_error(exc, getattr(args, "slab_thickness_mm", None))
    option = GRASP_OPTION_OF.get(exc.field)
    if option is None:
        return exc
    given = getattr(args, option.removeprefix("--").replace("-", "_"), None)
    value = list(given) if isinstance(given, (list, tuple)) else exc.value
    why = exc.why
    if given is None and exc.field == "jaw.slab_thickness_mm":  # the grasp's own default
        why = (f"{why}; " if why else "") + f"{option} not given: {exc.value:g} mm is its default"
    return DesignError(option, value, exc.allowed, why, alternatives=exc.alternatives)


def unsettled_slab_error(exc, given_mm: float | None):
    """An unsettled contact (:class:`~tactcad.in_use.grasp_experiment.UnsettledContact`)
    said as ``--slab-thickness-mm``: its value (as given, else the default thickness the
    grasp was solved on) and the thicker range of the option to give, whether the option
    was given or not.

    Args:
        exc: the refusal; its ``value`` is the thickness solved on (mm) where its field is
            ``jaw.slab_thickness_mm``.
        given_mm: ``--slab-thickness-mm`` as given (mm), None at its default.

    Returns:
        A :class:`~tactcad.errors.DesignError` of ``--slab-thickness-mm``.
    """
    from tactcad.errors import DesignError
    from tactcad.in_use.grasp_experiment import ACTIVE_SET_PASSES
    from tactcad.studies.grasp_report import GRASP_NUMBERS

    solved = exc.value if exc.field == "jaw.slab_thickness_mm" else None
    slab = given_mm if given_mm is not None else solved
    hi = GRASP_NUMBERS["slab_thickness_mm"][1]
    allowed = (f"> {slab:g} ... {hi:g} mm (a slab thicker than {slab:g} mm, on which the "
               "contact settles)" if isinstance(slab, (int, float)) else
               f"a thicker slab, at most {hi:g} mm, on which the contact settles")
    on = f"a {slab:g} mm slab" if isinstance(slab, (int, float)) else "the slab"
    why = (f"the tips' contact (their stops and lift-off) did not settle within "
           f"{ACTIVE_SET_PASSES} passes of its solve on {on}")
    why += (": give a thicker one" if given_mm is not None else
            ", the default thickness (--slab-thickness-mm not given: the design's "
            "[tissue_slab] or the assumed one): give a thicker one with --slab-thickness-mm")
    return DesignError("--slab-thickness-mm", slab, allowed, why)


COMMON_OPTIONS = frozenset({"design", "overrides", "json", "quiet", "cache", "no_cache", "func",
                            "command"})


def keep_option_defaults(parser: argparse.ArgumentParser) -> None:
    """Remember the parser's option defaults on its namespace (``option_defaults``), so that a
    mode of the command can tell an option the user set from one left at its default
    (:func:`options_given`)."""
    parser.set_defaults(option_defaults={a.dest: a.default for a in parser._actions
                                         if a.dest != "help"})


def options_given(args: argparse.Namespace, besides: Sequence[str]) -> list[tuple[str, object]]:
    """(``--option``, value) of every option set away from its default (a parser that
    :func:`keep_option_defaults` marked), but those whose dest is in ``besides``."""
    defaults = getattr(args, "option_defaults", None) or {}
    return [("--" + dest.replace("_", "-"), getattr(args, dest))
            for dest, default in defaults.items()
            if dest not in besides and dest != "option_defaults"
            and getattr(args, dest, default) != default]


def check_element_option(number: int, plan) -> None:
    """Refuse an ``--element`` that is none of the design's element numbers, by the option's
    name (the design's own lookup names its argument, not the option).

    Args:
        number: ``--element`` as given (:func:`element_number`: an integer, or the text
            where it is none).
        plan: the design's plan (its ``slots``, numbered 1 ... rows x columns).

    Raises:
        DesignError: ``--element``, its value and the design's element numbers.
    """
    numbers = sorted(s.number for s in plan.slots)
    if not isinstance(number, int) or number not in numbers:
        raise DesignError("--element", number,
                          f"an integer {numbers[0]} ... {numbers[-1]} (the design's element "
                          "numbers)")
