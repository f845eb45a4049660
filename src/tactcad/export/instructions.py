"""The build book: ``instructions/index.html`` and ``instructions/steps.json``.

The steps come from the complete kit (:func:`tactcad.export.bom.complete_kit`
and :func:`tactcad.export.bom.kit_steps`): each step lists the BOM items it
consumes with their quantities and BOM item numbers, its tools, consumables
and notes. The page is one self-contained HTML file (no script, no external
reference), so it opens from ``file://`` offline and prints as it shows;
``build_book.pdf`` carries the same steps and pictures. A picture is named by its
step's number (``step_05_<key>.png``); a step whose parts have no 3D model (the
read-out chain's amplifier, DAQ and cable) has none, and its page, PDF entry and
``steps.json`` (``no_picture``) say so, naming those parts.
"""

from __future__ import annotations

import base64
import html
import json
from pathlib import Path
from typing import BinaryIO, Callable, Collection, Mapping, Sequence

import numpy as np

from tactcad.atomic import write_bytes_atomic
from tactcad.export.book_paths import BOOK_DATA, BOOK_DIR, BOOK_PAGE, BOOK_PDF

#: Colour of a step's new parts in its picture (RGB 0-1); nothing else of the model is magenta.
HIGHLIGHT_RGB = (1.0, 0.0, 1.0)
#: Grey of the parts placed before (RGB 0-1).
CONTEXT_RGB = (0.72, 0.72, 0.72)
#: How far a step's new parts are drawn lifted along their axis (mm, per part extent along it).
EXPLODE_FACTOR = 1.5
#: Gap (mm) within which a part counts as sitting on another (bonded, fastened: they touch).
TOUCH_MM = 0.05
#: How far a stack's layers are spread apart: each moves this many times its distance
#: (mm, along the axis, centre to centre) from the stack's first layer, on top of the lift.
STACK_SPREAD = 1.0

_STYLE = ("body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.4}"
          "table{border-collapse:collapse}td,th{border:1px solid #999;padding:2px 6px}"
          "section{page-break-inside:avoid;margin-bottom:2em}")


def picture_name(n: int, key: str) -> str:
    """``instructions/step_<n>_<key>.png``."""
    return f"{BOOK_DIR}/step_{n:02d}_{key}.png"


def no_picture_said(step, shown: Collection[str] | None) -> str:
    """Why a step of the book has no picture, in words its page, PDF and ``steps.json``
    carry (its picture's number is left unused, so the others keep their step's number).

    Args:
        step: the :class:`tactcad.assembly.build_steps.Step`.
        shown: the parts its scene's 3D model places (None: it has no model).

    Returns:
        ``No picture: its parts (amplifier, daq, cable) have no 3D model.``, naming the
        step's parts the model does not place.
    """
    unmodelled = [p for p, _ in step.parts if shown is None or p not in shown]
    return (f"No picture: its parts ({', '.join(unmodelled or [p for p, _ in step.parts])}) "
            "have no 3D model.")


def placed_boxes(meshes, instances, matrices) -> np.ndarray:
    """World bounding box of each instance: (n, 2, 3) mm, min and max corner."""
    out = []
    for inst, m in zip(instances, matrices):
        v = meshes[inst.part][0] @ m[:3, :3].T + m[:3, 3]
        out.append((v.min(axis=0), v.max(axis=0)))
    return np.array(out, dtype=float).reshape(-1, 2, 3)


def carriers(boxes: np.ndarray, moving: Sequence[int], resting: Sequence[int],
             touch_mm: float = TOUCH_MM) -> dict[int, int]:
    """Which moving instance each resting one sits on: the one whose box, grown
    by ``touch_mm``, meets its box the most (bonded or fastened parts touch);
    resting instances touching none are left out."""
    out = {}
    for r in resting:
        lo = np.maximum(boxes[r, 0], boxes[list(moving), 0] - touch_mm)
        hi = np.minimum(boxes[r, 1], boxes[list(moving), 1] + touch_mm)
        common = np.prod(np.clip(hi - lo, 0.0, None) + 1e-9 * (hi >= lo), axis=1)
        if len(moving) and common.max() > 0:
            out[r] = moving[int(np.argmax(common))]
    return out


