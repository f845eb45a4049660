"""The paper's reproduction leaves every other design's export: the paper's
reference load enters through its hook in the reference-load registry
(:mod:`tactcad.studies.reference_loads`), so exporting a design that does not
cite the paper never imports ``tactcad.paper`` (checked in a fresh process,
every job in it); the paper's own design still imports it."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from tactcad.design.array_plan import DEFAULT_DESIGN, EXAMPLES

TI = str(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")

SCRIPT = """
import json, os, sys
os.environ["TACTCAD_WORKERS"] = "0"  # every job in this process
from tactcad import cli
try:
    cli.main(["export", "--design", sys.argv[1], "--out", sys.argv[2], "--no-cache", "--quiet"]
             + (["--only", sys.argv[3]] if len(sys.argv) > 3 else []))
except SystemExit:
    pass
print(json.dumps(sorted(m for m in sys.modules if m.startswith("tactcad.paper"))))
"""


def _paper_modules(design, out, only=None) -> list[str]:
    args = [sys.executable, "-c", SCRIPT, str(design), str(out)] + ([only] if only else [])
    done = subprocess.run(args, capture_output=True, text=True, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.slow  # a whole chain through the command line or an export
def test_manifest_and_shop_files_of_a_new_design_import_no_paper(tmp_path):
    assert _paper_modules(TI, tmp_path / "ti", "dxf,bom") == []
    assert _paper_modules(DEFAULT_DESIGN, tmp_path / "paper", "dxf,bom")  # the check can fail


@pytest.mark.slow
def test_a_full_export_of_a_new_design_imports_no_paper(tmp_path):
    assert _paper_modules(TI, tmp_path / "ti") == []
