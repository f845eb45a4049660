"""Content-addressed store of finished output files, for incremental export.

A job of the export run (one STEP file, one scene, one drawing ...) has a
*key*: the sha256 of everything that shapes its output bytes, namely the
job's kind, the data it reads (part specs, placements, titles), the versions
of the CAD stack and a digest of tactcad's own code and data files (so a
changed builder invalidates what it built). A job whose key is in the store
is not run: its files and file records are copied from the store.

Layout: ``<root>/<key[:2]>/<key>/records.json``, ``sums.json`` (each file's
sha256) and the job's files under their export-relative paths. An entry is
written into a temporary folder and renamed into place, so a killed run never
leaves a half entry; a damaged entry (a file missing, emptied or changed since
it was kept, or an entry without its sums) counts as a miss and is removed, so
the run that rebuilds the job keeps it again. Nothing here imports the CAD kernel.

The same store keeps costly intermediate values (``<root>/memo/<key[:2]>/<key>.pickle``,
:meth:`Store.memo`): a part view's projected edges, and the heavy
results of the estimators (a FEM level's stiffness, peak stress or modes,
:func:`kept_result`), so ``design``, ``verify``, ``modal``, ``stiffness`` and
``check`` solve each once for all of them.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import hashlib
import json
import os
import pickle
import shutil
import tempfile
from contextvars import ContextVar
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import Any, Callable, Iterator, Mapping, Sequence, TypeVar

from tactcad.atomic import file_sha256, write_bytes_atomic

#: Default store folder, relative to the working directory (git-ignored).
#: The store's folder name in a project (the working folder's by default).
STORE_FOLDER = ".tactcad-cache"
DEFAULT_STORE = Path(STORE_FOLDER)

STACK_PACKAGES = ("build123d", "cadquery", "cadquery-ocp", "ezdxf", "trimesh", "manifold3d",
                  "numpy", "scipy", "scikit-fem", "gmsh", "reportlab", "pypdfium2",
                  "pillow")


def stack_versions() -> dict[str, str]:
    """Installed version of each package of the CAD stack (``not installed`` if absent)."""
    from importlib import metadata  # 0.1 s to import: only a store key needs it

    out = {}
    for pkg in STACK_PACKAGES:
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


@functools.lru_cache(maxsize=1)
def code_digest(root: Path | None = None) -> str:
    """sha256 over tactcad's own source and data files (path and bytes; every file
    but Python's bytecode, so the review page's script and template count too), so
    that any change of a builder or writer changes every key. ``root``: the
    package folder (None: this tactcad's)."""
    root = Path(__file__).resolve().parent if root is None else root
    h = hashlib.sha256()
    for p in sorted(root.rglob("*")):
        if p.is_file() and p.suffix != ".pyc" and "__pycache__" not in p.relative_to(root).parts:
            h.update(str(p.relative_to(root)).encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()


@functools.lru_cache(maxsize=1)
def _salt() -> str:
    return json.dumps({"code": code_digest(), "stack": stack_versions()}, sort_keys=True)


def stable_repr(obj: Any) -> str:
    """A text of ``obj`` that is the same in every process: dataclasses field
    by field (fields declared ``repr=False`` left out: a plan's source path and
    raw tables shape no output), mappings in their order, sets sorted (their
    iteration order follows string hashing, which varies between processes).

    Raises:
        TypeError: an object whose text would not be stable (a function, an
            object printed with its address).
    """
    return _stable(obj, {})


_FIELDS: dict[type, tuple[str, ...]] = {}
_SCALARS = (str, int, float, bool, type(None), Path, PurePosixPath)


def _stable(obj: Any, memo: dict[int, str]) -> str:
    t = type(obj)
    if t in _SCALARS or isinstance(obj, _SCALARS):
        return repr(obj)
    if t is list or t is tuple:
        return "[" + ", ".join(_stable(x, memo) for x in obj) + "]"
    key = id(obj)  # the object lives through this call, so its id is its own
    if key in memo:
        return memo[key]
    if hasattr(t, "__dataclass_fields__"):
        names = _FIELDS.get(t)
        if names is None:
            shown = [f for f in dataclasses.fields(t) if f.repr]
            # in the constructor's order (keyword-only fields last), so moving a
            # field into a keyword-only base class keeps the key
            names = _FIELDS[t] = tuple(f.name for f in sorted(shown, key=lambda f: bool(f.kw_only)))
        text = t.__name__ + "(" + ", ".join(
            f"{n}={_stable(getattr(obj, n), memo)}" for n in names) + ")"
    elif isinstance(obj, Mapping):
        text = "{" + ", ".join(f"{_stable(k, memo)}: {_stable(v, memo)}"
                               for k, v in obj.items()) + "}"
    elif isinstance(obj, (set, frozenset)):
        text = "set(" + ", ".join(sorted(_stable(x, memo) for x in obj)) + ")"
    elif isinstance(obj, (list, tuple)):
        text = "[" + ", ".join(_stable(x, memo) for x in obj) + "]"
    else:
        raise TypeError(f"no stable key for {t.__name__}")
    memo[key] = text
    return text


def content_key(kind: str, *material: Any) -> str:
    """Key of a job: sha256 of its kind, its inputs (:func:`stable_repr`) and
    the code and stack salt."""
    h = hashlib.sha256(_salt().encode())
    h.update(b"\0" + kind.encode())
    memo: dict[int, str] = {}
    for m in material:
        h.update(b"\0" + _stable(m, memo).encode())
    return h.hexdigest()


@dataclass(frozen=True)
class Store:
    """The store under ``root``; ``Store(None)`` stores nothing (``--no-cache``)."""

    root: Path | None

    def _entry(self, key: str) -> Path:
        assert self.root is not None
        return self.root / key[:2] / key

    def fetch(self, key: str, staging: Path) -> list[dict] | None:
        """Copy a stored job's files into ``staging``; its records, or ``None`` on a miss
        (nothing kept, or a damaged entry, which is removed: each copied file must have
        the sha256 it was kept with)."""
        if self.root is None:
            return None
        entry = self._entry(key)
        if not entry.is_dir():
            return None
        try:
            records = json.loads((entry / "records.json").read_text(encoding="utf-8"))
            sums = json.loads((entry / "sums.json").read_text(encoding="utf-8"))
            for r in records:
                target = staging / r["path"]
                target.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(entry / "files" / r["path"], target)
                if file_sha256(target) != sums[r["path"]]:
                    raise ValueError(f"{r['path']} changed since it was kept")
        except (OSError, ValueError, KeyError, TypeError):
            shutil.rmtree(entry, ignore_errors=True)  # rebuilt and kept again by this run
            return None
        return records

    def _memo_path(self, key: str) -> Path:
        assert self.root is not None
        return self.root / "memo" / key[:2] / f"{key}.pickle"

    def recall(self, key: str) -> tuple[bool, Any]:
        """``(True, value)`` for a value kept under ``key`` by an earlier run,
        else ``(False, None)`` (nothing kept, an unreadable entry, or no store)."""
        if self.root is None:
            return False, None
        try:
            return True, pickle.loads(self._memo_path(key).read_bytes())
        except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ImportError,
                ValueError, TypeError, IndexError):
            return False, None

    def remember(self, key: str, value: Any) -> None:
        """Keep ``value`` (pickled) under ``key``, written atomically: a run
        killed while writing leaves no entry, only a temporary file beside it. Not
        flushed to the disk (``fsync`` cost milliseconds an entry, a second of a cold
        export): an entry a power cut left empty or cut short does not unpickle, and
        :meth:`recall` takes it as none kept.
        Best effort: a store that cannot be written costs only the next run's time."""
        if self.root is None:
            return
        path = self._memo_path(key)
        try:
            data = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        except (pickle.PicklingError, TypeError, AttributeError):
            return  # e.g. a warning a library issued that does not pickle: not kept
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            # a store entry, not an output: an interrupt's line names no store file, and
            # no fsync (a damaged entry is a miss: recall reads it as none kept)
            write_bytes_atomic(path, data, noted=False, durable=False)
        except OSError:
            pass

    def memo(self, key: str, compute: Callable[[], Any]) -> Any:
        """``compute()``, or its pickled result stored under ``key`` by an
        earlier run (for intermediate results too costly to redo, such as a
        part view's projected edges). Unreadable entries are recomputed."""
        found, value = self.recall(key)
        if found:
            return value
        value = compute()
        self.remember(key, value)
        return value

    def keep(self, key: str, staging: Path, records: Sequence[dict]) -> None:
        """Store a finished job's files (found in ``staging``) and records, in one
        rename of a finished temporary folder: an export keeps each job as it
        finishes, so a run stopped (Ctrl-C) or killed later leaves its finished jobs
        to the next run, and one stopped in the middle of a keep leaves no entry.
        Best effort: a store that cannot be written (read-only, disk full)
        costs only the next run's time."""
        if self.root is None:
            return
        entry = self._entry(key)
        if entry.is_dir():
            return
        tmp = None
        try:
            entry.parent.mkdir(parents=True, exist_ok=True)
            tmp = Path(tempfile.mkdtemp(prefix=".tmp-", dir=entry.parent))
            for r in records:
                target = tmp / "files" / r["path"]
                target.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(staging / r["path"], target)
            (tmp / "records.json").write_text(json.dumps(list(records)),
                                              encoding="utf-8")
            sums = {r["path"]: file_sha256(tmp / "files" / r["path"]) for r in records}
            (tmp / "sums.json").write_text(json.dumps(sums), encoding="utf-8")
            os.rename(tmp, entry)
        except BaseException as exc:  # a write error, or a stop in the middle of the copy
            if tmp is not None:
                shutil.rmtree(tmp, ignore_errors=True)
            if not isinstance(exc, OSError):
                raise


# ---------------------------------------------------------------------------
# Heavy estimator results (FEM solves), kept in the same store
# ---------------------------------------------------------------------------
#: The store :func:`kept_result` uses and the values kept in this block's
#: memory: none unless a command (``--cache DIR``, ``--no-cache``; by default
#: :data:`DEFAULT_STORE`) or a caller (:func:`keeping_results`) opens a block.
_RESULTS: ContextVar[tuple[Store, dict[str, Any]] | None] = ContextVar("tactcad_results",
                                                                        default=None)

T = TypeVar("T")


@contextlib.contextmanager
def keeping_results(store: Store) -> Iterator[Store]:
    """Within the block, :func:`kept_result` keeps and reuses results in ``store``
    and, for the block's length, in memory (so even ``Store(None)``, a run
    with ``--no-cache``, solves each thing once). The commands that run the
    estimators open one block with the store their ``--cache``/``--no-cache``
    name; a Python caller may do the same.

    Yields:
        ``store``.
    """
    token = _RESULTS.set((store, {}))
    try:
        yield store
    finally:
        _RESULTS.reset(token)


@contextlib.contextmanager
def memo_scope(var: ContextVar) -> Iterator[None]:
    """Within the block, ``var`` holds one dict for answers kept in memory by their inputs
    (a search's repeated pure steps); a nested block shares the outer one's, and the dict is
    dropped on leaving the outermost.

    Args:
        var: a ``ContextVar[dict | None]`` whose default is None (no scope open).
    """
    token = var.set({}) if var.get() is None else None
    try:
        yield
    finally:
        if token is not None:
            var.reset(token)


#: Inside :func:`only_kept`, :func:`kept_result` computes nothing: a value not kept raises.
_ONLY_KEPT: ContextVar[bool] = ContextVar("tactcad_only_kept", default=False)


class NotKept(LookupError):
    """:func:`kept_result` inside :func:`only_kept` found no kept value (its ``kind``)."""


@contextlib.contextmanager
def only_kept() -> Iterator[None]:
    """Within the block, :func:`kept_result` returns kept values and raises
    :class:`NotKept` instead of computing one: whether a result is at hand, asked without
    solving it (e.g. before solving the missing ones in other processes)."""
    token = _ONLY_KEPT.set(True)
    try:
        yield
    finally:
        _ONLY_KEPT.reset(token)


@dataclass
class ResultCounts:
    """How often :func:`kept_result` answered in this process, per ``kind``: values it
    computed, values it read back (from the store or the block's memory), and values
    :func:`only_kept` asked for that were not kept (each then solved elsewhere)."""

    computed: dict[str, int] = dataclasses.field(default_factory=dict)
    reused: dict[str, int] = dataclasses.field(default_factory=dict)
    missing: dict[str, int] = dataclasses.field(default_factory=dict)

    def add(self, tally: dict[str, int], kind: str) -> None:
        """One more of ``kind`` in ``tally``.

        Args:
            tally: one of this object's three counts.
            kind: what was asked for, as :func:`kept_result` names it.
        """
        tally[kind] = tally.get(kind, 0) + 1

    def solved(self) -> int:
        """How many values were solved.

        Returns:
            values computed here plus those found missing (so solved in another process).
        """
        return sum(self.computed.values()) + sum(self.missing.values())


#: The counts since this process started (or since :func:`counting_results` last began).
_COUNTS = ResultCounts()


def result_counts() -> ResultCounts:
    """What :func:`kept_result` answered in this process so far.

    Returns:
        a copy of the counts (of the enclosing :func:`counting_results` block, if any).
    """
    return ResultCounts(dict(_COUNTS.computed), dict(_COUNTS.reused), dict(_COUNTS.missing))


@contextlib.contextmanager
def counting_results() -> Iterator[ResultCounts]:
    """Within the block, count :func:`kept_result`'s answers from zero; the yielded
    counts are filled in as the block runs (e.g. "verify after export solved nothing").

    Yields:
        the block's :class:`ResultCounts`.
    """
    global _COUNTS
    outer, _COUNTS = _COUNTS, ResultCounts()
    try:
        yield _COUNTS
    finally:
        _COUNTS = outer


def active_store() -> Store | None:
    """The store of the enclosing :func:`keeping_results` block, or None outside one."""
    block = _RESULTS.get()
    return None if block is None else block[0]


def copy_block_results(target: Path) -> int:
    """Copy every value :func:`kept_result` answered in the enclosing
    :func:`keeping_results` block (computed or read back) from the block's store into the
    store at ``target``, where another run looks for them (``design --out NEW_DIR`` solves
    into the store beside the new folder, then gives the folder the results its commands
    read). Entries ``target`` holds already, and values never written (no store, a value
    that did not pickle), are left. Best effort: a store that cannot be written costs only
    the next run's time.

    Args:
        target: the store folder to copy into (made when a value is copied).

    Returns:
        How many values were copied.
    """
    block = _RESULTS.get()
    if block is None or block[0].root is None:
        return 0
    store, memory = block
    into = Store(Path(target))
    if into.root is not None and store.root is not None and \
            os.path.abspath(into.root) == os.path.abspath(store.root):
        return 0
    copied = 0
    for key in memory:
        source, kept = store._memo_path(key), into._memo_path(key)
        if kept.is_file() or not source.is_file():
            continue
        try:
            kept.parent.mkdir(parents=True, exist_ok=True)
            write_bytes_atomic(kept, source.read_bytes(), noted=False, durable=False)
            copied += 1
        except OSError:
            pass
    return copied


#: Where :func:`kept_result` found a kept value, as a progress line says it.
REUSED_FROM_STORE = "reused from the result store"
REUSED_IN_RUN = "reused from this run's earlier solve"


def kept_result(kind: str, compute: Callable[[], T], *inputs: Any,
                reused: Callable[[str], None] | None = None) -> T:
    """``compute()``, or the value an earlier call (in this block, or an
    earlier run) of the same ``kind`` with equal ``inputs`` kept in the
    store of :func:`keeping_results`.

    The key is :func:`content_key` of ``kind`` and ``inputs``: the inputs'
    :func:`stable_repr` (an element's geometry, the material, the level and
    its mesh settings), tactcad's own code and the stack's versions, so a
    changed input, estimator or library misses; never a file path. Outside
    a :func:`keeping_results` block, or when an input has no stable text (a
    function), this is ``compute()``. A new value is written atomically
    (:meth:`Store.remember`), with the warnings its computation issued: a read of a kept
    value issues them again, in order, through the caller's filters (as
    :func:`kept_per_process` does), so a command warns alike on its first run and on a run
    that reads every solve back.

    Args:
        kind: what is computed, e.g. ``"fem3d convergence"``.
        compute: makes the value (picklable).
        inputs: everything the value depends on.
        reused: called once when a kept value is returned (a progress line), with where
            it came from: :data:`REUSED_FROM_STORE` or :data:`REUSED_IN_RUN`.

    Returns:
        the value.
    """
    block = _RESULTS.get()
    if block is None:
        return compute()
    store, memory = block
    try:
        key = content_key(kind, *inputs)
    except TypeError:
        return compute()
    in_memory = key in memory
    found, kept = (True, memory[key]) if in_memory else store.recall(key)
    if found and not isinstance(kept, _KeptResult):  # written by no kept_result: not ours
        found = False
    if found:
        _COUNTS.add(_COUNTS.reused, kind)
        if reused is not None:  # said as it is: a run without a store (--no-cache) reads none
            reused(REUSED_IN_RUN if in_memory else REUSED_FROM_STORE)
    elif _ONLY_KEPT.get():
        _COUNTS.add(_COUNTS.missing, kind)
        raise NotKept(kind)
    else:
        _COUNTS.add(_COUNTS.computed, kind)
        kept = _KeptResult(*_issued_while(compute))
        store.remember(key, kept)
    memory[key] = kept
    _say_again(kept.said)  # a kept result warns as its computation did, every time it is read
    return kept.value


@dataclass(frozen=True)
class _KeptResult:
    """What :func:`kept_result` keeps: the value and the warnings its computation issued
    (a solve outside a fit's range says so on every read, not on the first run alone)."""

    value: Any
    said: tuple["_SaidWarning", ...]


@dataclass(frozen=True)
class _SaidWarning:
    """One warning a kept computation issued: what :func:`warnings.warn_explicit` takes."""

    message: Warning | str
    category: type[Warning]
    filename: str
    lineno: int


def _issued_while(compute: Callable[[], T]) -> tuple[T, tuple[_SaidWarning, ...]]:
    """``compute()`` with every warning it issued (each one, none filtered out)."""
    import warnings

    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        value = compute()
    return value, tuple(_SaidWarning(w.message, w.category, w.filename, w.lineno)
                        for w in said)


def _say_again(said: Sequence[_SaidWarning]) -> None:
    """Issue ``said`` in order, as their computation first issued them: each goes through
    the caller's filters again, with no registry, so none is taken as already shown."""
    import warnings

    for w in said:
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, registry={})


