"""The distinct elements of a design solved at one ladder level side by side, one process
each, into the store the command reads them back from.

``tactcad design`` verifies its two element geometries at fem3d (about half a minute
each on the finest mesh, one core each); solved in turn they take the sum, side by side
about the longer. Each process opens the command's store (:func:`tactcad.store.
keeping_results`) and solves one element; the command's own solve of it afterwards reads
the kept result. The processes start by ``spawn`` (no state of this process shared) with
the stop signals held (:mod:`tactcad.stopping`): Ctrl-C is this process's to handle (the
processes ignore it and are killed with it), and a process that dies leaves its element to
be solved here as before.

Nothing is prefetched without a store on disk (``--no-cache``: a process's result would be
lost), on one core, for fewer than two elements not yet kept in the store, or with
``TACTCAD_WORKERS=0``.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Sequence


def _start() -> None:
    from tactcad.stopping import stop_signals_unblocked

    stop_signals_unblocked()
    try:  # Linux: killed with its parent, so a stopped command leaves no process behind
        import ctypes
        import signal

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


#: What one process solves of an element: its K at the level (the sequence with its gauge's
#: layer, :func:`tactcad.mechanics.ladder.estimate`) or the sequence its peak stress is read
#: from (the bare element's, :func:`tactcad.mechanics.element_strength.peak_stress_sequence`).
STIFFNESS, PEAK_STRESS = "stiffness", "peak stress"


def _compute(what: str, model: str, geometry: Any, material: Any) -> None:
    if what == PEAK_STRESS:
        from tactcad.mechanics.element_strength import peak_stress_sequence

        peak_stress_sequence(geometry, material, model)
    else:
        from tactcad.mechanics.ladder import estimate

        estimate(model, geometry, material)


def _solve(root: str, model: str, geometry: Any, material: Any, what: str = STIFFNESS) -> None:
    import warnings

    from tactcad.store import Store, keeping_results

    with warnings.catch_warnings():  # the command warns once, when it reads the result
        warnings.simplefilter("ignore")
        with keeping_results(Store(Path(root))):
            _compute(what, model, geometry, material)


def _kept(model: str, geometry: Any, material: Any, what: str = STIFFNESS) -> bool:
    """Whether the active store holds ``what`` of ``geometry`` at ``model`` (nothing solved)."""
    import warnings

    from tactcad.store import NotKept, only_kept

    try:
        with warnings.catch_warnings(), only_kept():
            warnings.simplefilter("ignore")
            _compute(what, model, geometry, material)
    except NotKept:
        return False
    return True


def top_of_the_ladder(model: str) -> bool:
    """Whether ``model`` is the ladder's dearest level, the one whose elements are worth a
    process each (about a minute and a half an element; the levels below take seconds,
    less than a process's start)."""
    from tactcad.mechanics.ladder import models

    return model == models()[-1]


def solve_side_by_side(model: str, geometries: Sequence[Any], material: Any,
                       progress=None, peak_stress: bool = False,
                       stress_geometries: Sequence[Any] | None = None) -> int:
    """Solve ``geometries`` at ``model`` in up to as many processes as cores, into the
    active store; the number of processes used (0: nothing prefetched, see the module doc).
    A failed or killed process is not an error: its element is solved later, here.

    Args:
        model: the ladder level. geometries: the elements (mm). material: their material.
        progress: takes one line naming what is solved side by side.
        peak_stress: also each element's peak-stress sequence (:data:`PEAK_STRESS`; fem3d
            only), which a verification at the level reads beside K: four solves of two
            elements share the cores where the two stress sequences ran in turn after.
        stress_geometries: with ``peak_stress``, the elements whose peak-stress sequence
            is solved (default all of ``geometries``; a verification keeps the lower
            level's stresses of the elements decided there).

    Returns:
        The number of processes used.
    """
    from concurrent.futures import ProcessPoolExecutor, wait
    import multiprocessing

    from tactcad.stopping import pool_shut_down, spawn_ready, stop_signals_held
    from tactcad.store import active_store

    store = active_store()
    cores = os.cpu_count() or 1
    if (store is None or store.root is None or cores < 2 or len(geometries) < 2
            or os.environ.get("TACTCAD_WORKERS", "1") == "0"):  # one process asked for
        return 0
    whats = (STIFFNESS, PEAK_STRESS) if peak_stress and model == "fem3d" else (STIFFNESS,)
    stressed = geometries if stress_geometries is None else stress_geometries
    tasks = [(what, g) for what in whats
             for g in (stressed if what == PEAK_STRESS else geometries)
             if not _kept(model, g, material, what)]  # every K first: the matrix reads K first
    if len(tasks) < 2:  # one left is solved here, as soon
        return 0
    n = min(cores, len(tasks))
    if progress:
        progress(f"{model}: {solves_text(tasks)} side by side in {n} processes")
    spawn_ready()
    try:
        with stop_signals_held():
            pool = ProcessPoolExecutor(n, mp_context=multiprocessing.get_context("spawn"),
                                       initializer=_start)
    except OSError:  # no process to be had: each is solved here, in turn
        return 0
    try:
        wait([pool.submit(_solve, str(store.root), model, g, material, what)
              for what, g in tasks])
    except BaseException:  # a stop: the processes' solves are not waited for
        pool_shut_down(pool, kill=True)
        raise
    pool_shut_down(pool)
    return n


def solves_text(tasks: Sequence[tuple[str, Any]]) -> str:
    """What is solved side by side, in words: "2 elements solved" for their K alone, else
    "4 solves (the K and peak stress of 2 elements)"."""
    elements = len({id(g) for _, g in tasks})
    if all(what == STIFFNESS for what, _ in tasks):
        return f"{len(tasks)} elements solved"
    stressed = sum(what == PEAK_STRESS for what, _ in tasks)
    if stressed * 2 == len(tasks):
        return f"{len(tasks)} solves (the K and peak stress of {elements} elements)"
    return (f"{len(tasks)} solves (the K of {len(tasks) - stressed} elements, the peak stress "
            f"of {stressed})")
