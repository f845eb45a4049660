"""The comb's BOM counts its sensing elements through the row sheets that
carry them: every read-out item is bought for all of them, not for none."""

from __future__ import annotations

import csv
import io

from tactcad.assembly.inventory import design_assemblies
from tactcad.design.array_plan import EXAMPLES
from tactcad.design.project import load_project
from tactcad.export.bom import CSV_ENCODING, write_bom_files

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


def test_the_comb_bom_buys_the_read_out_for_every_element(tmp_path):
    project = load_project(GRASPER)
    plan = project.plan
    write_bom_files(plan, tmp_path, lambda line: None, design_assemblies(project))
    text = (tmp_path / "bom.csv").read_bytes().decode(CSV_ENCODING)
    rows = {r["part"]: r for r in csv.DictReader(io.StringIO(text))}
    n = len(plan.slots)
    assert int(rows["solder_terminal_pair"]["quantity"]) == n + int(rows["solder_terminal_pair"]["spares"])
    assert int(rows["bridge_completion_resistor"]["quantity"]) == 3 * n
    assert int(rows["instrumentation_amplifier"]["quantity"]) == n
    assert {s.part_name for s in plan.comb.sheets} <= set(rows)
