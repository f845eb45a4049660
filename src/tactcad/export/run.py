"""The main job: a plan -> every export file and the manifest.

A run is a list of jobs (:mod:`tactcad.export.jobs`): one STEP file, one DXF,
one scene, one drawing ... each with a content key. A job found in the store
(:mod:`tactcad.store`) is copied from it; any other job runs, sharing the
run's one :class:`~tactcad.solids.cache.PartCache`, so each distinct part is
built at most once per run, and only if some job needs it. The CAD kernel is
imported only then: a run with nothing to rebuild never loads it.

Every file is first written into a staging folder beside the export folder;
only when all of them and the manifest exist does that folder take the
export folder's place, in one step (:func:`tactcad.atomic.publish_dir`). A
failed or killed run leaves the previous export whole (its staging folder is
removed by the next run); files an earlier export wrote and this one does not
are gone with the old folder, files tactcad never wrote are kept. A partial export
(``--only``/``--part``) of the same design keeps the earlier export's other files (carried
into the staging folder before its jobs run, so a job reading them, the BOM naming each
part's files, finds what the published folder holds, and the swap stays one step) and lists
them in its manifest.
"""

from __future__ import annotations

import json
import os
import time
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Sequence

from tactcad.atomic import (SYSTEM_DIRS, carry_over, disk_full_error, in_target,
                            leftover_staging, publish_dir, refuse_output_path,
                            refuse_system_folder,
                            remove_partial_files, remove_tree, staging_dir, unmakeable_folder,
                            unremovable_tree, warn_left_behind, write_bytes_atomic,
                            writing_lock)
from tactcad.design.project import Project
from tactcad.errors import ExportPathError, TactcadError
from tactcad.export.export_owner import (EarlierExport, default_product_name,
                                         files_of_same_design, kept_by_partial_export,
                                         refuse_another_designs_export,
                                         stale_check_results, written_by_tactcad)
from tactcad.export.job import Job, Log, Run
from tactcad.assembly.rig_models import get_scene_spec
from tactcad.export.jobs import all_jobs, export_inputs, scene_jobs
from tactcad.export.manifest import manifest
from tactcad.export.selection import with_kept_files
from tactcad.export.worker import (Preparing, SessionWorker, Worker, can_fork, prepared_there,
                                   worker_jobs)
from tactcad.catalogue.files import MANIFEST
from tactcad.store import Store


@dataclass
class ExportResult:
    out_dir: Path
    files: list[dict] = field(default_factory=list)
    seconds: float = 0.0
    jobs_run: int = 0
    jobs_reused: int = 0
    builds: int = 0  # solids built in this run
    distinct_parts: int = 0  # distinct parts of the design (array, scenes, the kit's samples)
    worker_jobs: int = 0  # jobs made by the run's second process
    kept: list[str] = field(default_factory=list)  # a partial export's files of the earlier one

    def as_json(self) -> dict:
        """Summary for ``--json``: seconds, job and build counts, files written (path,
        bytes, sha256) and ``kept``: the files of the earlier export a partial one kept."""
        return {"out": str(self.out_dir), "seconds": round(self.seconds, 3),
                "jobs_run": self.jobs_run, "jobs_reused": self.jobs_reused,
                "builds": self.builds, "distinct_parts": self.distinct_parts,
                "files": [{k: f[k] for k in ("path", "bytes", "sha256", "part") if k in f}
                          for f in self.files], "kept": list(self.kept)}

    def summary_lines(self) -> list[str]:
        lines = [f"{f['path']:<34} {f['bytes']:>9,d} B  {f['part']}" for f in self.files]
        total = sum(f["bytes"] for f in self.files)
        lines.append(f"{len(self.files)} files, {total:,d} B in {self.out_dir} ({self.seconds:.1f} s; "
                     f"{self.jobs_run} jobs run, {self.jobs_reused} reused from the cache)")
        if self.kept:
            lines.append(f"{len(self.kept)} other files of the earlier export of this design "
                         "kept as they were (listed in the manifest)")
        return lines


