"""The second design, hardware/ti_array_2x3/ti_array_2x3.toml (made by `tactcad design`):
its requirements drive every answer, and nothing it writes mentions the paper."""

from __future__ import annotations

import json
import re
import shutil
import zipfile
from pathlib import Path

import pytest

from tactcad.cli import main
from tactcad.design.array_plan import read_toml
from tactcad.design.project import load_project
from tactcad.studies.verification import (GRID_POWER_REQUIREMENT, requirements_of,
                                          verification_matrix)

from shared_solves import ONE_WORKER, shared_store

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
#: The paper's words; DXF's own block name ``*Paper_Space`` is a format keyword, not a citation.
PAPER_TEXT = re.compile(r"paper(?!_space)|table [12]\b", re.IGNORECASE)


def _stated():
    return read_toml(EXAMPLE, "design file")["requirements"]


def test_example_is_an_inverse_design_with_its_own_requirements():
    text = EXAMPLE.read_text(encoding="utf-8")
    assert text.startswith("# Written by `tactcad design --kr-over-km 10 --kobj-range 1 5")
    assert not PAPER_TEXT.search(text)
    project = load_project(EXAMPLE)
    plan, rigs = project.plan, project.rigs
    assert (plan.rows, plan.columns) == (2, 3) and plan.material.grade == "Ti-6Al-4V-annealed"
    req = requirements_of(plan)
    stated = _stated()
    assert req.full_scale_force_N == stated["full_scale_force_N"]
    assert req.kobj_range_N_per_mm == tuple(stated["kobj_range_N_per_mm"]) == (1.0, 5.0)
    assert req.kr_over_km == stated["kr_over_km"] == 10.0 and not req.cites_paper
    # the rigs beside it carry samples inside its own K_obj range, not the paper's
    assert all(1.0 <= k <= 5.0 for k in rigs.sample_stiffness_N_per_mm)
    rows = verification_matrix(plan)
    assert all(r["pass"] for r in rows)
    # its 2.5 V is above TN-502's thin-section guidance, a few K only, as its note says: the
    # template states the density it accepts, so `tactcad new`'s project ends green
    power = next(r for r in rows if r["requirement"] == GRID_POWER_REQUIREMENT)
    assert power["verdict"] == "pass" and power["stated"]
    assert power["predicted"] > power["guidance_W_per_mm2"]
    assert "requirements.grid_power_density_W_per_mm2" in read_toml(EXAMPLE, "design file")[
        "assumptions"]


def test_arm_over_arm_height_stays_inside_the_corrections_fit():
    plan = load_project(EXAMPLE).plan
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
def test_example_exports_hold_no_paper_text_and_give_its_full_scale_force(tmp_path,
                                                                         example_exported):
    out = tmp_path / "ex"
    shutil.copytree(example_exported, out)  # `check` below adds its results to the set
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
    for svg in (out / "drawings").glob("element_*.svg"):
        notes = " ".join(re.sub(r"<[^>]+>", " ", svg.read_text(encoding="utf-8")).split())
        assert f"Rated full-scale force {force['required_N']:.3g} N" in notes
        assert force["binding_limit"] in notes or "bound by" in notes
    assert main(["check", "--design", str(EXAMPLE), "--out", str(out), "--quiet",
                 "--failures-only"]) == 0


def test_the_papers_design_keeps_its_citations(tmp_path):
    from tactcad.design.array_plan import load_design
    from tactcad.drawings.design_notes import numbering_note, web_tolerance_note

    plan = load_design()
    g = plan.element(1).geometry
    assert "paper's Table 1" in numbering_note(plan)
    assert "Table 1" in web_tolerance_note(plan, g, "0.25", 0.2, 0.2, (4.0, 40.12, 80.38, 2.0))
    ex = load_project(EXAMPLE).plan
    assert not PAPER_TEXT.search(numbering_note(ex))
    assert not PAPER_TEXT.search(web_tolerance_note(ex, g, "0.25", 0.2, 0.2,
                                                    (4.0, 40.12, 80.38, 2.0)))


