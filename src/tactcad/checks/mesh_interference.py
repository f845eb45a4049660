"""Pairwise interference with manifold3d meshes, confirmed by OpenCascade.

Fast path: every part is tessellated once (chordal tolerance
:data:`MESH_TOLERANCE_MM`), turned into a manifold3d ``Manifold`` (double
precision) and placed per instance; every pair with overlapping bounding
boxes is intersected on the meshes, once per export (two parts in a relative
pose an earlier scene held, the array's stack in every rig scene, are read
back). A tessellation is not conservative (the
facets of a convex face lie inside it, those of a hole stand into the hole),
so a pair goes to OpenCascade's exact boolean (:mod:`.interference`) when

* its mesh overlap exceeds the limit (a collision, or two coincident curved
  faces whose facets differ), or
* its meshes come closer than :data:`NEAR_MM` (an overlap smaller than the
  chordal error could hide there), or
* the scene declares it a contact (it must touch: exact distance <= 1e-6 mm).

The verdict of a confirmed pair is OpenCascade's; every other pair is clear
on the meshes by more than the chordal error. A failed mesh (not a
2-manifold) sends all its pairs to OpenCascade. A boolean that fails is a
failure, never "no overlap".
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass, field

import numpy as np

from tactcad.solids.tessellation import MESH_TOLERANCE_MM, tessellate

from tactcad.checks.interference import CONTACT_TOL_MM, OVERLAP_TOL_MM3, Placed
from tactcad.checks.check_result import CheckResult
from tactcad.kernel.inspect import bounding_box, common_volume, touching_gap
from tactcad.kernel.locations import matrix, relative

NEAR_MM = 4 * MESH_TOLERANCE_MM  # closer meshes than this go to the exact check


@dataclass
class InterferenceReport:
    """Rows plus the numbers the benchmark prints (seconds, pair counts)."""

    results: list[CheckResult]
    pairs_tested: int = 0
    pairs_confirmed: int = 0
    mesh_seconds: float = 0.0
    confirm_seconds: float = 0.0
    overlaps: dict[frozenset[str], float] = field(default_factory=dict)
    #: of ``pairs_tested``, those whose mesh verdict an earlier call with the same memo
    #: made (the same two parts in the same relative pose: the array's stack in every scene)
    pairs_reused: int = 0


def part_manifold(solid, tolerance_mm: float = MESH_TOLERANCE_MM, mesh=None):
    """A part's solid as a manifold3d ``Manifold`` in its own frame (mm), or
    ``None`` if its tessellation is not a closed 2-manifold. ``mesh``: the
    solid's :func:`tessellate` result, if already made."""
    import manifold3d

    v, t = mesh if mesh is not None else tessellate(solid, tolerance_mm)
    # OpenCascade meshes each face alone: merge the shared edge nodes by position
    key, inverse = np.unique(np.round(v, 9), axis=0, return_inverse=True)
    t = inverse.reshape(-1)[t]
    t = t[(t[:, 0] != t[:, 1]) & (t[:, 1] != t[:, 2]) & (t[:, 0] != t[:, 2])]
    m = manifold3d.Manifold(manifold3d.Mesh64(vert_properties=np.ascontiguousarray(key),
                                              tri_verts=np.ascontiguousarray(t, dtype=np.uint64)))
    if m.status() != manifold3d.Error.NoError or m.is_empty():
        return None
    return m


def _affine(location) -> np.ndarray:
    """3 x 4 affine matrix (mm) of a kernel location."""
    return matrix(location)[:3]


def _pose_key(a: str, b: str, part_of: dict, locations: dict) -> tuple:
    """(part, part, relative pose rounded to 1e-9 mm) of an instance pair."""
    a, b = sorted((a, b), key=lambda n: (part_of[n], n))
    rel = _affine(relative(locations[a], locations[b]))
    return (part_of[a], part_of[b], tuple(np.round(rel, 9).ravel()))


def mesh_verdict(ma, mb, contact: bool) -> tuple[float, bool]:
    """The fast path's verdict on two placed meshes: their overlap volume (mm3) and whether
    the pair goes to OpenCascade's exact check (an overlap above
    :data:`~tactcad.checks.interference.OVERLAP_TOL_MM3`, a declared contact, or meshes
    closer than :data:`NEAR_MM`).

    Args:
        ma, mb: the two parts' manifold3d ``Manifold`` placed in one frame (mm).
        contact: whether the scene declares the pair a contact.

    Returns:
        (overlap volume in mm3, whether it needs the exact check).
    """
    vol = (ma ^ mb).volume()
    return vol, vol > OVERLAP_TOL_MM3 or contact or ma.min_gap(mb, NEAR_MM) < NEAR_MM


