"""The CAD kernel's one door: the only package that imports build123d or OCP.

Everything above speaks tactcad's words to it: the modelling verbs of
:mod:`~tactcad.kernel.shapes` (boxes, cylinders, prisms of 2D profiles,
booleans that must leave one solid), placements and joints
(:mod:`~tactcad.kernel.locations`, :mod:`~tactcad.kernel.joints`), hidden-line
projection (:mod:`~tactcad.kernel.hlr`), STEP and BREP files
(:mod:`~tactcad.kernel.step_writer`, :mod:`~tactcad.kernel.brep`), measurements of
solids (:mod:`~tactcad.kernel.inspect`) and the build123d part objects of the
Python API (:mod:`~tactcad.kernel.objects`). Solids, locations and compounds
pass through the layers above as values they hand back here; no module
outside this package imports the kernel (``tests/kernel/test_kernel_wall.py``).

Importing this package is free; each module loads the kernel (2-4 s) when it
is imported, so a command that needs no geometry never imports one.
"""
