"""Sweeps at scale: design grids, the correction refit and Monte Carlo on Dask.

Every sweep is a list of independent points mapped by one function. The
points run on a Dask cluster: by default a ``distributed.LocalCluster`` of
two worker processes with one thread each (the machine's two cores; BLAS and
OpenMP held to one thread per worker, so two workers do not fight over
cores), or an existing cluster given by its scheduler address
(``tcp://HOST:PORT``), whose workers must import the same tactcad. A point's
result depends on the point only, and results are gathered in point order,
so a sweep gives the same numbers on any cluster. A text progress bar
(``distributed.progress``) goes to stderr on a terminal, plain progress lines
otherwise.

* :func:`design_grid`: K, gauge strain and error estimate at any ladder
  level over web x arm (x notch radius), CSV and a design chart (K against
  arm length for each web, Table 1's measured points on it).
* :func:`correction_refit`: the FEM points of the closed-form correction
  fit (:mod:`tactcad.studies.correction_fit`) and the fit.
* Monte Carlo: :func:`tactcad.studies.tolerance_montecarlo.run_tolerance` with
  :func:`dask_mapper` as its ``mapper``.

Units: mm, N, MPa, N/mm, s.
"""

from __future__ import annotations

import contextlib
import csv
import logging
import math
import re
import shutil
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Callable, Iterable, Iterator, Mapping, Sequence

from tactcad.design.array_plan import ElementGeometry, Material, Plan
from tactcad.errors import DesignError, DesignErrors, TactcadError

#: Local cluster: two worker processes, one thread each.
LOCAL_WORKERS = 2
THREADS_PER_WORKER = 1
#: Environment of every local worker process, set before it starts (BLAS and
#: OpenMP read it once): one thread per worker.
SINGLE_THREAD_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
                     "MKL_NUM_THREADS": "1"}
#: glibc's allocator in a local worker. Dask's default sets MALLOC_TRIM_THRESHOLD_ to 64 kB,
#: which also freezes the threshold above which an array gets its own mapping at 128 kB:
#: every temporary of the contact solve and the closed form was then mapped, page-faulted
#: and unmapped anew (an atlas's die point took 3.4 times as long in a worker as in the
#: main process, most of it in the kernel, and a second worker added nothing). Arrays
#: below 32 MiB come from the heap again, and it keeps up to 256 MiB free.
WORKER_ALLOCATOR_ENV = {"MALLOC_MMAP_THRESHOLD_": str(32 * 2**20),
                        "MALLOC_TRIM_THRESHOLD_": str(256 * 2**20)}
_ADDRESS = re.compile(r"^(tcp|tls|inproc|ucx)://[^\s/]+(:\d+)?$")
#: Longest wait for an existing scheduler's answer, s.
SCHEDULER_TIMEOUT_S = 10.0


class ClusterError(TactcadError):
    """No Dask scheduler answers at the given address."""


def check_scheduler_address(address: str) -> str:
    """``tcp://HOST:PORT`` (or tls://, inproc://) checked for form.

    Raises:
        DesignError: naming ``--scheduler``, the value and the allowed form.
    """
    if not isinstance(address, str) or not _ADDRESS.match(address.strip()):
        raise DesignError("--scheduler", address, "a scheduler address tcp://HOST:PORT")
    return address.strip()


async def _identity(address: str, timeout: float) -> Any:
    """The answer of whatever listens at ``address`` to the scheduler's
    ``identity`` request, sent with distributed's own framing."""
    from distributed.comm import connect

    comm = await connect(address, timeout=timeout)
    try:
        await comm.write({"op": "identity", "reply": True})
        return await comm.read()
    finally:
        comm.abort()


