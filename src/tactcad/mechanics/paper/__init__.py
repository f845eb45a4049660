"""The paper's own models and data: the lumped model of a stiffness sensing unit
(eq. 1-3), the calibration equations (eq. 4-6) and Tables 1 and 2."""
