"""The general estimators: numbers for one plan. The element-stiffness ladder
(closed form and its correction, beam, fem/), strength and the limits on a tip
force, the read-out chain, contact, the paper's lumped (eq. 1-3) and
calibration (eq. 4-6) models, the evaluation rig and measured-data files.

Modules here read the plan (:mod:`tactcad.design.array_plan`) and the exact profile
(:mod:`tactcad.geometry.profile`); the closed-form ones never import the CAD kernel.
The studies (:mod:`tactcad.studies`), the benchmarks and the paper's reproduction
run them; nothing here imports those.
Units: mm, N, MPa, N/mm, s.
"""