def kept_per_process(maxsize: int = 128) -> Callable[[Callable[..., T]], Callable[..., T]]:
    """A function's results kept per process on its (hashable) arguments, as
    :func:`functools.lru_cache` keeps them, with the warnings each computation issued: a
    call that finds its result kept issues them again, so every call warns alike (a
    command's or the API's ``warnings`` list is the same on the first call of a process
    and on every later one).

    Args:
        maxsize: how many results are kept (the least recently used go first).

    Returns:
        The decorator; the decorated function keeps ``cache_clear`` and ``cache_info``.
    """
    def decorate(function: Callable[..., T]) -> Callable[..., T]:
        @functools.lru_cache(maxsize=maxsize)
        def computed(*args: Any, **kwargs: Any) -> tuple[T, tuple[_SaidWarning, ...]]:
            return _issued_while(lambda: function(*args, **kwargs))

        @functools.wraps(function)
        def called(*args: Any, **kwargs: Any) -> T:
            value, said = computed(*args, **kwargs)
            _say_again(said)
            return value

        called.cache_clear = computed.cache_clear  # type: ignore[attr-defined]
        called.cache_info = computed.cache_info  # type: ignore[attr-defined]
        return called

    return decorate


#: What ``--cache`` (and the API's ``cache``) may name.
CACHE_ALLOWED = ("a folder tactcad can write: an existing writable folder, or a new one "
                 "whose nearest existing parent is a writable folder (not a file)")


def usable_cache_folder(text: str, option: str = "--cache") -> Path:
    """The ``--cache`` folder as given, refused before any work when the store could not be
    kept there: an existing file, a folder without write access, or a new folder under a
    file or under a folder without write access (nothing is created here); a system folder,
    or a new one in a system folder (:func:`tactcad.atomic.refuse_output_path`).

    Args:
        text: ``--cache`` as typed.
        option: the name the refusal gives it (the API's ``cache`` argument).

    Returns:
        The folder's path.

    Raises:
        DesignError: naming ``--cache``, the value and what is allowed.
    """
    import os

    from tactcad.atomic import refuse_output_path
    from tactcad.errors import DesignError

    folder = Path(text)
    nearest = next((p for p in (folder, *folder.parents) if p.exists() or p.is_symlink()),
                   Path("."))
    if not nearest.is_dir():
        why = ("it is an existing file" if nearest == folder
               else f"{nearest} is not a folder")
        raise DesignError(option, text, CACHE_ALLOWED, why)
    if not os.access(nearest, os.W_OK | os.X_OK):
        raise DesignError(option, text, CACHE_ALLOWED, f"{nearest} is not writable")
    refuse_output_path(option, text, "a folder")  # the rule of every folder a command writes
    return folder
