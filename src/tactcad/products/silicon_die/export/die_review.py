"""A die's export as every product's export ends: ``manifest.json`` (every file with its
sha256, the design's name and hash, the versions) and ``review/index.html``, the one offline
review page the arrays have (:mod:`tactcad.export.review_page`): the die on its carrier in
the jaw in 3D, its drawing, its bill of materials, each row's beam as a sensing element
(K, root stress), its verification matrix and K_obj budget, and ``tactcad check``'s results
once a check has run.

Units: the die's dimensions in um, the mount's solids in mm (as the STEP), N/mm, N, MPa.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from pathlib import Path
from types import SimpleNamespace
from typing import Any, Mapping

from tactcad.atomic import file_sha256

#: The product the die's manifest and page name.
PRODUCT_NAME = "silicon-die"
#: The scene of the die on its carrier in the jaw's face pocket, as the page lists it.
SCENE = "die_in_jaw"


def design_head(name: str, source: Mapping[str, Any] | None) -> dict:
    """The manifest's and page's head: the design's name, file and sha256 (the die asked by
    options has no file: its plan's own hash stands for it), the versions, the units."""
    from tactcad.store import stack_versions
    from tactcad.version import VERSION

    source = dict(source or {})
    return {"design": {"name": name, "source": source.get("source"),
                       "sha256": source.get("sha256")
                       or hashlib.sha256(name.encode("utf-8")).hexdigest(),
                       "overrides": source.get("overrides", {})},
            "product": PRODUCT_NAME, "tactcad_version": VERSION,
            "cad_stack": stack_versions(), "units": "um (the die), mm (the mount's STEP)"}


def assumptions_section(assumptions) -> dict:
    """The manifest's ``assumptions`` section of a die, in an array's layout
    (:func:`tactcad.export.manifest.assumptions_section`: one ``{"field", "reason"}`` each),
    from its design file's reasons as shown
    (:func:`tactcad.products.silicon_die.design.die_file.die_assumptions`: a reason a hand
    edit left stale says so); nothing for a die asked by options or a file without them.

    Args:
        assumptions: (key, text) pairs.

    Returns:
        ``{"assumptions": [...]}``, or ``{}`` without reasons.
    """
    rows = [{"field": key, "reason": why} for key, why in assumptions]
    return {"assumptions": rows} if rows else {}


def die_manifest(head: Mapping[str, Any], folder: Path, files: Mapping[str, str],
                 facts: Mapping[str, Any]) -> dict:
    """The die's ``manifest.json``: ``head`` (:func:`design_head`), every written file
    (``files``: kind -> path relative to ``folder``) with its sha256 and size, then ``facts``.

    Raises:
        OSError: a listed file cannot be read.
    """
    listed = [{"path": rel, "kind": kind, "sha256": file_sha256(folder / rel),
               "bytes": (folder / rel).stat().st_size} for kind, rel in sorted(files.items())]
    return {**head, "files": listed, **facts}


def die_manifest_sections(plan, verification: list[dict],
                          budget: Mapping[str, Any]) -> dict:
    """The sections an array's manifest carries, in its layout, for the die: its
    ``requirements`` (the verification matrix as ``closed_form_matrix``; the die's targets
    are its own record, ``die``,
    each beam's ``first_resonance``: Hz, Rayleigh's, on its frame with its post, as ``tactcad
    modal`` gives it) and its ``kobj_budget`` (``tactcad budget``'s record), so that one
    script reads every product's manifest the same way.

    Args:
        plan: the die (``DiePlan``). verification: its verification matrix (one record per
            requirement). budget: its K_obj budget as JSON.

    Returns:
        {"requirements": {...}, "kobj_budget": {...}}.
    """
    from tactcad.products.silicon_die.mechanics.die_dynamics import first_resonance_Hz

    rows = [{"row": b.row, "role": b.role, "first_Hz": first_resonance_Hz(plan, b)}
            for b in plan.beams[:: plan.columns]]
    return {"requirements": {
        "closed_form_matrix": list(verification),
        "first_resonance": {"model": "closed-form", "elements": rows,
                            "lowest_first_Hz": min(r["first_Hz"] for r in rows)}},
        "kobj_budget": dict(budget)}


