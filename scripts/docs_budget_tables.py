"""Rewrite the K_obj budget tables of the shipped examples in
docs/explanation/kobj-budget.md from ``tactcad budget --json``.

For each example the table shows, at the low end, the geometric middle and the high end of
its K_obj range, the array's best unit there (lowest RSS after correction): each source
after correction with the figure before it in brackets, the RSS, the worst case and the
dominant source; a line under it gives every unit's RSS at the three K_obj. The tables sit
between the page's ``budget-tables`` markers; the prose around them is the page's own.

Usage: ``python scripts/docs_budget_tables.py [docs/explanation/kobj-budget.md]``
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "explanation" / "kobj-budget.md"
START, END = "<!-- budget-tables:start -->", "<!-- budget-tables:end -->"
EXAMPLES = {
    "macro_array": "the paper's 2 x 5 array",
    "ti_array_2x3": "2 x 3 Ti-6Al-4V, K_r/K_m = 10",
}


def budget_json(example: str) -> dict:
    """``tactcad budget --json`` of a shipped example."""
    from tactcad.cli import main

    design = ROOT / "hardware" / example / f"{example}.toml"
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["budget", "--design", str(design), "--json", "--quiet"])
    if code != 0:
        raise SystemExit(f"docs_budget_tables: tactcad budget on {example} exited {code}")
    return json.loads(out.getvalue())


def pct(value) -> str:
    """A relative figure as a percentage of three digits; ``unreadable`` for none."""
    if value is None or not math.isfinite(value):
        return "unreadable"
    return f"{100 * value:.3g} %"


def cell(source: dict, i: int) -> str:
    after, before = source["after_rel"][i], source["before_rel"][i]
    if before == after:
        return pct(after)
    return f"{pct(after)} ({pct(before)})"


def unit_name(unit: dict) -> str:
    return f"{unit['reference_element']}/{unit['measuring_element']}"


def table(example: str, words: str) -> list[str]:
    """The example's Markdown: its heading line, the table and the units' RSS line."""
    b = budget_json(example)
    k = b["K_obj_N_per_mm"]
    columns = (0, len(k) // 2, len(k) - 1)
    best = [min(b["units"], key=lambda u: u["rss_rel"][i]) for i in columns]
    lo, hi = b["kobj_range_N_per_mm"]
    lines = [f"**{example}** ({words}, {b['force_N']:g} N, K_obj {lo:g}-{hi:g} N/mm):", "",
             "| source | " + " | ".join(f"{k[i]:.3g} N/mm ({unit_name(u)})"
                                        for i, u in zip(columns, best)) + " |",
             "| --- | --- | --- | --- |"]
    for src in b["sources"]:
        lines.append(f"| {src['words']} | " + " | ".join(
            cell(u["sources"][src["key"]], i) for i, u in zip(columns, best)) + " |")
    for key, name in (("rss_rel", "RSS"), ("worst_case_rel", "worst case")):
        lines.append(f"| {name} | " + " | ".join(pct(u[key][i]) for i, u in zip(columns, best))
                     + " |")
    words_of = {src["key"]: src["words"] for src in b["sources"]}
    lines.append("| dominant | " + " | ".join(words_of.get(u["dominant"][i], u["dominant"][i])
                                             for i, u in zip(columns, best)) + " |")
    lines += ["", "Every unit's RSS at the three K_obj: " + "; ".join(
        f"{unit_name(u)} " + " / ".join(pct(u["rss_rel"][i]) for i in columns)
        for u in b["units"]) + "."]
    return lines


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    page = Path(args[0]) if args else PAGE
    text = page.read_text(encoding="utf-8")
    if START not in text or END not in text:
        raise SystemExit(f"docs_budget_tables: {page} has no {START} ... {END} markers")
    body = []
    for example, words in EXAMPLES.items():
        body += table(example, words) + [""]
    head, rest = text.split(START, 1)
    _, tail = rest.split(END, 1)
    page.write_text(head + START + "\n\n" + "\n".join(body) + END + tail, encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
