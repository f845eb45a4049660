"""The jaw's design atlas in a project's review page.

``tactcad atlas --project DESIGN.toml`` writes the atlas of the project's jaw into the
design's folder (``atlas/``: the table and its summary). The export shows it in the review
page: every judged point drawn over rated force (N) and K_obj span, each with its figures or
refusal and the ``tactcad design`` line that writes it on hover, and the Pareto front as a
table. Only those two files of the design's own folder are read; what they hold is data
(numbers and words), never markup, so nothing of them runs in the page.
"""

from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path

from tactcad.studies.atlas_files import PROJECT_ATLAS_FOLDER, SUMMARY_NAME, TABLE_NAME

#: The front's columns as the page shows them: (record key, heading).
FRONT_COLUMNS = (("product", "product"), ("material", "material"),
                 ("full_scale_force_N", "rated force (N)"),
                 ("kobj_range", "K_obj range (N/mm)"), ("kr_over_km", "K_r/K_m"),
                 ("columns", "columns"), ("kobj_resolution_rel", "K_obj resolution"),
                 ("command", "design command"))


def atlas_paths(design_file: str | Path) -> tuple[Path, Path]:
    """Where a project's atlas is: (its table, its summary) in the design's folder.

    Args:
        design_file: the project's design file.

    Returns:
        The Parquet table's and the JSON summary's paths (either may not exist).
    """
    folder = Path(design_file).parent / PROJECT_ATLAS_FOLDER
    return folder / TABLE_NAME, folder / SUMMARY_NAME


def atlas_identity(design_file: str | Path | None) -> str:
    """The sha256 of the project's atlas files, for the keys of what shows them: a new
    atlas makes a new review page; "" when the project has none.

    Args:
        design_file: the project's design file (None: a design made in code).
    """
    if not _is_design_file(design_file):
        return ""
    digest = hashlib.sha256()
    found = False
    for path in atlas_paths(design_file):
        try:
            digest.update(path.read_bytes())
            found = True
        except OSError:
            digest.update(b"-")
    return digest.hexdigest() if found else ""


def atlas_view(design_file: str | Path | None,
               this_design: tuple[float, float, float] | None = None) -> dict | None:
    """The review page's atlas section of a project, or None when it has no atlas.

    Args:
        design_file: the project's design file (None: a design made in code, no atlas).
        this_design: the project's own targets (rated full-scale force N, K_obj range's low
            and high N/mm), marked on the figure; None: not marked.

    Returns:
        ``{"title", "note", "groups", "points", "front"}``: ``points`` are
        ``{"force_N", "span", "group", "feasible", "front", "title", "command"}`` (``group``
        indexes ``groups``, "product material" names; ``title`` the hover text of
        :func:`tactcad.studies.atlas_files.point_title`); ``front`` a table (``title``,
        ``columns``, ``rows``) of the Pareto front. A table or summary that cannot be read
        gives a section saying so (``points`` empty), never an error. ``design``:
        ``{"force_N", "span", "title"}`` of ``this_design``, or None.
    """
    if not _is_design_file(design_file):
        return None
    table, summary_file = atlas_paths(design_file)
    if not table.exists() and not summary_file.exists():
        return None
    records, summary = _read(table, summary_file)
    if records is None or summary is None:
        return {"title": f"Design atlas ({PROJECT_ATLAS_FOLDER}/)",
                "note": f"{PROJECT_ATLAS_FOLDER}/{TABLE_NAME} or {SUMMARY_NAME} could not be "
                        "read: run `tactcad atlas --project <design file>` again",
                "groups": [], "points": [], "front": None, "design": None}
    return {**_view(records, summary), "design": _design_mark(this_design)}


def _design_mark(this_design: tuple[float, float, float] | None) -> dict | None:
    if this_design is None:
        return None
    force, lo, hi = (float(v) for v in this_design)
    if not all(math.isfinite(v) and v > 0 for v in (force, lo, hi)):
        return None
    return {"force_N": force, "span": hi / lo,
            "title": f"this design: {force:.3g} N rated, K_obj {lo:.3g}-{hi:.3g} N/mm"}


def _is_design_file(design_file) -> bool:
    # a design made in code (its source "<dict>") has no folder: never the working folder's
    return bool(design_file) and Path(design_file).is_file()


