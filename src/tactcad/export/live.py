"""The review loop: a process that stays up, re-exports on every save and
serves the review page with live reload (``tactcad watch``).

Each change is handled in two steps so the 3D view comes first:

1. the design's files are validated once into a project; a refusal is shown
   (terminal and page) and the last good export stays;
2. the scenes' GLB files alone are made (every part the edit did not touch
   comes from this process's solids, every finished job from the store) and
   served with the last export's drawings and the new design's facts;
3. the full export follows (drawings, PDF, BOM, FreeCAD files, the page),
   published atomically as ``tactcad export`` does.

The page is served on 127.0.0.1 and, where the machine has IPv6, on [::1]
at the same port, by a process of its own (:mod:`tactcad.export.live_server`).
``GET /`` is the exported page as it is.
Served, the page polls ``/state`` and, when its sequence number moves, reads
its data (``/data``), the scenes (``/scene/<sha256>``) and sheets
(``/sheet/<sha256>``) whose bytes changed, not the page, keeping the camera,
the scene, the hidden parts and the sheets' zoom (``review_page.js``;
:mod:`tactcad.export.live_page`).
"""

from __future__ import annotations

import os
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable

from tactcad.design.project import Project
from tactcad.errors import TactcadError
from tactcad.export.job import Run, solid_key
from tactcad.export.review_page import (CHECKS_SCRIPT, REVIEW_PAGE, ReviewContents,
                                        unmet_requirements)
from tactcad.export.live_parts import LiveParts, keep_only
# the server's names, for the callers that know them from here
from tactcad.export.live_server import (CLIENT_TIMEOUT_S, LISTEN_BACKLOG, LiveState,  # noqa: F401
                                        ServerProcess, Servers, host_allowed, make_server, serve,
                                        serve_apart, waiting_page)
from tactcad.export.worker import SessionWorker
from tactcad.store import Store

Log = Callable[[str], None]


@dataclass
class Loop:
    """One design under watch: validate, preview the scenes, export in full."""

    load: Callable[[], Project]  # reads and validates the design files (raises DesignError)
    out: Path
    store: Store
    state: LiveState
    log: Log = print
    solids: dict = field(default_factory=dict)
    meshes: dict = field(default_factory=dict)
    project: Project | None = None  # the last good one
    #: the drawing worker kept for the session (None: every run makes its drawings itself)
    worker: SessionWorker | None = None

    def update(self) -> bool:
        """Handle one change; False when the edit was refused (the last export stays)."""
        t0 = time.perf_counter()
        try:
            project = self.load()
        except TactcadError as exc:
            text = str(exc)
            self.log(f"refused (the last good export stays):\n{text}")
            self.state.refuse(text)
            return False
        try:
            result, (unmet, total) = self._export(project, t0)
        except (TactcadError, OSError) as exc:  # the folder, the disk, a part: the session stays
            text = f"the export failed: {exc}"
            self.log(f"refused (the last good export stays):\n{text}")
            self.state.refuse(text, back_to_current=True)
            return False
        self.log(f"export current in {time.perf_counter() - t0:.2f} s ({result.jobs_run} jobs "
                 f"run, {result.jobs_reused} reused; {self._made_by(result.worker_jobs)})"
                 + (f"; {unmet_words(unmet, total)}" if unmet else ""))
        return True

    def _export(self, project: Project, t0: float):
        """The 3D preview (when there is a page to show it in), then the full export,
        each published; the export's result and its requirements not met
        (:func:`requirements_not_met`).

        Raises:
            TactcadError: the export was refused (its folder, a part).
            OSError: a file could not be written or read.
        """
        from tactcad.export.jobs import review_contents_of
        from tactcad.export.run import export

        if not self.state.seq:  # nothing shown yet: the page and /data say what is going on
            self.state.announce("first export under way")
        plan = project.plan
        parts = LiveParts(plan, self.solids, self.meshes)
        if (self.out / REVIEW_PAGE).is_file():
            self.state.publish(plan.design_hash, "3D updated; drawings follow",
                               self.preview(project, parts), checks_js=self._checks_js())
            self.log(f"3D view updated in {time.perf_counter() - t0:.2f} s")
        result = export(project, self.out, log=lambda s: None, store=self.store, parts=parts,
                        session=self.worker)
        self.project = project
        run = Run(project, self.out)
        not_met = requirements_not_met(self.out)
        self.state.publish(plan.design_hash, "current", review_contents_of(run, self.out),
                           (self.out / REVIEW_PAGE).read_bytes(), self._checks_js(),
                           unmet=tuple(not_met[0]))
        self._keep_parts_of(run)
        return result, not_met

    def _keep_parts_of(self, run: Run) -> None:
        """Keep the solids and meshes of ``run``'s parts only (every part of the
        design and its scenes), here and in the worker, so memory does not grow
        with each edit of a long session."""
        keys = {solid_key(s) for s in run.inventory[0].values()}
        keep_only(keys, self.solids, self.meshes)
        if self.worker is not None:
            self.worker.keep_only(keys)

    def _checks_js(self) -> str | None:
        """``review/checks.js`` of the export, when ``tactcad check`` wrote one."""
        try:
            return (self.out / CHECKS_SCRIPT).read_text(encoding="utf-8")
        except (OSError, UnicodeError):
            return None

    def _made_by(self, worker_jobs: int) -> str:
        if self.worker is None:
            return "drawings made here: no worker process"
        return f"{worker_jobs} made by the worker process, pid {self.worker.pid}"

    def close(self) -> None:
        """End the session's worker process."""
        if self.worker is not None:
            self.worker.close()

    def preview(self, project: Project, parts: LiveParts) -> ReviewContents:
        """What the page shows with the new scenes and the last export's drawings and BOM."""
        from tactcad.export.jobs import review_contents_of, scene_jobs
        from tactcad.export.run import run_jobs

        with tempfile.TemporaryDirectory(prefix="tactcad-watch-") as tmp:
            staging = Path(tmp)
            run = Run(project, staging, lambda s: None, self.store)
            run.parts = parts
            jobs = [j for j in scene_jobs(run) if j.name.startswith("scene:")]
            run_jobs(run, jobs, self.store)
            return review_contents_of(run, staging, self.out)


