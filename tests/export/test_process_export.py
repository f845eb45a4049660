"""A design that chooses photochemical etching for a 0.3 mm element sheet
exports through the command line (``--set``), its elements' DXF the etch
artwork; an unknown process is refused naming the allowed ones."""

from __future__ import annotations

import pytest

import json
import warnings

import ezdxf

from tactcad import cli
from tactcad.vocabulary.process import process_names
from tactcad.design.array_plan import EXAMPLES

TI = str(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")
ETCH = ["--set", 'element.process="photochemical-etching"', "--set", "sheet.thickness_mm=0.3",
        "--set", "element.web_tolerance_mm=0.045",
        "--set", "readout.grid_width_mm=0.3"]  # the gauge grid fits the 0.3 mm face


@pytest.mark.slow  # a whole chain through the command line or an export
def test_an_etched_0p3_mm_design_exports_its_artwork(tmp_path, capsys):
    out = tmp_path / "etched"
    with warnings.catch_warnings():  # the correction's range notice at a 0.3 mm sheet
        warnings.simplefilter("ignore")
        code = cli.main(["export", "--design", TI, *ETCH, "--only", "dxf,bom", "--out", str(out),
                         "--no-cache", "--quiet"])
    assert code == 0, capsys.readouterr().err
    man = json.loads((out / "manifest.json").read_text())
    element = next(r for r in man["files"] if r["kind"] == "dxf-profile"
                   and r["part"].startswith("element_"))
    assert element["process"] == "photochemical-etching" and element["thickness_mm"] == 0.3
    doc = ezdxf.readfile(out / element["path"])
    assert doc.header.custom_vars.get("FILE_KIND") == "etch artwork DXF"
    assert man["parts"][element["part"]]["process"] == "photochemical etching from foil"


def test_an_unknown_process_is_refused_naming_the_allowed_ones(tmp_path, capsys):
    code = cli.main(["export", "--design", TI, "--set", 'element.process="waterjet"',
                     "--out", str(tmp_path / "x")])
    err = capsys.readouterr().err
    assert code != 0 and "Traceback" not in err
    assert "element.process" in err and "'waterjet'" in err
    assert all(name in err for name in process_names())