def run_jobs(run: Run, jobs: Sequence[Job], store: Store, session: SessionWorker | None = None,
             planner: Callable[[Run], Sequence[Job]] | None = None) -> tuple[list[dict], int]:
    """Fetch every job from ``store`` or run it; (records in job order, jobs run).

    Jobs run in order, each after the jobs it reads (``after``); the solids
    they need are built first, once each. Jobs marked ``worker`` go to the
    run's second process (:mod:`tactcad.export.worker`): ``session``'s when
    given with the ``planner`` that made ``jobs`` (``planner(run)``, sent to
    it), else one forked for this run when one can be. When every job left here
    waits for the forked worker's files, this process takes back the last job
    handed to it that it has not begun and no job left to it reads
    (:func:`_taken_back`), so both cores work until the end (``tactcad watch``'s
    worker keeps its jobs: it keeps the solids it was handed). The ``prepare`` of this
    process's jobs (the review page's facts, kernel-free) runs in a process forked before
    this one imports the kernel (:class:`tactcad.export.worker.Preparing`), so it fills
    the second core during that import, when the store has a folder to carry the results
    back in (:func:`tactcad.export.worker.prepared_there`); such a job waits for it before
    it runs.

    Each job run is kept in ``store`` as soon as it finishes (its entry written
    in one step, :meth:`~tactcad.store.Store.keep`; the worker keeps its own jobs
    likewise), so a run stopped or killed part-way leaves its finished jobs to the
    next run; the export folder itself is still replaced only by a whole run
    (:func:`_write_locked`).
    """
    done: dict[str, list[dict]] = {}
    todo = []
    for job in jobs:
        got = store.fetch(job.key, run.staging)
        if got is None:
            todo.append(job)
        else:
            done[job.name] = got
    if not todo:
        return [r for job in jobs for r in done[job.name]], 0
    worker = None
    unclaimed: list[Callable[[], None]] = []  # ends what was started ahead and never taken
    # name -> the run of that job's prepare in a process of its own (a fork only)
    preparing: dict[str, Preparing] = {}
    by_name = {job.name: job for job in todo}
    futures = {}
    started = {}

    def finished(name: str, records: list[dict], keep: bool = True) -> None:
        """``name`` is done: its records noted and, if ``keep``, its files kept in the store."""
        done[name] = records
        if keep:
            store.keep(by_name[name].key, run.staging, records)

    def collect_reads(job: Job) -> None:
        """Collect the worker's jobs whose files ``job`` reads."""
        for name in job.after:
            if name in futures and name not in done:
                collect(name)

    def collect(name: str) -> None:
        """The records of a job handed to the worker, once the jobs it reads
        are collected; run here if the worker died before finishing it."""
        collect_reads(by_name[name])
        try:
            records = futures[name].result()
            run.worker_made.append(name)
        except BrokenProcessPool:
            run.log(f"  the worker process ended early; {name} runs in this process")
            remove_partial_files(run.staging)  # what the worker was writing when it died
            records = by_name[name].make(run)
        finished(name, records)

    try:  # from the first process started: a stop at any point ends each one started
        if session is not None and planner is not None:
            handed = worker_jobs(todo, done)
            if handed:
                worker = session.begin(run, planner)
        else:
            handed = worker_jobs(todo, done) if can_fork() else []
            # work that reads no file (the review page's facts), done in a process forked
            # before this one imports the kernel, where the store carries it back
            if can_fork() and prepared_there(run):
                preparing = _prepared_apart(run, [job for job in todo
                                                  if job.prepare is not None and not job.worker])
            if can_fork():  # another program's start-up while this process imports the kernel
                for job in todo:
                    if job.start is not None and job.ahead is not None:
                        unclaimed.append(job.ahead())
            if len(handed) > 1:
                try:
                    worker = Worker(run, handed, kernel=any(job.needs for job in todo))
                except OSError:  # no process to be had (memory, process limit): all of it here
                    pass
        if worker is None:
            handed = []
        # each of the worker's jobs is handed over as soon as its own solids are built, so
        # the worker draws while this process builds the rest (each part still built once)
        for job in handed:
            futures[job.name] = worker.submit(job, {s.name: run.parts.solid(s) for s in job.needs})
        for spec in {s.name: s for job in todo for s in job.needs}.values():
            run.parts.solid(spec)
        for job in todo:
            if job.start is not None:
                started[job.name] = job.start(run)
        here = [job for job in todo if job.start is None and job.name not in futures]
        prepared: set[str] = set(preparing)  # prepared apart: not here again
        # a worker kept across runs (tactcad watch) keeps the solids it was handed: its jobs
        # stay its own; a worker forked for this run may hand back what it has not begun
        take_back = ((lambda: _taken_back(handed, futures, done)) if isinstance(worker, Worker)
                     else None)
        while here:
            job = _next_here(here, futures, done, run, prepared, take_back)
            here.remove(job)
            collect_reads(job)
            _wait_prepared(preparing.pop(job.name, None))
            finished(job.name, job.make(run))
        for name in futures:
            if name not in done:
                collect(name)
        for name, pending in started.items():
            # a handle whose program failed but left the run whole (FreeCAD: ``keep``
            # False) keeps no store entry, so the next run starts that program again
            finished(name, pending.result(), getattr(pending, "keep", True))
            if getattr(pending, "not_written", None):  # the manifest says what is missing
                run.not_written.append(pending.not_written)
        if worker is not None:
            worker.close()
    finally:
        if worker is not None and len(done) < len(jobs):  # an error or an interrupt
            worker.kill()
        for pending in {id(p): p for p in preparing.values()}.values():
            pending.kill()  # ended already, unless the run failed or stopped first
        for end in unclaimed:
            end()
        for pending in started.values():
            pending.cancel()
    return [r for job in jobs for r in done[job.name]], len(todo)


