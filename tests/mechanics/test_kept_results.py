"""The estimators' heavy results are kept in the store by content key
(:func:`tactcad.store.kept_result`) and reused by every command: a second call
with the same element solves nothing, a changed input solves again.

Solves are counted by a counter put in place of the solver, never by time.
The fem3d tests put a stand-in for the solve itself (the keeping is under
test, not the FEM; a real sequence takes minutes) and always name their own
store, so no stand-in result reaches another test's store.
"""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from tactcad.cli import main
from tactcad.design.array_plan import load_design
from tactcad.mechanics import ladder
from tactcad.mechanics.fem import fem2d, fem3d
from tactcad.mechanics.fem.fields import FaceStrain, PeakStress
from tactcad.store import Store, keeping_results
from tactcad.studies.strength_studies import fem_peak_stress


@pytest.fixture
def counted(monkeypatch):
    """``counted(module, name)``: the calls of ``module.name`` from now on (a list)."""
    def install(module, name: str) -> list:
        real, calls = getattr(module, name), []

        def counting(*args, **kwargs):
            calls.append(args)
            return real(*args, **kwargs)

        monkeypatch.setattr(module, name, counting)
        return calls
    return install


@pytest.fixture
def fem3d_solves(monkeypatch) -> list:
    """fem3d's one-mesh solve replaced by a counted stand-in: the closed form's
    K and gauge strain, converging with the mesh size, and a peak stress that
    converges too. Returns the list of (part, size factor) solved."""
    from tactcad.mechanics.closed_form import estimate_closed_form

    calls: list = []

    def solve(g, material, *, size_factor=1.0, force_N=fem2d.DEFAULT_FORCE_N,
              keep_field=False, **settings):
        calls.append((g.part_name, size_factor))
        cf = estimate_closed_form(g, material)
        k = cf.stiffness_N_per_mm * (1.0 + 0.01 * size_factor ** 2)
        return fem2d.FemSolution(k, force_N / k, -cf.face_strain_per_N * force_N, force_N,
                                 n_dofs=1000, n_cells=100, neck_size_mm=0.05, wall_time_s=0.0,
                                 field=size_factor if keep_field else None)

    def peak(field, g):
        return PeakStress(100.0, 50.0 * (1.0 + 0.02 * field ** 2), (0.0, 0.0, 0.0))

    monkeypatch.setattr(fem3d, "solve_fem3d", solve)
    monkeypatch.setattr(fem3d, "peak_notch_stress", peak)
    monkeypatch.setattr(fem3d, "top_face_strain", lambda field, y_top_mm: FaceStrain(
        np.array([[[-1e3, 0.0], [1e3, 0.0], [1e3, 1e3]], [[-1e3, 0.0], [1e3, 1e3], [-1e3, 1e3]]]),
        np.full((2, 3), -1e-3 * (1.0 + 0.01 * field ** 2)), None))
    return calls


def test_a_second_estimate_of_the_same_element_solves_nothing(plan, tmp_path, counted):
    solves = counted(fem2d, "solve_fem2d")
    g, mat = plan.element(1).geometry, plan.material
    with keeping_results(Store(tmp_path / "store")):
        first = ladder.estimate("fem2d", g, mat, element=1)
        per_estimate = len(solves)
        assert per_estimate == 3  # the Richardson sequence
        # element 8 has element 1's geometry: its number is carried, nothing solved
        again = ladder.estimate("fem2d", plan.element(8).geometry, mat, element=8)
        assert len(solves) == per_estimate
        assert again.element == 8 and replace(again, element=1) == first
        # a changed geometry or material misses
        thicker = replace(g, web_thickness_mm=g.web_thickness_mm + 0.01)
        assert ladder.estimate("fem2d", thicker, mat).stiffness_N_per_mm > \
            first.stiffness_N_per_mm
        assert len(solves) == 2 * per_estimate
        ladder.estimate("fem2d", g, replace(mat, youngs_modulus_MPa=70000.0))
        assert len(solves) == 3 * per_estimate
    # with no store (--no-cache) a block keeps its results for its length only
    for _ in range(2):
        with keeping_results(Store(None)):
            ladder.estimate("fem2d", g, mat)
            ladder.estimate("fem2d", g, mat)
    assert len(solves) == 5 * per_estimate
    assert not (tmp_path / "store" / "memo").exists() or len(list(
        (tmp_path / "store" / "memo").rglob("*.pickle"))) == 3
    # outside a block every call solves
    ladder.estimate("fem2d", g, mat)
    assert len(solves) == 6 * per_estimate


