"""The build book: ``instructions/index.html`` and ``instructions/steps.json``.

The steps come from the complete kit (:func:`tactcad.export.bom.complete_kit`
and :func:`tactcad.export.bom.kit_steps`): each step lists the BOM items it
consumes with their quantities and BOM item numbers, its tools, consumables
and notes. The page is one self-contained HTML file (no script, no external
reference), so it opens from ``file://`` offline and prints as it shows;
``build_book.pdf`` carries the same steps and pictures.
"""

from __future__ import annotations

import base64
import html
import json
from pathlib import Path
from typing import Callable

from tactcad.atomic import write_bytes_atomic

BOOK_DIR = "instructions"
BOOK_PAGE = f"{BOOK_DIR}/index.html"
BOOK_DATA = f"{BOOK_DIR}/steps.json"
BOOK_PDF = f"{BOOK_DIR}/build_book.pdf"
#: Colour of a step's new parts in its picture (RGB 0-1); nothing else of the model is magenta.
HIGHLIGHT_RGB = (1.0, 0.0, 1.0)
#: Grey of the parts placed before (RGB 0-1).
CONTEXT_RGB = (0.72, 0.72, 0.72)
#: How far a step's new parts are drawn lifted along their part frame's z (mm, per part height).
EXPLODE_FACTOR = 1.5

_STYLE = ("body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.4}"
          "table{border-collapse:collapse}td,th{border:1px solid #999;padding:2px 6px}"
          "section{page-break-inside:avoid;margin-bottom:2em}")


def picture_name(n: int, key: str) -> str:
    """``instructions/step_<n>_<key>.png``."""
    return f"{BOOK_DIR}/step_{n:02d}_{key}.png"


def step_picture(meshes, instances, highlight, target: Path, title: str) -> int:
    """Render the array with ``highlight`` parts in :data:`HIGHLIGHT_RGB`,
    lifted along their own z by :data:`EXPLODE_FACTOR` x their height, the
    rest grey (:func:`tactcad.export.render.render_assembly_png`).

    Args:
        meshes: part name -> (vertices (n, 3) mm, triangles (m, 3)).
        instances: the array's placed instances.
        highlight: part names of the step.

    Returns:
        Triangles drawn.
    """
    from dataclasses import replace

    from tactcad.export.render import render_assembly_png

    shown, parts, colors = [], dict(meshes), {}
    for inst in instances:
        if inst.part in highlight:
            lifted = inst.part + "@step"
            if lifted not in parts:
                v, t = meshes[inst.part]
                height = float(v[:, 2].max() - v[:, 2].min()) or 1.0
                parts[lifted] = (v + [0.0, 0.0, EXPLODE_FACTOR * max(height, 2.0)], t)
                colors[lifted] = HIGHLIGHT_RGB
            shown.append(replace(inst, part=lifted))
        else:
            colors[inst.part] = CONTEXT_RGB
            shown.append(inst)
    return render_assembly_png(parts, shown, colors, target, title, size_px=(800, 500))


def book_html(name: str, steps, rows, pictures: dict[str, bytes] | None = None) -> str:
    """The book's HTML text: a contents list, then one section per step.

    Args:
        name: the design's name.
        steps: :class:`tactcad.assembly.build_steps.Step` in build order.
        rows: the BOM rows (:class:`tactcad.export.bom.BomRow`), for item numbers and units.
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
        out.append("<p>Tools: " + e(", ".join(s.tools) or "none") + "</p>")
        if s.consumables:
            out.append("<p>Consumables: " + e(", ".join(s.consumables)) + "</p>")
        out.append("<ul>" + "".join(f"<li>{e(t)}</li>" for t in s.notes) + "</ul></section>")
    out.append("</body></html>")
    return "\n".join(out) + "\n"


def book_pdf(name: str, steps, rows, pictures: dict[str, Path], target: Path) -> None:
    """The book as an A4 PDF (reportlab platypus, invariant mode: the same
    steps give the same bytes): per step its title, parts table, tools,
    notes and picture (``pictures``: step key -> PNG path)."""
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
        flow.append(Spacer(1, 6 * mm))
    SimpleDocTemplate(str(target), pagesize=A4, title=f"Build book: {name}",
                      invariant=1).build(flow)


def write_book(project, staging: Path, log: Callable[[str], None], assembled,
               array=None, mesh=None) -> list[dict]:
    """Write the book (see module doc) into ``staging``.

    Args:
        array: (specs, instances) of the array; with ``mesh`` (spec -> (vertices,
            triangles)), each array step gets a picture ``step_<n>_<key>.png``,
            also embedded in the page.

    Returns:
        File records ``{"path", "part": "instructions", "kind", "steps"}``.
    """
    from tactcad.export.bom import complete_kit, kit_steps

    rows = complete_kit(project, assembled)
    steps = kit_steps(project, rows, assembled[0])
    (staging / BOOK_DIR).mkdir(parents=True, exist_ok=True)
    pictures: dict[str, bytes] = {}
    picture_paths: dict[str, Path] = {}
    records = []
    if array is not None and mesh is not None:
        specs, inst = array
        meshes = {i.part: mesh(specs[i.part]) for i in inst}
        for n, s in enumerate(steps, start=1):
            new = set(s.highlight) & set(meshes)
            if not new:
                continue
            path = picture_name(n, s.key)
            step_picture(meshes, inst, new, staging / path, f"Step {n}: {s.title}")
            pictures[s.key] = (staging / path).read_bytes()
            picture_paths[s.key] = staging / path
            records.append({"path": path, "part": "instructions", "kind": "instructions-png",
                            "step": s.key})
    write_bytes_atomic(staging / BOOK_PAGE,
                       book_html(project.plan.name, steps, rows, pictures).encode("utf-8"))
    write_bytes_atomic(staging / BOOK_DATA, json.dumps(
        [s.as_dict() for s in steps], indent=1).encode("utf-8"))
    book_pdf(project.plan.name, steps, rows, picture_paths, staging / BOOK_PDF)
    records.append({"path": BOOK_PDF, "part": "instructions", "kind": "instructions-pdf",
                    "steps": len(steps)})
    log(f"  wrote {BOOK_PAGE} and {BOOK_PDF} ({len(steps)} steps, {len(pictures)} pictures)")
    return [{"path": BOOK_PAGE, "part": "instructions", "kind": "instructions-html",
             "steps": len(steps)},
            {"path": BOOK_DATA, "part": "instructions", "kind": "instructions-json",
             "steps": len(steps)}] + records


def instructions_jobs(run, before):
    """``instructions/index.html`` and ``steps.json`` (kernel-free)."""
    from tactcad.export.job import Job
    from tactcad.store import content_key

    from tactcad.export.jobs import RENDER_VERSION

    specs, inst = run.array

    def make(run) -> list[dict]:
        return write_book(run.project, run.staging, run.log, run.inventory, run.array,
                          run.parts.mesh)
    return [Job("instructions", content_key("instructions", RENDER_VERSION, run.plan, run.inventory,
                                            run.project.rigs_sha256, list(specs.values()), inst),
                make, tuple(specs.values()))]
