"""Errors that a user can act on: each names the field, the value and the allowed range."""

from __future__ import annotations

from contextvars import ContextVar

from pathlib import PurePath
from typing import Iterable, Mapping

#: The reason a design file's table of no known name is refused: a ``--set`` of a key in
#: it (``--set nope.x=1``) is what brought the table, so its refusal names that option.
UNKNOWN_SECTION = "unknown section"

#: Longest echo of a user's value in a message (a 100 000-entry list must not
#: turn into a 500 kB error line).
MAX_VALUE_CHARS = 80


def short_repr(value: object, limit: int = MAX_VALUE_CHARS) -> str:
    """``repr(value)`` cut to ``limit`` characters, with the size of what was
    cut. A string keeps its end too: a long path still names its file."""
    try:
        text = repr(value)
    except (ValueError, RecursionError):  # e.g. an int too long to print
        return f"<{type(value).__name__}>"
    if len(text) <= limit:
        return text
    if isinstance(value, (str, PurePath)):  # the count is the value's, not its quoted repr's
        head = limit // 2
        return f"{text[:head]}...{text[head - limit:]} ({len(str(value))} characters)"
    size = f"{len(value)} items, " if isinstance(value, (list, tuple, dict)) else ""
    return f"{text[:limit]}... ({size}{len(text)} characters)"


def file_value_repr(value: object, limit: int = MAX_VALUE_CHARS) -> str:
    """A value read from a TOML file as a refusal echoes it: :func:`short_repr`, with a
    boolean (in a list too) in TOML's spelling, ``true``/``false``, as the file holds it
    (Python's ``True`` is no TOML: pasted back it is refused)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)) and any(isinstance(v, bool) for v in value):
        text = "[" + ", ".join(file_value_repr(v, limit) for v in value) + "]"
        return text if len(text) <= limit else short_repr(value, limit)
    return short_repr(value, limit)


class TactcadError(Exception):
    """Base of all errors tactcad reports to a user (CLI exit code 2)."""


class DesignError(TactcadError, ValueError):
    """A design file value is missing, unknown or outside its allowed range.

    Attributes:
        field: dotted key in the design file, e.g. ``element.web_thickness_mm``.
        value: the offending value (``None`` when the key is missing).
        allowed: human-readable allowed range or set, with units.
        why: the physical reason for the range ("" when it goes without saying).
        file: the file the field belongs to ("" when not known).
        alternatives: what to ask instead, each a dict with at least
            ``option`` (the options to paste, e.g. ``--full-scale-force 0.077``)
            and ``words`` (what it gives); empty when the error names none.
        limit: the design limit that refuses it, a code of
            :data:`tactcad.vocabulary.binding_limits.BINDING_LIMITS` ("" when the refusal
            is of a value, not of a design limit).
    """

    def __init__(self, field: str, value: object, allowed: str, why: str = "", file: str = "",
                 alternatives: Iterable[dict] = (), limit: str = ""):
        self.field = field
        self.limit = limit
        self.value = value
        self.allowed = allowed
        self.why = why
        self.file = file
        self.alternatives = [dict(a) for a in alternatives]
        super().__init__(self.line())

    def line(self) -> str:
        """``file: field = value: allowed ... (why)``; a field with no value (missing, or
        an option not given) reads ``field (not given): allowed ...``, never ``= None``; a
        value of a file (or a ``--set``) with its booleans as TOML spells them
        (:func:`file_value_repr`)."""
        given = (" (not given)" if self.value is None else
                 f" = {file_value_repr(self.value) if self.file else short_repr(self.value)}")
        text = f"{self.field}{given}: allowed {self.allowed}"
        if self.why:
            text += f" ({self.why})"
        return f"{self.file}: {text}" if self.file else text


class RequirementFailure(DesignError):
    """A design's requirement that its own prediction fails (``field``:
    ``requirements.<name>``, ``value``: the target): the design would fail its own
    ``check``. Unlike a target the search derives from the options, no option names it."""


class DesignErrors(DesignError):
    """Every error found in one validation pass of the design files.

    ``field``, ``value``, ``allowed`` and ``why`` are the first error's; ``errors``
    holds them all; the message lists one per line.
    """

    def __init__(self, errors: Iterable[DesignError], alternatives: Iterable[dict] = (),
                 what: str = "the design files"):
        self.errors = tuple(errors)
        if not self.errors:
            raise ValueError("DesignErrors needs at least one error")
        first = self.errors[0]
        super().__init__(first.field, first.value, first.allowed, first.why, first.file,
                         alternatives or first.alternatives)
        lines = [e.line() for e in self.errors]
        head = lines[0] if len(lines) == 1 else f"{len(lines)} errors in {what}:\n  " + \
            "\n  ".join(lines)
        self.args = (head,)

    def __str__(self) -> str:
        return self.args[0]

    def sourced(self, sources: Mapping[str, str]) -> "DesignErrors":
        """These errors, each whose field is a key of ``sources`` or a part of
        one (``arms.lengths_mm[3]`` of ``arms.lengths_mm``) named as coming
        from ``sources[key]`` instead of its file: a value given elsewhere
        than the file (``--set KEY=VALUE``) is refused as given there."""
        def source(e: DesignError) -> str:
            return next((src for key, src in sources.items()
                         if e.field == key or e.field.startswith((key + "[", key + "."))
                         or (key.startswith(e.field + ".") and e.why == UNKNOWN_SECTION)),
                        e.file)

        return DesignErrors(DesignError(e.field, e.value, e.allowed, e.why, source(e),
                                        sourced_alternatives(e, source(e)))
                            for e in self.errors)


def sourced_alternatives(error: DesignError, source: str) -> list[dict]:
    """``error``'s alternatives as pasted where its value was given: one that writes the
    field's line of the design file (``design.name = "x"``) becomes the ``--set`` that sets
    it when ``source`` is a ``--set``; every other alternative as it is.

    Args:
        error: a design file's refusal.
        source: where its value came from (the file, or ``--set KEY=VALUE`` as typed).

    Returns:
        The alternatives, in order.
    """
    import shlex

    line = f"{error.field} = "
    if not source.startswith("--set "):
        return list(error.alternatives)
    return [{**a, "option": "--set " + shlex.quote(f"{error.field}={a['option'][len(line):]}")}
            if str(a.get("option", "")).startswith(line) else a for a in error.alternatives]


class SceneError(TactcadError):
    """An unknown scene or group, a bad scenes file, or a rig that cannot be
    assembled (a slide would leave its range)."""


class ExportPathError(TactcadError):
    """An export folder tactcad will not write: a system folder, a file, or a
    folder of other files."""


class CheckFailure(TactcadError):
    """A geometry, export or manufacturability check failed."""


class RepeatedOptionWarning(UserWarning):
    """An option of one value given more than once: the last is taken, as argparse does
    (a pasted alternative appended to the command line replaces the value before it)."""


class RenamedOptionWarning(UserWarning):
    """An option given by its earlier name (:func:`tactcad.commands.options.add_renamed_option`):
    taken, and said renamed to its new name (a user's warning, not Python's
    ``DeprecationWarning``, which a run drops)."""


#: True while a command of the command line runs (:func:`tactcad.cli.dispatch`): the API's
#: methods it calls keep their refusals in the command's option names, not their keyword
#: arguments' (:func:`tactcad.api.keyword_errors`).
COMMAND_LINE_RUN: "ContextVar[bool]" = ContextVar("tactcad_command_line_run", default=False)


class PastRatingWarning(UserWarning):
    """A force asked of a command lies past the design's rated full-scale force (a reading
    past full scale), or past an element's overload limit (named in the message); or a
    sample's K_obj outside the design's required K_obj range."""


class CalibrationAuditWarning(UserWarning):
    """A calibration file a budget reads has what ``tactcad calibrate --data`` flags in it:
    an element of the design without readings, a K far off the design, a signal per newton
    off the other elements' gain (named in the message)."""


