"""Every part module of :mod:`tactcad.partlib` (rig parts) and of
:mod:`tactcad.partlib.array` (the array's parts): the one registry of parts,
builders and drawings.

A module is registered by being in one of the two packages and naming its
part ``PART`` (a :class:`RigPart` or an :class:`ArrayPart`): adding a part
touches its module only (and the TOML files that show it).
"""

from __future__ import annotations

import functools
import importlib
import pkgutil
from typing import Any, Callable, Iterable, Mapping

from tactcad.partlib.base import ArrayPart, DrawingRecord, RigPart

#: Modules of the packages that are the form itself or shared by parts, not parts.
_FORM = {"base", "registry", "screws", "shapes", "stock", "prism"}
#: The packages of part modules: the rig parts', the array's.
PACKAGES = ("tactcad.partlib", "tactcad.partlib.array")

Part = RigPart | ArrayPart


@functools.cache
def in_use_parts() -> dict[str, RigPart]:
    """key -> part of every module that names an ``IN_USE_PART``: the parts of the sensor in
    use (the grasper's jaw and shaft, the tissue), placed by the grasper scene from the
    design file's tables of them (each optional), never by a rigs file (a design without a
    grasper stays as it was).

    Raises:
        ValueError: two modules declare the same key.
    """
    out: dict[str, RigPart] = {}
    package = importlib.import_module(PACKAGES[0])
    for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda i: i.name):
        if info.name in _FORM or info.ispkg:
            continue
        part = getattr(importlib.import_module(f"{PACKAGES[0]}.{info.name}"), "IN_USE_PART", None)
        if isinstance(part, RigPart):
            if part.key in out:
                raise ValueError(f"partlib: two modules declare the part key {part.key!r}")
            out[part.key] = part
    return out


@functools.cache
def part_modules() -> tuple[Part, ...]:
    """The ``PART`` of every part module, package by package, by module name."""
    out = []
    for name in PACKAGES:
        package = importlib.import_module(name)
        for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda i: i.name):
            if info.name in _FORM or info.ispkg:
                continue
            part = getattr(importlib.import_module(f"{name}.{info.name}"), "PART", None)
            if isinstance(part, (RigPart, ArrayPart)):
                out.append(part)
    return tuple(out)


def _keyed(form: type) -> dict[str, Any]:
    """key -> part of the modules of ``form``, by order, then key.

    Raises:
        ValueError: two modules declare the same key.
    """
    out: dict[str, Any] = {}
    for part in part_modules():
        if not isinstance(part, form):
            continue
        if part.key in out:
            raise ValueError(f"partlib: two modules declare the part key {part.key!r}")
        out[part.key] = part
    return dict(sorted(out.items(), key=lambda kv: (kv[1].order, kv[0])))


@functools.cache
def rig_parts_lib() -> dict[str, RigPart]:
    """key -> part of every rig part module, by :attr:`RigPart.order`, then key
    (the order of the rigs schema and of placement; stable output).

    Raises:
        ValueError: two modules declare the same key.
    """
    return _keyed(RigPart)


@functools.cache
def array_parts_lib() -> dict[str, ArrayPart]:
    """key -> part of every array part module, by :attr:`ArrayPart.order`, then
    key (the order of the array's part list; stable output).

    Raises:
        ValueError: two modules declare the same key.
    """
    return _keyed(ArrayPart)


@functools.cache
def builders() -> dict[str, Callable[[Any], Any]]:
    """builder key (``PartSpec.builder``) -> builder (geometry -> solid) of
    every part module, its own and its companions'.

    Raises:
        ValueError: two modules, or a module and a companion, share a builder key.
    """
    out: dict[str, Callable[[Any], Any]] = {}
    for part in (*part_modules(), *in_use_parts().values()):
        for key, build in part.builders().items():
            if key in out:
                raise ValueError(f"partlib: builder key {key!r} is declared twice "
                                 f"(again by part {part.key!r}): choose another key")
            out[key] = build
    return out


def array_parts_for(tables: Iterable[str]) -> list[ArrayPart]:
    """The array part modules a design with the tables ``tables`` uses, in
    their order: every family but one whose variant's table is given, and
    that variant (:attr:`ArrayPart.replaces`).

    Raises:
        ValueError: a variant replaces a key no module declares, or two given
            variants replace the same family.
    """
    lib, given = array_parts_lib(), set(tables)
    variants = [p for p in lib.values() if p.replaces and p.key in given]
    replaced = [p.replaces for p in variants]
    unknown = sorted({p.replaces for p in lib.values() if p.replaces} - set(lib))
    if unknown:
        raise ValueError(f"partlib: a variant replaces {', '.join(map(repr, unknown))}, "
                         "which no array part module declares")
    if len(set(replaced)) < len(replaced):
        raise ValueError("partlib: two variants of one family are given: "
                         + ", ".join(p.key for p in variants))
    return [p for p in lib.values()
            if p.key not in replaced and (not p.replaces or p.key in given)]


def drawing_record(builder_key: str) -> DrawingRecord | None:
    """The drawing of the part module (a rig's, the array's or one in use) whose own
    builder is ``builder_key``; None for a bought part, a companion or an unknown key."""
    modules = (*part_modules(), *in_use_parts().values())  # the jaw is drawn as any made part
    part = next((p for p in modules if p.builder_key == builder_key), None)
    return part.drawing if part is not None else None


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
