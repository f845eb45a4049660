"""``tactcad bench atlas``: the design atlas's speed and honesty.

Times one atlas on a local Dask cluster of one worker, then of two (one thread each; every
worker has judged :data:`WARM_POINTS` points of another sample before the clock starts), prints
the points judged per second and the two-worker scaling (goal >= 1.7x), and runs
``tactcad design`` itself on a few drawn records to count how many it answers as the atlas
did: the same verdict, the same option named and the same binding limit.

Units: s, points/s.
"""

from __future__ import annotations

import json
import random
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Callable, Mapping, Sequence

#: Two workers against one: the scaling the atlas aims for.
ATLAS_SCALING_GOAL = 1.7
#: Points per second the atlas aims for on two cores: 10 000 points in 2 minutes.
ATLAS_RATE_GOAL_PER_S = 10_000 / 120.0


#: Points of another sample each worker judges before the clock starts: enough that the
#: first feasible die's imports and per-process caches are paid outside the timing (at
#: 128 points they were a third of one worker's CPU seconds; 10 000 points amortise them).
WARM_POINTS = 16


def warm_worker(atlas, points: Sequence[Mapping[str, Any]]) -> int:
    """Judge a few points on a worker before the clock starts: its imports and the caches
    every later point shares (the tissue's contact solve of one face) are paid outside the
    timing.

    Args:
        atlas: the jaw (:class:`tactcad.studies.design_atlas.JawAtlas`). points: targets
            not among those timed.

    Returns:
        The records judged (one per point, product and material).
    """
    from tactcad.studies.design_atlas import evaluate_batch

    return len(evaluate_batch(atlas, [dict(p) for p in points]))


def worker_cpu_s() -> float:
    """This process's CPU time (s): a worker's, asked before and after the timed run."""
    return time.process_time()


def timed_atlas(atlas, points: Sequence[dict], workers: int, batch: int | None,
                warm: Sequence[dict] = ()) -> tuple[float, list[dict], list[float]]:
    """One atlas on a new local cluster of ``workers`` single-threaded processes.

    Args:
        atlas: the jaw. points: the targets. workers: worker processes (1 ... 64).
        batch: points per Dask task (None: as ``tactcad atlas`` chooses for ``workers``
            single-threaded workers, :func:`tactcad.studies.design_atlas.auto_batch`).
        warm: targets each worker judges first (default: the first of ``points``).

    Returns:
        (wall seconds from submitting the batches to gathering them, the records, the CPU
        seconds each worker spent meanwhile: on a busy machine a worker gets a fraction of
        a core, and the CPU time shows how the work split where the wall time cannot).
    """
    from tactcad.studies.design_atlas import auto_batch, run_atlas
    from tactcad.studies.sweeps import dask_client

    with dask_client(None, workers) as client:
        client.run(warm_worker, atlas, list(warm) or points[:1])
        cpu0 = client.run(worker_cpu_s)
        start = time.perf_counter()
        records, _ = run_atlas(atlas, points, client, batch or auto_batch(len(points), workers))
        wall = time.perf_counter() - start
        cpu1 = client.run(worker_cpu_s)
        return wall, records, [cpu1[w] - cpu0[w] for w in sorted(cpu0)]


def design_answer(record: Mapping[str, Any], folder: Path) -> tuple[int, dict]:
    """``tactcad design`` run in a new process on a record's own command line.

    Args:
        record: an atlas record (its ``command``). folder: where the design is written.

    Returns:
        (the exit code, the JSON it printed; ``{}`` when it printed none).
    """
    words = shlex.split(record["command"])[2:]  # less "tactcad design"
    words[-1] = str(folder / Path(words[-1]).name)
    run = subprocess.run([sys.executable, "-m", "tactcad", "design", *words, "--json"],
                         capture_output=True, text=True, check=False)
    try:
        return run.returncode, json.loads(run.stdout)
    except json.JSONDecodeError:
        return run.returncode, {}


def disagreement(record: Mapping[str, Any], code: int, answer: Mapping[str, Any]) -> str:
    """Where design's answer differs from the atlas's record.

    Args:
        record: the atlas's record. code, answer: design's exit code and JSON.

    Returns:
        "" when they agree: a feasible record designs (exit 0); a refused one is refused
        naming the same option (where the atlas sought it) with the same limit code. Else
        what differs.
    """
    if record["feasible"]:
        return "" if code == 0 else f"design refused it: {answer.get('error', {}).get('message')}"
    error = answer.get("error") or {}
    if code == 0 or not error:
        return "design wrote it"
    if record["design_field"] and error.get("field") != record["design_field"]:
        return f"design names {error.get('field')}, the atlas {record['design_field']}"
    if error.get("limit", "") != record["binding_limit"]:
        return f"design's limit {error.get('limit')!r}, the atlas's {record['binding_limit']!r}"
    return ""


