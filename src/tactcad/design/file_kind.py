"""What kind of design file a file's tables are: an array's, or a silicon die's.

A die's file (a ``[die]`` table) is made by ``tactcad die`` and exported and checked in its
folder; every array command refuses it by name rather than listing the array tables it
lacks. This module imports nothing of the design's, so that every reader of a design file
can ask it first.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

from tactcad.errors import DesignError

#: The table that makes a design file a die's.
DIE_TABLE = "die"


def is_die_file(data: Mapping[str, Any]) -> bool:
    """True when a design file's tables are a die's (a ``[die]`` table)."""
    return isinstance(data, Mapping) and DIE_TABLE in data


def die_refusal(design: Path) -> DesignError:
    """The refusal of a silicon die's design file where an array's is read: it names the
    die command and the array commands that print a die's own figures."""
    return DesignError("--design", design.name, "an array's design file ([design], "
                       "[material], [arms], ...)",
                       f"{design.name} is a silicon die's ([die]): `tactcad die --design "
                       f"{design.name}` makes it and prints its read-out, budget and "
                       "resonances; `tactcad modal`, `budget`, `readout`, `thermal` and "
                       "`verify` print those alone, `grasp` the grasp in its jaw, `crosstalk` the "
                       "crosstalk through the die; `tactcad "
                       "export` and `tactcad check` in its folder make and check its files")


def refuse_a_die(tables: Mapping[str, Any], design: Path) -> None:
    """A silicon die's design file is made by ``tactcad die`` (and ``export`` and ``check``
    in its folder), not read as an array's: say so, not every array table it lacks.

    Raises:
        DesignError: ``tables`` are a die's (:func:`die_refusal`).
    """
    if is_die_file(tables):
        raise die_refusal(design)


def read_array_tables(path: Path) -> dict:
    """An array's design file's tables, read as TOML; a die's file refused by name
    (:func:`die_refusal`) before any array table is looked for.

    Raises:
        DesignError: unreadable or not TOML (named), or a die's design file.
    """
    from tactcad.vocabulary.schema import read_toml

    tables = read_toml(path, "design file")
    refuse_a_die(tables, path)
    return tables
