"""``crosstalk/decoupling.csv`` and ``crosstalk/decoupling.json``: the array's
decoupling matrix for the lab's read-out software.

Written for every construction a crosstalk level describes, from the level its
registration gives the verification matrix
(:func:`tactcad.mechanics.crosstalk_ladder.verify_level`: the Timoshenko stack for the
stacked array, ``comb-beam`` for a monolithic comb; each well under a second), so
``make export`` does not slow down; the JSON names the level (``model``), its error
estimate (``error_estimate_rel``) and the units. A reading
vector r (volts or strain of each gauge, element order of the header)
divided by each gauge's own sensitivity (the matrix's diagonal, also written)
gives n = r / s; the forces on the tips are D @ n (N).
"""

from __future__ import annotations

import io
import json
from pathlib import Path
from typing import Callable

from tactcad.atomic import write_bytes_atomic
from tactcad.design.array_plan import Plan
from tactcad.store import content_key

CSV_NAME = "crosstalk/decoupling.csv"
JSON_NAME = "crosstalk/decoupling.json"


def decoupling_csv(result) -> str:
    """The decoupling matrix as CSV: a header of element numbers, one row per element."""
    out = io.StringIO()
    out.write("element," + ",".join(f"element_{e}" for e in result.elements) + "\n")
    for e, row in zip(result.elements, result.decoupling):
        out.write(f"element_{e}," + ",".join(repr(_stable(v)) for v in row) + "\n")
    return out.getvalue()


def decoupling_json(plan: Plan, result) -> dict:
    """The decoupling matrix with what it came from: level, crosstalk_rel, the
    sensitivity matrix (1/N), its diagonal, the tip compliance (mm/N)."""
    import numpy as np

    return {"design": plan.name, "units": {"sensitivity": "strain per N",
                                           "compliance": "mm per N", "decoupling": "1"},
            "usage": "forces_N = decoupling @ (readings / own_sensitivity)",
            "own_sensitivity_strain_per_N": _stable(np.diag(result.sensitivity).tolist()),
            **{k: _stable(v) for k, v in result.as_json().items()
               if k not in VARYING_KEYS}}


#: What a run's figures hold that another run of the same design may not: its
#: wall time, and the asymmetry at solver precision (a diagnostic, in the manifest's
#: verification, not in the file the read-out software reads).
VARYING_KEYS = ("seconds", "asymmetry_rel")
#: Significant digits written: far above the model's accuracy, below the last
#: bits a different BLAS or summation order may change.
DIGITS = 12


def _stable(v):
    """``v`` with every float rounded to :data:`DIGITS` significant digits, so the
    same design writes the same bytes in every process."""
    if isinstance(v, float):  # numpy float64 is one too
        return float(f"{float(v):.{DIGITS}g}")
    if isinstance(v, (list, tuple)):
        return [_stable(x) for x in v]
    if isinstance(v, dict):
        return {k: _stable(x) for k, x in v.items()}
    return v


def write_crosstalk_files(plan: Plan, staging: Path, log: Callable[[str], None]) -> list[dict]:
    """Write both files into ``staging`` from the level of the plan's construction that
    :func:`~tactcad.mechanics.crosstalk_ladder.verify_level` gives.

    Args:
        plan: the design's plan. staging: the export's staging folder.
        log: takes one progress line.

    Returns:
        The two file records (``path``, ``part``, ``kind``, ``items``, ``crosstalk_rel``,
        ``model``).

    Raises:
        DesignError: no crosstalk level describes the plan's construction
            (:func:`~tactcad.mechanics.crosstalk_ladder.level_for`).
    """
    from tactcad.mechanics.crosstalk_ladder import plan_crosstalk, verify_level

    result = plan_crosstalk(plan, verify_level(plan.construction))
    write_bytes_atomic(staging / CSV_NAME, decoupling_csv(result).encode("utf-8"))
    write_bytes_atomic(staging / JSON_NAME, (json.dumps(decoupling_json(plan, result), indent=1,
                                                        allow_nan=False) + "\n").encode("utf-8"))
    log(f"  wrote {CSV_NAME} and {JSON_NAME} ({result.model}: crosstalk_rel "
        f"{result.crosstalk_rel:.3g}, {result.seconds:.2g} s)")
    n = len(result.elements)
    return [{"path": CSV_NAME, "part": "crosstalk", "kind": "decoupling-csv", "items": n,
             "crosstalk_rel": result.crosstalk_rel, "model": result.model},
            {"path": JSON_NAME, "part": "crosstalk", "kind": "decoupling-json", "items": n,
             "crosstalk_rel": result.crosstalk_rel, "model": result.model}]


def crosstalk_jobs(run, before) -> list:
    """One job writing both files, keyed by the plan it reads; none for a construction no
    crosstalk level describes (the manifest's ``left_out`` says so)."""
    from tactcad.export.job import Job
    from tactcad.mechanics.crosstalk_ladder import crosstalk_reason

    if crosstalk_reason(run.plan):
        return []

    def make(run) -> list[dict]:
        return write_crosstalk_files(run.plan, run.staging, run.log)
    return [Job("crosstalk", content_key("crosstalk", run.plan), make)]
