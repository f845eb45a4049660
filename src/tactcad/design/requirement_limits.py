"""The ranges a design file's ``[requirements]`` may state, in a module of their own that
imports nothing: a command's ``--help`` and its options' ranges read them without loading
the design schema (:mod:`tactcad.design.requirements_section` re-exports them).

Units: N, N/mm, W/mm^2.
"""

#: The largest targets a design file states (the design command's options take the same).
MAX_FULL_SCALE_FORCE_N = 1000.0
MAX_KOBJ_N_PER_MM = 1e4
#: The least full-scale force a design file or option states (N): no read-out chain resolves
#: a force near it, and far below it a die's cavity depth rounds to zero.
MIN_FULL_SCALE_FORCE_N = 1e-9
#: The least object stiffness a K_obj range states (N/mm): the atlas's softest range end;
#: far below it K_obj is lost in K_m + K_obj's rounding and eq. 3 has no answer.
MIN_KOBJ_N_PER_MM = 1e-6
MAX_KR_OVER_KM = 1000.0
MAX_GRASP_FORCE_N = 100.0
#: The largest gauge-grid power density a design file accepts (W/mm^2, about 65 W/in^2): far
#: past TN-502's 1-2 W/in^2, where a foil grid on a thin web runs tens of kelvin hot.
MAX_GRID_POWER_DENSITY_W_PER_MM2 = 0.1
