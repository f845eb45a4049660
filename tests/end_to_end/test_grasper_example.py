"""The shipped grasper example (a 2 x 6 monolithic comb, no test rigs) exports
and checks through the command line with no failed check; the manifest says
what the export leaves out for this construction and why, and lists the decoupling
files written at the comb's own crosstalk level."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest

from tactcad import cli
from tactcad.design.array_plan import EXAMPLES

GRASPER = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


@pytest.mark.slow
def test_the_grasper_example_exports_and_checks_with_no_failure(tmp_path):
    out, junit = tmp_path / "x", tmp_path / "check.xml"
    assert cli.main(["export", "--design", str(GRASPER), "--out", str(out), "--quiet"]) == 0
    assert cli.main(["check", "--design", str(GRASPER), "--out", str(out), "--junit", str(junit),
                     "--quiet"]) == 0
    suites = ET.parse(junit).getroot()
    cases = list(suites.iter("testcase"))
    assert cases and not any(c.find("failure") is not None for c in cases)
    manifest = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    left = {item["what"].split(":")[0].split(",")[0]: item["reason"] for item in manifest["left_out"]}
    assert "crosstalk/decoupling.csv" not in left  # written at the comb's own level
    assert "mount" in left["test rigs"]
    decoupling = [f for f in manifest["files"] if f["part"] == "crosstalk"]
    assert [(f["path"], f["model"]) for f in decoupling] == [
        ("crosstalk/decoupling.csv", "comb-beam"), ("crosstalk/decoupling.json", "comb-beam")]
    assert (out / "crosstalk" / "decoupling.json").stat().st_size > 0
    assert {"comb_row1", "comb_row2"} <= set(manifest["parts"])
    # the insert in the jaw, open and closed on the tissue: exported and checked
    for scene in ("grasper-open", "grasper-closed"):
        assert (out / "scenes" / f"{scene}.step").stat().st_size > 0
        assert (out / "scenes" / f"{scene}.glb").stat().st_size > 0
    assert (out / "drawings" / "grasper_jaw.svg").exists()
    names = {c.get("name") for c in cases}
    assert any("equal radius" in (n or "") for n in names) or \
        any("equal radius" in (c.get("classname") or "") for c in cases)
