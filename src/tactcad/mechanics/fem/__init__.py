"""Finite-element levels of the stiffness ladder: gmsh meshes of the exact profile
(``mesh``), P2 plane stress/strain (``fem2d``) and P2 tetrahedra (``fem3d``),
both solved with scikit-fem."""
