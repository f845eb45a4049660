"""The CAD kernel behind one wall: only ``tactcad.kernel`` imports build123d,
OCP or cadquery (function-local imports and type-checking ones included), the
kernel imports nothing of tactcad above the foundation, and a command that
needs no geometry never loads the kernel, not even to refuse an option."""

from __future__ import annotations

import pytest

import ast
import json
import subprocess
import sys
from pathlib import Path

import tactcad
from source_trees import one_reader, parsed

SRC = Path(tactcad.__file__).resolve().parent
KERNEL_PACKAGES = ("build123d", "OCP", "cadquery")
#: What the kernel may import of tactcad: the foundation and, for type
#: checkers only, the 2D profiles it extrudes.
KERNEL_MAY_IMPORT = ("tactcad.kernel", "tactcad.atomic", "tactcad.errors")


def _imports(path: Path) -> list[tuple[int, str]]:
    """(line, module) of every import in ``path``, anywhere in the file."""
    out = []
    for node in ast.walk(parsed(path)):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            out.append((node.lineno, node.module))
    return out


def kernel_imports_outside_the_wall(src: Path) -> list[str]:
    """``file:line module`` for every import of a kernel package by a module
    of ``src`` outside ``src/kernel``."""
    wall = src / "kernel"
    return [f"{p.relative_to(src)}:{line} {name}"
            for p in sorted(src.rglob("*.py")) if wall not in p.parents
            for line, name in _imports(p) if name.split(".")[0] in KERNEL_PACKAGES]


@one_reader
def test_only_the_kernel_package_imports_the_cad_kernel():
    found = kernel_imports_outside_the_wall(SRC)
    assert found == [], "kernel imports outside tactcad/kernel:\n" + "\n".join(found)


def test_the_wall_check_finds_an_import_outside_it(tmp_path):
    (tmp_path / "kernel").mkdir()
    (tmp_path / "kernel" / "shapes.py").write_text("import build123d\n")
    (tmp_path / "parts.py").write_text("def build():\n    from OCP.gp import gp_Pnt\n")
    assert kernel_imports_outside_the_wall(tmp_path) == ["parts.py:2 OCP.gp"]


#: Methods and attributes of the kernel's own objects (build123d shapes and
#: OCP handles) that code above the wall must reach through tactcad.kernel.
KERNEL_METHODS = ("wrapped", "faces", "edges", "vertices", "solids", "bounding_box",
                  "tessellate", "moved", "is_valid", "axis_of_rotation", "geom_type")


#: Other libraries' objects that share a name with a kernel method, per file.
OTHER_LIBRARIES = {"checks/dxf_readback.py": {"vertices"},  # ezdxf POLYLINE entities
                   "mechanics/fem/fem2d.py": {"edges"},  # scikit-fem meshes
                   "products/silicon_die/export/die_solid.py": {"is_valid"}}  # shapely


def kernel_method_calls_outside_the_wall(src: Path) -> list[str]:
    """``file:line .name`` for every use of a :data:`KERNEL_METHODS` name as an
    attribute (``solid.faces()``, ``loc.wrapped``) outside ``src/kernel``."""
    wall = src / "kernel"
    return [f"{rel}:{node.lineno} .{node.attr}"
            for p in sorted(src.rglob("*.py")) if wall not in p.parents
            for rel in [p.relative_to(src).as_posix()]
            for node in ast.walk(parsed(p))
            if isinstance(node, ast.Attribute) and node.attr in KERNEL_METHODS
            and not _own_attribute(node) and node.attr not in OTHER_LIBRARIES.get(rel, ())]


def _own_attribute(node: ast.Attribute) -> bool:
    """``run.solids``, ``self.solids`` ...: tactcad's own objects named like a kernel method."""
    return node.attr == "solids" and isinstance(node.value, ast.Name) and node.value.id in (
        "run", "self", "cache", "parts", "result", "res")


