"""The watch's server as a server: only its own host, a lab-sized backlog,
idle clients dropped, a page that says why before the first export; and the
signals that end any run like Ctrl-C."""

from __future__ import annotations

import http.client
import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from contextlib import contextmanager
from pathlib import Path

import pytest

from tactcad.export.live import (CLIENT_TIMEOUT_S, LISTEN_BACKLOG, LiveState, host_allowed,
                                 make_server, serve)


@contextmanager
def serving(state: LiveState):
    server = make_server(state, 0)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        yield server, server.server_address[1]
    finally:
        server.shutdown()
        server.server_close()


def _get(port: int, path: str, host: str | None, address: str = "127.0.0.1") -> tuple[int, bytes]:
    conn = http.client.HTTPConnection(address, port, timeout=5)
    conn.putrequest("GET", path, skip_host=True)
    if host is not None:
        conn.putheader("Host", host)
    conn.endheaders()
    reply = conn.getresponse()
    return reply.status, reply.read()


@pytest.mark.parametrize("path", ["/", "/data", "/state", "/scene/" + "ab" * 32])
def test_only_the_loopback_names_at_its_own_port_are_answered(path):
    state = LiveState()
    state.publish("ab" * 32, "current", None, b"<html>design</html>")
    with serving(state) as (_, port):
        for host in (f"127.0.0.1:{port}", f"localhost:{port}", f"LOCALHOST:{port}"):
            assert _get(port, path, host)[0] in (200, 404)
        for host in ("evil.example", f"evil.example:{port}", "127.0.0.1", f"127.0.0.1:{port + 1}",
                     None, ""):
            code, body = _get(port, path, host)
            assert code == 421 and b"design" not in body


def _has_ipv6_loopback() -> bool:
    try:
        with socket.socket(socket.AF_INET6) as s:
            s.bind(("::1", 0))
        return True
    except OSError:
        return False


@pytest.mark.skipif(not _has_ipv6_loopback(), reason="this machine has no IPv6 loopback")
def test_the_ipv6_loopback_is_served_at_the_same_port_with_the_same_rule():
    state = LiveState()
    state.publish("ab" * 32, "current", None, b"<html>design</html>")
    servers = serve(state, 0)
    servers.start()
    try:
        port = servers.port
        assert [s.server_address[1] for s in servers.servers] == [port, port]
        assert servers.urls() == [f"http://127.0.0.1:{port}/", f"http://[::1]:{port}/"]
        code, body = _get(port, "/state", f"[::1]:{port}", "::1")
        assert code == 200 and json.loads(body)["seq"] == 1
        assert _get(port, "/", f"localhost:{port}", "::1") == (200, b"<html>design</html>")
        for host in ("evil.example", f"[::1]:{port + 1}", "[::1]"):
            code, body = _get(port, "/", host, "::1")
            assert code == 421 and b"design" not in body
        assert _get(port, "/state", f"127.0.0.1:{port}")[0] == 200  # IPv4 as before
    finally:
        servers.stop()
    for address in ("127.0.0.1", "::1"):  # both closed
        with pytest.raises(OSError):
            socket.create_connection((address, port), timeout=2).close()


def test_without_ipv6_the_watch_serves_ipv4_alone(monkeypatch):
    """No IPv6 (or its port taken): [::1] is left out, 127.0.0.1 answers as before."""
    import errno

    import tactcad.export.live as live

    made = live.make_server

    def no_ipv6(state, port, host=live.IPV4_LOOPBACK):
        if ":" in host:
            raise OSError(errno.EAFNOSUPPORT, "Address family not supported by protocol")
        return made(state, port, host)

    monkeypatch.setattr(live, "make_server", no_ipv6)
    servers = serve(LiveState(), 0)
    servers.start()
    try:
        assert len(servers.servers) == 1 and servers.urls() == [f"http://127.0.0.1:{servers.port}/"]
        assert _get(servers.port, "/state", f"127.0.0.1:{servers.port}")[0] == 200
    finally:
        servers.stop()


def test_servers_never_started_stop_at_once():
    serve(LiveState(), 0).stop()  # shutdown() would wait for a serve_forever that never ran


def test_host_rule_names_exactly_the_loopback_and_port():
    assert host_allowed("[::1]:8321", 8321) and host_allowed("localhost:8321 ", 8321)
    assert not host_allowed("localhost.evil.example:8321", 8321)
    assert not host_allowed("127.0.0.1:8321@evil", 8321)


def test_backlog_and_client_timeout_are_set():
    with serving(LiveState()) as (server, _):
        assert server.request_queue_size == LISTEN_BACKLOG >= 128
        assert server.RequestHandlerClass.timeout == CLIENT_TIMEOUT_S


def test_idle_clients_do_not_stop_others(monkeypatch):
    """Connections that send nothing hold a thread each, yet a real request is
    answered at once and the silent ones are dropped after the timeout."""
    import tactcad.export.live as live

    monkeypatch.setattr(live, "CLIENT_TIMEOUT_S", 0.5)
    state = LiveState()
    state.publish("ab" * 32, "current", None, b"<html>page</html>")
    with serving(state) as (_, port):
        idle = [socket.create_connection(("127.0.0.1", port)) for _ in range(40)]
        try:
            start = time.perf_counter()
            assert _get(port, "/", f"127.0.0.1:{port}") == (200, b"<html>page</html>")
            assert time.perf_counter() - start < 5
            idle[0].settimeout(5)
            assert idle[0].recv(1) == b""  # closed by the server
        finally:
            for s in idle:
                s.close()


def test_before_the_first_export_the_page_says_why():
    state = LiveState()
    with serving(state) as (_, port):
        code, body = _get(port, "/", f"127.0.0.1:{port}")
        assert code == 200 and b"No export to show yet" in body and b"starting" in body
        state.refuse("d.toml: element.web_thickness_mm = -1: allowed 0.05 ... 1 <b>")
        code, body = _get(port, "/", f"127.0.0.1:{port}")
        assert b"element.web_thickness_mm = -1" in body and b"&lt;b&gt;" in body


def test_an_export_onto_a_mount_point_is_refused_before_any_work(tmp_path, monkeypatch):
    from tactcad.errors import ExportPathError
    from tactcad.export.run import check_out_dir

    mount = (tmp_path / "usb").resolve()
    mount.mkdir()
    monkeypatch.setattr(os.path, "ismount", lambda p: Path(p) == mount)
    with pytest.raises(ExportPathError, match="mount point.*name a folder inside it, e.g. "
                                              "--out .*usb/exports"):
        check_out_dir(mount)
    assert check_out_dir(mount / "exports") == mount / "exports"


@pytest.mark.slow
@pytest.mark.parametrize("signum, code", [(signal.SIGTERM, 143), (signal.SIGHUP, 129)])
def test_a_terminating_signal_ends_an_export_like_ctrl_c(tmp_path, signum, code):
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "tactcad.cli", "export", "--no-cache",
                             "--out", str(out)], stderr=subprocess.PIPE, text=True,
                            cwd=tmp_path)
    for line in proc.stderr:  # the run is under way: jobs are being made
        if line.startswith("["):
            break
    proc.send_signal(signum)
    err = proc.stderr.read()
    assert proc.wait(timeout=120) == code
    assert f"terminated by {signal.Signals(signum).name}" in err and "Traceback" not in err
    assert "leaked" not in err
    assert not out.exists() and not list(tmp_path.glob(".out.staging-*"))