def probe_scheduler(address: str, timeout: float | None = None) -> None:
    """Check that a Dask scheduler answers at ``address`` within ``timeout``.

    ``distributed.Client`` alone waits forever on a service that never replies (an HTTP
    server) and reads a stranger's reply as a frame length of exabytes, so the address is
    asked for the scheduler's identity first, with a hard time limit.

    Args:
        address: a checked scheduler address (:func:`check_scheduler_address`).
        timeout: longest wait, s (``None``: :data:`SCHEDULER_TIMEOUT_S`).

    Raises:
        ClusterError: naming ``--scheduler`` and the address: nothing answers, or what
            answers is not a Dask scheduler.
    """
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    timeout = SCHEDULER_TIMEOUT_S if timeout is None else timeout
    try:
        # in a thread of its own: its own event loop, even where the caller runs one
        with ThreadPoolExecutor(1) as pool:
            reply = pool.submit(asyncio.run, asyncio.wait_for(_identity(address, timeout),
                                                              timeout)).result()
    except (OSError, asyncio.TimeoutError, TimeoutError) as exc:
        detail = f": {exc}" if str(exc) else ""
        raise ClusterError(f"--scheduler {address}: no Dask scheduler answers after "
                           f"{timeout:g} s (no answer{detail})") from None
    except Exception as exc:  # noqa: BLE001 - a stranger's bytes fail in any way, even MemoryError
        reply = exc
    if not (isinstance(reply, dict) and reply.get("type") == "Scheduler"):
        raise ClusterError(f"--scheduler {address}: the service there is not a Dask "
                           "scheduler (its answer is not a scheduler's identity)")


@contextlib.contextmanager
def dask_client(scheduler: str | None = None, workers: int = LOCAL_WORKERS,
                threads_per_worker: int = THREADS_PER_WORKER) -> Iterator[Any]:
    """A ``distributed.Client``: on a new LocalCluster, or on ``scheduler``.

    A LocalCluster keeps its workers' scratch space in a new temporary folder, removed
    when it closes (Dask's default leaves ``dask-scratch-space`` and its lock files in
    the system's temporary folder), and is started and closed whole
    (:func:`whole_local_cluster`).

    Args:
        scheduler: address of an existing scheduler (``tcp://HOST:PORT``);
            ``None`` starts a LocalCluster of ``workers`` processes.
        workers: worker processes of the LocalCluster (1 ... 64).
        threads_per_worker: threads per local worker.

    Raises:
        DesignError: a malformed address or worker count.
        ClusterError: nothing answers at ``scheduler`` within 10 s.
        KeyboardInterrupt: a stop while the LocalCluster started or closed, raised once
            it is closed.
    """
    import dask
    from distributed import Client

    if scheduler:
        address = check_scheduler_address(scheduler)
        probe_scheduler(address)
        try:
            client = Client(address, timeout=f"{SCHEDULER_TIMEOUT_S:g}s")
        except (OSError, TimeoutError) as exc:
            raise ClusterError(f"--scheduler {address}: no Dask scheduler answers ({exc})") from None
        try:
            yield client
        finally:
            client.close()
        return
    if isinstance(workers, bool) or not isinstance(workers, int) or not 1 <= workers <= 64:
        raise DesignError("--workers", workers, "an integer 1 ... 64")
    env = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}), **SINGLE_THREAD_ENV,
               **WORKER_ALLOCATOR_ENV)
    scratch = tempfile.mkdtemp(prefix=SCRATCH_PREFIX)
    # the workers' scratch space (and its lock files) in a folder of this run, not TMPDIR's
    with dask.config.set({"distributed.nanny.pre-spawn-environ": env,
                          "temporary-directory": scratch}):
        try:
            with whole_local_cluster(workers, threads_per_worker, scratch) as client:
                yield client
        finally:
            shutil.rmtree(scratch, ignore_errors=True)


#: Level of Dask's own log lines in a local cluster (its scheduler and its workers): none
#: below CRITICAL. A worker closed while its task runs (a stopped run) logs its lost
#: scheduler as an ERROR with a traceback, a race within Dask's close; a task's own error
#: reaches the run as the exception its result raises, so the log adds nothing.
DASK_LOG_LEVEL = logging.CRITICAL
#: Name prefix of a local cluster's scratch folder (removed when the cluster closes).
SCRATCH_PREFIX = "tactcad-dask-"


