"""Geometry sanity of a solved scene, measured on the placed solids.

* Array tips: the contact faces of all elements lie in one plane within
  :data:`PLANE_TOL_MM`, their centres on the design pitch (along each row
  and across the two rows) within :data:`PITCH_TOL_MM`.
* Wheels: each bearing touches the base plate (exact distance) and does not
  cut into it.
* Indenter: its contact face is centred over the target (a rubber sample's
  top face, or the calibrated element's tip face) within
  :data:`CENTRE_TOL_MM` and touches it; on an element its 2 x 3 mm face
  covers the tip's face.
* Tips on the sample: every tip face touches the sample's top face and lies
  inside it.

Faces are found on the solids (planar faces by normal and position), never
taken from the joint frames that placed them.
"""

from __future__ import annotations

import math

from tactcad.checks.interference import CONTACT_TOL_MM
from tactcad.checks.check_result import CheckResult
from tactcad.kernel.inspect import common_volume, distance, extreme_planar_face
from tactcad.kernel.locations import point

PLANE_TOL_MM = 0.01
PITCH_TOL_MM = 0.01
CENTRE_TOL_MM = 0.01


def _tip_faces(scene, shapes, up):
    out = {}
    for i in scene.instances:
        if i.name.startswith("element_"):
            out[i.name] = extreme_planar_face(shapes[i.name], up)
    return out


def check_scene_sanity(scene, shapes: dict) -> list[CheckResult]:
    """Sanity rows for ``scene`` (see module doc); ``shapes``: instance name ->
    placed solid."""
    out: list[CheckResult] = []
    name = scene.name
    checks = scene.model.checks
    shown = {i.name for i in scene.instances}
    if "tips" in checks and checks["tips"] in scene.node_locations and \
            any(n.startswith("element_") for n in shown):
        loc = scene.node_locations[checks["tips"]]
        o = point(loc, (0, 0, 0))
        up = point(loc, (0, 1, 0)) - o
        ax_x = point(loc, (1, 0, 0)) - o
        ax_z = point(loc, (0, 0, 1)) - o
        faces = _tip_faces(scene, shapes, (up.X, up.Y, up.Z))
        heights = [c.dot(up) for c, _, _ in faces.values()]
        spread = max(heights) - min(heights)
        out.append(CheckResult("tips_coplanar", name, spread <= PLANE_TOL_MM,
                               f"{len(faces)} tips, height spread {spread:.2e} mm"))
        plan_pitch = scene.plan.pitch_mm
        rows: dict[float, list[float]] = {}
        for c, _, _ in faces.values():
            rows.setdefault(round(c.dot(ax_x), 3), []).append(c.dot(ax_z))
        dev = 0.0
        xs = sorted(rows)
        for zs in rows.values():
            zs.sort()
            dev = max([dev] + [abs(b - a - plan_pitch) for a, b in zip(zs, zs[1:])])
        dev = max([dev] + [abs(b - a - plan_pitch) for a, b in zip(xs, xs[1:])])
        ok = dev <= PITCH_TOL_MM and len(xs) == 2
        out.append(CheckResult("tips_on_pitch", name, ok,
                               f"{len(xs)} rows, worst deviation from {plan_pitch:g} mm pitch "
                               f"{dev:.2e} mm"))
        target = checks.get("tips_on")
        if target in shown:
            top_c, (tmin, tmax), _ = extreme_planar_face(shapes[target], (-up.X, -up.Y, -up.Z))
            worst_gap, outside = 0.0, 0
            for c, (fmin, fmax), _ in faces.values():
                worst_gap = max(worst_gap, abs((c - top_c).dot(up)))
                inside = all(getattr(tmin, a) - 1e-9 <= getattr(fmin, a) and
                             getattr(fmax, a) <= getattr(tmax, a) + 1e-9 for a in "XYZ")
                outside += 0 if inside else 1
            out.append(CheckResult("tips_on_sample", f"{name}: {target}",
                                   worst_gap <= CONTACT_TOL_MM and outside == 0,
                                   f"worst gap {worst_gap:.1e} mm, {outside} tips outside the top face"))
    base = checks.get("base")
    for w in checks.get("bearings", []):
        if w in shown and base in shown:
            gap = distance(shapes[w], shapes[base])
            vol = common_volume(shapes[w], shapes[base])
            out.append(CheckResult("bearing_on_base", f"{w} / {base}",
                                   gap <= CONTACT_TOL_MM and vol <= 1e-6,
                                   f"gap {gap:.1e} mm, overlap {vol:.1e} mm3"))
    if "indenter" in checks:
        ind, target = checks["indenter"]
        if ind in shown and target in shown:
            down = (0.0, -1.0, 0.0)
            c, (imin, imax), area = extreme_planar_face(shapes[ind], down)
            t, (tmin, tmax), _ = extreme_planar_face(shapes[target], (0.0, 1.0, 0.0))
            off = math.hypot(c.X - t.X, c.Z - t.Z)
            gap = abs(c.Y - t.Y)
            out.append(CheckResult("indenter_centred", f"{ind} / {target}",
                                   off <= CENTRE_TOL_MM and gap <= CONTACT_TOL_MM,
                                   f"centre offset {off:.1e} mm, gap {gap:.1e} mm, "
                                   f"contact face {area:.3f} mm2"))
            if target.startswith("element_"):
                dev = max(abs(getattr(imin, a) - getattr(tmin, a)) for a in "XZ")
                dev = max([dev] + [abs(getattr(imax, a) - getattr(tmax, a)) for a in "XZ"])
                out.append(CheckResult("indenter_covers_tip", f"{ind} / {target}",
                                       dev <= CENTRE_TOL_MM,
                                       f"contact face vs tip face, worst edge offset {dev:.1e} mm"))
    return out
