"""The paper's reproduction, built on the general models of
:mod:`tactcad.mechanics` (never the reverse): its measured Tables 1 and 2
(:mod:`.data`), Table 1 against the stiffness ladder and the read-out chain
(:mod:`.table1`) and through the calibration equations
(:mod:`.calibration_table1`), Table 2 against eq. 2 (:mod:`.table2_eq2`) and its
models scored on held-out rows (:mod:`.table2_models`), the calibration audit
(:mod:`.calibration_audit`) and the paper's figures (:mod:`.figures`). A
comparison answers only for a design that cites the paper."""
