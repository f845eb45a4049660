"""A die's export as jobs: each file (or pair of files) one :class:`~tactcad.export.job.Job`
with the content key of what shapes its bytes, run by the export's own
:func:`~tactcad.export.run.run_jobs` against the store of finished jobs, as an array's are.

The keys are narrower than the die's plan where a file reads less of it: the die's STEP and
its scene in the jaw read the layer solids' inputs
(:func:`~tactcad.products.silicon_die.export.die_solid.die_layer_inputs`: the masks'
outlines and the stack's heights) and the mount, not the read-out, so a change of the
die's requirements, read-out or strength table builds no solid (nor loads the CAD
kernel); a change of the jaw builds the scene and keeps the die's STEP and masks. The
masks, the wafer, the traveller, the drawing and the bill of materials read the whole plan.

Order: the masks (GDS) and their picture, the wafer, the die's STEP, the scene in the jaw
(STEP, picture, glTF), the bill of materials, the drawing, the traveller. The record, the
review page and the manifest read them all and the analyses, and are written after them by
the command (:mod:`tactcad.commands.die`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any, Callable

from tactcad.export.job import Job
from tactcad.products.silicon_die.design.mems_die import DiePlan
from tactcad.store import Store, content_key


@dataclass
class DieRun:
    """What the jobs of one die export share: the plan, its mount in the jaw, the staging
    folder and the files' names in it (``names``: role -> path relative to the export
    folder, :data:`tactcad.commands.die.DIE_FILES`); the solids are built on first use,
    so a run whose solid jobs all come from the store never loads the CAD kernel."""

    plan: DiePlan
    mount: Any  # tactcad.products.silicon_die.design.die_mount.DieMount
    jaw_label: str
    staging: Path
    names: dict[str, str]
    store: Store = field(default_factory=lambda: Store(None))
    log: Callable[[str], None] = lambda line: None
    worker_made: list[str] = field(default_factory=list)  # run_jobs' record; a die has none

    def path(self, role: str) -> Path:
        """The staging path of the file of ``role``."""
        return self.staging / self.names[role]

    def record(self, role: str, kind: str) -> dict:
        """The job record of the file of ``role`` (``path`` relative to the export)."""
        return {"path": self.names[role], "part": self.plan.name, "kind": kind}

    @cached_property
    def layer_inputs(self) -> dict:
        """:func:`~tactcad.products.silicon_die.export.die_solid.die_layer_inputs` (kernel-free)."""
        from tactcad.products.silicon_die.export.die_solid import die_layer_inputs

        return die_layer_inputs(self.plan)

    @cached_property
    def layers(self) -> dict:
        """The die's layer solids (mm; imports the CAD kernel)."""
        from tactcad.products.silicon_die.export.die_solid import die_layer_solids

        return die_layer_solids(self.plan, self.layer_inputs)

    @cached_property
    def solids(self) -> dict:
        """The mount's solids, the die's layers placed in the jaw's pocket (mm)."""
        from tactcad.products.silicon_die.export.die_scene import mount_solids

        return mount_solids(self.plan, self.mount, self.layers)

    @cached_property
    def scene_inputs(self) -> tuple:
        """What the scene's solids are made from: the die's name and layer inputs, the mount."""
        return (self.plan.name, self.layer_inputs, self.mount.as_json())

    @cached_property
    def readout(self) -> dict:
        """The die's read-out (:func:`~tactcad.products.silicon_die.mechanics.piezoresistor.die_readout`)."""
        from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout

        return die_readout(self.plan)

    @cached_property
    def budget(self):
        """The die's K_obj budget (:func:`~tactcad.products.silicon_die.in_use.die_budget.die_budget`)."""
        from tactcad.products.silicon_die.in_use.die_budget import die_budget

        return die_budget(self.plan, self.readout)


