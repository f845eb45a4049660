"""Variants of the shipped grasper comb for tests that need a layout it no longer has."""
from tactcad.design.array_plan import plan_from_dict, with_overrides
from pathlib import Path

from tactcad.vocabulary.schema import read_toml

COMB = "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml"

#: The comb paired along its rows: each row's first element its reference, the others
#: measuring against it (the tips of a unit then lie at different radii in a jaw).
ROW_PAIRED = {
    "array.pairing": "row",
    "arms.lengths_mm": [2.0, 3.0, 3.0, 3.0, 3.0, 3.0] * 2,
    "arms.reference_elements": [1, 7],
    "comb.web_thicknesses_mm": [0.15, 0.08, 0.08, 0.08, 0.08, 0.08] * 2,
    "comb.stop_gaps_mm": [0.02, 0.036, 0.036, 0.036, 0.036, 0.036] * 2,
}


def comb_data() -> dict:
    """The shipped comb's design tables."""
    return dict(read_toml(Path(COMB), "design file"))


def row_paired_comb():
    """The shipped comb's plan with its units paired along the rows (:data:`ROW_PAIRED`)."""
    return plan_from_dict(with_overrides(comb_data(), ROW_PAIRED), source=COMB, file=COMB)
