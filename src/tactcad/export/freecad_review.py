"""FreeCAD review files: ``review/<assembly>.FCStd``, one per scene (the
array scene included), written by ``freecadcmd`` (Debian ``freecad-python3``).

What a reviewer finds on File > Open: a root ``App::Part`` named after the
scene, turned Z up (:mod:`tactcad.assembly.z_up`); under it one ``App::Part``
per group of the scene (``array``, ``cart``, ``xy_stage``, ...) holding one
``App::Link`` per instance, labelled with the instance name (``element_1``,
``clamp_plate_front``, ``bolt_1``); each distinct part is stored once, as a
hidden ``Part::Feature`` in the ``parts`` folder, with its colour (every
element variant its own). Geometry goes to FreeCAD as BREP of the same
solids the STEP file holds.

FreeCAD runs its own Python, so the document is built by
``freecad_review_script.py`` (which imports nothing from tactcad) in a
``freecadcmd`` subprocess; its main window is opened off screen
(``QT_QPA_PLATFORM=offscreen``) because colours live in the view providers,
which exist only with a GUI. Without ``freecadcmd`` the files are skipped
with a logged note, so an export works without FreeCAD; a ``freecadcmd`` that
ends without its result costs the export these files only (one warning names its
exit and the file keeping its output, :func:`skipped_review_files`).

Reproducibility: FreeCAD stamps each save with creation and modification
dates and a random document UUID; :func:`normalise_fcstd` replaces them with
fixed values (UUID derived from the assembly name), numbers the object ids
(one counter per FreeCAD process) from 1, sorts the view providers (written in memory
order) by name and rewrites the zip archive with fixed member times, so the
same design writes the same bytes with the same FreeCAD. What stays outside
tactcad's hands: the file carries FreeCAD's version (``ProgramVersion``) and
FreeCAD's own BREP and XML writers, so another FreeCAD release (or its
OpenCascade) may write other bytes for the same model.
"""

from __future__ import annotations

import html
import io
import json
import math
import os
import re
import shutil
import subprocess
import queue
import tempfile
import threading
import time
import uuid
import zipfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Sequence

from tactcad.atomic import write_bytes_atomic
from tactcad.stopping import popen_held
from tactcad.assembly.z_up import Z_UP_MATRIX

SCRIPT = Path(__file__).with_name("freecad_review_script.py")
FIXED_DATE = "2000-01-01T00:00:00Z"
ZIP_TIME = (1980, 1, 1, 0, 0, 0)
Matrix = tuple[tuple[float, ...], ...]  # row-major 4 x 4, mm


@dataclass(frozen=True)
class ReviewPart:
    """A distinct part: name, solid (build123d shape, part frame, mm) and RGB colour in 0 ... 1."""

    name: str
    shape: Any
    color: tuple[float, float, float]


@dataclass(frozen=True)
class ReviewInstance:
    """A placed part: instance name, part name, group and placement (scene frame)."""

    name: str
    part: str
    group: str
    matrix: Matrix


@dataclass(frozen=True)
class ReviewAssembly:
    """One review file: ``review/<name>.FCStd`` for the STEP file ``step``."""

    name: str
    step: str
    parts: tuple[ReviewPart, ...]
    instances: tuple[ReviewInstance, ...]

    def groups(self) -> dict[str, list[str]]:
        """Group -> instance names, groups in order of first use."""
        out: dict[str, list[str]] = {}
        for i in self.instances:
            out.setdefault(i.group, []).append(i.name)
        return out


def review_fcstd_name(name: str) -> str:
    return f"review/{name}.FCStd"


def location_matrix(location) -> Matrix:
    """Row-major 4 x 4 matrix of a build123d ``Location`` (mm), rounded to 1e-12 mm."""
    from tactcad.kernel.locations import matrix  # the kernel, only when a file is written

    m = matrix(location)
    rows = [tuple(round(float(m[i][j]), 12) + 0.0 for j in range(4)) for i in range(3)]
    return tuple(rows) + ((0.0, 0.0, 0.0, 1.0),)