@contextlib.contextmanager
def whole_local_cluster(workers: int, threads_per_worker: int,
                        scratch: str) -> Iterator[Any]:
    """A ``distributed.Client`` on a new LocalCluster, started and closed whole.

    A stop (Ctrl-C, SIGTERM) that arrives while the cluster starts or closes is held until
    it has (:func:`tactcad.stopping.stop_signals_held`): raised in the middle of either, it
    left a cluster half made or half closed, which Dask's exit then closed with an
    ``AssertionError`` traceback and whose workers logged their lost scheduler.

    Args:
        workers: worker processes. threads_per_worker: threads per worker.
        scratch: the workers' local directory (a folder the caller removes).

    Raises:
        KeyboardInterrupt: a stop held while the cluster started, once it is closed again.
        ClusterError: the cluster did not start (a worker's nanny failed: no process, no
            socket or no writable folder to be had), with Dask's reason.
    """
    from distributed import Client, LocalCluster

    from tactcad.stopping import stop_signals_held

    cluster = client = None
    try:
        # the workers are Dask's processes: their start-up does not unblock the signals
        with stop_signals_held(block_in_children=False):
            try:
                cluster = LocalCluster(n_workers=workers, threads_per_worker=threads_per_worker,
                                       processes=True, dashboard_address=None,
                                       local_directory=scratch, silence_logs=DASK_LOG_LEVEL)
                client = Client(cluster)
            except Exception as exc:  # Dask's own failures are of many types
                raise ClusterError(
                    f"a local Dask cluster of {workers} worker process(es) did not start "
                    f"({type(exc).__name__}: {str(exc)[:200]}); `--scheduler ADDRESS` runs "
                    "on a Dask cluster started apart") from None
        yield client
    finally:
        with stop_signals_held(block_in_children=False):
            if client is not None:
                client.close()
            if cluster is not None:
                cluster.close()


def dask_mapper(client, progress: bool = True) -> Callable:
    """A ``map(func, items)`` replacement that runs on ``client``: results in item order;
    while it waits, with ``progress``, Dask's progress bar on stderr when stderr is a
    terminal, else a plain line at every tenth of the items done
    (:func:`progress_lines`): the bar redraws itself with carriage returns, which a log
    file or a pipe keeps as one long line."""

    def mapper(func: Callable, items: Iterable) -> list:
        futures = client.map(func, list(items), pure=False)
        if progress and futures and stderr_is_terminal():
            from distributed import progress as progress_bar

            with contextlib.redirect_stdout(sys.stderr):
                progress_bar(futures)
                print(file=sys.stderr)
        elif progress and futures:
            progress_lines(futures)
        return client.gather(futures)

    return mapper


def stderr_is_terminal() -> bool:
    """True when stderr is a terminal (a closed or replaced stream without ``isatty`` is not)."""
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        return False


#: Plain progress lines of a sweep not on a terminal: one at every this fraction done.
PROGRESS_LINE_STEP = 0.1


def progress_lines(futures: Sequence, step: float = PROGRESS_LINE_STEP) -> None:
    """Wait for ``futures``, writing ``sweep: DONE/TOTAL points`` on stderr at every
    ``step`` of them done (and at the last): a log's progress, one line each.

    Args:
        futures: Dask futures. step: fraction of the points between two lines (0 ... 1].
    """
    from distributed import as_completed

    total, shown = len(futures), 0
    for done, _ in enumerate(as_completed(futures), start=1):
        if done == total or done - shown >= step * total:
            print(f"sweep: {done}/{total} points", file=sys.stderr, flush=True)
            shown = done


def run_grid(func: Callable, points: Sequence, scheduler: str | None = None,
             workers: int = LOCAL_WORKERS, progress: bool = True) -> list:
    """``[func(p) for p in points]`` on a Dask cluster (see :func:`dask_client`).

    ``func`` must be importable by the workers (a module-level function).
    """
    with dask_client(scheduler, workers) as client:
        return dask_mapper(client, progress)(func, points)


# ---------------------------------------------------------------------------
# Design grid
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class GridPoint:
    """One design of a grid: a model level on one element geometry."""

    model: str
    geometry: ElementGeometry
    material: Material