def die_jobs(run: DieRun) -> list[Job]:
    """Every file job of a die's export, in the order of the module's docstring.

    Args:
        run: the export's :class:`DieRun`.

    Returns:
        Jobs for :func:`tactcad.export.run.run_jobs`; the wafer's record carries ``dies``
        (the dies on the wafer).
    """
    plan = run.plan
    whole = plan.as_json()
    mount = run.mount.as_json()
    names = run.names
    drawing_post = _drawing_post_height(run)
    masks_key = content_key("die-gds", whole, names["masks"])

    def job(name: str, key: str, make: Callable[[], list[dict]], after: tuple = ()) -> Job:
        def logged(_run) -> list[dict]:
            records = make()
            run.log("  wrote " + ", ".join(r["path"] for r in records))
            return records

        return Job(name, key, logged, after=after)

    return [
        job("gds:masks", masks_key, lambda: _masks(run)),
        job("png:masks", content_key("die-mask-picture", masks_key, names["picture"]),
            lambda: _mask_picture(run), after=("gds:masks",)),
        job("gds:wafer", content_key("die-wafer", whole, names["wafer"]), lambda: _wafer(run)),
        job("step:die", content_key("die-step", plan.name, run.layer_inputs, names["step"]),
            lambda: _die_step(run)),
        job("step:scene", content_key("die-scene-step", run.scene_inputs, names["scene"]),
            lambda: _scene_step(run)),
        job("png:scene", content_key("die-scene-picture", run.scene_inputs, run.jaw_label,
                                     names["scene_picture"]), lambda: _scene_picture(run)),
        job("glb:scene", content_key("die-scene-glb", run.scene_inputs, names["glb"]),
            lambda: _scene_glb(run)),
        job("csv:bom", content_key("die-bom", whole, mount, run.jaw_label, names["bom"]),
            lambda: _bom(run)),
        job("svg:drawing", content_key("die-drawing", whole, mount, drawing_post,
                                       names["drawing"]), lambda: _drawing(run, drawing_post)),
        job("md:traveller", content_key("die-traveller", whole,
                                        run.readout["sheet_resistance_ohm_per_sq"],
                                        names["masks"], names["traveller"]),
            lambda: _traveller(run)),
    ]


def _drawing_post_height(run: DieRun):
    from tactcad.products.silicon_die.in_use.die_budget import post_height_drawing

    return post_height_drawing(run.budget)


def _masks(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.gds_masks import write_die_gds

    write_die_gds(run.plan, run.path("masks"))
    return [run.record("masks", "gds")]


def _mask_picture(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.gds_masks import write_mask_picture

    write_mask_picture(run.path("masks"), run.path("picture"))
    return [run.record("picture", "png")]


def _wafer(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.gds_masks import write_wafer_gds

    _, dies = write_wafer_gds(run.plan, run.path("wafer"))
    return [dict(run.record("wafer", "gds"), dies=dies)]


def _die_step(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.die_solid import write_die_step

    write_die_step(run.plan, run.path("step"), run.layers)
    return [run.record("step", "step")]


def _scene_step(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.die_scene import write_mount_step

    write_mount_step(run.solids, run.path("scene"), f"{run.plan.name}_in_jaw")
    return [run.record("scene", "step")]


def _scene_picture(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.die_scene import write_mount_picture

    write_mount_picture(run.solids, run.path("scene_picture"),
                        f"{run.plan.name} in the {run.jaw_label}")
    return [run.record("scene_picture", "png")]


def _scene_glb(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.die_review import write_scene_glb

    run.path("glb").parent.mkdir(parents=True, exist_ok=True)
    write_scene_glb(run.solids, run.path("glb"), f"{run.plan.name}_in_jaw")
    return [run.record("glb", "glb")]


def _bom(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.die_scene import mount_bom_rows, write_mount_bom

    write_mount_bom(mount_bom_rows(run.plan, run.mount, run.jaw_label), run.path("bom"))
    return [run.record("bom", "csv")]


def _drawing(run: DieRun, post_height) -> list[dict]:
    from tactcad.products.silicon_die.drawings.die_sheet import die_sheet

    run.path("drawing").write_text(die_sheet(run.plan, run.mount, post_height).svg(),
                                   encoding="utf-8")
    return [run.record("drawing", "svg")]


def _traveller(run: DieRun) -> list[dict]:
    from tactcad.products.silicon_die.export.traveller import write_traveller

    write_traveller(run.plan, run.readout["sheet_resistance_ohm_per_sq"],
                    Path(run.names["masks"]).name, run.path("traveller"))
    return [run.record("traveller", "md")]