def scene_review_assembly(scene, solids: dict, step: str) -> ReviewAssembly:
    """The review assembly of a built scene (:mod:`tactcad.assembly.scene_solver`): its
    shown parts with their solids and colours, its instances by group."""
    parts = tuple(ReviewPart(n, solids[n], tuple(spec.color)) for n, spec in scene.parts().items())
    inst = tuple(ReviewInstance(i.name, i.part, i.group, location_matrix(i.location))
                 for i in scene.instances)
    return ReviewAssembly(scene.name, step, parts, inst)


def freecadcmd() -> str | None:
    """Path of ``freecadcmd``, or ``None``."""
    return shutil.which("freecadcmd") or shutil.which("FreeCADCmd")


def freecad_identity() -> str | None:
    """What identifies the installed FreeCAD for the export store (its
    ``freecadcmd``'s resolved path, size and time), or ``None``: cheap, no
    FreeCAD process started."""
    exe = freecadcmd()
    if exe is None:
        return None
    real = Path(exe).resolve()
    st = real.stat()
    return f"{real}:{st.st_size}:{int(st.st_mtime)}"


def _job(a: ReviewAssembly, staging: Path, folder: Path) -> dict:
    from tactcad.kernel.brep import write_brep  # the kernel, only when a file is written

    folder.mkdir()
    parts = []
    for k, p in enumerate(a.parts):
        brep = folder / f"p{k}.brep"
        write_brep(p.shape, brep)
        parts.append({"name": p.name, "brep": str(brep), "color": list(p.color)})
    groups = [{"name": g, "instances": [{"name": i.name, "part": i.part, "matrix": i.matrix}
                                        for i in a.instances if i.group == g]}
              for g in a.groups()]
    return {"name": a.name, "out": str((staging / review_fcstd_name(a.name)).resolve()),
            "root_matrix": Z_UP_MATRIX, "parts": parts, "groups": groups}


class FreecadFailed(RuntimeError):
    """``freecadcmd`` ended without writing its result.

    Attributes:
        returncode: its exit status (negative: ended by that signal).
        output: what it wrote on stdout and stderr.
    """

    def __init__(self, returncode: int, output: str):
        super().__init__(f"freecadcmd exited {returncode} without a result:\n{output[-4000:]}")
        self.returncode, self.output = returncode, output


