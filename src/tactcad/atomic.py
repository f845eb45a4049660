"""Atomic writes: a reader sees the old file (or the old set of files) or the
new one, never half of one."""

from __future__ import annotations

import contextlib
import errno
import glob
import hashlib
import os
import shutil
import tempfile
from pathlib import Path
from typing import Callable, Iterator


@contextlib.contextmanager
def atomic_path(target: str | Path, noted: bool = True, durable: bool = True) -> Iterator[Path]:
    """Yield a temporary path beside ``target``; on success it replaces ``target``
    (``os.replace``, atomic on POSIX), on any error it is removed. ``noted``: the file
    counts among what an interrupted run says it wrote (:func:`note_changed`); False for
    a store's entries, which are no file of the user's. ``durable``: the file is flushed
    to the disk (``fsync``, milliseconds each) before it takes the target's place, so a
    power cut never leaves it empty; False for a store's entries, which a reader that
    finds one damaged takes as a miss (and recomputes)."""
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part", dir=target.parent)
    except OSError as exc:  # no room for the temporary file: name the file being written
        raise OSError(exc.errno, exc.strerror, str(target)) from exc
    os.close(fd)
    tmp_path = Path(tmp)
    os.chmod(tmp_path, 0o644)  # mkstemp creates 0600; exports are for sharing
    try:
        yield tmp_path
        if durable:
            with open(tmp_path, "rb+") as fh:
                os.fsync(fh.fileno())
        os.replace(tmp_path, target)
        if noted and not any(".staging-" in part for part in target.parent.parts):  # published
            note_changed(target)
    except OSError as exc:  # name the file being written, not its temporary name
        if exc.filename not in (None, str(tmp_path)) or exc.errno is None:
            raise  # a write() error names no file: it is this one
        raise OSError(exc.errno, exc.strerror, str(target)) from exc
    finally:
        if tmp_path.exists():
            tmp_path.unlink()


#: Free space (bytes) below which a writer's failure is put down to a full disk.
NEARLY_FULL_BYTES = 1 << 20


def free_bytes(path: str | Path) -> int | None:
    """Bytes free to this user on the file system holding ``path`` (or its
    nearest existing parent); None when the system cannot tell."""
    p = Path(path)
    while not p.exists() and p != p.parent:
        p = p.parent
    try:
        st = os.statvfs(p)
    except (OSError, AttributeError):
        return None
    return st.f_bavail * st.f_frsize


def disk_full_error(path: str | Path) -> OSError | None:
    """``OSError(ENOSPC)`` naming ``path`` when its file system is (nearly)
    full, else None: for writers that fail without saying why (OpenCascade's
    STEP writer returns a status, a subprocess an exit code)."""
    free = free_bytes(path)
    if free is not None and free < NEARLY_FULL_BYTES:
        return OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))
    return None


def unmakeable_folder(target: str | Path) -> str | None:
    """Why the folder ``target`` (or the staging folder beside it, :func:`staging_dir`)
    cannot be made, in words, or None when it can: the nearest existing folder on its way
    is a file, or takes no new folder (a probe folder is made there and removed at once,
    so a refusal leaves nothing behind).

    Args:
        target: the folder asked for (absolute or relative).

    Returns:
        The reason (naming the folder that refuses it and the system's words), or None.
    """
    target = Path(os.path.abspath(os.path.expanduser(str(target))))
    above = next(p for p in target.parents if p.exists() or p == p.parent)
    if not above.is_dir():
        return f"{above} is a file, not a folder"
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".tactcad-probe-", dir=above))
    except OSError as exc:
        if exc.errno in (errno.ENOSPC, errno.EDQUOT):
            return None  # a full disk is the writer's to report (disk_full_error), exit 3
        words = {errno.EROFS: "a read-only file system", errno.EACCES: "permission denied",
                 errno.EPERM: "permission denied"}
        cause = words.get(exc.errno, (exc.strerror or type(exc).__name__).lower())
        return f"no folder can be made in {above}: {cause}"
    return None


