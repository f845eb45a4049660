"""Command-line entry point ``tactcad``.

Each sub-command lives in a module of :mod:`tactcad.commands` that defines
``register(subparsers)``. Command modules import the CAD kernel and FEM
libraries only inside their handlers, so ``tactcad --help`` and the
closed-form commands start fast.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from tactcad import __version__
from tactcad.errors import TactcadError

COMMAND_MODULES = (
    "tactcad.commands.export",
    "tactcad.commands.check",
    "tactcad.commands.scenes",
    "tactcad.commands.bench",
    "tactcad.commands.mechanics",
    "tactcad.commands.lumped",
    "tactcad.commands.evaluate",
    "tactcad.commands.table2",
    "tactcad.commands.calibrate",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="tactcad",
        description="Generate CAD, wire-EDM DXF and stiffness estimates for spring-based "
                    "tactile sensor arrays. Units: mm, N, MPa, N/mm, s.")
    parser.add_argument("--version", action="version", version=f"tactcad {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name == name:  # command module not part of this build
                continue
            raise
        module.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    try:
        if getattr(args, "design", False) is not False:
            # every command that reads a design checks it with its rigs and
            # scenes files first: all errors at once, before any geometry
            from tactcad.design.project import load_project

            load_project(args.design)
        return int(args.func(args) or 0)
    except TactcadError as exc:
        print(f"tactcad: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
