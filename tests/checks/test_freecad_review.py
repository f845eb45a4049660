"""Design review in FreeCAD: every exported STEP file opened with
``freecadcmd`` matches its manifest record (solid count, part labels,
volume, bounding box).

FreeCAD is a system package (``freecad-python3``); the ``freecad`` fixture
(conftest.py) installs it when missing.
"""

from __future__ import annotations

import json
import shutil

from tactcad.checks.freecad_step import review_exports


def test_freecad_opens_every_step_as_the_manifest_says(freecad, exported):
    out, _ = exported
    rows, found = review_exports(out)
    man = json.loads((out / "manifest.json").read_text())
    steps = [f["path"] for f in man["files"] if f["path"].endswith(".step")]
    assert len(steps) >= 15  # 9 parts, the array and 5 scenes, all reviewed
    assert {r.subject for r in rows} == set(steps)
    bad = [r.line() for r in rows if not r.passed]
    assert not bad, "\n".join(bad)
    for check in ("freecad_solids", "freecad_labels", "freecad_volume", "freecad_bbox"):
        assert sum(r.check == check for r in rows) == len(steps)
    print(f"\nFreeCAD {'.'.join(found['freecad_version'])} reviewed {len(steps)} STEP files in "
          f"{found['wall_seconds']:.1f} s ({found['seconds']:.1f} s importing)")


def test_freecad_review_catches_a_wrong_record(freecad, exported, tmp_path):
    """The comparison is not vacuous: a manifest record off by one solid and
    a missing label fails."""
    out, _ = exported
    man = json.loads((out / "manifest.json").read_text())
    scene = next(f for f in man["files"] if f["path"] == "scenes/sample-stiffness-rig.step")
    (tmp_path / "scenes").mkdir()
    shutil.copy(out / scene["path"], tmp_path / scene["path"])
    wrong = dict(scene, solids=scene["solids"] + 1, labels=scene["labels"][1:])
    (tmp_path / "manifest.json").write_text(json.dumps({"files": [wrong]}))
    rows, _ = review_exports(tmp_path)
    failed = {r.check for r in rows if not r.passed}
    assert failed == {"freecad_solids", "freecad_labels", "freecad_shape_read"}