def _prepared_apart(run: Run, prepares: Sequence[Job]) -> dict:
    """Fork a process for ``prepares``' ``prepare`` (:class:`~tactcad.export.worker.Preparing`),
    before this process imports the kernel: {job name: that process}; empty when there is
    none to prepare or no process to be had (each job then prepares for itself).

    Args:
        run: the export run (its store has a folder).
        prepares: jobs of this process with a ``prepare``.

    Returns:
        {job name: the :class:`~tactcad.export.worker.Preparing` process}.
    """
    if not prepares:
        return {}
    try:
        apart = Preparing(run, prepares)
    except OSError:  # no process to be had: each job prepares for itself
        return {}
    return {job.name: apart for job in prepares}


def _wait_prepared(pending) -> None:
    """Wait for a job's ``prepare`` run in a process of its own (None: none was), so the
    job reads what it kept in the store; if it failed there, or that process died, the job
    works that out itself as it would have (the failure is the job's to say, not the
    process's).

    Args:
        pending: the :class:`~tactcad.export.worker.Preparing` process of the job's
            ``prepare``, or None.
    """
    if pending is None:
        return
    try:
        pending.result()
    except Exception:  # the process failed or died: made again here
        pass


def _waits(job: Job, futures: dict, done: dict) -> bool:
    """True if ``job`` reads a file the worker has not finished yet."""
    return any(name in futures and name not in done and not futures[name].done()
               for name in job.after)


def _next_here(here: list[Job], futures: dict, done: dict, run: Run, prepared: set[str],
               take_back: Callable[[], Job | None] | None = None) -> Job:
    """The next job for this process: the first that waits for no worker file; if every
    one waits, each job's ``prepare`` runs first (once), so the wait is spent on work;
    if every one still waits, a job handed to the worker that it has not begun
    (``take_back``, :func:`_taken_back`), added to ``here``, so both processes work."""
    ready = next((job for job in here if not _waits(job, futures, done)), None)
    if ready is not None:
        return ready
    for job in here:
        if job.prepare is not None and job.name not in prepared:
            prepared.add(job.name)
            job.prepare(run)
    ready = next((job for job in here if not _waits(job, futures, done)), None)
    if ready is not None:
        return ready
    taken = take_back() if take_back is not None else None
    if taken is not None:
        here.append(taken)
        return taken
    return here[0]


