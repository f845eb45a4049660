"""Solids and meshes that outlive one run, for the processes of ``tactcad watch``."""

from __future__ import annotations

from typing import Collection, MutableMapping

from tactcad.design.array_plan import Plan
from tactcad.export.job import solid_key
from tactcad.solids.cache import PartCache


class LiveParts(PartCache):
    """A :class:`~tactcad.solids.cache.PartCache` whose solids and meshes outlive
    one plan: keyed by the part spec's content (as the store keys a part's STEP
    file), so an edit rebuilds only the parts it changed."""

    def __init__(self, plan: Plan, solids: dict, meshes: dict):
        super().__init__(plan)
        self._solids_by_key, self._meshes_by_key = solids, meshes

    @staticmethod
    def _key(spec) -> str:
        return solid_key(spec)

    def adopt(self, spec, solid) -> None:
        self._solids_by_key.setdefault(self._key(spec), solid)

    def solid(self, spec):
        key = self._key(spec)
        if key not in self._solids_by_key:
            self._solids_by_key[key] = super().solid(spec)
        return self._solids_by_key[key]

    def mesh(self, spec):
        key = self._key(spec)
        if key not in self._meshes_by_key:
            from tactcad.solids.tessellation import tessellate

            self._meshes_by_key[key] = tessellate(self.solid(spec))
        return self._meshes_by_key[key]


def keep_only(keys: Collection[str], *kept: MutableMapping[str, object]) -> int:
    """Drop from each of ``kept`` (solids, meshes, hand-overs by content key,
    :func:`~tactcad.export.job.solid_key`) the entries whose key is not in
    ``keys``, so a long watch session holds the parts of the design it shows,
    not of every edit before; the number of entries dropped."""
    dropped = 0
    for store in kept:
        for key in [k for k in store if k not in keys]:
            del store[key]
            dropped += 1
    return dropped
