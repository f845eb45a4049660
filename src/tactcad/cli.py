"""Command-line entry point ``tactcad``.

Each sub-command lives in a module of :mod:`tactcad.commands` that defines
``register(subparsers)``. Command modules import the CAD kernel and FEM
libraries only inside their handlers, so ``tactcad --help`` and the
closed-form commands start fast.
"""

from __future__ import annotations

import argparse
import atexit
import errno
import importlib
import json
import os
import re
import sys
from typing import NoReturn

from tactcad.version import VERSION
from tactcad.errors import DesignError, TactcadError
from tactcad.stopping import (ENDING_SIGNALS, act_on_held_stop, end_child_processes,
                              exit_at_once_on_stop)

#: Exit codes: 0 done, 1 a check failed, 2 bad input (a named field, value and
#: allowed range), 3 a file-system error (path and cause), 130 interrupted.
EXIT_INPUT = 2
EXIT_OS = 3
EXIT_INTERRUPTED = 130

#: Each command (its first word) and the module that registers it; ``bench``'s
#: own sub-commands live in its module. Only the module of the command run is
#: imported (a few seconds less start-up than importing all of them).
COMMANDS: dict[str, str] = {
    "new": "tactcad.commands.new",
    "export": "tactcad.commands.export",
    "check": "tactcad.commands.check",
    "verify": "tactcad.commands.verify",
    "scenes": "tactcad.commands.scenes",
    "bench": "tactcad.commands.bench",
    "stiffness": "tactcad.commands.mechanics",
    "table1": "tactcad.commands.mechanics",
    "modal": "tactcad.commands.modal",
    "lumped": "tactcad.commands.lumped",
    "evaluate": "tactcad.commands.evaluate",
    "table2": "tactcad.commands.table2",
    "calibrate": "tactcad.commands.calibrate",
    "strength": "tactcad.commands.strength",
    "tolerance": "tactcad.commands.tolerance",
    "readout": "tactcad.commands.readout",
    "thermal": "tactcad.commands.thermal",
    "budget": "tactcad.commands.budget",
    "grasp": "tactcad.commands.grasp",
    "crosstalk": "tactcad.commands.crosstalk",
    "materials": "tactcad.commands.materials",
    "sweep": "tactcad.commands.sweep",
    "design": "tactcad.commands.design",
    "atlas": "tactcad.commands.atlas",
    "die": "tactcad.commands.die",
    "diff": "tactcad.commands.diff",
    "watch": "tactcad.commands.watch",
}
#: Each command's one-line summary, as ``tactcad --help`` lists it: the top-level help
#: and ``--version`` build the list from here and import no command module (a test holds
#: it equal to what each module registers).
SUMMARIES: dict[str, str] = {
    "new": "make a sensor project folder: design, rigs, scenes, README, CI workflow",
    "export": "write STEP, wire-EDM DXF, scenes, drawings, BOM and manifest",
    "check": "run part, DXF, STEP and interference checks",
    "verify": "verification matrix: each requirement, its prediction, margin and pass",
    "scenes": "list the scenes (array, wire-cut layout, test rigs) and their parts",
    "bench": ("speed benchmarks (export, stiffness, modal, die, atlas, closed-form, "
              "montecarlo, sweep)"),
    "stiffness": "tip stiffness K (N/mm) of one element at a ladder level",
    "table1": "predicted vs measured stiffness of every element (Table 1)",
    "modal": "natural frequencies (Hz) of each element as clamped",
    "lumped": "lumped model of a stiffness sensing unit: R from K_obj or K_obj from R",
    "evaluate": "simulate the array evaluation rig: R per element, sample and load step",
    "table2": "each model's error against the paper's 48 measured R (Table 2)",
    "calibrate": "fit K, K_v, V0 from calibration readings and audit them against the design",
    "strength": ("every element's force limits and its stress, gauge strain and tip "
                 "deflection at the design's rated full-scale force"),
    "tolerance": "Monte Carlo of the tolerances: K per element, R per unit, K_obj band",
    "readout": ("per element: gauge strain over the grid, K_v, K_v/K, force and "
                "K_obj resolution of the read-out chain"),
    "thermal": ("per element: zero and span drift per kelvin, self-heating offset, "
                "K_obj error per kelvin across the force range, what a dummy gauge "
                "cancels"),
    "budget": ("the K_obj error budget: each source's relative K_obj error over the "
               "K_obj range, their RSS and worst case, the source that dominates"),
    "grasp": ("the grasp as a virtual experiment: a pivoting jaw closes on tissue; "
              "each unit's radii, travels, R and K_obj read, as laid out and paired "
              "at equal radius; the leads through the shaft"),
    "crosstalk": ("crosstalk of an array (clamped stack or comb): n x n gauge "
                  "sensitivity, tip displacements, crosstalk_rel, decoupling matrix"),
    "materials": "list the material grades and strain gauges a design may name",
    "sweep": "design grids, correction refit and Monte Carlo on Dask",
    "design": "inverse design: K_r/K_m, K_obj range and full-scale force -> design file",
    "atlas": ("what fits a jaw: feasible targets and the Pareto front of every "
              "product and material, on Dask"),
    "die": "a silicon MEMS die for a grasper's jaw: plan, GDSII masks, KLayout DRC",
    "diff": "what changed between two exports (or two design files)",
    "watch": "re-export on save and serve the review page (live reload)",
}
#: Every command module, in the order ``tactcad --help`` lists their commands.
COMMAND_MODULES = tuple(dict.fromkeys(COMMANDS.values()))

