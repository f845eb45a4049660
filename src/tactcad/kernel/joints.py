"""Joints: empty carriers (compounds with a label) that rigid and linear
joints (build123d's ``RigidJoint`` and ``LinearJoint``) place on each other.
The rigs' solver (:mod:`tactcad.assembly.scene_solver`) is written in these words."""

from __future__ import annotations

import build123d as bd


def carrier(label: str) -> bd.Compound:
    """An empty, labelled carrier for joints; its ``location`` is where the joints put it."""
    return bd.Compound([], label=label)


def rigid_joint(label: str, on: bd.Compound, location: bd.Location) -> bd.RigidJoint:
    """A rigid joint of carrier ``on`` at ``location`` (the scene frame)."""
    return bd.RigidJoint(label, on, location)


def slide_joint(label: str, on: bd.Compound, location: bd.Location,
                travel_mm: tuple[float, float]) -> bd.LinearJoint:
    """A linear joint of carrier ``on`` along the x axis of ``location``,
    ``travel_mm`` (min, max) its range. ``connect_to(joint, position=mm)``
    raises ``ValueError`` for a position outside the range."""
    return bd.LinearJoint(label, on, bd.Axis.X.located(location), travel_mm)
