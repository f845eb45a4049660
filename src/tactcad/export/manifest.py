"""``manifest.json``: every file of an export with its sha256, the design's
hash, the versions of tactcad and its CAD stack, and one section per
registered source: the parts, the array assembly, the strength of every
element (with its row and column), the design's requirements, the thermal drift, the
derived values and assumptions, the values the design file states (``stated``), and
each export kind's own section (the DXF kind's ``shop``: every cut part's process, its
rules with their sources, tabs and cut order).

The sections are a registry (:data:`MANIFEST_SECTIONS`, as the export kinds
and check groups are): each names the function that makes it, imported only
when the manifest is made, so this module names no room; a new section is one
:func:`register_section`, an export kind's section its
:attr:`~tactcad.export.kinds.ExportKind.manifest_section`.
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any, Mapping

from tactcad.version import VERSION
from tactcad.design.array_plan import Plan
from tactcad.atomic import file_sha256
from tactcad.store import stack_versions


@dataclass(frozen=True)
class ManifestSection:
    """One section of the manifest.

    Attributes:
        key: its key in ``manifest.json``.
        function: ``"module:function"``, ``function(plan)`` -> the section's
            JSON value, or None to leave the section out for that design.
    """

    key: str
    function: str

    def of(self, plan: Plan) -> Any:
        """The section's value for ``plan`` (its module imported now)."""
        module, name = self.function.split(":")
        return getattr(importlib.import_module(module), name)(plan)


#: The design's sections in the manifest's order (the export kinds' follow them).
MANIFEST_SECTIONS: dict[str, ManifestSection] = {}


def register_section(section: ManifestSection) -> None:
    """Add a section to every manifest (after the others).

    Raises:
        ValueError: the key is taken.
    """
    if section.key in MANIFEST_SECTIONS or section.key in HEAD or section.key in WRITTEN_BY_RUN:
        raise ValueError(f"a manifest section {section.key!r} is registered already")
    MANIFEST_SECTIONS[section.key] = section


def manifest_sections() -> list[ManifestSection]:
    """The registered sections, then each export kind's
    (:attr:`~tactcad.export.kinds.ExportKind.manifest_section`), in order."""
    from tactcad.export.kinds import EXPORT_KINDS

    kinds = [ManifestSection(*k.manifest_section) for k in EXPORT_KINDS.values()
             if k.manifest_section is not None]
    return list(MANIFEST_SECTIONS.values()) + kinds


#: The keys that come before the files.
HEAD = ("design", "product", "tactcad_version", "cad_stack", "units")
#: The keys the export run writes itself: the files, what the export was made from
#: (:func:`tactcad.export.jobs.export_inputs`) and the files a failed program left out
#: (``not_written``: :func:`tactcad.export.freecad_review.not_written_record`).
WRITTEN_BY_RUN = ("files", "inputs", "not_written")


def manifest(plan: Plan, out_dir: Path, records: list[dict]) -> dict:
    """The manifest: every file with its sha256, its part, the design hash, the stack."""
    files = []
    for r in records:
        p = out_dir / r["path"]
        files.append({**r, "sha256": file_sha256(p), "bytes": p.stat().st_size})
    facts = design_facts(plan)
    return {**{k: facts[k] for k in HEAD}, "files": files,
            **{k: v for k, v in facts.items() if k not in HEAD}}


@lru_cache(maxsize=4)
def design_facts(plan: Plan) -> dict:
    """The manifest without its files: computed once per plan (the requirements'
    verification matrix alone takes about 0.2 s, and a run, the review page
    and ``tactcad watch``'s preview all ask for it) and kept in the result store
    (:func:`tactcad.store.kept_result`), so an export of an unchanged design reads it
    back instead of solving the tissue coupling and the K_obj budget again. Shared:
    read it, do not change it.

    Args:
        plan: the validated design.

    Returns:
        the manifest's keys but ``files``, in the manifest's order.
    """
    from tactcad.store import kept_result

    # the file's name is a field a plan's key leaves out, yet the head shows it; the sections
    # registered (a plugin may add one) shape the facts as much as the design does
    sections = [(s.key, s.function) for s in manifest_sections()]
    return kept_result("manifest facts", lambda: _facts_of(plan), plan, Path(plan.source).name,
                       plan.design_hash, sections)


def _facts_of(plan: Plan) -> dict:
    """:func:`design_facts` worked out (every section's function run)."""
    from tactcad.products import products

    head = {
        # the file's name only: an export names files relative to the project
        # folder, never by a path of the machine it was made on
        "design": {"name": plan.name, "source": Path(plan.source).name,
                   "sha256": plan.design_hash},
        # named as every product's manifest names it, so one script reads each kind's
        "product": next(p.name for p in products() if p.is_default),
        "tactcad_version": VERSION,
        "cad_stack": stack_versions(),
        "units": "mm",
    }
    sections = {s.key: s.of(plan) for s in manifest_sections()}
    # a section with nothing to say for this design (None) is left out
    return {**head, **{k: v for k, v in sections.items() if v is not None}}