def write_scene_glb(solids: Mapping[str, tuple[Any, tuple]], path: Path, name: str) -> int:
    """The mount's solids (:func:`tactcad.products.silicon_die.export.die_scene.mount_solids`: part name ->
    (solid in mm, colour)) as one binary glTF scene (:func:`tactcad.export.glb.write_glb`),
    each part one instance at its place; returns the triangle count.

    Raises:
        OSError: the file cannot be written.
    """
    from tactcad.export.glb import write_glb
    from tactcad.kernel.locations import offset
    from tactcad.solids.tessellation import tessellate

    specs = {part: SimpleNamespace(color=tuple(rgb), kind="die" if part.startswith(name)
                                   else "mount", material="", attributes={})
             for part, (_, rgb) in solids.items()}
    here = offset(0.0, 0.0, 0.0)
    scene = SimpleNamespace(
        name=name, spec=SimpleNamespace(rig="grasper jaw"), specs=specs,
        parts=lambda: specs,
        instances=[SimpleNamespace(name=part, part=part, group=specs[part].kind, level=0,
                                   location=here) for part in solids])
    meshes = {part: tessellate(solid, 0.002) for part, (solid, _) in solids.items()}
    return write_glb(path, scene, meshes)


def beam_elements(strength: Mapping[str, Any], stiffness: Mapping[str, Any]) -> list[dict]:
    """Each row's beam as the page's element table shows an array's elements, named as the
    die's other commands name it (its ``row`` and ``role``): K (N/mm), root stress per
    newton and at the force the row carries in use (MPa), that force (``rated_force_N``, N:
    the row's own, not the die's full-scale force), the strength of etched silicon over
    that stress (silicon is brittle: no yield), from the die's ``strength`` and
    ``stiffness`` reports (one row each).

    Args:
        strength: :func:`tactcad.products.silicon_die.studies.die_reports.strength_report`'s
            report.
        stiffness: the die's stiffness report (``rows``, each with its ``role`` and
            ``stiffness_N_per_mm``).

    Returns:
        One record a row, keyed ``row`` (1, 2) and ``role`` (reference, measuring).
    """
    k_of = {r["role"]: r for r in stiffness["rows"]}
    return [{"row": r["row"], "role": r["role"], "part_name": f"{r['role']} beam",
             "arm_length_mm": r["length_um"] / 1e3,
             "stiffness_N_per_mm": k_of[r["role"]]["stiffness_N_per_mm"],
             "rated_force_N": r["rated_force_N"],
             "stress_MPa_per_N": r["root_peak_stress_MPa_per_N"],
             "stress_MPa_at_rated_force": r["root_peak_stress_MPa_at_rated_force"],
             "strength_over_stress_at_rating": r["strength_over_stress"],
             "model": strength["model"]} for r in strength["rows"]]


def budget_table(budget: Mapping[str, Any]) -> dict | None:
    """The die's K_obj budget (:meth:`tactcad.products.silicon_die.in_use.die_budget.DieBudget.as_json`) as the
    page's one-table section (title, columns, rows), or None when it has no terms."""
    terms = budget.get("terms_rel") or {}
    if not terms:
        return None
    ks = budget.get("k_obj_N_per_mm") or []
    columns = ["term", *[f"K_obj {k:.3g} N/mm" for k in ks], "why"]
    reasons = budget.get("reasons") or {}

    def pct(v) -> str:
        return f"{100 * v:.3g} %" if isinstance(v, (int, float)) and math.isfinite(v) \
            else "unreadable"

    rows = [{"term": term, **{c: pct(v) for c, v in zip(columns[1:-1], values)},
             "why": reasons.get(term, "")} for term, values in terms.items()]
    if budget.get("rss_rel"):
        rows.append({"term": "root sum square", **{c: pct(v) for c, v in
                                                   zip(columns[1:-1], budget["rss_rel"])},
                     "why": f"without {budget.get('rss_leaves_out', '')}"})
    return {"title": "K_obj error budget of the middle unit, relative, 1 sigma",
            "columns": columns, "rows": rows}