def _taken_back(handed: Sequence[Job], futures: dict, done: dict) -> Job | None:
    """The last job handed to the worker that it has not begun, reads no file the worker
    has still to make and is read by no other job the worker has yet to make, taken back
    from it (its hand-over cancelled, removed from ``futures``) for this process to make
    while it would otherwise wait; None when there is none.

    Args:
        handed: the jobs handed to the worker, in the order it makes them.
        futures: the worker's pending results by job name (the taken job's is removed).
        done: the records of the jobs finished so far, by job name.

    Returns:
        The job taken back, or None.
    """
    pending = [job for job in handed if job.name in futures and job.name not in done]
    for job in reversed(pending):
        read_later = any(job.name in other.after for other in pending if other is not job)
        if not read_later and not _waits(job, futures, done) and futures[job.name].cancel():
            del futures[job.name]
            return job
    return None


def check_out_dir(out_dir: str | Path) -> Path:
    """The export folder, resolved, once it is shown safe to replace.

    Raises:
        DesignError: the output rule (:func:`tactcad.atomic.refuse_output_path`): a system
            folder, a missing one that would be made in one, or an existing folder that is
            not writable.
        ExportPathError: a system folder, the home folder or the working folder
            (or one above it), a file, a mount point, a non-empty folder that is not a
            tactcad export (no ``manifest.json``): an export replaces its
            folder as a whole, keeping only files it did not write; or a folder that cannot
            be made (a file on its way, a folder that takes no new one:
            :func:`tactcad.atomic.unmakeable_folder`), or an export whose files this user
            cannot remove (another user's: :func:`tactcad.atomic.unremovable_tree`), which
            would otherwise stay hidden beside the new one.
    """
    out = Path(os.path.abspath(os.path.expanduser(str(out_dir))))
    real = out.resolve()
    refuse_system_folder("--out", out_dir, real)  # the rule of every command's --out
    # an export replaces its folder as a whole: no top folder users write below either
    protected = {Path(d) for d in SYSTEM_DIRS} | {Path.home().resolve()}
    if real in protected or real in Path.cwd().resolve().parents or real == Path.cwd().resolve():
        raise ExportPathError(f"--out {out_dir}: refused, a system, home or working folder "
                              "(an export replaces its folder as a whole); name a folder of its own, "
                              "e.g. --out exports")
    if real.exists() and not real.is_dir():
        raise ExportPathError(f"--out {out_dir}: {real} is a file, not a folder")
    if real.is_dir() and os.path.ismount(real):
        raise ExportPathError(f"--out {out_dir}: {real} is a mount point, which an export cannot "
                              "replace as a whole (it swaps its folder in one rename); name a "
                              f"folder inside it, e.g. --out {Path(str(out_dir)) / 'exports'}")
    if real.is_dir() and any(real.iterdir()) and not (real / MANIFEST).is_file():
        raise ExportPathError(f"--out {out_dir}: {real} holds files but no {MANIFEST}, so it is no "
                              "tactcad export folder; name an empty or new folder")
    # the export is staged beside the folder and renamed into place: checked before any work,
    # so a folder that cannot be made is said in words and nothing is half written
    reason = unmakeable_folder(real)
    if reason is not None and real.is_dir():  # it is there: the folder beside it is not
        raise ExportPathError(f"--out {out_dir}: {real} exists, but the new export is built "
                              f"beside it and swapped in, and {reason}")
    if reason is not None:
        raise ExportPathError(f"--out {out_dir}: the folder cannot be made ({reason})")
    # the rule of every output (its default too): no folder made in a system folder, an
    # existing folder that is not writable said so
    refuse_output_path("--out", out_dir, "a folder")
    # the old export is removed once the new one takes its place: one that cannot be
    # removed would stay hidden beside it, so it is refused before any work
    stuck = unremovable_tree(real) if real.is_dir() else None
    if stuck is not None:
        raise ExportPathError(f"--out {out_dir}: the export there cannot be replaced, its "
                              f"files cannot be removed by this user ({stuck}); run as a user "
                              "who may remove them, or name another folder")
    return real


