"""Every job of an export run, in manifest order, each with its content key.

A key names everything that shapes the job's bytes (see
:func:`tactcad.store.content_key`): the part spec for a part's STEP file, the
profile and title for a DXF, the scene's spec and rig model for a scene, the
plan and the part for a drawing ... Planning the jobs needs no CAD kernel;
the ``make`` functions import the writers (and with them the kernel) only
when a job has to run.

Order: part STEP files, the array STEP, the element DXFs, the scenes (STEP
and GLB), the drawings (SVG, PDF, PNG), the array image, the BOM, the review
page. The BOM comes after the files it names; the review page last, as it
shows the scenes, the sheets and the BOM.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from tactcad.assembly.inventory import assembly_review, fabricated_parts, instance_counts
from tactcad.assembly.rig_models import shown_instances
from tactcad.drawings.compose import drawing_inputs
from tactcad.catalogue.files import (ARRAY_PNG, ARRAY_STEP, ASSEMBLY_DRAWING, PDF_NAME, drawing_name,
                                    drawing_png_name, part_step_name, scene_glb_name,
                                    scene_step_name, sheet_dxf_name)
from tactcad.export.dxf_sheet import (dxf_version_option, shop_profiles, write_part_dxf_files,
                                      write_shop_dxf_files)
from tactcad.export.freecad_review import freecad_identity
from tactcad.export.job import Job, Run
from tactcad.export.kinds import EXPORT_KINDS, full_export_kinds
from tactcad.store import content_key

PNG_DPI = 150
#: the array picture's renderer: part meshes at the run's mesh tolerance, windowed z-buffer;
#: 3: the model below the title, a build step framed on its new parts
RENDER_VERSION = 3


def all_jobs(run: Run, kinds: Sequence[str] = ()) -> list[Job]:
    """The jobs of a full export of ``run.plan``
    (:func:`~tactcad.export.kinds.full_export_kinds`) and of the ``kinds``
    outside it that are asked for, in the order of
    :data:`~tactcad.export.kinds.EXPORT_KINDS`. A selection picks from these
    by job prefix: a kind's jobs may be planned by another's (the FreeCAD
    review files, ``review:...``, with the scenes they show)."""
    wanted = set(full_export_kinds()) | set(kinds)
    jobs: list[Job] = []
    for kind in EXPORT_KINDS.values():
        if kind.name in wanted:
            jobs += kind.jobs(run, list(jobs))
    return jobs


# --- what an export is made from: the manifest's "inputs" ------------------------------------
def export_inputs(run: Run, planned: Sequence[Job] | None = None) -> dict:
    """What a full export of ``run.project`` is made from, for its manifest's ``inputs``:
    the project files (each with the sha256 of its validated tables), the shop DXF version
    and one sha256 over the key of every job of a full export (:func:`all_jobs`), the keys
    the store of finished jobs reuses a job by. A check that plans the same record from the
    current files (:func:`tactcad.export.reuse.changed_inputs`) knows the export is older
    than an edit of any file it reads (rigs, scenes, atlas ...), with no second list.

    Args:
        run: an export run of the project (its staging folder is not read).
        planned: ``all_jobs(run)`` where the caller has them already (None: planned here,
            about 0.2 s).

    Returns:
        ``{"files": [{"role", "file", "sha256"}], "dxf_version": str, "jobs_sha256": str}``;
        ``file`` relative to the design file's folder (a path of this machine never).
    """
    # the keys of a full export even for a partial one: what a check compares
    keys = [job.key for job in (all_jobs(run) if planned is None else planned)]
    return {"files": input_files(run.project),
            "dxf_version": run.dxf_version or dxf_version_option(),
            "jobs_sha256": content_key("export-jobs", keys)}


def input_files(project) -> list[dict]:
    """The design, rigs and scenes files of ``project`` that exist (a design made in code has
    none), each ``{"role", "file", "sha256"}``: its name as the project folder holds it and
    the sha256 of its validated tables (:attr:`tactcad.design.project.Project.hashes`)."""
    folder = Path(project.plan.source).parent
    paths = {"design": project.plan.source, "rigs": project.rigs_file,
             "scenes": project.scenes_file}
    return [{"role": role, "file": _named_in(folder, paths[role]), "sha256": sha}
            for role, sha in project.hashes.items() if paths[role] and sha]


def _named_in(folder: Path, path: str) -> str:
    """``path`` relative to ``folder`` when inside it, else its file name (an export names
    no path of the machine it was made on)."""
    try:
        return Path(path).resolve().relative_to(folder.resolve()).as_posix()
    except (ValueError, OSError):
        return Path(path).name


# --- the array: part STEP files, the assembly, the wire-EDM profiles --------------------------
def step_jobs(run: Run, before: list[Job]) -> list[Job]:
    """Each array part's STEP file, then the array's assembly."""
    specs, inst = run.array
    jobs = [Job(f"step:{name}", content_key("step-part", spec), _part_step(spec), (spec,))
            for name, spec in specs.items()]
    jobs.append(Job("step:array", content_key("step-array", list(specs.values()), inst),
                    _array_step(specs, inst), tuple(specs.values())))
    return jobs


def dxf_jobs(run: Run, before: list[Job]) -> list[Job]:
    """The wire-EDM shop files: one DXF per profile and one per nested sheet, in one job
    that ``--part`` cuts down to a part's own profile files (:attr:`Job.for_part`)."""
    specs, _ = run.array
    version = run.dxf_version or dxf_version_option()

    def for_part(name: str) -> Job | None:
        if name not in {sp.part for sp in shop_profiles(run.plan)}:
            return None
        return Job(f"dxf:{name}", content_key("dxf-part", run.plan, list(specs.values()),
                                              version, name), _part_dxf(name, version))

    return [Job("dxf:shop", content_key("dxf-shop", run.plan, list(specs.values()), version),
                _shop_dxf(version), for_part=for_part)]


