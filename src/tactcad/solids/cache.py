"""The solids of one run: each distinct part built once, on first request,
and tessellated at most once. Every writer and check of a run shares one
:class:`PartCache`."""

from __future__ import annotations

from typing import Any

from tactcad.catalogue.array_catalogue import PartSpec
from tactcad.design.array_plan import Plan
from tactcad.solids.tessellation import MESH_ANGULAR_TOLERANCE, MESH_TOLERANCE_MM, tessellate
from tactcad.solids.build import build_part
from tactcad.store import kept_result


class PartCache:
    """Solids (build123d, part frame, mm) and meshes of one plan's parts, by part name."""

    def __init__(self, plan: Plan):
        self.plan = plan
        self._solids: dict[str, Any] = {}
        self._meshes: dict[str, Any] = {}
        self.builds = 0  # solids built by this cache

    def adopt(self, spec: PartSpec, solid) -> None:
        """Take ``solid`` as the part's, built elsewhere in the same run (the
        run's other process); it does not count as a build here."""
        self._solids.setdefault(spec.name, solid)

    def solid(self, spec: PartSpec):
        """The part's solid, built on first request."""
        if spec.name not in self._solids:
            self._solids[spec.name] = build_part(spec)
            self.builds += 1
        return self._solids[spec.name]

    def mesh(self, spec: PartSpec):
        """The part's triangle mesh (vertices (n, 3) float64 mm, triangles (m, 3)
        int64) at :data:`tactcad.solids.tessellation.MESH_TOLERANCE_MM`, made once
        and kept in the result store by the part's spec (:func:`tactcad.store.kept_result`),
        so a run where one part changed meshes that part alone."""
        if spec.name not in self._meshes:
            self._meshes[spec.name] = kept_result(
                "part mesh", lambda: tessellate(self.solid(spec)), spec, MESH_TOLERANCE_MM,
                MESH_ANGULAR_TOLERANCE)
        return self._meshes[spec.name]