@one_reader
def test_code_above_the_wall_reads_solids_through_the_kernel():
    found = kernel_method_calls_outside_the_wall(SRC)
    assert found == [], "kernel objects used directly above the wall:\n" + "\n".join(found)


def test_the_method_check_finds_a_call_outside_the_wall(tmp_path):
    (tmp_path / "kernel").mkdir()
    (tmp_path / "kernel" / "inspect.py").write_text("def f(s):\n    return s.faces()\n")
    (tmp_path / "checks.py").write_text("def g(s):\n    return len(s.faces())\n")
    assert kernel_method_calls_outside_the_wall(tmp_path) == ["checks.py:2 .faces"]


def test_the_kernel_imports_only_itself_and_the_foundation():
    above = [f"{p.name}:{line} {name}" for p in sorted((SRC / "kernel").glob("*.py"))
             for line, name in _imports(p)
             if name.startswith("tactcad") and not name.startswith(KERNEL_MAY_IMPORT)
             and not _for_type_checkers(p, line)]
    assert above == [], "the kernel imports layers above it:\n" + "\n".join(above)


def _for_type_checkers(path: Path, line: int) -> bool:
    tree = parsed(path)
    return any(isinstance(n, ast.If) and isinstance(n.test, ast.Name)
               and n.test.id == "TYPE_CHECKING" and n.lineno < line <= n.end_lineno
               for n in ast.walk(tree))


#: Command lines every command refuses (exit 2) before it needs geometry, and
#: commands that answer without geometry at all.
REFUSALS = [
    ["export", "--only", "no-such-kind"],
    ["export", "--part", "no_such_part"],
    ["check", "--out", "no-such-folder", "--junit", "/"],
    ["watch", "--port", "80"],
    ["watch", "--port", "70000"],
    ["stiffness", "--element", "0"],
    ["stiffness", "--model", "no-such-model"],
    ["verify", "--model", "no-such-model"],
    ["diff"],
    ["scenes", "--design", "no-such-design.toml"],
    ["new"],
    ["bench", "export", "--design", "no-such-design.toml"],
]
ANSWERS_WITHOUT_GEOMETRY = [["stiffness", "--element", "1"], ["scenes"], ["lumped", "--km", "3", "--kr", "30", "--kobj", "5"],
                            ["materials"], ["table2"], ["design", "--help"]]


@pytest.mark.slow  # a whole chain through the command line or an export
def test_commands_that_need_no_geometry_never_load_the_kernel():
    """One process runs every line in turn and reports, after each, its exit
    code and whether a kernel package was loaded."""
    code = (
        "import contextlib, io, json, sys\n"
        "from tactcad.cli import main\n"
        "out = []\n"
        f"for argv in {REFUSALS + ANSWERS_WITHOUT_GEOMETRY!r}:\n"
        "    with contextlib.redirect_stdout(io.StringIO()), "
        "contextlib.redirect_stderr(io.StringIO()):\n"
        "        try:\n"
        "            rc = main(argv)\n"
        "        except SystemExit as exc:\n"
        "            rc = exc.code\n"
        f"    loaded = sorted({{m.split('.')[0] for m in sys.modules}} & {set(KERNEL_PACKAGES)!r})\n"
        "    out.append([argv, rc, loaded])\n"
        "print(json.dumps(out))\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=300, cwd=SRC.parent)
    assert proc.returncode == 0, proc.stderr
    rows = json.loads(proc.stdout.strip().splitlines()[-1])
    refused = {tuple(argv): rc for argv, rc, _ in rows[:len(REFUSALS)]}
    assert all(rc == 2 for rc in refused.values()), refused
    answered = {tuple(argv): rc for argv, rc, _ in rows[len(REFUSALS):]}
    assert all(rc == 0 for rc in answered.values()), answered
    loaded = [f"{' '.join(argv)}: {names}" for argv, _, names in rows if names]
    assert loaded == [], "these loaded the CAD kernel:\n" + "\n".join(loaded)
