"""A die's manifest, review page data and diff name its two rows as its other commands do
(row 1 reference, row 2 measuring) and key each row's force ``rated_force_N``: a measuring
row carries less than the die's full-scale force, so the old "element 2 full_scale_force_N"
said a number that was neither."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import tactcad
from conftest import DIE_EXAMPLE as EXAMPLE


def _rows_of(plan) -> list[dict]:
    from tactcad.products.silicon_die.export.die_review import beam_elements
    from tactcad.products.silicon_die.studies.die_reports import (stiffness_report,
                                                                  strength_report)

    return beam_elements(strength_report(plan)[0], stiffness_report(plan)[0])


def test_each_row_is_named_with_its_role_and_its_own_rated_force():
    plan = tactcad.load(EXAMPLE).plan
    rows = _rows_of(plan)
    beams = plan.beams[:: plan.columns]
    assert [(r["row"], r["role"]) for r in rows] == [(b.row, b.role) for b in beams]
    assert [r["role"] for r in rows] == ["reference", "measuring"]
    for r, beam in zip(rows, beams):
        assert r["rated_force_N"] == pytest.approx(plan.rated_force_N(beam), rel=1e-12)
        assert r["stress_MPa_at_rated_force"] == pytest.approx(
            plan.root_peak_stress_MPa_at_rated_force(beam), rel=1e-12)
        # no field says "element" or "full scale" of a row's own figures
        assert not {"element", "full_scale_force_N", "stress_MPa_at_full_scale"} & set(r)
    # the measuring row carries less than the die's full scale: the names matter
    assert rows[1]["rated_force_N"] < plan.full_scale_force_N


def _manifest(folder: Path, plan) -> Path:
    folder.mkdir()
    man = {"files": [], "die": plan.as_json(), "rows": _rows_of(plan)}
    (folder / "manifest.json").write_text(json.dumps(man), encoding="utf-8")
    return folder


def test_the_diff_names_a_dies_rows_and_their_rated_force(tmp_path):
    from tactcad.export.manifest_diff import compare

    old = tactcad.load(EXAMPLE).plan
    new = tactcad.load(EXAMPLE, set={"die.full_scale_force_N": 0.007}).plan
    d = compare(_manifest(tmp_path / "old", old), _manifest(tmp_path / "new", new))
    assert [(r["row"], r["role"]) for r in d.rows] == [(1, "reference"), (2, "measuring")]
    assert d.elements == [] and d.as_json()["rows"] == d.rows
    measuring = d.rows[1]["changes"]
    beam = new.beams[new.columns]
    assert measuring["rated_force_N"]["after"] == pytest.approx(new.rated_force_N(beam))
    lines = d.lines()
    row2 = next(line for line in lines if line.startswith("row 2 (measuring)"))
    assert "rated_force_N" in row2 and " N," in row2 and "stress_MPa_at_rated_force" in row2
    assert not any(line.startswith("element") for line in lines)
    assert "full_scale_force_N" not in " ".join(line for line in lines
                                                if line.startswith("row"))


def test_the_review_data_has_the_rows_and_the_dies_full_scale_force():
    from tactcad.products.silicon_die.export.die_review import (design_head,
                                                                review_contents_of_die)

    plan = tactcad.load(EXAMPLE).plan
    rows = _rows_of(plan)
    contents = review_contents_of_die(
        design_head(plan.name, None), [], ("drawings/die.svg", "<svg xmlns='"
                                           "http://www.w3.org/2000/svg'/>"),
        b"", "part,quantity\ndie,1\n", rows, {}, None,
        full_scale_force_N=plan.full_scale_force_N)
    assert [(r["row"], r["role"]) for r in contents.data["elements"]] == [
        (1, "reference"), (2, "measuring")]
    assert contents.data["full_scale_force_N"] == plan.full_scale_force_N
    # the page labels the row's force as the row's, and shows the die's full scale apart
    js = (Path(tactcad.__file__).parent / "data" / "review_page.js").read_text(encoding="utf-8")
    table = js[js.index("function showTables"):js.index("function showData")]
    assert "rated_force_N: 'rated force of its row (N)'" in table
    assert "DATA.full_scale_force_N" in table
    for key in ("'row'", "'role'", "'rated_force_N'", "'stress_MPa_at_rated_force'"):
        assert key in table[:table.index("const labels")]
