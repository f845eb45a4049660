# Runs inside FreeCAD (``freecadcmd``), not in tactcad's Python: it imports
# nothing from tactcad. Input and output come from the environment:
#   TACTCAD_FC_IN   JSON list of jobs: {name, out, root_matrix, parts: [{name,
#                   brep, color}], groups: [{name, instances: [{name, part,
#                   matrix}]}]}; matrices row-major 4 x 4, mm
#   TACTCAD_FC_OUT  JSON file to write: {freecad_version, gui, files: {name:
#                   {objects, bbox_mm} or {error}}}
# or, with TACTCAD_FC_SERVE set, one request a line on stdin, {"in_file": JSON
# file of the jobs, "out": file, "id": n}, each answered by the line
# "tactcad-fc-done <n>" written to file descriptor 1 once its file is written (one
# FreeCAD process for many runs).
# See tactcad/export/freecad_review.py for the document layout.
import json
import os
import re
import sys
import traceback

import FreeCAD
import FreeCADGui

try:  # off screen (QT_QPA_PLATFORM=offscreen): view providers keep the colours
    FreeCADGui.showMainWindow()
    GUI = True
except Exception:
    FreeCADGui.setupWithoutGUI()
    GUI = False
import Part  # noqa: E402

# Group, part and instance may share a name (group "column", instance "column").
DOCUMENT_PREFS = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Document")
DOCUMENT_PREFS.SetBool("DuplicateLabels", True)
DOCUMENT_PREFS.SetBool("CreateBackupFiles", False)  # no <name>.FCStd1 beside the file


def object_name(prefix, name):
    """A FreeCAD object name (letters, digits, underscores); the label keeps the real name."""
    return prefix + re.sub(r"\W", "_", name)


def placement(rows):
    m = FreeCAD.Matrix(*[v for row in rows for v in row])
    return FreeCAD.Placement(m)


def build(job):
    # hidden: no 3D view, whose teardown crashes without an OpenGL context
    doc = FreeCAD.newDocument(object_name("review_", job["name"]), hidden=True)
    doc.Label = job["name"]
    library = doc.addObject("App::DocumentObjectGroup", "parts")
    library.Label = "parts"
    features = {}
    for p in job["parts"]:
        shape = Part.Shape()
        shape.read(p["brep"])
        f = doc.addObject("Part::Feature", object_name("part_", p["name"]))
        f.Label = p["name"]
        f.Shape = shape
        f.Visibility = False  # shown through the links only
        library.addObject(f)
        if GUI:
            f.ViewObject.ShapeColor = tuple(p["color"])
        features[p["name"]] = f
    root = doc.addObject("App::Part", object_name("scene_", job["name"]))
    root.Label = job["name"]
    root.Placement = placement(job["root_matrix"])  # Z up
    for g in job["groups"]:
        group = doc.addObject("App::Part", object_name("group_", g["name"]))
        group.Label = g["name"]
        root.addObject(group)
        for inst in g["instances"]:
            link = doc.addObject("App::Link", object_name("", inst["name"]))
            link.Label = inst["name"]
            link.LinkedObject = features[inst["part"]]
            link.Placement = placement(inst["matrix"])
            group.addObject(link)
    doc.recompute()
    doc.saveAs(job["out"])
    n = len(doc.Objects)
    box = Part.getShape(root).BoundBox  # placed, Z up: what the saved camera fits
    FreeCAD.closeDocument(doc.Name)
    return {"objects": n, "bbox_mm": [box.XMin, box.YMin, box.ZMin, box.XMax, box.YMax, box.ZMax]}


def write_results(jobs, out):
    results = {"freecad_version": FreeCAD.Version()[:3], "gui": GUI, "files": {}}
    for job in jobs:
        try:
            results["files"][job["name"]] = build(job)
        except Exception:
            results["files"][job["name"]] = {"error": traceback.format_exc()}
    with open(out, "w") as fh:
        json.dump(results, fh, indent=1, sort_keys=True)


def done_line(number):
    """The answer to request ``number``: on a line of its own (a newline first, as
    FreeCAD's own output may end mid-line), as bytes for file descriptor 1."""
    return ("\ntactcad-fc-done %d\n" % number).encode()


def serve():
    for line in sys.stdin:
        request = json.loads(line)
        with open(request["in_file"]) as fh:
            jobs = json.load(fh)
        write_results(jobs, request["out"])
        # Written to the pipe itself: once the main window is shown, sys.stdout is
        # FreeCAD's console, which prints through C's stdout, block-buffered on a pipe
        # (unless PYTHONUNBUFFERED is set), and its flush() leaves that buffer as it is.
        os.write(1, done_line(request["id"]))


if os.environ.get("TACTCAD_FC_SERVE"):
    serve()
else:
    write_results(json.loads(os.environ["TACTCAD_FC_IN"]), os.environ["TACTCAD_FC_OUT"])