def _part_step(spec):
    def make(run: Run) -> list[dict]:
        from tactcad.kernel.step_writer import StepPart, write_step

        rel = part_step_name(spec.name)
        write_step(run.staging / rel, [StepPart(spec.name, run.parts.solid(spec), spec.color)])
        run.log(f"  wrote {rel}")
        return [{"path": rel, "part": spec.name, "kind": "step-part", "solids": 1,
                 "volume_mm3": spec.expected_volume_mm3,
                 "bbox_mm": list(spec.expected_bbox_mm), "labels": [spec.name]}]
    return make


def _array_step(specs, inst):
    def make(run: Run) -> list[dict]:
        from tactcad.assembly.plan_locations import location
        from tactcad.assembly.z_up import z_up_location
        from tactcad.kernel.step_writer import StepInstance, StepPart, write_step

        parts = [StepPart(n, run.parts.solid(s), s.color) for n, s in specs.items()]
        z_up = z_up_location()  # STEP is Z up
        instances = [StepInstance(i.name, i.part, z_up * location(i.placement)) for i in inst]
        write_step(run.staging / ARRAY_STEP, parts, instances, "array")
        run.log(f"  wrote {ARRAY_STEP}")
        return [{"path": ARRAY_STEP, "part": "array", "kind": "step-assembly",
                 **assembly_review(specs, inst)}]
    return make


def _shop_dxf(version: str):
    def make(run: Run) -> list[dict]:
        return write_shop_dxf_files(run.plan, run.staging, run.log, version)
    return make


def _part_dxf(part: str, version: str):
    def make(run: Run) -> list[dict]:
        return write_part_dxf_files(run.plan, run.staging, part, run.log, version)
    return make


# --- scenes: STEP and GLB per scene ---------------------------------------------------------
def scene_and_review_jobs(run: Run, before: list[Job]) -> list[Job]:
    """Every scene's STEP and GLB, and the FreeCAD review files of them all."""
    return scene_jobs(run)


