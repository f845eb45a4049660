"""Sub-commands of the ``tactcad`` CLI; see :mod:`tactcad.cli`."""

from __future__ import annotations

import argparse


def add_design_arg(p: argparse.ArgumentParser) -> None:
    """The ``--design FILE`` option every command that reads a design shares."""
    p.add_argument("--design", metavar="FILE", default=None,
                   help="design file (TOML); default: hardware/macro_array.toml")