class CoarseReadingWarning(UserWarning):
    """A written design reads K_obj only to within more than its own size (a K_obj
    resolution over 100 %): it is written, but what it reads does not tell a tissue from one
    twice or half as stiff."""


class JawNotJudgedWarning(UserWarning):
    """A design states a ``[grasper_jaw]`` table its construction is not judged against (the
    stacked array does not seat in a jaw): the message names the table and the
    constructions that are."""


class LeftoverWarning(UserWarning):
    """Files of an earlier or failed run that could not be removed (named in the message)."""


class FreecadFailedWarning(UserWarning):
    """FreeCAD (``freecadcmd``) failed: the export is written without its FreeCAD review
    files (the message names FreeCAD's exit and the file holding its output)."""


class FreecadAheadWarning(UserWarning):
    """The FreeCAD started ahead of an export's kernel import gave no answer in time: it
    was ended and the review files were written by a FreeCAD started for them (the message
    names the wait)."""


class HandEditedWarning(UserWarning):
    """Files of an earlier export changed by hand since it was written, which a partial
    export keeps as they are but no longer lists as the export's (named in the message)."""


class Terminated(KeyboardInterrupt):
    """The process was asked to end by a signal (SIGTERM from a CI runner or
    ``kill``, SIGHUP from a closed terminal): handled like Ctrl-C, so the run
    cleans up (children stopped, staging folders removed) before it exits with
    128 + the signal's number.

    Attributes:
        signum: the signal's number (15 SIGTERM, 1 SIGHUP).
    """

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum
