"""``review/index.html``: one page to review an export offline.

The page carries everything it shows, so it opens from ``file://`` with no
network and can be sent on its own: every scene's GLB (base64), every drawing
sheet (SVG), the BOM, each element's stiffness and strength, the manifest's
facts (design sha256, versions; a verification matrix when the manifest has
one) and three.js itself (:mod:`tactcad.export.review_assets`). The results
of ``tactcad check`` join it later as ``review/checks.js`` beside it
(:mod:`tactcad.checks.review_results`), shown only when they are for the same
design.

The page is written from the files the run wrote before it (nothing is built
again), with fixed key order, so the same export writes the same bytes.
"""

from __future__ import annotations

import base64
import csv
import hashlib
import html
import io
import json
import re
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Mapping, Sequence

from tactcad.atomic import write_bytes_atomic

REVIEW_PAGE = "review/index.html"
CHECKS_SCRIPT = "review/checks.js"


@lru_cache(maxsize=1)
def _template() -> tuple[str, str]:
    data = resources.files("tactcad") / "data"
    return ((data / "review_page.html").read_text(encoding="utf-8"),
            (data / "review_page.js").read_text(encoding="utf-8"))


def json_in_html(value) -> str:
    """JSON safe inside a ``<script>`` element (no ``</script>``, no ``<!--``)."""
    text = json.dumps(value, sort_keys=True, ensure_ascii=False, allow_nan=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def bom_table(csv_text: str) -> dict:
    """``bom.csv`` as ``{"columns": [...], "rows": [{column: text}]}``."""
    rows = list(csv.DictReader(io.StringIO(csv_text.lstrip("\ufeff"))))
    columns = list(rows[0]) if rows else []
    return {"columns": columns, "rows": rows}


@dataclass(frozen=True)
class ReviewContents:
    """What the review page shows, before it becomes one file.

    ``data`` is JSON-ready: the manifest's facts, revision, date, scene names,
    BOM, elements; each sheet as ``{"path", "title", "sha256"}`` and each
    scene's GLB named by its sha256 in ``scene_sha256``. The bytes are beside
    it: ``scenes`` (name -> GLB) and ``sheets`` (sha256 -> SVG, UTF-8).
    :func:`page_html` puts them all into the page; ``tactcad watch`` serves
    them on their own, so a browser fetches only what changed.
    """

    data: dict
    scenes: dict[str, bytes]
    sheets: dict[str, bytes]


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def review_contents(facts: dict, sheets: Sequence[tuple[str, str, str]],
                    scenes: Mapping[str, bytes], bom_csv: str, elements: list[dict],
                    revision: str, date: str, three_version: str,
                    book: Sequence[dict] = (), atlas: dict | None = None) -> ReviewContents:
    """What the page shows (see :class:`ReviewContents`).

    Args:
        facts: the manifest's facts (design, versions, parts, strength ...;
            any ``files`` key is left out; a ``verification`` key is shown as
            the verification matrix, else one is made from ``requirements``).
        sheets: (export path, title, SVG text) of every drawing sheet, in order.
        scenes: GLB bytes by scene name, in the order of the page's scene list.
        elements: :func:`tactcad.mechanics.element_strength.strength_summary` records.
        book: the build book's steps (``instructions/steps.json``: title, parts,
            notes, the scene, its new parts and each moving instance's explosion,
            mm); the page lists them and plays a step's explosion in its 3D view.
        atlas: the design atlas of the project's jaw
            (:func:`tactcad.export.atlas_view.atlas_view`), drawn with its points' hover
            texts and front; None: no atlas section.
    """
    manifest = {k: v for k, v in facts.items() if k != "files"}
    if "verification" not in manifest and manifest.get("requirements"):
        manifest["verification"] = verification_view(manifest["requirements"],
                                                      manifest.get("thermal"))
    svgs = {p: svg.encode("utf-8") for p, _, svg in sheets}
    data = {
        "manifest": manifest,
        "revision": revision, "date": date, "three_version": three_version,
        "scenes": list(scenes),
        "scene_sha256": {n: _sha256(glb) for n, glb in scenes.items()},
        "sheets": [{"path": p, "title": t, "sha256": _sha256(svgs[p])} for p, t, _ in sheets],
        "bom": bom_table(bom_csv), "elements": elements,
        "book": [step for step in book if step.get("scene") in scenes],
        "kobj_budget": kobj_budget_view(manifest.get("kobj_budget")),
        "tissue_coupling": tissue_coupling_view(manifest.get("tissue_coupling")),
        "grasp": grasp_view(manifest.get("grasp")),
        "atlas": atlas,
    }
    return ReviewContents(data, dict(scenes), {_sha256(b): b for b in svgs.values()})


def kobj_budget_view(budget: dict | None) -> dict | None:
    """The manifest's K_obj error budget as the page's table: one row per K_obj of the
    grid, read by the array's best unit there, each source's relative K_obj error after
    correction, the RSS, the worst case and the dominant source (texts with their units;
    ``columns`` in the order the page shows them); None without a budget or a unit."""
    if not budget or not budget.get("units"):
        return None
    from tactcad.in_use.kobj_budget import SOURCES

    def pct(x) -> str:
        return "unreadable" if x is None else f"{100 * x:.3g} %"

    units = {f"{u['reference_element']}/{u['measuring_element']}": u for u in budget["units"]}
    a = budget["array"]
    # the record's words: its crosstalk term named for the construction's own level
    said = {s.get("key"): s.get("words") for s in budget.get("sources", [])}
    words = {s.key: said.get(s.key) or s.words for s in SOURCES}
    columns = ["K_obj", "unit", *(words[s.key] for s in SOURCES), "RSS", "worst case",
               "dominant"]
    rows = []
    for i, k in enumerate(budget["K_obj_N_per_mm"]):
        u = units[a["unit"][i]]
        dominant = a["dominant"][i]
        rows.append({"K_obj": f"{k:.3g} N/mm", "unit": a["unit"][i],
                     **{words[s.key]: "not modelled" if "not_modelled" in u["sources"][s.key]
                        else pct(u["sources"][s.key]["after_rel"][i]) for s in SOURCES},
                     "RSS": pct(a["rss_rel"][i]), "worst case": pct(a["worst_case_rel"][i]),
                     "dominant": (words[dominant] if dominant == "crosstalk"
                                  else dominant.replace("_", " "))})
    title = (f"{budget['model']}, {budget['force_N']:.4g} N on the reference, "
             f"{budget['delta_T_K']:g} K step; relative K_obj error after correction, each "
             f"K_obj read by its best unit (reference/measuring element); tactcad budget "
             f"shows every unit and the figures before correction")
    return {"title": title, "columns": columns, "rows": rows}


def _signed_pct(x) -> str:
    return "no answer" if x is None else f"{100 * x:+.3g} %"


def tissue_coupling_view(record: dict | None) -> dict | None:
    """The manifest's tissue coupling record as the page's table: one row per sensing unit,
    its worst K_obj bias over the range by eq. 3 and by the coupled inversion (with the check
    level's error estimate on it), each with its verdict against the K_obj resolution (texts
    with their units); None without a unit."""
    from tactcad.in_use.tissue_coupling import unit_label

    if record and record.get("not_applicable"):
        return not_applicable_view(record["not_applicable"])
    if not record or not record.get("units"):
        return None
    eq3 = {tuple(it["unit"]): it for it in record["eq3"]["items"]}
    coupled = {tuple(it["unit"]): it for it in record["coupled"]["items"]}
    columns = ["unit", "coupling", "K_obj bias, eq. 3", "eq. 3", "K_obj bias, coupled inversion",
               "coupled inversion"]
    rows = []
    for u in record["units"]:
        key = tuple(u["unit"])
        rows.append({"unit": unit_label(key), "coupling": f"{u['coupling']:.3g}",
                     "K_obj bias, eq. 3": _signed_pct(eq3[key]["bias_rel"]),
                     "eq. 3": eq3[key]["verdict"].upper(),
                     "K_obj bias, coupled inversion": _signed_pct(coupled[key]["bias_rel"])
                     + _plus_minus_pct(coupled[key].get("bias_error_rel")),
                     "coupled inversion": coupled[key]["verdict"].upper()})
    title = (f"{record['tissue']}; worst K_obj bias over the K_obj range per unit "
             f"(reference/measuring element) against the {100 * record['target_rel']:.3g} % "
             f"K_obj resolution required (error estimate of the tissue model "
             f"{100 * record['eq3']['items'][0]['error_estimate_rel']:.3g} %)")
    return {"title": title, "columns": columns, "rows": rows}


def _plus_minus_pct(error_rel: float | None) -> str:
    """" +/- e %" of a bias's error estimate (relative), or nothing without one."""
    return "" if error_rel is None else f" \u00b1 {100 * error_rel:.2g} %"


def grasp_view(record: dict | None) -> dict | None:
    """The manifest's grasp at the maximum grasp force as the page's table: one row per
    element, its force on its spring, its stop's share, its rating, margin and verdict
    (texts with their units); None when the design states no maximum grasp force.

    A ``tactcad grasp`` record (any product's: its ``grasp`` holds the tips of the jaw
    closed on tissue, each element's force, stop share and rating) is shown with the same
    columns (:func:`grasp_tips_view`); a record ``{"not_applicable": why}`` as one line.

    Args:
        record: the manifest's ``grasp`` record, a grasp command's record, or None.

    Returns:
        The section's title, columns and rows, or None.
    """
    if record and record.get("not_applicable"):
        return not_applicable_view(record["not_applicable"])
    if record and "tips" in (record.get("grasp") or {}):
        return grasp_tips_view(record)
    if not record:
        return None
    columns = ["element", "force on its spring", "on the stop", "rating", "margin", "verdict"]
    rows = [{"element": str(it["element"]), "force on its spring": f"{it['element_force_N']:.4g} N",
             "on the stop": f"{it['stop_force_N']:.4g} N" if it["on_stop"] else "-",
             "rating": f"{it['rated_force_N']:.4g} N",
             "margin": "-" if it["margin_rel"] is None else f"{100 * it['margin_rel']:+.3g} %",
             "verdict": it["verdict"].upper()} for it in record.get("elements", [])]
    lay = (record.get("grasp") or {}).get("as_laid_out")
    at = (f"angle {lay['angle_deg']:.4g} degrees, largest element force "
          f"{lay['largest_element_force_N']:.4g} N (element {lay['largest_element']}), the "
          f"stops {lay['stop_force_N']:.4g} N; " if lay else "")
    title = (f"grasp force {record['target']:g} N: {record['verdict'].upper()}; {at}"
             f"{record['basis']}")
    return {"title": title, "columns": columns, "rows": rows}


def not_applicable_view(why: str) -> dict:
    """A section that does not apply to the product: shown as the one line ``why``, no table.

    Args:
        why: why the section does not apply (one sentence).

    Returns:
        The section's title (``why``) with no columns and no rows.
    """
    return {"title": str(why), "columns": [], "rows": []}


def grasp_tips_view(record: dict) -> dict:
    """A ``tactcad grasp`` record (its ``grasp``: the jaw closed on tissue, one tip per
    element) as the grasp section's table: each element's force on its spring (N), its
    stop's share (N), its rating (N), its margin to the rating (%) and its verdict (FAIL:
    past its overload limit; over rating: past its rating only).

    Args:
        record: the grasp command's record (``grasp`` with ``tips``, ``total_force_N``,
            ``angle_deg``; ``reasons`` and ``coupling`` where given).

    Returns:
        The section's title, columns and rows.
    """
    lay = record["grasp"]
    columns = ["element", "force on its spring", "on the stop", "rating", "margin", "verdict"]
    rows = []
    for t in lay["tips"]:
        rated = t.get("rated_force_N")
        margin = (None if not rated else 1.0 - t["element_force_N"] / rated)
        verdict = ("fail" if t.get("over_overload_limit") else
                   "over rating" if t.get("over_rating") else "pass")
        rows.append({"element": str(t["site"]),
                     "force on its spring": f"{t['element_force_N']:.4g} N",
                     "on the stop": f"{t['stop_force_N']:.4g} N" if t.get("on_stop") else "-",
                     "rating": "-" if rated is None else f"{rated:.4g} N",
                     "margin": "-" if margin is None else f"{100 * margin:+.3g} %",
                     "verdict": verdict.upper()})
    passed = record.get("passed", not any(t.get("over_overload_limit") for t in lay["tips"]))
    why = (record.get("reasons") or {}).get("force_N")
    title = (f"grasp force {lay['total_force_N']:.4g} N: {'PASS' if passed else 'FAIL'}; "
             f"angle {lay['angle_deg']:.4g} degrees"
             + (f", tissue coupling {record['coupling']}" if record.get("coupling") else "")
             + (f"; the force: {why}" if why else "") + "; tactcad grasp shows every unit")
    return {"title": title, "columns": columns, "rows": rows}


def verification_view(requirements: dict, thermal: dict | None = None) -> dict:
    """The manifest's requirements record as the page's verification section,
    read as ``tactcad verify`` prints it: one row per requirement (verdict,
    target, predicted with its error, margin, what binds, level), failures
    first, then undecided; the element force limits behind the rated full-scale force (the binding
    one marked); the stated or derived values; each element's first natural
    frequency; the thermal drift per kelvin (:func:`thermal_view`, when the manifest has
    it); and the requirements not met (the page's red banner)."""
    matrix = requirements.get("closed_form_matrix") or []
    order = {"fail": 0, "undecided": 1}
    rows = [verification_row(r) for r in sorted(
        matrix, key=lambda r: order.get(_verdict(r), 2))]
    limits = next((r["limits"] for r in matrix if r.get("limits")), [])
    view = {"verification matrix (closed form; tactcad verify --model auto decides the "
            "undecided)": rows,
            "element force limits behind the rated full-scale force": limits,
            "requirements": requirements.get("values", {})}
    if (requirements.get("first_resonance") or {}).get("elements"):
        view["first natural frequencies (closed form, in the sheet's plane)"] = \
            requirements["first_resonance"]["elements"]
    if thermal:
        view[THERMAL_VIEW_KEY] = thermal_view(thermal)
    unmet = unmet_requirements(requirements)
    if unmet:
        view["requirements not met"] = unmet
    return view


#: The verification section's heading of the thermal figures.
THERMAL_VIEW_KEY = ("thermal drift per kelvin (closed form, tactcad thermal; the K_obj zero part "
                    "scales as 1/F: full scale is the best case)")


def thermal_view(thermal: dict) -> dict:
    """The manifest's ``thermal`` record as the page shows it: the span per kelvin and its
    terms, the self-heating, the worst K_obj error per kelvin (element and force named), and
    per element zero, span, drift, self-heating offset and K_obj %/K at full scale and at the
    lowest force fraction."""
    low = min(thermal["force_fractions"])
    rows = [{"element": r["element"], "role": r["role"],
             "zero N/K": f"{r['zero_drift_N_per_K']:+.3g}",
             "span N/K (full scale)": f"{r['span_drift_N_per_K']:.3g}",
             "drift N/K": f"{r['drift_N_per_K']:.3g}",
             "self-heating offset N": f"{r['self_heating_offset_N']:+.3g}",
             "K_obj %/K at full scale": _pct(r["kobj_error_rel_per_K_at_full_scale"]),
             f"K_obj %/K at {100 * low:g} % of full scale": _pct(r["kobj_error_rel_per_K"])}
            for r in thermal["elements"]]
    worst = thermal.get("worst_kobj_element")
    return {"span per kelvin (ppm/K)": {k: f"{1e6 * v:+.4g}" for k, v in
                                        {**thermal["span_terms_rel_per_K"],
                                         "total": thermal["span_rel_per_K"]}.items()},
            "modulus coefficient sourced": thermal["setting"]["substrate_modulus_tc_sourced"],
            "lead wires": thermal["setting"]["lead_wires"],
            "self-heating": f"{thermal['self_heating_K']:.3g} K, "
                            f"{645.16 * thermal['grid_power_density_W_per_mm2']:.3g} W/in^2 "
                            f"in the grid (TN-502 thin sections: 1-2 W/in^2)",
            "worst K_obj error": None if worst is None else
            f"element {worst}: {_pct(thermal['worst_kobj_error_rel_per_K'])} %/K at "
            f"{100 * low:g} % of full scale",
            "elements": rows}


def _pct(rel: float | None) -> str:
    return "n/a" if rel is None else f"{100 * rel:.3g}"


def unmet_requirements(requirements: dict) -> list[str]:
    """The requirements a manifest's requirements record fails (verdict ``fail``
    at the closed form), in the matrix's order."""
    return [r["requirement"] for r in requirements.get("closed_form_matrix") or []
            if _verdict(r) == "fail"]


def _verdict(record: dict) -> str:
    """A record's verdict: ``info`` for a row reported, not judged (a manifest written before
    such rows said so in ``verdict`` marks them ``informational``)."""
    from tactcad.mechanics.verdicts import INFO

    if record.get("informational"):  # the design's own figure, reported, not judged
        return INFO
    return record.get("verdict", "pass" if record.get("pass") else "fail")


def verification_row(r: dict) -> dict:
    """One requirement as the page's table shows it (texts, in the CLI's columns;
    the page's script lists them in this order, ``VERIFY_COLUMNS``)."""
    from tactcad.studies.verification import (binding_text, margin_text, predicted_text,
                                              target_text)

    err = r.get("error_estimate_rel")
    shown = {**r, "verdict": _verdict(r)}  # a row reported, not judged: no target, no margin
    return {"requirement": r["requirement"], "verdict": verdict_cell(shown),
            "target": target_text(shown),
            "predicted": predicted_text(r)
            + ("" if err is None else f" \u00b1 {100 * err:.2g} %"),
            "margin": margin_text(shown),
            "binds": binding_text(r), "model": r.get("model", "")}


#: The verdict cell's words for a row the closed form leaves undecided and a higher ladder
#: level computes anew: verify's climb decides it (the page's script puts the decided verdict
#: of ``tactcad check`` there once ``review/checks.js`` holds it).
UNDECIDED_CLIMBS = "UNDECIDED at closed form; decided by `tactcad verify`"


def verdict_cell(record: dict) -> str:
    """A verification row's verdict as the page's table shows it: the verdict in capitals,
    and for a row undecided at the closed form that a higher level computes anew (not
    ``level_fixed``), :data:`UNDECIDED_CLIMBS`: the manifest's matrix is the closed form's,
    the verdict that counts the level ``tactcad verify`` (and ``tactcad check``) climbs to.

    Args:
        record: a verification record with its verdict (``info`` for a row not judged).

    Returns:
        The cell's text.
    """
    said = record["verdict"]
    if said == "undecided" and record.get("model") == "closed-form" \
            and not record.get("level_fixed", False):
        return UNDECIDED_CLIMBS
    return said.upper()


def page_html(contents: ReviewContents, import_map: str) -> str:
    """The page's text: the template with the data (each sheet's SVG inline,
    base64), the scenes (base64) and the import map in it."""
    page, script = _template()
    data = {**contents.data, "sheets": [
        {**sheet, "svg_base64": base64.b64encode(contents.sheets[sheet["sha256"]]).decode("ascii")}
        for sheet in contents.data["sheets"]]}
    sha = data["manifest"]["design"]["sha256"]
    scenes = {n: base64.b64encode(b).decode("ascii") for n, b in contents.scenes.items()}
    values = {"SHA256": html.escape(sha),
              "TITLE": html.escape(f"{data['manifest']['design']['name']}: review"),
              "IMPORTMAP": import_map.replace("</", "<\\/"),
              "DATA": json_in_html(data), "SCENES": json_in_html(scenes), "SCRIPT": script}
    # one pass: a value holding a token's text is never replaced again
    return re.sub(r"@@([A-Z0-9]+)@@", lambda m: values[m.group(1)], page)


def write_review_page(path: Path, contents: ReviewContents, import_map: str) -> int:
    """Write the page atomically; its size in bytes.

    Raises:
        OSError: the file cannot be written.
    """
    body = page_html(contents, import_map).encode("utf-8")
    write_bytes_atomic(path, body)
    return len(body)
