"""Cubic crystals for a silicon die: the anisotropic elasticity and piezoresistance of
single-crystal silicon, read along a direction of a (100) wafer.

A cubic crystal has three independent elastic constants (C11, C12, C44, Voigt notation) and
three piezoresistance coefficients (pi11, pi12, pi44), all stated in the crystal's cube axes
<100>. A beam cut along a wafer direction sees the modulus and the coefficients of that
direction: with direction cosines (l, m, n) to the cube axes (Nye, *Physical Properties of
Crystals*, 1957; Kanda, IEEE Trans. Electron Devices 29(1), 1982),

* 1/E = S11 - 2 (S11 - S12 - S44/2) (l^2 m^2 + m^2 n^2 + n^2 l^2),
* pi_l = pi11 - 2 (pi11 - pi12 - pi44) (l^2 m^2 + m^2 n^2 + n^2 l^2) along the current,
* pi_t = pi12 + (pi11 - pi12 - pi44) (l1^2 l2^2 + m1^2 m2^2 + n1^2 n2^2) across it,

and the full tensor turns into the beam's frame by the Bond rotation of its Voigt matrix (the
form an FE solver takes: CalculiX ``*ELASTIC, TYPE=ANISO``, 21 constants). The two are
independent computations of one thing: the tests check one against the other.

Sources of the constants: :data:`SILICON` (Hopcroft, Nix and Kenny, "What is the Young's
modulus of silicon?", J. Microelectromech. Syst. 19(2), 2010, Table I, from Hall 1967);
:data:`SILICON_P_TYPE`, :data:`SILICON_N_TYPE` (Smith, "Piezoresistance effect in germanium
and silicon", Phys. Rev. 94(1), 1954, at 7.8 and 11.7 ohm cm). Units: MPa, 1/MPa, 1/Pa for
the piezoresistance coefficients as published (x 1e-11).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class CubicElasticity:
    """A cubic crystal's stiffness in its cube axes (MPa, Voigt notation).

    Attributes:
        c11, c12, c44: the three constants (MPa); C44 is the engineering shear modulus.
        source: where they come from.
    """

    c11: float
    c12: float
    c44: float
    source: str

    def stiffness(self) -> np.ndarray:
        """The 6 x 6 Voigt stiffness in the cube axes (MPa; engineering shear strains)."""
        c = np.zeros((6, 6))
        c[:3, :3] = self.c12
        np.fill_diagonal(c[:3, :3], self.c11)
        c[3:, 3:] = np.diag([self.c44] * 3)
        return c

    def compliance(self) -> np.ndarray:
        """The 6 x 6 Voigt compliance in the cube axes (1/MPa)."""
        return np.linalg.inv(self.stiffness())

    def young_modulus_MPa(self, direction) -> float:
        """Young's modulus along ``direction`` (a 3-vector in the cube axes, any length;
        MPa): Nye's closed form for a cubic crystal.

        Raises:
            ValueError: a zero direction.
        """
        l, m, n = unit(direction)
        s = self.compliance()
        s11, s12, s44 = s[0, 0], s[0, 1], s[3, 3]
        return 1.0 / (s11 - 2 * (s11 - s12 - s44 / 2) * (l * l * m * m + m * m * n * n
                                                           + n * n * l * l))

    def in_frame(self, x_dir, y_dir) -> np.ndarray:
        """The 6 x 6 Voigt stiffness in the beam's frame (MPa): its x axis along ``x_dir``,
        y along ``y_dir`` (3-vectors in the cube axes, perpendicular), z = x cross y.

        Raises:
            ValueError: zero or not perpendicular directions.
        """
        return bond_rotation(frame_matrix(x_dir, y_dir)) @ self.stiffness() @ \
            bond_rotation(frame_matrix(x_dir, y_dir)).T


@dataclass(frozen=True)
class PiezoCoefficients:
    """A cubic crystal's piezoresistance coefficients in its cube axes (1/Pa x 1e-11, as
    published), with the resistivity they were measured at and their source."""

    pi11: float
    pi12: float
    pi44: float
    resistivity_ohm_cm: float
    source: str

    def longitudinal(self, current) -> float:
        """pi_l (1/Pa x 1e-11): the coefficient of a stress along the current (a 3-vector in
        the cube axes). Raises ValueError for a zero direction."""
        l, m, n = unit(current)
        a = self.pi11 - self.pi12 - self.pi44
        return self.pi11 - 2 * a * (l * l * m * m + m * m * n * n + n * n * l * l)

    def transverse(self, current, stress) -> float:
        """pi_t (1/Pa x 1e-11): the coefficient of a stress along ``stress``, perpendicular to
        ``current`` (3-vectors in the cube axes).

        Raises:
            ValueError: zero or not perpendicular directions.
        """
        (l1, m1, n1), (l2, m2, n2) = frame_matrix(current, stress)[:2]
        a = self.pi11 - self.pi12 - self.pi44
        return self.pi12 + a * (l1 * l1 * l2 * l2 + m1 * m1 * m2 * m2 + n1 * n1 * n2 * n2)


def unit(v) -> np.ndarray:
    """``v`` scaled to length 1. Raises ValueError for a zero or non-finite vector."""
    v = np.asarray(v, float)
    norm = float(np.linalg.norm(v))
    if not (math.isfinite(norm) and norm > 0):
        raise ValueError(f"direction {v.tolist()}: a non-zero finite 3-vector")
    return v / norm


def frame_matrix(x_dir, y_dir) -> np.ndarray:
    """The rotation whose rows are the frame's x, y and z axes in the cube axes.

    Raises:
        ValueError: zero or not perpendicular directions.
    """
    x, y = unit(x_dir), unit(y_dir)
    if abs(float(x @ y)) > 1e-9:
        raise ValueError(f"directions {x.tolist()} and {y.tolist()}: perpendicular")
    return np.vstack([x, y, np.cross(x, y)])


def bond_rotation(a: np.ndarray) -> np.ndarray:
    """The 6 x 6 Bond matrix M of rotation ``a`` (rows: the new axes in the old) for Voigt
    stresses and a stiffness with engineering shear strains: C' = M C M^T (Auld, *Acoustic
    Fields and Waves in Solids*, 1973, eq. 3.32; order xx, yy, zz, yz, zx, xy)."""
    m = np.zeros((6, 6))
    pairs = ((1, 2), (2, 0), (0, 1))
    for i in range(3):
        for j in range(3):
            m[i, j] = a[i, j] ** 2
        for k, (p, q) in enumerate(pairs):
            m[i, 3 + k] = 2 * a[i, p] * a[i, q]
            m[3 + k, i] = a[p, i] * a[q, i]
    for k, (p, q) in enumerate(pairs):
        for c, (r, s) in enumerate(pairs):
            m[3 + k, 3 + c] = a[p, r] * a[q, s] + a[p, s] * a[q, r]
    return m


def calculix_aniso_constants(c: np.ndarray) -> tuple[float, ...]:
    """The 21 constants of CalculiX's ``*ELASTIC, TYPE=ANISO`` from a 6 x 6 Voigt stiffness
    (MPa), in its order D1111, D1122, D2222, D1133, D2233, D3333, D1112, D2212, D3312, D1212,
    D1113, D2213, D3313, D1213, D1313, D1123, D2223, D3323, D1223, D1323, D2323 (CalculiX
    User's Manual, ``*ELASTIC``). Voigt index of each pair: 11 -> 0, 22 -> 1, 33 -> 2, 23 -> 3,
    13 -> 4, 12 -> 5."""
    v = {"11": 0, "22": 1, "33": 2, "23": 3, "13": 4, "12": 5}
    order = ("1111", "1122", "2222", "1133", "2233", "3333", "1112", "2212", "3312", "1212",
             "1113", "2213", "3313", "1213", "1313", "1123", "2223", "3323", "1223", "1323",
             "2323")
    return tuple(float(c[v[k[:2]], v[k[2:]]]) for k in order)


#: Single-crystal silicon (MPa): Hopcroft, Nix and Kenny 2010, Table I (Hall 1967).
SILICON = CubicElasticity(165.7e3, 63.9e3, 79.6e3,
                          "Hopcroft, Nix, Kenny, J. Microelectromech. Syst. 19(2), 2010, "
                          "Table I (Hall 1967)")
#: p-type silicon at 7.8 ohm cm (1/Pa x 1e-11): Smith 1954, Table I.
SILICON_P_TYPE = PiezoCoefficients(6.6, -1.1, 138.1, 7.8,
                                   "Smith, Phys. Rev. 94(1), 1954, Table I")
#: n-type silicon at 11.7 ohm cm (1/Pa x 1e-11): Smith 1954, Table I.
SILICON_N_TYPE = PiezoCoefficients(-102.2, 53.4, -13.6, 11.7,
                                   "Smith, Phys. Rev. 94(1), 1954, Table I")
#: Directions on a (100) wafer in the cube axes: the usual flat's <110> and the <100>
#: 45 degrees from it, with the wafer's normal [001].
WAFER_110 = (1.0, 1.0, 0.0)
WAFER_100 = (1.0, 0.0, 0.0)
WAFER_NORMAL = (0.0, 0.0, 1.0)


def in_plane_direction(angle_from_110_deg: float) -> np.ndarray:
    """A direction in a (100) wafer's plane, ``angle_from_110_deg`` from [110] towards
    [-110] (degrees), in the cube axes (unit vector)."""
    a = math.radians(angle_from_110_deg)
    base, across = unit(WAFER_110), unit((-1.0, 1.0, 0.0))
    return math.cos(a) * base + math.sin(a) * across
