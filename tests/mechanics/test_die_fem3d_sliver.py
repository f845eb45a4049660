"""The die's fem3d mesh snaps a sliver between the post's footprint and the beam's edge:
a lab's die with 100 um posts on 102 um beams left a 1 um layer of cells across the whole
block (the frame's cells graded from it), 206 000 unknowns and 865 s for ``stiffness
--model fem3d``; snapped, its mesh is the one of the same die with the sliver closed, and
K on a coarse mesh stays within 1 % of the unsnapped mesh's (the change is the mesh's: K
does not see the footprint)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import tactcad
from conftest import DIE_EXAMPLE as EXAMPLE

#: K's (and f1's) largest relative change between the snapped and the unsnapped mesh of a die
#: with a 1 um sliver, coarse divisions (6, 1, 1): measured 0.61 % in K and 0.33 % in f1 on
#: the shipped die's reference beam with 126 um posts (the unsnapped mesh is finer across the
#: beam and the frame; a lab's 102 um beam: 0.55 %, halving with the mesh, 0.23 % at
#: (12, 2, 2)).
COARSE_SNAP_TOLERANCE_REL = 0.01


@pytest.fixture(scope="module")
def plans():
    """The shipped die, the same with its posts 2 um narrower than its beams (a 1 um sliver
    each side) and with its posts as wide as its beams (the sliver closed)."""
    plan = tactcad.load(EXAMPLE).plan
    width = plan.beams[0].width_um
    return (plan, dataclasses.replace(plan, post_um=width - 2.0),
            dataclasses.replace(plan, post_um=width))


def test_an_edge_snaps_onto_its_anchor_only_within_the_tolerance():
    from tactcad.products.silicon_die.mechanics.die_fem3d import snapped_edge

    assert snapped_edge(50.0, (51.0,), 10.0) == 51.0
    assert snapped_edge(-50.0, (-51.0, 51.0), 10.0) == -51.0  # the nearest anchor
    assert snapped_edge(40.0, (51.0,), 10.0) == 40.0  # 11 um: kept
    assert snapped_edge(51.0, (51.0,), 10.0) == 51.0
    with pytest.raises(ValueError, match="tolerance -1"):
        snapped_edge(50.0, (51.0,), -1.0)


def test_a_sub_mesh_sliver_adds_no_node_planes(plans):
    from tactcad.products.silicon_die.mechanics.die_fem3d import (DIVISIONS, _mesh, mesh_dofs,
                                                                  sliver_tolerance_um,
                                                                  snapped_footprint)

    plan, thin, closed = plans
    for beam in plan.beams[:: plan.columns]:
        assert 1.0 < sliver_tolerance_um(beam)
        assert snapped_footprint(thin, beam).snapped_um == pytest.approx(1.0)
        assert mesh_dofs(thin, beam) == mesh_dofs(closed, beam)
        snapped, _ = _mesh(thin, beam, DIVISIONS, True)
        kept, _ = _mesh(thin, beam, DIVISIONS, True, snap=False)
        same, _ = _mesh(closed, beam, DIVISIONS, True)
        assert np.array_equal(np.unique(snapped.p[1]), np.unique(same.p[1]))
        # the sliver's planes, kept, cost the coarser mesh more than half again
        assert kept.nvertices > 1.5 * snapped.nvertices


def test_the_shipped_dies_post_is_not_snapped(plans):
    """The shipped 5 mm die's 100 um posts stand 14 um inside its 128 um beams: more than the
    tolerance (10 um in its 40 um layer), so its mesh is as before."""
    from tactcad.products.silicon_die.mechanics.die_fem3d import mesh_dofs, snapped_footprint

    plan = plans[0]
    for beam, fine in zip(plan.beams[:: plan.columns], (127_725, 100_077)):
        assert snapped_footprint(plan, beam).snapped_um == 0.0
        assert mesh_dofs(plan, beam)[1] == fine


def test_the_snap_is_kept_in_the_fem3d_record(plans, monkeypatch):
    from tactcad.products.silicon_die.mechanics import die_fem3d
    from tactcad.products.silicon_die.studies.die_reports import stiffness_report

    monkeypatch.setattr(die_fem3d, "_solve", lambda plan, beam, divisions, frame=True:
                        (1.0 + divisions[0], 1e4, 100 * divisions[0]))
    plan, thin, _ = plans
    snapped = die_fem3d.die_beam_fem3d(thin, thin.beams[0])
    assert snapped.snapped_um == pytest.approx(1.0)
    assert snapped.as_json()["snapped_um"] == pytest.approx(1.0)
    assert die_fem3d.die_beam_fem3d(plan, plan.beams[0]).as_json()["snapped_um"] == 0.0
    report, lines = stiffness_report(thin, "fem3d")
    assert [r["snapped_um"] for r in report["rows"]] == pytest.approx([1.0, 1.0])
    assert any("snapped 1 um onto the beams' sides" in line for line in lines)
    assert all(r["snapped_um"] == 0.0 for r in stiffness_report(plan, "fem3d")[0]["rows"])


@pytest.mark.slow  # the unsnapped coarse mesh: about 20 s
def test_the_snapped_k_stays_within_its_tolerance_of_the_unsnapped_on_a_coarse_mesh(plans):
    from tactcad.products.silicon_die.mechanics.die_fem3d import _solve

    _, thin, _ = plans
    beam = thin.beams[0]
    k, f1, dofs = _solve(thin, beam, (6, 1, 1))
    k_kept, f1_kept, dofs_kept = _solve(thin, beam, (6, 1, 1), snap=False)
    assert dofs < dofs_kept / 2
    assert k == pytest.approx(k_kept, rel=COARSE_SNAP_TOLERANCE_REL)
    assert f1 == pytest.approx(f1_kept, rel=COARSE_SNAP_TOLERANCE_REL)
    assert k != k_kept  # the meshes differ; the models do not see the footprint in K
