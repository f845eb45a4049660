"""JSON output without NaN or Infinity: non-finite floats become null."""

from __future__ import annotations

import json
import math


def finite(obj):
    """A copy of ``obj`` (dicts, lists, tuples, numbers, numpy scalars) with NaN/±inf as None and -0.0 as 0.0."""
    if isinstance(obj, dict):
        return {str(k): finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [finite(v) for v in obj]
    if hasattr(obj, "item") and not isinstance(obj, (str, bytes)):  # numpy scalar
        obj = obj.item()
    if isinstance(obj, float):
        return obj + 0.0 if math.isfinite(obj) else None  # -0.0 + 0.0 is 0.0: no "-0" printed
    return obj


def dumps(obj, indent: int = 2) -> str:
    """``json.dumps`` of :func:`finite` (obj); never writes NaN or Infinity."""
    return json.dumps(finite(obj), indent=indent, allow_nan=False)
