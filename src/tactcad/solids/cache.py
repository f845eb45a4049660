"""The solids of one run: each distinct part built once, on first request,
and tessellated at most once. Every writer and check of a run shares one
:class:`PartCache`.

A built solid is also kept in the result store (:func:`tactcad.store.kept_result`) by
its part spec, as OpenCascade's binary BREP (build123d's pickle): a run where one part
changed reads the others back (milliseconds each) instead of building them again. A
solid whose BREP does not read back (the binary reader fails on some shapes) is kept as
unreadable and built in every run, as before."""

from __future__ import annotations

import pickle
from typing import Any, Callable

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
        """The part's solid: made on first request, read back from the result store
        when an earlier run kept it (:func:`kept_solid`), else built."""
        if spec.name not in self._solids:
            self._solids[spec.name] = kept_solid(spec, self._build)
        return self._solids[spec.name]

    def _build(self, spec: PartSpec):
        """Build the part's solid and count the build."""
        solid = build_part(spec)
        self.builds += 1
        return solid

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


#: The result store's name for a part's solid (:func:`kept_solid`).
SOLID_KIND = "part solid brep"


def read_back(solid) -> tuple[bytes | None, Any]:
    """``solid`` pickled (build123d writes OpenCascade's binary BREP) and the solid read
    back from that: (blob, solid read back), or (None, ``solid``) when it does not read
    back (the binary reader fails on some solids, e.g. plated holes: 'UnExpected
    BRep_PointRepresentation') or does not pickle at all. The solid read back differs
    from the one built only in the sign of some zero coordinates (a direction
    (1, 0, -0) reads back as (1, 0, 0)); every run works on it, so an export's bytes
    do not depend on whether a solid was built now or kept."""
    try:
        blob = pickle.dumps(solid)
        return blob, pickle.loads(blob)
    except Exception:  # the kernel's reader and writer raise their own failure types
        return None, solid


def kept_solid(spec: PartSpec, build: Callable[[PartSpec], Any]):
    """The part's solid (part frame, mm) as its BREP reads back (:func:`read_back`):
    built by ``build(spec)``, or read from the result store where an earlier run kept
    the solid of an equal spec (:func:`tactcad.store.kept_result`, keyed by the spec,
    tactcad's code and the CAD stack's versions: a solid is made from its spec alone).
    Outside a result-store block a solid is built and read back; a solid whose BREP does
    not read back is built, in every run.

    Args:
        spec: the part's spec.
        build: builds the solid from the spec (and counts the build).

    Returns:
        the build123d solid.
    """
    built: list[Any] = []

    def made() -> bytes | None:
        blob, solid = read_back(build(spec))
        built.append(solid)
        return blob

    blob = kept_result(SOLID_KIND, made, spec)
    if built:
        return built[0]
    if blob is not None:
        try:
            return pickle.loads(blob)
        except Exception:  # read back when kept; a kernel that now refuses it builds anew
            pass
    return read_back(build(spec))[1]