@dataclass(frozen=True)
class GridRow:
    """Result of one grid point (mm, N/mm, 1/N, s). ``face_strain_per_N``: the level's
    :attr:`~tactcad.mechanics.stiffness_result.StiffnessResult.face_strain_per_N`, the face
    strain at the grid's centre under the gauge's glue line and carrier (1/N)."""

    model: str
    web_mm: float
    arm_mm: float
    notch_radius_mm: float
    K_N_per_mm: float
    face_strain_per_N: float
    error_estimate_rel: float
    wall_time_s: float


def evaluate_point(p: GridPoint) -> GridRow:
    """K of one grid point at its ladder level (runs on a worker)."""
    from tactcad.mechanics.correction import range_warnings_unsaid
    from tactcad.mechanics.ladder import estimate

    g = p.geometry
    with range_warnings_unsaid():  # the grid reports its own range
        r = estimate(p.model, g, p.material)
    return GridRow(p.model, g.web_thickness_mm, g.arm_length_mm, g.notch_radius_mm,
                   r.stiffness_N_per_mm, r.face_strain_per_N, r.error_estimate_rel,
                   r.wall_time_s)


#: Points of a default grid axis, and the default web axis's span around the
#: design's web (+/- this fraction of it).
GRID_AXIS_POINTS = 5
GRID_WEB_SPAN_REL = 0.5


def _axis(lo: float, hi: float) -> list[float]:
    """:data:`GRID_AXIS_POINTS` evenly spaced values lo ... hi (mm, 4 decimals), one when equal."""
    if hi - lo < 1e-9:
        return [round(lo, 4)]
    n = GRID_AXIS_POINTS - 1
    return [round(lo + (hi - lo) * k / n, 4) for k in range(n + 1)]


def default_grid_axes(plan: Plan) -> tuple[list[float], list[float]]:
    """The design's own grid (mm): webs within +/- :data:`GRID_WEB_SPAN_REL` of
    the design's web, kept within the web range of the design file and at least
    the cut process's minimum web on the design's sheet; arms from the design's
    shortest to its longest arm (one arm length: +/- half of it, within the arm
    range of the design file).

    Args:
        plan: the design swept.

    Returns:
        (webs, arms), each :data:`GRID_AXIS_POINTS` values from low to high.
    """
    from tactcad.design.array_plan import ARM_RANGE_MM, WEB_RANGE_MM, element_process_limits

    web = plan.element(1).geometry.web_thickness_mm
    thinnest = max(WEB_RANGE_MM[0], element_process_limits(plan.raw).min_web_mm.value_mm)
    webs = _axis(max(thinnest, web * (1 - GRID_WEB_SPAN_REL)),
                 min(WEB_RANGE_MM[1], web * (1 + GRID_WEB_SPAN_REL)))
    arms = [s.geometry.arm_length_mm for s in plan.slots]
    lo, hi = min(arms), max(arms)
    if hi - lo < 1e-9:  # one arm length: a span around it
        lo, hi = max(ARM_RANGE_MM[0], lo / 2), min(ARM_RANGE_MM[1], hi * 1.5)
    return webs, _axis(lo, hi)


def grid_points(plan: Plan, webs_mm: Sequence[float], arms_mm: Sequence[float],
                model: str = "closed-form",
                notch_radii_mm: Sequence[float] | None = None) -> list[GridPoint]:
    """Every web x arm (x notch radius) variant of the plan's element, each
    validated as a whole design (:func:`tactcad.studies.inverse_design.design_variant`).

    Notch radius default: the plan's, raised to the web where it is thinner
    (t/R <= 1).

    Raises:
        DesignError: a grid point breaks the design rules (field named), or
            an unknown model.
    """
    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies.inverse_design import design_variant
    from tactcad.mechanics.ladder import models

    if model not in models():
        raise DesignError("--model", model, ", ".join(models()))
    base = plan.element(1).geometry
    radii = list(notch_radii_mm) if notch_radii_mm else [None]
    out = []
    refused: dict[tuple[str, float], DesignError] = {}
    for t in webs_mm:
        for r in radii:
            R = max(base.notch_radius_mm, t) if r is None else r
            for a in arms_mm:
                data = design_variant(plan.raw, web_mm=t, notch_radius_mm=R,
                                      arms_mm=[a] * len(plan.slots))
                try:
                    g = plan_from_dict(data, source="<design grid>").element(1).geometry
                except DesignErrors as exc:
                    # a radius not given follows the web (t/R <= 1): its refusal is the web's
                    given = {"--webs": t, "--arms": a, "--radii": R if r is not None else t}
                    for e in grid_refusals(exc, given, radii_given=r is not None):
                        refused.setdefault((e.field, e.value), e)
                    continue
                out.append(GridPoint(model, g, plan.material))
    if refused:  # every grid value the rules refuse, each once, named by its option
        raise DesignErrors(list(refused.values()), what="the grid's values")
    return out