#: Folders tactcad never writes into itself (``--out`` of every command): the system's
#: top folders and the root; below the ones users write in (``/home``, ``/tmp``, ``/var``,
#: ``/opt``, ``/mnt`` ...) any folder is allowed.
SYSTEM_DIRS = ("/", "/bin", "/boot", "/dev", "/etc", "/home", "/lib", "/lib64", "/media",
               "/mnt", "/opt", "/proc", "/root", "/run", "/sbin", "/srv", "/sys", "/tmp", "/usr",
               "/var")
#: System folders whose whole tree tactcad never writes into.
SYSTEM_TREES = ("/bin", "/boot", "/dev", "/etc", "/lib", "/lib64", "/proc", "/run", "/sbin",
                "/sys", "/usr")
#: The folders the rule refuses, as ``--help`` and the refusal say them.
SYSTEM_RULE = (f"outside the system folders ({', '.join(d for d in SYSTEM_DIRS if d != '/tmp')} "
               f"and anything below {', '.join(SYSTEM_TREES)})")


def in_system_folder(folder: str | Path) -> bool:
    """True when tactcad must not write into ``folder``: one of :data:`SYSTEM_DIRS` (but
    ``/tmp``, where users write) or anything below one of :data:`SYSTEM_TREES`.

    Args:
        folder: the folder a command would write into (made absolute, links followed).

    Returns:
        Whether the rule refuses it.
    """
    real = Path(os.path.abspath(os.path.expanduser(str(folder)))).resolve()
    return (str(real) in SYSTEM_DIRS and str(real) != "/tmp") \
        or any(real.is_relative_to(t) for t in SYSTEM_TREES)


#: The longest name of a file or folder (bytes) where the file system does not say: the
#: limit of ext4, XFS, Btrfs, APFS and NTFS alike.
NAME_MAX_BYTES = 255


def name_limit_bytes(path: Path) -> int:
    """The longest name (bytes) the file system holding ``path`` takes: asked of its nearest
    folder that exists, else :data:`NAME_MAX_BYTES`."""
    for folder in (path, *path.parents):
        try:
            if folder.is_dir():
                return int(os.pathconf(folder, "PC_NAME_MAX"))
        except (OSError, ValueError, AttributeError):  # a name too long itself, no pathconf
            continue
    return NAME_MAX_BYTES


def too_long_name(given: str | Path) -> tuple[str, int, int] | None:
    """The first name along a path longer than its file system takes.

    Args:
        given: the path as given (``~`` expanded, made absolute).

    Returns:
        (the name, its length, the limit), both in bytes, or None where every name fits.
    """
    path = Path(os.path.abspath(os.path.expanduser(str(given))))
    limit = name_limit_bytes(path)
    for name in path.parts[1:]:
        size = len(os.fsencode(name))
        if size > limit:
            return name, size, limit
    return None


def refuse_too_long_name(option: str, given: object, what: str = "a folder") -> None:
    """Refuse an output path with a name the file system cannot hold, before anything is
    made (the system's own refusal would name the whole path as its field).

    Args:
        option: the option named in the refusal, e.g. ``--out``.
        given: the value as the user gave it.
        what: what the option names (``a folder``, ``a file``).

    Raises:
        DesignError: naming ``option``, the value and the file system's limit.
    """
    from tactcad.errors import DesignError

    long = too_long_name(str(given))
    if long is not None:
        _, size, limit = long
        raise DesignError(option, str(given), f"{what} whose every name is at most {limit} "
                          "bytes (the file system's limit)",
                          f"one of its names is {size} bytes")


def refuse_system_folder(option: str, given: object, folder: str | Path,
                         what: str = "a folder") -> None:
    """Refuse an output in a system folder: the one rule of every ``--out``.

    Args:
        option: the option named in the refusal, e.g. ``--out``.
        given: the value as the user gave it.
        folder: the folder that would be written into (for a file, its folder).
        what: what the option names (``a folder``, ``a file``).

    Raises:
        DesignError: naming ``option``, the value and :data:`SYSTEM_RULE`.
    """
    from tactcad.errors import DesignError

    refuse_too_long_name(option, given, what)
    if in_system_folder(folder):
        raise DesignError(option, str(given), f"{what} {SYSTEM_RULE}")


