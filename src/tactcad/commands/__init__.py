"""Sub-commands of the ``tactcad`` CLI; see :mod:`tactcad.cli`."""

from __future__ import annotations

import argparse
from pathlib import Path


def add_design_arg(p: argparse.ArgumentParser) -> None:
    """The ``--design FILE`` option every command that reads a design shares."""
    p.add_argument("--design", metavar="FILE", default=None,
                   help="design file (TOML); default: hardware/macro_array.toml")


def add_cache_args(p: argparse.ArgumentParser) -> None:
    """``--cache DIR`` and ``--no-cache``: the store of finished export jobs."""
    p.add_argument("--cache", metavar="DIR", default=None,
                   help="store of finished export jobs, reused when nothing that shapes a file "
                        "changed (default: .tactcad-cache in the working folder)")
    p.add_argument("--no-cache", action="store_true",
                   help="build and write every file afresh; read and write no store")


def store_from_args(args: argparse.Namespace):
    """The :class:`tactcad.store.Store` the options ask for."""
    from tactcad.store import DEFAULT_STORE, Store

    if args.no_cache:
        return Store(None)
    return Store(Path(args.cache) if args.cache else DEFAULT_STORE)
