"""The stiffness ladder against the paper: Table 1, gauge strain, as-built web, Table 2."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest

from conftest import run_cli
from tactcad.errors import TactcadError
from tactcad.mechanics.ladder import MODELS, estimate
from tactcad.paper.table1 import as_built_webs, gauge_strain_at_paper_load, table1_comparison, table2_predicted
from tactcad.paper.data import table1


def test_table1_rows_cover_every_calibrated_element(plan):
    rows = table1_comparison(plan, "closed-form")
    assert [r.element for r in rows] == [m.element for m in table1()]
    for r in rows:
        expected = 100 * (r.predicted.stiffness_N_per_mm - r.measured_N_per_mm) / r.measured_N_per_mm
        assert r.error_percent == pytest.approx(expected)
        assert r.predicted.stiffness_N_per_mm > 0


def test_table1_states_k_with_the_bonded_gauge_as_the_readout_does(plan):
    """Table 1 predicts K with the bonded gauge, as the paper measured it, and states the
    element as cut beside it: the read-out's own layer rise on each element (one number
    per quantity), a stiffening of a few per cent, and the shift it gives is said."""
    from tactcad.mechanics.readout_chain import readout_report
    from tactcad.paper.table1 import gauge_layer_shift
    from tactcad.studies.verification import requirements_of

    rows = table1_comparison(plan, "closed-form")
    report = readout_report(plan, requirements_of(plan))
    by_element = {r["element"]: r["gauge_layer_k_rel"] for r in report.records}
    for r in rows:
        assert r.gauge_layer_k_rel == pytest.approx(by_element[r.element], rel=1e-12)
        assert 0.02 < r.gauge_layer_k_rel < 0.15
        g = plan.element(r.element).geometry
        assert r.predicted.stiffness_N_per_mm == pytest.approx(
            estimate("closed-form", g, plan.material).stiffness_N_per_mm, rel=1e-12)
        assert r.without_gauge_layer_N_per_mm == pytest.approx(
            estimate("closed-form", g.bare(), plan.material).stiffness_N_per_mm, rel=1e-12)
    shift = gauge_layer_shift(rows)
    bare, layered = shift["mean_error_percent"]
    assert layered > bare  # a stiffer prediction reads higher against the same measurements
    r = run_cli("table1", "--json")
    assert r.returncode == 0 and json.loads(r.stdout)["gauge_layer"] == pytest.approx(shift)


def test_longer_arm_is_softer_across_the_table(plan):
    rows = {r.arm_length_mm: r.predicted.stiffness_N_per_mm for r in table1_comparison(plan, "beam")}
    ks = [rows[a] for a in sorted(rows)]
    assert all(k1 > k2 for k1, k2 in zip(ks, ks[1:]))


def test_as_built_web_reproduces_measured_stiffness(plan):
    from dataclasses import replace

    for w in as_built_webs(plan):
        g = replace(plan.element(w["element"]).geometry, web_thickness_mm=w["web_as_built_mm"])
        k = estimate("closed-form", g, plan.material).stiffness_N_per_mm
        assert k == pytest.approx(w["measured_N_per_mm"], rel=1e-6)
    webs = {w["element"]: w["web_as_built_mm"] for w in as_built_webs(plan)}
    assert webs[8] > webs[1]  # same 4 mm arm, twice the measured K: a thicker web


def test_gauge_strain_grows_with_the_lever(plan):
    s = gauge_strain_at_paper_load(plan)
    ratio = s[-1]["face_strain_as_cut_percent"] / s[0]["face_strain_as_cut_percent"]
    assert ratio == pytest.approx(8.0 / 4.0, rel=0.05)  # bending moment at the web ~ F a
    assert all(0.1 < x["face_strain_as_cut_percent"] < 2.0 for x in s)
    # the paper's ANSYS strain is the bare face's: the element as cut, not under the gauge
    g = plan.element(1).geometry
    assert g.gauge is not None
    bare = estimate("closed-form", g.bare(), plan.material).face_strain_per_N
    assert s[0]["face_strain_as_cut_percent"] == pytest.approx(200 * bare, rel=1e-12)
    assert estimate("closed-form", g, plan.material).face_strain_per_N < 0.95 * bare


def test_table2_with_predicted_stiffness_reports_out_of_domain_rows(plan):
    t2 = table2_predicted(plan, "closed-form")
    assert len(t2["rows"]) == 48
    # Element 1 and element 8 share the 4 mm arm: equal predicted K, outside eq. 2's domain.
    e1 = [r for r in t2["rows"] if r["element"] == 1]
    assert e1 and not any(r["in_domain"] for r in e1)
    assert all(math.isnan(r["R_predicted"]) for r in e1)
    assert t2["n_in_domain"] == 40
    assert all(r["R_predicted"] > 1 for r in t2["rows"] if r["in_domain"])


def test_unknown_model_is_refused(plan):
    with pytest.raises(TactcadError, match="closed-form"):
        estimate("magic", plan.element(1).geometry, plan.material)
    assert MODELS[0] == "closed-form" and MODELS[-1] == "fem3d"


def test_stiffness_cli_json_keys():
    out = run_cli("stiffness", "--element", "3", "--model", "closed-form", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert set(data) - {"notices"} == {"element", "model", "stiffness_N_per_mm",
                                       "face_strain_per_N", "error_estimate_rel",
                                       "wall_time_s", "warnings", "grid_strain_per_N",
                                       "grid_strain_error_rel", "with_gauge"}
    assert 0 < data["grid_strain_error_rel"] < 0.05  # the fit's residual inside its range
    assert data["with_gauge"] is True and abs(data["grid_strain_per_N"]) > data["face_strain_per_N"]
    assert data["warnings"] == []  # the default design lies inside the fitted range
    assert data["element"] == 3 and data["stiffness_N_per_mm"] > 0


def test_stiffness_cli_unknown_element_exits_2():
    out = run_cli("stiffness", "--element", "11")
    assert out.returncode == 2 and "element" in out.stderr and "Traceback" not in out.stderr


def test_closed_form_commands_do_not_import_the_cad_kernel():
    code = ("import sys; from tactcad.cli import main; main(['stiffness', '--element', '1', '--json']);"
            "print('CAD', any(m.split('.')[0] in ('build123d', 'cadquery', 'OCP') for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().endswith("CAD False")


def test_table1_all_levels_side_by_side(plan, monkeypatch, capsys):
    import tactcad.commands.mechanics as cmd
    from tactcad.mechanics import ladder

    fast = {n: ladder.LEVELS[n] for n in ("closed-form", "beam")}  # the fast levels only
    monkeypatch.setattr(ladder.LADDER, "levels", fast)  # what models() lists
    monkeypatch.setattr(ladder, "LEVELS", fast)
    assert cmd._table1_all_levels(plan, True, None) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) == {"closed-form", "beam"}
    for level in data.values():
        assert [r["element"] for r in level] == [m.element for m in table1()]
    # Beam theory (uncorrected) is stiffer than the 3D-corrected closed form everywhere.
    assert all(b["predicted_N_per_mm"] > c["predicted_N_per_mm"]
               for b, c in zip(data["beam"], data["closed-form"]))


def test_closed_form_estimates_kept_inside_give_the_same_estimate_worked_out_once(
        plan, monkeypatch):
    from tactcad.mechanics import ladder

    g, material = plan.element(1).geometry, plan.material
    fresh = estimate("closed-form", g, material, element=1)
    runs = []
    run = ladder.LADDER.run
    monkeypatch.setattr(ladder.LADDER, "run", lambda *a, **k: runs.append(a[0]) or run(*a, **k))
    with ladder.closed_form_estimates_kept():
        first = estimate("closed-form", g, material, element=1)
        again = estimate("closed-form", g, material, element=2)
        beam = estimate("beam", g, material)
    after = estimate("closed-form", g, material)
    assert runs == ["closed-form", "beam", "closed-form"]  # kept inside, not after
    assert again.element == 2 and again.wall_time_s == first.wall_time_s
    for r in (first, again, after):
        assert (r.stiffness_N_per_mm, r.face_strain_per_N, r.error_estimate_rel) == \
            (fresh.stiffness_N_per_mm, fresh.face_strain_per_N, fresh.error_estimate_rel)
    assert beam.model == "beam"
