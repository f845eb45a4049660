"""The sensor products tactcad makes, one registry: which design files each one reads and
what every command, writer and the Python API does with them.

A product is a kind of sensor with a design file of its own: the metal array (its
``[design]`` file, built as the paper's stacked array or as a monolithic comb, the two
constructions of :mod:`tactcad.design.construction_registry`) and the silicon MEMS die (a
``[die]`` file). Each product is one package of :mod:`tactcad.products` whose
``__init__`` holds a :data:`PRODUCT` (:class:`Product`); another package may add one
through the ``tactcad.products`` entry-point group, so a new product is one new package
and no edit elsewhere.

A product names what it does as ``"module:function"`` hooks, imported only when asked for
(as the constructions and the estimator ladders are), so that reading a design file's
kind loads nothing of any product. Commands ask this registry, never a product by name:
:func:`product_of_tables` gives a design file's product (read by the commands,
:func:`tactcad.project_folder.product_of`), :meth:`Product.view` the product's
answer to an array command (``strength``, ``budget``, ...), and a command a product has
no answer to is refused naming those it has (:meth:`Product.refusal`).
"""

from __future__ import annotations

import importlib
import pkgutil
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Any, Callable, Mapping

from tactcad.errors import DesignError

#: The entry-point group through which another package adds a product.
ENTRY_POINT_GROUP = "tactcad.products"


def resolved(hook: str) -> Callable[..., Any]:
    """The function a ``"module:function"`` hook names, imported now.

    Raises:
        ValueError: ``hook`` is not ``module:function``.
    """
    module, colon, name = hook.partition(":")
    if not (module and colon and name):
        raise ValueError(f"a product hook is 'module:function', not {hook!r}")
    return getattr(importlib.import_module(module), name)


@dataclass(frozen=True)
class Product:
    """One kind of sensor tactcad designs, makes and checks.

    Attributes:
        name: the product's name (``silicon-die``), as help texts and records give it.
        summary: one line for help texts and the reference pages.
        design_table: the table that makes a design file this product's (``die``); empty for
            the default product, whose files are those no other product claims.
        views: command name -> hook ``(design: Path, args) -> (report dict, text lines)``:
            the product's answer to that command (its ``--json`` prints the report).
        export: hook ``(design: Path, args) -> exit code`` of ``tactcad export``.
        check: hook ``(design: Path, args) -> exit code`` of ``tactcad check``.
        new_project: hook ``(folder, source: Path, force: bool) -> NewProject`` of ``tactcad
            new`` from one of its design files.
        load: hook ``(design: Path, set: Mapping | None) -> object`` of :func:`tactcad.load`.
        examples: the shipped examples of this product (folder names under the package's
            examples).
        commands_done_elsewhere: the commands that answer this product by a command of
            their own (``die``), named in a refusal.
    """

    name: str
    summary: str
    design_table: str = ""
    views: Mapping[str, str] = field(default_factory=dict)
    export: str = ""
    check: str = ""
    new_project: str = ""
    load: str = ""
    examples: tuple[str, ...] = ()
    commands_done_elsewhere: tuple[str, ...] = ()

    @property
    def is_default(self) -> bool:
        """True for the product of every design file no other product claims."""
        return not self.design_table

    def owns(self, tables: Mapping[str, Any]) -> bool:
        """True when a design file's ``tables`` are this product's (its :attr:`design_table`;
        the default product claims nothing by itself)."""
        return bool(self.design_table) and isinstance(tables, Mapping) \
            and self.design_table in tables

    def hook(self, name: str) -> Callable[..., Any]:
        """The function of hook ``name`` (``export``, ``check``, ``new_project``, ``load``).

        Raises:
            DesignError: the product has no such hook.
        """
        spec = getattr(self, name, "")
        if not spec:
            raise DesignError("product", self.name, f"a product with a {name.replace('_', ' ')}",
                              f"the {self.name} has none")
        return resolved(spec)

    def view(self, command: str) -> Callable[..., tuple[dict, list[str]]] | None:
        """The product's answer to ``command``, or None when it has none."""
        spec = self.views.get(command)
        return resolved(spec) if spec else None

    def refusal(self, command: str | None, design: Path) -> DesignError:
        """The refusal of ``command`` (None: a reader of the default product's files) on
        this product's design file ``design``: it names the commands that do answer for
        it, so a user knows where to go."""
        what = f"`tactcad {command}`" if command else "this command"
        answers = sorted({*self.views, *(("export", "check") if self.export else ())})
        made = "".join(f"; `tactcad {c} --design {design.name}` makes it"
                       for c in self.commands_done_elsewhere)
        return DesignError("--design", design.name,
                           f"a design file {what} reads (not a {self.name}'s)",
                           f"{design.name} is a {self.name}'s design ([{self.design_table}]) "
                           f"and {what} has no answer for it; these commands do, in its "
                           f"folder or with --design: " + ", ".join(answers) + made)


def _package_products() -> list[Product]:
    # the packages of tactcad.products, each one product (a package without PRODUCT is none)
    found = []
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda i: i.name):
        if info.ispkg:
            product = getattr(importlib.import_module(f"{__name__}.{info.name}"), "PRODUCT", None)
            if isinstance(product, Product):
                found.append(product)
    return found


def _entry_point_products() -> list[Product]:
    # products added by other packages; one that does not load is named, never skipped quietly
    found = []
    for entry in sorted(metadata.entry_points(group=ENTRY_POINT_GROUP), key=lambda e: e.name):
        product = entry.load()
        if not isinstance(product, Product):
            raise TypeError(f"entry point {entry.name} of {ENTRY_POINT_GROUP} is no Product")
        found.append(product)
    return found


@lru_cache(maxsize=1)
def products() -> tuple[Product, ...]:
    """Every registered product: those claiming a design table first (in name order), the
    default product last.

    Raises:
        ValueError: two products share a name or a design table, or no product or more than
            one is the default.
    """
    every = [*_package_products(), *_entry_point_products()]
    names = [p.name for p in every]
    tables = [p.design_table for p in every if p.design_table]
    defaults = [p for p in every if p.is_default]
    if len(set(names)) != len(names) or len(set(tables)) != len(tables):
        raise ValueError(f"products share a name or a design table: {names}, {tables}")
    if len(defaults) != 1:
        raise ValueError(f"one default product (no design table) expected, found "
                         f"{[p.name for p in defaults]}")
    return tuple(sorted((p for p in every if not p.is_default), key=lambda p: p.name)) \
        + tuple(defaults)


def product_named(name: str) -> Product:
    """The registered product ``name``.

    Raises:
        DesignError: no product has that name (the allowed ones listed).
    """
    for product in products():
        if product.name == name:
            return product
    raise DesignError("product", name, "one of " + ", ".join(p.name for p in products()))


def product_of_tables(tables: Mapping[str, Any]) -> Product:
    """The product a design file's tables belong to (the default one when none claims them)."""
    return next(p for p in products() if p.is_default or p.owns(tables))
