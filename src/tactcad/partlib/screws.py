"""Stock lengths of the rig parts' socket head cap screws (ISO 4762)."""

from __future__ import annotations

from typing import Any

from tactcad.vocabulary.schema import Problems, fmt
from tactcad.vocabulary.standards import BoltSpec, shortest_stock_length


def stock_length(bolt: BoltSpec, needed: float, field: str, value: Any, p: Problems) -> float:
    """Shortest stock length (mm) of ``bolt`` >= ``needed`` (mm); when there is
    none, a refusal naming ``field`` and ``value`` and the longest stock length."""
    length = shortest_stock_length(bolt, needed)
    if length is None:
        p.add(field, value, f"a smaller grip: {bolt.size} needs {fmt(needed)} mm, "
              f"longest stock is {fmt(max(bolt.catalogue_lengths_mm))} mm")
        return max(bolt.catalogue_lengths_mm)
    return length
