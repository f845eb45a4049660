"""The documentation site's pages as the tests read them: the Markdown pages
of ``docs/`` (hand-written; the generated reference parts are made by
``docs/_ext/tactcad_reference.py``), their fenced code blocks, and the
conventions of ``docs/about.md``:

* a block whose first line is ``# not run: REASON`` is not run;
* a page that starts with the MyST comment ``% runs: slow (REASON)`` is run by
  the slow tests only;
* a page runs in an empty folder, as a reader who installed tactcad meets it,
  unless it carries the MyST comment ``% runs: in a checkout (REASON)``: its
  commands read the checkout's ``hardware/``, copied into its folder;
* ``sh``, ``console``, ``python`` and ``toml`` blocks run; ``text`` blocks are
  pictures of trees or output and hold no command;
* a ``toml`` block whose first line is ``# file: NAME`` is a file the reader
  saves as ``NAME`` (the page's later commands read it).
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
README = ROOT / "README.md"
#: Languages of blocks that run (each as :mod:`test_code_blocks` says).
RUNNABLE = ("sh", "console", "python", "toml")
NOT_RUN = re.compile(r"^# not run: \S")
SAVED_AS = re.compile(r"^# file: ([\w.-]+)[ \t]*$", re.M)
SLOW = re.compile(r"^% runs: slow \(.+\)$", re.M)
CHECKOUT = re.compile(r"^% runs: in a checkout \(.+\)$", re.M)
_FENCE = re.compile(r"^(`{3,})([^`\n]*)\n(.*?)^\1[ \t]*$", re.M | re.S)


@dataclass(frozen=True)
class Block:
    """One fenced code block of a page."""

    page: str  # path relative to docs/
    line: int  # 1-based line of the opening fence
    language: str
    code: str

    @property
    def not_run(self) -> bool:
        return bool(NOT_RUN.match(self.code))

    @property
    def saved_as(self) -> str | None:
        """The file name a ``# file: NAME`` first line gives the block, else None."""
        m = SAVED_AS.match(self.code)
        return m.group(1) if m else None

    def where(self) -> str:
        return f"docs/{self.page}:{self.line}"


def pages() -> list[Path]:
    """The hand-written Markdown pages of the site (not the build, not the generated parts)."""
    return sorted(p for p in DOCS.rglob("*.md")
                  if not {"_build", "_generated"} & set(p.relative_to(DOCS).parts))


def blocks(page: Path) -> list[Block]:
    """Every fenced block of ``page`` (MyST directives such as ``{toctree}`` left out)."""
    text = page.read_text(encoding="utf-8")
    out = []
    for m in _FENCE.finditer(text):
        info = m.group(2).strip()
        if info.startswith("{"):
            continue
        out.append(Block(page.relative_to(DOCS).as_posix(), text.count("\n", 0, m.start()) + 1,
                         info.split()[0] if info else "", m.group(3)))
    return out


def is_slow(page: Path) -> bool:
    return bool(SLOW.search(page.read_text(encoding="utf-8")))


def in_checkout(page: Path) -> bool:
    """True when ``page`` says its commands read the checkout's ``hardware/``."""
    return bool(CHECKOUT.search(page.read_text(encoding="utf-8")))


def reference_extension():
    """``docs/_ext/tactcad_reference.py``, the generator of the reference pages."""
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        import tactcad_reference
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    return tactcad_reference
