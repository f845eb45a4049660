"""``tactcad verify`` run right after ``tactcad export`` of the same design solves
nothing: every analysis the export worked out (the tissue coupling, the contact
checks, the K_obj budget, any FEM level) is read back from the result store.

Counted by :func:`tactcad.store.counting_results` (what
:func:`tactcad.store.kept_result` computed, read back, or found missing), never by time.
"""

from __future__ import annotations

import pytest

from conftest import EXAMPLE_DESIGN, run_cli


def clear_process_caches() -> int:
    """Empty every in-memory cache of tactcad's functions (``functools.lru_cache``), as a
    fresh process starts: an earlier test in this worker may have exported the same design,
    and the export would then read its facts from memory and never fill this test's store.
    Returns how many caches were emptied."""
    import functools
    import gc

    caches = [f for f in gc.get_objects() if isinstance(f, functools._lru_cache_wrapper)
              and str(getattr(f, "__module__", "")).startswith("tactcad")]
    for f in caches:
        f.cache_clear()
    return len(caches)


@pytest.mark.slow  # a cold export of the example (about 20 s on two quiet cores)
def test_verify_after_export_solves_nothing(tmp_path):
    from tactcad.store import counting_results

    assert clear_process_caches() > 0
    store = tmp_path / "store"
    with counting_results() as exported:
        done = run_cli("export", "--design", EXAMPLE_DESIGN, "--out", tmp_path / "out",
                       "--cache", store, "--json")
    assert done.returncode == 0, done.stdout[-2000:]
    assert sum(exported.computed.values()) > 0  # the export did solve something to reuse
    with counting_results() as verified:
        checked = run_cli("verify", "--design", EXAMPLE_DESIGN, "--cache", store,
                          "--model", "closed-form", "--json")
    assert checked.returncode in (0, 1), checked.stdout[-2000:]  # 1: a requirement fails
    assert verified.solved() == 0, (verified.computed, verified.missing)
    shared = set(exported.computed) & set(verified.reused)
    assert shared, "verify read back none of the export's analyses"
