"""Closed form and beam against fem3d's own gauge strain on both shipped examples.

The softest and the stiffest element of the paper's design and of the Ti
example: the closed form's grid average (EB x the fitted factor) and its
point strain at the notch centre must be within 3 % of fem3d's, and the
read-out at fem3d must read fem3d's own field from the stiffness level's kept
solves (no solve of its own). fem3d at its default meshes: about 10 s per
element.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from shared_solves import ONE_WORKER, shared_store

ROOT = Path(__file__).resolve().parents[2]
DESIGNS = ("hardware/macro_array/macro_array.toml", "hardware/ti_array_2x3/ti_array_2x3.toml")


def _extremes(design: str):
    from tactcad.api import load

    plan = load(ROOT / design).plan
    parts = sorted(plan.distinct_elements.values(), key=lambda g: g.arm_length_mm)
    return plan, (parts[0], parts[-1])


@pytest.mark.slow
@ONE_WORKER  # its fem3d solves are test_bonded_layer's and the CalculiX test's
@pytest.mark.parametrize("design", DESIGNS)
@pytest.mark.parametrize("which", ("stiffest", "softest"))
def test_closed_form_gauge_strain_within_3_percent_of_fem3d(design, which):
    from tactcad.mechanics.ladder import estimate
    from tactcad.mechanics.readout_chain import (grid_strain_per_N, readout_chain,
                                                 face_mean_strain_as_cut_per_N)
    from tactcad.store import keeping_results

    plan, (stiff, soft) = _extremes(design)
    # the element as cut: the fitted strain factors' subject, and the face the read-out's
    # surface strain reads (the gauge's layer: test_bonded_layer's fem3d test)
    g = (stiff if which == "stiffest" else soft).bare()
    mat, chain = plan.material, readout_chain(plan)
    L, W = chain.grid_length_mm, chain.grid_width_mm
    solved = []
    with keeping_results(shared_store()):
        ref = estimate("fem3d", g, mat)
        import tactcad.mechanics.fem.fem3d as fem3d

        real = fem3d._converge
        fem3d._converge = lambda *a, **k: solved.append(a) or real(*a, **k)
        try:
            fem = face_mean_strain_as_cut_per_N(g, mat, L, W, "fem3d")
            read = grid_strain_per_N(g, mat, chain, "fem3d")
        finally:
            fem3d._converge = real
    assert not solved, "the read-out solved again instead of reading the kept solves"
    for model in ("closed-form", "beam"):
        cf = face_mean_strain_as_cut_per_N(g, mat, L, W, model)
        point = estimate(model, g, mat).face_strain_per_N
        print(f"{design} {g.part_name} {model}: grid {cf['surface']:.5e} vs fem3d "
              f"{fem['surface']:.5e} ({cf['surface'] / fem['surface']:.4f}); point {point:.5e} "
              f"vs {ref.face_strain_per_N:.5e} ({point / ref.face_strain_per_N:.4f})")
        assert cf["surface"] == pytest.approx(fem["surface"], rel=0.03)
        assert point == pytest.approx(ref.face_strain_per_N, rel=0.03)
        # the stated error estimate covers the difference
        assert abs(cf["surface"] / fem["surface"] - 1) <= cf["error_rel"] + fem["error_rel"]
    assert fem["peak"] == pytest.approx(-ref.face_strain_per_N, rel=1e-12)
    assert read["grid"] == pytest.approx(fem["surface"] * read["read_factor"], rel=1e-12)


#: fem3d's ``face_strain_per_N`` (1/N) on the examples' elements as installed (the gauge's
#: glue line and carrier meshed), default meshes, Richardson error < 0.05 %: measured with
#: ``tactcad stiffness --model fem3d --json`` (macro_array elements 1 and 4, ti_array_2x3
#: elements 1 and 2); :func:`test_installed_face_strain_within_3_percent_of_fem3d` holds
#: them to this run's fem3d solves (kept for the run: :mod:`shared_solves`).
FEM3D_FACE_STRAIN_PER_N = {
    ("hardware/macro_array/macro_array.toml", "element_a4mm"): 1.45633e-3,
    ("hardware/macro_array/macro_array.toml", "element_a8mm"): 2.91282e-3,
    ("hardware/ti_array_2x3/ti_array_2x3.toml", "element_a6p196mm"): 3.13721e-3,
    ("hardware/ti_array_2x3/ti_array_2x3.toml", "element_a19p605mm"): 9.92827e-3,
}


@pytest.mark.parametrize("design,part", sorted(FEM3D_FACE_STRAIN_PER_N))
def test_installed_face_strain_is_fem3d_s_quantity(design, part):
    """One name, one quantity: the closed form's and the beam's ``face_strain_per_N`` on
    the element as installed is the face strain under the gauge's layer, as fem3d's is
    (it meshes the layer): within 3 % of fem3d's recorded figure, where the bare face's
    lies about 11 % above it."""
    from tactcad.api import load
    from tactcad.mechanics.ladder import estimate

    plan = load(ROOT / design).plan
    g, mat = plan.distinct_elements[part], plan.material
    assert g.gauge is not None
    fem = FEM3D_FACE_STRAIN_PER_N[(design, part)]
    for model in ("closed-form", "beam"):
        got = estimate(model, g, mat).face_strain_per_N
        assert got == pytest.approx(fem, rel=0.03), model
    bare = estimate("closed-form", g.bare(), mat).face_strain_per_N
    assert bare / fem - 1 > 0.08  # the quantity the closed form reported before


@pytest.mark.slow  # fem3d with the layer meshed on four elements (about 15-35 s each)
@ONE_WORKER  # its fem3d solves are test_bonded_layer's
@pytest.mark.parametrize("design", DESIGNS)
@pytest.mark.parametrize("which", ("stiffest", "softest"))
def test_installed_face_strain_within_3_percent_of_fem3d(design, which):
    """The closed form's and the beam level's face strain at the grid's centre under the
    gauge's layer against fem3d's with the layer meshed, on the element as installed; and
    the recorded figures of :data:`FEM3D_FACE_STRAIN_PER_N` still fem3d's."""
    from tactcad.mechanics.ladder import estimate
    from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain
    from tactcad.store import keeping_results

    plan, (stiff, soft) = _extremes(design)
    g = stiff if which == "stiffest" else soft
    assert g.gauge is not None
    mat = plan.material
    with keeping_results(shared_store()):
        fem3d = estimate("fem3d", g, mat)
        read = grid_strain_per_N(g, mat, readout_chain(plan), "fem3d")
    ref = fem3d.face_strain_per_N
    assert ref == pytest.approx(FEM3D_FACE_STRAIN_PER_N[(design, g.part_name)], rel=1e-4)
    # one name, one quantity: stiffness's grid strain at fem3d is the read-out's (and
    # strength's) mean over the grid's area, not the strain along its centre line
    assert fem3d.grid_strain_per_N == pytest.approx(read["grid"], rel=1e-12)  # signed, as printed
    for model in ("closed-form", "beam"):
        got = estimate(model, g, mat).face_strain_per_N
        print(f"{design} {g.part_name} {model}: face strain under the layer {got:.5e} vs "
              f"fem3d {ref:.5e} ({got / ref:.4f})")
        assert got == pytest.approx(ref, rel=0.03)
        # what the grid reads, the layer's read factor taken section by section along the
        # grid: within the stated errors of fem3d's grid plane (the web's factor alone on
        # the whole span read 4.5 % above it on the Ti example, past its 2.6 %)
        grid = grid_strain_per_N(g, mat, readout_chain(plan), model)
        gap = abs(grid["grid"] / read["grid"] - 1)
        print(f"  grid strain {grid['grid']:.5e} vs fem3d {read['grid']:.5e} ({gap:.4f})")
        assert gap <= grid["error_rel"] + read["grid_error_rel"]
