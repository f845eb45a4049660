"""Warnings as part of a command's output, never in Python's own format.

Within :func:`WarningLines.capture` every warning a run issues (tactcad's,
e.g. the closed form's ``CorrectionRangeWarning``, or a library's) becomes
one line ``tactcad: warning: ...`` on stderr, once per distinct text per run,
as it happens; ``--quiet`` silences the lines. With ``--json`` they go into
the output object as a ``warnings`` list (:func:`json_with_warnings`) instead.
Deprecation, import and resource warnings are for developers and dropped.
"""

from __future__ import annotations

import contextlib
import json
import sys
import warnings
from typing import Iterator

_FOR_DEVELOPERS = (DeprecationWarning, PendingDeprecationWarning, ImportWarning, ResourceWarning)

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
    ``categories`` keeps each line's warning category (a closing line: its first warning's).
    """

    def __init__(self, echo: bool):
        self.echo = echo
        self.lines: list[str] = []
        self.categories: dict[str, type[Warning]] = {}
        self.folded: dict[str, dict[str, float]] = {}  # fold -> its other texts' errors
        self.fold_categories: dict[str, type[Warning]] = {}

    def _add(self, text: str, category: type[Warning] = UserWarning) -> None:
        self.lines.append(text)
        self.categories.setdefault(text, category)
        if self.echo:
            print_heads()
            print(f"tactcad: warning: {text}", file=sys.stderr, flush=True)

    def show(self, message, category, filename, lineno, file=None, line=None) -> None:
        """``warnings.showwarning`` while capturing: record, and echo once."""
        text = one_line(message)
        if text in self.lines:
            return
        fold = getattr(message, "fold_as", "")
        if fold and fold in self.folded:
            self.folded[fold][text] = float(getattr(message, "error_rel", 0.0) or 0.0)
            return
        if fold:
            self.folded[fold] = {}
            self.fold_categories[fold] = category
        self._add(text, category)

    def close_folds(self) -> None:
        """One line per folded kind that had more than its first warning."""
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
            try:
                yield self
            finally:
                self.close_folds()


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
