"""Digital force gauges a rig may carry: the catalogue the rigs made for a
design choose from (:mod:`tactcad.studies.rig_sizing`), what a rig asks of its
gauge (:class:`GaugeNeed`) and the catalogue gauge that meets it
(:func:`choose_force_gauge`), the rule of the rigs; a design without rigs is
calibrated on the catalogue gauge that leaves the least expected calibration error
(:func:`tactcad.studies.verification.catalogue_calibration_gauge`).

Data: ``tactcad/data/force_gauges.toml``; each model carries its maker's
range (capacity) and resolution and the document they come from, its own
stiffness and its housing envelope. Imports only the standard library and
:mod:`tactcad.errors`, as :mod:`tactcad.vocabulary.material_library`.

Units: N, N/mm, mm.
"""

from __future__ import annotations

import functools
import math
import tomllib
from dataclasses import dataclass, fields
from importlib import resources

GAUGES_FILE = "force_gauges.toml"


@dataclass(frozen=True)
class ForceGaugeModel:
    """One catalogue force gauge.

    Attributes:
        model: the maker's model name, as ``[force_gauge] model`` writes it.
        maker: the maker. range_N: capacity (N). resolution_N: smallest
            increment shown (N). stiffness_N_per_mm: the gauge's own spring
            (N/mm). length_mm, width_mm, depth_mm: housing envelope (mm).
        shaft_diameter_mm, shaft_length_mm: measuring shaft envelope (mm).
        source: the document range and resolution come from.
    """

    model: str
    maker: str
    range_N: float
    resolution_N: float
    stiffness_N_per_mm: float
    length_mm: float
    width_mm: float
    depth_mm: float
    shaft_diameter_mm: float
    shaft_length_mm: float
    source: str


@functools.lru_cache(maxsize=1)
def force_gauges() -> tuple[ForceGaugeModel, ...]:
    """Every catalogue gauge, by range then resolution (smallest first).

    Raises:
        ValueError: an entry with a missing field or a number that is not
            finite and > 0, or a resolution not below its range (names the
            model and the field).
    """
    text = resources.files("tactcad").joinpath("data", GAUGES_FILE).read_text(encoding="utf-8")
    out = [_gauge(name, table) for name, table in tomllib.loads(text)["gauges"].items()]
    return tuple(sorted(out, key=lambda g: (g.range_N, g.resolution_N)))


def _gauge(name: str, table: dict) -> ForceGaugeModel:
    values = {"model": name}
    for f in fields(ForceGaugeModel)[1:]:
        if f.name not in table:
            raise ValueError(f"{GAUGES_FILE}: gauges.{name!r} has no {f.name}")
        v = table[f.name]
        if f.type == "float" and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"{GAUGES_FILE}: gauges.{name!r}.{f.name} = {v!r}: allowed a number > 0")
        values[f.name] = float(v) if f.type == "float" else str(v)
    gauge = ForceGaugeModel(**values)
    if gauge.resolution_N >= gauge.range_N:
        raise ValueError(f"{GAUGES_FILE}: gauges.{name!r}.resolution_N = {gauge.resolution_N:g}: "
                         f"allowed < range_N = {gauge.range_N:g}")
    return gauge


# ---------------------------------------------------------------------------
# What a rig asks of its gauge, and the catalogue gauge that meets it
# ---------------------------------------------------------------------------
#: The gauge resolves this share of the rated full-scale force (1 %: the first of
#: the calibration's six steps to full scale is read to 6 %).
RESOLUTION_SHARE = 0.01


@dataclass(frozen=True)
class GaugeNeed:
    """What the rigs ask of their force gauge.

    Attributes:
        rated_N: the design's rated full-scale force F (N).
        sample_depth_mm: the sample rig's depth, F / K_lo (mm).
        sample_force_N: the stiffest sample at that depth (N).
        range_N: the largest force read, max(F, sample force) (N).
        resolution_N: the coarsest resolution allowed, :data:`RESOLUTION_SHARE` x F (N).
    """

    rated_N: float
    sample_depth_mm: float
    sample_force_N: float
    range_N: float
    resolution_N: float

    def words(self) -> str:
        """The need in words, with its reasons."""
        return (f"range >= {self.range_N:.3g} N (the rated full-scale force {self.rated_N:.3g} N, "
                f"the stiffest sample {self.sample_force_N:.3g} N at the softest's "
                f"{self.sample_depth_mm:.3g} mm), "
                f"resolution <= {self.resolution_N:.3g} N ({100 * RESOLUTION_SHARE:g} % of "
                f"{self.rated_N:.3g} N)")