def test_an_unreadable_entry_is_solved_again(plan, tmp_path, counted):
    solves = counted(fem2d, "solve_fem2d")
    g, mat = plan.element(1).geometry, plan.material
    with keeping_results(Store(tmp_path / "store")):
        first = ladder.estimate("fem2d", g, mat)
    for entry in (tmp_path / "store" / "memo").rglob("*.pickle"):
        entry.write_bytes(entry.read_bytes()[:20])  # a damaged entry
    with keeping_results(Store(tmp_path / "store")):  # the next run
        again = ladder.estimate("fem2d", g, mat)
    assert len(solves) == 6
    assert replace(again, wall_time_s=first.wall_time_s) == first


def test_fem3d_stiffness_and_peak_stress_share_one_kept_sequence(plan, tmp_path, fem3d_solves):
    """The element as cut: its K and its peak stress from one kept sequence. With its
    gauge: the peak read from that sequence, K from the layered one (one sequence more)."""
    g, mat = plan.element(1).geometry, plan.material
    with keeping_results(Store(tmp_path / "store")):
        k = ladder.estimate("fem3d", g.bare(), mat)
        assert len(fem3d_solves) == 3
        stress = fem_peak_stress(g.bare(), mat, "fem3d")  # the strength study's solves are the same
        assert len(fem3d_solves) == 3
        assert stress.stiffness_N_per_mm == k.stiffness_N_per_mm
        assert ladder.estimate("fem3d", g.bare(), mat) == k
        assert len(fem3d_solves) == 3
        installed = fem_peak_stress(g, mat, "fem3d")
        assert len(fem3d_solves) == 6
        assert installed.stress_MPa_per_N == stress.stress_MPa_per_N
        assert installed.stiffness_N_per_mm == ladder.estimate("fem3d", g, mat).stiffness_N_per_mm
        assert len(fem3d_solves) == 6
        shorter = replace(g.bare(), arm_length_mm=g.arm_length_mm - 0.5)
        fem_peak_stress(shorter, mat, "fem3d")
        assert len(fem3d_solves) == 9


@pytest.mark.slow  # a whole chain through the command line or an export
def test_verify_right_after_design_solves_no_fem3d_again(tmp_path, monkeypatch, fem3d_solves,
                                                         capsys):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("TACTCAD_WORKERS", "0")  # every solve in this process, where it is counted
    store = ["--cache", str(tmp_path / "store")]
    # the stand-in's stresses decide the fem3d verdicts (exit 1 on a fail); written either way
    assert main(["design", "--kr-over-km", "3", "--kobj-range", "5", "20",
                 "--full-scale-force", "0.3", "--material", "7075-T6", "--verify", "fem3d",
                 "--out", "next.toml", "--json", *store]) in (0, 1)
    assert json.loads(capsys.readouterr().out)["verify"]["level"] == "fem3d"
    distinct = len(load_design(tmp_path / "next.toml").distinct_elements)
    # two sequences of three meshes an element: K with the gauge's layer meshed, the
    # hinge's peak stress on the element as cut
    per_run = 2 * 3 * distinct
    assert len(fem3d_solves) == per_run
    capsys.readouterr()
    main(["verify", "--design", "next.toml", "--model", "fem3d", "--json", *store])
    record = json.loads(capsys.readouterr().out)
    assert record["model"] == "fem3d" and record["matrix"]
    assert len(fem3d_solves) == per_run  # stiffness and peak stress from design's solves
    # --no-cache solves afresh, each sequence once in the run
    main(["verify", "--design", "next.toml", "--model", "fem3d", "--json", "--no-cache"])
    assert len(fem3d_solves) == 2 * per_run


@pytest.mark.slow  # a second interpreter
def test_the_key_is_the_same_in_a_new_process(tmp_path):
    """A second command in a new process reuses the first's solve (and says so)."""
    argv = [sys.executable, "-m", "tactcad.cli", "stiffness", "--element", "1", "--model",
            "fem2d", "--cache", str(tmp_path / "store")]
    first = subprocess.run(argv, capture_output=True, text=True, cwd=tmp_path, check=True)
    second = subprocess.run(argv, capture_output=True, text=True, cwd=tmp_path, check=True)
    assert "mesh 3/3" in first.stderr and "reused" not in first.stderr
    assert "fem2d element_a4mm: reused from the result store" in second.stderr
    assert "mesh" not in second.stderr
    assert second.stdout == first.stdout
    assert not any(Path(tmp_path).glob("*.part"))


