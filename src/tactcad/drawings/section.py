"""Section views (ISO 128-40 / ISO 128-50): the solid cut by a plane, the
part between the viewer and the plane taken away, the rest projected by
hidden-line removal, the cut faces hatched with thin lines at 45 degrees.

Model millimetres in, a :class:`tactcad.drawings.views.View` out; its
``hatch`` polylines are view coordinates like the edges.
"""

from __future__ import annotations

import copy
import math

import numpy as np

from tactcad.drawings.views import View, cameras_for, project

HATCH_SPACING_MM = 1.5  # paper mm between hatching lines (ISO 128-50: thin, 45 degrees)


def hatch_lines(loops: list[list[tuple[float, float]]], spacing: float,
                angle_deg: float = 45.0) -> list[list[tuple[float, float]]]:
    """Hatching of the region bounded by ``loops`` (even-odd rule): parallel
    lines ``spacing`` apart at ``angle_deg``, clipped to the region."""
    a = math.radians(angle_deg)
    d = np.array((math.cos(a), math.sin(a)))
    n = np.array((-d[1], d[0]))
    segs = [(np.array(p), np.array(q)) for loop in loops for p, q in zip(loop, loop[1:] + loop[:1])]
    offs = [float(p @ n) for loop in loops for p in map(np.array, loop)]
    out = []
    k = math.floor(min(offs) / spacing) + 1
    while k * spacing < max(offs):
        c = k * spacing
        ts = []
        for p, q in segs:
            sp, sq = p @ n - c, q @ n - c
            if (sp < 0) != (sq < 0):
                x = p + (q - p) * (sp / (sp - sq))
                ts.append(float(x @ d))
        ts.sort()
        for t0, t1 in zip(ts[0::2], ts[1::2]):
            p0, p1 = c * n + t0 * d, c * n + t1 * d
            out.append([(float(p0[0]), float(p0[1])), (float(p1[0]), float(p1[1]))])
        k += 1
    return out


#: The result store's name for a section's projected edges and cut face (:func:`section_view`).
SECTION_KIND = "part section projection"


def section_view(solid, origin, normal, up, name: str, scale: float, spec=None) -> View:
    """Section of ``solid`` by the plane through ``origin`` with unit
    ``normal`` pointing at the viewer, ``up`` upwards in the view; the view
    gets ``hatch`` (view coordinates) spaced :data:`HATCH_SPACING_MM` on paper.

    Args:
        solid: the part's solid (mm).
        origin, normal, up: the cutting plane's point, its unit normal and the view's up (mm).
        name: the view's name (``A-A``).
        scale: paper mm per model mm (the hatching's spacing).
        spec: the part's spec the solid is built from: with it, the cut's edges and
            faces are kept in the result store (:func:`tactcad.store.kept_result`) by
            the spec and the plane, so an unchanged part is not cut again.

    Returns:
        the section :class:`View`.

    Raises:
        ValueError: the plane misses the solid (no cut face).
    """
    plane = tuple(tuple(float(c) for c in v) for v in (origin, normal, up))
    if spec is None:
        view, loops = _cut_and_project(solid, *plane)
    else:
        from tactcad.store import kept_result

        view, loops = kept_result(SECTION_KIND, lambda: _cut_and_project(solid, *plane),
                                  spec, plane)
        view = copy.copy(view)  # the kept view stays as made
    if not loops:
        raise ValueError(f"section {name}: the plane misses the solid")
    view.name = name
    view.scale = scale
    view.hatch = [h for lp in loops for h in hatch_lines(lp, HATCH_SPACING_MM / scale)]
    return view


def _cut_and_project(solid, origin, normal, up) -> tuple[View, list]:
    """The part of ``solid`` behind the plane projected along ``-normal``, and the cut
    face's loops in view coordinates (mm; none when the plane misses the solid)."""
    from tactcad.kernel.hlr import cut_away, cut_face_loops  # the kernel, only when drawn

    kept = cut_away(solid, origin, normal)
    cams = cameras_for(normal, up)
    view = project(kept, "front", cameras=cams)
    nv, uv = np.array(normal, float), np.array(up, float)
    rv = np.cross(uv, nv)

    def to_uv(p):
        return (float(p @ rv), float(p @ uv))

    return view, cut_face_loops(kept, origin, normal, to_uv)
