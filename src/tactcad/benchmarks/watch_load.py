"""Loopback load on a ``tactcad watch`` server: reviewers' browsers, simulated.

Each simulated reviewer does what the review page does in a browser
(``review_page.js``): it opens the page (``GET /``), then asks ``/state``
200 ms after each answer; when the state's sequence number moves it reads
``/data`` and then the shown (first) scene and the sheets whose sha256 it has
not seen (``/scene/<sha256>``, ``/sheet/<sha256>``). The page it opened
carries the scenes and sheets of its time, so the first ``/data`` fetches none.

Every request is timed from the connection to the last byte of the answer;
an answer other than 2xx, a connection error or a timeout is an error. Only
127.0.0.1 is asked; each reviewer stops by itself at the deadline or after
:data:`MAX_REQUESTS_PER_CLIENT` requests, whichever comes first.

Threads and :mod:`http.client` (standard library); the figures are pure
functions of the requests recorded (:func:`load_summary`).
"""

from __future__ import annotations

import http.client
import json
import math
import threading
import time
from dataclasses import dataclass, field
from typing import Callable

#: Seconds between a ``/state`` answer and the next ask, as the page polls.
POLL_INTERVAL_S = 0.2
#: Seconds a request may take before it counts as a timeout error.
REQUEST_TIMEOUT_S = 10.0
#: A reviewer's requests at most (a bound beside the deadline: 5 polls a second for 10 min).
MAX_REQUESTS_PER_CLIENT = 3000
#: Seconds the load waits past its deadline for a reviewer's last request.
JOIN_GRACE_S = REQUEST_TIMEOUT_S + 5.0
#: The goal on two cores: no error, 99 % of the requests answered within 250 ms.
P99_GOAL_MS = 250.0
#: The percentiles reported (per cent).
PERCENTILES = (50, 95, 99)


@dataclass(frozen=True)
class Request:
    """One timed request: its route (``/state``, ``/scene``...), the seconds from
    the load's start at which it began, its latency (s) and its error (None: 2xx)."""

    route: str
    start_s: float
    latency_s: float
    error: str | None = None


def route_of(path: str) -> str:
    """The route a path belongs to: ``/scene/<sha256>`` -> ``/scene``, ``/state`` -> ``/state``."""
    head = path.split("?", 1)[0]
    return head if head.count("/") < 2 else head.rsplit("/", 1)[0]


def percentile(ordered: list[float], q: float) -> float:
    """The ``q``-th percentile (0 < q <= 100) of ascending ``ordered`` by the
    nearest-rank rule (a value that occurred); NaN when there is none.

    Raises:
        ValueError: ``q`` outside 0 < q <= 100.
    """
    if not 0 < q <= 100:
        raise ValueError(f"percentile {q!r}: allowed 0 < q <= 100")
    if not ordered:
        return math.nan
    return ordered[max(1, math.ceil(q / 100 * len(ordered))) - 1]


def latency_figures(latencies_s: list[float]) -> dict:
    """``p50_ms``, ``p95_ms``, ``p99_ms`` and ``max_ms`` of latencies in seconds,
    rounded to 0.1 ms (NaN when there is none)."""
    ordered = sorted(latencies_s)
    figures = {f"p{q}_ms": round(percentile(ordered, q) * 1000, 1) if ordered else math.nan
               for q in PERCENTILES}
    figures["max_ms"] = round(ordered[-1] * 1000, 1) if ordered else math.nan
    return figures


def load_summary(requests: list[Request], clients: int, seconds: float, edits: int) -> dict:
    """The figures of a load run: ``clients``, ``seconds``, ``edits`` (saved during
    the run), ``requests``, ``errors`` (with ``error_kinds``: count per kind), the
    latency percentiles of every request (errors included: a timeout is a slow
    answer) and per route, and the goal (:data:`P99_GOAL_MS`, no error)."""
    errors: dict[str, int] = {}
    for r in requests:
        if r.error is not None:
            errors[r.error] = errors.get(r.error, 0) + 1
    routes = sorted({r.route for r in requests})
    per_route = {route: {"requests": sum(r.route == route for r in requests),
                         **latency_figures([r.latency_s for r in requests if r.route == route])}
                 for route in routes}
    figures = {"clients": clients, "seconds": seconds, "edits": edits,
               "requests": len(requests), "errors": sum(errors.values()),
               "error_kinds": errors, **latency_figures([r.latency_s for r in requests]),
               "routes": per_route, "p99_goal_ms": P99_GOAL_MS}
    figures["met"] = figures["errors"] == 0 and figures["p99_ms"] <= P99_GOAL_MS
    return figures


