"""The package tree is the pipeline: every import of tactcad (function-local
ones too) goes from a layer to one above it, and no modules import each other
in a circle.

The layer order is written once, in the block of docs/reference/layout.md (the lines
under ``src/tactcad/``, top to bottom); this file reads it from there. The
mechanics read plans only: foundation, vocabulary, design, geometry and
mechanics; the studies those and the mechanics; the paper those and the
studies. And a module's name is one in the package (docs/reference/layout.md): a
``commands/<name>.py`` is named after its command, and no module elsewhere
has its name or another's.
"""

from __future__ import annotations

import ast
import functools
import re
from collections import defaultdict
from pathlib import Path

import pytest

import tactcad
from source_trees import one_reader, parsed

SRC = Path(tactcad.__file__).resolve().parent
LAYOUT_PAGE = SRC.parents[1] / "docs" / "reference" / "layout.md"


def layers_from_layout_page(text: str) -> list[str]:
    """The layers of the Layout page's block (docs/reference/layout.md), top to bottom: a folder ``name/``
    is the layer ``name``; a module file is in the layer :data:`FOUNDATION` or
    :data:`TOP_LEVEL` gives it (``errors.py ...`` the foundation, ``cli.py
    commands/`` and ``api.py`` the commands)."""
    block = text.split("# Layout", 1)[1].split("```", 2)[1]
    layers, inside = [], False
    for line in block.splitlines():
        if line.startswith("src/tactcad/"):
            inside = True
            continue
        if inside and not line.startswith("  "):
            break
        m = re.match(r"^  (\S+)", line)
        if not inside or not m:
            continue
        first = m.group(1)
        if first.endswith(".py"):
            module = "tactcad." + first[:-3]
            layer = "foundation" if module in FOUNDATION else TOP_LEVEL[module]
        else:
            layer = first.rstrip("/")
        if layer not in layers:
            layers.append(layer)
    return layers


FOUNDATION = {"tactcad", "tactcad.errors", "tactcad.atomic", "tactcad.store", "tactcad.stopping",
              "tactcad.version"}
TOP_LEVEL = {"tactcad.cli": "commands", "tactcad.__main__": "commands",
             "tactcad.api": "commands", "tactcad.project_folder": "commands"}
LAYERS = layers_from_layout_page(LAYOUT_PAGE.read_text(encoding="utf-8"))
MECHANICS_MAY_USE = {"foundation", "vocabulary", "design", "geometry", "mechanics"}
#: The sensor in use reads the plans and the mechanics' results, never the CAD kernel.
IN_USE_MAY_USE = MECHANICS_MAY_USE | {"in_use"}
#: The design studies run the general models over many plans, never the reverse.
STUDIES_MAY_USE = IN_USE_MAY_USE | {"studies"}
#: The paper's reproduction reads the general models and the studies, never the reverse.
PAPER_MAY_USE = STUDIES_MAY_USE | {"paper"}
#: The layers whose imports are a set, not "everything above in the order".
MAY_USE = {"mechanics": MECHANICS_MAY_USE, "in_use": IN_USE_MAY_USE, "studies": STUDIES_MAY_USE,
           "paper": PAPER_MAY_USE}


#: Folders of src/tactcad left out of the one-name rule (none: every module
#: outside commands/ has a name of its own).
NAME_RULE_NOT_YET: tuple[str, ...] = ()


def module_name(path: Path) -> str:
    parts = ("tactcad",) + path.relative_to(SRC).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


#: The package of the products (docs/reference/layout.md): each product's own code is laid
#: out by layer inside its package (``products/<product>/<layer>/``).
PRODUCTS = "products"


def layer_of(module: str) -> str:
    """The layer of ``module``: its top package's, but for a product's own code, which sits in
    the layer its sub-package names (``tactcad.products.silicon_die.export.x``: export); a
    product's registry entry (its package's ``__init__``) sits in the products layer."""
    if module in FOUNDATION:
        return "foundation"
    if module in TOP_LEVEL:
        return TOP_LEVEL[module]
    parts = module.split(".")
    if len(parts) > 3 and parts[1] == PRODUCTS:
        if parts[3] not in LAYERS or parts[3] == PRODUCTS:
            raise AssertionError(f"{module}: a product's code outside the layers {LAYERS}")
        return parts[3]
    top = parts[1]
    if top not in LAYERS:
        raise AssertionError(f"{module}: a module outside the layers {LAYERS}")
    return top


