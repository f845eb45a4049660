"""build123d's part-object protocol, for the part objects of tactcad's Python
API (:mod:`tactcad.assembly.part_objects`): a user places them inside a
``BuildPart`` as any build123d part (``rotation``, ``align``, ``mode``)."""

from __future__ import annotations

from typing import Sequence

import build123d as bd

#: The base class of a build123d part object, and the builder it applies to.
PartObject = bd.BasePartObject
BUILD_PART = bd.BuildPart._tag
#: build123d's own option types of a part object.
Align = bd.Align
Mode = bd.Mode
RotationLike = bd.RotationLike


def labelled_part(children: Sequence[bd.Shape], label: str) -> bd.Part:
    """One part holding ``children`` (each keeps its label and location)."""
    return bd.Part(children=list(children), label=label)


def labelled_compound(children: Sequence[bd.Shape], label: str | None = None) -> bd.Compound:
    """One compound holding ``children`` (each keeps its label, colour and location)."""
    if label is None:
        return bd.Compound(children=list(children))
    return bd.Compound(children=list(children), label=label)


def rgb_colour(rgb: Sequence[float]) -> bd.Color:
    """A display colour from red, green, blue (0 ... 1)."""
    return bd.Color(*rgb)
