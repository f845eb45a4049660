"""Sweeps on Dask: grids validated as designs, the design chart, local vs existing cluster."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tactcad.cli import main
from tactcad.design.array_plan import plan_from_dict
from tactcad.errors import DesignError
from tactcad.studies.inverse_design import design_variant
from tactcad.studies.sweeps import check_scheduler_address, design_grid, grid_points


def test_grid_is_monotonic_in_web_and_arm(plan):
    webs, arms = (0.15, 0.25, 0.4), (4.0, 6.0, 8.0)
    rows = design_grid(plan, webs, arms)
    k = {(r.web_mm, r.arm_mm): r.K_N_per_mm for r in rows}
    assert [(r.web_mm, r.arm_mm) for r in rows] == [(t, a) for t in webs for a in arms]
    for t in webs:
        assert k[(t, 4.0)] > k[(t, 6.0)] > k[(t, 8.0)]
    for a in arms:
        assert k[(0.15, a)] < k[(0.25, a)] < k[(0.4, a)]


def test_grid_points_raise_the_notch_radius_to_the_web(plan, design_data):
    design_data["element"]["notch_radius_mm"] = 0.3
    small_r = plan_from_dict(design_data)
    assert [p.geometry.notch_radius_mm for p in grid_points(small_r, [0.2, 0.4], [5.0])] == [0.3, 0.4]
    assert grid_points(small_r, [0.2], [5.0], notch_radii_mm=[1.0])[0].geometry.notch_radius_mm == 1.0
    with pytest.raises(DesignError, match="--model"):
        grid_points(plan, [0.25], [5.0], model="fem9d")


def test_design_variant_grows_length_and_arm_height_only_when_needed(design_data):
    same = design_variant(design_data, arms_mm=design_data["arms"]["lengths_mm"])
    assert same == design_data
    long = design_variant(design_data, web_mm=0.4, notch_radius_mm=1.8, arms_mm=[8.0] * 9 + [14.0])
    assert long["element"]["overall_length_mm"] > design_data["element"]["overall_length_mm"]
    assert long["element"]["arm_height_mm"] == pytest.approx(0.4 + 1.8 + 0.5)
    assert design_data["element"]["web_thickness_mm"] == 0.25  # input untouched
    plan = plan_from_dict(long)  # the grown length holds the bolt pattern
    assert plan.element(10).geometry.arm_length_mm == 14.0
    too_long = design_variant(design_data, arms_mm=[8.0] * 9 + [99.0])
    with pytest.raises(DesignError, match="element.overall_length_mm"):  # still validated
        plan_from_dict(too_long)


def test_malformed_scheduler_address_is_refused(capsys):
    with pytest.raises(DesignError, match="--scheduler"):
        check_scheduler_address("localhost 8786")
    assert main(["tolerance", "--samples", "100", "--scheduler", "8786"]) == 2
    assert "tactcad: error: --scheduler" in capsys.readouterr().err


@pytest.mark.slow
def test_local_cluster_and_existing_cluster_give_the_same_numbers(tmp_path, capsys):
    """An existing scheduler + worker on 127.0.0.1, reached by address, against the
    default LocalCluster: equal Monte Carlo JSON and equal grid CSV."""
    from distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1",
                      scheduler_port=0, dashboard_address=None) as cluster:
        address = cluster.scheduler_address
        assert address.startswith("tcp://127.0.0.1:")
        mc = ["tolerance", "--samples", "6000", "--seed", "5", "--json"]
        assert main(mc + ["--scheduler", address]) == 0
        remote = json.loads(capsys.readouterr().out)
        grid = ["sweep", "grid", "--webs", "0.2", "0.3", "--arms", "4", "7", "--json"]
        assert main(grid + ["--scheduler", address, "--out", str(tmp_path / "remote")]) == 0
        remote_grid = json.loads(capsys.readouterr().out)
    assert main(mc + ["--workers", "2"]) == 0
    local = json.loads(capsys.readouterr().out)
    assert main(mc) == 0  # in this process, no cluster
    inproc = json.loads(capsys.readouterr().out)
    assert main(grid + ["--out", str(tmp_path / "local")]) == 0
    local_grid = json.loads(capsys.readouterr().out)
    assert remote == local == inproc
    assert remote["samples"] == 6000
    drop = lambda rows: [{k: v for k, v in r.items() if k != "wall_time_s"} for r in rows]  # noqa: E731
    assert drop(remote_grid) == drop(local_grid)
    for d in ("remote", "local"):
        assert (tmp_path / d / "design_chart.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    lines = (tmp_path / "local" / "design_grid.csv").read_text().splitlines()
    assert lines[0].startswith("model,web_mm,arm_mm") and len(lines) == 5
    assert Path(tmp_path / "remote" / "design_grid.csv").read_text() != ""


def test_correction_refit_plans_stores_and_fits_without_rerunning(tmp_path):
    """The driver with a stand-in evaluator (fem3d replaced by a known notch
    softening, K = K_EB / (1 + 0.5 q t/R)): every planned design is evaluated
    once, stored, skipped on the next run, and the fit recovers c1 = 0.5."""
    from tactcad.mechanics.closed_form import closed_form_compliance
    from tactcad.studies.correction_sweep import grid_geometry, plan_designs
    from tactcad.studies.sweeps import correction_refit

    def known(job):
        (t, R, a, b, nu), label = job
        g, mat = grid_geometry(t, a, R, sheet_mm=b, poisson_ratio=nu)
        p = closed_form_compliance(t, R, a, arm_height_mm=g.arm_height_mm,
                                   tip_width_mm=g.tip_width_mm, tip_height_mm=g.tip_height_mm,
                                   E=mat.youngs_modulus_MPa, nu=nu, b=b)
        q = float(p.notch_bending / p.total)
        return {"set": label, "web_mm": t, "notch_radius_mm": R, "arm_mm": a, "sheet_mm": b,
                "poisson_ratio": nu, "C_notch_bending": float(p.notch_bending),
                "C_notch_shear": float(p.notch_shear), "C_arm_bending": float(p.arm_bending),
                "C_arm_shear": float(p.arm_shear), "err_fem3d": 0.0,
                "arm_height_mm": g.arm_height_mm,
                "K_fem3d": 1.0 / float(p.total) / (1.0 + 0.5 * q * t / R)}

    calls = []

    def mapper(func, jobs):
        jobs = list(jobs)
        calls.append(len(jobs))
        return [known(j) for j in jobs]

    points = tmp_path / "points.jsonl"
    first = correction_refit(mapper, n_fit=8, n_holdout=2, points_path=points)
    assert first["new_points"] == len(plan_designs(8, 2)) == calls[0]
    assert first["document"]["coefficients"]["c1"] == pytest.approx(0.5, abs=1e-3)
    again = correction_refit(mapper, n_fit=8, n_holdout=2, points_path=points)
    assert calls[1] == 0 and again["new_points"] == 0
    assert len(points.read_text().splitlines()) == calls[0]


def test_the_default_grid_is_the_designs_own_not_the_papers_study(capsys):
    # every design got the paper's arms 4-8 mm and webs 0.15-0.4 mm, and its chart
    # Table 1's measured elements
    from tactcad.commands.sweep import _measured
    from tactcad.design.array_plan import EXAMPLES, element_process_limits, load_design
    from tactcad.studies.sweeps import default_grid_axes

    ti = load_design(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")
    webs, arms = default_grid_axes(ti)
    assert (arms[0], arms[-1], len(arms)) == (6.196, 19.605, 5)
    web = ti.element(1).geometry.web_thickness_mm
    thinnest = element_process_limits(ti.raw).min_web_mm.value_mm
    assert webs[0] == pytest.approx(max(web / 2, thinnest), abs=1e-4)
    assert webs[-1] == pytest.approx(1.5 * web, abs=1e-4) and len(webs) == 5
    assert _measured(ti) == {} and _measured(load_design())["measured"]
    with pytest.raises(SystemExit):
        main(["sweep", "grid", "--help"])
    words = " ".join(capsys.readouterr().out.split())
    assert "design's shortest arm to its longest" in words and "design's web" in words
    assert "[4.0, 5.0" not in words


def test_a_local_cluster_leaves_nothing_in_the_temporary_folder(tmp_path, monkeypatch):
    import tempfile

    from tactcad.studies.sweeps import dask_client

    monkeypatch.setenv("TMPDIR", str(tmp_path))
    monkeypatch.setattr(tempfile, "tempdir", None)  # asked again: TMPDIR
    with dask_client(workers=1) as client:
        assert client.submit(sum, [1, 2]).result() == 3
        assert list(tmp_path.iterdir())  # the scratch space is in the temporary folder
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("terminal", [False, True])
def test_a_sweep_draws_its_progress_bar_on_a_terminal_only(tmp_path, monkeypatch, terminal):
    import tactcad.studies.sweeps as sweeps
    from conftest import run_cli

    if terminal:  # stderr as a terminal's (run_cli's own stderr is a buffer: none)
        monkeypatch.setattr(sweeps, "stderr_is_terminal", lambda: True)
    r = run_cli("sweep", "grid", "--workers", "1", "--webs", "0.3", "0.35", "--arms", "5",
                "--no-cache", "--out", tmp_path)
    assert r.returncode == 0, r.stderr
    assert ("Completed" in r.stderr) is terminal
    if not terminal:  # plain lines a log keeps one by one
        assert "\r" not in r.stderr
        assert "sweep: 2/2 points" in r.stderr.splitlines()


def test_a_grid_value_the_rules_refuse_is_named_by_its_option_each_once(tmp_path, capsys):
    """`--arms 1 50`: both arms refused as --arms with the range (not eight arm entries of
    the design file, nor the element length the 50 mm arm drags along); a web past the range
    is --webs', the notch radius that follows it not named apart."""
    code = main(["sweep", "grid", "--out", str(tmp_path / "a"), "--arms", "1", "50", "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2
    assert [(e["field"], e["value"]) for e in error["errors"]] == [("--arms", 1.0),
                                                                    ("--arms", 50.0)]
    code = main(["sweep", "grid", "--out", str(tmp_path / "w"), "--webs", "0.3", "3", "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and error["field"] == "--webs" and error["value"] == 3.0
    assert "errors" not in error or len(error["errors"]) == 1


def test_a_refused_grid_value_starts_no_cluster(tmp_path, capsys, monkeypatch):
    """`sweep grid --arms 1 50` started a local Dask cluster (its processes, seconds of a
    refusal) before the rules judged the grid: the values are judged first."""
    from tactcad.studies import sweeps

    started = []

    def client(*args, **kwargs):
        started.append(args)
        raise AssertionError("a cluster started for a refused grid")

    monkeypatch.setattr(sweeps, "dask_client", client)
    code = main(["sweep", "grid", "--out", str(tmp_path / "a"), "--arms", "1", "50", "--json"])
    assert code == 2 and started == []
    assert json.loads(capsys.readouterr().out)["error"]["errors"][0]["field"] == "--arms"


def test_a_bad_grid_value_is_refused_without_calling_the_grids_own_options_unknown(capsys):
    code = main(["sweep", "grid", "--webs", "-1", "--out", "x", "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and error["field"] == "--webs"
    assert "unrecognized" not in error["message"]