def _type_checking_only(tree: ast.AST) -> set[int]:
    """ids of the nodes under ``if TYPE_CHECKING:``: names for type checkers,
    never imported when the code runs."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) \
                and node.test.id == "TYPE_CHECKING":
            out |= {id(n) for stmt in node.body for n in ast.walk(stmt)}
    return out


def imports_of(path: Path, types_too: bool = False) -> set[str]:
    """Every tactcad module ``path`` imports, anywhere in the file (but for
    type checkers only, under ``if TYPE_CHECKING:``, unless ``types_too``)."""
    me = module_name(path)
    package = me if path.name == "__init__.py" else me.rsplit(".", 1)[0]
    out = set()
    tree = _tree(path)
    types_only = set() if types_too else _type_checking_only(tree)
    for node in ast.walk(tree):
        if id(node) in types_only:
            continue
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            # "from pkg import mod" imports the module pkg.mod when there is one
            names = [base] + [f"{base}.{a.name}" for a in node.names]
        else:
            continue
        out |= {n for n in names if n == "tactcad" or n.startswith("tactcad.")}
    return {m for m in out if _exists(m)} - {me}


def _exists(module: str) -> bool:
    rel = Path(*module.split(".")[1:])
    return module == "tactcad" or (SRC / rel).with_suffix(".py").is_file() \
        or (SRC / rel / "__init__.py").is_file()


def _tree(path: Path) -> ast.Module:
    return parsed(path)  # each source parsed once a process: the house tests share it


@functools.cache
def graph(types_too: bool = False) -> dict[str, frozenset[str]]:
    return {module_name(p): frozenset(imports_of(p, types_too))
            for p in sorted(SRC.rglob("*.py"))}


#: the tests that read the whole import graph run in one process, which builds it once
one_graph = one_reader


#: Modules whose names for type checkers may go against the order: the
#: package's ``__init__`` names the public API's types (it loads them lazily).
TYPE_NAMES_ANYWHERE = {"tactcad"}


@one_graph
@pytest.mark.parametrize("types_too", [False, True], ids=["run", "type-checking"])
def test_every_import_goes_up_the_layers(types_too):
    """Imports the code runs, and (``type-checking``) those under ``if
    TYPE_CHECKING:`` too: a type hint names nothing below its layer either
    (geometry's profile reads an element through a Protocol, not partlib's
    class)."""
    bad = []
    for mod, deps in graph(types_too).items():
        if types_too and mod in TYPE_NAMES_ANYWHERE:
            continue
        mine = layer_of(mod)
        for dep in sorted(deps):
            theirs = layer_of(dep)
            if mine in MAY_USE:
                ok = theirs in MAY_USE[mine]
            else:
                ok = LAYERS.index(theirs) <= LAYERS.index(mine)
            if not ok:
                bad.append(f"{mod} ({mine}) imports {dep} ({theirs})")
    assert not bad, "imports against the layer order:\n" + "\n".join(bad)


@one_graph
@pytest.mark.parametrize("types_too", [False, True], ids=["run", "type-checking"])
def test_no_import_circle(types_too):
    g = graph(types_too)
    # a package's __init__ importing its own modules is not a circle of the pipeline
    g = {m: {d for d in deps if not m.startswith(d + ".")} for m, deps in g.items()}
    state: dict[str, int] = {}
    stack: list[str] = []
    circles = []

    def visit(m: str) -> None:
        state[m] = 1
        stack.append(m)
        for d in sorted(g.get(m, ())):
            if state.get(d) == 1:
                circles.append(stack[stack.index(d):] + [d])
            elif d not in state:
                visit(d)
        stack.pop()
        state[m] = 2

    for m in sorted(g):
        if m not in state:
            visit(m)
    assert not circles, "import circles:\n" + "\n".join(" -> ".join(c) for c in circles)


def test_the_checker_sees_function_local_and_relative_imports(tmp_path, monkeypatch):
    """The reader finds an import inside a function and resolves a relative one."""
    pkg = tmp_path / "tactcad"
    (pkg / "export").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "errors.py").write_text("")
    (pkg / "export" / "__init__.py").write_text("")
    (pkg / "export" / "names.py").write_text("")
    f = pkg / "export" / "x.py"
    f.write_text("def f():\n    from tactcad.errors import A\n    from .names import b\n")
    monkeypatch.setitem(globals(), "SRC", pkg)
    assert imports_of(f) == {"tactcad.errors", "tactcad.export.names"}


@pytest.mark.parametrize("module,layer", [("tactcad.store", "foundation"),
                                          ("tactcad.design.array_plan", "design"),
                                          ("tactcad.mechanics.fem.fem3d", "mechanics"),
                                          ("tactcad.products", "products"),
                                          ("tactcad.products.silicon_die", "products"),
                                          ("tactcad.products.silicon_die.export.die_review",
                                           "export")])
def test_layer_names(module, layer):
    assert layer_of(module) == layer


def test_the_one_layer_order_is_the_layout_pages_and_covers_every_package():
    assert LAYERS[0] == "foundation" and LAYERS[-1] == "commands"
    assert len(set(LAYERS)) == len(LAYERS)
    packages = {p.name for p in SRC.iterdir() if (p / "__init__.py").is_file()}
    assert packages <= set(LAYERS), packages - set(LAYERS)


def repeated_module_names(src: Path, not_yet=NAME_RULE_NOT_YET) -> dict[str, list[str]]:
    """Module file names that repeat in ``src`` (docs/reference/layout.md: every
    module but ``__init__.py`` has a name no other has; a ``commands/<name>.py``
    is named after its command, so only a module outside ``commands/`` can
    repeat its name), leaving out the folders ``not_yet``."""
    where = defaultdict(list)
    for p in sorted(src.rglob("*.py")):
        rel = p.relative_to(src)
        if p.name != "__init__.py" and rel.parts[0] not in not_yet:
            where[p.name].append(rel.as_posix())
    return {name: paths for name, paths in where.items()
            if len(paths) > 1 and any(not q.startswith("commands/") for q in paths)}


def test_every_module_name_is_one_in_the_package():
    repeated = repeated_module_names(SRC)
    assert not repeated, "module names that repeat (docs/reference/layout.md):\n" + "\n".join(
        f"{name}: {', '.join(paths)}" for name, paths in sorted(repeated.items()))


def test_the_name_rule_sees_a_repeat(tmp_path):
    for rel in ("commands/scenes.py", "design/scenes.py", "mechanics/ladder.py",
                "commands/ladder.py", "checks/step.py", "kernel/step_writer.py",
                "design/__init__.py", "mechanics/__init__.py"):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text("")
    assert repeated_module_names(tmp_path) == {
        "ladder.py": ["commands/ladder.py", "mechanics/ladder.py"],
        "scenes.py": ["commands/scenes.py", "design/scenes.py"]}
    (tmp_path / "kernel" / "step.py").write_text("")
    assert repeated_module_names(tmp_path)["step.py"] == ["checks/step.py", "kernel/step.py"]
    assert "step.py" not in repeated_module_names(tmp_path, not_yet=("checks",))


def modules_named_after_a_product(src: Path, tables: dict[str, str]) -> list[str]:
    """Modules outside a product's package whose name is the product's (its design table,
    ``die``, alone or as the first word: ``die_budget.py``), but the command named after it
    (``commands/die.py``): a product's own code lives in its package
    (``products/<package>/<layer>/``), never beside the generic rooms as their twin.

    Args:
        tables: design table -> the product's package under ``products/``.
    """
    out = []
    for p in sorted(src.rglob("*.py")):
        rel = p.relative_to(src)
        for table, package in tables.items():
            named = p.stem == table or p.stem.startswith(f"{table}_")
            own = rel.parts[:2] == ("products", package)
            command = rel.parts[0] == "commands" and p.stem == table
            if named and not own and not command:
                out.append(rel.as_posix())
    return out


def _product_tables() -> dict[str, str]:
    import importlib
    import pkgutil

    import tactcad.products as registry

    out = {}
    for info in pkgutil.iter_modules(registry.__path__):
        product = getattr(importlib.import_module(f"tactcad.products.{info.name}"), "PRODUCT",
                          None)
        if product is not None and product.design_table:
            out[product.design_table] = info.name
    return out


def test_a_products_own_modules_live_in_its_package():
    tables = _product_tables()
    assert tables == {"die": "silicon_die"}
    outside = modules_named_after_a_product(SRC, tables)
    assert not outside, "a product's modules outside its package:\n" + "\n".join(outside)


def test_the_product_rule_sees_a_twin_beside_the_rooms(tmp_path):
    for rel in ("mechanics/die_fem3d.py", "commands/die.py", "products/silicon_die/in_use/"
                "die_budget.py", "design/dies.py", "export/die.py"):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text("")
    assert modules_named_after_a_product(tmp_path, {"die": "silicon_die"}) == [
        "export/die.py", "mechanics/die_fem3d.py"]
