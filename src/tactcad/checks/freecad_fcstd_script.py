# Runs inside FreeCAD (``freecadcmd``), not in tactcad's Python: it imports
# nothing from tactcad. Opens each review file as a reviewer would and lists
# what it shows:
#   TACTCAD_FC_IN   JSON list of .FCStd files
#   TACTCAD_FC_OUT  JSON file to write: {freecad_version, files: {path:
#                   {label, roots, tree: {group: [instance labels]},
#                   group_bbox_mm: {group: [6 floats]}, solids, part_labels,
#                   linked: {instance: part}} or {error}}}
# Boxes are global (root placement applied): the file is Z up when the
# scene's up axis comes out as Z.
import json
import os
import traceback

import FreeCAD
import Part


def global_bbox(obj):
    shape = Part.getShape(obj)  # the object's own placement applied
    parent_placement = obj.getGlobalPlacement().multiply(obj.Placement.inverse())
    shape.Placement = parent_placement.multiply(shape.Placement)
    bb = shape.BoundBox
    return [bb.XMin, bb.YMin, bb.ZMin, bb.XMax, bb.YMax, bb.ZMax], len(shape.Solids)


def read(path):
    doc = FreeCAD.openDocument(path, hidden=True)
    try:
        roots = [o for o in doc.RootObjects]
        scene = [o for o in roots if o.TypeId == "App::Part"]
        out = {"label": doc.Label, "roots": sorted(o.Label for o in roots), "tree": {},
               "group_bbox_mm": {}, "solids": 0, "linked": {},
               "part_labels": sorted(o.Label for o in doc.Objects if o.TypeId == "Part::Feature")}
        for root in scene:
            bb, n = global_bbox(root)
            out["bbox_mm"] = bb
            out["solids"] += n
            out["root_placement"] = list(root.Placement.Rotation.Q) + list(root.Placement.Base)
            for g in root.Group:
                out["tree"][g.Label] = [o.Label for o in g.Group]
                out["group_bbox_mm"][g.Label] = global_bbox(g)[0]
                for o in g.Group:
                    if o.TypeId == "App::Link":
                        out["linked"][o.Label] = o.LinkedObject.Label
        return out
    finally:
        FreeCAD.closeDocument(doc.Name)


def main():
    paths = json.loads(os.environ["TACTCAD_FC_IN"])
    results = {"freecad_version": FreeCAD.Version()[:3], "files": {}}
    for p in paths:
        try:
            results["files"][p] = read(p)
        except Exception:
            results["files"][p] = {"error": traceback.format_exc()}
    with open(os.environ["TACTCAD_FC_OUT"], "w") as fh:
        json.dump(results, fh, indent=1, sort_keys=True)


main()