def scene_jobs(run: Run, names=None) -> list[Job]:
    """One job per scene (all, or ``names`` in that order)."""
    names = list(run.scenes) if names is None else list(names)
    jobs = []
    for n in names:
        spec, model = run.scenes[n]
        shown = {part: model.specs[part] for _, part, _ in shown_instances(model, spec)}
        jobs.append(Job(f"scene:{n}", content_key("scene", spec, model), _scene(n),
                        tuple(shown.values())))
    # one FreeCAD process writes the review files of all these scenes
    jobs.append(Job("review:" + ",".join(names),
                    content_key("review-fcstd", [j.key for j in jobs], freecad_identity()),
                    None, tuple({s.name: s for j in jobs for s in j.needs}.values()),
                    start=_start_review(names), ahead=_freecad_ahead))
    return jobs


def _scene(name: str):
    def make(run: Run) -> list[dict]:
        from tactcad.assembly.scene_solver import review_record
        from tactcad.assembly.z_up import z_up_location
        from tactcad.export.glb import write_glb
        from tactcad.kernel.step_writer import StepInstance, StepPart, write_step

        scene, solids = run.scene(name)
        parts = [StepPart(n, solids[n], spec.color) for n, spec in scene.parts().items()]
        z_up = z_up_location()  # STEP is Z up, the GLB keeps glTF's y up
        inst = [StepInstance(i.name, i.part, z_up * i.location) for i in scene.instances]
        rel = scene_step_name(name)
        write_step(run.staging / rel, parts, inst, name)
        rel_glb = scene_glb_name(name)
        tri = write_glb(run.staging / rel_glb, scene,
                        {n: run.parts.mesh(spec) for n, spec in scene.parts().items()})
        run.log(f"  wrote {rel} and {rel_glb} ({len(scene.instances)} parts)")
        return [{"path": rel, "part": name, "kind": "step-scene", **review_record(scene)},
                {"path": rel_glb, "part": name, "kind": "glb-scene",
                 "nodes": len(scene.instances), "meshes": len(parts), "triangles": tri}]
    return make


def _freecad_ahead():
    """FreeCAD started ahead of the review files
    (:func:`tactcad.export.freecad_review.start_freecad_ahead`)."""
    from tactcad.export.freecad_review import start_freecad_ahead

    return start_freecad_ahead()


def _start_review(names: list[str]):
    """FreeCAD writes the review files in its own process while the run goes on."""
    def start(run: Run):
        from tactcad.export.freecad_review import scene_review_assembly, start_review_files

        assemblies = []
        for name in names:
            scene, solids = run.scene(name)
            assemblies.append(scene_review_assembly(scene, solids, scene_step_name(name)))
        return start_review_files(run.staging, assemblies, run.log)
    return start


# --- drawings: one SVG per fabricated part, the PDF, the first element's page as PNG ----------
def drawing_jobs(run: Run, before: list[Job]) -> list[Job]:
    plan = run.plan
    parts, qty = fabricated_parts(run.project, run.inventory)
    jobs = []
    for spec, tip in planned_drawings(plan, parts):
        jobs.append(Job(f"drawing:{spec.name}",
                        content_key("drawing-svg", drawing_inputs(plan, spec, tip),
                                    qty[spec.name]),
                        _drawing(spec, qty[spec.name], tip), (spec,), worker=True))
    svgs = [drawing_name(s.name) for s in parts]
    # --- the assembly sheet: last page of the PDF ---
    jobs.append(assembly_sheet_job(run))
    svgs.append(ASSEMBLY_DRAWING)
    # --- end of the assembly sheet ---
    jobs.append(Job("drawings:pdf", content_key("drawing-pdf", plan.name, [j.key for j in jobs]),
                    _drawings_pdf(svgs), after=tuple(j.name for j in jobs), worker=True))
    elements = [k for k, s in enumerate(parts) if s.builder == "element"]
    if elements:
        # the PNG shows one page: it depends on that page's drawing only
        page = elements[0]
        jobs.append(Job("drawings:png", content_key("drawing-png", jobs[page].key, PNG_DPI),
                        _drawing_png(parts[page].name, page), after=("drawings:pdf",),
                        worker=True))
    return jobs


