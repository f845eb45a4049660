"""The BOM's read-out items come from the design's [readout] chain: the
amplifier and DAQ it names, one amplifier and one cable per element."""

from __future__ import annotations

from tactcad.catalogue.gauges import sensor_items
from tactcad.design.array_plan import default_design_data, plan_from_dict, with_overrides


def test_the_amplifier_and_daq_named_in_readout_are_bought():
    plan = plan_from_dict(with_overrides(default_design_data(), {
        "readout.amplifier": "INA826 module", "readout.amplifier_noise_nV_per_rtHz": 18.0,
        "readout.daq": "LabJack T7"}))
    items = {i.part: i for i in sensor_items(plan)}
    assert "INA826 module" in items["instrumentation_amplifier"].reference
    assert "LabJack T7" in items["daq"].reference
    n = len(plan.slots)
    assert items["instrumentation_amplifier"].quantity(n) == n
    assert items["signal_cable"].quantity(n) == n and items["daq"].quantity(n) == 1


def test_the_lead_wire_names_the_readout_lead_connection():
    default = {i.part: i for i in sensor_items(plan_from_dict(default_design_data()))}
    assert "three-wire quarter bridge" in default["lead_wire"].reference
    two = {i.part: i for i in sensor_items(plan_from_dict(with_overrides(
        default_design_data(), {"readout.lead_wires": "two-wire"})))}
    assert "two-wire quarter bridge" in two["lead_wire"].reference