def stacks(boxes: np.ndarray, axes: np.ndarray, moving: Sequence[int],
           touch_mm: float = TOUCH_MM) -> list[list[int]]:
    """The moving instances grouped into stacks: instances that move along the
    same axis and whose boxes, grown by ``touch_mm``, meet (layers clamped
    together, a screw through a spacer), joined transitively; an instance
    alone is a stack of one. ``axes``: unit axis per instance (n, 3). Stacks
    in the order of their first instance in ``moving``, each in that order."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components

    idx = np.asarray(moving, dtype=int)
    lo, hi, ax = boxes[idx, 0], boxes[idx, 1], axes[idx]
    same_axis = ax @ ax.T > 1.0 - 1e-6
    meet = np.all(np.minimum(hi[:, None], hi[None]) + touch_mm
                  >= np.maximum(lo[:, None], lo[None]), axis=-1)
    count, label = connected_components(csr_matrix(same_axis & meet), directed=False)
    return [[int(k) for k in idx[label == c]] for c in range(count)]


def lift_axis(part: str) -> int:
    """The part-frame axis a new part is drawn lifted along in its step (0, 1, 2 for x, y, z):
    a strain gauge off its bonded face (+y, :mod:`tactcad.partlib.array.strain_gauge`), any
    other part along its z (the array's stacking axis)."""
    from tactcad.partlib.array.strain_gauge import GAUGE_PART

    return 1 if part == GAUGE_PART else 2


def explode_offsets(meshes, instances, new: Collection[str], earlier: Collection[str] = (),
                    axes: Mapping[str, Sequence[float]] | None = None) -> dict[int, np.ndarray]:
    """World offsets (mm) of a step's exploded view. Each instance of a ``new``
    part moves along its joint axis (``axes``: instance name -> unit vector,
    :meth:`tactcad.assembly.scene_solver.Scene.joint_axes`; else its own
    :func:`lift_axis`) by :data:`EXPLODE_FACTOR` x its extent
    along it (at least 2 mm). A stack of them (:func:`stacks`: the array's
    elements, spacers and clamp plates; a column on its base plate) is spread
    apart in its order instead: its first layer along the axis moves as a
    part alone, each other layer :data:`STACK_SPREAD` x its distance from the
    first further, so a gap opens between every two. A part of an
    ``earlier`` step that sits on a new one (a gauge bonded on an element)
    moves with it; the parts of later steps stay where the model has them."""
    from tactcad.export.render import instance_matrix

    matrices = [instance_matrix(i) for i in instances]
    moving = [k for k, i in enumerate(instances) if i.part in new]
    if not moving:
        return {}
    unit = np.zeros((len(instances), 3))
    lift = np.zeros(len(instances))
    for k in moving:
        m = matrices[k]
        given = (axes or {}).get(instances[k].name)
        unit[k] = np.asarray(given, dtype=float) if given is not None \
            else m[:3, lift_axis(instances[k].part)]
        v = meshes[instances[k].part][0] @ m[:3, :3].T  # the part turned into the scene
        along = v @ unit[k]
        lift[k] = EXPLODE_FACTOR * max(float(along.max() - along.min()), 2.0)
    boxes = placed_boxes(meshes, instances, matrices)
    centres = boxes.mean(axis=1)
    offsets = {}
    for stack in stacks(boxes, unit, moving):
        axis = unit[stack[0]]
        along = {k: float(centres[k] @ axis) for k in stack}
        first = min(stack, key=along.__getitem__)
        for k in stack:
            offsets[k] = axis * (lift[first] + STACK_SPREAD * (along[k] - along[first]))
    resting = [k for k, i in enumerate(instances) if k not in offsets and i.part in earlier]
    for r, c in carriers(boxes, moving, resting).items():
        offsets[r] = offsets[c]
    return offsets


def step_picture(meshes, instances, highlight, target: Path | BinaryIO, title: str,
                 offsets: Mapping[int, np.ndarray]) -> int:
    """Render a step's model: the ``highlight`` parts in :data:`HIGHLIGHT_RGB`
    moved by ``offsets`` (:func:`explode_offsets`, with the parts they carry),
    every other part grey where the model has it
    (:func:`tactcad.export.render.render_assembly_png`); the picture frames
    the highlighted parts with the model around them as context (a rig's few
    small parts are not lost in the whole rig).

    Args:
        meshes: part name -> (vertices (n, 3) mm, triangles (m, 3)).
        instances: the scene's placed instances (array instances or scene parts).
        highlight: part names of the step.

    Returns:
        Triangles drawn.
    """
    from tactcad.export.render import render_assembly_png

    colors = {i.part: HIGHLIGHT_RGB if i.part in highlight else CONTEXT_RGB for i in instances}
    new = [k for k, i in enumerate(instances) if i.part in highlight]
    return render_assembly_png(meshes, instances, colors, target, title, size_px=(800, 500),
                               offsets=offsets, fit=new)


def explode_record(instances, offsets: dict[int, np.ndarray]) -> dict[str, list[float]]:
    """``{instance name: [dx, dy, dz]}`` (mm, the scene's frame, full explosion) of
    the instances that move: the book's ``steps.json`` carries it for the review
    page, whose 3D view plays the explosion with a slider."""
    return {instances[k].name: [round(float(x), 4) + 0.0 for x in v]
            for k, v in sorted(offsets.items())}


def book_html(name: str, steps, rows, pictures: dict[str, bytes] | None = None,
              unpictured: Mapping[str, str] | None = None) -> str:
    """The book's HTML text: a contents list, then one section per step.

    Args:
        name: the design's name.
        steps: :class:`tactcad.assembly.build_steps.Step` in build order.
        rows: the BOM rows (:class:`tactcad.export.bom.BomRow`), for item numbers and units.
        pictures: step key -> its picture (PNG bytes).
        unpictured: step key -> why it has no picture (:func:`no_picture_said`).
    """
    e = html.escape
    by_part = {r.part: r for r in rows}
    out = ["<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
           f"<title>Build book: {e(name)}</title><style>{_STYLE}</style></head><body>",
           f"<h1>Build book: {e(name)}</h1>",
           "<p>Steps in build order; every item of bom.csv is consumed by one step "
           "(its <code>step</code> column).</p><ol>"]
    out += [f"<li><a href=\"#{e(s.key)}\">{e(s.title)}</a> ({e(s.sub_assembly)})</li>"
            for s in steps]
    out.append("</ol>")
    for n, s in enumerate(steps, start=1):
        out += [f"<section id=\"{e(s.key)}\" data-step=\"{e(s.key)}\">",
                f"<h2>Step {n}: {e(s.title)}</h2>",
                f"<p>Sub-assembly: {e(s.sub_assembly)}; model: {e(s.scene)}</p>",
                "<table><tr><th>BOM item</th><th>Part</th><th>Quantity</th><th>Unit</th></tr>"]
        for part, qty in s.parts:
            r = by_part.get(part)
            out.append(f"<tr><td>{r.item if r else ''}</td><td>{e(part)}</td><td>{qty:g}</td>"
                       f"<td>{e(r.unit if r else '')}</td></tr>")
        out.append("</table>")
        if pictures and s.key in pictures:
            data = base64.b64encode(pictures[s.key]).decode("ascii")
            out.append(f"<img alt=\"{e(s.title)}: new parts in magenta, lifted\" width=\"800\" "
                       f"src=\"data:image/png;base64,{data}\">")
        elif unpictured and s.key in unpictured:
            out.append(f"<p class=\"no-picture\">{e(unpictured[s.key])}</p>")
        out.append("<p>Tools: " + e(", ".join(s.tools) or "none") + "</p>")
        if s.consumables:
            out.append("<p>Consumables: " + e(", ".join(s.consumables)) + "</p>")
        out.append("<ul>" + "".join(f"<li>{e(t)}</li>" for t in s.notes) + "</ul></section>")
    out.append("</body></html>")
    return "\n".join(out) + "\n"


def book_pdf(name: str, steps, rows, pictures: dict[str, Path], target: Path,
             unpictured: Mapping[str, str] | None = None) -> None:
    """The book as an A4 PDF (reportlab platypus, invariant mode: the same
    steps give the same bytes): per step its title, parts table, tools,
    notes and picture (``pictures``: step key -> PNG path), or why it has none
    (``unpictured``: step key -> :func:`no_picture_said`)."""
    from xml.sax.saxutils import escape

    from reportlab.lib.pagesizes import A4
    from reportlab.lib.styles import getSampleStyleSheet
    from reportlab.lib.units import mm
    from reportlab.platypus import Image, Paragraph, SimpleDocTemplate, Spacer, Table

    styles = getSampleStyleSheet()
    by_part = {r.part: r for r in rows}
    flow = [Paragraph(escape(f"Build book: {name}"), styles["Title"])]
    for n, s in enumerate(steps, start=1):
        flow.append(Paragraph(escape(f"Step {n}: {s.title}"), styles["Heading2"]))
        table = [["BOM item", "Part", "Quantity", "Unit"]] + [
            [str(by_part[p].item) if p in by_part else "", p, f"{q:g}",
             by_part[p].unit if p in by_part else ""] for p, q in s.parts]
        flow.append(Table(table, hAlign="LEFT"))
        flow.append(Paragraph(escape("Tools: " + (", ".join(s.tools) or "none")), styles["Normal"]))
        flow += [Paragraph(escape("- " + t), styles["Normal"]) for t in s.notes]
        if s.key in pictures:
            flow.append(Image(str(pictures[s.key]), width=160 * mm, height=100 * mm))
        elif unpictured and s.key in unpictured:
            flow.append(Paragraph(escape(unpictured[s.key]), styles["Normal"]))
        flow.append(Spacer(1, 6 * mm))
    SimpleDocTemplate(str(target), pagesize=A4, title=f"Build book: {name}",
                      invariant=1).build(flow)


def write_book(project, staging: Path, log: Callable[[str], None], assembled,
               array=None, mesh=None, scene_of=None) -> list[dict]:
    """Write the book (see module doc) into ``staging``.

    Args:
        array: (specs, instances) of the array; with ``mesh`` (spec -> (vertices,
            triangles)), each step that places a part of the array gets a
            picture ``step_<n>_<key>.png``, also embedded in the page.
        scene_of: scene name -> (its placed parts, its part specs by name, its
            joint axes by instance); with ``mesh``, the steps of the rigs and the
            samples get pictures of their scenes, exploded along those axes.

    Returns:
        File records ``{"path", "part": "instructions", "kind", "steps"}``.
    """
    from tactcad.export.bom import complete_kit, kit_steps

    from dataclasses import replace

    rows = complete_kit(project, assembled)
    steps = [replace(s, scene=drawn_scene(s, assembled[1]))
             for s in kit_steps(project, rows, assembled[0])]
    (staging / BOOK_DIR).mkdir(parents=True, exist_ok=True)
    pictures: dict[str, bytes] = {}
    picture_paths: dict[str, Path] = {}
    explode: dict[str, dict[str, list[float]]] = {}
    unpictured: dict[str, str] = {}  # a step without a picture says why, its number kept
    records = []
    if mesh is not None:
        order: dict[str, int] = {}
        for n, s in enumerate(steps):  # a part shared over steps (a nut) is placed at its first
            for part, _ in s.parts:
                order.setdefault(part, n)
        models: dict = {}
        for n, s in enumerate(steps):
            model = _step_model(s.scene, array, scene_of, models)
            if model is None:
                unpictured[s.key] = no_picture_said(s, None)
                continue
            instances, specs, axes = model
            new = set(s.highlight) & {i.part for i in instances}
            if not new:
                unpictured[s.key] = no_picture_said(s, {i.part for i in instances})
                continue
            earlier = {i.part for i in instances if order.get(i.part, -1) < n}
            path = picture_name(n + 1, s.key)
            png, explode[s.key] = step_picture_kept(
                instances, specs, axes, new, earlier, f"Step {n + 1}: {s.title}", mesh)
            write_bytes_atomic(staging / path, png)
            pictures[s.key] = png
            picture_paths[s.key] = staging / path
            records.append({"path": path, "part": "instructions", "kind": "instructions-png",
                            "step": s.key})
    write_bytes_atomic(staging / BOOK_PAGE,
                       book_html(project.plan.name, steps, rows, pictures,
                                 unpictured).encode("utf-8"))
    write_bytes_atomic(staging / BOOK_DATA, json.dumps(
        [{**s.as_dict(), "explode": explode.get(s.key, {}),
          "no_picture": unpictured.get(s.key)} for s in steps],
        indent=1).encode("utf-8"))
    book_pdf(project.plan.name, steps, rows, picture_paths, staging / BOOK_PDF, unpictured)
    records.append({"path": BOOK_PDF, "part": "instructions", "kind": "instructions-pdf",
                    "steps": len(steps)})
    log(f"  wrote {BOOK_PAGE} and {BOOK_PDF} ({len(steps)} steps, {len(pictures)} pictures)")
    return [{"path": BOOK_PAGE, "part": "instructions", "kind": "instructions-html",
             "steps": len(steps)},
            {"path": BOOK_DATA, "part": "instructions", "kind": "instructions-json",
             "steps": len(steps)}] + records


def drawn_scene(step, assemblies) -> str:
    """The model a step shows: its own scene, or, when that holds none of the
    step's parts (the terminal board is wired before it is mounted on a rig),
    the first assembly that does (``assemblies``: name -> instances with ``part``)."""
    want = set(step.highlight)
    names = [step.scene] + [a for a in assemblies if a != step.scene]
    return next((a for a in names if want & {i.part for i in assemblies.get(a, ())}), step.scene)


def _step_model(scene: str, array, scene_of, models: dict):
    """(instances, their part specs by name, joint axes) of the model a step's picture
    shows, made once per scene; None when it cannot be drawn here."""
    if scene not in models:
        axes: dict = {}
        if scene == "array" and array is not None:
            specs, instances = array
        elif scene != "array" and scene_of is not None:
            instances, specs, axes = scene_of(scene)
        else:
            models[scene] = None
            return None
        models[scene] = (list(instances), specs, axes)
    return models[scene]


def step_picture_kept(instances, specs, axes, new: set[str], earlier: set[str], title: str,
                      mesh) -> tuple[bytes, dict[str, list[float]]]:
    """A step's picture (PNG bytes, :func:`step_picture`) and its explosion record
    (:func:`explode_record`), or both as an earlier run kept them in the result store
    (:func:`tactcad.store.kept_result`) when the picture shows the same parts in the
    same places: a design change redraws only the steps that show a changed part.

    Args:
        instances: the model's placed instances (array instances or scene parts).
        specs: part name -> part spec, for every part of ``instances``.
        axes: instance name -> joint axis (the scene's), used by the explosion.
        new, earlier: part names of the step's new parts and of those placed before it.
        title: the picture's title.
        mesh: part spec -> (vertices (n, 3) mm, triangles (m, 3)), called only on a miss.

    Returns:
        (the PNG's bytes, {instance name: [dx, dy, dz] mm}).
    """
    import io

    from tactcad.export.jobs import RENDER_VERSION
    from tactcad.export.render import instance_matrix
    from tactcad.store import kept_result

    def draw() -> tuple[bytes, dict[str, list[float]]]:
        meshes = {i.part: mesh(specs[i.part]) for i in instances}
        offsets = explode_offsets(meshes, instances, new, earlier, axes)
        png = io.BytesIO()
        step_picture(meshes, instances, new, png, title, offsets)
        return png.getvalue(), explode_record(instances, offsets)

    shown = [(i.name, i.part, np.round(instance_matrix(i), 9).tolist()) for i in instances]
    parts = {name: specs[name] for name in sorted({i.part for i in instances})}
    given_axes = {k: [float(x) for x in v] for k, v in axes.items()}
    return kept_result("build-book picture", draw, RENDER_VERSION, title, shown, parts,
                       sorted(new), sorted(earlier), given_axes)


def instructions_jobs(run, before):
    """``instructions/index.html`` and ``steps.json`` (kernel-free)."""
    from tactcad.export.job import Job
    from tactcad.store import content_key

    from tactcad.export.jobs import RENDER_VERSION, keeping_run_results

    specs, inst = run.array

    def make(run) -> list[dict]:
        def scene_of(name: str):
            scene, _ = run.scene(name)
            return scene.instances, scene.parts(), scene.joint_axes()
        with keeping_run_results(run):
            return write_book(run.project, run.staging, run.log, run.inventory, run.array,
                              run.parts.mesh, scene_of)
    every_part = {**specs, **run.inventory[0]}  # the array's and every scene's parts
    return [Job("instructions", content_key("instructions", RENDER_VERSION, run.plan, run.inventory,
                                            run.project.rigs_sha256, list(specs.values()), inst),
                make, tuple(every_part.values()), worker=True)]