def _not_writable_words(folder: Path) -> str:
    """Why this user cannot write in ``folder``, in words."""
    try:
        read_only = bool(os.statvfs(folder).f_flag & os.ST_RDONLY)
    except (OSError, AttributeError):
        read_only = False
    return "a read-only file system" if read_only else "permission denied"


def refuse_output_path(option: str, given: object, what: str = "a file") -> Path:
    """Refuse, before any work, an output a command could not write or must not: the one
    rule of every option naming a file or folder a command writes (``--out``, ``--vtk``,
    ``--junit``, ``--plot`` ...). A name too long for the file system, a system folder
    (:func:`refuse_system_folder`), a folder that exists but is not writable, a file on the
    way, and a missing folder that would be made in a system folder or in a folder this user
    cannot write are refused; missing folders below a writable folder outside the system
    folders are the command's to make (as ``export --out`` makes them).

    Args:
        option: the option named in the refusal, e.g. ``--out``.
        given: the value as the user gave it.
        what: ``a file`` (written into its folder) or ``a folder`` (written, or written into).

    Returns:
        The path, absolute (``~`` expanded).

    Raises:
        DesignError: naming ``option``, the value and what is allowed.
    """
    from tactcad.errors import DesignError

    try:
        return _output_path_kept(option, given, what)
    except (OSError, RuntimeError) as exc:  # a path too long in all, a loop of links
        raise DesignError(option, str(given), f"{what} the system can name",
                          reason_in_words(exc) if isinstance(exc, OSError)
                          else "a loop of symbolic links") from None


def _output_path_kept(option: str, given: object, what: str) -> Path:
    """:func:`refuse_output_path`'s checks, the system's own errors let through."""
    from tactcad.errors import DesignError

    path = Path(os.path.abspath(os.path.expanduser(str(given))))
    folder = path if what == "a folder" else path.parent
    refuse_system_folder(option, given, folder, what)
    writable = "a writable folder (new or existing)" if what == "a folder" \
        else "a file in a writable folder"
    if what == "a folder" and path.exists() and not path.is_dir():
        raise DesignError(option, str(given), writable, f"{path} is a file, not a folder")
    if what != "a folder" and path.is_dir():
        raise DesignError(option, str(given), "a file name, not a folder", f"{path} is a folder")
    nearest = next(p for p in (folder, *folder.parents) if p.exists() or p == p.parent)
    if not nearest.is_dir():
        raise DesignError(option, str(given), writable, f"{nearest} is a file, not a folder")
    if nearest != folder and in_system_folder(nearest):
        missing = next(p for p in (folder, *folder.parents) if p.parent == nearest)
        raise DesignError(option, str(given), f"{what} whose missing folders are made in an "
                          "existing folder that is not a system folder",
                          f"{missing} does not exist and would be made in {nearest}, a system "
                          "folder")
    if not os.access(nearest, os.W_OK | os.X_OK):
        words = _not_writable_words(nearest)
        if nearest == folder:  # it is there: it takes no file
            raise DesignError(option, str(given), writable,
                              f"{folder} exists and is not writable: {words}")
        raise DesignError(option, str(given), "a folder that can be made" if folder == path
                          else f"{what} in a folder that can be made",
                          f"no folder can be made in {nearest}: it is not writable ({words})")
    return path


def write_failed(path: str | Path, what: str) -> OSError:
    """The error for a writer that reported failure at ``path``: a full disk
    when it is one (:func:`disk_full_error`), else an I/O error naming ``what``."""
    return disk_full_error(path) or OSError(errno.EIO, f"{what} failed", str(path))


#: The system's reasons a removal fails, in words (errno -> words); others are its own.
_REMOVAL_WORDS = {errno.EACCES: "permission denied", errno.EPERM: "permission denied",
                  errno.EROFS: "a read-only file system", errno.EBUSY: "in use"}


def reason_in_words(exc: BaseException | None) -> str:
    """Why an operation on a path failed, in words (``permission denied``).

    Args:
        exc: the error raised (None: the reason is not known).

    Returns:
        The words, from the error's errno where it has one.
    """
    if not isinstance(exc, OSError):
        return "cause not known" if exc is None else type(exc).__name__
    return _REMOVAL_WORDS.get(exc.errno, (exc.strerror or type(exc).__name__).lower())


