"""One registry for every ladder of estimator levels (stiffness, modal, crosstalk).

A ladder lists its levels cheapest first. Each level names its estimator as
a module and a function, imported only when the level is asked for, so a
command that never runs the FEM never imports it, and a typical cost for
help texts. Each ladder keeps its own level type (what its estimators take
differs) and its own error for an unknown name; the registering, listing
and dispatch are this module's, written once.
"""

from __future__ import annotations

import importlib
from typing import Callable, Generic, Protocol, TypeVar


class Level(Protocol):
    """What every ladder's level holds."""

    name: str
    module: str
    function: str
    cost: str


L = TypeVar("L", bound=Level)


class LevelRegistry(Generic[L]):
    """The levels of one ladder, cheapest first.

    Args:
        what: the ladder's name in messages (``a {what} level 'x' is registered already``).
        unknown: the error raised for a name no level has, called with that name.
    """

    def __init__(self, what: str, unknown: Callable[[str], Exception]):
        self.what = what
        self.unknown = unknown
        self.levels: dict[str, L] = {}

    def register(self, level: L) -> None:
        """Add a level to the ladder (after the others).

        Raises:
            ValueError: a level of that name is there already.
        """
        if level.name in self.levels:
            raise ValueError(f"a {self.what} level {level.name!r} is registered already")
        self.levels[level.name] = level

    def names(self) -> tuple[str, ...]:
        """Every level's name, cheapest first."""
        return tuple(self.levels)

    def help(self) -> str:
        """``name cost, ...``: the levels with their typical cost, for help texts."""
        return ", ".join(f"{n} {level.cost}" for n, level in self.levels.items())

    def estimator(self, name: str) -> Callable:
        """The estimator function of level ``name``, imported now.

        Raises:
            the ladder's ``unknown`` error: no level has that name.
        """
        level = self.levels.get(name)
        if level is None:
            raise self.unknown(name)
        return getattr(importlib.import_module(level.module), level.function)