#: The design field each grid option varies.
GRID_FIELDS = {"element.web_thickness_mm": "--webs", "arms.lengths_mm": "--arms",
               "element.notch_radius_mm": "--radii"}


def grid_refusals(exc: DesignErrors, given: Mapping[str, float],
                  radii_given: bool = True) -> list[DesignError]:
    """A grid point's refusal named by the grid options that set the refused values (the
    arm ``arms.lengths_mm[3]`` is ``--arms``' value), each with the range the rules allow.
    Where an option's value is refused, the point's other refusals are its consequences (a
    longer arm lengthens the element) and are left out; else they are kept as they are.

    Args:
        exc: the point's design refusal. given: option -> the point's value of it (mm).
        radii_given: ``--radii`` was given; else the notch radius follows the web and its
            refusal is ``--webs``'.

    Returns:
        The refusals, one per field (an arm refused for every element once).
    """
    fields = dict(GRID_FIELDS)
    if not radii_given:
        fields["element.notch_radius_mm"] = "--webs"
    named: dict[str, DesignError] = {}
    others: dict[str, DesignError] = {}
    for e in exc.errors:
        option = fields.get(e.field.split("[")[0])
        if option is None:
            others.setdefault(e.field, e)
        else:
            named.setdefault(option, DesignError(option, given[option], e.allowed, e.why))
    return list((named or others).values())


def design_grid(plan: Plan, webs_mm: Sequence[float], arms_mm: Sequence[float],
                model: str = "closed-form", notch_radii_mm: Sequence[float] | None = None,
                mapper: Callable = map) -> list[GridRow]:
    """Evaluate the design grid (see :func:`grid_points`), rows in grid order."""
    return evaluated_grid(grid_points(plan, webs_mm, arms_mm, model, notch_radii_mm), mapper)


def evaluated_grid(points: Sequence[GridPoint], mapper: Callable = map) -> list[GridRow]:
    """The rows of grid points already judged by the design rules (:func:`grid_points`).

    Args:
        points: the grid's points, in grid order.
        mapper: ``map`` or a cluster's (:func:`dask_mapper`).

    Returns:
        One row per point (K in N/mm, strain per N, wall time in s), in grid order.
    """
    return list(mapper(evaluate_point, points))


def write_grid_csv(path: str | Path, rows: Sequence[GridRow]) -> Path:
    """CSV of grid rows (header = :class:`GridRow` fields with units), atomically."""
    from tactcad.atomic import write_atomic

    names = list(GridRow.__dataclass_fields__)

    def w(tmp: Path) -> None:
        with open(tmp, "w", newline="") as fh:
            wr = csv.writer(fh)
            wr.writerow(names)
            for row in rows:
                wr.writerow([f"{v:.9g}" if isinstance(v, float) else v
                             for v in asdict(row).values()])

    return write_atomic(path, w)