def traveller_book(steps) -> list[dict]:
    """The die's process traveller (:func:`tactcad.products.silicon_die.export.traveller.
    traveller_steps`) as the review page's build book: one step each, in process order,
    shown in the die's one scene (a wafer step adds no part to it, so nothing is
    highlighted or exploded), its mask as its tool, what is done, what stops it and what it
    leaves as its notes.

    Args:
        steps: the traveller's steps (each with ``name``, ``mask``, ``action``, ``stop``,
            ``leaves``, ``kinds``).

    Returns:
        The book's steps (``key``, ``title``, ``scene``, ``parts``, ``tools``, ``notes``,
        ``highlight``, ``explode``), as :func:`tactcad.export.review_page.review_contents`
        takes them.
    """
    return [{"key": f"traveller-{i}", "title": s.name, "scene": SCENE, "parts": [],
             "tools": [f"mask {s.mask}"] if s.mask else [],
             "notes": [f"{', '.join(s.kinds)}: {s.action}" if s.kinds else s.action,
                       *([f"stops on: {s.stop}"] if s.stop else []), f"leaves: {s.leaves}"],
             "highlight": [], "explode": {}}
            for i, s in enumerate(steps, start=1)]


def review_contents_of_die(head: Mapping[str, Any], verification: list[dict],
                           drawing: tuple[str, str], scene_glb: bytes, bom_csv: str,
                           elements: list[dict], budget: Mapping[str, Any],
                           atlas: dict | None = None, full_scale_force_N: float | None = None,
                           grasp: Mapping[str, Any] | None = None,
                           tissue_coupling: Mapping[str, Any] | None = None,
                           book: list[dict] | None = None):
    """The review page's contents (:class:`tactcad.export.review_page.ReviewContents`) of a
    die: ``drawing`` (export path, SVG text), the mount's GLB, the BOM's CSV text, the beams
    as elements (:func:`beam_elements`: each row with its own rated force), the die's
    full-scale force (N; the page's "rated full-scale force", None: not shown), the jaw's atlas (:mod:`tactcad.export.atlas_view`;
    None: none), the verification records
    (:func:`tactcad.products.silicon_die.studies.die_verification.die_verification`) and the K_obj budget; dated
    as the sheets are (``SOURCE_DATE_EPOCH``, else undated), never by the clock.

    The grasp (``tactcad grasp``'s record on the die), the tissue coupling
    (:func:`tactcad.products.silicon_die.studies.die_verification.die_tissue_coupling_record`) and
    the build book (:func:`traveller_book`) go through the page's own sections, as an
    array's do; one not given is shown as a line saying why, never hidden."""
    from tactcad.drawings.frame import epoch_date
    from tactcad.export.review_assets import three_version
    from tactcad.export.review_page import review_contents

    facts = {**head, "requirements": {"closed_form_matrix": verification},
             "grasp": dict(grasp) if grasp else {
                 "not_applicable": "no grasp was computed for this die: `tactcad grasp` on "
                                   "its design file closes its jaw on tissue"},
             "tissue_coupling": dict(tissue_coupling) if tissue_coupling else {
                 "not_applicable": "no tissue coupling was computed for this die: `tactcad "
                                   "budget` on its design file gives its tissue terms"}}
    contents = review_contents(facts, [(drawing[0], "the die and its carrier", drawing[1])],
                               {SCENE: scene_glb}, bom_csv, elements, "A",
                               epoch_date(os.environ) or "\u2014", three_version(),
                               book or (), atlas=atlas)
    contents.data["kobj_budget"] = budget_table(budget)
    contents.data["full_scale_force_N"] = full_scale_force_N
    return contents


def manifest_text(manifest: Mapping[str, Any]) -> str:
    """The manifest as written: JSON, sorted within each record as built, finite numbers."""
    return json.dumps(manifest, indent=1, allow_nan=False) + "\n"
