"""The silicon MEMS die: two rows of piezoresistive cantilevers in an SOI wafer's device
layer, posts on their free ends, hard stops etched into the handle, for a small grasper's
jaw (``tactcad die``; a ``[die]`` design file).

Its registry entry: the array commands that answer for a die, its export and check, its
project folder and its object in the Python API. The die's own models are planned by
:mod:`tactcad.products.silicon_die.design.mems_die` and read by the views of
:mod:`tactcad.products.silicon_die.commands.die_views`.
"""

from tactcad.products import Product

_VIEWS = "tactcad.products.silicon_die.commands.die_views"

PRODUCT = Product(
    name="silicon-die",
    summary="a silicon MEMS die in an SOI wafer (piezoresistive cantilevers, posts, hard "
            "stops etched into the handle) for a small grasper's jaw",
    design_table="die",
    views={command: f"{_VIEWS}:{command}_view"
           for command in ("modal", "budget", "readout", "thermal", "verify", "grasp",
                           "crosstalk", "strength", "stiffness", "tolerance", "scenes")},
    export="tactcad.commands.die:export_die",
    check="tactcad.commands.die:check_die",
    new_project="tactcad.project_folder:new_die_project",
    load="tactcad.api:load_die",
    examples=("grasper_jaw_5mm_mems",),
    commands_done_elsewhere=("die",),
)