#: Commands that run until they are stopped (Ctrl-C or an ending signal): a
#: stop is their normal end (exit 0, a "stopped" line) whenever it comes,
#: their start-up included (README: watch).
RUN_UNTIL_STOPPED = ("watch",)


class UsageError(TactcadError):
    """A command line argparse refuses (unknown option, bad choice, missing argument).

    Attributes:
        field, value, allowed: read from argparse's message (:func:`usage_fields`;
            None where it names none), for ``--json``'s error record.
    """

    def __init__(self, parser: argparse.ArgumentParser, message: str):
        self.parser = parser
        self.field, self.value, self.allowed = usage_fields(message)
        super().__init__(message)

    @property
    def errors(self) -> list[DesignError]:
        """One refusal per argument the message names (several for a line missing or not
        knowing several, or holding a bad value and an unknown option): the ``errors`` of
        the JSON record."""
        out = []
        for part in str(self).split("; "):
            named = named_fields(part)
            if named:
                out += [DesignError(name, name if allowed == UNKNOWN_ALLOWED else None, allowed,
                                    "not an option of this command"
                                    if allowed == UNKNOWN_ALLOWED else "required")
                        for name, allowed in named]
            else:
                field, value, allowed = usage_fields(part)
                out.append(DesignError(field or "", value, allowed or part))
        return out


#: argparse's refusal of a required group left out ("one of the arguments --a --b is required").
_ONE_OF = re.compile(r"^one of the arguments (?P<names>.+) is required$")
#: argparse's "argument --verify: ..." head, its option strings joined by "/".
_ARGUMENT = re.compile(r"^argument (?P<names>[^:]+?): (?P<rest>.*)$", re.DOTALL)
_INVALID_CHOICE = re.compile(r"^invalid choice: (?P<value>.*?) \(choose from (?P<choices>.*)\)$",
                             re.DOTALL)
_EXPECTED = re.compile(r"^expected (?P<n>one|\d+) arguments?$")
#: The wording of tactcad's own argparse types (:mod:`tactcad.commands.options`).
_TYPE_REFUSAL = re.compile(r"^(?P<value>'.*?'|\".*?\"): allowed (?P<allowed>.*)$", re.DOTALL)


def _unquoted(text: str) -> str:
    return text[1:-1] if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"" else text