def planned_drawings(plan, parts) -> list[tuple]:
    """(part spec, its tip-height decision or None) per fabricated part to draw: the
    decision (:func:`tactcad.export.drawn_tolerances.tip_height_for`) worked out once here
    from the K_obj budget and handed to the drawings of the parts with tips.

    Args:
        plan: the validated design.
        parts: the fabricated parts' specs, in drawing order.

    Returns:
        [(spec, :class:`~tactcad.in_use.tip_height_drawing.TipHeightDrawing` or None)].
    """
    from tactcad.export.drawn_tolerances import tip_height_for

    return [(spec, tip_height_for(plan, spec.builder)) for spec in parts]


def _drawing(spec, quantity: int, tip_height=None):
    def make(run: Run) -> list[dict]:
        from tactcad.atomic import write_bytes_atomic
        from tactcad.drawings.compose import compose
        from tactcad.drawings.views import scale_text

        with keeping_run_results(run):  # each view's edges, kept by the part's spec
            d = compose(run.plan, spec, run.parts.solid(spec), quantity, tip_height)
        rel = drawing_name(spec.name)
        write_bytes_atomic(run.staging / rel, d.sheet.svg().encode("utf-8"))
        run.log(f"  wrote {rel}")
        return [{"path": rel, "part": spec.name, "kind": "drawing-svg", "quantity": quantity,
                 "scale": scale_text(d.scale)}]
    return make


def keeping_run_results(run: Run):
    """A block in which :func:`tactcad.store.kept_result` keeps values in the run's store:
    the enclosing block when it has that store (the command's ``--cache``), else a new
    one (a worker, or a caller of the export without a block).

    Args:
        run: the export run.

    Returns:
        a context manager.
    """
    import contextlib

    from tactcad.store import active_store, keeping_results

    return contextlib.nullcontext() if active_store() == run.store else keeping_results(run.store)


def assembly_sheet_job(run: Run) -> Job:
    """The array's assembly sheet (:mod:`tactcad.drawings.assembly`): its key
    holds the sheet's inputs, BOM item numbers included; it needs the array's
    part solids."""
    from tactcad.drawings.assembly import assembly_inputs
    from tactcad.export.bom import bom_rows, complete_kit

    plan = run.plan
    specs, assemblies = run.inventory
    # numbered as bom.csv numbers them: the complete kit (samples and consumables included)
    rows = complete_kit(run.project, run.inventory) if run.project is not None \
        else bom_rows(assemblies, specs)
    items = {r.part: r.item for r in rows}
    array_specs = run.array[0]

    def make(run: Run) -> list[dict]:
        from tactcad.atomic import write_bytes_atomic
        from tactcad.drawings.assembly import compose_assembly
        from tactcad.drawings.views import scale_text

        solids = {n: run.parts.solid(s) for n, s in array_specs.items()}
        a = compose_assembly(plan, solids, items)
        write_bytes_atomic(run.staging / ASSEMBLY_DRAWING, a.sheet.svg().encode("utf-8"))
        run.log(f"  wrote {ASSEMBLY_DRAWING}")
        return [{"path": ASSEMBLY_DRAWING, "part": "array", "kind": "drawing-assembly",
                 "scale": scale_text(a.scale), "slots": len(a.slot_rows),
                 "torque_Nm": round(a.torque_Nm, 3)}]
    return Job("drawing:assembly", content_key("drawing-assembly", assembly_inputs(plan, items)),
               make, tuple(array_specs.values()), worker=True)


