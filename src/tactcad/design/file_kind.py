"""What kind of design file a file's tables are: an array's, or another product's (a
silicon die's, :mod:`tactcad.products`).

Another product's file (a die's ``[die]`` table) is read by the commands that answer for
it; every array reader refuses it by name rather than listing the array tables it lacks.
This module imports nothing of the design's, so that every reader of a design file can ask
it first.
"""

from __future__ import annotations

import shlex
from pathlib import Path
from typing import Any, Mapping

from tactcad.errors import DesignError

#: The table that makes a design file a die's.
DIE_TABLE = "die"


def is_die_file(data: Mapping[str, Any]) -> bool:
    """True when a design file's tables are a die's (a ``[die]`` table)."""
    return isinstance(data, Mapping) and DIE_TABLE in data


#: The table of a lab's own jaw file (``--jaw FILE``): a jaw, not a design.
JAW_TABLE = "grasper_jaw"


def is_jaw_file(data: Mapping[str, Any]) -> bool:
    """True when a file's tables are a jaw file's: a ``[grasper_jaw]`` table and no
    ``[design]``, ``[arms]`` or ``[die]`` table (a design made for a jaw keeps its jaw's
    ``[grasper_jaw]`` beside its own tables)."""
    return (isinstance(data, Mapping) and isinstance(data.get(JAW_TABLE), Mapping)
            and not any(t in data for t in ("design", "arms", DIE_TABLE)))


def refuse_jaw_file(tables: Mapping[str, Any], design: Path, field: str = "design file") -> None:
    """A jaw file read where a design file is wanted is refused as a jaw file, naming
    ``--jaw FILE`` (``tactcad design --jaw FILE``, ``tactcad atlas --jaw FILE``) that reads
    it, not with every design table it lacks.

    Args:
        tables: the file's tables. design: its path. field: the option or argument that
            named it (``design file``, ``--design``).

    Raises:
        DesignError: ``tables`` are a jaw file's.
    """
    if is_jaw_file(tables):
        jaw = f"--jaw {shlex.quote(str(design))}"
        raise DesignError(field, str(design), "a design file ([design] and [arms] tables, "
                          "or a die's [die])",
                          f"{Path(design).name} holds only [{JAW_TABLE}]: it is a jaw file, read "
                          f"by `tactcad design {jaw}` (or `tactcad atlas {jaw}`), which designs "
                          "an insert for that jaw",
                          alternatives=[{"option": jaw, "words": "design an insert for this jaw "
                                                                 "(tactcad design)"}])


def refuse_another_product(tables: Mapping[str, Any], design: Path) -> None:
    """A design file of another product than the array's (a silicon die's) is refused by
    name where an array's is read, naming the commands that do answer for it
    (:meth:`tactcad.products.Product.refusal`), not every array table it lacks.

    Raises:
        DesignError: ``tables`` are another product's, or a jaw file's (:func:`refuse_jaw_file`).
    """
    from tactcad.products import product_of_tables

    refuse_jaw_file(tables, design)
    product = product_of_tables(tables)
    if not product.is_default:
        raise product.refusal(None, design)


def read_array_tables(path: Path) -> dict:
    """An array's design file's tables, read as TOML; a die's file refused by name
    (:func:`refuse_another_product`) before any array table is looked for.

    Raises:
        DesignError: unreadable or not TOML (named), or a die's design file.
    """
    from tactcad.vocabulary.schema import read_toml

    tables = read_toml(path, "design file")
    refuse_another_product(tables, path)
    return tables
