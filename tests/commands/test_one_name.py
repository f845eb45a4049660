"""One name, one quantity: a strain, stiffness or stress name in the commands' ``--json``
means the same figure in every command that prints it at the same level
(docs/reference/glossary.md): ``stiffness``'s, ``readout``'s and ``strength``'s, at the
closed form, on the macro array and the Ti array; the grid strain also at fem2d on the Ti
array (``thermal``'s too), and in the Python API's ``Element.stiffness()``.
``gauge_strain_per_N``, which meant the face strain in one command and the grid strain in
another, is printed by none."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
MACRO = ROOT / "hardware" / "macro_array" / "macro_array.toml"
TI = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
#: The old name of two quantities (face strain in ``stiffness``, grid strain in ``readout``).
OLD_NAME = "gauge_strain_per_N"


def _json(*argv) -> dict:
    out = run_cli(*argv, "--json")
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def _keys(data) -> set[str]:
    """Every key of a JSON document, at any depth."""
    if isinstance(data, dict):
        return set(data) | set().union(*(_keys(v) for v in data.values()))
    if isinstance(data, list):
        return set().union(*(_keys(v) for v in data))
    return set()


@pytest.fixture(scope="module", params=[MACRO, TI], ids=["macro", "ti"])
def printed(request) -> dict:
    design = request.param
    readout = _json("readout", "--design", design)
    # at the closed form, as the others (strength's default climbs for an undecided rating)
    strength = _json("strength", "--design", design, "--model", "closed-form")
    stiffness = {r["element"]: _json("stiffness", "--design", design, "--element",
                                     r["element"])
                 for r in readout["elements"]}
    return {"design": design, "readout": readout, "strength": strength,
            "stiffness": stiffness}


def test_no_command_prints_the_old_name(printed):
    docs = [printed["readout"], printed["strength"], *printed["stiffness"].values()]
    for doc in docs:
        assert OLD_NAME not in _keys(doc)
    assert all("face_strain_per_N" in s for s in printed["stiffness"].values())
    assert all("grid_strain_per_N" in r for r in printed["readout"]["elements"])


def test_the_grid_strain_is_one_figure_in_stiffness_readout_and_strength(printed):
    readout = {r["element"]: r for r in printed["readout"]["elements"]}
    for rec in printed["strength"]["elements"]:
        n = rec["element"]
        grid = readout[n]["grid_strain_per_N"]  # signed in both: one key, one quantity
        assert printed["stiffness"][n]["grid_strain_per_N"] == pytest.approx(grid, rel=1e-12)
        grid = abs(grid)  # strength's figure at the rating is a magnitude
        # strength prints it at the rating: grid_strain_per_N x the full-scale force
        assert rec["gauge_strain_at_full_scale"] / rec["full_scale_force_N"] == \
            pytest.approx(grid, rel=1e-12)


def test_the_stiffness_is_one_figure_in_stiffness_readout_and_strength(printed):
    readout = {r["element"]: r for r in printed["readout"]["elements"]}
    assert printed["readout"]["model"] == "closed-form"
    for rec in printed["strength"]["elements"]:
        n = rec["element"]
        assert rec["model"] == "closed-form"
        k = printed["stiffness"][n]["stiffness_N_per_mm"]
        assert printed["stiffness"][n]["model"] == "closed-form"
        assert readout[n]["stiffness_N_per_mm"] == pytest.approx(k, rel=1e-12)
        assert rec["stiffness_N_per_mm"] == pytest.approx(k, rel=1e-12)


def test_the_face_strains_say_where_and_whether_as_cut(printed):
    """stiffness's face_strain_per_N is the face under the gauge's layer; readout's
    face_strain_as_cut_per_N the same point on the element as cut (the closed form's
    stiffness result of the bare element); neither is what the grid reads."""
    from tactcad.design.array_plan import load_design
    from tactcad.mechanics.ladder import estimate

    plan = load_design(printed["design"])
    for r in printed["readout"]["elements"]:
        n = r["element"]
        g = plan.element(n).geometry
        bare = estimate("closed-form", g.bare(), plan.material).face_strain_per_N
        assert abs(r["face_strain_as_cut_per_N"]) == pytest.approx(bare, rel=1e-12)
        face = printed["stiffness"][n]["face_strain_per_N"]
        assert face == pytest.approx(
            estimate("closed-form", g, plan.material).face_strain_per_N, rel=1e-12)
        # the layer relieves the face under it; the grid, above the face, reads more
        assert face < 0.95 * bare
        assert abs(r["grid_strain_per_N"]) > 1.05 * face
        assert r["face_mean_over_centre_as_cut"] == pytest.approx(
            r["face_mean_strain_as_cut_per_N"] / r["face_strain_as_cut_per_N"], rel=1e-12)


@pytest.fixture(scope="module")
def printed_fem2d(tmp_path_factory) -> dict:
    """The Ti array's figures at fem2d: ``readout``, ``strength`` and ``thermal`` of every
    element, ``stiffness`` of one element of each distinct part. The commands share one
    store, as a project's do: a quantity two of them name is solved once and read by both
    (a command that computed another quantity would key it apart and solve it itself)."""
    store = str(tmp_path_factory.mktemp("one-name-store"))
    readout = _json("readout", "--design", TI, "--model", "fem2d", "--cache", store)
    first_of_part = {}
    for r in readout["elements"]:
        first_of_part.setdefault(r["part"], r["element"])
    numbers = sorted(first_of_part.values())
    return {"readout": readout,
            "strength": _json("strength", "--design", TI, "--model", "fem2d", "--cache", store),
            "thermal": _json("thermal", "--design", TI, "--model", "fem2d", "--cache", store),
            "stiffness": {n: _json("stiffness", "--design", TI, "--element", n, "--model",
                                   "fem2d", "--cache", store) for n in numbers}}


def test_the_grid_strain_is_one_figure_at_fem2d(printed_fem2d):
    """At fem2d the grid strain is the grid's plane over the grid's area (the line the plane
    solve gives times the fem3d-fitted width factor) in every command, ``stiffness`` too."""
    signed = {r["element"]: r["grid_strain_per_N"] for r in printed_fem2d["readout"]["elements"]}
    readout = {n: abs(e) for n, e in signed.items()}
    thermal = {r["element"]: abs(r["grid_strain_per_N"])
               for r in printed_fem2d["thermal"]["elements"]}
    strength = {r["element"]: r["gauge_strain_at_full_scale"] / r["full_scale_force_N"]
                for r in printed_fem2d["strength"]["elements"]}
    assert printed_fem2d["readout"]["model"] == printed_fem2d["thermal"]["model"] == "fem2d"
    assert len(printed_fem2d["stiffness"]) >= 2  # the Ti array's two arm lengths
    assert {r["model"] for r in printed_fem2d["strength"]["elements"]} == {"fem2d"}
    for n, s in printed_fem2d["stiffness"].items():
        assert s["model"] == "fem2d"
        assert s["grid_strain_per_N"] == pytest.approx(signed[n], rel=1e-12)
        assert thermal[n] == pytest.approx(readout[n], rel=1e-12)
        assert strength[n] == pytest.approx(readout[n], rel=1e-12)


def test_the_api_gives_stiffness_its_grid_strain_at_the_closed_form(printed):
    """``Element.stiffness()`` (the closed form) carries the grid strain ``tactcad stiffness``
    prints for that element."""
    import tactcad

    project = tactcad.load(printed["design"])
    for n, s in printed["stiffness"].items():
        api = project.element(n).stiffness()
        assert api.model == s["model"] == "closed-form"
        assert api.grid_strain_per_N is not None
        assert api.grid_strain_per_N == pytest.approx(s["grid_strain_per_N"], rel=1e-12)


def test_the_tolerance_studys_nominal_k_is_the_stiffness_commands_to_the_last_digit(printed):
    # the Monte Carlo's nominal K came from the vectorised kernel: equal to rounding
    # (30.074653416256602 against 30.074653416256595), not one figure
    tolerance = _json("tolerance", "--design", printed["design"], "--samples", "200")
    assert tolerance["elements"]
    for rec in tolerance["elements"]:
        assert rec["K_nominal_N_per_mm"] == \
            printed["stiffness"][rec["element"]]["stiffness_N_per_mm"], rec["element"]