def _drawings_pdf(svgs: list[str]):
    def make(run: Run) -> list[dict]:
        from tactcad.atomic import write_atomic
        from tactcad.drawings.pdf import svgs_to_pdf

        texts = [(run.staging / rel).read_text(encoding="utf-8") for rel in svgs]
        write_atomic(run.staging / PDF_NAME,
                     lambda tmp: svgs_to_pdf(texts, tmp, f"{run.plan.name} fabrication drawings",
                                             run.store))
        run.log(f"  wrote {PDF_NAME} ({len(texts)} pages)")
        return [{"path": PDF_NAME, "part": "drawings", "kind": "drawing-pdf", "pages": len(texts)}]
    return make


def _drawing_png(part: str, page: int):
    def make(run: Run) -> list[dict]:
        from tactcad.atomic import write_atomic
        from tactcad.export.render import pdf_page_png

        rel = drawing_png_name(part)
        write_atomic(run.staging / rel,
                     lambda tmp: pdf_page_png(run.staging / PDF_NAME, page, tmp, PNG_DPI))
        run.log(f"  wrote {rel}")
        return [{"path": rel, "part": part, "kind": "image-png"}]
    return make


# --- the array image and the bill of materials ----------------------------------------------
def image_jobs(run: Run, before: list[Job]) -> list[Job]:
    """``images/array.png``: the array rendered from the run's part meshes."""
    plan = run.plan
    specs, inst = run.array
    title = (f"{plan.name}: {plan.rows} x {plan.columns} elements, pitch "
             f"{plan.pitch_mm:g} mm (design {plan.design_hash[:12]})")

    def make(run: Run) -> list[dict]:
        from tactcad.atomic import write_atomic
        from tactcad.export.render import render_assembly_png

        # the run's part meshes (kept across edits under watch), as the scenes use them
        meshes = {i.part: run.parts.mesh(specs[i.part]) for i in inst}
        colors = {n: specs[n].color for n in meshes}
        box = {}
        write_atomic(run.staging / ARRAY_PNG, lambda tmp: box.setdefault(
            "n", render_assembly_png(meshes, inst, colors, tmp, title)))
        run.log(f"  wrote {ARRAY_PNG} ({box['n']} triangles)")
        return [{"path": ARRAY_PNG, "part": "array", "kind": "image-png", "triangles": box["n"]}]
    return [Job("image:array", content_key("array-png", RENDER_VERSION, list(specs.values()),
                                           inst, title), make, tuple(specs.values()))]


def bom_jobs(run: Run, before: list[Job]) -> list[Job]:
    """``bom.csv`` and ``bom.md``. The BOM names the files of the jobs before it, so its key holds theirs."""
    def make(run: Run) -> list[dict]:
        from tactcad.export.bom import write_bom_files

        return write_bom_files(run.plan, run.staging, run.log, run.inventory, run.project)
    return [Job("bom", content_key("bom", run.plan, run.inventory, run.project.rigs_sha256,
                            [j.key for j in before]),
                make, after=tuple(j.name for j in before))]


# --- the files of each kind that describe a part, for the BOM's files column ------------------
def drawing_part_files(plan, assemblies):
    """``drawings/<part>.svg``."""
    return lambda part, found: [drawing_name(part)]


def dxf_part_files(plan, assemblies):
    """A cut part's profile DXF (with its quantity) and the nested sheet it is cut from."""
    dxf_of = {sp.part: [sp.file_name, sheet_dxf_name(sp.sheet_material, sp.thickness_mm)]
              for sp in shop_profiles(plan)}
    return lambda part, found: dxf_of.get(part, [])


def step_part_files(plan, assemblies):
    """``step/<part>.step``."""
    return lambda part, found: [part_step_name(part)]


def scene_part_files(plan, assemblies):
    """The scene STEP files that show a part, for a part without a STEP file of its own."""
    shown_in: dict[str, list[str]] = {}
    for name, inst in assemblies.items():
        for part in instance_counts(inst):
            shown_in.setdefault(part, []).append(scene_step_name(name))
    return lambda part, found: ([] if part_step_name(part) in found
                                else shown_in.get(part, []))


