"""``tactcad watch``: re-export on every save and serve the review page with live reload."""

from __future__ import annotations

import argparse
import json
import os
import sys
import threading
from pathlib import Path
from typing import Callable

from tactcad.commands.options import ascii_integer, output_folder
from tactcad.commands import add_cache_args, add_design_arg, add_output_args, store_from_args

DEFAULT_PORT = 8321


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("watch", help="re-export on save and serve the review page (live reload)",
                       description="Export the design, then stay up: every save of the design, "
                                   "rigs or scenes file re-exports what changed (the 3D view "
                                   "first, then the drawings, the PDF and the rest) and the "
                                   "review page at http://127.0.0.1:PORT/ (and "
                                   "http://[::1]:PORT/ where the machine has IPv6) reloads "
                                   "in place, keeping its camera and hidden parts. A refused "
                                   "edit is shown in the page and here; the last good export "
                                   "stays. Ctrl-C, SIGTERM or SIGHUP stops it (exit 0).")
    add_design_arg(p)
    p.add_argument("--out", metavar="DIR", type=output_folder, default="exports",
                   help="the export folder kept current (default: exports)")
    p.add_argument("--port", metavar="N", type=ascii_integer, default=DEFAULT_PORT,
                   help=f"port of the review page on 127.0.0.1 and [::1], 1024 ... 65535 or 0 "
                        f"for any free one (default: {DEFAULT_PORT})")
    p.add_argument("--poll", action="store_true",
                   help="poll the files instead of waiting for file-system events (network "
                        "drives, some containers)")
    add_cache_args(p)
    add_output_args(p, "print one JSON object per event on stdout (update, refusal, stop) "
                       "instead of progress lines")
    p.set_defaults(func=run)


def note_stop_signals(stop: threading.Event) -> Callable[[], None]:
    """Set ``stop`` on each signal that stops a run (Ctrl-C and
    :data:`tactcad.stopping.ENDING_SIGNALS`), then let the signal's own
    handler raise as before; returns what puts the handlers back. A stop's
    exception can be lost (inside a library call) or change on its way (a
    kernel module interrupted while it loads raises ImportError): the event
    says a stop was asked whatever became of it. Outside the main thread
    nothing is installed (signals are the main thread's)."""
    import signal

    from tactcad.stopping import stop_signal_numbers

    if threading.current_thread() is not threading.main_thread():
        return lambda: None
    previous = {}
    for signum in stop_signal_numbers():
        handler = signal.getsignal(signum)
        if not callable(handler):  # ignored or the default: left as it is
            continue

        def noted(number, frame, handler=handler):
            stop.set()
            handler(number, frame)
        previous[signum] = signal.signal(signum, noted)

    def restore() -> None:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
    return restore


