"""Every part written one module each: the rig parts here (schema table,
derivation with reasons, spec with its process, seat, drawing record,
builder) and the clamped array's parts in :mod:`tactcad.partlib.array`
(tables, dimensions, spec, drawing record, builder; their coupled derivation
is :mod:`tactcad.design.array_plan`'s). The forms are :mod:`tactcad.partlib.base`
(:class:`~tactcad.partlib.base.RigPart`, :class:`~tactcad.partlib.base.ArrayPart`),
the one registry of parts, builders and drawings :mod:`tactcad.partlib.registry`."""