def _inside(folder: Path, rel: str) -> Path:
    """``folder / rel``, proven to stay inside ``folder`` (no absolute path,
    no ``..`` out of it, no link leading out).

    Raises:
        ExportPathError: the path would leave the folder.
    """
    path = (folder / rel).resolve()
    if Path(rel).is_absolute() or not path.is_relative_to(folder.resolve()):
        raise ExportPathError(f"output path {rel!r} would leave the export folder {folder}")
    return path


def _write_set(out_dir: Path, jobs_of: Callable[[Run], list[Job]], project: Project, log: Log,
               store: Store, with_manifest: bool, parts=None,
               dxf_version: str | None = None, partial: dict | None = None,
               session: SessionWorker | None = None) -> ExportResult:
    """Build the files of ``jobs_of`` in a staging folder beside ``out_dir``,
    then put that folder in the place of ``out_dir`` in one step
    (:func:`tactcad.atomic.publish_dir`). A full export keeps, of the old
    folder, only the files no tactcad export wrote (and no check results of another
    design: :func:`tactcad.export.export_owner.stale_check_results`); a partial one
    (``partial``: ``--only``/``--part``) keeps the other files of an earlier export of the
    same design too, listing them in its manifest, and refuses a folder holding another
    design's (:func:`tactcad.export.export_owner.kept_by_partial_export`); the scenes alone
    (``with_manifest`` False) keep every old file they do not rewrite.

    Raises:
        DesignError: a partial export into a folder holding an export of another design
            whose files it would leave beside its own.
        ExportPathError: ``out_dir`` refused (:func:`check_out_dir`).
    """
    t0 = time.perf_counter()
    out = check_out_dir(out_dir)
    with writing_lock(out, "--out"):  # a second run at once would remove this one's staging
        return _write_locked(out, Path(out_dir), t0, jobs_of, project, log, store,
                             with_manifest, parts, dxf_version, partial, session)


def _write_locked(out: Path, out_dir: Path, t0: float, jobs_of: Callable[[Run], list[Job]],
                  project: Project, log: Log, store: Store, with_manifest: bool, parts,
                  dxf_version: str | None, partial: dict | None,
                  session: SessionWorker | None) -> ExportResult:
    """:func:`_write_set`'s work, once ``out`` is checked and its lock held."""
    refuse_another_designs_export(out, default_product_name(), project.plan.name)
    stuck = [p for old in leftover_staging(out) for p in remove_tree(old)]  # an earlier run's
    warn_left_behind(stuck)
    staging = staging_dir(out)
    published = False
    try:
        run = Run(project, staging, log, store, dxf_version)
        if parts is not None:
            run.parts = parts  # share the caller's solids (e.g. with the checks)
        jobs = jobs_of(run)
        if with_manifest and partial is not None:
            # the same design's earlier files in place first: a job reading them (the BOM
            # naming the files the folder holds) finds them, and is keyed by them
            carried = carried_before_jobs(out, staging, project.plan.design_hash)
            jobs = with_kept_files(jobs, carried)
        records, ran = run_jobs(run, jobs, store, session, jobs_of)
        for r in records:
            _inside(staging, r["path"])
        files = [{**r, "bytes": (staging / r["path"]).stat().st_size} for r in records]
        earlier = EarlierExport()
        if with_manifest and partial is not None and out.is_dir():
            # a partial export refreshes its kinds; the same design's other files stay
            earlier = kept_by_partial_export(out, project.plan.name, project.plan.design_hash,
                                             [r["path"] for r in records])
            kept_paths = {f["path"] for f in earlier.kept}
            carry_over(out, staging, lambda rel: rel in kept_paths)
            warn_changed_by_hand(out, earlier.changed)
        if with_manifest:
            full = jobs if jobs_of is all_jobs else None  # a full export's jobs: not planned twice
            man = with_inputs(manifest(project.plan, staging, records), export_inputs(run, full))
            man["files"] = in_earlier_order(man["files"], earlier)
            if partial is not None:  # a selection of the jobs (export --only/--part)
                man["partial"] = partial_with_kept(partial, earlier)
            left_out = not_written_now(run.not_written, earlier,
                                       {f["path"] for f in man["files"]})
            if left_out:  # files a failed program left out (FreeCAD's review files)
                man["not_written"] = left_out
            man_bytes = (json.dumps(man, indent=2, sort_keys=False) + "\n").encode()
            write_bytes_atomic(staging / MANIFEST, man_bytes)
            written = {r["path"] for r in records}
            files = [f for f in man["files"] if f["path"] in written] + [
                {"path": MANIFEST, "bytes": len(man_bytes), "part": "-"}]
        if out.is_dir():
            # the earlier export's files changed by hand are the lab's now: never removed
            ours = written_by_tactcad(out) - set(earlier.changed) if with_manifest else set()
            # check results of another design belong to the export they checked, not this one
            stale = stale_check_results(out, project.plan.design_hash) if with_manifest else set()
            carry_over(out, staging, lambda rel: rel not in ours and rel not in stale)
        os.chmod(staging, 0o755)  # mkdtemp makes it private; an export folder is for sharing
        publish_dir(staging, out)
        published = True  # staging now holds the old export, which publish_dir removed
    except OSError as exc:  # name the file in the export folder, not in the staging one
        raise in_target(exc, staging, out) from exc
    except (TactcadError, KeyboardInterrupt):
        raise
    except Exception as exc:  # a writer failing without an OSError: a full disk is said as such
        full = disk_full_error(staging)
        if full is None:
            raise
        raise in_target(full, staging, out) from exc
    finally:
        if not published and staging.exists():
            warn_left_behind(remove_tree(staging))
    builds = run.parts.builds if "parts" in vars(run) else 0  # no solid asked: kernel never loaded
    return ExportResult(Path(out_dir), files, time.perf_counter() - t0, ran, len(jobs) - ran,
                        builds, run.distinct_parts, len(run.worker_made),
                        [f["path"] for f in earlier.kept])


