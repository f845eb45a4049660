"""A die's design file as an array's: ``tactcad design`` records after each reason under
``[assumptions]`` the value it was written for, and after a hand edit of that value the
die's outputs (its manifest and review page, ``tactcad die``'s and ``verify``'s text) show
the reason as no longer applying; an older die file reads as it always did. The die's
next steps offer no ``tactcad watch`` (it serves the metal designs)."""

from __future__ import annotations

import json
from pathlib import Path

import tomllib

from tactcad.commands.die import stale_notes
from tactcad.products.silicon_die.design.die_file import (die_assumptions, die_file_text,
                                                          load_die_design)
from tactcad.products.silicon_die.export.die_review import assumptions_section

HARDWARE = Path(__file__).resolve().parents[2] / "hardware"
DIE = HARDWARE / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml"
STALE = "(written for 5; the file now states 7: the reason no longer applies)"


def _written(tmp_path: Path) -> Path:
    """A die file as ``tactcad design`` writes it, 5 columns."""
    text = die_file_text("5", 10.0, (0.5, 5.0), 0.0085, 5, 1000.0, "d5", "tactcad design",
                         {"die.columns": "5 units along the die (the default).",
                          "die.kobj_range_N_per_mm": "The range asked (--kobj-range)."})
    path = tmp_path / "d5.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_design_records_the_value_each_reason_is_written_for(tmp_path):
    why = tomllib.loads(_written(tmp_path).read_text(encoding="utf-8"))["assumptions"]
    assert why == {"die.columns": "5 units along the die (the default). [written for 5]",
                   "die.kobj_range_N_per_mm": "The range asked (--kobj-range). "
                                              "[written for [0.5, 5]]"}
    d = load_die_design(_written(tmp_path))
    assert d.stale == {} and dict(d.assumptions) == {  # unedited: as the words were
        "die.columns": "5 units along the die (the default).",
        "die.kobj_range_N_per_mm": "The range asked (--kobj-range)."}


def test_a_hand_edited_value_shows_its_reason_stale(tmp_path):
    path = _written(tmp_path)
    path.write_text(path.read_text(encoding="utf-8").replace("columns = 5", "columns = 7"),
                    encoding="utf-8")
    d = load_die_design(path)
    stale = f"5 units along the die (the default). {STALE}"
    assert d.stale == {"die.columns": stale}
    assert dict(d.assumptions)["die.columns"] == stale
    assert assumptions_section(d.assumptions)["assumptions"][0] == {
        "field": "die.columns", "reason": stale}
    assert stale_notes(d.stale) == [f"note: [assumptions] die.columns: {stale}"]
    # a --set of the value is the same edit
    assert load_die_design(_written(tmp_path), {"die.columns": 7}).stale == d.stale


def test_an_older_die_file_reads_as_before():
    d = load_die_design(DIE, {"die.columns": 4})
    written = tomllib.loads(DIE.read_text(encoding="utf-8"))["assumptions"]
    assert d.stale == {} and dict(d.assumptions) == {k: v.strip() for k, v in written.items()}
    assert die_assumptions({"die": {}}) == () and assumptions_section(()) == {}


def test_a_designed_die_offers_no_watch_and_an_edit_shows_in_verify(tmp_path):
    from conftest import run_cli

    folder = tmp_path / "d5"
    r = run_cli("design", "--jaw", "5", "--kr-over-km", "10", "--kobj-range", "0.5", "5",
                "--full-scale-force", "0.0085", "--out", str(folder), "--json")
    assert r.returncode == 0, r.stderr
    assert "watch" not in json.loads(r.stdout)["next"]
    readme = (folder / "README.md").read_text(encoding="utf-8")
    assert "tactcad watch --design" not in readme and "not a die" in readme
    design = folder / "d5.toml"
    design.write_text(design.read_text(encoding="utf-8").replace("columns = 5", "columns = 7"),
                      encoding="utf-8")
    v = run_cli("verify", "--design", str(design))
    assert v.returncode == 0, v.stderr
    assert f"note: [assumptions] die.columns: 5 units along the die (the default). {STALE}" \
        in v.stdout


def test_the_die_commands_json_lists_the_reasons_that_no_longer_apply(tmp_path):
    from conftest import run_cli

    path = _written(tmp_path)
    path.write_text(path.read_text(encoding="utf-8").replace("columns = 5", "columns = 7"),
                    encoding="utf-8")
    r = run_cli("die", "--design", str(path), "--out", str(tmp_path / "die"), "--json")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["stale_reasons"] == [
        {"field": "die.columns", "reason": f"5 units along the die (the default). {STALE}"}]
    fresh = run_cli("die", "--design", str(_written(tmp_path)), "--out", str(tmp_path / "die"),
                    "--json")
    assert fresh.returncode == 0, fresh.stderr
    assert json.loads(fresh.stdout)["stale_reasons"] == []