# --- the review page: scenes, sheets, BOM and facts in one offline HTML file ------------------
def review_sources(run: Run) -> tuple[list[str], list[tuple[str, str]]]:
    """(scene names, array first; (sheet path, title) of every drawing, the assembly last)."""
    names = sorted(run.scenes, key=lambda n: n != "array")
    parts, _ = fabricated_parts(run.project, run.inventory)
    sheets = [(drawing_name(s.name), f"{s.name} (fabrication drawing)") for s in parts]
    return names, sheets + [(ASSEMBLY_DRAWING, "array (assembly drawing)")]


def review_contents_of(run: Run, *folders: Path):
    """The review page's contents (:class:`~tactcad.export.review_page.ReviewContents`)
    from the scenes, sheets and BOM in ``folders`` (each file from the first
    folder that has it: a run's staging folder, an export)."""
    import json

    from tactcad.drawings.compose import revision_and_date
    from tactcad.export.atlas_view import atlas_view
    from tactcad.export.book_paths import BOOK_DATA
    from tactcad.export.manifest import design_facts
    from tactcad.export.review_assets import three_version
    from tactcad.export.review_page import review_contents
    from tactcad.studies.reference_loads import strength_summary

    def found(rel: str) -> Path | None:
        return next((f / rel for f in folders if (f / rel).is_file()), None)

    names, sheet_list = review_sources(run)
    glbs = {n: glb.read_bytes() for n in names if (glb := found(scene_glb_name(n)))}
    sheets = [(p, t, svg.read_text(encoding="utf-8")) for p, t in sheet_list if (svg := found(p))]
    bom = found("bom.csv")
    book = found(BOOK_DATA)
    rev, date = revision_and_date(run.plan)
    facts = design_facts(run.plan)
    return review_contents(facts, sheets, glbs,
                           bom.read_text(encoding="utf-8-sig") if bom else "",
                           strength_summary(run.plan), rev, date, three_version(),
                           json.loads(book.read_text(encoding="utf-8")) if book else (),
                           atlas_view(run.plan.source, design_targets(facts)))


def design_targets(facts: dict) -> tuple[float, float, float] | None:
    """(rated full-scale force N, K_obj low, high N/mm) the design's requirements state, for
    its mark on the atlas; None where it states no K_obj range."""
    values = (facts.get("requirements") or {}).get("values") or {}
    force, kobj = values.get("full_scale_force_N"), values.get("kobj_range_N_per_mm")
    if force is None or not kobj:
        return None
    return float(force), float(kobj[0]), float(kobj[1])


def review_page_jobs(run: Run, before: list[Job]) -> list[Job]:
    """``review/index.html`` from the files of the jobs before it (its key holds theirs)."""
    from tactcad.export.atlas_view import atlas_identity
    from tactcad.export.review_assets import assets_identity

    def make(run: Run) -> list[dict]:
        from tactcad.export.review_assets import import_map
        from tactcad.export.review_page import REVIEW_PAGE, write_review_page

        contents = review_contents_of(run, run.staging)
        size = write_review_page(run.staging / REVIEW_PAGE, contents, import_map())
        run.log(f"  wrote {REVIEW_PAGE} ({size / 1e6:.1f} MB: {len(contents.scenes)} scenes, "
                f"{len(contents.data['sheets'])} sheets)")
        return [{"path": REVIEW_PAGE, "part": "review", "kind": "review-page",
                 "scenes": len(contents.scenes), "sheets": len(contents.data["sheets"])}]
    return [Job("review:page", content_key("review-page", [j.key for j in before],
                                           assets_identity(), atlas_identity(run.plan.source)),
                make, after=tuple(j.name for j in before), prepare=_review_facts)]


def _review_facts(run: Run) -> None:
    """The review page's design facts (cached per plan): they read no file, so they are
    worked out while the drawings are still being made."""
    from tactcad.export.manifest import design_facts

    design_facts(run.plan)
