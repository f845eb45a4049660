"""The mesh fast path of the interference check judges two parts in one relative pose once
per export: the array's stack recurs in every rig scene, and its pairs' mesh verdicts are
read back, not intersected again, whatever the scene's instance names or frame."""

from __future__ import annotations

from tactcad.checks.interference import Placed
from tactcad.checks.mesh_interference import check_mesh_interference
from tactcad.kernel.locations import offset, placed
from tactcad.kernel.shapes import box_at_origin


def scene(names: tuple[str, str], shift_mm: float, gap_mm: float):
    """Two 2 mm cubes ``gap_mm`` apart along x, the pair moved by ``shift_mm`` along y:
    (placed, part_of, part_solids, locations)."""
    solids = {"block": box_at_origin(2.0, 2.0, 2.0), "stop": box_at_origin(2.0, 2.0, 2.0)}
    locations = {names[0]: offset(0.0, shift_mm, 0.0),
                 names[1]: offset(2.0 + gap_mm, shift_mm, 0.0)}
    part_of = {names[0]: "block", names[1]: "stop"}
    shown = [Placed(n, placed(solids[part_of[n]], loc)) for n, loc in locations.items()]
    return shown, part_of, solids, locations


def test_a_pair_in_the_same_relative_pose_is_judged_on_meshes_once_per_memo():
    memo: dict = {}
    first = check_mesh_interference(*_args(scene(("a", "b"), 0.0, 0.01)), memo=memo)
    again = check_mesh_interference(*_args(scene(("rig_a", "rig_b"), 7.5, 0.01)), memo=memo)
    assert (first.pairs_tested, first.pairs_reused) == (1, 0)
    assert (again.pairs_tested, again.pairs_reused) == (1, 1)
    assert [r.passed for r in again.results] == [r.passed for r in first.results] == [True]
    # another relative pose (the blocks overlapping) is judged anew, and fails
    moved = check_mesh_interference(*_args(scene(("a", "b"), 0.0, -0.5)), memo=memo)
    assert moved.pairs_reused == 0
    assert not all(r.passed for r in moved.results)
    assert any("overlap" in r.detail for r in moved.results if not r.passed)


def _args(made):
    shown, part_of, solids, locations = made
    return shown, set(), part_of, solids, locations
