"""The watch's review page as a server: the state it shows and the HTTP
servers that answer for it, in the watching process or in a process of its own.

The server answers ``GET /`` (the exported page as it is), ``/state``,
``/data``, ``/scene/<sha256>``, ``/sheet/<sha256>`` and ``/checks.js``
(:meth:`LiveState.response`), only for its own loopback host and port
(:func:`host_allowed`), on 127.0.0.1 and, where the machine has IPv6, on
[::1] at the same port (:func:`serve`).

``tactcad watch`` serves from a second process (:class:`ServerProcess`): the
export holds the watching process's interpreter lock for up to a tenth of a
second at a time (the CAD kernel, the scenes' meshes), and each request's
thread, one per connection, waited its turn for it with every other one (40
reviewers during edits: p99 310 ms in this process, 90 ms in its own). The second process is sent each state
as it is published (:func:`state_update`, :meth:`LiveState.apply`); it
answers on the sockets bound here, so a taken port is refused here, and it is
started again, with the state as it is, when it ends.

This module imports neither the CAD kernel nor the design, so the second
process starts in a fraction of a second and holds little more than the bytes
it serves.
"""

from __future__ import annotations

import json
import socket
import sys
import threading
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any, Callable

from tactcad.export.live_page import LiveView, checks_json, live_view
from tactcad.export.review_page import ReviewContents

Log = Callable[[str], None]


#: ``/checks.js`` before ``tactcad check`` has run on the export: the page asks
#: for it on every load, so it is always there (the page reads null as "not run").
NO_CHECKS_JS = b"window.TACTCAD_CHECKS = null;\n"


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
    #: the requirements the shown design does not meet (their verdict is ``fail``)
    unmet: tuple[str, ...] = ()
    #: what the last state published as "current" showed (contents, design sha256, the
    #: checks' JSON), shown again when the export after a preview fails
    current: tuple[ReviewContents | None, str, str | None] | None = None
    previewed: bool = False  # the state shown is a preview, not a "current" one
    lock: threading.Lock = field(default_factory=threading.Lock)
    #: called after each change (publish, refuse), outside the lock: the server
    #: process is sent the new state (:class:`ServerProcess`)
    on_change: Callable[[], None] | None = field(default=None, repr=False, compare=False)

    def publish(self, sha256: str, status: str, contents: ReviewContents | None = None,
                page: bytes | None = None, checks_js: str | None = None,
                unmet: tuple[str, ...] = ()) -> None:
        """Show ``contents`` of design ``sha256`` (and ``review/checks.js``'s text,
        when the export has one); ``page``: a new exported page for ``GET /``
        (None: the last one stays); ``unmet``: the requirements it fails."""
        checks = checks_json(checks_js)
        with self.lock:
            seq = self.seq + 1
        view = live_view(contents, seq, sha256, checks)  # outside the lock
        with self.lock:
            self._show(view, sha256, seq)
            if page is not None:
                self.page = page
            self.checks_js = checks_js.encode("utf-8") if checks_js else None
            self.status, self.refusal, self.unmet = status, None, tuple(unmet)
            self.previewed = status != "current"
            if not self.previewed:
                self.current = (contents, sha256, checks)
        self._changed()

    def refuse(self, text: str, back_to_current: bool = False) -> None:
        """Show ``text`` as the refusal of the last edit; with ``back_to_current``, the
        last current state again (a preview of the refused edit may have been shown)."""
        with self.lock:
            self.refusal, self.status = text, "last edit refused"
            if back_to_current and self.previewed and self.current is not None:
                contents, sha256, checks = self.current
                self._show(live_view(contents, self.seq + 1, sha256, checks), sha256, self.seq + 1)
                self.previewed = False
        self._changed()

    def announce(self, status: str) -> None:
        """Say what the watch is doing (``status``, e.g. the first export under
        way) without a new state to show."""
        with self.lock:
            self.status = status
        self._changed()

    def _changed(self) -> None:
        if self.on_change is not None:
            self.on_change()

    def apply(self, update: dict) -> None:
        """Show what :func:`state_update` made of another process's state: the
        served fields only (a server process's state is never published to).
        Scenes and sheets sent as None are those this state already holds."""
        with self.lock:
            glbs = {d: b if b is not None else self.kept.glbs.get(d)
                    for d, b in update["glbs"].items()}
            sheets = {d: b if b is not None else self.kept.sheets.get(d)
                      for d, b in update["sheets"].items()}
            self.view = LiveView(update["data"])
            self.kept = LiveView(update["data"], {d: b for d, b in glbs.items() if b is not None},
                                 {d: b for d, b in sheets.items() if b is not None})
            self.seq, self.sha256 = update["seq"], update["sha256"]
            self.status, self.refusal = update["status"], update["refusal"]
            self.unmet = tuple(update["unmet"])
            self.checks_js = update["checks_js"]
            if update["page"] is not None:
                self.page = update["page"]

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
                           "status": self.status, "unmet": list(self.unmet)}).encode()

    def _nothing_yet(self) -> bytes:
        """``GET /data`` before the first state is published: the same fields
        with no data (as a refused export's), and what the watch is doing."""
        return json.dumps({"seq": self.seq, "sha256": self.sha256, "checks": None,
                           "data": None, "status": self.status,
                           "refusal": self.refusal}).encode()

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
                return self.view.data if self.seq else self._nothing_yet(), "application/json"
            if path == "/checks.js":  # before any check has run: a script that says so
                return self.checks_js or NO_CHECKS_JS, "text/javascript; charset=utf-8"
            if folder == "/scene" and digest in self.kept.glbs:
                return self.kept.glbs[digest], "model/gltf-binary"
            if folder == "/sheet" and digest in self.kept.sheets:
                return self.kept.sheets[digest], "image/svg+xml"
        return None


