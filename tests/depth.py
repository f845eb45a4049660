"""How many random designs the suite draws: a share in ``make test``, all of them in
``make test-deep``.

The property tests that export, check or design whole random designs cost a minute each;
``make test`` draws a few of each (every test still runs, on fresh draws of its seed), and
``make test-deep`` (``TACTCAD_TEST_DEPTH=deep``) draws the counts the suite was written
with, for a nightly run or before a release. ``make fuzz`` goes further still.
"""

from __future__ import annotations

import os

#: ``quick`` (the default) or ``deep``.
DEPTH = os.environ.get("TACTCAD_TEST_DEPTH", "quick").strip().lower()
DEPTHS = ("quick", "deep")


def draws(quick: int, deep: int) -> int:
    """``deep`` under ``TACTCAD_TEST_DEPTH=deep``, else ``quick`` (counts of drawn designs)."""
    return deep if DEPTH == "deep" else quick
