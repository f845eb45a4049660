"""What kind of design file a file's tables are: an array's, or another product's (a
silicon die's, :mod:`tactcad.products`).

Another product's file (a die's ``[die]`` table) is read by the commands that answer for
it; every array reader refuses it by name rather than listing the array tables it lacks.
This module imports nothing of the design's, so that every reader of a design file can ask
it first.
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


def refuse_another_product(tables: Mapping[str, Any], design: Path) -> None:
    """A design file of another product than the array's (a silicon die's) is refused by
    name where an array's is read, naming the commands that do answer for it
    (:meth:`tactcad.products.Product.refusal`), not every array table it lacks.

    Raises:
        DesignError: ``tables`` are another product's.
    """
    from tactcad.products import product_of_tables

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