def plot_design_chart(path: str | Path, rows: Sequence[GridRow], plan: Plan,
                      title: str = "", measured: Sequence[tuple[int, float, float]] = (),
                      measured_label: str = "measured") -> Path:
    """Design chart: K (N/mm, log) against arm length (mm) for each web, with
    the closed form as a line, other levels as markers and the ``measured``
    elements (element number, arm length mm, K N/mm; the caller's, e.g. the
    paper's Table 1) as black crosses labelled ``measured_label``. Written
    atomically as PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from tactcad.atomic import write_atomic

    fig, ax = plt.subplots(figsize=(6.4, 4.6), dpi=120)
    webs = sorted({r.web_mm for r in rows})
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, max(len(webs), 1)))
    for web, colour in zip(webs, colours):
        for model in dict.fromkeys(r.model for r in rows):
            pts = sorted((r.arm_mm, r.K_N_per_mm) for r in rows
                         if r.web_mm == web and r.model == model)
            if not pts:
                continue
            x, y = zip(*pts)
            if model == "closed-form":
                ax.plot(x, y, "-", color=colour, label=f"web {web:g} mm")
            else:
                ax.plot(x, y, "o", color=colour, mfc="none", label=f"web {web:g} mm, {model}")
    if measured:
        ax.plot([arm for _, arm, _ in measured], [k for _, _, k in measured], "kx",
                ms=7, label=measured_label)
    for element, arm, k in measured:
        ax.annotate(str(element), (arm, k), textcoords="offset points", xytext=(4, 2), fontsize=7)
    ax.set_yscale("log")
    ax.set_xlabel("arm length a (mm)")
    ax.set_ylabel("tip stiffness K (N/mm)")
    g = plan.element(1).geometry
    ax.set_title(title or f"{plan.material.name}, sheet {g.sheet_thickness_mm:g} mm, "
                          f"notch radius max({g.notch_radius_mm:g} mm, web)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    write_atomic(path, lambda tmp: fig.savefig(tmp, format="png", metadata={"Software": None}))
    plt.close(fig)
    return Path(path)


# ---------------------------------------------------------------------------
# Correction refit
# ---------------------------------------------------------------------------
_DESIGN_KEYS = ("web_mm", "notch_radius_mm", "arm_mm", "sheet_mm", "poisson_ratio")


def refit_point(job: tuple[Sequence[float], str]) -> dict:
    """fem3d and the closed form's terms at one design (t, R, a, b, nu) with
    its set label: :func:`tactcad.studies.correction_sweep.evaluate_point`
    as a one-argument task."""
    from tactcad.studies.correction_sweep import evaluate_point as correction_point

    design, label = job
    return correction_point(design, label)


def correction_refit(mapper: Callable = map, n_fit: int = 64, n_holdout: int = 16,
                     points_path: str | Path | None = None) -> dict:
    """The fem3d sweep of the closed-form correction on a cluster, then the fit.

    Designs are those of :func:`tactcad.studies.correction_sweep.plan_designs`;
    designs already stored in ``points_path`` (JSON lines, default the
    sweep's own file) are skipped, new points are appended in design order,
    and :func:`tactcad.studies.correction_fit.build_document` fits all of them.
    The stored correction file is not touched.

    Returns:
        ``{"new_points": n, "wall_time_s": s, "document": {...}}``.

    Raises:
        ValueError: no fit points at all.
    """
    import json

    from tactcad.studies import correction_sweep as cs
    from tactcad.studies.correction_fit import build_document

    path = Path(cs.POINTS_FILE if points_path is None else points_path)

    def key(values) -> tuple:
        return tuple(round(float(v), 9) for v in values)

    done = {key(r[k] for k in _DESIGN_KEYS) for r in cs.read_points(path)}
    jobs = [(tuple(d), label) for d, label in cs.plan_designs(n_fit, n_holdout)
            if key(d) not in done]
    t0 = time.perf_counter()
    rows = list(mapper(refit_point, jobs))
    wall = time.perf_counter() - t0
    if rows:
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "a", encoding="utf-8") as fh:
            fh.writelines(json.dumps(r) + "\n" for r in rows)
    return {"new_points": len(rows), "wall_time_s": wall,
            "document": build_document(cs.read_points(path))}


def finite_or_none(x: float) -> float | None:
    """JSON-safe number: None for NaN or infinity."""
    return float(x) if isinstance(x, (int, float)) and math.isfinite(x) else None


def rows_as_json(rows: Sequence[GridRow]) -> list[dict]:
    return [{k: finite_or_none(v) if isinstance(v, float) else v for k, v in asdict(r).items()}
            for r in rows]

