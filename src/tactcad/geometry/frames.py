"""Joint frames as data: a point and two directions on a part, no CAD kernel.

A part declares its joints as frames in its own coordinates: the origin on a
mating face (or an axis), ``z_dir`` the face's outward normal, ``x_dir`` a
reference direction in the face that fixes the rotation about the normal.
Two parts mate face to face when the child's frame, flipped (turned 180
degrees about its x axis), coincides with the parent's frame: the normals
oppose and the reference directions agree. The assembly solver
(:mod:`tactcad.assembly.scene_solver`) hands these frames to build123d joints.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

Vec3 = tuple[float, float, float]


def _unit(v: Vec3) -> Vec3:
    n = math.sqrt(sum(c * c for c in v))
    if n == 0:
        raise ValueError("zero direction")
    return (v[0] / n, v[1] / n, v[2] / n)


@dataclass(frozen=True)
class Frame:
    """A joint frame in a part's coordinates (mm).

    Attributes:
        origin: the frame's origin.
        x_dir: reference direction, perpendicular to ``z_dir``.
        z_dir: outward normal of the mating face (or the axis direction).
        owner: for a frame of a sub-assembly, the instance whose face it is
            (names the contact the mate declares); empty for a part's own frame.
    """

    origin: Vec3
    x_dir: Vec3
    z_dir: Vec3
    owner: str = ""

    def __post_init__(self):
        x, z = _unit(self.x_dir), _unit(self.z_dir)
        if abs(sum(a * b for a, b in zip(x, z))) > 1e-9:
            raise ValueError(f"x_dir {self.x_dir} not perpendicular to z_dir {self.z_dir}")
        object.__setattr__(self, "x_dir", x)
        object.__setattr__(self, "z_dir", z)

    def flipped(self) -> "Frame":
        """The frame turned 180 degrees about its x axis (normal reversed)."""
        z = self.z_dir
        return Frame(self.origin, self.x_dir, (-z[0], -z[1], -z[2]), self.owner)

    def location(self):
        """The frame as a CAD location (imports the CAD kernel)."""
        from tactcad.kernel.locations import frame

        return frame(self.origin, self.x_dir, self.z_dir)


def face(origin: Vec3, normal: Vec3, x_dir: Vec3) -> Frame:
    """Shorthand: a frame on a face with outward ``normal``."""
    return Frame(tuple(float(c) for c in origin), x_dir, normal)  # type: ignore[arg-type]
