"""tactcad: CAD-driven generator for spring-based tactile sensor arrays.

Data flows one way: design file (TOML) -> validated plan (:mod:`tactcad.design.array`)
-> geometry (:mod:`tactcad.parts`) -> exports and checks. Units are mm, N, MPa,
N/mm and s throughout.
"""

__version__ = "0.1.0"
