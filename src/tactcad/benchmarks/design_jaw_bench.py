"""``tactcad bench design-jaw``: the search of ``design --jaw`` timed on the grasper case of a
2 x 6 Ti-6Al-4V insert for a 10 mm jaw (K_r/K_m 10, K_obj 0.5-5 N/mm) at several full-scale
forces: seconds, candidates tried and counted, and what each force found (the sheet, or the
nearest force). Goal: an answer in at most 30 s on two cores. Units: s, N, mm.
"""

from __future__ import annotations

import time
from typing import Any, Mapping, Sequence

#: The grasper case's forces (N): one the jaw's comb carries, one near, one beyond.
FORCES_N = (0.05, 0.1, 0.3)
#: Seconds ``design --jaw`` may take to answer.
GOAL_S = 30.0


def design_jaw_figures(base: Mapping[str, Any], forces_N: Sequence[float] = FORCES_N,
                       shaft_class_mm: str = "10", columns: int = 6) -> dict:
    """Each force's search: seconds, candidates, the answer.

    Args:
        base: the comb construction's template tables (its ``jaw_template``, read by the
            command).

    Returns:
        ``{"goal_s", "runs": [{"force_N", "seconds", "found", "sheet_mm" | "nearest"}]}``.
    """
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.errors import DesignError
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.studies.comb_design import comb_for_jaw
    from tactcad.studies.inverse_design import Targets

    runs = []
    for force in forces_N:
        t0 = time.perf_counter()
        try:
            r = comb_for_jaw(Targets(10.0, (0.5, 5.0), force), jaw_room(shaft_class_mm), columns,
                             base, grade="Ti-6Al-4V-annealed", envelope_of=array_envelope_mm)
            answer = {"found": True, "sheet_mm": r.data["sheet"]["thickness_mm"],
                      "candidates": len(r.candidates),
                      "counted": sum(c.plan is not None and not c.failures for c in r.candidates)}
        except DesignError as exc:
            answer = {"found": False, "refusal": str(exc).splitlines()[-1].strip()}
        runs.append({"force_N": force, "seconds": time.perf_counter() - t0, **answer})
    return {"goal_s": GOAL_S, "runs": runs}


def design_jaw_lines(figures: dict) -> list[str]:
    """The figures as the bench prints them."""
    out = [f"design --jaw 10, 2 x 6 Ti-6Al-4V, K_r/K_m 10, K_obj 0.5-5 N/mm "
           f"(goal <= {figures['goal_s']:g} s):"]
    for r in figures["runs"]:
        what = (f"{r['sheet_mm']:g} mm sheet, {r['counted']} of {r['candidates']} candidates count"
                if r["found"] else f"refused; {r['refusal']}")
        out.append(f"  {r['force_N']:g} N: {r['seconds']:.2f} s, {what}")
    return out
