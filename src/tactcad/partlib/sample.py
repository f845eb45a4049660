"""Rubber samples (made parts, cast): tissue-phantom blocks of measured
stiffness that lie on the cart's vacuum pocket, one part per stiffness of
the ``[sample]`` table (``sample_k3p85`` ...), pink, darker when stiffer.

The sample carries every tip of the array with a margin; its size follows
the array unless the table sets it (30 x 20 mm at least, as the paper's
phantom block). The measured stiffness is an attribute of its part, not a
geometry. Part frame: block centred in x and y, z = 0 on its underside.
Units: mm, N/mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from tactcad.partlib.base import BuildStep, PartData, RigPart, Seat
from tactcad.kernel.shapes import box
from tactcad.vocabulary.process import Method, Process
from tactcad.vocabulary.schema import Problems, Section, Text, fmt, listing, name_number, number

#: Sample size when the rigs file gives none (the paper's phantom block), mm;
#: larger when the array's tips need it, with this margin around them.
SAMPLE_LENGTH_MM = 30.0
SAMPLE_WIDTH_MM = 20.0
SAMPLE_MARGIN_MM = 2.0


class SampleSection(Section):
    """``[sample]`` of ``rigs.toml``: the size may follow the array."""

    length_mm: Optional[number(5.0, 200.0)] = None  # default: covers the tip field (30 mm at least)
    width_mm: Optional[number(5.0, 200.0)] = None  # default: covers the tip field (20 mm at least)
    height_mm: number(1.0, 100.0)
    material: Text
    stiffness_N_per_mm: listing(number(0.01, 1e4, unit="N/mm"), 1, 64,
                                "a non-empty list of at most 64 stiffnesses (N/mm)")


@dataclass(frozen=True)
class SampleGeometry:
    """One sample block (mm) and its material."""

    length_mm: float
    width_mm: float
    height_mm: float
    material: str


def sample_name(stiffness_N_per_mm: float) -> str:
    """Part name of the rubber sample of the given stiffness, e.g. ``sample_k3p85``."""
    return "sample_k" + name_number(stiffness_N_per_mm)


def sample_color(k: float, ks: tuple[float, ...]) -> tuple[float, float, float]:
    """Pink rubber, darker for a stiffer sample (RGB 0 ... 1)."""
    lo, hi = min(ks), max(ks)
    t = 0.0 if hi == lo else (k - lo) / (hi - lo)
    return (round(0.95 - 0.35 * t, 4), round(0.60 - 0.30 * t, 4), round(0.65 - 0.30 * t, 4))


def tip_field(plan) -> tuple[float, float]:
    """(along the stack, across the rows) extent of the array's contact faces, mm
    (:attr:`tactcad.design.array_plan.Plan.tip_field_mm`, whatever the construction)."""
    return plan.tip_field_mm


def derive(s: SampleSection, context, p: Problems) -> PartData:
    """The samples for the array's tips (``context.plan``); the first
    stiffness is the part, the others its companions (the cart checks that
    a sample seals its vacuum pocket)."""
    along, across = tip_field(context.plan)
    need_l, need_w = along + 2 * SAMPLE_MARGIN_MM, across + 2 * SAMPLE_MARGIN_MM
    why = (f"every tip of the array rests on the sample with {fmt(SAMPLE_MARGIN_MM)} mm to spare "
           f"(tip field {fmt(along)} x {fmt(across)} mm)")
    length = max(SAMPLE_LENGTH_MM, need_l) if s.length_mm is None else \
        p.within("sample.length_mm", s.length_mm, need_l, why=why)
    width = max(SAMPLE_WIDTH_MM, need_w) if s.width_mm is None else \
        p.within("sample.width_mm", s.width_mm, need_w, why=why)
    stiffness = tuple(s.stiffness_N_per_mm)
    names = [sample_name(k) for k in stiffness]
    if len(set(names)) != len(names):  # 1 and 1.0000001 would both be sample_k1
        p.add("sample.stiffness_N_per_mm", list(stiffness), "values distinct in their first 6 "
              "significant digits", "each stiffness names one sample part, sample_k<value>")
    g = SampleGeometry(length, width, s.height_mm, s.material)
    first, *others = (_sample(g, k, stiffness) for k in stiffness)
    return PartData(**first, companions=tuple(PartData(**o) for o in others))


def _sample(g: SampleGeometry, k: float, ks: tuple[float, ...]) -> dict:
    """The fields of the :class:`PartData` of the sample of stiffness ``k``."""
    return dict(
        name=sample_name(k), kind="fabricated",
        process=Process(f"cast {g.material} block, measured stiffness {k:g} N/mm", Method.CAST),
        material=g.material, color=sample_color(k, ks),
        expected_volume_mm3=g.length_mm * g.width_mm * g.height_mm,
        expected_bbox_mm=(-g.length_mm / 2, -g.width_mm / 2, 0.0, g.length_mm / 2, g.width_mm / 2,
                          float(g.height_mm)),
        geometry=g, attributes={"stiffness_N_per_mm": k},
        frames={"bottom": Seat((0, 0, 0), (0, 0, -1), (1, 0, 0)),
                "top": Seat((0, 0, g.height_mm), (0, 0, 1), (1, 0, 0))})


def stiffnesses(data: PartData) -> tuple[float, ...]:
    """The measured stiffness of every sample (N/mm), in the table's order."""
    return tuple(d.attributes["stiffness_N_per_mm"] for d in (data, *data.companions))


def build(g: SampleGeometry):
    """Block ``length x width x height`` (build123d ``Solid``, mm)."""
    return box(-g.length_mm / 2, -g.width_mm / 2, 0, g.length_mm / 2, g.width_mm / 2, g.height_mm)


def casting_notes(book) -> tuple[str, ...]:
    return ("Cast one block per stiffness of the rigs file; measure each block's stiffness on the "
            "sample-stiffness rig and label it with the value.",) + tuple(
        f"{part}: {k:g} N/mm" for part, k in book.sample_stiffness.items())


PART = RigPart(key="sample", section=SampleSection, host="", derive=derive, build=build, order=10,
               assembly=BuildStep("samples-cast", "Cast the sample kit",
                                  tools=lambda book: ("mould", "scale"), notes=casting_notes))
