"""The thread count of the OpenBLAS libraries numpy and scipy load.

A dense solve of a few thousand unknowns (the contact model's collocation system) or the
FEM iteration's small BLAS calls gain little from BLAS threads on two cores, and on a
shared, loaded machine the threads' idle spinning costs more CPU time than it saves: the
tissue coupling's contact solves of a design search took about three times the CPU time
(and more wall time) on two threads as on one.

Works like threadpoolctl: the OpenBLAS builds that numpy and scipy load expose
``*_set_num_threads``; a block's old count is restored on exit. A no-op where no such
library is found (e.g. not Linux).
"""

from __future__ import annotations

import contextlib
import ctypes
import sys
from typing import Callable, Iterator

#: The symbol prefixes and suffixes of the OpenBLAS builds' thread setters and getters.
_PREFIXES = ("scipy_openblas", "openblas")
_SUFFIXES = ("64_", "")


def _openblas_paths() -> list[str]:
    """The OpenBLAS libraries this process has loaded (their paths), sorted."""
    try:
        with open("/proc/self/maps", encoding="utf-8") as fh:
            paths = {ln.split()[-1] for ln in fh if "openblas" in ln.lower() and "/" in ln}
    except OSError:
        paths = set()
    return sorted(paths)


#: The controls last found and the module count they were found at (:func:`blas_thread_controls`).
_FOUND: list = [None, None]


def blas_thread_controls() -> list[tuple[Callable[[int], object], Callable[[], int]]]:
    """(setter, getter) of each loaded OpenBLAS library's thread count, looked up again
    only when a module has been imported since the last look: a library is loaded by
    importing an extension (numpy, scipy.linalg), and reading the process's maps and
    opening each library cost a design search's hundred contact solves about 0.2 CPU s.

    Returns:
        One pair per library found (none where none is loaded or it exposes neither).
    """
    modules = len(sys.modules)
    if _FOUND[0] != modules:
        _FOUND[1] = _found_controls()
        _FOUND[0] = modules
    return list(_FOUND[1])


def _found_controls() -> list[tuple[Callable[[int], object], Callable[[], int]]]:
    """(setter, getter) of each OpenBLAS library :func:`_openblas_paths` lists.

    Returns:
        One pair per library found (none where none is loaded or it exposes neither).
    """
    controls = []
    for path in _openblas_paths():
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for suffix in _SUFFIXES:
            found = None
            for prefix in _PREFIXES:
                setter = getattr(lib, f"{prefix}_set_num_threads{suffix}", None)
                getter = getattr(lib, f"{prefix}_get_num_threads{suffix}", None)
                if setter is not None and getter is not None:
                    found = (setter, getter)
                    break
            if found is not None:
                controls.append(found)
                break
    return controls


def blas_thread_counts() -> list[int]:
    """The thread count of each loaded OpenBLAS library (:func:`blas_thread_controls`).

    Returns:
        One count per library, in the order of :func:`blas_thread_controls`.
    """
    return [int(getter()) for _, getter in blas_thread_controls()]


@contextlib.contextmanager
def blas_threads(count: int) -> Iterator[None]:
    """Run the block with every loaded OpenBLAS library on ``count`` threads.

    Args:
        count: threads (>= 1).

    Raises:
        ValueError: ``count`` is not an integer >= 1.
    """
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise ValueError(f"count = {count!r}: allowed an integer >= 1")
    restore = []
    for setter, getter in blas_thread_controls():
        old = int(getter())
        setter(count)
        restore.append((setter, old))
    try:
        yield
    finally:
        for setter, old in restore:
            setter(old)


def single_threaded_blas() -> contextlib.AbstractContextManager[None]:
    """Run the block with the process's OpenBLAS libraries on one thread
    (:func:`blas_threads` of 1); the old counts are restored on exit.

    Returns:
        The context manager.
    """
    return blas_threads(1)
