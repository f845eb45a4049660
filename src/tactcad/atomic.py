"""Atomic writes: a reader sees the old file (or the old set of files) or the
new one, never half of one."""

from __future__ import annotations

import contextlib
import errno
import glob
import os
import shutil
import tempfile
from pathlib import Path
from typing import Callable, Iterator


@contextlib.contextmanager
def atomic_path(target: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``target``; on success it replaces ``target``
    (``os.replace``, atomic on POSIX), on any error it is removed."""
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part", dir=target.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    os.chmod(tmp_path, 0o644)  # mkstemp creates 0600; exports are for sharing
    try:
        yield tmp_path
        with open(tmp_path, "rb+") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp_path, target)
    finally:
        if tmp_path.exists():
            tmp_path.unlink()


def remove_partial_files(folder: Path) -> None:
    """Remove the temporary files of :func:`atomic_path` under ``folder`` that a
    killed writer left (none of them is a finished file)."""
    for tmp in folder.rglob(".*.part"):
        tmp.unlink(missing_ok=True)


def write_atomic(target: str | Path, writer: Callable[[Path], object]) -> Path:
    """Call ``writer(tmp_path)`` and move the result onto ``target`` atomically."""
    with atomic_path(target) as tmp:
        writer(tmp)
    return Path(target)


def write_bytes_atomic(target: str | Path, data: bytes) -> Path:
    return write_atomic(target, lambda p: p.write_bytes(data))


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


def staging_dir(target: Path) -> Path:
    """A new empty folder beside ``target`` (same file system, so it can take
    its place in one rename), named ``.<target>.staging-*``."""
    target.parent.mkdir(parents=True, exist_ok=True)
    return Path(tempfile.mkdtemp(prefix=f".{target.name}.staging-", dir=target.parent))


def leftover_staging(target: Path) -> list[Path]:
    """Staging folders of ``target`` that a killed run left behind."""
    if not target.parent.is_dir():
        return []
    return sorted(p for p in target.parent.glob(f".{glob.escape(target.name)}.staging-*")
                  if p.is_dir() and not p.is_symlink())


def carry_over(old: Path, new: Path, keep: Callable[[str], bool]) -> list[str]:
    """Link (or copy) into ``new`` every file of ``old`` whose relative path
    ``keep`` accepts and ``new`` does not have; returns those paths."""
    kept = []
    for path in sorted(old.rglob("*")):
        rel = path.relative_to(old).as_posix()
        if path.is_dir() or not keep(rel) or (new / rel).exists():
            continue
        (new / rel).parent.mkdir(parents=True, exist_ok=True)
        try:
            os.link(path, new / rel, follow_symlinks=False)
        except OSError:
            shutil.copy2(path, new / rel, follow_symlinks=False)
        kept.append(rel)
    return kept


def publish_dir(staging: Path, target: Path) -> None:
    """Put the finished folder ``staging`` in the place of ``target``.

    Where the system can (Linux, most local file systems) the two are swapped
    in one atomic step, so a reader, or a run killed at any moment, finds
    either the whole old folder or the whole new one; the old one is then
    removed. Elsewhere the old folder is renamed aside first (a killed run
    can then leave ``target`` missing for an instant, the old set beside it).
    """
    if not target.exists():
        os.rename(staging, target)
        return
    if _exchange(staging, target):
        shutil.rmtree(staging, ignore_errors=True)
        return
    aside = Path(tempfile.mkdtemp(prefix=f".{target.name}.old-", dir=target.parent))
    os.rename(target, aside / "old")
    os.rename(staging, target)
    shutil.rmtree(aside, ignore_errors=True)
