"""The die's implant dose: the stock dose whose quarter bridge drifts least per newton."""
from __future__ import annotations

import dataclasses

import pytest

from tactcad.products.silicon_die.design import mems_die as md
from tactcad.errors import DesignError
from tactcad.products.silicon_die.export.traveller import traveller_steps
from tactcad.products.silicon_die.mechanics.piezoresistor import die_readout
from tactcad.partlib.grasper_jaw import jaw_room
from tactcad.products.silicon_die.studies.die_doping import (STOCK_DOSES_PER_CM2,
                                                             acceptors_of_dose,
                                                             chosen_implant_dose, doped_die_plan,
                                                             drift_per_sensitivity_per_K)
from tactcad.studies.inverse_design import Targets


@pytest.fixture(scope="module")
def die():
    return doped_die_plan(Targets(10.0, (0.5, 5.0), 0.009), jaw_room("5"), columns=5)


def test_the_chosen_dose_has_the_least_drift_per_newton_and_the_minimum_is_inside_the_series():
    dose, why = chosen_implant_dose()
    ratios = [drift_per_sensitivity_per_K(d) for d in STOCK_DOSES_PER_CM2]
    assert drift_per_sensitivity_per_K(dose) == min(ratios)
    # TCR falls and then P falls faster: neither end of the series is best
    assert dose not in (STOCK_DOSES_PER_CM2[0], STOCK_DOSES_PER_CM2[-1])
    assert f"{dose:.2g} cm^-2" in why and f"{acceptors_of_dose(dose):.2g} cm^-3" in why


def test_the_readouts_zero_drift_per_newton_goes_as_tcr_over_p(die):
    """Through the whole read-out (geometry, bias, bridge), the zero drift in newtons per
    kelvin scales between two doses as TCR / P does: the geometry cancels, as the choice
    assumes."""
    other = dataclasses.replace(die, implant_dose_per_cm2=2e15)
    a, b = die_readout(die), die_readout(other)
    for role in ("reference", "measuring"):
        seen = b["rows"][role]["zero_drift_N_per_K"] / a["rows"][role]["zero_drift_N_per_K"]
        assert seen == pytest.approx(drift_per_sensitivity_per_K(2e15)
                                     / drift_per_sensitivity_per_K(die.implant_dose_per_cm2),
                                     rel=1e-9)


def test_the_plan_and_traveller_carry_the_chosen_dose_with_its_reason(die):
    dose, why = chosen_implant_dose()
    assert die.implant_dose_per_cm2 == dose
    assert die.acceptors_per_cm3 == pytest.approx(acceptors_of_dose(dose))
    assert die.reasons["implant_dose_per_cm2"] == why
    implant = next(s for s in traveller_steps(die, 300.0) if s.name == "implant")
    assert f"dose {dose:.2g} cm^-2" in implant.action


@pytest.mark.parametrize("dose", [0.0, float("nan"), 1e20])
def test_a_dose_out_of_range_is_refused_by_name(dose):
    with pytest.raises(DesignError, match="implant_dose_per_cm2"):
        md.die_plan(Targets(10.0, (0.5, 5.0), 0.009), jaw_room("5"), implant_dose_per_cm2=dose)