# --- the built-in sections ------------------------------------------------------
def parts_section(plan: Plan) -> dict:
    """Every part of the array: kind, process, material, quantity, volume, box."""
    from tactcad.assembly.inventory import instance_counts
    from tactcad.catalogue.array_catalogue import array_instances, array_parts

    counts = instance_counts(array_instances(plan))
    return {n: _part_record(s, counts.get(n, 0)) for n, s in array_parts(plan).items()}


def assemblies_section(plan: Plan) -> dict:
    """The array assembly: its STEP file, instance count and review."""
    from tactcad.assembly.inventory import assembly_review
    from tactcad.catalogue.array_catalogue import array_instances, array_parts
    from tactcad.catalogue.files import ARRAY_STEP

    inst = array_instances(plan)
    return {"array": {"file": ARRAY_STEP, "instances": len(inst),
                      **assembly_review(array_parts(plan), inst)}}


def strength_section(plan: Plan) -> list[dict]:
    """Every element's strength at the rated full-scale force (:func:`_strength_record`)."""
    from tactcad.studies.reference_loads import strength_summary

    return [_strength_record(r, plan.element(r["element"]))
            for r in strength_summary(plan)]


def requirements_section(plan: Plan) -> dict:
    """The requirements and their verification at the closed form, in the array's envelope."""
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.studies.verification import requirements_record

    return requirements_record(plan, array_envelope_mm(plan))


def thermal_section(plan: Plan) -> dict | None:
    """The closed-form thermal drift of every element (:mod:`tactcad.mechanics.thermal_drift`);
    None when the material's CTE is unknown. The run time is left out (the manifest is
    compared across runs)."""
    from tactcad.errors import DesignError
    from tactcad.mechanics.thermal_drift import thermal_report
    from tactcad.studies.verification import requirements_of

    try:
        out = thermal_report(plan, requirements_of(plan)).as_json()
    except DesignError:
        return None
    out.pop("seconds")
    return out


def kobj_budget_section(plan: Plan) -> dict | None:
    """The closed-form K_obj error budget (:mod:`tactcad.in_use.kobj_budget`) at the
    full-scale force and the default temperature step over the required K_obj range;
    None when a source cannot be evaluated (no CTE known for the material)."""
    from tactcad.errors import DesignError
    from tactcad.in_use.kobj_budget import DEFAULT_DELTA_T_K, kobj_budget
    from tactcad.studies.verification import calibration_gauge
    from tactcad.studies.verification import requirements_of

    req = requirements_of(plan)
    try:
        return kobj_budget(plan, req.kobj_range_N_per_mm, req.full_scale_force_N,
                           DEFAULT_DELTA_T_K, force_gauge=calibration_gauge(plan),
                           readable_within_rel=req.kobj_resolution_rel).as_json()
    except DesignError:
        return None


#: Significant digits kept of a figure that comes out of a linear solve (the tissue and the
#: grasp): another numpy build or thread count changes its last bits, never these.
SOLVE_DIGITS = 10