def test_a_run_killed_while_keeping_a_result_leaves_no_entry(plan, tmp_path, counted,
                                                             monkeypatch):
    """The entry is written beside its place and renamed into it: killed just
    before the rename, the run leaves nothing the next run would read."""
    import os

    solves = counted(fem2d, "solve_fem2d")
    g, mat = plan.element(1).geometry, plan.material

    def killed(src, dst):
        raise KeyboardInterrupt

    with monkeypatch.context() as m:
        m.setattr(os, "replace", killed)
        with pytest.raises(KeyboardInterrupt), keeping_results(Store(tmp_path / "store")):
            ladder.estimate("fem2d", g, mat)
    assert not list((tmp_path / "store").rglob("*.pickle"))
    with keeping_results(Store(tmp_path / "store")):
        ladder.estimate("fem2d", g, mat)
    assert len(solves) == 6
    assert len(list((tmp_path / "store").rglob("*.pickle"))) == 1


def test_the_counts_tell_computed_reused_and_missing_apart(tmp_path):
    from tactcad.store import NotKept, counting_results, kept_result, only_kept

    with keeping_results(Store(tmp_path / "store")), counting_results() as counts:
        assert kept_result("a product", lambda: 6 * 7, "six", "seven") == 42
        assert kept_result("a product", lambda: -1, "six", "seven") == 42  # read back
        with only_kept(), pytest.raises(NotKept):
            kept_result("a product", lambda: 0, "other", "inputs")
    assert counts.computed == {"a product": 1}
    assert counts.reused == {"a product": 1}
    assert counts.missing == {"a product": 1}
    assert counts.solved() == 2
    with keeping_results(Store(tmp_path / "store")), counting_results() as again:
        kept_result("a product", lambda: -1, "six", "seven")  # a later run: from the store
    assert again.solved() == 0 and again.reused == {"a product": 1}


def test_a_reused_result_says_whether_a_store_was_read(tmp_path):
    """--no-cache said "reused from the result store" for a solve kept in the run's memory."""
    from tactcad.store import REUSED_FROM_STORE, REUSED_IN_RUN, kept_result

    said = []
    for store in (Store(None), Store(tmp_path / "store"), Store(tmp_path / "store")):
        with keeping_results(store):
            for _ in range(2):
                kept_result("probe", lambda: 42, "inputs", reused=said.append)
    # no store: the second call reuses the first's solve; a store: the third block reads it
    assert said == [REUSED_IN_RUN, REUSED_IN_RUN, REUSED_FROM_STORE, REUSED_IN_RUN]
    assert "store" not in REUSED_IN_RUN


def test_a_kept_result_warns_as_its_computation_did_on_every_read(tmp_path):
    # a solve outside a fit's range warned on the run that solved it and was silent on
    # every run that read it back from the store
    import warnings

    from tactcad.store import kept_result

    runs: list[str] = []

    def warned() -> float:
        runs.append("solved")
        warnings.warn("outside the fit's range: web 0.02 mm", UserWarning)
        return 1.5

    for attempt in range(3):  # a first run, then two runs reading the store back
        with keeping_results(Store(tmp_path / "store")), \
                warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always")
            assert kept_result("a warned solve", warned, "inputs") == 1.5
            assert kept_result("a warned solve", warned, "inputs") == 1.5  # in memory
        assert [str(w.message) for w in said] == ["outside the fit's range: web 0.02 mm"] * 2, \
            attempt
    assert runs == ["solved"]


def test_a_kept_result_whose_warning_does_not_pickle_is_still_returned_and_said(tmp_path):
    import warnings

    from tactcad.store import kept_result

    class Unpicklable(UserWarning):
        pass  # a class local to a function does not pickle

    def warned() -> int:
        warnings.warn(Unpicklable("a library's own warning"))
        return 7

    for _ in range(2):
        with keeping_results(Store(tmp_path / "store")), \
                warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always")
            assert kept_result("an unpicklable warning", warned, "inputs") == 7
        assert [str(w.message) for w in said] == ["a library's own warning"]
