"""Catalogue data of standard parts (mm): ISO metric bolts and nuts, ISO 15
deep groove ball bearings, and the stock-length rule shared by every bolt.

Sources: ISO 273 (clearance holes, medium series), ISO 4762 (socket head cap
screws: head diameter d_k, head height k, stock lengths), ISO 4032 (hex nuts:
width across flats s, height m), ISO 15 (bearing boundary dimensions, series 02);
below M1.6, where ISO 4762 and ISO 4032 end, DIN 912 (socket head cap screws
M1.2: d_k 2.3, k 1.2, s 0.9) and DIN 934 (hex nuts M1.2: s 3.0, m 1.0); ISO 8734
(hardened dowel pins, tolerance m6: nominal diameters and stock lengths).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: Stock lengths are compared with this tolerance (mm) so that a grip computed
#: as 27.999999999 still takes the 28 mm bolt.
LENGTH_TOLERANCE_MM = 1e-9


#: Hexagon socket size s (mm) of ISO 4762 socket head cap screws, by thread size.
ISO_4762_SOCKET_MM = {"M1.2": 0.9, "M1.6": 1.5, "M2": 1.5, "M2.5": 2.0, "M3": 2.5, "M4": 3.0, "M5": 4.0}


@dataclass(frozen=True)
class BoltSpec:
    """ISO metric bolt + nut envelope data (mm)."""

    size: str
    nominal_diameter_mm: float
    clearance_hole_mm: float  # ISO 273 medium series
    thread_pitch_mm: float
    head_diameter_mm: float  # ISO 4762 d_k
    head_height_mm: float  # ISO 4762 k
    nut_width_across_flats_mm: float  # ISO 4032 s
    nut_height_mm: float  # ISO 4032 m
    catalogue_lengths_mm: tuple[float, ...]  # ISO 4762 / DIN 912 stock lengths

    @property
    def socket_across_flats_mm(self) -> float:
        """Hexagon socket size s of ISO 4762 (the hex key that drives it); a
        size outside that table: 0.75 d, the ratio of the small sizes."""
        return ISO_4762_SOCKET_MM.get(self.size, 0.75 * self.nominal_diameter_mm)

    @property
    def nut_across_corners_mm(self) -> float:
        """Width across the corners of the ISO 4032 nut: s * 2 / sqrt(3)."""
        return self.nut_width_across_flats_mm * 2.0 / math.sqrt(3.0)

    @property
    def safe_name(self) -> str:
        """Size for part and file names: ``M2.5`` -> ``M2p5`` (no dot, which STEP
        readers and file names treat differently)."""
        return self.size.replace(".", "p")


#: Miniature socket head cap screws below the clamp bolts' table (DIN 912, nut
#: DIN 934; ISO 273 medium clearance hole 1.4 mm), for constructions small
#: enough for a grasper's jaw (:data:`MINIATURE_SCREWS`).
M1P2 = BoltSpec("M1.2", 1.2, 1.4, 0.25, 2.3, 1.2, 3.0, 1.0, (3, 4, 5, 6, 8, 10))

#: The array's clamp bolts.
BOLTS: dict[str, BoltSpec] = {
    "M1.6": BoltSpec("M1.6", 1.6, 1.8, 0.35, 3.0, 1.6, 3.2, 1.3,
                     (3, 4, 5, 6, 8, 10, 12, 16, 20)),
    "M2": BoltSpec("M2", 2.0, 2.4, 0.4, 3.8, 2.0, 4.0, 1.6,
                   (4, 5, 6, 8, 10, 12, 16, 20, 25, 30)),
    "M2.5": BoltSpec("M2.5", 2.5, 2.9, 0.45, 4.5, 2.5, 5.0, 2.0,
                     (5, 6, 8, 10, 12, 16, 20, 25, 30)),
    "M3": BoltSpec("M3", 3.0, 3.4, 0.5, 5.5, 3.0, 5.5, 2.4,
                   (5, 6, 8, 10, 12, 16, 20, 25, 30, 35, 40)),
}

#: Screws of the miniature constructions (the comb's rows): M1.2 (DIN 912) and
#: the clamp table's M1.6 (ISO 4762).
MINIATURE_SCREWS: dict[str, BoltSpec] = {"M1.2": M1P2, "M1.6": BOLTS["M1.6"]}

#: ISO 8734 hardened dowel pins (m6; the hole is reamed to the nominal
#: diameter, H7): nominal diameter (mm) -> stock lengths (mm).
DOWEL_PINS: dict[float, tuple[float, ...]] = {
    1.0: (3, 4, 5, 6, 8, 10),
    1.5: (4, 5, 6, 8, 10, 12),
    2.0: (5, 6, 8, 10, 12, 16),
}


def shortest_dowel_length(diameter_mm: float, needed_mm: float) -> float | None:
    """The shortest ISO 8734 stock length of a dowel pin >= ``needed_mm`` (mm),
    or None when even the longest is too short."""
    fits = [n for n in DOWEL_PINS[diameter_mm] if n >= needed_mm - LENGTH_TOLERANCE_MM]
    return float(min(fits)) if fits else None


#: The rigs' screws: the array's sizes and M4 for the wheel axles.
RIG_BOLTS: dict[str, BoltSpec] = {
    **BOLTS,
    "M4": BoltSpec("M4", 4.0, 4.5, 0.7, 7.0, 4.0, 7.0, 3.2,
                   (6, 8, 10, 12, 16, 20, 25, 30, 35, 40)),
}


@dataclass(frozen=True)
class BearingSpec:
    """Deep groove ball bearing, ISO 15 boundary dimensions (mm)."""

    designation: str
    bore_mm: float  # d
    outer_diameter_mm: float  # D
    width_mm: float  # B


# ISO 15, dimension series 02 (62xx) for the small sizes used as cart wheels.
BEARINGS: dict[str, BearingSpec] = {
    "623ZZ": BearingSpec("623ZZ", 3.0, 10.0, 4.0),
    "624ZZ": BearingSpec("624ZZ", 4.0, 13.0, 5.0),
    "625ZZ": BearingSpec("625ZZ", 5.0, 16.0, 5.0),
    "626ZZ": BearingSpec("626ZZ", 6.0, 19.0, 6.0),
}


def shortest_stock_length(bolt: BoltSpec, needed_mm: float) -> float | None:
    """Shortest ISO 4762 stock length (mm) of ``bolt`` >= ``needed_mm``, or
    ``None`` when even the longest stock bolt is too short."""
    lengths = [L for L in bolt.catalogue_lengths_mm if L >= needed_mm - LENGTH_TOLERANCE_MM]
    return float(lengths[0]) if lengths else None


#: Nut factor K of a dry steel thread (Shigley, Mechanical Engineering Design, ch. 8).
NUT_FACTOR = 0.2
#: Proof stress of property class 8.8 below M16 (MPa, ISO 898-1).
PROOF_STRESS_MPA = 580.0


def tightening_torque_Nm(d_mm: float, pitch_mm: float) -> float:
    """Tightening torque (N m) of a class 8.8 metric screw of nominal diameter
    ``d_mm`` and pitch ``pitch_mm``: T = K F d with the nut factor K = 0.2 and
    the preload F = 0.75 x proof stress x stress area A_s = pi/4 (d - 0.9382 P)^2
    (Shigley ch. 8; ISO 898-1)."""
    stress_area = math.pi / 4 * (d_mm - 0.9382 * pitch_mm) ** 2
    preload_N = 0.75 * PROOF_STRESS_MPA * stress_area
    return NUT_FACTOR * preload_N * d_mm / 1000.0
