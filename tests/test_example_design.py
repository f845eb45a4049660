"""The second design, hardware/examples/ti_array_2x3.toml (made by `tactcad design`):
its requirements drive every answer, and nothing it writes mentions the paper."""

from __future__ import annotations

import json
import re
import zipfile
from pathlib import Path

import pytest

from tactcad.cli import main
from tactcad.design.array import read_toml
from tactcad.design.project import load_project
from tactcad.mechanics.requirements import requirements_of, verification_matrix

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "hardware" / "examples" / "ti_array_2x3.toml"
#: The paper's words; DXF's own block name ``*Paper_Space`` is a format keyword, not a citation.
PAPER_TEXT = re.compile(r"paper(?!_space)|table\s*[12]\b", re.IGNORECASE)


def _stated():
    return read_toml(EXAMPLE, "design file")["requirements"]


def test_example_is_an_inverse_design_with_its_own_requirements():
    text = EXAMPLE.read_text(encoding="utf-8")
    assert text.startswith("# Written by `tactcad design --kr-over-km 10 --kobj-range 1 5")
    assert not PAPER_TEXT.search(text)
    plan, rigs, scenes = load_project(EXAMPLE)
    assert (plan.rows, plan.columns) == (2, 3) and plan.material.grade == "Ti-6Al-4V-annealed"
    req = requirements_of(plan)
    stated = _stated()
    assert req.full_scale_force_N == stated["full_scale_force_N"]
    assert req.kobj_range_N_per_mm == tuple(stated["kobj_range_N_per_mm"]) == (1.0, 5.0)
    assert req.kr_over_km == stated["kr_over_km"] == 10.0 and not req.cites_paper
    # the rigs beside it carry samples inside its own K_obj range, not the paper's
    assert all(1.0 <= k <= 5.0 for k in rigs.sample_stiffness_N_per_mm)
    assert all(r["pass"] for r in verification_matrix(plan))


def test_arm_over_arm_height_stays_inside_the_corrections_fit():
    plan, _, _ = load_project(EXAMPLE)
    for g in plan.distinct_elements.values():
        assert g.arm_length_mm / g.arm_height_mm <= 4.0 + 1e-9


def test_strength_judges_the_designs_full_scale_force(capsys):
    assert main(["strength", "--design", str(EXAMPLE), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    req = out["requirement"]
    assert req["full_scale_force_N"] == _stated()["full_scale_force_N"] and req["met"]
    assert req["binding_limit"]
    text = json.dumps(out)
    assert not PAPER_TEXT.search(text.replace("paper_load", ""))


def _text_of(path: Path) -> list[tuple[str, str]]:
    """(name, text) of an exported file, the members of a zip (FCStd) included."""
    data = path.read_bytes()
    if zipfile.is_zipfile(path):
        with zipfile.ZipFile(path) as z:
            return [(f"{path.name}:{n}", z.read(n).decode("latin-1")) for n in z.namelist()]
    return [(path.name, data.decode("latin-1"))]


@pytest.mark.slow
def test_example_exports_hold_no_paper_text_and_give_its_full_scale_force(tmp_path):
    out = tmp_path / "ex"
    assert main(["export", "--design", str(EXAMPLE), "--out", str(out), "--quiet"]) == 0
    files = [p for p in out.rglob("*") if p.is_file()]
    kinds = {p.suffix for p in files}
    assert {".svg", ".dxf", ".step", ".csv", ".md", ".json"} <= kinds
    for p in files:
        for name, text in _text_of(p):
            hit = PAPER_TEXT.search(text)
            assert hit is None, f"{name}: {text[max(0, hit.start() - 60):hit.end() + 60]!r}"
    man = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    force = man["requirements"]["full_scale_force"]
    assert force["required_N"] == _stated()["full_scale_force_N"] and force["binding_limit"]
    notes = " ".join((out / "drawings").glob("*.svg").__next__().read_text().split())
    assert f"Full-scale tip force {force['required_N']:.3g} N" in notes
    assert main(["check", "--design", str(EXAMPLE), "--out", str(out), "--quiet",
                 "--failures-only"]) == 0


def test_the_papers_design_keeps_its_citations(tmp_path):
    from tactcad.design.array import load_design
    from tactcad.drawings.design_notes import numbering_note, web_tolerance_note

    plan = load_design()
    g = plan.element(1).geometry
    assert "paper's Table 1" in numbering_note(plan)
    assert "Table 1" in web_tolerance_note(plan, g, "0.25", 0.2, 0.2, (4.0, 40.12, 80.38, 2.0))
    ex, _, _ = load_project(EXAMPLE)
    assert not PAPER_TEXT.search(numbering_note(ex))
    assert not PAPER_TEXT.search(web_tolerance_note(ex, g, "0.25", 0.2, 0.2,
                                                    (4.0, 40.12, 80.38, 2.0)))
