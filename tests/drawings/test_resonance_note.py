"""The element drawing's first-natural-frequency note binds only where the
design states ``requirements.min_first_resonance_Hz``."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

from tactcad.design.array_plan import plan_from_dict, read_toml, with_overrides
from tactcad.drawings.design_notes import resonance_note
from tactcad.drawings.part_sets import PEN
from tactcad.partlib.array import element
from tactcad.studies.resonance import first_frequencies

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def example(**overrides):
    return plan_from_dict(with_overrides(read_toml(EXAMPLE, "design"), overrides), str(EXAMPLE))


def _notes(plan, part):
    from tactcad.catalogue.array_catalogue import array_parts

    spec = array_parts(plan, ("element",))[part]
    return element.notes(SimpleNamespace(plan=plan, spec=spec), PEN)


def test_the_note_appears_only_with_a_stated_minimum():
    plan = example()
    low = first_frequencies(plan, "closed-form")[0]
    assert resonance_note(plan, low["part"]) is None
    assert not any("natural frequency" in n for n in _notes(plan, low["part"]))
    strict = example(**{"requirements.min_first_resonance_Hz": 2 * low["first_Hz"]})
    note = resonance_note(strict, low["part"])
    assert f"{low['first_Hz']:.4g} Hz" in note and "NOT met" in note
    assert note in _notes(strict, low["part"])
    loose = example(**{"requirements.min_first_resonance_Hz": 0.5 * low["first_Hz"]})
    assert "NOT met" not in resonance_note(loose, low["part"])
