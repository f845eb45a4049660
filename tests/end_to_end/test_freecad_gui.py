"""A review file opened in the FreeCAD GUI (under Xvfb) shows the scene at once:
the file's saved camera is used and the first view is not empty."""

from __future__ import annotations

import json
import os
import shutil
import subprocess

import pytest

from tactcad.export.freecad_review import isometric_camera

MACRO = r'''
import json, os
import FreeCAD, FreeCADGui
res = {}
try:
    doc = FreeCAD.openDocument(os.environ["TACTCAD_FC_FILE"])
    FreeCADGui.updateGui()
    view = FreeCADGui.getDocument(doc.Name).activeView()
    cam = view.getCameraNode()
    res["camera"] = cam.getTypeId().getName().getString()
    res["position"] = list(cam.position.getValue().getValue())
    view.saveImage(os.environ["TACTCAD_FC_PNG"], 400, 300, "#ffffff")
except Exception:
    import traceback
    res["error"] = traceback.format_exc()
with open(os.environ["TACTCAD_FC_OUT"], "w") as fh:
    json.dump(res, fh)
os._exit(0)
'''


def test_camera_is_deterministic_and_refuses_a_broken_box():
    assert isometric_camera([0, 0, 0, 10, 20, 30]) == isometric_camera((0, 0, 0, 10, 20, 30.0))
    assert "OrthographicCamera" in isometric_camera([0, 0, 0, 10, 20, 30])
    for bad in ([0, 0, 0, -1, 1, 1], [0, 0, 0, float("nan"), 1, 1]):
        with pytest.raises(ValueError, match="not a finite box"):
            isometric_camera(bad)


@pytest.mark.slow
def test_review_file_opens_with_the_scene_in_view(exported, tmp_path):
    from PIL import Image

    gui, xvfb = shutil.which("freecad"), shutil.which("xvfb-run")
    if not (gui and xvfb):
        pytest.skip("the FreeCAD GUI (Debian freecad) and xvfb-run are needed")
    out, _ = exported
    fcstd = out / "review" / "calibration-rig.FCStd"
    if not fcstd.is_file():
        pytest.skip("no FreeCAD review files in this export (freecadcmd missing)")
    macro = tmp_path / "open_review.py"
    macro.write_text(MACRO)
    env = {**os.environ, "TACTCAD_FC_FILE": str(fcstd), "TACTCAD_FC_OUT": str(tmp_path / "r.json"),
           "TACTCAD_FC_PNG": str(tmp_path / "view.png"),
           # FreeCAD's start page embeds Chromium, which refuses root without this
           "QTWEBENGINE_DISABLE_SANDBOX": "1", "QTWEBENGINE_CHROMIUM_FLAGS": "--no-sandbox"}
    subprocess.run([xvfb, "-a", gui, str(macro)], env=env, timeout=300, capture_output=True)
    res = json.loads((tmp_path / "r.json").read_text())
    assert "error" not in res, res.get("error")
    assert res["camera"] == "OrthographicCamera"
    img = Image.open(tmp_path / "view.png").convert("L")
    hist = img.histogram()
    drawn = sum(hist[:240]) / (img.width * img.height)  # pixels darker than the white background
    assert drawn > 0.02, f"the saved view shows almost nothing ({drawn:.1%} drawn)"
    # the camera is the file's: FreeCAD's default view looks from +z at the origin
    assert res["position"][0] > 0 and res["position"][1] < 0 and res["position"][2] > 0
