"""Builders of the rig parts, keyed like :data:`tactcad.parts.registry.BUILDERS`:
``builder(plan, spec) -> Solid`` with the rig geometry in ``spec.geometry``."""

from __future__ import annotations

from typing import Callable

from tactcad.parts import bracket, indenter, purchased, rig_base, rig_cart, sample
from tactcad.parts.fasteners import build_bolt

RIG_BUILDERS: dict[str, Callable] = {
    "base_plate": lambda plan, spec: rig_base.build_base_plate(spec.geometry),
    "column": lambda plan, spec: rig_base.build_column(spec.geometry),
    "cart": lambda plan, spec: rig_cart.build_cart(spec.geometry),
    "wheel_spacer": lambda plan, spec: rig_cart.build_wheel_spacer(spec.geometry),
    "sample": lambda plan, spec: sample.build_sample(spec.geometry),
    "sample_holder": lambda plan, spec: sample.build_sample_holder(spec.geometry),
    "indenter": lambda plan, spec: indenter.build_indenter(spec.geometry),
    "array_bracket": lambda plan, spec: bracket.build_bracket(spec.geometry),
    "axis_carrier": lambda plan, spec: bracket.build_carrier(spec.geometry),
    "hanger_bar": lambda plan, spec: bracket.build_hanger_bar(spec.geometry),
    "force_gauge": lambda plan, spec: purchased.build_force_gauge(spec.geometry),
    "z_stage_body": lambda plan, spec: purchased.build_z_body(spec.geometry),
    "z_stage_carriage": lambda plan, spec: purchased.build_z_carriage(spec.geometry),
    "xy_stage_base": lambda plan, spec: purchased.build_stage_base(spec.geometry),
    "xy_stage_table": lambda plan, spec: purchased.build_stage_table(spec.geometry),
    "rail": lambda plan, spec: purchased.build_rail(spec.geometry),
    "block": lambda plan, spec: purchased.build_block(spec.geometry),
    "weight": lambda plan, spec: purchased.build_weight(spec.geometry),
    "bearing": lambda plan, spec: purchased.build_bearing(spec.geometry),
    "rig_bolt": lambda plan, spec: build_bolt(*spec.geometry),
}
