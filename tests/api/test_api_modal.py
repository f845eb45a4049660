"""``Element.modes``: the modal ladder from the Python API."""

from __future__ import annotations

import pytest

import tactcad


def test_element_modes_match_the_command_and_refuse_an_unknown_level():
    from tactcad.mechanics.modal_ladder import UnknownModalModelError

    project = tactcad.load()
    short, long_ = project.element(1), project.element(4)  # 4 and 8 mm arms
    r = short.modes()
    assert r.element == 1 and r.model == "closed-form" and r.modes[0].family == "in-plane"
    assert r.first_Hz > long_.modes().first_Hz > 0
    assert r.as_json()["first_Hz"] == r.first_Hz
    with pytest.raises(UnknownModalModelError):
        short.modes("beam")