def usage_fields(message: str) -> tuple[str | None, str | None, str | None]:
    """(field, value, allowed) of an argparse refusal: the option (its longest name) or
    positional it names, the value refused and what is allowed, each None where the
    message does not say (argparse 3.11's wording)."""
    message = message.split("; ")[0]  # the first refusal (tactcad appends unknown options)
    group = _ONE_OF.match(message)
    if group is not None:
        names = group["names"].split()
        return names[0], None, "one of " + ", ".join(names)
    head = _ARGUMENT.match(message)
    if head is not None:
        field = max(head["names"].split("/"), key=len)
        rest = head["rest"]
        choice = _INVALID_CHOICE.match(rest)
        if choice is not None:
            return field, _unquoted(choice["value"]), "one of " + choice["choices"].replace("'", "")
        typed = _TYPE_REFUSAL.match(rest)
        if typed is not None:
            return field, _unquoted(typed["value"]), typed["allowed"]
        counted = _EXPECTED.match(rest)
        if counted is not None:
            n = counted["n"]
            return field, None, f"{'1' if n == 'one' else n} value{'' if n == 'one' else 's'} after it"
        return field, None, rest
    for lead, allowed in (("unrecognized arguments: ", UNKNOWN_ALLOWED),
                          ("the following arguments are required: ", MISSING_ALLOWED)):
        if message.startswith(lead):
            first = message[len(lead):].split(", ")[0].split(" ")[0]
            return first, (first if lead.startswith("unrec") else None), allowed
    return None, None, None


#: argparse's lists of missing and unknown arguments (tactcad joins the two with "; ").
_LISTS = (("the following arguments are required: ", ", "), ("unrecognized arguments: ", " "))
#: What a missing and an unknown argument allow.
MISSING_ALLOWED, UNKNOWN_ALLOWED = "a value", "an option of this command (see --help)"


def named_fields(message: str) -> list[tuple[str, str]]:
    """(name, allowed) of every argument a "required" or "unrecognized" refusal names, in
    order (an unknown option's ``=value`` cut off)."""
    out = []
    for part in message.split("; "):
        for (lead, sep), allowed in zip(_LISTS, (MISSING_ALLOWED, UNKNOWN_ALLOWED)):
            if part.startswith(lead):
                out += [(w.split("=")[0], allowed) for w in part[len(lead):].split(sep) if w]
    return out


def command_parser(parser: argparse.ArgumentParser,
                   argv: list[str]) -> tuple[argparse.ArgumentParser, list[str]]:
    """The parser that reads the options of ``argv``'s command (``sweep grid``'s own for
    ``sweep grid``), down the command words from ``parser``.

    Args:
        parser: the command-line parser (:func:`build_parser`).
        argv: the command line (without the program name).

    Returns:
        (that parser, the words after its command words); ``parser`` itself and ``argv``
        when the line names no command.
    """
    command, words = parser, list(argv)
    while words:
        sub = next((a for a in command._actions if isinstance(a, argparse._SubParsersAction)),
                   None)
        if sub is None or words[0] not in sub.choices:
            break
        command, words = sub.choices[words[0]], words[1:]
    return command, words


def unknown_options(parser: argparse.ArgumentParser, argv: list[str]) -> list[str]:
    """The options of ``argv`` its command's parser does not know (a refusal of a missing
    argument names them too: argparse stops at the first)."""
    command, words = command_parser(parser, argv)
    if command is parser:
        return []
    known = command._option_string_actions
    return [w for w in words if w.startswith("-") and not re.match(r"^-\d", w)
            and w != "--" and w.split("=")[0] not in known]


