"""The clamped array's parts written one module each, in the form of
:class:`tactcad.partlib.base.ArrayPart` (builder, drawing, spec data and the
part's dimensions under one key), found by :mod:`tactcad.partlib.registry`
beside the rig parts: ``element``, ``spacer``, ``clamp_plate``,
``strain_gauge``, ``fasteners`` (bolts and nuts); ``prism`` holds what the
extruded ones share (through holes, the drilled plate, a prism's box).

The array's dimensions stay one coupled derivation (element, clamp plates and
bolt pattern from one design file) in :mod:`tactcad.design.array_plan`, which sits
above this layer and reads the dimension classes from here; each module reads
its part's dimensions back from the plan. Units: mm.
"""