def calibration_gauge_need(rated_N: float) -> GaugeNeed:
    """The force gauge a calibration alone needs (no sample rig) by the rigs' rule: the
    rated force's range and :data:`RESOLUTION_SHARE` of it (the fallback of
    :func:`tactcad.studies.verification.catalogue_calibration_gauge` when no catalogue
    gauge's range holds the calibration's force).

    Args:
        rated_N: the design's rated full-scale force (N), > 0.

    Returns:
        the need, with no sample (depth and sample force 0).
    """
    return GaugeNeed(rated_N, 0.0, 0.0, rated_N, RESOLUTION_SHARE * rated_N)


def gauge_shortfalls(range_N: float, resolution_N: float, need: GaugeNeed) -> list[str]:
    """How a gauge of ``range_N`` and ``resolution_N`` (N) misses ``need``, in
    words (empty when it fits)."""
    out = []
    if range_N < need.range_N * (1 - 1e-9):
        out.append(f"range {range_N:g} N < {need.range_N:.3g} N")
    if resolution_N > need.resolution_N * (1 + 1e-9):
        out.append(f"resolution {resolution_N:g} N > {need.resolution_N:.3g} N")
    return out


def choose_force_gauge(need: GaugeNeed) -> tuple[ForceGaugeModel, list[str]]:
    """The catalogue gauge of smallest range that meets ``need`` (of equal
    ranges the finest resolution), with no shortfalls; when none meets it,
    the finest of those with the range (else the largest range) with its
    shortfalls in words, for ``check`` to fail and the rigs file to say."""
    gauges = force_gauges()
    fits = [g for g in gauges if not gauge_shortfalls(g.range_N, g.resolution_N, need)]
    if fits:
        return fits[0], []
    ranged = [g for g in gauges if g.range_N >= need.range_N]
    best = min(ranged, key=lambda g: g.resolution_N) if ranged else gauges[-1]
    return best, gauge_shortfalls(best.range_N, best.resolution_N, need)


def catalogue_gauge(model: str) -> ForceGaugeModel | None:
    """The catalogue gauge named ``model`` (as ``[force_gauge] model`` writes it, in any
    letter case and spacing: "mark-10 m5-05" is the Mark-10 M5-05), or None for a gauge the
    catalogue does not hold (a lab's own)."""
    return next((g for g in force_gauges() if _model_words(g.model) == _model_words(model)),
                None)


def _model_words(model: str) -> tuple[str, ...]:
    # a model name as a lab may type it: case and runs of spaces do not name another gauge
    return tuple(str(model).casefold().split())


def catalogue_mismatches(model: str, range_N: float, resolution_N: float) -> list[str]:
    """How a rig's stated range and resolution (N) differ from its catalogue model's, in
    words naming the key (empty for a model the catalogue does not hold, or one that agrees):
    a stated range left over from another model would judge the rig on a gauge it lacks.

    Args:
        model: the rig's ``[force_gauge] model``.
        range_N: its stated ``range_N`` (N).
        resolution_N: its stated ``resolution_N`` (N).

    Returns:
        e.g. ``["range_N = 0.5 N, the catalogue's Mark-10 M5-025 reads 1 N"]``.
    """
    gauge = catalogue_gauge(model)
    if gauge is None:
        return []
    stated = {"range_N": (range_N, gauge.range_N), "resolution_N": (resolution_N, gauge.resolution_N)}
    return [f"{key} = {value:g} N, the catalogue's {gauge.model} reads {own:g} N"
            for key, (value, own) in stated.items()
            if not math.isclose(value, own, rel_tol=1e-9)]