def carried_before_jobs(out: Path, staging: Path, design_sha256: str) -> tuple[dict, ...]:
    """Copy into ``staging`` the files of the earlier export in ``out`` of the same design,
    unchanged since it wrote them, before a partial export's jobs run: those jobs write
    their own files over them, the others are the files the published folder keeps. Copied,
    not linked: a writer that writes its file in place (the store's copy of a job it kept,
    a PDF library, a registered kind's own writer) would otherwise write through the link
    into the earlier export, which must stay whole until the new one is published.

    Args:
        out: the export folder (``out`` missing or empty: nothing carried).
        staging: the run's staging folder.
        design_sha256: the exported design's sha256.

    Returns:
        The earlier manifest's records of the files carried
        (:func:`tactcad.export.export_owner.files_of_same_design`).
    """
    if not out.is_dir():
        return ()
    found = files_of_same_design(out, design_sha256)
    paths = {f["path"] for f in found}
    carry_over(out, staging, lambda rel: rel in paths, copy=True)
    return found


def with_inputs(man: dict, inputs: dict) -> dict:
    """The manifest with ``inputs`` (:func:`tactcad.export.jobs.export_inputs`) right after
    its ``design``: what the export was made from, which a check compares with the project's
    files now (:func:`tactcad.export.reuse.export_state`)."""
    out: dict = {}
    for key, value in man.items():
        out[key] = value
        if key == "design":
            out["inputs"] = inputs
    return out


def in_earlier_order(files: list[dict], earlier: EarlierExport) -> list[dict]:
    """The manifest's records of the files written now and of those kept of the earlier
    export, in the earlier manifest's order (a file it did not list after them, in job order)."""
    place = {path: k for k, path in enumerate(earlier.order)}
    records = list(files) + list(earlier.kept)
    return sorted(records, key=lambda f: place.get(f["path"], len(place)))


