"""One rule for every product's export folder: an export replaces an earlier export of the
same design and refuses a folder holding another design's export (an array's export no
longer deletes a die's; a die's is not mixed into an array's)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import run_cli
from tactcad.errors import DesignError
from tactcad.export.export_owner import export_owner, refuse_another_designs_export

DIE_EXAMPLE = (Path(__file__).resolve().parents[2] / "hardware" / "grasper_jaw_5mm_mems"
               / "grasper_jaw_5mm_mems.toml")


def _fake_export(folder: Path, design: str, product: str | None) -> Path:
    """A folder holding an export's manifest (and one file it lists) of ``design``."""
    folder.mkdir()
    (folder / "a.txt").write_text("a")
    manifest = {"design": {"name": design}, "files": [{"path": "a.txt", "sha256": ""}]}
    if product is not None:
        manifest["product"] = product
    (folder / "manifest.json").write_text(json.dumps(manifest))
    return folder


def test_the_owner_is_read_from_the_manifest_an_arrays_naming_no_product(tmp_path):
    assert export_owner(_fake_export(tmp_path / "d", "d", "silicon-die")) == ("silicon-die", "d")
    assert export_owner(_fake_export(tmp_path / "c", "c", None)) == ("metal-array", "c")
    assert export_owner(tmp_path) is None


def test_the_same_designs_export_or_an_empty_folder_is_taken_another_refused(tmp_path):
    die = _fake_export(tmp_path / "d", "d", "silicon-die")
    refuse_another_designs_export(die, "silicon-die", "d")  # its own earlier export
    refuse_another_designs_export(tmp_path / "new", "metal-array", "c")
    (tmp_path / "empty").mkdir()
    refuse_another_designs_export(tmp_path / "empty", "metal-array", "c")
    for product, name in (("metal-array", "d"), ("silicon-die", "e")):
        with pytest.raises(DesignError, match="holds the export of the silicon-die d") as exc:
            refuse_another_designs_export(die, product, name)
        assert exc.value.field == "--out"
    (tmp_path / "loose").mkdir()
    (tmp_path / "loose" / "notes.txt").write_text("mine")
    with pytest.raises(DesignError, match="no manifest.json"):
        refuse_another_designs_export(tmp_path / "loose", "silicon-die", "d")


def test_an_arrays_export_refuses_a_dies_export_folder_and_keeps_its_files(tmp_path):
    die = _fake_export(tmp_path / "exports", "grasper_jaw_5mm_mems", "silicon-die")
    r = run_cli("export", "--out", "exports", "--no-cache", cwd=tmp_path)
    assert r.returncode == 2 and "--out" in r.stderr and "silicon-die" in r.stderr, r.stderr
    assert "Traceback" not in r.stderr
    assert sorted(p.name for p in die.iterdir()) == ["a.txt", "manifest.json"]


def test_a_dies_export_refuses_an_arrays_export_folder(tmp_path):
    (tmp_path / DIE_EXAMPLE.name).write_bytes(DIE_EXAMPLE.read_bytes())
    array = _fake_export(tmp_path / "exports", "macro_array", None)
    r = run_cli("export", "--out", "exports", cwd=tmp_path)
    assert r.returncode == 2 and "metal-array macro_array" in r.stderr, r.stderr
    assert sorted(p.name for p in array.iterdir()) == ["a.txt", "manifest.json"]


def test_check_refuses_another_designs_export_before_saying_it_exports_there(tmp_path,
                                                                            capsys):
    # check's help said such a folder "is exported there first"; it printed "exporting to
    # ... first" and then failed with export's refusal: it refuses at once, as export does
    (tmp_path / DIE_EXAMPLE.name).write_bytes(DIE_EXAMPLE.read_bytes())
    _fake_export(tmp_path / "comb", "comb10", None)
    (tmp_path / "arr").mkdir()
    array = _fake_export(tmp_path / "arr" / "exports", "grasper_jaw_5mm_mems", "silicon-die")
    for cwd, out in ((tmp_path, "comb"), (tmp_path / "arr", "exports")):
        r = run_cli("check", "--out", out, cwd=cwd)
        assert r.returncode == 2 and "holds the export of the" in r.stderr, r.stderr
        assert "exporting to" not in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert sorted(p.name for p in array.iterdir()) == ["a.txt", "manifest.json"]
    from tactcad.cli import main

    with pytest.raises(SystemExit):
        main(["check", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "the export of a design of another name (or product), or files no export wrote, " \
           "is refused" in text