def check_mesh_interference(placed: list[Placed], contacts: set[frozenset[str]],
                            part_of: dict[str, str], part_solids: dict, locations: dict,
                            confirm: bool = True, part_meshes: dict | None = None,
                            memo: dict | None = None) -> InterferenceReport:
    """Overlap of every pair (fast path on meshes, exact confirmation), and
    touching of the declared contacts.

    Args:
        placed: instances in the scene frame (name, placed solid).
        contacts: declared touching pairs of instance names.
        part_of: instance name -> part name (meshes are made once per part).
        part_solids: part name -> solid in the part's frame.
        locations: instance name -> build123d ``Location`` that placed it
            (``placed`` holds ``placed(part_solids[part], location)``).
        confirm: run the OpenCascade confirmation (off: mesh verdicts only,
            for timing the fast path).
        part_meshes: part name -> :func:`tessellate` result, if already made.
        memo: the mesh verdicts and exact answers of earlier calls, by the two
            parts, their relative pose and whether they are a contact (the same
            part names must mean the same solids: one export's scenes share it).
    """
    t0 = time.perf_counter()
    part_meshes = part_meshes or {}
    meshes = {name: part_manifold(s, mesh=part_meshes.get(name)) for name, s in part_solids.items()}
    items = []
    for p in placed:
        base = meshes[part_of[p.name]]
        m = None if base is None else base.transform(_affine(locations[p.name]))
        items.append((p, m, bounding_box(p.shape)))
    out: list[CheckResult] = []
    to_confirm: list[tuple[Placed, Placed, float | None]] = []
    tested = reused = 0
    # same two parts in the same relative pose: same answer (across scenes too)
    memo = {} if memo is None else memo
    for (a, ma, ba), (b, mb, bb) in itertools.combinations(items, 2):
        pair = frozenset({a.name, b.name})
        if not ba.overlaps(bb, max(NEAR_MM, CONTACT_TOL_MM)):
            if pair in contacts:
                out.append(CheckResult("contact_touching", f"{a.name} / {b.name}", False,
                                       "boxes apart"))
            continue
        tested += 1
        if ma is None or mb is None:
            to_confirm.append((a, b, None))
            continue
        key = ("mesh",) + _pose_key(a.name, b.name, part_of, locations) + (pair in contacts,)
        if key in memo:
            reused += 1
        else:
            memo[key] = mesh_verdict(ma, mb, pair in contacts)
        vol, exact = memo[key]
        if exact:
            to_confirm.append((a, b, vol))
    t1 = time.perf_counter()
    overlaps: dict[frozenset[str], float] = {}
    if confirm:
        for a, b, mvol in to_confirm:
            subject = f"{a.name} / {b.name}"
            pair = frozenset({a.name, b.name})
            mesh = "" if mvol is None else f" (mesh {mvol:.3g} mm3)"
            key = _pose_key(a.name, b.name, part_of, locations) + (pair in contacts,)
            if key not in memo:
                try:
                    vol = common_volume(a.shape, b.shape)
                except Exception as exc:
                    memo[key] = (exc, None)
                else:
                    gap = touching_gap(a.shape, b.shape, CONTACT_TOL_MM) if pair in contacts else None
                    memo[key] = (vol, gap)
            vol, gap = memo[key]
            if isinstance(vol, Exception):
                out.append(CheckResult("interference", subject, False, f"boolean failed: {vol}"))
                continue
            if vol > OVERLAP_TOL_MM3:
                overlaps[pair] = vol
                out.append(CheckResult("interference", subject, False,
                                       f"overlap {vol:.6g} mm3{mesh}"))
            if gap is not None:
                out.append(CheckResult("contact_touching", subject, gap <= CONTACT_TOL_MM,
                                       f"gap {gap:.1e} mm"))
    else:
        for a, b, mvol in to_confirm:
            if mvol is not None and mvol > OVERLAP_TOL_MM3 and frozenset({a.name, b.name}) not in contacts:
                overlaps[frozenset({a.name, b.name})] = mvol
    t2 = time.perf_counter()
    ok = not any(r.check == "interference" and not r.passed for r in out)
    out.append(CheckResult(
        "interference", f"{len(placed)} parts", ok,
        f"{tested} pairs on meshes ({t1 - t0:.2f} s), {len(to_confirm)} confirmed exactly "
        f"({t2 - t1:.2f} s), overlap limit {OVERLAP_TOL_MM3:g} mm3"))
    return InterferenceReport(out, tested, len(to_confirm), t1 - t0, t2 - t1, overlaps, reused)
