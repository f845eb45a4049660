"""Stock materials of the made rig parts, with alloy and temper (EN 573-3 /
EN 515, EN 10088-3, EN 12164): 6082-T651 plate is stretched (stress
relieved), so milled pockets stay flat; 1.4305 is the free-machining
austenitic stainless steel (no rust on a damp sample); CW614N is the
free-machining brass for small turned parts."""

from __future__ import annotations

PLATE_ALUMINIUM = "aluminium EN AW-6082-T651"
BAR_ALUMINIUM = "aluminium EN AW-6082-T6"
INDENTER_STEEL = "stainless steel 1.4305 (X8CrNiS18-9)"
TURNED_BRASS = "brass CW614N (CuZn39Pb3)"
