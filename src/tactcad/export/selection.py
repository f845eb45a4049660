"""Part of an export (``tactcad export --only KINDS --part NAME``) and its progress.

A job's kind is the word before the colon of its name (``step:element_a4mm``,
``dxf:shop``, ``scene:array``, ``review:...``, ``drawing:cart``,
``drawings:pdf``, ``image:array``, ``bom``); the STEP and drawing jobs belong
to one part, named after the colon. The shop DXF job writes every part's profile
and the nested sheets: ``--part`` cuts it down to the part's own profile files
(``dxf:<part>``, :attr:`~tactcad.export.job.Job.for_part`), a sheet nesting every
part cut from it being no one part's. Jobs that cover many parts in one file
(the nested sheets, the scenes, the PDF, the BOM) have no part and are left out
by ``--part``.
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Callable, Collection, Sequence

from tactcad.errors import DesignError
from tactcad.export.job import Job, Run
from tactcad.export.kinds import EXPORT_KINDS
from tactcad.store import content_key


def job_kind(name: str) -> str:
    """The ``--only`` kind of a job name (``"drawings:pdf"`` -> ``"drawings"``)."""
    prefix = name.split(":", 1)[0]
    return next((k.name for k in EXPORT_KINDS.values() if prefix in k.prefixes), prefix)


def job_part(name: str) -> str | None:
    """The part a job writes alone (``"step:cart"`` -> ``"cart"``), None for a job of many."""
    prefix, _, rest = name.partition(":")
    part_prefixes = {k.part_prefix for k in EXPORT_KINDS.values() if k.part_prefix}
    return rest if prefix in part_prefixes and rest else None


#: What ``--part`` keeps, for ``--help`` and its refusal.
PART_KEEPS = ("a part's own STEP, drawing and DXF profile files (dxf/<part>_qty<n>.dxf; "
              "not the nested sheets, which hold every part cut from them)")


def select_jobs(jobs: Sequence[Job], only: Sequence[str] = (),
                parts: Sequence[str] = ()) -> list[Job]:
    """The jobs of the kinds ``only`` and the parts ``parts`` (empty: no filter).

    A job of many parts that can write a part's own files alone (the shop DXF,
    :attr:`~tactcad.export.job.Job.for_part`) stands, with ``parts``, for one job per
    named part it has files of. A kept job that reads the files of jobs left out (the
    BOM lists the files present) is given a key of its own, so the store never hands it
    the copy a full export made; the earlier export's files it finds in their place go
    into that key too (:func:`with_kept_files`, once the export folder is known).

    Args:
        jobs: every job of the run, in order.
        only: the ``--only`` kinds.
        parts: the ``--part`` names.

    Returns:
        The jobs to run, in order.

    Raises:
        DesignError: a part no job writes alone (the message lists them), or
            a selection that leaves no job.
    """
    split = _jobs_with_parts(jobs, parts)
    known = sorted({p for p in map(job_part, (j.name for j in jobs)) if p}
                   | {p for _, p in split if p})
    for name in parts:
        if name not in known:
            raise DesignError("--part", name, "one of " + ", ".join(known))
    keep = [j for j, part in split if (not only or job_kind(j.name) in only)
            and (not parts or part in parts)]
    if not keep:
        raise DesignError("--only/--part", {"only": list(only), "part": list(parts)},
                          "a selection that writes at least one file",
                          f"--part keeps {PART_KEEPS}")
    names = sorted(j.name for j in keep)
    return [replace(j, key=content_key("partial-set", j.key, names))
            if reads_left_out(j, names) else j for j in keep]


def reads_left_out(job: Job, names: Collection[str]) -> bool:
    """True if ``job`` reads the files of a job not among ``names`` (the jobs run)."""
    return not set(job.after) <= set(names)


def with_kept_files(jobs: Sequence[Job], kept: Sequence[dict]) -> list[Job]:
    """The selected ``jobs``, each that reads the files of jobs left out keyed by the
    earlier export's files it finds in their place too (``kept``: the manifest records,
    path and sha256, of the files a partial export carries into its staging folder before
    its jobs run), so the store hands such a job only to a run that finds the same files.

    Args:
        jobs: the jobs of a partial export (:func:`select_jobs`), in order.
        kept: the earlier export's records of the files found beside them; empty: none.

    Returns:
        The jobs, in order; unchanged when ``kept`` is empty.
    """
    if not kept:
        return list(jobs)
    found = sorted((f["path"], f.get("sha256")) for f in kept)
    names = {j.name for j in jobs}
    return [replace(j, key=content_key("kept-files", j.key, found))
            if reads_left_out(j, names) else j for j in jobs]


def _jobs_with_parts(jobs: Sequence[Job], parts: Sequence[str]) -> list[tuple[Job, str | None]]:
    """Each job with the part it writes alone (None: a job of many); with ``parts``, a job
    that can be cut down to a part's own files is replaced by one such job per named part
    it has files of."""
    found: list[tuple[Job, str | None]] = []
    for job in jobs:
        if parts and job.for_part is not None:
            found += [(own, name) for name in parts if (own := job.for_part(name)) is not None]
        else:
            found.append((job, job_part(job.name)))
    return found


def partial_record(only: Sequence[str], parts: Sequence[str], jobs: Sequence[Job]) -> dict:
    """What the manifest says of a partial export: the selection and the jobs run."""
    return {"only": list(only), "part": list(parts), "jobs": [j.name for j in jobs],
            "note": "a partial export: only the files listed here were written"}


def with_progress(jobs: Sequence[Job], report: Callable[[str], None]) -> list[Job]:
    """The jobs, each reporting ``[k/n] name seconds`` when it has run (a job
    taken from the store does not run and reports nothing)."""
    n = len(jobs)

    def timed(k: int, job: Job) -> Job:
        def make(run: Run) -> list[dict]:
            t0 = time.perf_counter()
            records = job.make(run)
            report(f"[{k}/{n}] {job.name} {time.perf_counter() - t0:.1f} s")
            return records
        return replace(job, make=make)

    return [timed(k, job) for k, job in enumerate(jobs, start=1)]


#: Solid builds shorter than this (s) are not reported: most take milliseconds.
REPORT_BUILD_S = 1.0


class ReportingParts:
    """A run's part cache, made on first use (so a run with nothing to build
    never loads the CAD kernel), that reports each solid whose build took
    :data:`REPORT_BUILD_S` or more. Anything else is the cache's own."""

    def __init__(self, plan, report: Callable[[str], None]):
        self.plan = plan
        self._report = report
        self._cache = None

    def _real(self):
        if self._cache is None:
            from tactcad.solids.cache import PartCache

            self._cache = PartCache(self.plan)
        return self._cache

    @property
    def builds(self) -> int:
        return 0 if self._cache is None else self._cache.builds

    def solid(self, spec):
        cache = self._real()
        before, t0 = cache.builds, time.perf_counter()
        solid = cache.solid(spec)
        seconds = time.perf_counter() - t0
        if cache.builds > before and seconds >= REPORT_BUILD_S:
            self._report(f"  built {spec.name} {seconds:.1f} s")
        return solid

    def __getattr__(self, name: str):
        return getattr(self._real(), name)