class FreecadRun:
    """``script`` running under ``freecadcmd`` with ``payload`` (JSON) in
    ``$TACTCAD_FC_IN``; :meth:`result` waits for the JSON the script writes
    to ``$TACTCAD_FC_OUT``. FreeCAD is its own process, so the caller can go
    on with other work meanwhile.

    Raises:
        RuntimeError: no ``freecadcmd``.
    """

    def __init__(self, script: Path, payload: Any, timeout_s: float = 900.0):
        exe = freecadcmd()
        if exe is None:
            raise RuntimeError("freecadcmd not found (Debian package freecad-python3)")
        self._tmp = tempfile.TemporaryDirectory(prefix="tactcad-fc-")
        tmp = self._tmp.name
        self._out = Path(tmp) / "result.json"
        self._timeout = timeout_s
        env = dict(os.environ, TACTCAD_FC_IN=json.dumps(payload), TACTCAD_FC_OUT=str(self._out),
                   HOME=tmp, QT_QPA_PLATFORM="offscreen")  # FreeCAD's user config goes to HOME
        env.pop("PYTHONPATH", None)
        env.pop("PYTHONHOME", None)
        try:
            self._proc = popen_held([exe, str(script)], env=env, cwd=tmp, text=True,
                                    stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        except BaseException:  # not started, or ended again by a stop that came meanwhile
            self._tmp.cleanup()
            raise

    def result(self) -> dict:
        """The script's JSON result.

        Raises:
            FreecadFailed: FreeCAD wrote no result (its exit status and output with it).
            subprocess.TimeoutExpired: FreeCAD ran longer than the timeout.
        """
        try:
            stdout, stderr = self._proc.communicate(timeout=self._timeout)
            if not self._out.exists():
                raise FreecadFailed(self._proc.returncode, f"{stdout}\n{stderr}")
            return json.loads(self._out.read_text())
        finally:
            self.cancel()

    def cancel(self) -> None:
        """Stop FreeCAD if it still runs and remove its folder."""
        if self._proc.poll() is None:
            self._proc.kill()
            self._proc.communicate()
        self._tmp.cleanup()


class FreecadServer:
    """One ``freecadcmd`` kept running for many review runs (``tactcad
    watch``): :data:`SCRIPT` in its serving mode, one request a line on its
    stdin. Saves FreeCAD's start-up (about 0.8 s) on every run after the
    first; the files are the same bytes as a fresh process writes (object ids
    are numbered again by :func:`normalise_fcstd` either way).

    Raises:
        RuntimeError: no ``freecadcmd``.
    """

    def __init__(self):
        exe = freecadcmd()
        if exe is None:
            raise RuntimeError("freecadcmd not found (Debian package freecad-python3)")
        self._tmp = tempfile.TemporaryDirectory(prefix="tactcad-fc-kept-")
        tmp = self._tmp.name
        self._log = open(Path(tmp) / "stderr.txt", "w+")
        env = dict(os.environ, TACTCAD_FC_SERVE="1", HOME=tmp, QT_QPA_PLATFORM="offscreen")
        env.pop("PYTHONPATH", None)
        env.pop("PYTHONHOME", None)
        try:
            self._proc = popen_held([exe, str(SCRIPT)], env=env, cwd=tmp, text=True,
                                    stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                    stderr=self._log)
        except BaseException:  # not started, or ended again by a stop that came meanwhile
            self._log.close()
            self._tmp.cleanup()
            raise
        self._count = self._done = 0  # requests sent, and answered
        self._lines: queue.Queue = queue.Queue()  # its stdout, read as it comes (never blocks it)
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        for line in self._proc.stdout:
            self._lines.put(line)
        self._lines.put(None)  # FreeCAD has ended

    @property
    def alive(self) -> bool:
        return self._proc.poll() is None

    def submit(self, payload: Any, out: Path) -> int:
        """Send one request (the script writes its result to ``out``); its number. The
        payload goes in a file beside ``out`` and the line names it: a line of a few
        hundred bytes fits the pipe at once, so sending never waits on FreeCAD (a payload
        of a large scene is more than the pipe holds).

        Raises:
            OSError: FreeCAD has ended (a broken pipe), or the payload's file cannot be
                written.
        """
        self._count += 1
        given = out.with_name(f"{out.stem}.request.json")
        given.write_text(json.dumps(payload))
        self._proc.stdin.write(json.dumps({"in_file": str(given), "out": str(out),
                                           "id": self._count}) + "\n")
        self._proc.stdin.flush()
        return self._count

    def wait(self, number: int, timeout_s: float) -> None:
        """Wait for request ``number`` to be done.

        Raises:
            RuntimeError: FreeCAD ended first (its output is in the message).
            subprocess.TimeoutExpired: not done within ``timeout_s``.
        """
        end = time.monotonic() + timeout_s
        done, seen = f"tactcad-fc-done {number}", []
        while True:
            try:
                line = self._lines.get(timeout=max(end - time.monotonic(), 0.0))
            except queue.Empty:
                raise subprocess.TimeoutExpired("freecadcmd", timeout_s) from None
            if line is None:
                self._proc.wait()
                self._log.seek(0)
                raise RuntimeError(f"freecadcmd exited {self._proc.returncode} without a result:\n"
                                   f"{''.join(seen)[-2000:]}\n{self._log.read()[-2000:]}")
            if line.strip() == done:
                self._done = number
                return
            seen.append(line)

    def close(self) -> None:
        """End FreeCAD and remove its folder: killed at once while a request is
        unanswered (a run that was stopped or failed: its file is not wanted),
        else told by its stdin closed (killed if it lingers)."""
        if self.alive and self._done < self._count:
            self._proc.kill()
            self._proc.wait()
        if self.alive:
            try:
                self._proc.stdin.close()
                self._proc.wait(timeout=5)
            except (OSError, subprocess.TimeoutExpired):
                self._proc.kill()
                self._proc.wait()
        self._log.close()
        self._tmp.cleanup()


    def end(self) -> None:
        """End FreeCAD at once, its requests answered or not (a server of one run, whose
        files are written: nothing is left to wait for), and remove its folder."""
        if self.alive:
            self._proc.kill()
        self._proc.wait()
        try:
            self._proc.stdin.close()
        except OSError:  # a request not sent whole: the pipe is gone with FreeCAD
            pass
        self.close()

    def fds(self) -> list[int]:
        """The file descriptors this process holds on FreeCAD (its stdin and stdout pipes,
        its log), which a process forked from this one must not keep open
        (:func:`forget_ahead_in_child`)."""
        return [f.fileno() for f in (self._proc.stdin, self._proc.stdout, self._log)
                if f is not None and not f.closed]


#: Seconds a FreeCAD started ahead (:func:`start_freecad_ahead`) is given to answer its
#: one request once the run waits for it (about 2 s on a quiet machine, tens of seconds
#: on a loaded one); past that it is ended and a FreeCAD started for the files writes them.
AHEAD_ANSWER_S = 120.0


class ServedRun:
    """A :class:`FreecadRun`'s counterpart on a :class:`FreecadServer`; when
    that FreeCAD ends before answering, the run is made again by a new one.
    ``own``: the server serves this run alone (:func:`start_freecad_ahead`) and is
    ended with it; one that gives no answer within :data:`AHEAD_ANSWER_S` is ended too,
    the run made again by a new FreeCAD and the user told so in one warning
    (:func:`warn_ahead_replaced`)."""

    def __init__(self, server: FreecadServer, payload: Any, timeout_s: float = 900.0,
                 own: bool = False):
        self._server, self._payload, self._timeout = server, payload, timeout_s
        self._own = own
        self._tmp = tempfile.TemporaryDirectory(prefix="tactcad-fc-")
        self._out = Path(self._tmp.name) / "result.json"
        self._number = server.submit(payload, self._out)

    def result(self) -> dict:
        """The script's JSON result (see :meth:`FreecadRun.result`).

        Raises:
            FreecadFailed: the FreeCAD that made the run again wrote no result.
            subprocess.TimeoutExpired: a kept FreeCAD (not ``own``) gave no answer
                within the timeout, or the one that made the run again ran longer.
        """
        try:
            self._server.wait(self._number, AHEAD_ANSWER_S if self._own else self._timeout)
            return json.loads(self._out.read_text())
        except RuntimeError:  # the kept FreeCAD died: this run in a process of its own
            self._server.close()
            return FreecadRun(SCRIPT, self._payload, self._timeout).result()
        except subprocess.TimeoutExpired:
            if not self._own:
                self._server.close()  # busy or broken: the next run starts another
                raise
            self._server.end()
            warn_ahead_replaced(AHEAD_ANSWER_S)
            return FreecadRun(SCRIPT, self._payload, self._timeout).result()
        except BaseException:
            self._server.close()  # busy or broken: the next run starts another
            raise
        finally:
            if self._own:
                self._server.end()
            self._tmp.cleanup()

    def cancel(self) -> None:
        if self._out.parent.exists():  # not waited for: FreeCAD may be writing still
            self._server.close()
            self._tmp.cleanup()


def ahead_replaced_text(waited_s: float) -> str:
    """The warning's words when the FreeCAD started ahead gave no answer in time.

    Args:
        waited_s: the seconds it was given (:data:`AHEAD_ANSWER_S`).

    Returns:
        One line naming the wait, the FreeCAD ended and the one that wrote the files.
    """
    return (f"the FreeCAD started ahead of the export gave no answer in {waited_s:g} s: it "
            "was ended, and the review files were written by a FreeCAD started for them")


def warn_ahead_replaced(waited_s: float) -> None:
    """One :class:`~tactcad.errors.FreecadAheadWarning` (``tactcad: warning: ...`` on the
    command's stderr, :mod:`tactcad.commands.notices`) saying so (:func:`ahead_replaced_text`).

    Args:
        waited_s: the seconds the FreeCAD started ahead was given.
    """
    import warnings

    from tactcad.errors import FreecadAheadWarning

    warnings.warn(ahead_replaced_text(waited_s), FreecadAheadWarning, stacklevel=2)


class _Kept:
    """The FreeCAD process kept by :func:`keep_freecad`."""

    wanted = False
    server: FreecadServer | None = None


def keep_freecad(on: bool) -> None:
    """Keep one FreeCAD process for the review runs from now on (``on``), or
    end the kept one and go back to one process per run."""
    if _Kept.server is not None and not on:
        _Kept.server.close()
        _Kept.server = None
    _Kept.wanted = on


class _Ahead:
    """The FreeCAD process started ahead of one run's review files (:func:`start_freecad_ahead`)."""

    server: FreecadServer | None = None


def start_freecad_ahead() -> Callable[[], None]:
    """Start ``freecadcmd`` in its serving mode now, for the review files of the run about
    to begin (:func:`_start_freecad` hands it their one request), so FreeCAD's start-up
    (about 0.8 CPU s) runs while this process imports the CAD kernel, with the second
    core otherwise idle; the files are the same bytes a FreeCAD started for them writes.
    Nothing is started when FreeCAD is not installed, one is kept already
    (:func:`keep_freecad`) or one was started ahead and not yet taken.

    The FreeCAD is given :data:`AHEAD_ANSWER_S` to answer once the run waits for it, and
    is then ended and replaced by a FreeCAD started for the files (:class:`ServedRun`).

    Returns:
        A function ending that FreeCAD if no run took it (called when the run ends).
    """
    if _Kept.wanted or _Ahead.server is not None or freecadcmd() is None:
        return lambda: None
    try:
        server = FreecadServer()
    except (OSError, RuntimeError):  # no process to be had: the run starts its own
        return lambda: None
    _Ahead.server = server

    def unclaimed() -> None:
        if _Ahead.server is server:
            _Ahead.server = None
            server.end()
    return unclaimed


def forget_ahead_in_child() -> None:
    """In a process forked from the run's (its drawing worker), let go of the FreeCAD
    started ahead: its pipes and log are pointed at ``/dev/null`` (the numbers stay taken,
    so nothing of this process writes to them or closes another file by them), so FreeCAD
    sees its stdin end when the run's process closes it, whatever this one does."""
    server = _Ahead.server
    if server is None:
        return
    null = os.open(os.devnull, os.O_RDWR)
    try:
        for fd in server.fds():
            os.dup2(null, fd)
    finally:
        os.close(null)


def _start_freecad(payload: Any):
    """The review script on the FreeCAD started ahead for this run
    (:func:`start_freecad_ahead`; a warning says so if it gives no answer), else on the kept
    one when there is one (started again when it has ended), else in a new one."""
    ahead, _Ahead.server = _Ahead.server, None
    if ahead is not None:
        if ahead.alive:
            try:
                return ServedRun(ahead, payload, own=True)
            except OSError:  # it ended between the check and the request
                pass
        ahead.end()
    if _Kept.wanted and freecadcmd() is not None:
        try:
            if _Kept.server is None or not _Kept.server.alive:
                if _Kept.server is not None:
                    _Kept.server.close()
                _Kept.server = FreecadServer()
            return ServedRun(_Kept.server, payload)
        except OSError:  # it ended between the check and the request: a process for this run
            _Kept.server = None
    return FreecadRun(SCRIPT, payload)


def run_freecad_script(script: Path, payload: Any, timeout_s: float = 900.0) -> dict:
    """:class:`FreecadRun` and wait for its result (see there)."""
    return FreecadRun(script, payload, timeout_s).result()


_DATE_RE = re.compile(rb'(<Property name="(?:CreationDate|LastModifiedDate)" [^>]*>\s*<String value=")[^"]*(")')
_UID_RE = re.compile(rb'(<Property name="Uid" [^>]*>\s*<Uuid value=")[^"]*(")')
_OBJECT_ID_RE = re.compile(rb'(<Object type="[^"]+" name="[^"]+" id=")(\d+)(")')
_VIEW_PROVIDERS_RE = re.compile(rb'(<ViewProviderData Count="\d+">\s*)(.*?)(\s*</ViewProviderData>)', re.S)
_VIEW_PROVIDER_RE = re.compile(rb'<ViewProvider name="([^"]+)".*?</ViewProvider>', re.S)
_FILE_RE = re.compile(rb'file="([A-Za-z]+)(\d*)"')


def _renumber_ids(xml: bytes) -> bytes:
    """Object ids count on across the documents of one FreeCAD process: number them 1, 2, ..."""
    counter = iter(range(1, 1 << 30))
    return _OBJECT_ID_RE.sub(lambda m: m.group(1) + str(next(counter)).encode() + m.group(3), xml)


def _sort_view_providers(xml: bytes) -> tuple[bytes, dict[str, str]]:
    """FreeCAD writes the view providers in memory order: sort them by object
    name and rename their colour-list files (``DiffuseColor``, ``DiffuseColor1``,
    ...) in the new order. Returns the XML and old -> new file names."""
    m = _VIEW_PROVIDERS_RE.search(xml)
    if m is None:
        return xml, {}
    blocks = [b.group(0) for b in _VIEW_PROVIDER_RE.finditer(m.group(2))]
    blocks.sort(key=lambda b: _VIEW_PROVIDER_RE.match(b).group(1))
    sep = b"\n        "
    body = m.group(1) + sep.join(blocks) + m.group(3)
    xml = xml[:m.start()] + body + xml[m.end():]
    renamed: dict[str, str] = {}
    seen: dict[bytes, int] = {}

    def rename(f: re.Match) -> bytes:
        base = f.group(1)
        k = seen.get(base, 0)
        seen[base] = k + 1
        new = base + (str(k).encode() if k else b"")
        renamed[(f.group(1) + f.group(2)).decode()] = new.decode()
        return b'file="' + new + b'"'

    return _FILE_RE.sub(rename, xml), renamed


#: FreeCAD's isometric view: the camera's axis along (1, -1, 1), Z up
#: (rotation axis and angle in radians, as FreeCAD's View > Isometric sets it)
ISOMETRIC_ORIENTATION = (0.742906, 0.307722, 0.594473, 1.217116)
ISOMETRIC_DIRECTION = (0.57735027, -0.57735027, 0.57735027)
_CAMERA_RE = re.compile(rb'<Camera settings="[^"]*"/>')


def _mm(v: float) -> str:
    """A length to 1 µm, without trailing zeros or a negative zero."""
    text = f"{round(v, 3) + 0.0:.3f}".rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def isometric_camera(bbox_mm: Sequence[float]) -> str:
    """An OpenInventor orthographic camera, isometric, fitting the box
    ``(xmin, ymin, zmin, xmax, ymax, zmax)`` (mm) with a 10 % margin: the
    ``settings`` of GuiDocument.xml's ``<Camera/>``, so the file opens with the
    whole scene in view. Numbers to 1 µm, so the same box writes the same text.

    Raises:
        ValueError: a box with a non-finite or inverted extent.
    """
    lo, hi = [float(v) for v in bbox_mm[:3]], [float(v) for v in bbox_mm[3:6]]
    if not all(map(math.isfinite, lo + hi)) or any(a > b for a, b in zip(lo, hi)):
        raise ValueError(f"bounding box {list(bbox_mm)}: not a finite box")
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    size = max(math.dist(lo, hi), 1.0)  # the diagonal: the box fits from any side
    dist = 2 * size
    pos = [c + d * dist for c, d in zip(centre, ISOMETRIC_DIRECTION)]
    return ("#Inventor V2.1 ascii\n\n\nOrthographicCamera {\n  viewportMapping ADJUST_CAMERA\n"
            f"  position {' '.join(_mm(v) for v in pos)}\n"
            f"  orientation {' '.join(f'{v:g}' for v in ISOMETRIC_ORIENTATION)}\n"
            f"  nearDistance {_mm(dist - size)}\n  farDistance {_mm(dist + size)}\n"
            f"  aspectRatio 1\n  focalDistance {_mm(dist)}\n  height {_mm(size * 1.1)}\n\n}}\n")


def _with_camera(gui_xml: bytes, camera: str) -> bytes:
    """GuiDocument.xml with ``camera`` as its saved view (XML-escaped)."""
    value = html.escape(camera, quote=True).replace("\n", "&#10;").encode()
    return _CAMERA_RE.sub(lambda m: b'<Camera settings="' + value + b'"/>', gui_xml, count=1)


def normalise_fcstd(path: Path, name: str, camera: str | None = None) -> None:
    """Make a FreeCAD file reproducible (see module doc): fixed dates and
    document UUID, object ids from 1, view providers in name order, zip
    members with fixed times; with ``camera`` (:func:`isometric_camera`) the
    document opens with that view."""
    uid = str(uuid.uuid5(uuid.NAMESPACE_URL, f"tactcad/review/{name}")).encode()
    with zipfile.ZipFile(path) as zin:
        members = {info.filename: zin.read(info.filename) for info in zin.infolist()}
    doc = members["Document.xml"]
    doc = _DATE_RE.sub(rb"\g<1>" + FIXED_DATE.encode() + rb"\g<2>", doc)
    doc = _UID_RE.sub(rb"\g<1>" + uid + rb"\g<2>", doc)
    members["Document.xml"] = _renumber_ids(doc)
    # FreeCAD reads the members in the order it wrote them: Document.xml, its
    # files, GuiDocument.xml, then the view providers' files in XML order.
    renamed: dict[str, str] = {}
    if "GuiDocument.xml" in members:
        members["GuiDocument.xml"], renamed = _sort_view_providers(members["GuiDocument.xml"])
        if camera is not None:
            members["GuiDocument.xml"] = _with_camera(members["GuiDocument.xml"], camera)
    gui_files = [renamed_name for renamed_name in renamed.values()]  # in XML order
    new_data = {renamed.get(n, n): data for n, data in members.items()}
    order = [n for n in members if n not in renamed]
    if gui_files:
        at = order.index("GuiDocument.xml") + 1
        order[at:at] = gui_files
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zout:
        zout.comment = b"FreeCAD Document"
        for n in order:
            info = zipfile.ZipInfo(n, ZIP_TIME)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            zout.writestr(info, new_data[n], compresslevel=6)

    write_bytes_atomic(path, buf.getvalue())


def start_review_files(staging: Path, assemblies: Sequence[ReviewAssembly],
                       log: Callable[[str], None]) -> "PendingReview":
    """Start writing ``review/<name>.FCStd`` for each assembly into ``staging``
    (one ``freecadcmd`` run for all); :meth:`PendingReview.result` waits for
    it and returns the file records (see :func:`write_review_files`)."""
    return PendingReview(staging, tuple(assemblies), log)


class PendingReview:
    """Review files being written by FreeCAD in its own process. ``keep`` is False once
    FreeCAD failed (:meth:`result`): the run keeps no store entry of its review files, so
    the next one asks FreeCAD again; ``not_written`` is then the manifest's record of the
    files left out (:func:`not_written_record`), None otherwise."""

    def __init__(self, staging: Path, assemblies: tuple[ReviewAssembly, ...],
                 log: Callable[[str], None]):
        self.staging, self.assemblies, self.log = staging, assemblies, log
        # the earlier export's files a partial export put in place first: kept if FreeCAD fails
        self.earlier = [review_fcstd_name(a.name) for a in assemblies
                        if (staging / review_fcstd_name(a.name)).is_file()]
        self.keep = True
        self.not_written: dict | None = None
        self._run = None
        self._breps = None
        if not assemblies:
            return
        if freecadcmd() is None:
            log("  skipped review/*.FCStd: freecadcmd not found (install the Debian package "
                "freecad-python3, e.g. scripts/install-system-deps.sh)")
            return
        (staging / "review").mkdir(parents=True, exist_ok=True)
        self._breps = tempfile.TemporaryDirectory(prefix="tactcad-review-")
        jobs = [_job(a, staging, Path(self._breps.name) / f"a{k}") for k, a in enumerate(assemblies)]
        self._run = _start_freecad(jobs)

    def cancel(self) -> None:
        if self._run is not None:
            self._run.cancel()
        if self._breps is not None:
            self._breps.cleanup()

    def result(self) -> list[dict]:
        if self._run is None:
            return []
        try:
            result = self._run.result()
        except FreecadFailed as exc:  # the other files are good: the export goes on without
            self.keep = False
            self.not_written = not_written_record(self.assemblies, exc)
            skipped_review_files(self.staging, self.assemblies, exc, self.earlier)
            return []
        finally:
            self.cancel()
        records = []
        for a in self.assemblies:
            found = result["files"].get(a.name, {"error": "not written"})
            if "error" in found:
                raise RuntimeError(f"FreeCAD could not write {review_fcstd_name(a.name)}:\n"
                                   f"{found['error']}")
            box = found.get("bbox_mm")
            normalise_fcstd(self.staging / review_fcstd_name(a.name), a.name,
                            isometric_camera(box) if box else None)
            records.append({"path": review_fcstd_name(a.name), "part": a.name,
                            "kind": "freecad-review", "step": a.step,
                            "freecad_version": ".".join(result["freecad_version"]),
                            "groups": a.groups(), "instances": len(a.instances),
                            "colours": {p.name: list(p.color) for p in a.parts}})
        self.log(f"  wrote {len(records)} FreeCAD review files in review/ "
                 f"(FreeCAD {'.'.join(result['freecad_version'])}, colours: {result['gui']})")
        return records


def not_written_record(assemblies: Sequence[ReviewAssembly], exc: FreecadFailed) -> dict:
    """The manifest's record of the review files a failed FreeCAD left out of the export
    (its ``not_written``, read by ``tactcad check``'s export files group).

    Args:
        assemblies: the review files asked for.
        exc: FreeCAD's failure.

    Returns:
        ``{"what": "review/*.FCStd", "files": [path, ...], "reason": words}``.
    """
    return {"what": "review/*.FCStd",
            "files": [review_fcstd_name(a.name) for a in assemblies],
            "reason": f"freecadcmd exited {exc.returncode} without a result"}


def freecad_output_file(exc: FreecadFailed) -> Path:
    """Keep FreeCAD's output of a failed run in a file of its own in the temporary
    folder (``tactcad-freecad-*.log``), where the lab can read it after the run.

    Args:
        exc: the failure, with its exit status and output.

    Returns:
        The file's path.

    Raises:
        OSError: the file cannot be written.
    """
    fd, name = tempfile.mkstemp(prefix="tactcad-freecad-", suffix=".log")
    with os.fdopen(fd, "w") as f:
        f.write(f"freecadcmd ({freecadcmd()}) exited {exc.returncode} without a result; "
                f"its output:\n{exc.output}")
    return Path(name)


def skipped_review_files(staging: Path, assemblies: Sequence[ReviewAssembly],
                         exc: FreecadFailed, earlier: Sequence[str] = ()) -> None:
    """An export without its FreeCAD review files, FreeCAD having failed: any it wrote
    before it failed removed from ``staging`` (a set whole or none; ``review/`` too when
    that leaves it empty; a partial export puts the earlier export's back, which it keeps),
    its output kept (:func:`freecad_output_file`) and one
    :class:`~tactcad.errors.FreecadFailedWarning` naming its exit and that file.

    Args:
        staging: the run's staging folder.
        assemblies: the review files asked for.
        exc: FreeCAD's failure.
        earlier: the earlier export's review files a partial export keeps (in ``staging``
            before FreeCAD ran), which the manifest lists as kept.
    """
    import warnings

    from tactcad.errors import FreecadFailedWarning

    for a in assemblies:
        (staging / review_fcstd_name(a.name)).unlink(missing_ok=True)
    try:
        (staging / "review").rmdir()
    except OSError:  # other review files there (the review page), or none made
        pass
    try:
        seen = f"its output is in {freecad_output_file(exc)}"
    except OSError as err:  # no temporary folder to write to: the output's end, in the line
        seen = f"its output could not be kept ({err.strerror}), it ends: " + " | ".join(
            exc.output.strip().splitlines()[-3:])
    warnings.warn(f"review/*.FCStd not written: freecadcmd exited {exc.returncode} without a "
                  f"result ({seen}); the export's other files are written and "
                  f"{listed_review_words(len(assemblies), len(earlier))}; the next export "
                  "runs FreeCAD again", FreecadFailedWarning, stacklevel=2)


def listed_review_words(asked: int, kept: int) -> str:
    """What the manifest holds of the review files after FreeCAD failed, in words.

    Args:
        asked: the review files asked for.
        kept: those of them the earlier export wrote, which a partial export keeps.

    Returns:
        The words, e.g. ``manifest.json does not list the review files``.
    """
    if not kept:
        return "manifest.json does not list the review files"
    which = "the" if kept == asked else f"{kept} of the {asked}"
    return (f"{which} earlier export's review files are kept as they were, listed in "
            "manifest.json under partial.kept")


def write_review_files(staging: Path, assemblies: Sequence[ReviewAssembly],
                       log: Callable[[str], None]) -> list[dict]:
    """Write ``review/<name>.FCStd`` for each assembly into ``staging`` (one
    ``freecadcmd`` run for all of them); see the module doc.

    Returns:
        File records ``{"path", "part": name, "kind": "freecad-review",
        "step", "freecad_version", "groups": {group: [instance, ...]},
        "instances", "colours": {part: [r, g, b]}}``; an empty list, with a logged note, when FreeCAD is not
        installed.

    Raises:
        RuntimeError: FreeCAD is installed but failed (its output is in the message).
    """
    return start_review_files(staging, assemblies, log).result()
