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
at the same port (:func:`serve`). ``GET /`` is the exported page as it is.
Served, the page polls ``/state`` and, when its sequence number moves, reads
its data (``/data``), the scenes (``/scene/<sha256>``) and sheets
(``/sheet/<sha256>``) whose bytes changed, not the page, keeping the camera,
the scene, the hidden parts and the sheets' zoom (``review_page.js``;
:mod:`tactcad.export.live_page`).
"""

from __future__ import annotations

import json
import socket
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any, Callable, Iterable

from tactcad.design.project import Project
from tactcad.errors import TactcadError
from tactcad.export.job import Run, solid_key
from tactcad.export.review_page import CHECKS_SCRIPT, REVIEW_PAGE, ReviewContents
from tactcad.export.live_page import LiveView, checks_json, live_view
from tactcad.export.live_parts import LiveParts, keep_only
from tactcad.export.worker import SessionWorker
from tactcad.store import Store

Log = Callable[[str], None]


@dataclass
class LiveState:
    """What the server shows: the exported page, the sequence number, the last
    refusal; beside the page, its data, scenes and sheets on their own
    (:mod:`live_page`)."""

    page: bytes = b""  # GET /: the last exported review page, as it is
    seq: int = 0
    sha256: str = ""
    refusal: str | None = None
    status: str = "starting"
    #: this state's data, and the scenes and sheets of this state and the one
    #: before (a page may ask for those it was just told of)
    view: LiveView = field(default_factory=LiveView)
    kept: LiveView = field(default_factory=LiveView)
    checks_js: bytes | None = None
    #: what the last state published as "current" showed (contents, design sha256, the
    #: checks' JSON), shown again when the export after a preview fails
    current: tuple[ReviewContents | None, str, str | None] | None = None
    previewed: bool = False  # the state shown is a preview, not a "current" one
    lock: threading.Lock = field(default_factory=threading.Lock)

    def publish(self, sha256: str, status: str, contents: ReviewContents | None = None,
                page: bytes | None = None, checks_js: str | None = None) -> None:
        """Show ``contents`` of design ``sha256`` (and ``review/checks.js``'s text,
        when the export has one); ``page``: a new exported page for ``GET /``
        (None: the last one stays)."""
        checks = checks_json(checks_js)
        with self.lock:
            seq = self.seq + 1
        view = live_view(contents, seq, sha256, checks)  # outside the lock
        with self.lock:
            self._show(view, sha256, seq)
            if page is not None:
                self.page = page
            self.checks_js = checks_js.encode("utf-8") if checks_js else None
            self.status, self.refusal = status, None
            self.previewed = status != "current"
            if not self.previewed:
                self.current = (contents, sha256, checks)

    def refuse(self, text: str, back_to_current: bool = False) -> None:
        """Show ``text`` as the refusal of the last edit; with ``back_to_current``, the
        last current state again (a preview of the refused edit may have been shown)."""
        with self.lock:
            self.refusal, self.status = text, "last edit refused"
            if back_to_current and self.previewed and self.current is not None:
                contents, sha256, checks = self.current
                self._show(live_view(contents, self.seq + 1, sha256, checks), sha256, self.seq + 1)
                self.previewed = False

    def _show(self, view: LiveView, sha256: str, seq: int) -> None:
        """Serve ``view`` as state ``seq`` of design ``sha256`` (the lock held); the
        scenes and sheets of the state before stay fetchable for one more state."""
        self.kept = LiveView(view.data, {**self.view.glbs, **view.glbs},
                             {**self.view.sheets, **view.sheets})
        self.view, self.sha256, self.seq = view, sha256, seq

    def as_json(self) -> bytes:
        with self.lock:
            return self._state_json()

    def _state_json(self) -> bytes:
        return json.dumps({"seq": self.seq, "sha256": self.sha256, "refusal": self.refusal,
                           "status": self.status}).encode()

    def response(self, path: str) -> tuple[bytes, str] | None:
        """The body and content type of ``GET path``; None: not found."""
        folder, _, digest = path.rpartition("/")
        with self.lock:
            if path in ("/", "/index.html"):
                return self.page or waiting_page(self.status, self.refusal), \
                    "text/html; charset=utf-8"
            if path == "/state":
                return self._state_json(), "application/json"
            if path == "/data":
                return self.view.data, "application/json"
            if path == "/checks.js" and self.checks_js is not None:
                return self.checks_js, "text/javascript; charset=utf-8"
            if folder == "/scene" and digest in self.kept.glbs:
                return self.kept.glbs[digest], "model/gltf-binary"
            if folder == "/sheet" and digest in self.kept.sheets:
                return self.kept.sheets[digest], "image/svg+xml"
        return None


def waiting_page(status: str, refusal: str | None) -> bytes:
    """``GET /`` before the first good export: what the watch is doing, and why
    there is nothing to show when the design or its export was refused; the
    page reloads itself every 2 s until the review page is there."""
    import html

    why = f"<pre>{html.escape(refusal)}</pre>" if refusal else ""
    return (f'<!doctype html><html><head><meta charset="utf-8">'
            f'<meta http-equiv="refresh" content="2"><title>tactcad watch: {html.escape(status)}'
            f'</title></head><body><h1>tactcad watch: {html.escape(status)}</h1>'
            f"<p>No export to show yet.</p>{why}</body></html>").encode("utf-8")


#: Seconds a connection may stay silent before its thread is given back.
CLIENT_TIMEOUT_S = 15.0
#: Connections the kernel queues while every thread is busy (socketserver's default is 5).
LISTEN_BACKLOG = 128
#: The host names a page on this machine may use for the watch (DNS rebinding guard).
LOOPBACK_HOSTS = ("127.0.0.1", "localhost", "[::1]")


def host_allowed(host: str | None, port: int) -> bool:
    """True when a request's ``Host`` header names this machine's loopback at
    ``port`` (``127.0.0.1:PORT``, ``localhost:PORT``, ``[::1]:PORT``): a web page
    whose name was rebound to 127.0.0.1 sends its own name and is refused."""
    return host is not None and host.strip().lower() in {f"{h}:{port}" for h in LOOPBACK_HOSTS}


#: The loopback addresses the watch listens on: IPv4 always, IPv6 when the machine has it.
IPV4_LOOPBACK = "127.0.0.1"
IPV6_LOOPBACK = "::1"


def make_server(state: LiveState, port: int, host: str = IPV4_LOOPBACK) -> ThreadingHTTPServer:
    """An HTTP server on ``host`` (127.0.0.1, or ::1 for IPv6) at ``port`` (0: any free
    port; ``HEAD`` as ``GET`` without the body): ``GET /`` the
    page, ``GET /state`` its JSON state, ``GET /data`` the page's data,
    ``GET /scene/<sha256>`` a scene's GLB, ``GET /sheet/<sha256>`` a drawing
    sheet's SVG, ``GET /checks.js`` the check results (:meth:`LiveState.response`).

    Raises:
        OSError: the port is taken or not allowed, or the machine has no such address
            (no IPv6).
    """
    class Handler(BaseHTTPRequestHandler):
        timeout = CLIENT_TIMEOUT_S  # an idle or slow client gives its thread back

        def do_GET(self, with_body: bool = True):  # noqa: N802 (http.server's name)
            if not host_allowed(self.headers.get("Host"), self.server.server_address[1]):
                self.send_error(421, "Misdirected Request",
                                "tactcad watch answers requests for 127.0.0.1, localhost or "
                                "[::1] at its own port only")
                return
            found = state.response(self.path.split("?")[0])
            if found is None:
                self.send_error(404)
                return
            body, kind = found
            self.send_response(200)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            if with_body:
                self.wfile.write(body)

        def do_HEAD(self):  # noqa: N802: GET's answer without its body (link checkers, curl -I)
            self.do_GET(with_body=False)

        def log_message(self, *args: Any) -> None:  # quiet: the terminal shows the exports
            pass

    kind = _QuietServer6 if ":" in host else _QuietServer
    server = kind((host, port), Handler)
    server.daemon_threads = True
    return server


class _QuietServer(ThreadingHTTPServer):
    """A browser that reloads or closes the page while it downloads (6 MB) resets the
    connection: that is no error for the terminal; any other is printed as before.
    A client that stays silent past :data:`CLIENT_TIMEOUT_S` is dropped the same way."""

    request_queue_size = LISTEN_BACKLOG

    def handle_error(self, request, client_address) -> None:
        if not isinstance(sys.exc_info()[1], (ConnectionError, TimeoutError)):
            super().handle_error(request, client_address)


class _QuietServer6(_QuietServer):
    """:class:`_QuietServer` on IPv6 (``[::1]``)."""

    address_family = socket.AF_INET6

    def server_bind(self) -> None:
        """Bind to the IPv6 address only (never the IPv4 one as well, whatever
        the system's default)."""
        self.socket.setsockopt(socket.IPPROTO_IPV6, socket.IPV6_V6ONLY, 1)
        super().server_bind()


@dataclass
class Servers:
    """The watch's servers: one on 127.0.0.1 and, when the machine has an IPv6
    loopback, one on [::1] at the same port, sharing one :class:`LiveState`
    (:func:`serve`)."""

    servers: list[ThreadingHTTPServer]
    threads: list[threading.Thread] = field(default_factory=list)

    @property
    def port(self) -> int:
        """The port both listen on."""
        return self.servers[0].server_address[1]

    def urls(self) -> list[str]:
        """The review page's address on each loopback served (``http://127.0.0.1:PORT/``,
        ``http://[::1]:PORT/``)."""
        return [f"http://{loopback_url_host(s.server_address[0])}:{self.port}/"
                for s in self.servers]

    def start(self) -> None:
        """Serve each in a daemon thread of its own."""
        for server in self.servers:
            thread = threading.Thread(target=server.serve_forever, daemon=True,
                                      name=f"watch server {server.server_address[0]}")
            thread.start()
            self.threads.append(thread)

    def stop(self) -> None:
        """Stop every server (those started wait for their loop to end) and close
        its socket; connections being answered end with their daemon threads."""
        # shutdown() waits for serve_forever to see it (up to 0.5 s): all at once
        stoppers = [threading.Thread(target=s.shutdown) for s in self.servers[:len(self.threads)]]
        for stopper in stoppers:
            stopper.start()
        for stopper in stoppers:
            stopper.join()
        for server in self.servers:
            server.server_close()
        self.threads.clear()


def loopback_url_host(address: str) -> str:
    """``address`` as a URL's host: ``127.0.0.1``, ``[::1]``."""
    return f"[{address}]" if ":" in address else address


def serve(state: LiveState, port: int) -> Servers:
    """:func:`make_server` on 127.0.0.1 at ``port`` (0: any free one) and on [::1] at
    the port it got, so ``localhost`` reaches the watch whichever address a browser
    tries first; a machine without IPv6 (or whose [::1] port is taken) is served on
    127.0.0.1 alone. Not started (:meth:`Servers.start`).

    Raises:
        OSError: the port is taken or not allowed on 127.0.0.1.
    """
    first = make_server(state, port)
    try:
        second = make_server(state, first.server_address[1], IPV6_LOOPBACK)
    except OSError:  # no IPv6 (EAFNOSUPPORT, EADDRNOTAVAIL) or the port taken on [::1]
        return Servers([first])
    return Servers([first, second])


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
            result = self._export(project, t0)
        except (TactcadError, OSError) as exc:  # the folder, the disk, a part: the session stays
            text = f"the export failed: {exc}"
            self.log(f"refused (the last good export stays):\n{text}")
            self.state.refuse(text, back_to_current=True)
            return False
        self.log(f"export current in {time.perf_counter() - t0:.2f} s ({result.jobs_run} jobs "
                 f"run, {result.jobs_reused} reused; {self._made_by(result.worker_jobs)})")
        return True

    def _export(self, project: Project, t0: float):
        """The 3D preview (when there is a page to show it in), then the full export,
        each published; the export's result.

        Raises:
            TactcadError: the export was refused (its folder, a part).
            OSError: a file could not be written or read.
        """
        from tactcad.export.jobs import review_contents_of
        from tactcad.export.run import export

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
        self.state.publish(plan.design_hash, "current", review_contents_of(run, self.out),
                           (self.out / REVIEW_PAGE).read_bytes(), self._checks_js())
        self._keep_parts_of(run)
        return result

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
                                  watch_filter=lambda _c, p: str(Path(p).resolve()) in targets,
                                  debounce=150, step=50, force_polling=poll, poll_delay_ms=200,
                                  stop_event=stop, rust_timeout=100, yield_on_timeout=True):
        if found or first:  # an empty set: nothing changed within rust_timeout
            first = False
            yield