def _read(table: Path, summary_file: Path) -> tuple[list[dict] | None, dict | None]:
    from tactcad.studies.atlas_files import read_table

    records = read_table(table) if table.is_file() else None
    try:
        summary = json.loads(summary_file.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        summary = None
    if not isinstance(summary, dict) or not _well_formed(records):
        return None, None
    return records, summary


#: The most points the page draws (a page of an atlas of 10^5 targets in every material
#: would weigh hundreds of MB): the front and the designed points first, then refused points
#: evenly through the table; the title says how many of how many are drawn.
MAX_DRAWN_POINTS = 5000


def drawn_points(points: list[dict], limit: int = MAX_DRAWN_POINTS) -> list[dict]:
    """The points the page draws: all when there are at most ``limit``, else the front's,
    then the designed ones, then the refused ones, each kind taken evenly through its rows
    (every k-th) to fill ``limit``.

    Args:
        points: the view's points (``front``, ``feasible``). limit: the most drawn, >= 1.

    Returns:
        The points kept, in their table order.
    """
    if len(points) <= limit:
        return points
    kinds = ([i for i, p in enumerate(points) if p["front"]],
             [i for i, p in enumerate(points) if p["feasible"] and not p["front"]],
             [i for i, p in enumerate(points) if not p["feasible"]])
    kept: list[int] = []
    for rows in kinds:
        room = limit - len(kept)
        if room <= 0:
            break
        step = max(1, math.ceil(len(rows) / room))
        kept += rows[::step][:room]
    return [points[i] for i in sorted(kept)]


#: The record fields the view reads, with their types.
_FIELDS = {"product": str, "material": str, "point": int, "feasible": bool,
           "full_scale_force_N": float, "kobj_lo_N_per_mm": float,
           "kobj_hi_N_per_mm": float, "kr_over_km": float, "columns": int, "command": str}


def _well_formed(records) -> bool:
    # a table edited or written by another version: checked before anything is drawn
    if not isinstance(records, list):
        return False
    for r in records:
        for key, kind in _FIELDS.items():
            value = r.get(key)
            if kind is float:
                if not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
                    return False
            elif not isinstance(value, kind):
                return False
    return True


def _view(records: list[dict], summary: dict) -> dict:
    from tactcad.studies.atlas_files import point_title, span
    from tactcad.studies.design_atlas import FRONT_OBJECTIVES, pareto_front

    groups = sorted({f"{r['product']} {r['material']}" for r in records})
    on_front: set[tuple[str, str, int]] = set()
    front_rows = []
    for label in groups:
        feasible = [r for r in records if r["feasible"]
                    and f"{r['product']} {r['material']}" == label]
        for r in pareto_front(feasible, FRONT_OBJECTIVES):
            on_front.add((r["product"], r["material"], r["point"]))
            front_rows.append(_front_row(r))
    points = [{"force_N": r["full_scale_force_N"], "span": span(r),
               "group": groups.index(f"{r['product']} {r['material']}"),
               "feasible": bool(r["feasible"]),
               "front": (r["product"], r["material"], r["point"]) in on_front,
               "title": point_title(r), "command": r["command"]} for r in records]
    feasible = sum(p["feasible"] for p in points)
    drawn = drawn_points(points)
    jaw = str(summary.get("jaw", "?"))
    title = (f"Design atlas of the jaw {Path(jaw).name}: {len(points)} verdicts "
             f"({summary.get('points', '?')} target points, seed {summary.get('seed', '?')}), "
             f"{feasible} designed"
             + ("" if len(drawn) == len(points) else
                f"; {len(drawn)} drawn (the front and the designed points first)"))
    note = ("Each point is a target judged as `tactcad design` judges it. Hover a point for "
            "its figures or the limit that refused it; click it to copy its design command, "
            "to paste in the project's folder."
            + ("" if summary.get("complete", True) else
               " The run was stopped: only the points that finished are shown.")
            + "".join(f" Not searched: {product}: {misfit}." for product, misfit
                      in left_out_of(summary)))
    columns = [heading for _, heading in FRONT_COLUMNS]
    return {"title": title, "note": note, "groups": groups, "points": drawn,
            "front": {"title": "Pareto front (rated force, K_obj span and K_obj resolution; "
                               "none beaten in all three) per product and material",
                      "columns": columns, "rows": front_rows}}


def left_out_of(summary: dict) -> list[tuple[str, str]]:
    """The products an atlas left out, as its summary names them (``left_out``).

    Args:
        summary: the atlas's ``atlas.json`` as read.

    Returns:
        (product, its misfit in the jaw in words, mm) of each; entries that are not a
        product and its words (a summary edited or written by another version) are
        skipped.
    """
    found = summary.get("left_out")
    if not isinstance(found, list):
        return []
    return [(g["product"], g["misfit"]) for g in found if isinstance(g, dict)
            and isinstance(g.get("product"), str) and isinstance(g.get("misfit"), str)]


def _front_row(r: dict) -> dict:
    headings = dict(FRONT_COLUMNS)
    resolution = r.get("kobj_resolution_rel")
    cells = {"product": r["product"], "material": r["material"],
             "full_scale_force_N": f"{r['full_scale_force_N']:.4g}",
             "kobj_range": f"{r['kobj_lo_N_per_mm']:.3g} ... {r['kobj_hi_N_per_mm']:.3g}",
             "kr_over_km": f"{r['kr_over_km']:.3g}", "columns": str(r["columns"]),
             "kobj_resolution_rel": (f"{100 * resolution:.2g} %"
                                     if isinstance(resolution, (int, float))
                                     and math.isfinite(resolution) else "\u2014"),
             "command": r["command"]}
    return {headings[k]: v for k, v in cells.items()}