@dataclass(frozen=True)
class Held:
    """What a server process holds of the bytes it was sent: the page (the very
    object, None: none yet) and the scenes' and sheets' sha256."""

    page: bytes | None = None
    glbs: frozenset[str] = frozenset()
    sheets: frozenset[str] = frozenset()


def state_update(state: LiveState, held: Held) -> tuple[dict, Held]:
    """The message that brings a server process holding ``held`` to ``state``
    (:meth:`LiveState.apply`), and what it holds then: the state's fields, its
    data, and only the bytes it lacks (the page when it changed, each scene and
    sheet by sha256, None for those it has)."""
    with state.lock:
        page = state.page if state.page is not held.page and state.page else None
        update = {"seq": state.seq, "sha256": state.sha256, "status": state.status,
                  "refusal": state.refusal, "unmet": state.unmet, "data": state.view.data,
                  "checks_js": state.checks_js, "page": page,
                  "glbs": {d: None if d in held.glbs else b for d, b in state.kept.glbs.items()},
                  "sheets": {d: None if d in held.sheets else b
                             for d, b in state.kept.sheets.items()}}
        now = Held(state.page or None, frozenset(state.kept.glbs), frozenset(state.kept.sheets))
    return update, now


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
#: How often a serving loop looks whether it is asked to stop (s): the
#: socketserver default of 0.5 s made every stop of the watch wait that long.
STOP_POLL_S = 0.05
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
    kind = _QuietServer6 if ":" in host else _QuietServer
    server = kind((host, port), _handler(state))
    server.daemon_threads = True
    return server


def adopt(state: LiveState, listening: socket.socket) -> ThreadingHTTPServer:
    """:func:`make_server`'s server on a socket another process bound and set
    listening (:class:`ServerProcess`)."""
    kind = _QuietServer6 if listening.family == socket.AF_INET6 else _QuietServer
    server = kind(listening.getsockname(), _handler(state), bind_and_activate=False)
    server.socket.close()  # the one made for it, never bound
    server.socket = listening
    server.daemon_threads = True
    return server


def _handler(state: LiveState) -> type[BaseHTTPRequestHandler]:
    """The request handler answering from ``state`` (see :func:`make_server`)."""
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

    return Handler


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
            thread = threading.Thread(target=server.serve_forever, args=(STOP_POLL_S,),
                                      daemon=True, name=f"watch server {server.server_address[0]}")
            thread.start()
            self.threads.append(thread)

    def stop(self) -> None:
        """Stop every server (those started wait for their loop to end) and close
        its socket; connections being answered end with their daemon threads."""
        # shutdown() waits for serve_forever to see it (up to STOP_POLL_S): all at once
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


#: Times one session starts its server process again after it ended; after that
#: (or when no process can be started) the watching process serves the page itself.
SERVER_RESTARTS = 5


