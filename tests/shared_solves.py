"""The fem3d solves that several test modules ask of the same elements, solved once per
test process.

The read-out's tests (test_gauge_strain_fem3d.py, test_gauge_strain_calculix.py,
test_bonded_layer.py) each check a different claim against fem3d on the examples' extreme
elements, bare and with the gauge's layer meshed: the same few convergence sequences.
Each test opens its own :func:`tactcad.store.keeping_results` block, as a command does,
on the one store this module hands out (a temporary folder, removed when the process
ends), so a sequence one test solved is read back by the next; the tests that share it
carry :data:`ONE_WORKER` so that ``make test``'s xdist workers do not each solve it.
"""

from __future__ import annotations

import atexit
import shutil
import tempfile
from pathlib import Path

import pytest

#: Runs the tests that share the store's solves on one xdist worker (``--dist loadgroup``).
ONE_WORKER = pytest.mark.xdist_group("fem3d-read-out-elements")

_STORE = None


def shared_store():
    """The process's :class:`tactcad.store.Store` for the shared fem3d solves (made on the
    first call, its folder removed at exit)."""
    global _STORE
    if _STORE is None:
        from tactcad.store import Store

        folder = Path(tempfile.mkdtemp(prefix="tactcad-test-solves-"))
        atexit.register(shutil.rmtree, folder, ignore_errors=True)
        _STORE = Store(folder)
    return _STORE