def remove_tree(path: Path) -> list[tuple[str, str]]:
    """Remove the folder ``path``.

    Args:
        path: the folder to remove with all it holds.

    Returns:
        What could not be removed (a read-only leftover, another user's files), each as
        (path, why in words: :func:`reason_in_words`), which the caller reports; empty when
        the folder is gone.
    """
    stuck: list[tuple[str, str]] = []

    def failed(fn, failed_path, exc_info) -> None:
        stuck.append((str(failed_path), reason_in_words(exc_info[1] if exc_info else None)))

    shutil.rmtree(path, onerror=failed)
    if not path.exists():
        return []
    if str(path) not in {p for p, _ in stuck}:  # the folder itself is left: it is named first
        stuck.insert(0, (str(path), "directory not empty"))
    return stuck


def folder_bytes(path: Path) -> int:
    """Bytes of the files under ``path`` that can be seen (unreadable folders count 0)."""
    total = 0
    for root, _, names in os.walk(path):
        for name in names:
            with contextlib.suppress(OSError):
                total += os.lstat(os.path.join(root, name)).st_size
    return total


def _outermost(stuck: list[tuple[str, str]]) -> list[str]:
    """The paths of ``stuck`` inside no other path of it (a folder, not all it holds)."""
    listed = dict.fromkeys(p for p, _ in stuck)
    return [p for p in listed if not any(str(a) in listed for a in Path(p).parents)]


def _reasons(stuck: list[tuple[str, str]]) -> str:
    """The distinct reasons of ``stuck``; "directory not empty", which follows from the
    others, only when it is the one."""
    words = list(dict.fromkeys(w for _, w in stuck))
    return ", ".join([w for w in words if w != "directory not empty"] or words)


def _sized(path: str) -> str:
    """``path``, with its size in MB for a folder."""
    return f"{path} ({folder_bytes(Path(path)) / 1e6:.1f} MB)" if os.path.isdir(path) else path


def warn_left_behind(stuck: list[tuple[str, str]]) -> None:
    """One warning naming what could not be removed (the outermost paths, a folder's size)
    and why; nothing when all went.

    Args:
        stuck: (path, why in words) as :func:`remove_tree` returns them.
    """
    if stuck:
        import warnings

        from tactcad.errors import LeftoverWarning

        paths = _outermost(stuck)
        shown = ", ".join(map(_sized, paths[:5])) + (f" and {len(paths) - 5} more"
                                                     if len(paths) > 5 else "")
        warnings.warn(f"could not remove {len(paths)} leftover path(s) of an earlier or failed "
                      f"run ({_reasons(stuck)}): {shown}; remove them as a user who may",
                      LeftoverWarning, stacklevel=2)


def warn_old_export_left(old: Path, target: Path, stuck: list[tuple[str, str]]) -> None:
    """One warning for an export folder replaced but not removed: the new export in
    ``target`` is whole, the old one stays hidden beside it as ``old`` (a leftover
    :func:`leftover_staging` finds, so the next run that may remove it does).

    Args:
        old: the hidden folder now holding the old export.
        target: the export folder (holding the new export).
        stuck: (path, why in words) as :func:`remove_tree` returns them; nothing is said
            when empty.
    """
    if not stuck:
        return
    import warnings

    from tactcad.errors import LeftoverWarning

    size = folder_bytes(old) / 1e6
    warnings.warn(f"the old export replaced in {target} could not be removed "
                  f"({_reasons(stuck)}: {stuck[0][0]}); it is kept as {old} ({size:.1f} MB). "
                  f"The new export is whole. Remove it as a user who may (rm -rf {old}); the "
                  f"next export into {target} by such a user removes it", LeftoverWarning,
                  stacklevel=2)


def unremovable_tree(folder: Path) -> str | None:
    """Why the files in ``folder`` cannot all be removed by this user, in words (the first
    folder that takes no removal, and why), or None when they can as far as the system's
    permissions tell (a folder must be writable and searchable to lose its entries).

    Args:
        folder: an existing folder (an export about to be replaced).

    Returns:
        ``<folder>: permission denied`` (or ``a read-only file system``), or None.
    """
    for root, _, _ in os.walk(folder, onerror=lambda exc: None):
        if not os.access(root, os.W_OK | os.X_OK):
            read_only = bool(os.statvfs(root).f_flag & os.ST_RDONLY)
            return f"{root}: {'a read-only file system' if read_only else 'permission denied'}"
    return None