def _design_tables(design: Path) -> dict:
    """The design file's tables, or none when it cannot be read (the loader says why)."""
    import tomllib

    try:
        return tomllib.loads(design.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return {}


def watched_files(design: Path) -> list[Path]:
    """The design file and the rigs and scenes files it names (else
    ``rigs.toml`` and ``scenes.toml`` beside it), as the loader picks them;
    a file that does not exist yet is watched for."""
    from tactcad.design.project import companion_paths

    # realpath, not Path.resolve: Python 3.11's resolve raises on a symbolic link loop
    return [Path(os.path.realpath(p)) for p in
            (design, *companion_paths(design, _design_tables(design)).values())]


def named_files(design: Path) -> list[Path]:
    """The watched files a user is told of: the design file, the companions its ``[files]``
    table names, and the default ones only where they exist (a comb has no ``rigs.toml``).

    Args:
        design: the design file watched.

    Returns:
        The files, as :func:`watched_files` gives them.
    """
    from tactcad.design.project import companion_paths

    tables = _design_tables(design)
    named = tables.get("files") if isinstance(tables.get("files"), dict) else {}
    kinds = list(companion_paths(design, tables))
    first, *companions = watched_files(design)
    return [first, *(f for kind, f in zip(kinds, companions) if named.get(kind) or f.exists())]


def run(args: argparse.Namespace) -> int:
    """Watch until stopped (see the command's help); 0 once stopped, by a stop at any moment.

    Raises:
        DesignError: a bad ``--port``, ``--out`` or ``--design`` (before anything starts).
    """
    import contextlib

    from tactcad.errors import DesignError
    from tactcad.stopping import end_child_processes, exit_at_once_on_stop

    # the option first, before the exporter is loaded: a refusal is quick
    if not (args.port == 0 or 1024 <= args.port <= 65535):
        raise DesignError("--port", args.port, "1024 ... 65535, or 0 for any free port")
    _refuse_a_die_at_once(args)

    stop = threading.Event()
    log = watch_log(args)
    at_once_undone = None
    with contextlib.ExitStack() as started:
        started.callback(note_stop_signals(stop))
        started.callback(end_child_processes)  # what the closes below missed, if anything
        try:
            watch(args, log, stop, started)
        except BaseException:
            if not stop.is_set():  # an error of its own, not a stop's
                raise
            # a stop, whatever its exception became: the clean-up (the callbacks
            # of ``started``) takes no long wait, and a second stop ends it at once
            at_once_undone = exit_at_once_on_stop(0)
            log("stopped")
    if at_once_undone is not None:  # the clean-up is done: this process may go on (in-process runs)
        at_once_undone()
    return 0


def _refuse_a_die_at_once(args: argparse.Namespace) -> None:
    """Another product's design file (a silicon die's) (``--design``, or the working folder's one design file) is
    refused before anything starts: a watch re-exports an array, and no edit turns a die's
    file into one (an unreadable file is the watch's own refusal, which waits for the next
    save).

    Raises:
        DesignError: the design is a die's file.
    """
    from tactcad.commands import design_and_product

    found = design_and_product(args)
    if found is not None and not found[1].is_default:
        raise found[1].refusal("watch", found[0])


def watch_log(args: argparse.Namespace) -> Callable[[str], None]:
    """The watch's log: one JSON event a line on stdout with ``--json``, else
    ``watch: ...`` lines on stderr (only refusals with ``--quiet``)."""
    def log(line: str) -> None:
        if args.json:
            print(json.dumps({"event": line.split(" ", 1)[0], "text": line}), flush=True)
        elif not args.quiet or line.startswith("refused"):
            print(f"watch: {line}", file=sys.stderr, flush=True)
    return log


def watch(args: argparse.Namespace, log: Callable[[str], None], stop: threading.Event,
          started) -> None:
    """Serve, export and re-export until ``stop`` is set (a stop's exception
    ends it sooner); each thing started is closed by ``started`` (a
    :class:`contextlib.ExitStack`) as soon as it exists, so a stop at any
    moment closes what there is.

    Raises:
        DesignError: a bad ``--out``, ``--design`` or a port that is taken.
        KeyboardInterrupt: a stop (``stop`` set).
    """
    from tactcad.commands import load_from_args
    from tactcad.errors import DesignError
    from tactcad.export.freecad_review import keep_freecad
    from tactcad.export.live import LiveState, Loop, changes, serve, serve_apart
    from tactcad.export.run import check_out_dir
    from tactcad.export.worker import session_worker

    check_out_dir(args.out)  # refused before anything starts

    def load():  # the design, rigs and scenes files validated once per change
        return load_from_args(args).validated

    if args.design:
        design = Path(args.design)
    else:
        from tactcad.commands import announced_default_design
        design = announced_default_design()
    if not design.is_file():  # a file that exists but is refused is watched until it is mended
        raise DesignError("--design", str(design), "an existing design file (TOML)")
    state = LiveState()
    try:
        servers = serve(state, args.port)
    except OSError as exc:
        raise DesignError("--port", args.port, f"a free port on 127.0.0.1, or 0 for any "
                          f"({exc.strerror or exc})") from None
    started.callback(servers.stop)
    # the drawings' process, kept for the session: it loads the kernel while the first run plans
    loop = Loop(load, Path(args.out), store_from_args(args), state, log)
    started.callback(loop.close)
    loop.worker = session_worker()
    keep_freecad(True)  # one FreeCAD process for the review files of every run
    started.callback(keep_freecad, False)
    # the page is served by a process of its own, so the exports do not slow its answers
    server = serve_apart(servers, state, log)
    if server is not None:
        started.callback(server.close)
    log(f"review page at {' and '.join(servers.urls())} (Ctrl-C stops)")
    files = watched_files(design)
    log("watching " + ", ".join(str(f) for f in named_files(design)))
    # the first: the files are watched; the watcher also ends once ``stop`` is set
    for k, _ in enumerate(changes(files, args.poll, stop)):
        if k:
            log("change seen")
        loop.update()
        if stop.is_set():  # a stop whose KeyboardInterrupt the update lost
            break
    raise KeyboardInterrupt  # the watcher ended: only ``stop`` ends it
