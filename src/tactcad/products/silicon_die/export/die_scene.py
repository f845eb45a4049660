"""The die in its jaw: the jaw with its face pocket, the carrier and the die's layers as
solids (:class:`tactcad.products.silicon_die.design.die_mount.DieMount`'s places), written as one STEP assembly,
a shaded picture, and the bill of materials of the die's insert.

Units: mm.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

from tactcad.products.silicon_die.design.die_mount import CARRIER_MM, DieMount
from tactcad.products.silicon_die.design.mems_die import DiePlan

#: Part colours (RGB 0-1): the jaw's steel, the alumina carrier; the die's layers as the
#: die's own STEP colours them.
JAW_RGB = (0.70, 0.72, 0.76)
CARRIER_RGB = (0.93, 0.91, 0.84)


def mount_solids(plan: DiePlan, mount: DieMount,
                 layers: dict | None = None) -> dict[str, tuple[object, tuple]]:
    """Part name -> (solid in the jaw's frame, colour): ``jaw``, ``carrier`` and the die's
    layers (``<die>_handle``, ``_oxide``, ``_device``, ``_posts``); ``layers``: the die's
    :func:`~tactcad.products.silicon_die.export.die_solid.die_layer_solids` when already
    built (they are moved, not changed)."""
    from tactcad.products.silicon_die.export.die_solid import COLOURS, die_layer_solids
    from tactcad.kernel.shapes import box, cut, cylinder, translated

    m = mount
    half = m.jaw_width_mm / 2
    face = m.face_z_mm
    bar = box(0.0, -half, 0.0, m.jaw_length_mm, half, face)
    pocket = box(m.pocket_x0_mm, -m.pocket_width_mm / 2, face - m.pocket_depth_mm,
                 m.pocket_x0_mm + m.pocket_length_mm, m.pocket_width_mm / 2, face + 1.0)
    tools = [pocket]
    if m.pin_x_mm > 0:  # the pivot in the bar: its pin hole
        tools.append(cylinder(m.pin_diameter_mm / 2, (m.pin_x_mm, -half - 1.0, face / 2),
                              (0, 1, 0), m.jaw_width_mm + 2.0))
    floor = face - m.pocket_depth_mm
    out = {"grasper_jaw": (cut(bar, *tools), JAW_RGB),
           "die_carrier": (box(m.carrier_x0_mm, -m.carrier_width_mm / 2, floor,
                               m.carrier_x0_mm + m.carrier_length_mm, m.carrier_width_mm / 2,
                               floor + m.carrier_mm), CARRIER_RGB)}
    at = (m.die_x0_mm, -m.die_width_mm / 2, m.die_z0_mm)
    for layer, solid in (die_layer_solids(plan) if layers is None else layers).items():
        out[f"{plan.name}_{layer}"] = (translated(solid, at), COLOURS[layer])
    return out


def write_mount_step(solids: dict, path: Path, name: str) -> Path:
    """The mount's solids as one STEP assembly (AP214, mm), each a named, coloured part."""
    from tactcad.kernel.locations import offset
    from tactcad.kernel.step_writer import StepInstance, StepPart, write_step

    parts = [StepPart(k, s, rgb) for k, (s, rgb) in solids.items()]
    return write_step(path, parts, [StepInstance(p.name, p.name, offset(0.0, 0.0, 0.0))
                                    for p in parts], assembly_name=name)


def write_mount_picture(solids: dict, path: Path, title: str) -> Path:
    """A shaded picture of the jaw's distal end with the die in it (PNG), framed on the
    pocket's parts."""
    from types import SimpleNamespace

    from tactcad.export.render import render_assembly_png
    from tactcad.kernel.locations import offset
    from tactcad.solids.tessellation import tessellate

    meshes = {k: tessellate(s, 0.005) for k, (s, _) in solids.items()}
    instances = [SimpleNamespace(part=k, location=offset(0.0, 0.0, 0.0)) for k in solids]
    fit = [i for i, k in enumerate(solids) if k != "grasper_jaw"]
    render_assembly_png(meshes, instances, {k: rgb for k, (_, rgb) in solids.items()}, path,
                        title=title, size_px=(1400, 900), elev=35.0, azim=-60.0, fit=fit)
    return path


#: The fixed arms that complete each beam's half bridge off the die: their tolerance (relative;
#: a mismatch offsets the zero, tared) and temperature coefficient (ppm/K; it moves the zero as
#: the die's own resistors' mismatch does, so it is chosen far below the implant's TCR).
COMPLETION_TOLERANCE_REL, COMPLETION_TCR_PPM_PER_K = 0.001, 5.0


def mount_bom_rows(plan: DiePlan, mount: DieMount, jaw_label: str) -> list[dict[str, str]]:
    """The insert's bill of materials: the die, its carrier, the die attach, the jaw's
    machining and the resistors that complete the beams' half bridges off the die (quantity
    per jaw; the flex cable and its solder are the lab's to choose)."""
    from tactcad.products.silicon_die.mechanics.piezoresistor import die_resistance_ohm

    m = mount
    arms = 2 * len(plan.beams)
    return [
        {"item": plan.name, "qty": "1", "kind": "fabricated (SOI MEMS process)",
         "description": f"silicon die {m.die_length_mm:g} x {m.die_width_mm:g} x "
                        f"{m.die_stack_mm:.4g} mm without its posts "
                        f"({1e-3 * plan.thickness_um:.4g} mm with its "
                        f"{plan.post_height_um:g} um posts), 2 x {plan.columns} beams",
         "source": f"{plan.name}.gds, {plan.name}_traveller.md"},
        {"item": "die_carrier", "qty": "1", "kind": "bought, cut to size",
         "description": f"alumina {m.carrier_length_mm:.4g} x {m.carrier_width_mm:g} x "
                        f"{m.carrier_mm:.4g} mm, thin-film pads on its {m.carrier_length_mm - m.die_length_mm:.4g} mm "
                        "bond shelf", "source": "assumption: a stock thin-film substrate"
                        + ("" if abs(m.carrier_mm - CARRIER_MM) < 1e-9 else
                           f" lapped to the jaw's {m.pocket_depth_mm:g} mm pocket")},
        {"item": "die_attach", "qty": "1", "kind": "consumable",
         "description": f"{plan.attach.material}, {m.attach_mm:g} mm, "
                        f"{m.die_length_mm:g} x {m.die_width_mm:g} mm",
         "source": plan.attach.source},
        {"item": "grasper_jaw", "qty": "1", "kind": "machined",
         "description": f"the {jaw_label}: face pocket {m.pocket_length_mm:.4g} x "
                        f"{m.pocket_width_mm:.4g} x {m.pocket_depth_mm:.4g} mm, "
                        f"{m.jaw_length_mm - m.pocket_x0_mm - m.pocket_length_mm:.4g} mm from "
                        "its tip", "source": f"{plan.name}_in_jaw.step"},
        {"item": "bridge_completion_resistor", "qty": str(arms), "kind": "bought",
         "description": f"{die_resistance_ohm(plan):.3g} ohm (the die's resistor), "
                        f"+-{100 * COMPLETION_TOLERANCE_REL:g} %, <= "
                        f"{COMPLETION_TCR_PPM_PER_K:g} ppm/K thin film: the two fixed arms of "
                        f"each of the {len(plan.beams)} beams' half bridges, at the amplifier",
         "source": "assumption: a matched thin-film network"},
    ]


def write_mount_bom(rows: list[dict[str, str]], path: Path) -> Path:
    """``rows`` as CSV (UTF-8, a header line)."""
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    path.write_text(buf.getvalue(), encoding="utf-8")
    return path
