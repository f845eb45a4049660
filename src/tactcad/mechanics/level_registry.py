"""One registry for every ladder of estimator levels (stiffness, modal, crosstalk).

A ladder lists its levels cheapest first. Each level names its estimator as
a module and a function, imported only when the level is asked for, so a
command that never runs the FEM never imports it, and a typical cost for
help texts. Each ladder keeps its own level type (what its estimators take
differs) and its own error for an unknown name; the registering, listing
and dispatch are this module's, written once, and so is the keeping of a
FEM level's result in the result store (:meth:`LevelRegistry.run`,
:func:`tactcad.store.kept_result`): ``design``, ``verify``, ``modal``,
``stiffness`` and ``check`` solve each element once for all of them.
"""

from __future__ import annotations

import importlib
from typing import Any, Callable, Generic, Mapping, Protocol, TypeVar

from tactcad.store import kept_result


class Level(Protocol):
    """What every ladder's level holds."""

    name: str
    module: str
    function: str
    cost: str
    #: a FEM level (seconds to minutes per element): its results are kept
    meshed: bool


L = TypeVar("L", bound=Level)

#: Estimator options that shape no kept result, left out of its key: what a
#: level reports while it runs, and whether it hands back its mode shapes (a
#: result with them is never kept).
UNKEYED_OPTIONS = frozenset({"progress", "verbose", "keep_shapes"})


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

    def run(self, name: str, inputs: tuple, options: Mapping[str, Any], *, label: str,
            keep: bool = True) -> Any:
        """Level ``name``'s estimator on ``inputs`` (positional) and ``options``
        (keywords). A FEM level of tactcad's own (whose code is in the key)
        runs through the result store (:func:`tactcad.store.kept_result`),
        keyed by this ladder, the level's name, ``inputs`` and the options but
        :data:`UNKEYED_OPTIONS`; a kept result is reported on the
        ``progress`` option as one line, ``<level> <label>: reused ...``.

        Args:
            keep: False: never from or into the store (a result that holds
                more than the store keeps, such as mode shapes).

        Raises:
            the ladder's ``unknown`` error: no level has that name.
        """
        estimator = self.estimator(name)
        level = self.levels[name]
        if not (keep and level.meshed and level.module.startswith("tactcad.")):
            return estimator(*inputs, **options)
        shaping = {k: v for k, v in sorted(options.items()) if k not in UNKEYED_OPTIONS}
        progress = options.get("progress")
        reused = None if progress is None else (
            lambda where: progress(f"{name} {label}: {where} (same inputs)"))
        return kept_result(f"{self.what} level", lambda: estimator(*inputs, **options), name,
                           *inputs, shaping, reused=reused)
