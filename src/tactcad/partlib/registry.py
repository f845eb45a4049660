"""Every part module of :mod:`tactcad.partlib`, keyed by :attr:`RigPart.key`.

A module is registered by being in the package and naming its part ``PART``:
adding a part touches its module only (and the TOML files that show it).
"""

from __future__ import annotations

import functools
import importlib
import pkgutil

from tactcad.partlib.base import RigPart

#: Modules of the package that are the form itself, not parts.
_FORM = {"base", "registry"}


@functools.cache
def rig_parts_lib() -> dict[str, RigPart]:
    """key -> part of every part module, in module-name order (stable output).

    Raises:
        ValueError: two modules declare the same key.
    """
    import tactcad.partlib as package

    out: dict[str, RigPart] = {}
    for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda i: i.name):
        if info.name in _FORM:
            continue
        part = getattr(importlib.import_module(f"{package.__name__}.{info.name}"), "PART", None)
        if not isinstance(part, RigPart):
            continue
        if part.key in out:
            raise ValueError(f"partlib: two modules declare the part key {part.key!r}")
        out[part.key] = part
    return out
