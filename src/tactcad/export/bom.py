"""Bill of materials: one row per distinct item, quantities counted from the
assemblies' instances (never from a separate list).

Sources of parts and instances: the array and every scene
(:func:`tactcad.assembly.inventory.design_assemblies`). The scenes are set-ups
of one set of hardware, so an item's quantity is its largest count in any one
assembly (:func:`tactcad.assembly.inventory.part_quantities`); the Markdown
shows the count per assembly.

Files written by :func:`write_bom_files`:

* ``bom.csv``: RFC 4180 CSV in UTF-8 with a byte order mark (``utf-8-sig``:
  Excel and LibreOffice then read "Ø", "×" and "µ" right instead of guessing
  a legacy code page), ``\\n`` line ends, header row then one row per item
  (fabricated parts first, then purchased, each in catalogue order);
  ``material`` gives alloy and temper, ``stock`` the raw blank of a
  fabricated part (:func:`tactcad.catalogue.shop.stock_size`, with the
  allowances' reason in :data:`tactcad.catalogue.shop.STOCK_REASON`);
* ``bom.md``: the same table in Markdown, with a per-assembly breakdown.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Mapping, Sequence

from tactcad.version import VERSION
from tactcad.assembly.inventory import fabricated_parts, instance_counts, part_quantities, sample_kit
from tactcad.atomic import write_bytes_atomic
from tactcad.catalogue.array_catalogue import Instance, PartSpec
from tactcad.design.array_plan import Plan
from tactcad.drawings.sheet import fmt_mm
from tactcad.catalogue.shop import STOCK_REASON, material_designation, stock_size
from tactcad.export.kinds import bom_file_kinds

BOM_COLUMNS = ("item", "part", "quantity", "unit", "spares", "type", "material", "stock",
               "process_or_reference", "key_dimensions_mm", "files", "step")
#: Encoding of bom.csv: UTF-8 with a byte order mark, so spreadsheets detect UTF-8.
CSV_ENCODING = "utf-8-sig"


@dataclass(frozen=True)
class BomRow:
    """One distinct item of the bill of materials."""

    item: int
    part: str
    quantity: int
    per_assembly: tuple[tuple[str, int], ...]
    kind: str
    material: str
    process: str
    key_dimensions: str
    files: tuple[str, ...]
    stock: str = ""
    spares: int = 0  # included in quantity
    unit: str = "pcs"
    step: str = ""  # key of the build-book step that consumes it

    def as_dict(self) -> dict[str, str]:
        return {"item": str(self.item), "part": self.part, "quantity": str(self.quantity),
                "unit": self.unit, "spares": str(self.spares), "type": self.kind, "material": self.material, "stock": self.stock,
                "process_or_reference": self.process, "key_dimensions_mm": self.key_dimensions,
                "files": " ".join(self.files), "step": self.step}


def key_dimensions(spec: PartSpec) -> str:
    """``L x H x T`` (mm) of the part's designed bounding box, plus hole sizes
    from its profile (``2x Ø2.4``)."""
    x0, y0, z0, x1, y1, z1 = spec.expected_bbox_mm
    text = " x ".join(fmt_mm(v, 2) for v in (x1 - x0, y1 - y0, z1 - z0))
    if spec.profile is not None and spec.profile.holes:
        sizes: dict[str, int] = {}
        for h in spec.profile.holes:
            d = fmt_mm(2 * h.radius, 2)
            sizes[d] = sizes.get(d, 0) + 1
        text += "; holes " + ", ".join(f"{n}x Ø{d}" for d, n in sizes.items())
    return text


def bom_rows(instances: Sequence[Instance] | Mapping[str, Sequence[Instance]],
             specs: Mapping[str, PartSpec],
             files: Callable[[PartSpec], Sequence[str]] = lambda spec: (),
             plan: Plan | None = None) -> list[BomRow]:
    """BOM rows from placed instances.

    Args:
        instances: one assembly's instances, or ``{assembly: instances}``.
        specs: part specs by name (every instance's part must be there).
        files: the export files describing a part (drawing, DXF, STEP), paths
            relative to the export folder.
        plan: the design, whose material grade names the alloy and temper of
            the array's parts (:func:`tactcad.catalogue.shop.material_designation`).

    Returns:
        One row per distinct part used, fabricated first then purchased, in
        ``specs`` order within each; quantity = its instance count, the
        largest of any one assembly when several are given
        (:func:`part_quantities`).

    Raises:
        KeyError: an instance names a part missing from ``specs``.
    """
    asm = dict(instances) if isinstance(instances, Mapping) else {"assembly": list(instances)}
    per = {name: instance_counts(inst) for name, inst in asm.items()}
    used = part_quantities(asm)
    for part in used:
        if part not in specs:
            raise KeyError(f"instance part {part!r} has no PartSpec")
    order = [n for n in specs if n in used]
    order.sort(key=lambda n: 0 if specs[n].kind == "fabricated" else 1)
    return [part_row(specs[name], k, used[name],
                     tuple((a, c.get(name, 0)) for a, c in per.items()), files, plan)
            for k, name in enumerate(order, start=1)]


def part_row(spec: PartSpec, item: int, quantity: int, per_assembly: tuple[tuple[str, int], ...],
             files: Callable[[PartSpec], Sequence[str]] = lambda spec: (),
             plan: Plan | None = None) -> BomRow:
    """The BOM row of the part ``spec``: material, process, key dimensions,
    its files and, for a fabricated part, its stock (see :func:`bom_rows`)."""
    return BomRow(item=item, part=spec.name, quantity=quantity, per_assembly=per_assembly,
                  kind=spec.kind, material=material_designation(spec, plan), process=spec.process,
                  key_dimensions=key_dimensions(spec), files=tuple(files(spec)),
                  stock=stock_size(spec) if spec.kind == "fabricated" else "")


def sensor_rows(plan: Plan, rows: Sequence[BomRow], specs: Mapping[str, PartSpec]
                ) -> list[BomRow]:
    """Rows of the read-out's bought items (:func:`tactcad.catalogue.gauges.sensor_items`),
    numbered after ``rows``: per assembly as many as it has elements, in total that plus the
    spares."""
    from tactcad.catalogue.gauges import sensor_items

    elements = _elements_per_assembly(rows, specs)
    n_max = max(elements.values(), default=0)
    out = []
    modelled = {r.part for r in rows}  # the gauge is a placed part: its row is counted
    items = [i for i in sensor_items(plan) if i.part not in modelled]
    for k, item in enumerate(items, start=len(rows) + 1):
        out.append(BomRow(
            item=k, part=item.part, quantity=item.quantity(n_max),
            per_assembly=tuple((a, item.need(n) if n else 0) for a, n in elements.items()),
            kind="purchased", material=item.material, process=item.reference,
            key_dimensions=item.key_dimensions, files=(), spares=item.spares, unit=item.unit))
    return out


def with_spares(plan: Plan, rows: Sequence[BomRow]) -> list[BomRow]:
    """Rows with the read-out's spares added to the placed parts that have them (the gauge)."""
    from dataclasses import replace

    from tactcad.catalogue.gauges import sensor_items

    spares = {i.part: i.spares for i in sensor_items(plan) if i.spares}
    return [replace(r, quantity=r.quantity + spares[r.part], spares=spares[r.part])
            if r.part in spares else r for r in rows]


def bom_csv(rows: Sequence[BomRow]) -> str:
    """RFC 4180 CSV text of the rows (header :data:`BOM_COLUMNS`)."""
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=BOM_COLUMNS, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow(r.as_dict())
    return buf.getvalue()


def _md_cell(text: str) -> str:
    return text.replace("|", "\\|")


def bom_markdown(plan: Plan, rows: Sequence[BomRow]) -> str:
    """The BOM as a Markdown document: the item table, then instances per assembly."""
    lines = [f"# Bill of materials: {plan.name}", "",
             f"Design sha256 `{plan.design_hash[:12]}`, tactcad {VERSION}. Units: mm. "
             "Quantities are counted from the assemblies' placed instances. Stock: raw blank "
             f"per part; {STOCK_REASON}.", "",
             "| Item | Part | Qty | Unit | Spares | Type | Material | Stock | Process / reference "
             "| Key dimensions (mm) | Files | Step |",
             "| ---: | --- | ---: | --- | ---: | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        files = ", ".join(f"[{Path(f).name}]({f})" for f in r.files)
        lines.append(f"| {r.item} | {_md_cell(r.part)} | {r.quantity} | {r.unit} | {r.spares} | "
                     f"{r.kind} | "
                     f"{_md_cell(r.material)} | {_md_cell(r.stock)} | {_md_cell(r.process)} | "
                     f"{_md_cell(r.key_dimensions)} | {files} | {r.step} |")
    assemblies = [a for a, _ in rows[0].per_assembly] if rows else []
    if len(assemblies) > 1:
        lines += ["", "## Quantities per assembly", "",
                  "| Part | " + " | ".join(assemblies) + " | Quantity (largest, spares included) |",
                  "| --- | " + " | ".join("---:" for _ in assemblies) + " | ---: |"]
        for r in rows:
            lines.append(f"| {r.part} | " + " | ".join(str(n) for _, n in r.per_assembly)
                         + f" | {r.quantity} |")
    return "\n".join(lines) + "\n"


def source_confidence(row: BomRow) -> str:
    """How sure a bought part's modelled size is, from its reference: an envelope is to be
    checked against the bought part, a standard's part is sized by its table."""
    ref = row.process.lower()
    if "envelope" in ref:
        return "envelope: check against the bought part before the rig is built"
    if any(k in row.process for k in ("ISO ", "DIN ", "EN ")):
        return "catalogue standard"
    return "catalogue or data sheet named in the reference"


def purchased_parts_markdown(project) -> str:
    """``purchased-parts.md`` of a project: every bought part and consumable of its complete
    kit (:func:`complete_kit`) with its quantity, reference, modelled size and how sure that
    size is, so the list names the design's own bolts, gauges, read-out and rig parts.

    Args:
        project: a loaded project (:func:`tactcad.design.project.load_project`).

    Returns:
        Markdown text (UTF-8), units mm.
    """
    from tactcad.assembly.inventory import design_assemblies

    plan = project.plan
    rows = [r for r in complete_kit(project, design_assemblies(project))
            if r.kind != "fabricated"]
    lines = [f"# Bought parts of {plan.name}: what they are and how sure their sizes are", "",
             f"Generated by tactcad {VERSION} from the design's bill of materials (the same "
             "rows as the export's `bom.md`): every purchased part and consumable, its "
             "reference and the size the models use. Units: mm. A part modelled as an "
             "envelope is drawn as a simple solid of its outer size; check it against the "
             "part you buy. Regenerate after a change with `tactcad export` (`bom.md`).", "",
             "| Part | Qty | Unit | Type | Reference | Size modelled | Material | Build step "
             "| Confidence |",
             "| --- | ---: | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        confidence = "consumable" if r.kind == "consumable" else source_confidence(r)
        lines.append(f"| {_md_cell(r.part)} | {r.quantity} | {r.unit} | {r.kind} | "
                     f"{_md_cell(r.process)} | {_md_cell(r.key_dimensions)} | "
                     f"{_md_cell(r.material)} | {r.step} | {confidence} |")
    return "\n".join(lines) + "\n"


def part_files(plan: Plan, staging: Path,
               assemblies: Mapping[str, Sequence] | None = None) -> Callable[[PartSpec], list[str]]:
    """The export files that describe a part, as found in ``staging``: what each
    export kind names for it (:func:`tactcad.export.kinds.bom_file_kinds`, in
    their order: its drawing (SVG), its shop DXF files, its STEP model or, for a
    part without a STEP file of its own, the scene STEP files that show it).
    Only files that exist are named: those the run wrote and, in a partial export, those
    of the earlier export of the same design it keeps (copied in before its jobs run,
    :func:`tactcad.export.run.carried_before_jobs`)."""
    listers = [kind.files_of_parts(plan, assemblies or {}) for kind in bom_file_kinds()]

    def files(spec: PartSpec) -> list[str]:
        found: list[str] = []
        for lister in listers:
            found += [f for f in lister(spec.name, tuple(found)) if (staging / f).is_file()]
        return found

    return files


def _placed_and_sensor_rows(plan: Plan, assembled, files=lambda spec: ()) -> list[BomRow]:
    specs, assemblies = assembled
    rows = bom_rows(assemblies, specs, files, plan)
    return with_spares(plan, rows) + sensor_rows(plan, rows, specs)


def _elements_carried(spec: PartSpec | None) -> int:
    """Sensing elements one copy of a part carries: an element part one, a
    sheet cut with a row of elements (its geometry's ``elements``) that many."""
    if spec is None:
        return 0
    return 1 if spec.builder == "element" else len(getattr(spec.geometry, "elements", ()) or ())


def _elements_per_assembly(rows: Sequence[BomRow], specs: Mapping[str, PartSpec]
                           ) -> dict[str, int]:
    """Sensing elements per assembly, by the parts that carry them."""
    elements = {a: 0 for a, _ in rows[0].per_assembly} if rows else {"array": 0}
    for r in rows:
        carried = _elements_carried(specs.get(r.part))
        for a, n in r.per_assembly:
            elements[a] = elements.get(a, 0) + n * carried
    return elements


def _element_count(rows: Sequence[BomRow], specs: Mapping[str, PartSpec]) -> int:
    """Elements of the array (carried by its parts in the ``array`` assembly)."""
    return _elements_per_assembly(rows, specs).get("array", 0)


def kit_steps(project, rows: Sequence[BomRow], specs: Mapping[str, PartSpec]):
    """The build book's steps (:func:`tactcad.assembly.build_steps.build_steps`) for BOM ``rows``."""
    from tactcad.assembly.build_steps import build_steps, fastener_sizes, tip_zeroing_note
    from tactcad.export.drawn_tolerances import tip_height_drawing

    assemblies = [a for a, _ in rows[0].per_assembly] if rows else ["array"]
    scenes = [a for a in assemblies if a not in ("array", "wirecut")]

    def first(r: BomRow) -> str:
        shown = [a for a, n in r.per_assembly if n and a != "wirecut"]
        return shown[0] if shown else "array"

    # a step consumes what is fitted; the spares stay in the kit, said in the step's notes
    items = [(r.part, r.quantity - r.spares, getattr(specs.get(r.part), "builder", None),
              first(r)) for r in rows]
    samples = {p: k for p, (k, _) in sample_kit(project).items()}
    for r in rows:  # sample rows of the kit carry no spec
        if r.part in samples:
            items = [(p, q, "sample" if p == r.part else b, f) for p, q, b, f in items]
    board = project.rigs.library.get("terminal_board") if project.rigs is not None else None
    pairs = int(board.attributes.get("terminal_pairs", 0)) if board is not None else 0
    gauge = next((r for r in rows if r.part == "strain_gauge"), None)
    adhesive = next((r for r in rows if r.part == "gauge_adhesive"), None)
    screws = {name: spec.geometry[0] for name, spec in specs.items()
              if getattr(spec, "builder", None) == "rig_bolt"}  # geometry: (BoltSpec, length)
    return build_steps(items, _element_count(rows, specs), gauge.process if gauge else "",
                       adhesive.process if adhesive else "the gauge adhesive",
                       project.plan.bolt, pairs, scenes, samples, screws,
                       {name: spec.rig for name, spec in project.scenes.items()},
                       spares={r.part: r.spares for r in rows if r.spares},
                       tip_zeroing=tip_zeroing_note(tip_height_drawing(project.plan)),
                       fasteners=fastener_sizes(specs))


def complete_kit(project, assembled, files=lambda spec: ()) -> list[BomRow]:
    """The whole kit: placed parts, the sample kit (every sample the rigs file
    names, one per stiffness, placed or not), the read-out chain, consumables
    (:data:`tactcad.assembly.build_steps.CONSUMABLES`) and spares, each row
    naming the build-book step that consumes it."""
    from dataclasses import replace

    from tactcad.assembly.build_steps import CONSUMABLES

    plan = project.plan
    specs, _ = assembled
    rows = _placed_and_sensor_rows(plan, assembled, files)
    names = {r.part for r in rows}
    per = [a for a, _ in rows[0].per_assembly] if rows else ["array"]
    elements = _element_count(rows, specs)
    # the samples no scene shows: made and drawn as every part is (fabricated_parts)
    made, qty = fabricated_parts(project, assembled)
    samples = [part_row(spec, 0, qty[spec.name], tuple((a, 0) for a in per), files, plan)
               for spec in made if spec.name not in names]
    consumables = [BomRow(item=0, part=c.part, quantity=c.quantity(elements),
                          per_assembly=tuple((a, 0) for a in per), kind="consumable",
                          material=c.material, process=c.reference, key_dimensions=c.size,
                          files=(), unit=c.unit) for c in CONSUMABLES]
    fabricated = [r for r in rows if r.kind == "fabricated"]
    rows = fabricated + samples + [r for r in rows if r.kind != "fabricated"] + consumables
    rows = [replace(r, item=i) for i, r in enumerate(rows, start=1)]
    step_of: dict[str, str] = {}
    for s in kit_steps(project, rows, specs):  # a nut shared over steps: its first one's
        for p, _ in s.parts:
            step_of.setdefault(p, s.key)
    return [replace(r, step=step_of.get(r.part, "")) for r in rows]


def write_bom_files(plan: Plan, staging: Path, log: Callable[[str], None],
                    assembled, project=None) -> list[dict]:
    """Write ``bom.csv`` and ``bom.md`` into ``staging`` (see module doc).

    Run after the writers of the files it names (drawings, DXF, STEP): only
    files present in ``staging`` are referenced (a partial export's staging folder holds
    the earlier export's files it keeps too).

    Args:
        assembled: :func:`tactcad.assembly.inventory.design_assemblies` of the run's project.
        project: the run's project; given, the BOM is the complete kit (:func:`complete_kit`).

    Returns:
        File records ``{"path", "part": "bom", "kind", "items"}``.
    """
    specs, assemblies = assembled
    rows = complete_kit(project, assembled, part_files(plan, staging, assemblies)) \
        if project is not None else _placed_and_sensor_rows(plan, assembled,
                                                            part_files(plan, staging, assemblies))
    write_bytes_atomic(staging / "bom.csv", bom_csv(rows).encode(CSV_ENCODING))
    write_bytes_atomic(staging / "bom.md", bom_markdown(plan, rows).encode("utf-8"))
    log(f"  wrote bom.csv and bom.md ({len(rows)} items)")
    return [{"path": "bom.csv", "part": "bom", "kind": "bom-csv", "items": len(rows)},
            {"path": "bom.md", "part": "bom", "kind": "bom-markdown", "items": len(rows)}]
