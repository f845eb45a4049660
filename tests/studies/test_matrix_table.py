"""verify's text table: each requirement's ``limit:`` rows under that requirement's own row,
and a grasp whose deciding element rests on its stop shows what is predicted, not ``none``."""
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TI = str(ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")
COMB = ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


def _row_names(table: str) -> list[str]:
    """The first cell of every body row of a Markdown table."""
    return [line.split("|")[1].strip() for line in table.splitlines()[2:]]


def test_the_limit_rows_follow_the_full_scale_force_not_the_last_requirement():
    from tactcad.api import load
    from tactcad.studies.verification import matrix_table, verification_matrix

    records = verification_matrix(load(TI).plan)
    names = _row_names(matrix_table(records))
    limits = [i for i, n in enumerate(names) if n.startswith("limit:")]
    first = names.index("full_scale_force_N")
    assert limits and limits == list(range(first + 1, first + 1 + len(limits)))
    assert names[-1] == records[-1]["requirement"] != "full_scale_force_N"


def test_a_grasp_decided_on_a_stop_shows_the_force_its_element_carries():
    from tactcad.design.array_plan import plan_from_dict, with_overrides
    from tactcad.studies.verification import (element_figures, matrix_table,
                                              max_grasp_force_record, requirements_of)
    from tactcad.vocabulary.schema import read_toml

    plan = plan_from_dict(with_overrides(read_toml(COMB, "design file"),
                                         {"requirements.max_grasp_force_N": 10.0}),
                          source=str(COMB), file=COMB.name)
    fig = element_figures(plan)
    r = max_grasp_force_record(plan, fig, requirements_of(plan, fig))
    w = next(it for it in r["elements"] if it["element"] == r["binding_element"])
    assert w["on_stop"] and r["predicted"] is None  # no grasp force predicted: on the stop
    row = next(line for line in matrix_table([r]).splitlines()
               if line.startswith("| max_grasp_force_N"))
    cells = [c.strip() for c in row.split("|")]
    assert cells[3] != "none" and cells[3].startswith("on its stop")
    assert f"element {w['element']} carries {w['element_force_N']:.4g} N" in cells[3]
    assert f"{w['overload_limit_N']:.4g} N" in cells[3]
