"""``tactcad stiffness --model fem3d`` on a silicon die says what it solves and how it goes
(its meshes' unknowns, counted before solving, against the shipped dies'), as ``modal``
does; and the help's fem3d cost covers a die, whose solve grows with its mesh (an atlas
die's took 865 s wall where the help said 2 min)."""

from __future__ import annotations

import dataclasses
import re

import tactcad
from conftest import DIE_EXAMPLE as EXAMPLE

#: The wall time of ``stiffness --model fem3d`` on an atlas die whose posts stand 1 um inside
#: its beams' edges (s), as reported.
ATLAS_DIE_WALL_S = 865.0


def test_mesh_dofs_counts_the_solves_unknowns_without_solving():
    from skfem import Basis, ElementHex2

    from tactcad.products.silicon_die.mechanics.die_fem3d import DIVISIONS, _mesh, mesh_dofs

    plan = tactcad.load(EXAMPLE).plan
    beam = plan.beams[0]
    coarse, fine = mesh_dofs(plan, beam)
    for d, n in ((DIVISIONS, coarse), (tuple(2 * x for x in DIVISIONS), fine)):
        mesh, _ = _mesh(plan, beam, d, True)
        assert n == 3 * Basis(mesh, ElementHex2(), intorder=1).N  # as the solve counts them
    assert fine > coarse


def test_a_sliver_between_post_and_beam_edges_is_named_as_snapped_with_the_closed_mesh():
    from tactcad.products.silicon_die.mechanics.die_fem3d import mesh_dofs
    from tactcad.products.silicon_die.studies.die_reports import fem3d_solving_line

    plan = tactcad.load(EXAMPLE).plan
    beam = plan.beams[0]
    plain = fem3d_solving_line(plan, beam)
    assert f"{mesh_dofs(plan, beam)[1]:,} unknowns" in plain and "sliver" not in plain
    assert "inside the beam's" not in plain
    thin = dataclasses.replace(plan, post_um=beam.width_um - 2.0)  # a 1 um sliver each side
    line = fem3d_solving_line(thin, thin.beams[0])
    assert "1 um inside the beam's snapped onto them" in line
    closed = dataclasses.replace(plan, post_um=beam.width_um)
    assert mesh_dofs(thin, thin.beams[0]) == mesh_dofs(closed, closed.beams[0])
    assert f"{mesh_dofs(closed, beam)[1]:,} unknowns" in line


def test_stiffness_fem3d_on_a_die_prints_progress_before_and_during_each_solve(
        die_folder, capsys, monkeypatch):
    from tactcad import cli
    from tactcad.products.silicon_die.mechanics import die_fem3d

    solved = []

    def quick(plan, beam, divisions, frame=True):  # no solve: the lines around it
        solved.append(divisions)
        return 1.0 + len(solved), 1e4, 1000 * len(solved)

    monkeypatch.setattr(die_fem3d, "_solve", quick)
    assert cli.main(["stiffness", "--design", str(die_folder / EXAMPLE.name), "--model",
                     "fem3d", "--no-cache"]) == 0
    err = capsys.readouterr().err
    assert len(solved) == 4  # two beams, two meshes each
    for role in ("reference", "measuring"):
        assert re.search(rf"fem3d of die \S+'s {role} beam on its frame: .* [\d,]+ unknowns",
                         err), err
        assert f"{role} beam, mesh 1 of 2" in err and f"{role} beam, mesh 2 of 2" in err
    capsys.readouterr()
    assert cli.main(["stiffness", "--design", str(die_folder / EXAMPLE.name), "--model",
                     "fem3d", "--no-cache", "--quiet"]) == 0
    assert "mesh 1 of 2" not in capsys.readouterr().err  # --quiet: none


def test_the_helps_fem3d_cost_covers_a_dies_solve():
    from tactcad.mechanics.ladder import LEVELS

    cost = LEVELS["fem3d"].cost
    assert "die" in cost and "mesh" in cost
    # every "a-b min" the cost states for a die reaches the reported solve
    die_part = cost[cost.index("die"):]
    top = re.search(r"(\d+(?:\.\d+)?)-(\d+(?:\.\d+)?) min", die_part)
    assert top and 60 * float(top.group(2)) >= ATLAS_DIE_WALL_S
