"""The review loop: a process that stays up, re-exports on every save and
serves the review page with live reload (``tactcad watch``).

Each change is handled in two steps so the 3D view comes first:

1. the design's files are validated once into a project; a refusal is shown
   (terminal and page) and the last good export stays;
2. the scenes' GLB files alone are made (every part the edit did not touch
   comes from this process's solids, every finished job from the store) and
   the page is served with them, next to the last export's drawings;
3. the full export follows (drawings, PDF, BOM, FreeCAD files, the page),
   published atomically as ``tactcad export`` does.

The page polls ``/state`` and re-reads ``/`` when its sequence number moves,
keeping the camera, the scene and the hidden parts (``review_page.js``).
"""

from __future__ import annotations

import json
import shutil
import tempfile
import threading
import time
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any, Callable, Iterable

from tactcad.catalogue.files import scene_glb_name
from tactcad.design.project import Project
from tactcad.errors import TactcadError
from tactcad.export.job import Run
from tactcad.export.review_page import REVIEW_PAGE
from tactcad.export.live_parts import LiveParts
from tactcad.export.worker import SessionWorker
from tactcad.store import Store

Log = Callable[[str], None]


@dataclass
class LiveState:
    """What the server shows: the page, its sequence number, the last refusal."""

    page: bytes = b""
    seq: int = 0
    sha256: str = ""
    refusal: str | None = None
    status: str = "starting"
    lock: threading.Lock = field(default_factory=threading.Lock)

    def publish(self, page: bytes, sha256: str, status: str) -> None:
        with self.lock:
            self.page, self.sha256, self.status = page, sha256, status
            self.refusal = None
            self.seq += 1

    def refuse(self, text: str) -> None:
        with self.lock:
            self.refusal, self.status = text, "last edit refused"

    def as_json(self) -> bytes:
        with self.lock:
            return json.dumps({"seq": self.seq, "sha256": self.sha256, "refusal": self.refusal,
                               "status": self.status}).encode()


def make_server(state: LiveState, port: int) -> ThreadingHTTPServer:
    """An HTTP server on 127.0.0.1:``port`` (0: any free port): ``GET /`` the
    page, ``GET /state`` its JSON state.

    Raises:
        OSError: the port is taken or not allowed.
    """
    class Handler(BaseHTTPRequestHandler):
        def do_GET(self):  # noqa: N802 (http.server's name)
            path = self.path.split("?")[0]
            if path in ("/", "/index.html"):
                with state.lock:
                    body, kind = state.page, "text/html; charset=utf-8"
            elif path == "/state":
                body, kind = state.as_json(), "application/json"
            else:
                self.send_error(404)
                return
            self.send_response(200)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, *args: Any) -> None:  # quiet: the terminal shows the exports
            pass

    server = ThreadingHTTPServer(("127.0.0.1", port), Handler)
    server.daemon_threads = True
    return server


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
        plan = project.plan
        parts = LiveParts(plan, self.solids, self.meshes)
        if (self.out / REVIEW_PAGE).is_file():
            page = self.preview(project, parts)
            self.state.publish(page, plan.design_hash, "3D updated; drawings follow")
            self.log(f"3D view updated in {time.perf_counter() - t0:.2f} s")
        from tactcad.export.run import export

        result = export(project, self.out, log=lambda s: None, store=self.store, parts=parts,
                        session=self.worker)
        self.project = project
        self.state.publish((self.out / REVIEW_PAGE).read_bytes(), plan.design_hash, "current")
        self.log(f"export current in {time.perf_counter() - t0:.2f} s ({result.jobs_run} jobs "
                 f"run, {result.jobs_reused} reused; {self._made_by(result.worker_jobs)})")
        return True

    def _made_by(self, worker_jobs: int) -> str:
        if self.worker is None:
            return "drawings made here: no worker process"
        return f"{worker_jobs} made by the worker process, pid {self.worker.pid}"

    def close(self) -> None:
        """End the session's worker process."""
        if self.worker is not None:
            self.worker.close()

    def preview(self, project: Project, parts: LiveParts) -> bytes:
        """The page with the new scenes and the last export's drawings and BOM."""
        from tactcad.export.jobs import review_page_job, review_sources, scene_jobs
        from tactcad.export.run import run_jobs

        with tempfile.TemporaryDirectory(prefix="tactcad-watch-") as tmp:
            staging = Path(tmp)
            run = Run(project, staging, lambda s: None, self.store)
            run.parts = parts
            jobs = [j for j in scene_jobs(run) if j.name.startswith("scene:")]
            run_jobs(run, jobs, self.store)
            _, sheets = review_sources(run)
            for rel in [p for p, _ in sheets] + ["bom.csv"]:
                if (self.out / rel).is_file():
                    (staging / rel).parent.mkdir(parents=True, exist_ok=True)
                    shutil.copyfile(self.out / rel, staging / rel)
            review_page_job(run, []).make(run)
            return (staging / REVIEW_PAGE).read_bytes()


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
                                  watch_filter=lambda _c, p: str(Path(p).resolve()) in targets,
                                  debounce=150, step=50, force_polling=poll, poll_delay_ms=200,
                                  stop_event=stop, rust_timeout=100, yield_on_timeout=True):
        if found or first:  # an empty set: nothing changed within rust_timeout
            first = False
            yield
