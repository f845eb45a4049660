"""``tactcad bench die``'s beams and rows (the figures themselves are the benchmark's to
print, not a test's)."""

from __future__ import annotations

import pytest

from conftest import run_cli
from tactcad.products.silicon_die.benchmarks import die_bench
from tactcad.products.silicon_die.design import mems_die as md
from tactcad.partlib.grasper_jaw import jaw_room
from tactcad.studies.inverse_design import Targets


@pytest.fixture(scope="module")
def plan():
    return md.die_plan(Targets(8.0, (0.3, 3.0), 0.0065), jaw_room("5"), columns=3)


def test_the_beams_are_the_dies_rows_and_slender_corners_of_its_layer(plan):
    rows = die_bench.beams(plan, "rows")
    assert [b.role for _, _, b in rows] == ["reference", "measuring"]
    domain = die_bench.beams(plan, "domain")
    assert len(domain) == len(die_bench.DOMAIN)
    t = plan.stack.device_um
    for _, p, b in domain:
        assert b.thickness_um == t and b.length_um >= md.SLENDERNESS * b.width_um
        assert p.post_um == min(b.width_um, md.POST_MAX_UM)
    ratios = {round(b.width_um / t, 6) for _, _, b in domain}
    assert min(ratios) == 1.0 and max(ratios) == 12.0
    assert len(die_bench.beams(plan, "all")) == len(rows) + len(domain)


def test_each_row_is_measured_against_the_reference_level(plan, monkeypatch):
    """fem3d replaced by a stand-in 3 % softer than the closed form: the closed form then
    reads +3.1 % against it, the clamped form more, and fem3d itself 0."""
    from tactcad.products.silicon_die.mechanics import die_fem3d

    class Fake:
        def __init__(self, k):
            self.k_N_per_mm, self.k_error_rel = k, 0.01

    monkeypatch.setattr(die_fem3d, "die_beam_fem3d", lambda p, b: Fake(
        md.beam_stiffness_N_per_mm(p.youngs_modulus_MPa, b.width_um, b.thickness_um,
                                   b.length_um) * 0.97))
    rows = die_bench.run(plan, "rows", calculix=False)
    assert [r["model"] for r in rows[:3]] == ["clamped", "closed-form", "fem3d"]
    by = {(r["beam"], r["model"]): r for r in rows}
    for role in ("reference beam", "measuring beam"):
        assert by[role, "closed-form"]["error_vs_fem3d_rel"] == pytest.approx(1 / 0.97 - 1)
        assert by[role, "clamped"]["error_vs_fem3d_rel"] > by[role, "closed-form"]["error_vs_fem3d_rel"]
        assert by[role, "fem3d"]["error_vs_fem3d_rel"] == 0.0
        assert by[role, "clamped"]["error_estimate_rel"] is None


def test_bench_die_on_an_arrays_design_is_refused_by_name():
    r = run_cli("bench", "die", "--design", "hardware/macro_array/macro_array.toml")
    assert r.returncode == 2 and "--design" in r.stderr and "die" in r.stderr
    assert "Traceback" not in r.stderr
