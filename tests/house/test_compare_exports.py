"""scripts/compare_exports.py, the byte-identity check of two export folders:
every file by sha256, the manifest without the fields that name the software."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "compare_exports.py"
spec = importlib.util.spec_from_file_location("compare_exports", SCRIPT)
compare_exports = importlib.util.module_from_spec(spec)
spec.loader.exec_module(compare_exports)


def _folder(root: Path, version: str, part_bytes: bytes = b"solid") -> Path:
    (root / "step").mkdir(parents=True)
    (root / "step" / "a.step").write_bytes(part_bytes)
    man = {"design": {"name": "d"}, "tactcad_version": version, "cad_stack": {"ocp": version},
           "files": [{"path": "step/a.step"}]}
    (root / "manifest.json").write_text(json.dumps(man))
    return root


def test_versions_aside_identical_exports_compare_equal(tmp_path):
    a = _folder(tmp_path / "a", "1.0")
    b = _folder(tmp_path / "b", "2.0")
    assert compare_exports.compare(a, b, set()) == []
    assert compare_exports.main([str(a), str(b)]) == 0


def test_a_changed_added_or_removed_file_is_named(tmp_path, capsys):
    a = _folder(tmp_path / "a", "1.0")
    b = _folder(tmp_path / "b", "1.0", b"other solid")
    (b / "new.dxf").write_text("x")
    (a / "gone.svg").write_text("y")
    assert compare_exports.compare(a, b, set()) == [
        "removed  gone.svg", "added    new.dxf", "changed  step/a.step"]
    assert compare_exports.main([str(a), str(b)]) == 1
    assert "3 differences" in capsys.readouterr().out
    assert compare_exports.compare(a, b, {"new.dxf", "gone.svg", "step/a.step"}) == []


def test_a_manifest_field_of_the_design_counts(tmp_path):
    a = _folder(tmp_path / "a", "1.0")
    b = _folder(tmp_path / "b", "1.0")
    man = json.loads((b / "manifest.json").read_text())
    man["design"]["name"] = "e"
    (b / "manifest.json").write_text(json.dumps(man))
    assert compare_exports.compare(a, b, set()) == ["changed  manifest.json (fields: design)"]
