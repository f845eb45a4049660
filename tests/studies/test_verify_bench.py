"""``tactcad bench verify`` times each level and auto and compares their verdicts."""

from __future__ import annotations

import json
from pathlib import Path

from tactcad import cli

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def test_bench_verify_prints_each_level_and_auto(capsys):
    assert cli.main(["bench", "verify", "--design", str(EXAMPLE), "--models", "closed-form",
                     "beam", "--json", "--quiet"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert [row["model"] for row in report["levels"]] == ["closed-form", "beam"]
    assert all(row["seconds"] > 0 for row in report["levels"])
    assert report["auto"]["levels"][0]["model"] == "closed-form"
    assert report["compared_with"] == "beam" and report["agree"] is True
    assert set(report["auto"]["decided_by"]) == set(report["levels"][0]["verdicts"])
