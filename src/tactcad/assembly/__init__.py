"""Assemblies: the array and the test rigs as kinematic trees of parts placed
by joints (build123d ``RigidJoint`` / ``LinearJoint``), and the scenes that
show them."""
