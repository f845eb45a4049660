"""The die's mount checked on its solids: no part enters another, the die stands in the
pocket on its carrier below the jaw's face, and the posts, and nothing else, stand proud.

Units: mm.
"""

from __future__ import annotations

from itertools import combinations

from tactcad.checks.check_result import CheckResult

#: The overlap (mm^3) counted as none: the boolean's round-off on touching faces.
TOUCHING_MM3 = 1e-6
#: Heights within this (mm) are equal.
HEIGHT_TOL_MM = 1e-6


def mount_checks(solids: dict, mount, posts_part: str) -> list[CheckResult]:
    """Interference of every pair of the mount's parts, the die's and the carrier's
    heights against the face, and the posts' proud height against the mount's.

    Args:
        solids: part name -> (solid, colour) (:func:`tactcad.products.silicon_die.export.die_scene.mount_solids`).
        mount: the :class:`tactcad.products.silicon_die.design.die_mount.DieMount` they were placed by.
        posts_part: the name of the die's posts part.
    """
    from tactcad.kernel.inspect import bbox_tuple, common_volume

    out = []
    for (a, (sa, _)), (b, (sb, _)) in combinations(solids.items(), 2):
        v = common_volume(sa, sb)
        out.append(CheckResult("die_mount_interference", f"{a} / {b}", v <= TOUCHING_MM3,
                               f"overlap {v:.3g} mm3" if v > TOUCHING_MM3 else "apart"))
    face = mount.face_z_mm
    tops = {k: bbox_tuple(s)[5] for k, (s, _) in solids.items()}
    proud = {k: top - face for k, top in tops.items() if top > face + HEIGHT_TOL_MM}
    out.append(CheckResult("die_mount_proud", "grasping face", set(proud) == {posts_part},
                           "only the posts stand proud of the face" if set(proud) == {posts_part}
                           else f"proud of the face: {sorted(proud) or 'nothing'}"))
    got = proud.get(posts_part, 0.0)
    out.append(CheckResult("die_mount_proud", posts_part,
                           abs(got - mount.post_proud_mm) <= HEIGHT_TOL_MM and got > 0,
                           f"{got * 1e3:.4g} um proud (the mount: {mount.post_proud_mm * 1e3:.4g} um)"))
    floor = face - mount.pocket_depth_mm
    carrier_bottom = bbox_tuple(solids["die_carrier"][0])[2]
    out.append(CheckResult("die_mount_seat", "die_carrier", abs(carrier_bottom - floor) <= HEIGHT_TOL_MM,
                           f"on the pocket's floor {floor:.4g} mm above the jaw's back"
                           if abs(carrier_bottom - floor) <= HEIGHT_TOL_MM
                           else f"bottom at {carrier_bottom:.4g} mm, the floor at {floor:.4g} mm"))
    return out
