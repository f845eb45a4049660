"""The package's sources parsed once a test process: the house tests (the import layers,
the kernel wall, the project's readers) each walk every module's syntax tree."""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import pytest

#: tests that read every module's tree run in one process (``--dist loadgroup``), so the
#: trees are parsed once for all of them
one_reader = pytest.mark.xdist_group("import-graph")


@functools.cache
def parsed(path: Path) -> ast.Module:
    """The syntax tree of the source file ``path`` (UTF-8), parsed once a process."""
    return ast.parse(path.read_text(encoding="utf-8"))