def not_written_now(now: Sequence[dict], earlier: EarlierExport,
                    listed: set[str]) -> list[dict]:
    """The manifest's ``not_written``: the records of files a failed program left out in
    this run, and the earlier export's records (a partial export keeps them as it keeps
    the earlier files) of a kind this run did not ask for again; each naming only the
    files still absent (the manifest does not list them), none left when all are there.

    Args:
        now: this run's records (:func:`tactcad.export.freecad_review.not_written_record`).
        earlier: the earlier export a partial export keeps (empty for a full export).
        listed: the paths the new manifest lists (written now or kept of the earlier).

    Returns:
        The records, each with its absent files; an empty list when none is absent.
    """
    asked = {r.get("what") for r in now}
    carried = [r for r in earlier.not_written if r.get("what") not in asked]
    out = []
    for record in list(now) + carried:
        absent = [p for p in record.get("files", []) if p not in listed]
        if absent:
            out.append({**record, "files": absent})
    return out


def partial_with_kept(partial: dict, earlier: EarlierExport) -> dict:
    """The manifest's ``partial`` record: what was written now (the selection and its
    jobs) and, when files of the earlier export of the same design were kept, their paths."""
    if not earlier.kept:
        return partial
    return {**partial, "kept": [f["path"] for f in earlier.kept],
            "note": "a partial export: the jobs listed here wrote their files now; the files "
                    "under kept are the earlier export's of the same design (sha256 checked)"}


def warn_changed_by_hand(out: Path, changed: Sequence[str]) -> None:
    """One warning naming the earlier export's files changed by hand since, which a partial
    export keeps as they are but no longer lists in the manifest; nothing when none."""
    if changed:
        import warnings

        from tactcad.errors import HandEditedWarning

        shown = ", ".join(changed[:5]) + (f" and {len(changed) - 5} more" if len(changed) > 5
                                          else "")
        warnings.warn(f"{len(changed)} file(s) of the export in {out} changed by hand since it "
                      f"was written, kept as they are but no longer listed in its manifest: "
                      f"{shown}; `tactcad export` without --only/--part writes them again",
                      HandEditedWarning, stacklevel=2)


def export_scenes(project: Project, out_dir: str | Path, names: Sequence[str], log: Log = print,
                  store: Store | None = None, parts=None) -> ExportResult:
    """Write only the named scenes (``scenes/<name>.step`` and ``.glb``); the
    manifest is left as it is.

    Raises:
        SceneError: an unknown scene name (nothing is written); the message lists the scenes.
    """
    for n in names:
        get_scene_spec(project, n)  # unknown names fail before anything is written
    return _write_set(Path(out_dir), lambda run: scene_jobs(run, names), project, log,
                      store or Store(None), with_manifest=False, parts=parts)


def export(project: Project, out_dir: str | Path, log: Log = print,
           store: Store | None = None, parts=None, dxf_version: str | None = None,
           select: Callable[[list[Job]], list[Job]] | None = None,
           partial: dict | None = None, session: SessionWorker | None = None,
           kinds: Sequence[str] = ()) -> ExportResult:
    """Write all exports of ``project`` into ``out_dir`` (see module doc).

    Args:
        project: the validated :class:`~tactcad.design.project.Project`; no
            design, rigs or scenes file is read again.
        store: finished jobs to reuse (``Store(None)`` or ``None``: build everything).
        parts: a :class:`~tactcad.solids.cache.PartCache` of ``project.plan`` to share
            (default: the run makes its own, only if a job needs a solid).
        dxf_version: ``R2010`` (default) or ``R12`` for the shop DXF files.
        select: the jobs to run out of every job of the run (default: all),
            e.g. :func:`tactcad.export.selection.select_jobs`.
        partial: when ``select`` drops jobs, what was asked for; kept in the
            manifest as ``"partial"``.
        session: a worker kept across runs (``tactcad watch``,
            :class:`~tactcad.export.worker.SessionWorker`) for the drawings;
            default: one forked for this run when it can be.
        kinds: kinds outside a full export whose jobs are planned too
            (``--only`` may name one; ``select`` then picks the jobs).

    Raises:
        OSError: the files cannot be written; ``out_dir`` is left as it was.
    """
    # a full export plans with the module function itself, which a kept worker can be sent
    jobs_of = all_jobs if select is None and not kinds else (
        lambda run: (select or list)(all_jobs(run, kinds)))
    return _write_set(Path(out_dir), jobs_of, project, log, store or Store(None),
                      with_manifest=True, parts=parts, dxf_version=dxf_version, partial=partial,
                      session=session)
