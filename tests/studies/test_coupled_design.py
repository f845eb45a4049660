"""Inverse design with the tissue coupling: stiffnesses centred on the range as the coupled units see it."""
from __future__ import annotations

import json
import re
import shutil

import numpy as np
import pytest

from conftest import STACKED_7075_DESIGN
from tactcad.cli import main
from tactcad.design.array_plan import load_design
from tactcad.errors import DesignError
from tactcad.in_use.tissue_coupling import Tissue, apparent_kobj_factor, coupled_sample, design_units
from tactcad.mechanics.evaluation import ladder_stiffness_by_element
from tactcad.studies.inverse_design import Targets, design_for_targets, sensing_unit_numbers

TI = "hardware/ti_array_2x3/ti_array_2x3.toml"


def test_the_seen_factor_scales_both_stiffness_targets():
    plain, seen = Targets(10.0, (1.0, 5.0), 0.1), Targets(10.0, (1.0, 5.0), 0.1, kobj_seen_factor=1.2)
    assert seen.k_m == pytest.approx(1.2 * plain.k_m)
    assert seen.k_r / seen.k_m == pytest.approx(10.0)


def test_a_seen_factor_out_of_range_names_the_option():
    with pytest.raises(DesignError, match="--tissue-coupling"):
        Targets(10.0, (1.0, 5.0), 0.1, kobj_seen_factor=0.0)


def test_coupled_design_centres_on_the_range_the_units_see():
    """After the coupled re-design, eq. 2 sees K_obj on the new design by the factor it was centred for."""
    plan = load_design(TI)
    coupled = design_for_targets(plan, Targets(10.0, (1.0, 5.0), 0.09, tissue=Tissue()))
    factor = coupled.targets.kobj_seen_factor
    assert abs(factor - 1) > 0.02  # 2 x 3 mm tips at 4 mm pitch: the coupling moves the centre
    k = ladder_stiffness_by_element(coupled.plan)
    units = sensing_unit_numbers(coupled.plan)
    seen = apparent_kobj_factor(coupled_sample(coupled.plan), k, units, (1.0, 5.0))
    assert seen == pytest.approx(factor, rel=0.01)
    k_m = min(k.values())
    assert k_m == pytest.approx(coupled.targets.k_m, rel=2e-3)
    assert "tissue-coupling on" in coupled.data["assumptions"]["requirements.kobj_range_N_per_mm"]


def test_without_a_tissue_the_design_is_eq2s_and_says_so():
    plan = load_design(TI)
    plain = design_for_targets(plan, Targets(10.0, (1.0, 5.0), 0.09))
    assert plain.targets.kobj_seen_factor == 1.0
    assert "tissue-coupling off" in plain.data["assumptions"]["requirements.kobj_range_N_per_mm"]


def test_a_layout_whose_coupled_ratio_cannot_span_the_range_is_refused_naming_the_coupling(monkeypatch):
    """The refusal names --tissue-coupling when a unit's coupled R does not fall over the range."""
    import tactcad.studies.inverse_design as inv

    monkeypatch.setattr(inv, "report_points", lambda targets, n=5: np.array([2.0, 1.0]))  # a rising R
    with pytest.raises(DesignError, match="tissue coupling binds") as info:
        design_for_targets(load_design(TI), Targets(10.0, (1.0, 5.0), 0.09, tissue=Tissue()))
    assert info.value.field == "--tissue-coupling"


@pytest.mark.parametrize("mode, says", [("on", "tissue-coupling on"), ("off", "tissue-coupling off")])
def test_cli_states_the_tissue_model_and_reports_the_bias(tmp_path, monkeypatch, capsys, mode, says,
                                                          request):
    monkeypatch.chdir(tmp_path)
    argv = ["design", "--kr-over-km", "3", "--kobj-range", "5", "20", "--full-scale-force", "0.3",
            "--material", "7075-T6", "--verify", "none", "--out", "next.toml", "--json",
            "--tissue-coupling", mode]
    if mode == "on":  # conftest's STACKED_7075_DESIGN: these options, searched once a run
        folder, said = request.getfixturevalue("stacked_7075_designed")
        assert argv == list(STACKED_7075_DESIGN)
        shutil.copytree(folder, tmp_path, dirs_exist_ok=True)
    else:
        assert main(argv) == 0
        said = capsys.readouterr().out
    doc = json.loads(said)
    assert doc["tissue_coupling"]["mode"] == mode
    assert all(0 < u["coupling"] < 1 for u in doc["tissue_coupling"]["units"])
    assert says in (tmp_path / "next.toml").read_text()


def test_cli_refuses_a_bad_tissue_poisson_ratio_by_name(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["design", "--kr-over-km", "3", "--kobj-range", "5", "20", "--full-scale-force", "0.3",
                 "--verify", "none", "--out", "next.toml", "--tissue-poisson", "0.7"]) == 2
    assert "--tissue-poisson" in capsys.readouterr().err


def test_verify_records_the_kobj_bias_before_and_after_the_coupled_correction():
    from tactcad.studies.verification import requirements_of, tissue_coupling_record

    plan = load_design(TI)
    rec = tissue_coupling_record(plan, requirements_of(plan))
    worst_eq3 = max(abs(u["worst_eq3_rel"]) for u in rec["units"])
    assert worst_eq3 > rec["target_rel"]  # eq. 3 on one sample misreads by more than the resolution
    assert rec["eq3"]["verdict"] == "fail"
    # the coupled inversion read against the check level: the two models' disagreement,
    # small against the resolution but not the 0 of a model read against itself
    worst = [abs(u["worst_corrected_rel"]) for u in rec["units"]]
    assert 0 < max(worst) < rec["target_rel"]
    assert rec["coupled"]["verdict"] == "pass"


def test_verify_prints_the_tissue_coupling_as_how_to_read_not_a_failed_requirement(capsys):
    assert main(["verify", "--design", TI, "--model", "closed-form"]) == 0
    line = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("tissue coupling"))
    assert "not a requirement" in line and "FAIL" not in line
    assert "eq. 3 alone" in line and "must not be read so" in line and "reads within it" in line
    # a unit is named reference first, as grasp and the budget name it
    plan = load_design(TI)
    named = {f"{r}/{m}" for m, r in design_units(plan, ladder_stiffness_by_element(plan))}
    shown = re.findall(r"\(unit (\d+/\d+)\)", line)
    assert len(shown) == 2 and set(shown) <= named, (shown, named)


def test_when_eq2s_centring_is_kept_the_factor_the_units_see_is_still_reported(monkeypatch):
    """The report's "K_obj seen" is the coupling's factor, as [assumptions] quotes it, also when
    the centring for the coupling broke a limit and eq. 2's centring was kept."""
    import tactcad.studies.inverse_design as inv

    real = inv._design_from_tables

    def refuse_the_coupled_centring(data, targets, **kw):
        if targets.kobj_seen_factor != 1.0:
            raise inv.InverseDesignError("a limit binds")
        return real(data, targets, **kw)

    monkeypatch.setattr(inv, "_design_from_tables", refuse_the_coupled_centring)
    kept = design_for_targets(load_design(TI), Targets(10.0, (1.0, 5.0), 0.09, tissue=Tissue()))
    assert kept.targets.kobj_seen_factor == 1.0
    assert abs(kept.coupling_seen_factor - 1) > 0.02
    said = kept.data["assumptions"]["requirements.kobj_range_N_per_mm"]
    assert f"x{kept.coupling_seen_factor:.3g}" in said and "eq. 2's centring" in said