#: Paths this process changed (a folder replaced whole, a file written in place), for the
#: line an interrupt ends with (:func:`changed_paths`).
_CHANGED: list[str] = []


def note_changed(path: str | Path) -> None:
    """Record that this run has changed ``path`` (a folder replaced, a file written), so an
    interrupt's line says so instead of "the previous files are left as they were".

    Args:
        path: the folder or file, as the user named it or absolute.
    """
    if str(path) not in _CHANGED:
        _CHANGED.append(str(path))


def forget_changed() -> None:
    """Start a new run's record of :func:`note_changed` (a command run in this process)."""
    _CHANGED.clear()


def changed_paths() -> list[str]:
    """The paths :func:`note_changed` recorded in this process that are still there (a
    temporary folder removed since is not), in order."""
    return [p for p in _CHANGED if os.path.lexists(p)]


def remove_partial_files(folder: Path) -> None:
    """Remove the temporary files of :func:`atomic_path` under ``folder`` that a
    killed writer left (none of them is a finished file)."""
    for tmp in folder.rglob(".*.part"):
        tmp.unlink(missing_ok=True)


def write_atomic(target: str | Path, writer: Callable[[Path], object],
                 noted: bool = True) -> Path:
    """Call ``writer(tmp_path)`` and move the result onto ``target`` atomically (``noted``:
    see :func:`atomic_path`)."""
    with atomic_path(target, noted) as tmp:
        writer(tmp)
    return Path(target)


def write_bytes_atomic(target: str | Path, data: bytes, noted: bool = True,
                       durable: bool = True) -> Path:
    """Write ``data`` to ``target`` atomically (``noted``, ``durable``: see
    :func:`atomic_path`)."""
    with atomic_path(target, noted, durable) as tmp:
        tmp.write_bytes(data)
    return Path(target)


# ---------------------------------------------------------------------------
# Whole sets of files: a folder is replaced by another in one step
# ---------------------------------------------------------------------------
_RENAME_EXCHANGE = 2  # linux/fs.h
_AT_FDCWD = -100


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths in one atomic step (Linux ``renameat2`` with
    ``RENAME_EXCHANGE``); False where the system or file system cannot."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        fn = libc.renameat2
    except (OSError, AttributeError):
        return False
    if fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EXDEV):
        return False
    raise OSError(err, os.strerror(err), str(b))


