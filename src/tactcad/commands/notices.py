"""Warnings as part of a command's output, never in Python's own format.

Within :func:`WarningLines.capture` every warning a run issues (tactcad's,
e.g. the closed form's ``CorrectionRangeWarning``, or a library's) becomes
one line ``tactcad: warning: ...`` on stderr, once per distinct text per run,
as it happens (but the closed form's range warnings: all of a run's are said as one line
when it ends, naming the worst); ``--quiet`` silences the lines, but for a run that ends in a refusal,
which prints the warnings issued before it first (:func:`print_unsaid`). With ``--json``
they go into the output object as a ``warnings`` list (:func:`json_with_warnings`) instead.
Deprecation, import and resource warnings are for developers and dropped.
"""

from __future__ import annotations

import contextlib
import json
import sys
import warnings
from typing import Iterator

_FOR_DEVELOPERS = (DeprecationWarning, PendingDeprecationWarning, ImportWarning, ResourceWarning)

#: The captures under way (:meth:`WarningLines.capture`), the innermost last.
_CAPTURES: list["WarningLines"] = []

#: Lines that head a run's stderr (what the run works on), printed before its first
#: progress or warning line, or when it ends if it printed none; dropped when it ends in
#: an error (the error stays one line) and under ``--json``/``--quiet``.
_HEADS: list[str] = []


def announce(text: str) -> None:
    """Head this run's stderr with ``tactcad: TEXT`` (see :data:`_HEADS`)."""
    if text not in _HEADS:
        _HEADS.append(text)


def print_heads(echo: bool = True) -> list[str]:
    """Print (when ``echo``) and forget the announced heads; returns them (for ``--json``,
    whose object carries them as ``notices``)."""
    heads = list(_HEADS)
    _HEADS.clear()
    for text in heads if echo else ():
        print(f"tactcad: {text}", file=sys.stderr, flush=True)
    return heads


def one_line(message: object) -> str:
    """The warning's text on one line (whitespace runs made one space)."""
    return " ".join(str(message).split())


class WarningLines:
    """The distinct warnings of one run, in order; echoed to stderr when ``echo``.

    A warning whose object has a ``fold_as`` text (one of many alike, e.g. each element
    geometry outside a fit) is shown the first time; the others of that text are counted
    and told in one closing line, with the largest ``error_rel`` they carry.
    A warning whose object has a ``merge_as`` text (the closed form's
    :class:`~tactcad.mechanics.correction.CorrectionRangeWarning`: each element, and each
    end of its web tolerance, outside the correction's fit) is held, and all of a run's
    are said as one line when the run ends (or before its refusal), made by the warning
    class's ``merged_text`` (each coordinate's values over all of them, the worst's error).
    ``categories`` keeps each line's warning category (a closing line: its first warning's).
    """

    def __init__(self, echo: bool):
        self.echo = echo
        self.lines: list[str] = []
        self.categories: dict[str, type[Warning]] = {}
        self.folded: dict[str, dict[str, float]] = {}  # fold -> its other texts' errors
        self.fold_categories: dict[str, type[Warning]] = {}
        self.merging: dict[str, dict[str, Warning]] = {}  # merge -> its warnings by text
        self.said = 0  # the lines echoed, the first ones

    def _add(self, text: str, category: type[Warning] = UserWarning) -> None:
        self.lines.append(text)
        self.categories.setdefault(text, category)
        if self.echo:
            self.say_unsaid()

    def say_unsaid(self, heads: bool = True) -> None:
        """Echo the lines not echoed yet, each once (after the run's heads, with ``heads``)."""
        if heads and self.said < len(self.lines):
            print_heads()
        for text in self.lines[self.said:]:
            print(f"tactcad: warning: {text}", file=sys.stderr, flush=True)
        self.said = len(self.lines)

    def show(self, message, category, filename, lineno, file=None, line=None) -> None:
        """``warnings.showwarning`` while capturing: record, and echo once."""
        text = one_line(message)
        if text in self.lines:
            return
        merge = getattr(message, "merge_as", "")
        if merge and callable(getattr(type(message), "merged_text", None)):
            held = self.merging.setdefault(merge, {})
            held.setdefault(text, message)
            self.fold_categories.setdefault(merge, category)
            return
        fold = getattr(message, "fold_as", "")
        if fold and fold in self.folded:
            self.folded[fold][text] = float(getattr(message, "error_rel", 0.0) or 0.0)
            return
        if fold:
            self.folded[fold] = {}
            self.fold_categories[fold] = category
        self._add(text, category)

    def close_merges(self) -> None:
        """One line per merged kind held (:attr:`merging`), made by its class's
        ``merged_text`` from the warnings in the order issued."""
        merging, self.merging = self.merging, {}
        for merge, held in merging.items():
            if held:
                said = list(held.values())
                text = one_line(type(said[0]).merged_text(said))
                if text not in self.lines:
                    self._add(text, self.fold_categories[merge])

    def close_folds(self) -> None:
        """One line per folded kind that had more than its first warning, and one per
        merged kind (:meth:`close_merges`)."""
        self.close_merges()
        for fold, errors in self.folded.items():
            if errors:
                self._add(f"{fold}: {len(errors)} more alike, estimated error up to "
                          f"{100 * max(errors.values()):.1f} %", self.fold_categories[fold])
        self.folded = {key: {} for key in self.folded}

    @contextlib.contextmanager
    def capture(self) -> Iterator["WarningLines"]:
        with warnings.catch_warnings():
            warnings.simplefilter("always")
            for category in _FOR_DEVELOPERS:
                warnings.simplefilter("ignore", category)
            warnings.showwarning = self.show
            _CAPTURES.append(self)
            try:
                yield self
            finally:
                _CAPTURES.remove(self)
                self.close_folds()


def print_unsaid() -> None:
    """Print on stderr, once each, the warnings the run's capture holds and did not echo
    (``--quiet``): a refusal prints them before itself, as what it followed from (the
    ``--set`` given twice whose last value is refused)."""
    if _CAPTURES:  # the refusal stays the run's last lines, without the heads
        notes = _CAPTURES[-1]
        echo, notes.echo = notes.echo, False  # the held range warnings, said below
        try:
            notes.close_merges()
        finally:
            notes.echo = echo
        notes.say_unsaid(heads=False)


def json_with_warnings(text: str, lines: list[str], notices: list[str] = ()) -> str | None:
    """The JSON object ``text`` with ``"warnings": lines`` added (joined to a
    ``warnings`` list it has, NaN written as null) and the run's heads as ``"notices"``
    where it has any (such as the shipped example it worked on); None when ``text`` is not
    one JSON object (a list keeps its shape, and its warnings go to stderr)."""
    from tactcad.commands.finite_json import finite

    try:
        obj = json.loads(text)
    except ValueError:
        return None
    if not isinstance(obj, dict):
        return None
    own = obj.get("warnings")
    if own is None:
        obj["warnings"] = list(lines)
    elif isinstance(own, list):
        obj["warnings"] = own + [w for w in lines if w not in own]
    else:
        return None
    if notices:
        obj["notices"] = list(notices)
    second = text.lstrip().split("\n", 2)[1:2]
    indent = len(second[0]) - len(second[0].lstrip(" ")) if second else 2
    return json.dumps(finite(obj), indent=indent or None, allow_nan=False)