def test_evaluate_loads_to_the_full_scale_force_over_the_designs_range(capsys):
    # equal steps (--steps) go to the full-scale force; by default the rig's weights load it
    assert main(["evaluate", "--design", str(EXAMPLE), "--coupling", "none", "--steps", "6",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    lo, hi = _stated()["kobj_range_N_per_mm"]
    ks = [s["K_obj_N_per_mm"] for s in out["samples"]]
    assert min(ks) == lo and max(ks) == hi and 3.85 not in ks
    force = _stated()["full_scale_force_N"]
    assert out["full_scale_force_N"] == force
    loads = out["fig6"]["loads_N"]
    assert 3.235 not in loads
    last = max(max(e["tip_force_N"][-1] for e in s["elements"]) for s in out["samples"])
    assert last == pytest.approx(force, rel=1e-9)  # the most loaded element reaches full scale


def test_evaluate_warns_of_samples_outside_the_designs_range_and_prints_them_readably(capsys):
    lo, hi = _stated()["kobj_range_N_per_mm"]
    inside, tiny, huge = (lo * hi) ** 0.5, lo * 1e-6, hi * 1e9
    assert main(["evaluate", "--design", str(EXAMPLE), "--coupling", "none",
                 "--samples", f"{tiny!r},{inside!r},{huge!r}"]) == 0
    captured = capsys.readouterr()
    warned = [line for line in captured.err.splitlines() if "outside the design's K_obj" in line]
    assert len(warned) == 2 and f"{tiny:g}" in warned[0] and f"{huge:g}" in warned[1]
    rows = [line.split() for line in captured.out.splitlines()
            if line.strip() and line.split()[0] in (f"{tiny:.4g}", f"{inside:.4g}", f"{huge:.4g}")]
    assert len(rows) == 3  # a tiny sample is not printed as 0.00; every row keeps its columns
    assert len({len(r) for r in rows}) == 1


def test_ratio_map_tells_apart_elements_of_one_design_ratio(tmp_path, monkeypatch):
    from tactcad.paper import figures

    drawn = []
    plt = figures._pyplot()
    real = plt.Axes.plot

    def record(ax, *args, **kwargs):
        drawn.append((args[2] if len(args) > 2 else None, kwargs.get("label")))
        return real(ax, *args, **kwargs)

    monkeypatch.setattr(plt.Axes, "plot", record)
    series = [{"label": f"element {n}", "K_r_over_K_m": 4.0, "K_m_over_K_obj": [0.1, 1.0],
               "R": [1.2 + n / 10, 3.0]} for n in (1, 3, 4)]
    figures.plot_ratio_map(series, tmp_path / "fig7.png", "three elements of one ratio")
    styles = [style for style, label in drawn if label]
    assert len(styles) == 3 and len(set(styles)) == 3


def test_calibrate_simulate_goes_to_the_full_scale_force(tmp_path, capsys):
    from tactcad.mechanics.measured_io import read_measured

    csv = tmp_path / "cal.csv"
    assert main(["calibrate", "--simulate", "--design", str(EXAMPLE), "--noise-force", "0",
                 "--write-csv", str(csv), "--quiet"]) == 0
    data, _ = read_measured(csv)
    force = _stated()["full_scale_force_N"]
    for d in data.values():
        assert max(d.force_N) == pytest.approx(force, rel=1e-6)


def test_tolerance_reports_the_designs_range_not_the_papers_samples(capsys):
    assert main(["tolerance", "--design", str(EXAMPLE), "--samples", "500", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ks = sorted({u["K_obj_true_N_per_mm"] for u in out["units"]})
    assert ks[0] == 1.0 and ks[-1] == 5.0 and not {2.34, 5.41, 10.01} & set(ks)
    assert not out["table1_equal_arm_spread"]


@pytest.mark.slow
@ONE_WORKER  # its binding element's fem3d solves are the read-out tests' Ti element's
def test_example_meets_every_requirement_and_its_binding_limit_holds_at_fem3d():
    """The inverse design's closed-form geometry holds: `verify --model auto`
    decides every requirement ``pass`` (each margin beyond its level's error),
    and the limit that binds the full-scale force, computed again at fem3d for
    the element it binds (three P2 meshes, Richardson), binds there too, the
    closed form's value (its gauge strain carries the fem3d-fitted plane-strain
    factor) within its stated error. (`tactcad bench verify` compares auto with
    the whole fem3d matrix.)"""
    from tactcad.mechanics.element_strength import at_the_grid
    from tactcad.mechanics.limits import binding, element_limits
    from tactcad.studies.strength_studies import element_stress, fem_peak_stress
    from tactcad.studies.verification import verification_auto
    from tactcad.store import keeping_results

    plan = load_project(EXAMPLE).plan
    # one block, as `tactcad verify` opens: a level's solves of an element serve each
    # question asked of it (on the store the read-out tests of the same element share)
    with keeping_results(shared_store()):
        records, _ = verification_auto(plan, stress=element_stress)
        # every requirement (the excitation, above TN-502's guidance, as the design accepts
        # it: no level computes it anew)
        decided = [r for r in records if r["requirement"] != GRID_POWER_REQUIREMENT]
        assert [r["verdict"] for r in decided] == ["pass"] * len(decided), records
        cf = verification_matrix(plan, "closed-form")[0]
        assert cf["binding_limit"] == "gauge_fatigue"
        number = cf["binding_element"]
        g = plan.element(number).geometry
        # fem3d's own grid reading (its face field averaged over the grid, the bonded layer)
        fem = at_the_grid(fem_peak_stress(g, plan.material, "fem3d"), g, plan)
    at_fem3d = binding(element_limits(number, g, plan, fem, fem.stress_error_rel))
    assert at_fem3d.limit == cf["binding_limit"]
    assert abs(1 - cf["predicted"] / at_fem3d.force_N) <= cf["error_estimate_rel"]


def test_the_ti_examples_excitation_note_states_the_resolution_verify_gives_at_tn502():
    # the note said the resolution missed its target at 0.6 V (about 7 %); verify said 0.39 %
    import re

    from tactcad.design.array_plan import EXAMPLES, plan_from_dict, with_overrides
    from tactcad.studies.verification import verification_matrix
    from tactcad.vocabulary.schema import read_toml

    tables = read_toml(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml", "design file")
    note = tables["assumptions"]["readout.excitation_V"]
    stated = float(re.search(r"\(0\.6 V\) the K_obj resolution would be about ([\d.]+) %",
                             note).group(1))
    plan = plan_from_dict(with_overrides(tables, {"readout.excitation_V": 0.6}))
    row = next(r for r in verification_matrix(plan, "closed-form")
               if r["requirement"] == "kobj_resolution_rel")
    assert round(100 * row["predicted"], 2) == stated and row["verdict"] == "pass"