@contextlib.contextmanager
def writing_lock(target: Path, option: str = "--out") -> Iterator[Path]:
    """Hold, for the block, the lock of the folder ``target``: one run at a time writes it
    (a second one's clean-up would delete the first's staging folder under it). The lock
    is ``flock`` on ``.<target>.lock`` beside the folder, never in it; the system frees it
    when the process ends, killed or not, and the file is removed on the way out.

    Args:
        target: the folder about to be written (its parent is made when missing).
        option: the option that named it, for the refusal (``--out``).

    Yields:
        The lock file's path.

    Raises:
        ExportPathError: another run holds the lock (refused at once, naming ``option``
            and the folder).
        OSError: the lock file cannot be made (naming ``target``).
    """
    import fcntl

    from tactcad.errors import ExportPathError

    lock = target.parent / f".{target.name}.lock"
    while True:
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            fd = os.open(lock, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise OSError(exc.errno, exc.strerror, str(target)) from exc
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            os.close(fd)
            raise ExportPathError(f"{option} {target}: another tactcad run is writing this "
                                  "folder now; wait for it to end, or name another folder") \
                from None
        try:  # the run that held it may have removed the file: hold the one on disk
            held = os.path.samestat(os.fstat(fd), os.stat(lock))
        except FileNotFoundError:
            held = False
        if held:
            break
        os.close(fd)
    try:
        yield lock
    finally:
        with contextlib.suppress(OSError):
            os.unlink(lock)  # removed while still held: a waiting run makes a new one
        os.close(fd)


def staging_dir(target: Path) -> Path:
    """A new empty folder beside ``target`` (same file system, so it can take
    its place in one rename), named ``.<target>.staging-*``.

    Raises:
        OSError: naming ``target`` (the folder asked for), not the staging one.
    """
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        return Path(tempfile.mkdtemp(prefix=f".{target.name}.staging-", dir=target.parent))
    except OSError as exc:
        raise OSError(exc.errno, exc.strerror, str(target)) from exc


def in_target(exc: OSError, staging: Path, target: Path) -> OSError:
    """``exc`` with a path in ``staging`` (of :func:`staging_dir`) shown as the
    same path in ``target``, the folder asked for, which the staging folder
    becomes; an error that names no file (a failed write()) names ``target``."""
    name = str(exc.filename or staging)
    if exc.errno is None or not name.startswith(str(staging)):
        return exc
    return OSError(exc.errno, exc.strerror, str(target) + name[len(str(staging)):])


def leftover_staging(target: Path) -> list[Path]:
    """Folders beside ``target`` that an earlier run left behind: a killed run's staging
    folder, or an old export replaced but not removed (``.<target>.staging-*`` after a
    swap, ``.<target>.old-*`` after a rename aside).

    Args:
        target: the export folder.

    Returns:
        Those folders, sorted (none when ``target``'s parent is missing).
    """
    if not target.parent.is_dir():
        return []
    name = glob.escape(target.name)
    found = [*target.parent.glob(f".{name}.staging-*"), *target.parent.glob(f".{name}.old-*")]
    return sorted(p for p in found if p.is_dir() and not p.is_symlink())


def carry_over(old: Path, new: Path, keep: Callable[[str], bool],
               copy: bool = False) -> list[str]:
    """Link (or copy) into ``new`` every file of ``old`` whose relative path
    ``keep`` accepts and ``new`` does not have; returns those paths.

    Args:
        old: the folder the files are in.
        new: the folder they go into (sub-folders made as needed).
        keep: which relative paths (POSIX) to carry.
        copy: copy each file, never link it: for files a writer may write over
            in ``new`` before it is published (a link would be written through).

    Returns:
        The relative paths carried, in sorted order.
    """
    kept = []
    for path in sorted(old.rglob("*")):
        rel = path.relative_to(old).as_posix()
        if path.is_dir() or not keep(rel) or (new / rel).exists():
            continue
        (new / rel).parent.mkdir(parents=True, exist_ok=True)
        _link_or_copy(path, new / rel, copy)
        kept.append(rel)
    return kept


def _link_or_copy(source: Path, target: Path, copy: bool) -> None:
    """Make ``target`` a hard link to ``source``, or a copy of it where it cannot be
    linked (another file system) or ``copy`` asks for one."""
    if not copy:
        try:
            os.link(source, target, follow_symlinks=False)
            return
        except OSError:
            pass
    shutil.copy2(source, target, follow_symlinks=False)


def publish_dir(staging: Path, target: Path) -> None:
    """Put the finished folder ``staging`` in the place of ``target``.

    Where the system can (Linux, most local file systems) the two are swapped
    in one atomic step, so a reader, or a run killed at any moment, finds
    either the whole old folder or the whole new one; the old one is then
    removed. Elsewhere the old folder is renamed aside first (a killed run
    can then leave ``target`` missing for an instant, the old set beside it).
    The old folder that cannot be removed (another user's files) stays beside ``target``
    under a hidden name, said in one warning (:func:`warn_old_export_left`); the next run
    that may remove it does (:func:`leftover_staging`).
    """
    if not target.exists():
        os.rename(staging, target)
        note_changed(target)
        return
    if _exchange(staging, target):
        note_changed(target)
        warn_old_export_left(staging, target, remove_tree(staging))
        return
    aside = Path(tempfile.mkdtemp(prefix=f".{target.name}.old-", dir=target.parent))
    os.rename(target, aside / "old")
    os.rename(staging, target)
    note_changed(target)
    warn_old_export_left(aside, target, remove_tree(aside))


def file_sha256(path: str | Path) -> str:
    """sha256 (hex) of a file's bytes, read in chunks (a large STEP or GLB is not held whole).

    Raises:
        OSError: the file cannot be read.
    """
    with open(path, "rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest()

