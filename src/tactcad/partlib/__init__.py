"""Rig parts written one module each (schema table, derivation with reasons,
spec with its process, seat, drawing record, builder): the form is
:mod:`tactcad.partlib.base`, the registry :mod:`tactcad.partlib.registry`.
The rig parts written before this form stay in ``design/rigs.py``,
``catalogue/rigs.py``, ``parts/``, ``assembly/rigs.py`` and
``drawings/part_sets.py``; both forms are read side by side."""
