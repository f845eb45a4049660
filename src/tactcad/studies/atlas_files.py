"""The design atlas's files: the table (Parquet), the summary (JSON) and the figure a run of
``tactcad atlas`` writes in its folder, read back by a second run and by a project's review
page; and each point's hover text (its targets, verdict and ``tactcad design`` line)."""

from __future__ import annotations

import json
import math
from pathlib import Path

#: The table, the figure and the summary written in ``--out``.
TABLE_NAME, FIGURE_NAME, SUMMARY_NAME = "atlas.parquet", "atlas_front.svg", "atlas.json"
#: The folder in a design's folder where ``tactcad atlas --project`` writes them, and where a
#: project's export finds them for its review page.
PROJECT_ATLAS_FOLDER = "atlas"
#: The table's schema: 2 since its lowest first resonance is ``lowest_first_Hz``, as
#: ``tactcad modal --json`` names it (schema 1 called it ``f1_Hz``). Kept in the table's
#: metadata and in the store's key of an atlas (:func:`tactcad.commands.atlas.atlas_key`),
#: so a table kept before the rename is not read as this one.
ATLAS_SCHEMA = 2
#: The table's columns renamed, old -> new: a table written before (a project's ``atlas/``)
#: is read under the new names (:func:`read_table`); the summary's front points keep the old
#: key beside the new one and list this mapping as their ``deprecated_keys``.
ATLAS_RENAMED = {"f1_Hz": "lowest_first_Hz"}


def write_table(path: Path, records: list[dict], inputs: dict, noted: bool = True) -> None:
    """Records as a Parquet table (pyarrow), written atomically.

    Args:
        path: the file. records: flat records, one row each.
        inputs: the run's inputs, kept in the table's metadata (``tactcad.atlas``, with
            the table's ``schema``, :data:`ATLAS_SCHEMA`).
        noted: False for the store's copy, which a stopped run's message does not name
            among the files it wrote (:func:`tactcad.atomic.atomic_path`).
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    from tactcad.atomic import write_atomic

    table = pa.Table.from_pylist(records).replace_schema_metadata(
        {"tactcad.atlas": json.dumps({**inputs, "schema": ATLAS_SCHEMA}, sort_keys=True)})
    path.parent.mkdir(parents=True, exist_ok=True)
    # the house's atomic write: a whole file or none, with the mode its siblings get
    write_atomic(path, lambda tmp: pq.write_table(table, str(tmp)), noted)


def read_table(path: Path) -> list[dict] | None:
    """A Parquet table's records.

    Args:
        path: a table :func:`write_table` wrote.

    Returns:
        Its rows as dicts, each column under its current name (:data:`ATLAS_RENAMED`: a
        table of an earlier schema read as this one's); None when it cannot be read.
    """
    import pyarrow.parquet as pq

    try:
        rows = pq.read_table(path).to_pylist()
    except (OSError, ValueError):
        return None
    return [{ATLAS_RENAMED.get(k, k): v for k, v in row.items()} for row in rows]


def point_title(r: dict) -> str:
    """A point's hover text: its product, targets and verdict, the design's figures or the
    limit that refused it, and the ``tactcad design`` command that writes or refuses it."""
    head = (f"{r['product']} {r['material']}: K_r/K_m {r['kr_over_km']:.3g}, K_obj "
            f"{r['kobj_lo_N_per_mm']:.3g}-{r['kobj_hi_N_per_mm']:.3g} N/mm, "
            f"{r['full_scale_force_N']:.3g} N, {r['columns']} columns")
    if r["feasible"]:
        figs = [f"{name} {r[key]:{fmt}}{unit}" for key, name, fmt, unit in (
            ("kobj_resolution_rel", "K_obj resolution", ".2%", ""),
            ("max_force_N", "largest force", ".3g", " N"),
            ("lowest_first_Hz", "f1", ".4g", " Hz"),
            ("sheet_mm", "sheet", ".3g", " mm"), ("layer_um", "device layer", ".3g", " um"))
            if isinstance(r.get(key), (int, float)) and math.isfinite(r[key])]
        verdict = "designed: " + ", ".join(figs)
    else:
        verdict = f"refused ({r.get('binding_limit') or 'limit'}): {r.get('binding_detail') or ''}"
    return f"{head}\n{verdict}\n{r['command']}"



def span(r: dict) -> float:
    """A record's K_obj span (high / low)."""
    return r["kobj_hi_N_per_mm"] / r["kobj_lo_N_per_mm"]