class ServerProcess:
    """The sockets of ``servers`` answered by a process of its own, sent
    ``state`` at each change (see the module doc); :meth:`close` ends it.

    A process that ends (killed, out of memory) is started again and sent the
    state as it is, at most :data:`SERVER_RESTARTS` times a session; after
    that, or when no process can be started, this process serves the page
    itself (``servers`` started here), as slow under an export as that is.

    Raises:
        OSError: no process can be started (from the constructor; the caller
            serves the page itself).
    """

    def __init__(self, servers: Servers, state: LiveState, log: Log = print):
        self.servers, self.state, self.log = servers, state, log
        self.restarts = 0
        self._lock = threading.RLock()
        self._closing = threading.Event()
        self._process: Any = None
        self._conn: Any = None  # the pipe's sending end; None: not sending (closed, or served here)
        self._held = Held()
        self._start()
        state.on_change = self.send
        self.send()
        threading.Thread(target=self._keep_up, daemon=True, name="watch server keeper").start()

    @property
    def pid(self) -> int:
        """The server process's id (0: the page is served by this process)."""
        return self._process.pid if self._conn is not None else 0

    def _start(self) -> None:
        """Start the server process on the servers' sockets (the lock held or alone),
        with the stop signals held (:func:`tactcad.stopping.stop_signals_held`)."""
        import multiprocessing
        import os

        from tactcad.stopping import spawn_ready, stop_signals_held

        spawn = multiprocessing.get_context("spawn")
        spawn_ready()
        reader, writer = spawn.Pipe(duplex=False)
        process = spawn.Process(target=_serve_apart, daemon=True, name="tactcad watch server",
                                args=(reader, [s.socket for s in self.servers.servers],
                                      os.getpid()))
        try:
            with stop_signals_held():
                process.start()
                self._process, self._conn, self._held = process, writer, Held()
        except BaseException:  # not started, or a stop came meanwhile: none is left running
            writer.close()
            if process.pid is not None:
                process.kill()
                process.join()
            raise
        finally:
            reader.close()

    def send(self) -> None:
        """Send the server process what changed in the state since the last send
        (:func:`state_update`); a process that ended is left to :meth:`_keep_up`."""
        with self._lock:
            if self._conn is None:
                return
            update, held = state_update(self.state, self._held)
            try:
                self._conn.send(update)
            except (OSError, ValueError):  # the process ended: _keep_up starts another
                return
            self._held = held

    def _keep_up(self) -> None:
        """Wait for the server process to end; unless closing, start another and send
        it the state, or serve here (see the class doc)."""
        from multiprocessing.connection import wait

        while True:
            process = self._process
            wait([process.sentinel])
            with self._lock:
                if self._closing.is_set() or self._conn is None:
                    return
                self._conn.close()
                process.join()
                code = process.exitcode
                if self.restarts < SERVER_RESTARTS:
                    self.restarts += 1
                    try:
                        self._start()
                    except OSError:
                        pass
                    else:
                        self.log(f"server process of the review page ended (exit code {code}); "
                                 f"started again, pid {self._process.pid}")
                        self.send()
                        continue
                self._conn = None
                self.state.on_change = None
                self.servers.start()
                self.log(f"server process of the review page ended (exit code {code}); the "
                         f"page is served by the watching process from now on")
                return

    def close(self) -> None:
        """End the server process at once (killed and reaped: it holds nothing
        the watch needs, and a stop must not wait for its interpreter to end);
        the caller then stops ``servers``, which closes the sockets here and
        stops them if they were served here."""
        self._closing.set()
        with self._lock:
            self.state.on_change = None
            conn, self._conn = self._conn, None
            if conn is None:
                return
            self._process.kill()
            self._process.join()
            conn.close()


def serve_apart(servers: Servers, state: LiveState, log: Log = print) -> ServerProcess | None:
    """``servers`` answered by a :class:`ServerProcess` sent ``state``; None when no
    process can be started, and then ``servers`` are started here."""
    try:
        return ServerProcess(servers, state, log)
    except OSError:
        servers.start()
        return None


def _serve_apart(reader: Any, sockets: list[socket.socket], parent: int) -> None:
    """The server process: answer on ``sockets``, from the first message
    ``reader`` gives on, from a state brought up to date by each message
    (:meth:`LiveState.apply`), until the pipe closes. Ctrl-C and a closed
    terminal are the watching process's (``parent``) to handle; the process
    ends with it (Linux)."""
    from tactcad.stopping import stop_signals_unblocked

    stop_signals_unblocked(ignore=("SIGINT", "SIGHUP"))
    _die_with_parent(parent)
    state, servers = LiveState(), None
    while True:
        try:
            update = reader.recv()
        except (EOFError, OSError):  # the watching process closed the pipe or ended
            return
        state.apply(update)
        if servers is None:  # requests wait in the sockets' queue for the state as it is
            servers = Servers([adopt(state, s) for s in sockets])
            servers.start()


def _die_with_parent(parent: int) -> None:
    """Linux: be sent SIGKILL when the parent process (``parent``, its pid) dies
    (``kill -9`` of the watch leaves no server behind); end at once if it already has."""
    import os
    import signal

    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
        if os.getppid() != parent:
            os._exit(1)
    except (OSError, AttributeError):
        pass
