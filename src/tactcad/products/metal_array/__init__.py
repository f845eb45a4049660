"""The metal array: wire-cut (or etched, laser-cut) flexure elements read by bonded foil
strain gauges, built as the paper's stacked array or as a monolithic comb for a grasper's
jaw (the constructions of :mod:`tactcad.design.construction_registry`); an array's design
file (``[design]``, ``[material]``, ``[arms]`` ...).

The default product: every design file no other product claims is an array's, and the
array commands' own code answers for it.
"""

from tactcad.products import Product

PRODUCT = Product(
    name="metal-array",
    summary="wire-cut flexure elements with bonded strain gauges, stacked (the paper's) or a "
            "monolithic comb for a grasper's jaw",
    examples=("macro_array", "ti_array_2x3", "grasper_jaw_10mm"),
)
