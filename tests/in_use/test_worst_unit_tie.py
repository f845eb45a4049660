"""``design`` and ``verify`` name the same unit for the same worst K_obj bias: mirrored
units tie to round-off (+50.1 % at units 2/1 and 2/3), and one rule
(:func:`tactcad.in_use.tissue_coupling.worst_unit`) gives the tie to the first unit in the
array's order (design named unit 2/1, verify unit 2/3)."""

from __future__ import annotations

import pytest

from tactcad.in_use.tissue_coupling import worst_unit

#: Two mirrored units, the second's bias larger by round-off only.
TIED = [((1, 2), 0.501), ((3, 2), 0.501 + 3e-13)]


def test_a_tie_to_round_off_goes_to_the_first_unit():
    assert worst_unit(TIED, lambda u: u[1])[0] == (1, 2)
    assert worst_unit(TIED[::-1], lambda u: u[1])[0] == (3, 2)


def test_no_answer_is_worst_and_a_real_difference_decides():
    units = [((1, 2), 0.6), ((3, 2), None), ((4, 5), -0.7)]
    assert worst_unit(units, lambda u: u[1])[0] == (3, 2)
    assert worst_unit([units[0], units[2]], lambda u: u[1])[0] == (4, 5)
    assert worst_unit([((1, 2), float("inf")), units[2]], lambda u: u[1])[0] == (1, 2)
    with pytest.raises(ValueError):
        worst_unit([], lambda u: u[1])


def test_verify_names_the_tied_unit_as_design_does():
    from tactcad.commands.verify import tissue_text

    items = [{"unit": list(u), "bias_rel": b, "verdict": "fail"} for u, b in TIED]
    record = {"units": [1, 2], "tissue": "half-space", "target_rel": 0.0052,
              "eq3": {"items": items, "verdict": "fail"},
              "coupled": {"items": items, "verdict": "fail"}}
    said = tissue_text(record)
    assert "eq. 3 alone worst +50.1 % (unit 2/1)" in said
    assert "(unit 2/3)" not in said
