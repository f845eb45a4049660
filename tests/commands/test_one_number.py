"""One number per quantity: a figure a lab reads in several commands is computed in one
place, so every command's ``--json`` (and the BOM) quotes the same value: the force
resolution (readout, thermal), the bridge excitation (readout, thermal, BOM), the lead
wire (thermal's lead resistance, the BOM's lead wire, grasp's bundle through the shaft),
the gauge strain at the rating (strength, readout)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from tactcad.catalogue.gauges import sensor_items
from tactcad.cli import main
from tactcad.design.array_plan import load_design
from tactcad.design.readout_section import LEAD_WIRE

ROOT = Path(__file__).resolve().parents[2]
TI = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
GRASPER = ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
#: Annealed copper at 20 C (ohm m, IEC 60028), for an independent lead resistance.
COPPER_OHM_M = 1.724e-8


def command_json(argv: list[str], capsys) -> dict:
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.fixture(scope="module")
def ti_readout_and_thermal():
    import io
    from contextlib import redirect_stdout

    out = {}
    for command in ("readout", "thermal"):
        buf = io.StringIO()
        with redirect_stdout(buf):
            assert main([command, "--design", str(TI), "--json"]) == 0
        out[command] = json.loads(buf.getvalue())
    return out


def test_the_force_resolution_is_one_figure_in_readout_and_thermal(ti_readout_and_thermal):
    readout, thermal = ti_readout_and_thermal["readout"], ti_readout_and_thermal["thermal"]
    quoted = {r["element"]: r["force_resolution_N"] for r in readout["elements"]}
    for rec in thermal["elements"]:
        assert rec["force_resolution_N"] == pytest.approx(quoted[rec["element"]], rel=1e-9)


def test_the_excitation_is_one_figure_in_readout_thermal_and_the_bom(ti_readout_and_thermal):
    readout, thermal = ti_readout_and_thermal["readout"], ti_readout_and_thermal["thermal"]
    volts = readout["chain"]["excitation_V"]
    # thermal's grid power is V^2 / (4 R_g) at the same excitation
    assert thermal["grid_power_W"] == pytest.approx(
        volts ** 2 / (4 * readout["chain"]["gauge_resistance_ohm"]), rel=1e-9)
    amplifier = next(i for i in sensor_items(load_design(TI)) if "amplifier" in i.part)
    assert f"excitation {volts:g} V" in amplifier.reference


def test_the_lead_wire_is_one_wire_in_thermal_the_bom_and_the_shaft(ti_readout_and_thermal,
                                                                     capsys):
    chain = ti_readout_and_thermal["readout"]["chain"]
    area_m2 = math.pi * (LEAD_WIRE["conductor_diameter_mm"] * 1e-3) ** 2 / 4
    assert chain["lead_resistance_ohm_per_m"] == pytest.approx(COPPER_OHM_M / area_m2, rel=1e-4)
    lead = next(i for i in sensor_items(load_design(TI)) if i.part == "lead_wire")
    assert f"AWG {LEAD_WIRE['awg']}" in lead.key_dimensions
    leads = command_json(["grasp", "--design", str(GRASPER)], capsys)["leads"]
    assert leads["conductor_diameter_mm"] == LEAD_WIRE["conductor_diameter_mm"]
    assert leads["wire_diameter_mm"] == LEAD_WIRE["insulated_diameter_mm"]


@pytest.mark.slow  # a whole design through the command line
def test_design_reads_the_kobj_resolution_with_the_read_out_chains_force_resolution(tmp_path,
                                                                                  capsys):
    # design printed dK_obj at a fixed 0.01 N (134 %), readout and verify 0.10 %
    out = tmp_path / "d.toml"
    d = command_json(["design", "--kr-over-km", "10", "--kobj-range", "1", "5",
                      "--full-scale-force", "0.14", "--material", "7075-T6", "--columns", "3",
                      "--verify", "none", "--design", str(TI), "--out", str(out)], capsys)
    readout = command_json(["readout", "--design", str(out)], capsys)
    by_role = {e["role"]: e["element"] for e in d["elements"]}
    quoted = {r["element"]: r["force_resolution_N"] for r in readout["elements"]}
    for role in ("reference", "measuring"):
        assert d["force_resolution_N"][role] == pytest.approx(quoted[by_role[role]], rel=1e-9)
    assert all(u["K_obj_resolution_rel"] < 0.05 for u in d["units"])  # not the 0.01 N figure's


@pytest.mark.parametrize("design", [TI, GRASPER], ids=["ti", "grasper"])
def test_the_gauge_strain_at_the_rating_is_the_grids_in_strength_and_readout(design, capsys):
    """strength's gauge strain and gauge fatigue force read the strain the grid reads (the
    read-out's, bonded layer included), not the face's at the notch centre."""
    readout = command_json(["readout", "--design", str(design)], capsys)
    strength = command_json(["strength", "--design", str(design)], capsys)
    grid = {r["element"]: abs(r["grid_strain_per_N"]) for r in readout["elements"]}
    face = {r["element"]: abs(r["face_strain_as_cut_per_N"]) for r in readout["elements"]}
    rating = readout["full_scale_force_N"]
    gauge_fatigue = load_design(design).strength.gauge.fatigue_strain
    for rec in strength["elements"]:
        n = rec["element"]
        assert rec["full_scale_force_N"] == pytest.approx(rating, rel=1e-12)
        assert rec["gauge_strain_at_full_scale"] == pytest.approx(grid[n] * rating, rel=1e-9)
        assert rec["gauge_strain_at_full_scale"] != pytest.approx(face[n] * rating, rel=1e-3)
        assert rec["gauge_fatigue_force_N"] == pytest.approx(gauge_fatigue / grid[n], rel=1e-9)
