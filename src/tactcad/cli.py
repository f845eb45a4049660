"""Command-line entry point ``tactcad``.

Each sub-command lives in a module of :mod:`tactcad.commands` that defines
``register(subparsers)``. Command modules import the CAD kernel and FEM
libraries only inside their handlers, so ``tactcad --help`` and the
closed-form commands start fast.
"""

from __future__ import annotations

import argparse
import errno
import importlib
import sys

from tactcad import __version__
from tactcad.errors import TactcadError

#: Exit codes: 0 done, 1 a check failed, 2 bad input (a named field, value and
#: allowed range), 3 a file-system error (path and cause), 130 interrupted.
EXIT_INPUT = 2
EXIT_OS = 3
EXIT_INTERRUPTED = 130

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
    "tactcad.commands.strength",
    "tactcad.commands.tolerance",
    "tactcad.commands.sweep",
    "tactcad.commands.design",
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
        return int(args.func(args) or 0)
    except TactcadError as exc:
        print(f"tactcad: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except OSError as exc:
        print(f"tactcad: error: {os_error_text(exc)}", file=sys.stderr)
        return EXIT_OS
    except KeyboardInterrupt:
        print("tactcad: interrupted; the previous files are left as they were", file=sys.stderr)
        return EXIT_INTERRUPTED


def os_error_text(exc: OSError) -> str:
    """One line for a file-system error: the path and the cause, a full disk said as such."""
    cause = {errno.ENOSPC: "disk full", errno.EDQUOT: "disk quota exceeded",
             errno.EROFS: "read-only file system", errno.EACCES: "permission denied",
             errno.EPERM: "permission denied"}.get(exc.errno, exc.strerror or type(exc).__name__)
    paths = [p for p in (exc.filename, exc.filename2) if p]
    return (f"{paths[0]}: {cause}" if paths else cause) + (
        "" if cause == (exc.strerror or "") else f" ({exc.strerror})" if exc.strerror else "")


if __name__ == "__main__":
    sys.exit(main())
