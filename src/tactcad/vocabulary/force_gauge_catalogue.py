"""Digital force gauges a rig may carry: the catalogue the rigs made for a
design choose from (:mod:`tactcad.studies.rig_sizing`).

Data: ``tactcad/data/force_gauges.toml``; each model carries its maker's
range (capacity) and resolution and the document they come from, its own
stiffness and its housing envelope. Imports only the standard library and
:mod:`tactcad.errors`, as :mod:`tactcad.vocabulary.material_library`.

Units: N, N/mm, mm.
"""

from __future__ import annotations

import functools
import math
import tomllib
from dataclasses import dataclass, fields
from importlib import resources

GAUGES_FILE = "force_gauges.toml"


@dataclass(frozen=True)
class ForceGaugeModel:
    """One catalogue force gauge.

    Attributes:
        model: the maker's model name, as ``[force_gauge] model`` writes it.
        maker: the maker. range_N: capacity (N). resolution_N: smallest
            increment shown (N). stiffness_N_per_mm: the gauge's own spring
            (N/mm). length_mm, width_mm, depth_mm: housing envelope (mm).
        shaft_diameter_mm, shaft_length_mm: measuring shaft envelope (mm).
        source: the document range and resolution come from.
    """

    model: str
    maker: str
    range_N: float
    resolution_N: float
    stiffness_N_per_mm: float
    length_mm: float
    width_mm: float
    depth_mm: float
    shaft_diameter_mm: float
    shaft_length_mm: float
    source: str


@functools.lru_cache(maxsize=1)
def force_gauges() -> tuple[ForceGaugeModel, ...]:
    """Every catalogue gauge, by range then resolution (smallest first).

    Raises:
        ValueError: an entry with a missing field or a number that is not
            finite and > 0, or a resolution not below its range (names the
            model and the field).
    """
    text = resources.files("tactcad").joinpath("data", GAUGES_FILE).read_text(encoding="utf-8")
    out = [_gauge(name, table) for name, table in tomllib.loads(text)["gauges"].items()]
    return tuple(sorted(out, key=lambda g: (g.range_N, g.resolution_N)))


def _gauge(name: str, table: dict) -> ForceGaugeModel:
    values = {"model": name}
    for f in fields(ForceGaugeModel)[1:]:
        if f.name not in table:
            raise ValueError(f"{GAUGES_FILE}: gauges.{name!r} has no {f.name}")
        v = table[f.name]
        if f.type == "float" and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"{GAUGES_FILE}: gauges.{name!r}.{f.name} = {v!r}: allowed a number > 0")
        values[f.name] = float(v) if f.type == "float" else str(v)
    gauge = ForceGaugeModel(**values)
    if gauge.resolution_N >= gauge.range_N:
        raise ValueError(f"{GAUGES_FILE}: gauges.{name!r}.resolution_N = {gauge.resolution_N:g}: "
                         f"allowed < range_N = {gauge.range_N:g}")
    return gauge
