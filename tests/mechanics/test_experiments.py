"""Virtual experiments: punch contact model, evaluation rig, calibration audit, Table 2 models, CLI."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from conftest import with_default_companions
import tactcad
from tactcad.cli import main
from tactcad.mechanics import contact
from tactcad.mechanics import calibration as cal
from tactcad.paper import calibration_audit as ca
from tactcad.paper import data as paper_data
from tactcad.mechanics import measured_io
from tactcad.mechanics import evaluation as ev
from tactcad.paper import table2_models as t2

REPO = Path(__file__).resolve().parents[2]
DEFAULT_TOML = REPO / "hardware" / "macro_array" / "macro_array.toml"


def strict_json(text: str):
    """json.loads that fails on NaN/Infinity."""
    def reject(name):
        raise AssertionError(f"non-finite number {name} in JSON")
    return json.loads(text, parse_constant=reject)


# ---------------------------------------------------------------------------
# Love's rectangle and the rigid punch
# ---------------------------------------------------------------------------
def love_centre(a: float, b: float, p: float, e: float, nu: float) -> float:
    """Love (1929): centre displacement of a 2a x 2b rectangle under uniform p, written out."""
    d = math.hypot(a, b)
    return (1 - nu ** 2) * p / (math.pi * e) * 4 * (a * math.log((b + d) / a) + b * math.log((a + d) / b))


@pytest.mark.parametrize("a,b", [(1.0, 1.0), (1.0, 1.5), (0.3, 2.0)])
def test_uniform_rectangle_matches_love_centre_formula(a, b):
    w = contact.love_rectangle_displacement(0.0, 0.0, -a, a, -b, b, 0.7, 3.0, 0.45)
    assert float(w) == pytest.approx(love_centre(a, b, 0.7, 3.0, 0.45), rel=1e-12)


def test_single_cell_punch_compliance_is_love_centre_over_area():
    # One pressure cell: the punch compliance is Love's centre displacement per unit force.
    a, b, e, nu = 1.0, 1.5, 2.0, 0.3
    one_cell = contact.single_punch_compliance(2 * a, 2 * b, contact.Sample(e, nu), cell_mm=10.0,
                                                min_cells=1)
    assert one_cell == pytest.approx(love_centre(a, b, 1.0, e, nu) / (4 * a * b), rel=1e-12)


def test_a_small_tip_gets_enough_cells_to_converge():
    """A 0.5 mm tip at the default cell size: within 4 % of the rigid square punch's
    K = 1.012 (2/sqrt(pi)) E/(1 - nu^2) sqrt(A) (it got 2 x 2 cells before: 13 % low)."""
    e, nu, side = 1.0, 0.3, 0.5
    k = 1.0 / contact.single_punch_compliance(side, side, contact.Sample(e, nu))
    exact = contact.SQUARE_PUNCH_BETA * 2 / math.sqrt(math.pi) * e / (1 - nu ** 2) * side
    assert k == pytest.approx(exact, rel=0.04)


def test_uniform_square_centre_and_corner_match_johnson_coefficients():
    # Johnson, Contact Mechanics, sec. 3.3: square of side 2a, centre 2.24 and corner 1.12 x (1 - nu^2) p a / E.
    a, e, nu = 1.0, 1.0, 0.0
    centre = contact.love_rectangle_displacement(0.0, 0.0, -a, a, -a, a, 1.0, e, nu)
    corner = contact.love_rectangle_displacement(a, a, -a, a, -a, a, 1.0, e, nu)
    assert float(centre) == pytest.approx(2.244, abs=1e-3)
    assert float(corner) == pytest.approx(1.122, abs=1e-3)


@pytest.mark.slow  # a mesh-convergence study
def test_rigid_square_punch_converges_to_literature_compliance_factor():
    # K = beta (2/sqrt(pi)) E/(1 - nu^2) sqrt(A), beta = 1.012 for a square (King 1987).
    sample = contact.Sample(1.0, 0.3)
    side = 2.0
    exact = contact.SQUARE_PUNCH_BETA * 2 / math.sqrt(math.pi) * side / (1 - 0.3 ** 2)
    coarse = 1 / contact.single_punch_compliance(side, side, sample, cell_mm=side / 8)
    fine = 1 / contact.single_punch_compliance(side, side, sample, cell_mm=side / 32)
    assert coarse < fine  # piecewise-constant collocation is too compliant on coarse meshes
    assert fine == pytest.approx(exact, rel=0.01)


def test_rigid_punch_is_stiffer_than_uniform_pressure_mean_displacement():
    # Complementary energy: a rigid punch's compliance <= mean displacement / force of a uniform load.
    a, b, sample = 1.0, 1.5, contact.Sample(1.0, 0.5)
    rigid = contact.single_punch_compliance(2 * a, 2 * b, sample, cell_mm=0.125)
    xs, zs = np.meshgrid(np.linspace(-a, a, 81)[1:-1], np.linspace(-b, b, 121)[1:-1])
    mean_w = float(np.mean(contact.love_rectangle_displacement(xs, zs, -a, a, -b, b, 1.0, 1.0, 0.5)))
    uniform = mean_w / (4 * a * b)
    assert rigid < uniform
    assert rigid > 0.85 * uniform


def test_distant_punches_couple_as_point_loads():
    r = 60.0
    sample = contact.Sample(2.0, 0.4)
    sol = contact.solve_punches([contact.Punch(0, 0, 2, 3), contact.Punch(r, 0, 2, 3)], sample)
    c = sol.compliance_mm_per_N
    assert c[0, 1] == pytest.approx(c[1, 0], rel=1e-9)
    assert c[0, 1] == pytest.approx((1 - 0.4 ** 2) / (math.pi * 2.0 * r), rel=0.01)


def test_thick_layer_tends_to_half_space_and_thin_layer_is_stiffer():
    half = contact.single_punch_compliance(2, 3, contact.Sample(1.0, 0.3))
    thick = contact.single_punch_compliance(2, 3, contact.Sample(1.0, 0.3, 2000.0))
    thin = contact.single_punch_compliance(2, 3, contact.Sample(1.0, 0.3, 2.0))
    assert thick == pytest.approx(half, rel=2e-3)
    assert thin < 0.8 * half


@pytest.mark.parametrize("field,sample", [
    ("youngs_modulus_MPa", contact.Sample(-1.0, 0.3)),
    ("poisson_ratio", contact.Sample(1.0, 0.7)),
    ("thickness_mm", contact.Sample(1.0, 0.3, 0.0)),
])
def test_bad_sample_names_field(field, sample):
    with pytest.raises(contact.ContactError, match=field):
        contact.single_punch_compliance(2, 3, sample)


def test_modulus_from_k_obj_gives_k_obj_back():
    e = contact.modulus_from_punch_stiffness(3.85, 2.0, 3.0, 0.5)
    k = e / contact.unit_punch_compliance([contact.Punch(0.0, 0.0, 2.0, 3.0)], 0.5)[0, 0]
    assert k == pytest.approx(3.85, rel=1e-10)


# ---------------------------------------------------------------------------
# Evaluation rig
# ---------------------------------------------------------------------------
def paper_elements(plan):
    return ev.elements_from_plan(plan, t2.paper_stiffness_by_element(plan))


def test_coupling_off_is_eq2_exactly_at_every_load(plan):
    elements = paper_elements(plan)
    for k_obj in paper_data.SAMPLE_STIFFNESSES_N_PER_MM:
        res = ev.simulate_rig(elements, k_obj, ev.SampleSpec("none"))
        assert res.reference == 8
        for i, e in enumerate(elements):
            expected = (80.38 + k_obj) / (e.stiffness_N_per_mm + k_obj)
            np.testing.assert_allclose(res.ratio[:, i], expected, rtol=1e-13)
        np.testing.assert_allclose(res.tip_force_N.sum(axis=1), res.loads_N, rtol=1e-12)


def test_coupled_rig_balances_the_dead_weight_and_is_load_independent(plan):
    res = ev.simulate_rig(paper_elements(plan), 3.85, ev.SampleSpec("halfspace"))
    np.testing.assert_allclose(res.tip_force_N.sum(axis=1), res.loads_N, rtol=1e-12)
    np.testing.assert_allclose(res.loads_N[:2], [3.235, 3.235 + 0.980665])
    assert np.ptp(res.ratio, axis=0).max() < 1e-12
    assert not res.contact_lost.any()
    # coupling changes R: the surface sinks most under the central, stiffest element
    independent = ev.simulate_rig(paper_elements(plan), 3.85, ev.SampleSpec("none"))
    assert np.max(np.abs(res.ratio[0] - independent.ratio[0])) > 0.1


def test_reference_is_the_stiffest_and_ties_prefer_the_papers_element(plan):
    ladder_k = ev.ladder_stiffness_by_element(plan)
    assert ladder_k[1] == ladder_k[8]  # both 4 mm arms
    assert ev.reference_element(ev.elements_from_plan(plan, ladder_k)) == 8
    k = dict(ladder_k)
    k[3] = 100.0
    assert ev.reference_element(ev.elements_from_plan(plan, k)) == 3


def test_rig_rejects_bad_inputs(plan):
    k = ev.ladder_stiffness_by_element(plan)
    k[2] = -3.0
    with pytest.raises(contact.ContactError, match="element 2"):
        ev.simulate_rig(ev.elements_from_plan(plan, k), 3.0, ev.SampleSpec("none"))
    with pytest.raises(contact.ContactError, match="K_obj"):
        ev.simulate_rig(paper_elements(plan), 0.0, ev.SampleSpec("none"))
    with pytest.raises(contact.ContactError, match="coupling"):
        ev.SampleSpec("glue")


# ---------------------------------------------------------------------------
# Calibration: simulated rig, CSV, audit
# ---------------------------------------------------------------------------
def test_simulated_design_calibration_is_recovered_within_noise(plan):
    data = ca.simulate_design_calibration(plan, gauge_gain_V_per_strain=ca.DEFAULT_GAUGE_GAIN_V_PER_STRAIN,
                                          noise_force_N=0.002, noise_signal_V=0.002, seed=3)
    truth = ev.ladder_stiffness_by_element(plan)
    fits = ca.fit_all(data)
    k_eps = _ladder_k_eps(plan)
    for element, c in fits.items():
        assert abs(c.K_N_per_mm - truth[element]) < 4 * c.stderr_K_N_per_mm
        k_v = ca.DEFAULT_GAUGE_GAIN_V_PER_STRAIN * k_eps[element][1] * k_eps[element][0]
        assert abs(c.K_v_V_per_mm - k_v) < 4 * c.stderr_K_v_V_per_mm
    audit = ca.audit(plan, ca.from_fits(fits, "simulated"))
    assert audit["gauge_gain_V_per_strain"] == pytest.approx(ca.DEFAULT_GAUGE_GAIN_V_PER_STRAIN, rel=0.01)
    for r in audit["elements"]:
        assert r["web_as_built_mm"] == pytest.approx(r["web_design_mm"], abs=2e-3)
        assert r["signal_ratio"] == pytest.approx(1.0, abs=0.02)
    assert audit["flags"] == []


def test_audit_flags_a_disagreeing_element(plan):
    cals = [ca.ElementCalibration(e, k, ca.DEFAULT_GAUGE_GAIN_V_PER_STRAIN * eps * k, 0.0)
            for e, (k, eps) in _ladder_k_eps(plan).items()]
    cals[2] = ca.ElementCalibration(cals[2].element, cals[2].K_N_per_mm, 0.5 * cals[2].K_v_V_per_mm, 0.0)
    flags = ca.audit(plan, cals)["flags"]
    flagged = [f for f in flags if f["check"].startswith("signal per N")]
    assert [f["elements"] for f in flagged] == [[3]]
    assert flagged[0]["value"] == pytest.approx(0.5, rel=0.02)


def _ladder_k_eps(plan):
    """{element: (K, the grid's strain per newton, signed)} at the closed form."""
    from tactcad.mechanics import ladder
    from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain

    chain = readout_chain(plan)
    return {s.number: (ladder.estimate("closed-form", s.geometry, plan.material).stiffness_N_per_mm,
                       grid_strain_per_N(s.geometry, plan.material, chain, "closed-form")["grid"])
            for s in plan.slots}


def test_table1_audit_flags_the_4mm_twins_with_their_ratio(plan):
    audit = ca.audit(plan, ca.from_table1())
    twin = next(t for t in audit["twins"] if t["elements"] == [1, 8])
    assert twin["stiffness_ratio"] == pytest.approx(80.38 / 40.12)
    assert twin["allowed_stiffness_ratio"] < twin["stiffness_ratio"]
    assert any(f["check"] == "twin stiffness ratio" and f["elements"] == [1, 8] for f in audit["flags"])
    e8 = next(r for r in audit["elements"] if r["element"] == 8)
    assert e8["series_amplification"] == pytest.approx(1 + 80.38 / 57.04)


def test_calibration_csv_round_trip(plan):
    data = ca.simulate_design_calibration(plan, seed=5)
    back, _ = measured_io.parse_csv_text(cal.format_calibration_csv(data, ("a comment",)))
    assert sorted(back) == sorted(data)
    for e in data:
        np.testing.assert_allclose(back[e].force_N, data[e].force_N, atol=5e-5)
        np.testing.assert_allclose(back[e].z_travel_um, data[e].z_travel_um)


@pytest.mark.parametrize("text,needle", [
    ("", "no header"),
    ("# only a comment\n", "no header"),
    ("element,run,z_um,force_N\n1,1,0,0\n", "missing ['signal_V']"),
    ("element,run,z_um,force_N,signal_V,extra\n", "unknown ['extra']"),
    ("element,run,z_um,force_N,signal_V\n", "readings = 0"),
    ("element,run,z_um,force_N,signal_V\n1,1,-25,0,0\n", "z_um = -25.0"),
    ("element,run,z_um,force_N,signal_V\n1,1,0,abc,0\n", "force_N = 'abc'"),
    ("element,run,z_um,force_N,signal_V\n0,1,0,0,0\n", "line 2, column element = 0.0"),
    ("element,run,z_um,force_N,signal_V\n1,1,0,0,0\n1,1,25,1,1\n", "readings = 2"),
    ("# k_sensor_N_per_mm = -5\nelement,run,z_um,force_N,signal_V\n", "column k_sensor_N_per_mm = '-5'"),
])
def test_bad_calibration_csv_is_named(text, needle):
    with pytest.raises(cal.CalibrationError) as err:
        measured_io.parse_csv_text(text)
    assert needle in str(err.value)


def test_example_csv_reads_back_table1():
    fits = ca.fit_all(measured_io.read_measured(REPO / "hardware" / "macro_array" / "calibration_example.csv")[0])
    for row in paper_data.table1():
        assert fits[row.element].K_N_per_mm == pytest.approx(row.stiffness_N_per_mm, rel=0.01)


# ---------------------------------------------------------------------------
# Table 2 models: held-out truthfulness
# ---------------------------------------------------------------------------
def test_cross_validation_never_fits_on_scored_rows():
    rows = t2.Rows.table2()
    seen: list[set] = []

    def predict(p, rows_, idx):
        return t2.eq2(rows_.k_m[idx], p[0], rows_.k_obj[idx])

    class Spy(t2.FittedModel):
        def fit(self, rows_, index):
            seen.append(set(index.tolist()))
            return super().fit(rows_, index)

    model = Spy("spy", ("K_r",), (80.0,), predict)
    for groups in (rows.k_obj, rows.element):
        seen.clear()
        predicted, folds = t2.cross_validate(model, rows, groups)
        assert np.all(np.isfinite(predicted))
        for fold_train, g in zip(seen, np.unique(groups)):
            test = set(np.flatnonzero(groups == g).tolist())
            assert not fold_train & test
            assert fold_train | test == set(range(48))
        # each held-out prediction is the model fitted without those rows
        g0 = np.unique(groups)[0]
        test0 = np.flatnonzero(groups == g0)
        np.testing.assert_allclose(predicted[test0], predict(folds[0], rows, test0))


@pytest.mark.slow
def test_table2_json_schema_and_held_out(capsys):
    assert main(["table2", "--json"]) == 0
    out = strict_json(capsys.readouterr().out)
    names = {(m["name"], m["scheme"]) for m in out["models"]}
    assert {("eq2", "none"), ("coupled-halfspace", "none")} <= names
    for m in out["models"]:
        assert set(m) >= {"name", "fitted_parameters", "median_rel_error", "max_rel_error", "held_out"}
        assert 0 <= m["median_rel_error"] <= m["max_rel_error"]
        assert m["held_out"] is True
        if m["fitted_parameters"]:
            assert m["scheme"] in ("leave-one-sample-out", "leave-one-element-out")
        assert len(m["predicted_R"]) == 48
    eq2 = next(m for m in out["models"] if m["name"] == "eq2")
    r_meas = np.array([r["R"] for r in out["table2"]])
    r_pred = np.array(eq2["predicted_R"])
    assert eq2["median_rel_error"] == pytest.approx(np.median(np.abs(r_pred - r_meas) / r_meas))


# ---------------------------------------------------------------------------
# CLI
# ---------------------------------------------------------------------------
def other_design(tmp_path) -> Path:
    text = DEFAULT_TOML.read_text(encoding="utf-8")
    text = text.replace("web_thickness_mm = 0.25", "web_thickness_mm = 0.3")
    text = text.replace("lengths_mm = [4.0, 7.0, 6.0, 8.0, 6.0, 8.0, 5.0, 4.0, 5.0, 7.0]",
                        "lengths_mm = [5.0, 6.0, 7.0, 8.0, 4.5, 8.0, 7.0, 6.0, 5.0, 4.5]")
    assert "4.5, 8.0" in text
    path = tmp_path / "other.toml"
    path.write_text(text, encoding="utf-8")
    return with_default_companions(path)


def test_evaluate_and_calibrate_run_on_another_design(tmp_path, capsys):
    design = str(other_design(tmp_path))
    png = tmp_path / "fig7.png"
    assert main(["evaluate", "--design", design, "--samples", "5,2.5", "--plot", str(png), "--json"]) == 0
    out = strict_json(capsys.readouterr().out)
    assert out["reference_element"] == 5  # the 4.5 mm arm is the stiffest
    assert png.stat().st_size > 1000
    assert len(out["samples"]) == 2 and len(out["samples"][0]["elements"]) == 10
    assert main(["calibrate", "--design", design, "--simulate", "--json"]) == 0
    cal_out = strict_json(capsys.readouterr().out)
    assert cal_out["audit"]["flags"] == []


def test_calibrate_a_design_without_rigs_takes_the_catalogue_gauge_for_its_rating(capsys):
    # a comb for the 10 mm jaw has no rigs: the gauge in series is the catalogue's for its
    # rated force, said in the report (it crashed reading the rigs' gauge)
    from tactcad.design.array_plan import EXAMPLES
    from tactcad.vocabulary.force_gauge_catalogue import force_gauges

    design = str(EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")
    assert main(["calibrate", "--design", design, "--simulate", "--json"]) == 0
    out = strict_json(capsys.readouterr().out)
    gauge = out["force_gauge"]
    rated = out["full_scale_force_N"]
    chosen = next(g for g in force_gauges() if g.model == gauge["model"])
    assert "no rigs" in gauge["source"] and gauge["stiffness_N_per_mm"] == chosen.stiffness_N_per_mm
    assert chosen.range_N >= rated  # sized for the rating
    assert out["simulated_noise"]["force_N"] == chosen.resolution_N
    assert main(["calibrate", "--design", design, "--simulate"]) == 0
    assert f"force gauge in series: {chosen.model}" in capsys.readouterr().out


def six_element_design(tmp_path) -> Path:
    text = DEFAULT_TOML.read_text(encoding="utf-8")
    text = text.replace("columns = 5\n", "columns = 3\n")
    text = text.replace("lengths_mm = [4.0, 7.0, 6.0, 8.0, 6.0, 8.0, 5.0, 4.0, 5.0, 7.0]",
                        "lengths_mm = [4.0, 7.0, 6.0, 8.0, 5.0, 4.5]")
    path = tmp_path / "six.toml"
    path.write_text(text, encoding="utf-8")
    return with_default_companions(path)


def test_table1_audit_on_a_smaller_array_skips_missing_elements(tmp_path, capsys):
    assert main(["calibrate", "--design", str(six_element_design(tmp_path)), "--json"]) == 0
    out = strict_json(capsys.readouterr().out)
    assert out["skipped_elements"] == [7, 8, 9, 10]
    assert [r["element"] for r in out["audit"]["elements"]] == [1, 2, 3, 4, 6]


def test_evaluate_none_coupling_json_is_eq2(capsys):
    assert main(["evaluate", "--coupling", "none", "--stiffness", "table1", "--samples", "3.85",
                 "--json"]) == 0
    out = strict_json(capsys.readouterr().out)
    e6 = next(e for e in out["samples"][0]["elements"] if e["element"] == 6)
    assert e6["R"][0] == pytest.approx((80.38 + 3.85) / (7.35 + 3.85), rel=1e-12)
    assert out["fig6"]["K_obj_N_per_mm"] == 3.85


def test_calibrate_table1_text(capsys):
    assert main(["calibrate"]) == 0
    out = capsys.readouterr().out
    assert "elements 1 and 8 (element_a4mm): K differ 2.00x" in out


@pytest.mark.parametrize("argv,needle", [
    (["evaluate", "--samples", "3,-1"], "samples = -1.0"),
    (["evaluate", "--samples", "3,x"], "samples = 'x'"),
    (["evaluate", "--poisson", "0.7", "--samples", "3"], "--poisson: '0.7': allowed a number 0 ... 0.5"),
    (["evaluate", "--coupling", "layer", "--thickness", "-2", "--samples", "3"],
     "--thickness: '-2': allowed a number >0 ... 10000 (mm)"),
    (["calibrate", "--data", "{empty}"], "no header"),
    (["calibrate", "--data", "{wrong}"], "missing ['force_N', 'signal_V']"),
    (["calibrate", "--data", "{missing_file}"], "cannot be read"),
    (["calibrate", "--simulate", "--gain", "0"], "gauge_gain_V_per_strain = 0.0"),
    (["calibrate", "--data", "{falling}"], "allowed > 0"),
    (["calibrate", "--data", "{unknown_element}"], "element = 11"),
])
def test_cli_errors_exit_2_with_field_and_value(argv, needle, tmp_path, capsys):
    (tmp_path / "empty.csv").write_text("", encoding="utf-8")
    (tmp_path / "wrong.csv").write_text("element,run,z_um\n1,1,0\n", encoding="utf-8")
    header = "element,run,z_um,force_N,signal_V\n"
    (tmp_path / "falling.csv").write_text(header + "1,1,0,0,0\n1,1,25,-0.5,0.1\n1,1,50,-1.0,0.2\n",
                                          encoding="utf-8")
    (tmp_path / "unknown.csv").write_text(header + "11,1,0,0,0\n11,1,25,0.5,0.1\n11,1,50,1.0,0.2\n",
                                          encoding="utf-8")
    files = {"empty": tmp_path / "empty.csv", "wrong": tmp_path / "wrong.csv",
             "falling": tmp_path / "falling.csv", "unknown_element": tmp_path / "unknown.csv",
             "missing_file": tmp_path / "nope.csv"}
    argv = [a.format(**files) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(("tactcad: error:", f"tactcad {argv[0]}: error:"))
    assert needle in err and err.count("\n") == 1
    assert "Traceback" not in err


def test_finite_json_replaces_non_finite():
    from tactcad.commands.finite_json import dumps

    text = dumps({"a": float("nan"), "b": [np.float64("inf"), 1.5], "c": np.int64(3)})
    assert strict_json(text) == {"a": None, "b": [None, 1.5], "c": 3}


def test_the_sample_modulus_comes_from_the_designs_own_tip_face():
    """K_obj is what one tip reads: a lone tip of any face sees compliance 1/K_obj on the coupled sample."""
    from tactcad.mechanics.contact import Punch
    from tactcad.mechanics.evaluation import ArrayElement, SampleSpec, sample_compliance

    for face in ((1.0, 3.0), (2.0, 3.0), (0.6, 1.0)):
        lone = [ArrayElement(1, 10.0, Punch(0.0, 0.0, *face))]
        assert sample_compliance(lone, 4.0, SampleSpec("halfspace"))[0, 0] == pytest.approx(1 / 4.0, rel=1e-9)


def test_a_reading_file_that_leaves_out_an_element_flags_it(tmp_path, capsys):
    # one element's rows missing: the rest were fitted and the report said "flags (0)"
    source = REPO / "hardware" / "macro_array" / "calibration_example.csv"
    lines = source.read_text(encoding="utf-8").splitlines(keepends=True)
    short = tmp_path / "short.csv"
    short.write_text("".join(l for l in lines if not l.startswith("3,")), encoding="utf-8")
    assert main(["calibrate", "--data", str(source), "--json"]) == 0
    whole = strict_json(capsys.readouterr().out)["elements_without_readings"]
    assert whole == [5]  # the paper's element 5 did not work: the example has no rows of it
    assert main(["calibrate", "--data", str(short), "--json"]) == 0
    out = strict_json(capsys.readouterr().out)
    assert out["elements_without_readings"] == [3, 5]
    assert any(f["text"].startswith("element 3: no readings") for f in out["audit"]["flags"])


@pytest.mark.parametrize("command", ["table1", "table2"])
def test_a_design_that_does_not_cite_the_paper_is_refused_with_the_command_to_run(command,
                                                                                  capsys):
    # table2's refusal told the lab to run table1 in the paper's project
    ti = str(REPO / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")
    assert main([command, "--design", ti, "--json"]) == 2
    error = strict_json(capsys.readouterr().out)["error"]
    assert error["alternatives"][0]["words"].endswith(f"run {command} in it")
    # table2's refusal said the design could not reproduce the paper's Table 1
    table = {"table1": "Table 1", "table2": "Table 2"}[command]
    assert error["allowed"].startswith(f"a design that cites the paper and can reproduce its "
                                       f"{table}")


def test_evaluate_loads_a_design_as_its_own_rig_states(tmp_path, monkeypatch, capsys):
    # a designed project's rigs give their own preload and weights (the shipped 2 x 3
    # example, written by `design`: 0.049 N and 4 x 5 g), but evaluate loaded six equal
    # steps to 1.119 N; its help quoted the paper's 2 x 3 mm punch. The shipped project
    # stands for a fresh design's (a whole design search is the slow tier's)
    monkeypatch.chdir(tmp_path)
    shutil.copytree(REPO / "hardware" / "ti_array_2x3", tmp_path / "ti")
    design = ["--design", "ti/ti_array_2x3.toml", "--samples", "5", "--json"]
    assert main(["evaluate", *design]) == 0
    out = strict_json(capsys.readouterr().out)
    step = 5e-3 * ev.STANDARD_GRAVITY
    assert out["fig6"]["loads_N"] == pytest.approx([0.049033 + k * step for k in range(5)])
    assert "evaluation rig (rigs.toml): 0.04903 N preload + 4 x 5 g" in out["load_steps_from"]
    assert main(["evaluate", *design, "--steps", "3"]) == 0  # equal steps, when asked
    out = strict_json(capsys.readouterr().out)
    assert len(out["fig6"]["loads_N"]) == 3 and "(--steps)" in out["load_steps_from"]
    with pytest.raises(SystemExit):
        main(["evaluate", "--help"])
    words = " ".join(capsys.readouterr().out.split())
    assert "2 x 3 mm" not in words and "the design's own tip face" in words


def test_evaluate_warns_where_the_rig_loads_an_element_past_its_rating_or_yield(
        tmp_path, monkeypatch, capsys):
    """A lab's `new --example macro_array`, its K_obj range and arms edited: evaluate put
    tip forces up to 0.83 N against the 0.26 N rating and warned nothing, under the keys
    `fig6` and `fig7` (the paper's figure numbers). It warns naming each element past its
    rating or yield-limited force; the keys say what the series are (the old ones
    deprecated duplicates)."""
    import re

    from tactcad.project_folder import new_project
    from tactcad.studies.reference_loads import strength_summary
    from tactcad.studies.verification import rated_full_scale_force

    made = new_project(tmp_path / "stack6", example="macro_array")
    text = made.design.read_text(encoding="utf-8")
    text = re.sub(r"kobj_range_N_per_mm = \[[^\]]*\]", "kobj_range_N_per_mm = [0.8, 6.0]", text)
    text = re.sub(r"thickness_mm = 3\.0 ", "thickness_mm = 2.5 ", text, count=1)
    text = re.sub(r"lengths_mm = \[[^\]]*\]",
                  "lengths_mm = [4.5, 5.0, 6.0, 7.0, 7.5, 6.0, 7.5, 7.0, 6.5, 5.5]", text)
    made.design.write_text(text, encoding="utf-8")
    monkeypatch.chdir(made.folder)
    assert main(["evaluate", "--design", made.design.name, "--json"]) == 0
    out = strict_json(capsys.readouterr().out)
    plan = tactcad.load(made.design).plan
    rated = rated_full_scale_force(plan)
    yield_N = {r["element"]: r["yield_limited_force_N"] for r in strength_summary(plan)}
    top = {}
    for s in out["samples"]:
        for e in s["elements"]:
            top[e["element"]] = max(top.get(e["element"], 0.0), max(e["tip_force_N"]))
    past_rating = [n for n, f in top.items() if f > rated]
    past_yield = [n for n, f in top.items() if f > yield_N[n]]
    assert past_rating and past_yield
    for n in past_rating:
        [line] = [w for w in out["warnings"] if w.startswith(f"evaluate: element {n} carries")]
        assert f"{top[n]:.3g} N" in line and f"rated full-scale force {rated:.3g} N" in line
        assert ("yield-limited force" in line) == (n in past_yield)
    assert out["R_against_load"] == out["fig6"]
    assert out["R_against_K_m_over_K_obj"] == out["fig7"]
    assert out["deprecated_keys"] == {"fig6": "R_against_load", "fig7": "R_against_K_m_over_K_obj"}
    assert main(["evaluate", "--design", made.design.name, "--quiet"]) == 0
    assert "carries up to" not in capsys.readouterr().err
