"""Stiffness estimators and the paper's lumped and calibration models.

Modules here read the plan (:mod:`tactcad.design.array`) and the exact profile
(:mod:`tactcad.geometry.profile`); the closed-form ones never import the CAD kernel.
Units: mm, N, MPa, N/mm, s.
"""