def significant(value, digits: int = SOLVE_DIGITS):
    """``value`` with every float (in lists and dicts too) to ``digits`` significant digits;
    non-finite floats and other values as they are."""
    if isinstance(value, float):
        return float(f"{value:.{digits}g}") + 0.0 if math.isfinite(value) else value  # no -0.0
    if isinstance(value, dict):
        return {k: significant(v, digits) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [significant(v, digits) for v in value]
    return value


def tissue_coupling_section(plan: Plan) -> dict:
    """The K_obj bias the tissue coupling causes per unit over the required K_obj range, by
    eq. 3 and by the coupled inversion, judged against the K_obj resolution
    (:func:`tactcad.studies.verification.tissue_coupling_record`, as verify prints it)."""
    from tactcad.studies.verification import requirements_of, tissue_coupling_record

    return significant(tissue_coupling_record(plan, requirements_of(plan)))


def grasp_section(plan: Plan) -> dict | None:
    """The grasp at the design's ``max_grasp_force_N`` (its verify record: every element's
    force on its spring against its overload limit, the grasp's summary, the jaw and tissue assumed);
    None when the design states no maximum grasp force."""
    from tactcad.studies.verification import (element_figures, max_grasp_force_record,
                                              requirements_of)

    fig = element_figures(plan)
    return significant(max_grasp_force_record(plan, fig, requirements_of(plan, fig)))


def derived_section(plan: Plan) -> list[dict]:
    """The plan's derived values, each with its reason."""
    return [{"name": d.name, "value": d.value, "unit": d.unit, "reason": d.reason}
            for d in plan.derived]


def assumptions_section(plan: Plan) -> list[dict]:
    """The design file's assumptions."""
    return [{"field": k, "reason": v} for k, v in plan.assumptions]


def _strength_record(r: dict, slot=None) -> dict:
    """An element's place in the array (``row`` and ``column``, 1-based, from its ``slot``;
    the diff pairs elements by them), its arm, stiffness K, yield-limited force, its
    fatigue limits (the material's at the notch, ``fatigue_force_N``, None without a fatigue
    strength, and the gauge's, ``gauge_fatigue_force_N``; N, as ``strength --json`` names
    them), and its safety factor, gauge strain and tip deflection at the design's rated
    full-scale force (``full_scale_force_N``, the same for every element) for the manifest
    (closed form).

    Args:
        r: the element's strength summary record.
        slot: its :class:`~tactcad.design.array_plan.ElementSlot` (None: no place recorded).

    Returns:
        the manifest's record of the element.
    """
    keys = ("element", "part_name", "arm_length_mm", "model", "stiffness_N_per_mm",
            "stress_MPa_per_N", "full_scale_force_N", "yield_limited_force_N",
            "fatigue_force_N", "gauge_fatigue_force_N",
            "yield_safety_factor_at_full_scale", "gauge_strain_at_full_scale",
            "tip_deflection_mm_at_full_scale", "warnings")
    record = {k: r[k] for k in keys}
    if slot is None:
        return record
    return {"element": record["element"], "row": slot.row + 1, "column": slot.column + 1,
            **record}


#: The design file's tables the ``stated`` section leaves out: the reasons for the values
#: (``[assumptions]``, kept in their own section) and where the companion files lie.
UNSTATED_TABLES = ("assumptions", "files")


def stated_section(plan: Plan) -> dict[str, Any]:
    """The values the design file states, by dotted key (``comb.web_thicknesses_mm``), as
    the plan read them, so ``tactcad diff`` names the design values that were edited, as a
    die's ``[die]`` keys. A material grade's E and nu where the file leaves them out are not
    stated (:attr:`Plan.from_grade`): ``material.grade`` names that change.

    Args:
        plan: the validated design (its ``raw`` tables).

    Returns:
        {dotted key: value}: numbers, texts and lists as in the file (units as the key's
        name says: mm, N, MPa, N/mm ...), tables flattened, other values as text;
        :data:`UNSTATED_TABLES` and the grade's values left out.
    """
    grade = {f"material.{k}" for k in getattr(plan, "from_grade", ())}
    stated = flat_tables({k: v for k, v in plan.raw.items() if k not in UNSTATED_TABLES})
    return {k: v for k, v in stated.items() if k not in grade}


def flat_tables(table: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """``table``'s values by dotted key, nested tables flattened, each value JSON's own
    (a TOML date or time as its ISO text).

    Args:
        table: design tables, as a TOML file reads.
        prefix: the dotted key of ``table`` itself, with its dot ("" at the top).

    Returns:
        {dotted key: value}, in the tables' order.
    """
    out: dict[str, Any] = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(flat_tables(value, name + "."))
        else:
            out[name] = _json_value(value)
    return out


def _json_value(value: Any) -> Any:
    """``value`` as JSON holds it: numbers, texts, booleans and lists of them as they are,
    tables as tables, anything else (a TOML date) as text."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, (list, tuple)):
        return [_json_value(v) for v in value]
    if isinstance(value, Mapping):
        return {str(k): _json_value(v) for k, v in value.items()}
    return value.isoformat() if hasattr(value, "isoformat") else str(value)


def left_out_section(plan: Plan) -> list[dict[str, str]] | None:
    """What this export leaves out and why: the decoupling files and the K_obj budget's
    crosstalk term where no crosstalk level describes the construction
    (:func:`tactcad.mechanics.crosstalk_ladder.crosstalk_reason`), then what the
    construction does not declare (:func:`tactcad.design.construction_registry.left_out`);
    None (no section) when it leaves nothing out."""
    from tactcad.design.construction_registry import left_out
    from tactcad.mechanics.crosstalk_ladder import crosstalk_reason

    why = crosstalk_reason(plan)
    crosstalk = [{"what": "crosstalk/decoupling.csv, crosstalk/decoupling.json and the K_obj "
                          "budget's crosstalk term", "reason": why}] if why else []
    return [*crosstalk, *left_out(plan)] or None


def _part_record(spec, count: int) -> dict:
    return {"kind": spec.kind, "process": spec.process, "material": spec.material,
            "quantity": count, "volume_mm3": spec.expected_volume_mm3,
            "bbox_mm": list(spec.expected_bbox_mm)}


for _key, _function in (("parts", "parts_section"), ("assemblies", "assemblies_section"),
                        ("strength", "strength_section"),
                        ("requirements", "requirements_section"),
                        ("thermal", "thermal_section"), ("kobj_budget", "kobj_budget_section"),
                        ("tissue_coupling", "tissue_coupling_section"),
                        ("grasp", "grasp_section"),
                        ("derived", "derived_section"),
                        ("assumptions", "assumptions_section"),
                        ("left_out", "left_out_section"),
                        ("stated", "stated_section")):
    register_section(ManifestSection(_key, f"{__name__}:{_function}"))
