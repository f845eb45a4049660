"""Every part module of :mod:`tactcad.partlib`, keyed by :attr:`RigPart.key`.

A module is registered by being in the package and naming its part ``PART``:
adding a part touches its module only (and the TOML files that show it).
"""

from __future__ import annotations

import functools
import importlib
import pkgutil
from typing import Iterable, Mapping

from tactcad.partlib.base import RigPart

#: Modules of the package that are the form itself, not parts.
_FORM = {"base", "registry", "screws", "shapes", "stock"}


@functools.cache
def rig_parts_lib() -> dict[str, RigPart]:
    """key -> part of every part module, by :attr:`RigPart.order`, then key
    (the order of the rigs schema and of placement; stable output).

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
    return dict(sorted(out.items(), key=lambda kv: (kv[1].order, kv[0])))


@functools.cache
def derivation_order() -> tuple[str, ...]:
    """The part keys so that every part comes after the parts it ``needs``;
    among parts free to go either way, by :attr:`RigPart.order`.

    Raises:
        ValueError: a part needs a key no module declares, or parts need each
            other in a circle (the message names the circle).
    """
    lib = rig_parts_lib()
    for part in lib.values():
        unknown = [n for n in part.needs if n not in lib]
        if unknown:
            raise ValueError(f"partlib: part {part.key!r} needs {', '.join(map(repr, unknown))}, "
                             f"which no part module declares (known: {', '.join(lib)})")
    return tuple(topological(lib, {k: p.needs for k, p in lib.items()}))


def topological(ordered: Iterable[str], needs: Mapping[str, Iterable[str]]) -> list[str]:
    """``ordered``'s keys, each after its ``needs``, else in ``ordered``'s order.

    Raises:
        ValueError: a circle of needs, named ``a -> b -> a``.
    """
    keys, done, out = list(ordered), set(), []
    while len(out) < len(keys):
        ready = next((k for k in keys if k not in done and set(needs[k]) <= done), None)
        if ready is None:
            raise ValueError("partlib: parts need each other in a circle: "
                             + " -> ".join(_circle([k for k in keys if k not in done], needs)))
        done.add(ready)
        out.append(ready)
    return out


def _circle(left: list[str], needs: Mapping[str, Iterable[str]]) -> list[str]:
    """One circle among ``left`` (each needs one of ``left``), first key repeated at its end."""
    path, k = [], left[0]
    while k not in path:
        path.append(k)
        k = next(n for n in needs[k] if n in left)
    return path[path.index(k):] + [k]
