"""The paper's own models and data: the lumped model of a stiffness sensing unit
(eq. 1-3), the calibration equations (eq. 4-6) and Tables 1 and 2, and the
paper's two experiments as simulations: the calibration rig with its audit
(:mod:`.calibration`, :mod:`.calibration_audit`), the array evaluation rig
(:mod:`.evaluation`) and the models of Table 2 scored on held-out rows
(:mod:`.table2_models`)."""