class Parser(argparse.ArgumentParser):
    """An argument parser that raises :class:`UsageError` instead of exiting, so
    ``main`` can report a bad command line as JSON when ``--json`` is given."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)  # --foo is no --footprint: a typo is refused
        super().__init__(*args, **kwargs)

    def error(self, message: str):  # argparse's hook; it must not return
        raise UsageError(self, message)


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The command-line parser. Given the command line, it registers only the command it
    names (:data:`COMMANDS`); for a line naming none (``--version``, ``--help``, a typo
    argparse then refuses with the full list), every command by its summary alone
    (:data:`SUMMARIES`: no command module imported, so that start-up stays short); for
    None, every command with all its options (the reference docs, the tests).

    Args:
        argv: the command line (without the program name), or None for every command.

    Returns:
        the parser.
    """
    parser = Parser(
        prog="tactcad",
        description="Generate CAD, wire-EDM DXF and stiffness estimates for spring-based "
                    "tactile sensor arrays. Units: mm, N, MPa, N/mm, s.")
    parser.add_argument("--version", action="version", version=f"tactcad {VERSION}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    named = COMMANDS.get(command_of(argv or []) or "")
    if argv is not None and not named:
        # only the list of commands is shown or refused: no command's options are read
        for command, summary in SUMMARIES.items():
            sub.add_parser(command, help=summary)
        return parser
    for name in (named,) if named else COMMAND_MODULES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name == name:  # command module not part of this build
                continue
            raise
        module.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run one command; the exit code (see the ``EXIT_*`` constants).

    With ``--json`` an error is printed on stdout as one JSON object
    ``{"error": {"message", "field", "value", "allowed", "alternatives", "exit_code"}}``
    (see :func:`error_record`); without it as ``tactcad: error: ...`` on stderr.
    """
    try:
        return run_command(argv)
    except BrokenPipeError:  # the reader stopped early (`tactcad scenes | head`): not an error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


def run_command(argv: list[str] | None) -> int:
    """:func:`main` without its guard against a closed stdout: the command
    with its warnings as output (:mod:`tactcad.commands.notices`); with
    ``--json`` the command's JSON object gets them as a ``warnings`` list."""
    import contextlib
    import io

    from tactcad.atomic import forget_changed
    from tactcad.commands.notices import WarningLines, json_with_warnings, print_heads

    argv = sys.argv[1:] if argv is None else list(argv)
    forget_changed()  # what this run writes, for the line an interrupt ends with
    as_json, quiet = "--json" in argv, "--quiet" in argv
    # a stream of JSON lines goes out as it happens; its warnings go to stderr
    streams = as_json and streams_json_lines(argv)
    notes = WarningLines(echo=not (as_json or quiet) or (streams and not quiet))
    captured = io.StringIO()
    with notes.capture(), (contextlib.redirect_stdout(captured) if as_json and not streams
                           else contextlib.nullcontext()):
        code = dispatch(argv, as_json)
    # the design a run worked on heads its stderr; an error stays one line
    heads = print_heads(echo=not (as_json or quiet) and code in (0, 1))
    if as_json and not streams:
        text = captured.getvalue()
        merged = json_with_warnings(text, notes.lines, heads if code in (0, 1) else [])
        sys.stdout.write(text if merged is None else merged + "\n")
        if merged is None and not quiet:
            for line in notes.lines:
                print(f"tactcad: warning: {line}", file=sys.stderr)
    return code


#: Commands whose ``--json`` is a stream of JSON lines, one event a line as it happens
#: (``watch``): their stdout is not held back to merge the warnings into one object.
STREAMING_JSON_COMMANDS = frozenset({"watch"})


def streams_json_lines(argv: list[str]) -> bool:
    """True when ``argv``'s command writes its ``--json`` as a stream of JSON lines
    (:data:`STREAMING_JSON_COMMANDS`): the first word that is not an option names it."""
    command = next((a for a in argv if not a.startswith("-")), None)
    return command in STREAMING_JSON_COMMANDS


def parse_checked(argv: list[str]) -> argparse.Namespace:
    """The parsed command line with every option checked (:mod:`tactcad.commands.options`).

    Raises:
        UsageError: argparse refuses the line (unknown option, bad value for a typed option).
        DesignError: a value the rules for every option refuse (non-finite, empty text).
    """
    from tactcad.commands.options import validate_options, warn_repeated

    parser = build_parser(argv)
    try:
        args = parser.parse_args(argv)
    except UsageError as exc:
        # argparse refuses a command's extra words from the top parser: the help to point
        # to is the command's own (`tactcad lumped --help`), not the list of commands
        command = command_parser(parser, argv)[0] if exc.parser is parser else exc.parser
        unknown = unknown_options(parser, argv)
        if not unknown or _LISTS[1][0] in str(exc):
            if command is exc.parser:
                raise
            raise UsageError(command, str(exc)) from None
        raise UsageError(command, f"{exc}; {_LISTS[1][0]}{' '.join(unknown)}") from None
    warn_repeated(parser, args, argv)
    validate_options(parser, args)
    from tactcad.commands import settle_design

    settle_design(args)
    return args


def dispatch(argv: list[str], as_json: bool) -> int:
    """Parse, check every option (:mod:`tactcad.commands.options`), run; every
    error a user can act on becomes one line (or the JSON error) and its exit code."""
    from tactcad.errors import COMMAND_LINE_RUN

    # refusals say the command's options (tactcad.api.keyword_errors); an API call after
    # this run in the same process (a test, a notebook) names its keywords again
    running = COMMAND_LINE_RUN.set(True)
    try:
        return _dispatched(argv, as_json)
    finally:
        COMMAND_LINE_RUN.reset(running)


def _dispatched(argv: list[str], as_json: bool) -> int:
    """:func:`dispatch`'s work, while :data:`tactcad.errors.COMMAND_LINE_RUN` is set."""
    try:
        from tactcad.drawings.source_date import epoch_date

        # before any import reads it (numpy's f2py turns a bad value into a traceback)
        epoch_date(os.environ)
        args = parse_checked(argv)
        if not getattr(args, "func", None):
            build_parser(argv).print_help()
            return EXIT_INPUT
        if not hasattr(args, "no_cache"):  # a command without a store (bench: costs)
            return int(args.func(args) or 0)
        from tactcad.commands import store_from_args
        from tactcad.store import keeping_results

        # a FEM result one command solved is reused by the next (--cache, --no-cache)
        with keeping_results(store_from_args(args)):
            return int(args.func(args) or 0)
    except UsageError as exc:  # argparse's wording, on one line
        if as_json:
            return report_error(error_record(exc, EXIT_INPUT), as_json)
        from tactcad.commands.notices import print_unsaid

        print_unsaid()
        print(f"{exc.parser.prog}: error: {exc} (see {exc.parser.prog} --help)", file=sys.stderr)
        return EXIT_INPUT
    except TactcadError as exc:
        return report_error(error_record(exc, EXIT_INPUT), as_json)
    except BrokenPipeError:  # not a file-system error: main's guard handles it
        raise
    except OSError as exc:
        record = error_record(exc, EXIT_OS, os_error_text(exc))
        record["field"] = exc.filename
        return report_error(record, as_json)
    except KeyboardInterrupt as exc:
        return report_interrupt(exc, as_json, command_of(argv))
    except ImportError as exc:
        # Ctrl-C while a compiled module (the CAD kernel) initialises surfaces
        # as "ImportError: initialization failed" caused by the interrupt
        if isinstance(exc.__cause__, KeyboardInterrupt):
            return report_interrupt(exc.__cause__, as_json, command_of(argv))
        raise


def command_of(argv: list[str]) -> str | None:
    """The command a command line names (its first word that is not an option), if any."""
    return next((word for word in argv if not word.startswith("-")), None)


def report_interrupt(exc: KeyboardInterrupt, as_json: bool, command: str | None = None) -> int:
    """One line (or one JSON error) for Ctrl-C (:data:`EXIT_INTERRUPTED`) or
    a terminating signal (128 + its number: 143 for SIGTERM, 129 for SIGHUP);
    for a command of :data:`RUN_UNTIL_STOPPED`, its normal end: the line
    ``<command>: stopped`` (with ``--json`` the event ``{"event": "stopped"}``
    on stdout) and 0."""
    import signal

    from tactcad.errors import Terminated

    if command in RUN_UNTIL_STOPPED:
        if as_json:
            print(json.dumps({"event": "stopped", "text": "stopped"}), flush=True)
        else:
            print(f"{command}: stopped", file=sys.stderr, flush=True)
        return 0
    if isinstance(exc, Terminated):
        code = 128 + exc.signum
        message = f"terminated by {signal.Signals(exc.signum).name}; {files_left_said()}"
    else:
        code, message = EXIT_INTERRUPTED, f"interrupted; {files_left_said()}"
    if as_json:
        return report_error(error_record(exc, code, message), as_json)
    print(f"tactcad: {message}", file=sys.stderr)
    return code


def files_left_said() -> str:
    """What an interrupted run left, in words: the previous files as they were, or, once it
    has written something in place (:func:`tactcad.atomic.changed_paths`, e.g. ``check``'s
    export before its checks), what it wrote."""
    from tactcad.atomic import changed_paths

    written = changed_paths()
    if not written:
        return "the previous files are left as they were"
    shown = ", ".join(written[:3]) + (f" and {len(written) - 3} more" if len(written) > 3 else "")
    return f"this run had already written {shown} before it; the other files are left as they were"


def end_like_ctrl_c() -> None:
    """Make SIGTERM and SIGHUP raise :class:`tactcad.errors.Terminated` in the
    main thread, so every run's Ctrl-C path (children stopped, staging removed,
    one line) serves them too; by default they end the process at once."""
    import signal

    from tactcad.errors import Terminated

    def ending(signum: int, frame) -> None:
        for name in ENDING_SIGNALS:  # a second signal while cleaning up is not a new error
            signal.signal(getattr(signal, name), signal.SIG_IGN)
        raise Terminated(signum)

    for name in ENDING_SIGNALS:
        signal.signal(getattr(signal, name), ending)


def error_record(exc: BaseException, exit_code: int, message: str | None = None) -> dict:
    """The fields of an error: message, field, value and allowed range (None
    where the error names none), what to ask instead (``alternatives``, each
    with the ``option`` to paste; empty where the error names none), every
    error of several (``errors``: field, value, allowed, why; only where there
    are several), the design limit's code where one refuses it (``limit``,
    :data:`tactcad.vocabulary.binding_limits.BINDING_LIMITS`) and the exit code."""
    record = {"message": str(exc) if message is None else message,
              "field": getattr(exc, "field", None), "value": getattr(exc, "value", None),
              "allowed": getattr(exc, "allowed", None),
              "alternatives": list(getattr(exc, "alternatives", None) or ()),
              "exit_code": exit_code}
    if getattr(exc, "limit", ""):  # the design limit that refuses it, as a code
        record["limit"] = exc.limit
    several = getattr(exc, "errors", ())
    if len(several) > 1:
        record["errors"] = [{"field": e.field, "value": e.value, "allowed": e.allowed,
                             "why": e.why} for e in several]
    return record


def report_error(record: dict, as_json: bool) -> int:
    """Print an error record (JSON on stdout, or one line on stderr, after the warnings
    issued before it that ``--quiet`` kept back: :func:`tactcad.commands.notices.print_unsaid`);
    its exit code."""
    from tactcad.commands.finite_json import finite
    from tactcad.commands.notices import print_unsaid

    if as_json:
        print(json.dumps({"error": finite(record)}, indent=2, default=str, allow_nan=False))
    else:
        print_unsaid()
        print(f"tactcad: error: {record['message']}", file=sys.stderr)
        for alt in record.get("alternatives") or ():  # those the message does not quote
            if alt.get("option") and alt["option"] not in record["message"]:
                words = f" ({alt['words']})" if alt.get("words") else ""
                print(f"  to paste: {alt['option']}{words}", file=sys.stderr)
    return record["exit_code"]


def os_error_text(exc: OSError) -> str:
    """One line for a file-system error: the path and the cause, a full disk said as such."""
    cause = {errno.ENOSPC: "disk full", errno.EDQUOT: "disk quota exceeded",
             errno.EROFS: "read-only file system", errno.EACCES: "permission denied",
             errno.EPERM: "permission denied"}.get(exc.errno, exc.strerror or type(exc).__name__)
    paths = [p for p in (exc.filename, exc.filename2) if p]
    return (f"{paths[0]}: {cause}" if paths else cause) + (
        "" if cause == (exc.strerror or "") else f" ({exc.strerror})" if exc.strerror else "")


def console(argv: list[str] | None = None) -> NoReturn:
    """The ``tactcad`` program: :func:`main`, then the process ends without
    the interpreter's teardown, which costs 0.8 s once the CAD kernel is
    loaded (OpenCascade's objects and modules freed one by one) and frees
    nothing the OS would not. Output is flushed and the ``atexit`` handlers
    (temporary folders left to a finaliser) run first; an export has closed
    its worker process before it returns; a child process still running then
    is killed (``multiprocessing``'s exit would wait for it). A stop signal
    from then on ends the process at once with the command's code
    (:func:`tactcad.stopping.exit_at_once_on_stop`). A stop that came while
    the program loaded (:mod:`tactcad.__main__` holds them) or before
    :func:`main` could catch it is the command's interrupt all the same."""
    args = sys.argv[1:] if argv is None else list(argv)
    try:  # a stop before main's own guard (held while loading, or in its first imports)
        end_like_ctrl_c()
        act_on_held_stop()
        code = main(args)
    except KeyboardInterrupt as exc:
        code = report_interrupt(exc, "--json" in args, command_of(args))
    exit_at_once_on_stop(code)
    end_child_processes()
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except BrokenPipeError:
        pass
    atexit._run_exitfuncs()
    os._exit(code)


if __name__ == "__main__":
    console()
