"""The silicon die as a solid model built from its masks and its wafer stack: the handle
less its two cavities (each row's to its own depth, the rows' hard stops), the buried oxide
on the bond face around them (the thin oxide lining the cavities is not drawn), the device
layer less the front etch (the beams standing free over the cavities) and the posts, each a
part of one STEP assembly (mm) for the review and the jaw's scene.

The outlines are :func:`tactcad.products.silicon_die.export.gds_masks.die_polygons`' (the masks' own polygons),
so the solid and the GDS cannot disagree (the beams' root fillets, quarter circles of
straight chords in the mask, are the solid's faceted fillets); the heights are the plan's
stack (um -> mm).
"""

from __future__ import annotations

from pathlib import Path

from tactcad.products.silicon_die.design.mems_die import DiePlan

#: Layer colours (RGB 0-1): silicon grey, oxide blue-white, posts amber.
COLOURS = {"handle": (0.45, 0.47, 0.52), "oxide": (0.80, 0.85, 0.95),
           "device": (0.55, 0.58, 0.66), "posts": (0.85, 0.60, 0.20)}
UM = 1e-3  # mm per um


def _prism(points, z0_um: float, height_um: float, holes=()):
    from tactcad.kernel.shapes import extrude, polygon_face

    def at_z(polygon):
        return [(x * UM, y * UM, z0_um * UM) for x, y in polygon]

    face = polygon_face(at_z(points), [at_z(h) for h in holes])
    return extrude(face, height_um * UM)


def holes_inside(outline, holes) -> bool:
    """True when every polygon of ``holes`` (um) lies inside ``outline`` clear of its
    boundary and of each other: then the layer is one face with holes, extruded."""
    import shapely

    outer = shapely.Polygon(outline)
    inner = [shapely.Polygon(h) for h in holes]
    if not outer.is_valid or not all(h.is_valid for h in inner):
        return False
    if not all(outer.contains_properly(h) for h in inner):
        return False
    return all(not a.intersects(b) for i, a in enumerate(inner) for b in inner[i + 1:])


def _through(outline, holes, z0_um: float, height_um: float):
    """The layer ``outline`` less the through openings ``holes`` (um): a face with holes
    extruded where they lie clear inside it (no boolean: the device etch's filleted
    outline took the 3D cut a second), else the 3D cut."""
    from tactcad.kernel.shapes import cut

    if holes_inside(outline, holes):
        return _prism(outline, z0_um, height_um, holes)
    return cut(_prism(outline, z0_um, height_um),
               *[_prism(h, z0_um - 1.0, height_um + 2.0) for h in holes])


def die_layer_inputs(plan: DiePlan) -> dict:
    """Everything the die's layer solids are built from, kernel-free: the masks' outlines
    (um: the die, each row's cavity with its depth, the device etch, the posts) and the
    stack's heights (um). :func:`die_layer_solids` reads only these, so an export names its
    solids' files by them (a change of the die's read-out or requirements leaves them).

    Returns:
        ``{"outline", "cavities": [(polygon, depth_um)], "device_etch", "posts",
        "handle_um", "box_um", "device_um", "post_height_um"}``.
    """
    from tactcad.products.silicon_die.export.gds_masks import die_polygons

    masks = die_polygons(plan)
    s = plan.stack
    return {"outline": masks["die"][0],
            "cavities": [(masks[f"cavity_{role}"][0], depth) for role, depth
                         in zip(("reference", "measuring"), plan.cavity_depths_um)],
            "device_etch": masks["device_etch"], "posts": masks["tip"],
            "handle_um": s.handle_um, "box_um": s.box_um, "device_um": s.device_um,
            "post_height_um": plan.post_height_um}


def die_layer_solids(plan: DiePlan, inputs: dict | None = None) -> dict:
    """Layer name -> solid (mm): ``handle``, ``oxide``, ``device``, ``posts``; ``inputs``:
    :func:`die_layer_inputs` when already made."""
    from tactcad.kernel import shapes
    from tactcad.kernel.shapes import cut

    i = die_layer_inputs(plan) if inputs is None else inputs
    outline, cavities, handle_um = i["outline"], i["cavities"], i["handle_um"]
    z_oxide, z_device = handle_um, handle_um + i["box_um"]
    z_top = z_device + i["device_um"]
    handle = cut(_prism(outline, 0.0, handle_um),
                 *[_prism(c, handle_um - depth, depth + 1.0) for c, depth in cavities])
    oxide = _through(outline, [c for c, _ in cavities], z_oxide, i["box_um"])
    device = _through(outline, i["device_etch"], z_device, i["device_um"])
    posts = shapes.Compound([_prism(p, z_top, i["post_height_um"]) for p in i["posts"]])
    return {"handle": handle, "oxide": oxide, "device": device, "posts": posts}


def write_die_step(plan: DiePlan, path: Path, layers: dict | None = None) -> Path:
    """The die's layers as one STEP assembly (AP214, mm), each layer a named, coloured part
    at its place in the stack; ``layers``: :func:`die_layer_solids` when already built."""
    from tactcad.kernel.locations import offset
    from tactcad.kernel.step_writer import StepInstance, StepPart, write_step

    solids = die_layer_solids(plan) if layers is None else layers
    parts = [StepPart(f"{plan.name}_{k}", v, COLOURS[k]) for k, v in solids.items()]
    instances = [StepInstance(p.name, p.name, offset(0.0, 0.0, 0.0)) for p in parts]
    return write_step(path, parts, instances, assembly_name=plan.name)