def get(port: int, path: str, timeout_s: float = REQUEST_TIMEOUT_S) -> tuple[bytes | None, str | None]:
    """``GET http://127.0.0.1:port/path``: (body, None) for a 2xx answer, else
    (None, the error's kind: ``HTTP 421``, ``timeout``, ``ConnectionResetError``...)."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout_s)
    try:
        conn.request("GET", path)
        reply = conn.getresponse()
        body = reply.read()
        if not 200 <= reply.status < 300:
            return None, f"HTTP {reply.status}"
        return body, None
    except TimeoutError:
        return None, "timeout"
    except (OSError, http.client.HTTPException) as exc:
        return None, type(exc).__name__
    finally:
        conn.close()


@dataclass
class Reviewer:
    """One simulated browser with the page open (see the module doc)."""

    port: int
    t0: float  # time.perf_counter() of the load's start
    deadline: float  # time.perf_counter() at which it stops
    record: Callable[[Request], None]
    seq: int | None = None  # the state its page shows (None: the page as opened)
    scene: str | None = None  # the sha256 of the scene it shows
    sheets: set[str] | None = None  # the sha256 of the sheets it has (None: those of the page)
    asked: int = 0
    stop: threading.Event = field(default_factory=threading.Event)

    def ask(self, path: str) -> bytes | None:
        """One timed request, recorded; its body (None: an error)."""
        start = time.perf_counter()
        body, error = get(self.port, path)
        self.asked += 1
        self.record(Request(route_of(path), start - self.t0, time.perf_counter() - start, error))
        return body

    def running(self) -> bool:
        return (not self.stop.is_set() and time.perf_counter() < self.deadline
                and self.asked < MAX_REQUESTS_PER_CLIENT)

    def run(self) -> None:
        """Open the page, then poll until the deadline (bounded in requests too)."""
        self.ask("/")
        while self.running():
            state = _json(self.ask("/state"))
            if state and state.get("seq") != self.seq and state.get("sha256") and self.running():
                self.follow(_json(self.ask("/data")))
            self.stop.wait(POLL_INTERVAL_S)

    def follow(self, live: dict | None) -> None:
        """Read what a new state changed: the shown scene and the new sheets."""
        if not live or not live.get("data"):
            return
        data = live["data"]
        scene = (data.get("scene_sha256") or {}).get((data.get("scenes") or [None])[0])
        sheets = {s["sha256"] for s in data.get("sheets", [])}
        if self.seq is not None:  # the page as opened carries its scenes and sheets
            if scene and scene != self.scene:
                self.ask(f"/scene/{scene}")
            for digest in sorted(sheets - (self.sheets or set())):
                if not self.running():
                    break
                self.ask(f"/sheet/{digest}")
        self.seq, self.scene, self.sheets = live.get("seq"), scene, sheets


def _json(body: bytes | None) -> dict | None:
    try:
        return json.loads(body) if body else None
    except ValueError:
        return None


def run_load(port: int, clients: int, seconds: float,
             during: Callable[[float], int] = lambda deadline: 0) -> dict:
    """``clients`` reviewers (threads) on ``http://127.0.0.1:port`` for ``seconds``,
    while ``during(deadline)`` runs in this thread (the edits: it returns how
    many it saved, and must return by the deadline, ``time.perf_counter()``);
    the figures (:func:`load_summary`).

    Raises:
        ValueError: ``clients`` < 1 or ``seconds`` <= 0.
    """
    if clients < 1 or not seconds > 0:
        raise ValueError(f"clients {clients!r}, seconds {seconds!r}: allowed >= 1 and > 0")
    requests: list[Request] = []
    lock = threading.Lock()

    def record(r: Request) -> None:
        with lock:
            requests.append(r)

    t0 = time.perf_counter()
    deadline = t0 + seconds
    reviewers = [Reviewer(port, t0, deadline, record) for _ in range(clients)]
    threads = [threading.Thread(target=r.run, daemon=True, name=f"reviewer {k}")
               for k, r in enumerate(reviewers)]
    for t in threads:
        t.start()
    try:
        edits = during(deadline)
    finally:
        for t in threads:
            t.join(timeout=max(0.0, deadline - time.perf_counter()) + JOIN_GRACE_S)
        for r in reviewers:  # a reviewer still waiting on its last answer stops after it
            r.stop.set()
    with lock:
        done = list(requests)
    return load_summary(done, clients, seconds, edits)