def drawn_records(records: Sequence[dict], count: int, seed: int) -> list[dict]:
    """``count`` records drawn without replacement, feasible and refused alike where both
    exist (half each, as far as each kind goes).

    Args:
        records: the atlas's records. count: how many (>= 0). seed: the draw's seed.

    Returns:
        The drawn records, in the atlas's order.
    """
    rng = random.Random(seed)
    feasible = [r for r in records if r["feasible"]]
    refused = [r for r in records if not r["feasible"]]
    take_f = min(len(feasible), max(count - len(refused), count // 2))
    picked = rng.sample(feasible, take_f) + rng.sample(refused, min(len(refused),
                                                                    count - take_f))
    return sorted(picked, key=lambda r: (r["point"], r["product"], r["material"]))


def atlas_bench_figures(atlas, points: int, agree: int, batch: int | None, seed: int = 0,
                        say: Callable[[str], None] = lambda s: None) -> dict:
    """The benchmark's figures.

    Args:
        atlas: the jaw and its products (:class:`tactcad.studies.design_atlas.JawAtlas`,
            as ``tactcad atlas`` makes it). points: target points of the sample (>= 2).
            agree: records checked against ``tactcad design``. batch: points per task (None: the atlas's own choice).
            seed: the sample's and the draw's seed. say: progress lines.

    Returns:
        ``points``, ``records``, ``one_worker_s``, ``two_workers_s``, ``points_per_s``
        (two workers), ``points_per_s_one``, ``scaling`` (one's seconds over two's),
        ``same_records`` (both runs gave the same table), ``agreement`` (checked, agreed,
        rate, each disagreement) and the goals.
    """
    from tactcad.studies.design_atlas import atlas_targets

    jaw = atlas.jaw
    targets = atlas_targets(points, None, seed)
    warm = atlas_targets(WARM_POINTS, None, seed + 1)  # another scramble: not timed points
    say(f"tactcad bench atlas: jaw {jaw}, {points} points, one worker")
    one_s, one, one_cpu = timed_atlas(atlas, targets, 1, batch, warm)
    say(f"  one worker {one_s:.1f} s; two workers")
    two_s, two, two_cpu = timed_atlas(atlas, targets, 2, batch, warm)
    checked = drawn_records(two, agree, seed)
    misses = []
    with tempfile.TemporaryDirectory() as tmp:
        for r in checked:
            say(f"  design on point {r['point']} ({r['product']} {r['material']})")
            why = disagreement(r, *design_answer(r, Path(tmp)))
            if why:
                misses.append({"command": r["command"], "why": why})
    agreed = len(checked) - len(misses)
    return {"jaw": jaw, "points": points, "records": len(two),
            "products": [list(p) for p in atlas.products],
            "one_worker_s": one_s, "two_workers_s": two_s,
            "points_per_s_one": points / one_s, "points_per_s": points / two_s,
            "scaling": one_s / two_s,
            "one_worker_cpu_s": one_cpu[0], "two_workers_cpu_s": two_cpu,
            "cpu_scaling": one_cpu[0] / max(two_cpu),
            "same_records": json.dumps(one, sort_keys=True) == json.dumps(two, sort_keys=True),
            "agreement": {"checked": len(checked), "agreed": agreed,
                          "rate": agreed / len(checked) if checked else None,
                          "disagreements": misses},
            "goals": {"scaling": ATLAS_SCALING_GOAL, "points_per_s": ATLAS_RATE_GOAL_PER_S}}


def atlas_bench_lines(f: Mapping[str, Any], load: str) -> list[str]:
    """The figures as the command prints them.

    Args:
        f: :func:`atlas_bench_figures`. load: the machine's load average.

    Returns:
        Lines of text.
    """
    a = f["agreement"]
    scaling = "ok" if f["scaling"] >= ATLAS_SCALING_GOAL else "under goal"
    rate = "ok" if f["points_per_s"] >= ATLAS_RATE_GOAL_PER_S else "under goal"
    agreed = ("no records drawn" if not a["checked"] else
              f"{a['agreed']}/{a['checked']} agree ({100 * a['rate']:.0f} %)")
    return [f"tactcad bench atlas: jaw {f['jaw']}, {f['points']} points, {f['records']} "
            f"records ({', '.join(' '.join(p) for p in f['products'])})",
            f"  1 worker  {f['one_worker_s']:7.1f} s  {f['points_per_s_one']:8.2f} points/s",
            f"  2 workers {f['two_workers_s']:7.1f} s  {f['points_per_s']:8.2f} points/s   "
            f"goal >= {ATLAS_RATE_GOAL_PER_S:.0f}: {rate}",
            f"  scaling {f['scaling']:.2f}x   goal >= {ATLAS_SCALING_GOAL:g}x: {scaling}; "
            f"same table both runs: {f['same_records']}",
            f"  worker CPU: 1 worker {f['one_worker_cpu_s']:.1f} s, 2 workers "
            f"{' + '.join(f'{c:.1f}' for c in f['two_workers_cpu_s'])} s: the work splits "
            f"{f['cpu_scaling']:.2f}x (wall scaling needs the cores free)",
            f"  agreement with tactcad design: {agreed}",
            *[f"    differs: {m['why']}: {m['command']}" for m in a["disagreements"]],
            f"  load average {load}"]
