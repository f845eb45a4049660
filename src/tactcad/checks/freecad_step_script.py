# Runs inside FreeCAD (``freecadcmd``), not in tactcad's Python: it imports
# nothing from tactcad. Input and output paths come from the environment:
#   TACTCAD_FC_IN   JSON list of STEP files
#   TACTCAD_FC_OUT  JSON file to write: {path: {solids, volume_mm3, bbox_mm,
#                   labels, shape_read: {...}, seconds} or {error}}
# Each file is imported into a document the way a reviewer opens it
# (ImportGui.insert with merge off, instances as links) and, independently,
# read as a bare shape (Part.Shape.read).
import json
import os
import time
import traceback

import FreeCAD
import FreeCADGui
import Part

# Import.insert crashes FreeCAD 0.20 headless on assemblies (a colour hook
# without a GUI); ImportGui works once the GUI module is set up without a GUI.
FreeCADGui.setupWithoutGUI()
import ImportGui  # noqa: E402


def _bbox(shapes):
    bb = FreeCAD.BoundBox()
    for s in shapes:
        bb.add(s.BoundBox)
    return [bb.XMin, bb.YMin, bb.ZMin, bb.XMax, bb.YMax, bb.ZMax]


def review(path):
    t0 = time.time()
    name = "r%d" % (abs(hash(path)) % 10**8)
    doc = FreeCAD.newDocument(name)
    try:
        ImportGui.insert(path, doc.Name, merge=False, useLinkGroup=True)
        shaped = [o for o in doc.Objects if hasattr(o, "Shape")]
        roots = [o for o in shaped if not o.InList]
        parts = [o for o in doc.Objects if o.TypeId == "Part::Feature"]
        shapes = [o.Shape for o in roots]
        out = {
            "solids": sum(len(s.Solids) for s in shapes),
            "volume_mm3": sum(s.Volume for s in shapes),
            "bbox_mm": _bbox(shapes),
            "labels": sorted({o.Label for o in parts}),
            "roots": sorted(o.Label for o in roots),
            "objects": len(doc.Objects),
        }
    finally:
        FreeCAD.closeDocument(doc.Name)
    bare = Part.Shape()
    bare.read(path)
    out["shape_read"] = {"solids": len(bare.Solids), "volume_mm3": bare.Volume,
                         "bbox_mm": _bbox([bare])}
    out["seconds"] = time.time() - t0
    return out


def main():
    paths = json.loads(os.environ["TACTCAD_FC_IN"])
    results = {"freecad_version": FreeCAD.Version()[:3], "files": {}}
    t0 = time.time()
    for p in paths:
        try:
            results["files"][p] = review(p)
        except Exception:
            results["files"][p] = {"error": traceback.format_exc()}
    results["seconds"] = time.time() - t0
    with open(os.environ["TACTCAD_FC_OUT"], "w") as fh:
        json.dump(results, fh, indent=1, sort_keys=True)


main()
