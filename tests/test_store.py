"""The content key of a spec is the constructor's view of it: moving a field
into a keyword-only base class (as the drilled plates and the resolved design
tables do) keeps every key, so a refactor re-uses the cache and the part
hashes printed on drawings."""

from dataclasses import dataclass, field

from tactcad.design.array import ClampPlateGeometry, Hole, SpacerGeometry
from tactcad.store import stable_repr


def _flat():
    @dataclass(frozen=True)
    class Plate:
        length_mm: float
        thickness_mm: float
        holes: tuple

    return Plate


def _based():
    @dataclass(frozen=True)
    class Base:
        holes: tuple = field(kw_only=True)

    @dataclass(frozen=True)
    class Plate(Base):
        length_mm: float
        thickness_mm: float

    return Plate


def test_keyword_only_base_field_keeps_the_key():
    holes = (Hole(1.0, 2.0, 3.4),)
    flat, based = _flat()(5.0, 2.0, holes), _based()(5.0, 2.0, holes=holes)
    assert stable_repr(flat) == stable_repr(based)
    assert stable_repr(_based()(5.0, 2.5, holes=holes)) != stable_repr(based)


def test_plates_key_in_constructor_order():
    spacer = SpacerGeometry(7.0, 8.0, 2.0, holes=())
    assert stable_repr(spacer).startswith("SpacerGeometry(length_mm=7.0, height_mm=8.0, "
                                          "thickness_mm=2.0, holes=")
    clamp = ClampPlateGeometry(10.0, 6.0, 8.0, 3.0, 2.0, 1.0, holes=())
    assert stable_repr(clamp).endswith("window_corner_radius_mm=1.0, holes=[])")
