"""Benchmarks of the design tools at scale, printed by ``tactcad bench``.

* ``bench closed-form``: corrected closed-form K evaluations per second
  (vectorised in cache-sized blocks), on one thread and on two, goal >= 1e7/s on
  two cores;
* ``bench montecarlo``: a 10 000-sample tolerance Monte Carlo of the design
  at the closed form, in this process, goal <= 1 s;
* ``bench sweep``: a fem3d design sweep on a LocalCluster of one worker
  and of two workers (one thread each, BLAS/OpenMP held to one thread),
  goal >= 1.7x.

Each prints the machine's load average next to its figure: the cores are
shared, and a busy machine lowers every figure.

Units: s, evaluations/s.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass

import numpy as np

CLOSED_FORM_GOAL_PER_S = 1e7
MONTE_CARLO_GOAL_S = 1.0
SWEEP_SPEEDUP_GOAL = 1.7


def load_average() -> str:
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def closed_form_rate(plan, n: int = 2_000_000, repeat: int = 5,
                     threads: int = 1) -> tuple[float, np.ndarray]:
    """Corrected closed-form K evaluations per second over ``n`` random designs
    (web 0.15-0.4 mm, arm 4-8 mm, notch radius web-2 mm), best of ``repeat`` passes of
    one call (the kernel works through blocks of
    :data:`~tactcad.mechanics.closed_form_batch.BLOCK` designs, ``threads`` at a time).

    Returns:
        (evaluations/s, the n K values in N/mm), the values for comparing thread counts.

    Raises:
        RuntimeError: a non-finite K.
    """
    from tactcad.mechanics.closed_form_batch import corrected_stiffness_batch
    from tactcad.mechanics.correction import load_correction

    g, mat, corr = plan.element(1).geometry, plan.material, load_correction()
    rng = np.random.default_rng(0)
    t = rng.uniform(0.15, 0.4, n)
    a = rng.uniform(4.0, 8.0, n)
    R = rng.uniform(t, 2.0)
    out = np.empty(n)
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        corrected_stiffness_batch(t, R, a, mat.youngs_modulus_MPa, g, mat.poisson_ratio, corr,
                                  out=out, threads=threads)
        best = min(best, time.perf_counter() - t0)
    if not np.all(np.isfinite(out)):
        raise RuntimeError("closed form gave a non-finite K in the benchmark")
    return n / best, out


def monte_carlo_times(plan, samples: int = 10_000, repeat: int = 3) -> tuple[float, float]:
    """(first, best of ``repeat``) wall time (s) of a tolerance Monte Carlo."""
    from tactcad.studies.tolerance_montecarlo import run_tolerance

    times = []
    for k in range(repeat):
        t0 = time.perf_counter()
        run_tolerance(plan, samples, seed=k)
        times.append(time.perf_counter() - t0)
    return times[0], min(times)


@dataclass(frozen=True)
class SweepTiming:
    points: int
    one_worker_s: float
    two_workers_s: float
    same_numbers: bool

    @property
    def speedup(self) -> float:
        return self.one_worker_s / self.two_workers_s


def _warm_worker() -> bool:
    """Import the FEM stack on a worker before timing (each worker pays it once)."""
    import tactcad.mechanics.fem.fem3d  # noqa: F401

    return True


def fem3d_sweep_timing(plan, webs=(0.25, 0.4), arms=(4.0, 8.0), model: str = "fem3d",
                       progress: bool = True) -> SweepTiming:
    """Wall time of the same fem3d grid on one, then two local workers.

    The workers are started and have imported the FEM modules before the
    clock starts; the time runs from submitting the points to gathering them.
    """
    from tactcad.studies.sweeps import dask_client, dask_mapper, evaluate_point, grid_points

    points = grid_points(plan, webs, arms, model)
    walls, results = [], []
    for workers in (1, 2):
        with dask_client(None, workers) as client:
            client.run(_warm_worker)
            t0 = time.perf_counter()
            rows = dask_mapper(client, progress)(evaluate_point, points)
            walls.append(time.perf_counter() - t0)
        results.append([r.K_N_per_mm for r in rows])
    return SweepTiming(len(points), walls[0], walls[1], results[0] == results[1])
