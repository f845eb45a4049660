"""Single-crystal silicon read along a (100) wafer's directions: the moduli and the
piezoresistance coefficients against their published values, and the closed forms against
the rotated tensor (two independent computations of one quantity)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tactcad.vocabulary.crystal import (SILICON, SILICON_N_TYPE, SILICON_P_TYPE, WAFER_100,
                                        WAFER_110, WAFER_NORMAL, calculix_aniso_constants,
                                        in_plane_direction, unit)


@pytest.mark.parametrize("direction, modulus_GPa", [
    (WAFER_100, 130.0), (WAFER_110, 169.0), ((1.0, 1.0, 1.0), 188.0)])
def test_silicons_modulus_along_its_directions_is_hopcrofts(direction, modulus_GPa):
    # Hopcroft, Nix, Kenny 2010: 130 GPa along <100>, 169 along <110>, 188 along <111>
    assert SILICON.young_modulus_MPa(direction) / 1e3 == pytest.approx(modulus_GPa, abs=0.5)


def test_a_beam_along_110_on_a_100_wafer_has_hopcrofts_poisson_ratios_and_shear():
    s = np.linalg.inv(SILICON.in_frame(WAFER_110, (-1.0, 1.0, 0.0)))
    assert -s[0, 2] / s[0, 0] == pytest.approx(0.36, abs=0.005)  # into the wafer's normal
    assert 0.05 < -s[0, 1] / s[0, 0] < 0.07  # in the wafer's plane: about 0.06
    assert 1 / s[5, 5] == pytest.approx(50.9e3, rel=2e-3)  # in-plane shear, 45 deg off <100>
    assert 1 / s[4, 4] == pytest.approx(79.6e3, rel=1e-9)  # C44 about the normal's planes
    along_100 = np.linalg.inv(SILICON.in_frame(WAFER_100, (0.0, 1.0, 0.0)))
    assert -along_100[0, 1] / along_100[0, 0] == pytest.approx(0.28, abs=0.005)


@settings(max_examples=60, deadline=None)
@given(st.tuples(*[st.floats(-1.0, 1.0)] * 3).filter(lambda v: np.linalg.norm(v) > 0.1))
def test_nyes_closed_form_is_the_rotated_tensors_modulus(direction):
    x = unit(direction)
    y = unit(np.cross(x, (0.3, -0.7, 0.2)) if abs(x @ unit((0.3, -0.7, 0.2))) < 0.99
             else np.cross(x, (1.0, 0.0, 0.0)))
    rotated = 1.0 / np.linalg.inv(SILICON.in_frame(x, y))[0, 0]
    assert SILICON.young_modulus_MPa(x) == pytest.approx(rotated, rel=1e-10)


def test_the_in_plane_modulus_swings_between_110_and_100_every_45_degrees():
    e = [SILICON.young_modulus_MPa(in_plane_direction(a)) for a in (0.0, 45.0, 90.0, 22.5)]
    assert e[0] == pytest.approx(e[2]) and e[1] == pytest.approx(SILICON.young_modulus_MPa(WAFER_100))
    assert e[1] < e[3] < e[0]
    assert all(abs(in_plane_direction(a) @ unit(WAFER_NORMAL)) < 1e-12 for a in (10.0, 77.0))


def test_a_p_type_resistor_along_110_has_smiths_longitudinal_and_transverse_coefficients():
    # (pi11 + pi12 +- pi44) / 2 along <110> of a (100) wafer: 71.8 and -66.3 x 1e-11 1/Pa
    assert SILICON_P_TYPE.longitudinal(WAFER_110) == pytest.approx(71.8, abs=0.05)
    assert SILICON_P_TYPE.transverse(WAFER_110, (-1.0, 1.0, 0.0)) == pytest.approx(-66.3, abs=0.05)
    # along the cube axes the coefficients are the tensor's own
    assert SILICON_N_TYPE.longitudinal(WAFER_100) == pytest.approx(-102.2)
    assert SILICON_N_TYPE.transverse(WAFER_100, (0.0, 1.0, 0.0)) == pytest.approx(53.4)


def test_calculix_takes_the_rotated_tensor_as_21_symmetric_constants():
    c = SILICON.in_frame(WAFER_110, (-1.0, 1.0, 0.0))
    d = calculix_aniso_constants(c)
    assert len(d) == 21 and np.allclose(c, c.T)
    assert d[0] == pytest.approx(c[0, 0]) and d[9] == pytest.approx(c[5, 5])  # D1111, D1212
    assert d[20] == pytest.approx(c[3, 3])  # D2323
    # the cube axes' own: C11, C12, C11, C12, C12, C11 and no coupling of normal and shear
    cube = calculix_aniso_constants(SILICON.stiffness())
    assert cube[:6] == (165.7e3, 63.9e3, 165.7e3, 63.9e3, 63.9e3, 165.7e3)
    assert cube[6:9] == (0.0, 0.0, 0.0)


@pytest.mark.parametrize("bad", [(0.0, 0.0, 0.0), (math.nan, 1.0, 0.0)])
def test_a_zero_or_undefined_direction_is_refused_naming_it(bad):
    with pytest.raises(ValueError, match="direction"):
        SILICON.young_modulus_MPa(bad)
    with pytest.raises(ValueError, match="perpendicular"):
        SILICON.in_frame(WAFER_110, WAFER_110)
