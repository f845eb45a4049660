"""The one place where a part's solid is built: by the builder its spec names
(:attr:`PartSpec.builder`, a key of :func:`tactcad.partlib.registry.builders`,
which answers for every part module, the array's and the rigs'), and counted,
so tests can prove that a scene builds only its own parts and a run builds
each part once."""

from __future__ import annotations

from collections import Counter
from typing import TYPE_CHECKING

from tactcad.catalogue.array_catalogue import PartSpec
from tactcad.partlib.registry import builders

if TYPE_CHECKING:
    from tactcad.kernel.shapes import Solid

BUILD_COUNTS: Counter[str] = Counter()  # part name -> times built in this process


def build_part(spec: PartSpec) -> Solid:
    """Build one part's solid (part frame, mm) from ``spec.geometry`` and count
    the build in :data:`BUILD_COUNTS`.

    Raises:
        KeyError: the spec names no known builder (a catalogue error).
    """
    solid = builders()[spec.builder](spec.geometry)
    BUILD_COUNTS[spec.name] += 1
    return solid