def changes(files: Iterable[Path], poll: bool, stop: threading.Event | None = None):
    """Yield once as soon as ``files`` are watched, then once per burst of
    saves to them (watchfiles: native events, or polling with ``poll``, for
    network drives; 150 ms debounce), so a save made while the caller handles
    the first yield (the first export) is seen too. Their folders are
    watched, as editors save by writing a new file and renaming it."""
    import watchfiles

    targets = {str(f) for f in files}
    folders = sorted({str(Path(f).parent) for f in files})
    first = True
    for found in watchfiles.watch(*folders,
                                  watch_filter=lambda _c, p: os.path.realpath(p) in targets,
                                  debounce=150, step=50, force_polling=poll, poll_delay_ms=200,
                                  stop_event=stop, rust_timeout=100, yield_on_timeout=True):
        if found or first:  # an empty set: nothing changed within rust_timeout
            first = False
            yield


def requirements_record(out: Path) -> dict:
    """The requirements record of the export in ``out`` (its manifest's closed-form
    verification, as ``tactcad verify`` reads it); ``{}`` without a readable manifest.

    Args:
        out: the export's folder.

    Returns:
        The manifest's ``requirements`` table.
    """
    import json

    try:
        doc = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    record = doc.get("requirements") if isinstance(doc, dict) else None
    return record if isinstance(record, dict) else {}


def requirements_not_met(out: Path) -> tuple[list[str], int]:
    """The requirements the export's design fails (verdict ``fail`` at the closed
    form, :func:`tactcad.export.review_page.unmet_requirements`) and how many its
    manifest verifies; ``([], 0)`` without a readable manifest."""
    record = requirements_record(out)
    return unmet_requirements(record), len(record.get("closed_form_matrix") or [])


def unmet_words(unmet: list[str], total: int) -> str:
    """``3 of 7 requirements not met: a, b, c``."""
    return f"{len(unmet)} of {total} requirements not met: {', '.join(unmet)}"


def unmet_line(out: Path) -> str:
    """The line ``tactcad export`` ends with when the export's design fails requirements
    (read from its manifest, as watch's :func:`requirements_not_met`): ``2 of 8
    requirements not met: kobj_resolution_rel (margin -55.9 %), ...; `tactcad verify` for
    the table``; empty when every one is met (watch says nothing then either).

    Args:
        out: the export's folder.

    Returns:
        The line, or "".
    """
    from tactcad.studies.verification import margin_text

    record = requirements_record(out)
    unmet, total = requirements_not_met(out)
    if not unmet:
        return ""
    rows = {r.get("requirement"): r for r in record.get("closed_form_matrix") or []}
    named = [f"{name} (margin {margin_text(rows[name])})"
             for name in unmet]
    return unmet_words(named, total) + "; `tactcad verify` for the table"
