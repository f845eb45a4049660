"""Material grades and strain gauges: the library a design file names.

Data: ``tactcad/data/materials.toml``; every value carries the document it
comes from (ASM Handbook, MMPDS, manufacturers' data sheets). This module
imports only the standard library and :mod:`tactcad.errors`, so any layer
(design, mechanics, commands) may use it.

A design's ``[material]`` table may name a ``grade``; modulus, Poisson
ratio, yield and fatigue strength and density then come from the library
unless the table gives its own value. An optional ``[strength]`` table sets
the ``safety_factor`` on yield and the ``gauge`` (a name from the library).

Units: MPa, g/cm^3, strain dimensionless, ohm.
"""

from __future__ import annotations

import functools
import math
import tomllib
from dataclasses import dataclass
from importlib import resources
from typing import Any, Mapping

from tactcad.errors import DesignError

MATERIALS_FILE = "materials.toml"

#: Grade the paper's aluminium is taken to be (the paper gives only E and nu).
DEFAULT_GRADE = "6061-T6"
#: The paper's 120 ohm quarter-bridge foil gauge.
DEFAULT_GAUGE = "constantan-foil"
#: Factor on yield at full-scale force: a usual static design factor for a
#: ductile metal part whose load is known (no impact).
DEFAULT_SAFETY_FACTOR = 1.5

#: Optional keys of a design's [material] table (besides name, E, nu).
MATERIAL_OPTIONAL_KEYS = ("grade", "yield_strength_MPa", "fatigue_strength_MPa",
                          "density_g_per_cm3")
#: Keys of a design's optional [strength] table.
STRENGTH_KEYS = ("safety_factor", "gauge")

_CORE_MATERIAL_KEYS = ("name", "youngs_modulus_MPa", "poisson_ratio")
_GRADE_FIELDS = ("youngs_modulus_MPa", "poisson_ratio", "yield_strength_MPa",
                 "ultimate_strength_MPa", "density_g_per_cm3")
#: What a grade's fatigue datum may be: the stress amplitude or the maximum stress of the cycle.
FATIGUE_DATUM_STRESSES = ("amplitude", "maximum")
#: Keys every grade's fatigue datum states (the datum defined one way, with its source).
FATIGUE_DATUM_KEYS = ("fatigue_datum_MPa", "fatigue_datum_stress", "fatigue_R_ratio",
                      "fatigue_cycles", "fatigue_specimen")
_GAUGE_FIELDS = ("resistance_ohm", "gauge_factor", "max_strain", "fatigue_strain",
                 "backing_thickness_mm", "adhesive_thickness_mm", "backing_modulus_MPa",
                 "installed_mass_mg", "terminal_pair_mass_mg", "lead_mass_mg_per_mm")

# Ranges a design file's own values must fall in (MPa, g/cm^3).
STRENGTH_RANGE_MPA = (1.0, 5000.0)
DENSITY_RANGE = (0.5, 25.0)
SAFETY_FACTOR_RANGE = (1.0, 10.0)


@dataclass(frozen=True)
class MaterialGrade:
    """One material grade of the library.

    Attributes:
        name: grade name, e.g. ``6061-T6``.
        description: alloy, temper / heat treatment.
        youngs_modulus_MPa: E (MPa). poisson_ratio: nu.
        yield_strength_MPa: 0.2 % offset tensile yield (MPa).
        ultimate_strength_MPa: ultimate tensile strength S_u (MPa).
        fatigue_datum_MPa: the fatigue datum as its source gives it (MPa): the
            ``fatigue_datum_stress`` ("amplitude" or "maximum") of the smooth
            specimen ``fatigue_specimen`` at ``fatigue_cycles`` cycles and stress
            ratio ``fatigue_R_ratio``.
        fatigue_strength_MPa: the datum converted to the fully reversed (R = -1)
            stress amplitude (Goodman, :func:`fully_reversed_amplitude`), the
            form the strength model uses (MPa).
        density_g_per_cm3: density (g/cm^3).
        sources: (field, document) pairs naming where each value comes from.
        family: the metal in words (``aluminium``, ``titanium``), as drawings and BOM name it.
        cte_ppm_per_K: mean linear coefficient of thermal expansion near room
            temperature (ppm/K = 1e-6 /K); the thermal drift of a gauge bonded on it.
        youngs_modulus_tc_per_K: temperature coefficient of Young's modulus
            (1/E) dE/dT near room temperature (1/K); the span drift of a spring of it.
        unsourced: (field, note) pairs of values no document was found for: the
            note says where the stand-in comes from.
    """

    name: str
    description: str
    youngs_modulus_MPa: float
    poisson_ratio: float
    yield_strength_MPa: float
    fatigue_strength_MPa: float
    fatigue_cycles: float
    fatigue_R_ratio: float
    density_g_per_cm3: float
    sources: tuple[tuple[str, str], ...]
    family: str = ""
    cte_ppm_per_K: float = math.nan
    ultimate_strength_MPa: float = math.nan
    fatigue_datum_MPa: float = math.nan
    fatigue_datum_stress: str = "amplitude"
    fatigue_specimen: str = ""
    youngs_modulus_tc_per_K: float = math.nan
    unsourced: tuple[tuple[str, str], ...] = ()

    def source(self, field: str) -> str:
        """Document a value comes from ('' if none is recorded)."""
        return dict(self.sources).get(field, "")

    def is_sourced(self, field: str) -> bool:
        """True when a document backs ``field`` (False for a stand-in in ``unsourced``)."""
        return bool(self.source(field)) and field not in dict(self.unsourced)

    def provenance(self, field: str) -> str:
        """The document ``field`` comes from, or ``unsourced: <where the stand-in comes from>``."""
        note = dict(self.unsourced).get(field)
        return f"unsourced: {note}" if note else self.source(field)

    def cited(self) -> str:
        """The grade in words with where its values come from, for a design file's reason:
        ``the material library's grade 6061-T6, Aluminium alloy 6061 ... (tactcad's
        data/materials.toml, every value with its source): E 68900 MPa (ASM Handbook ...),
        yield strength 276 MPa (ASM Handbook ...)`` (MPa)."""
        return (f"the material library's grade {self.name}, {self.description} (tactcad's "
                f"data/{MATERIALS_FILE}, every value with its source): E "
                f"{self.youngs_modulus_MPa:g} MPa ({self.provenance('youngs_modulus_MPa')}), "
                f"yield strength {self.yield_strength_MPa:g} MPa "
                f"({self.provenance('yield_strength_MPa')})")


@dataclass(frozen=True)
class StrainGauge:
    """A foil strain gauge of the library.

    Attributes:
        name: library name. description: type and carrier.
        alloy: foil alloy. resistance_ohm: nominal resistance (ohm).
        gauge_factor: k, relative resistance change per unit strain.
        bridge: Wheatstone bridge arrangement of the paper's elements.
        max_strain: largest strain (magnitude) for a single excursion.
        fatigue_strain: alternating strain amplitude survived for
            ``fatigue_cycles`` cycles.
        sources: (field, document) pairs.
        backing_thickness_mm: the carrier under the foil grid (mm).
        adhesive_thickness_mm: the cured glue line under the carrier (mm).
        backing_modulus_MPa: Young's modulus of carrier and glue line (MPa).
        installed_mass_mg: the gauge with its adhesive line (mg).
        terminal_pair_mass_mg: its pair of solder terminals with solder (mg).
        lead_mass_mg_per_mm: its three-wire lead per mm (mg/mm).
    """

    name: str
    description: str
    alloy: str
    resistance_ohm: float
    gauge_factor: float
    bridge: str
    max_strain: float
    fatigue_strain: float
    fatigue_cycles: float
    sources: tuple[tuple[str, str], ...]
    backing_thickness_mm: float = 0.0
    adhesive_thickness_mm: float = 0.0
    backing_modulus_MPa: float = 0.0
    installed_mass_mg: float = 0.0
    terminal_pair_mass_mg: float = 0.0
    lead_mass_mg_per_mm: float = 0.0

    @property
    def grid_height_mm(self) -> float:
        """Height of the foil grid above the surface it is bonded to: glue line + carrier (mm)."""
        return self.backing_thickness_mm + self.adhesive_thickness_mm


@dataclass(frozen=True)
class StrengthSettings:
    """A design's ``[strength]`` table, resolved.

    Attributes:
        safety_factor: factor on yield at the full-scale force (>= 1).
        gauge: the strain gauge bonded over the web.
    """

    safety_factor: float
    gauge: StrainGauge


@functools.lru_cache(maxsize=1)
def _library() -> dict[str, Any]:
    text = resources.files("tactcad").joinpath("data", MATERIALS_FILE).read_text(encoding="utf-8")
    return tomllib.loads(text)


#: Accepted CTE of a library grade (ppm/K): from invar (~1) to polymers (~200).
CTE_RANGE_PPM_PER_K = (0.0, 200.0)
#: Accepted temperature coefficient of Young's modulus (1/K): metals and alloys near room
#: temperature lie within about -1e-3 ... 0 (constant-modulus alloys such as Elinvar near 0,
#: a little positive at most).
MODULUS_TC_RANGE_PER_K = (-2e-3, 1e-4)


def _grade_modulus_tc(name: str, t: Mapping[str, Any]) -> float:
    """The grade's (1/E) dE/dT, with its document in ``sources`` or its stand-in's origin in
    ``unsourced`` (exactly one of them)."""
    key = "youngs_modulus_tc_per_K"
    tc = _number(f"grades.{name}.{key}", t.get(key), *MODULUS_TC_RANGE_PER_K, "1/K")
    sourced = bool(t.get("sources", {}).get(key))
    unsourced = bool(t.get("unsourced", {}).get(key))
    if sourced == unsourced:
        raise DesignError(f"grades.{name}.sources.{key}", None,
                          "the document the modulus coefficient comes from in [sources], or, "
                          "when none was found, the stand-in's origin in [unsourced] (one of "
                          "the two)")
    return tc


#: How a sourced modulus coefficient's basis is recorded ([grades.X.youngs_modulus_tc_basis]).
MODULUS_TC_BASIS_KINDS = ("points", "polynomial", "stated")


def modulus_tc_from_points(temperatures_K: tuple[float, float], moduli: tuple[float, float]
                           ) -> tuple[float, float]:
    """(1/E) dE/dT of the line through two tabulated E(T) points, normalised by E at each end.

    Args:
        temperatures_K: the two temperatures (K), different.
        moduli: E at them, in any one unit (it cancels), > 0.

    Returns:
        (by E at the first point, by E at the second) (1/K): a table's coefficient over
        the interval lies between them.

    Raises:
        ValueError: equal temperatures or a modulus not above 0.

    Source: the slope of a straight line through a table's rows (ASME B31.3 Table C-6
    style E(T) tables are read this way between rows).
    """
    (t1, t2), (e1, e2) = temperatures_K, moduli
    if t1 == t2 or min(e1, e2) <= 0:
        raise ValueError(f"modulus points need two temperatures and E > 0; got "
                         f"{temperatures_K!r}, {moduli!r}")
    slope = (e2 - e1) / (t2 - t1)
    return slope / e1, slope / e2


def modulus_tc_from_polynomial(coefficients: tuple[float, ...], at_K: float) -> float:
    """(1/E) dE/dT (1/K) of a fit E(T) = sum c_i T^i (lowest order first) at ``at_K`` (K).

    Args:
        coefficients: c_0, c_1, ... of the fit, E in any one unit, T in K.
        at_K: the temperature to evaluate it at (K).

    Returns:
        (1/E) dE/dT at ``at_K`` (1/K).

    Raises:
        ValueError: no coefficients or E(at_K) not above 0.

    Source: differentiation of the fit (e.g. NIST cryogenic material properties' E(T)).
    """
    if not coefficients:
        raise ValueError("a modulus fit needs its coefficients")
    e = sum(c * at_K ** i for i, c in enumerate(coefficients))
    de = sum(i * c * at_K ** (i - 1) for i, c in enumerate(coefficients) if i)
    if e <= 0:
        raise ValueError(f"the modulus fit gives E = {e:g} at {at_K:g} K")
    return de / e


def modulus_tc_bounds_per_K(name: str) -> tuple[float, float]:
    """The range of (1/E) dE/dT (1/K) the grade's recorded basis gives: every reading of
    its points normalised at either end, its fit at its temperature, or the figure its
    document states.

    Args:
        name: a library grade (as :func:`material_grade` matches it).

    Returns:
        (lowest, highest) coefficient (1/K).

    Raises:
        DesignError: the grade records no basis, or one of an unknown kind (naming
            ``grades.<name>.youngs_modulus_tc_basis`` and the kinds allowed).
    """
    grade = material_grade(name, "grade")
    basis = _library()["grades"][grade.name].get("youngs_modulus_tc_basis")
    field = f"grades.{grade.name}.youngs_modulus_tc_basis"
    kind = basis.get("kind") if isinstance(basis, Mapping) else None
    if kind not in MODULUS_TC_BASIS_KINDS:
        raise DesignError(field, kind, "a table whose kind is one of "
                          + ", ".join(MODULUS_TC_BASIS_KINDS))
    if kind == "stated":
        values = [float(basis["per_K"])]
    elif kind == "polynomial":
        values = [modulus_tc_from_polynomial(tuple(basis["coefficients"]), float(basis["at_K"]))]
    else:
        temps = tuple(basis["temperatures_K"])
        values = [v for reading in basis["readings"]
                  for v in modulus_tc_from_points(temps, tuple(reading))]
    return min(values), max(values)


def fully_reversed_amplitude(datum_MPa: float, datum_stress: str, R_ratio: float,
                             ultimate_MPa: float) -> float:
    """The fully reversed (R = -1) stress amplitude equivalent to a fatigue datum.

    The datum's cycle: from a maximum stress, sigma_a = sigma_max (1 - R) / 2
    and sigma_m = sigma_max (1 + R) / 2; from an amplitude, sigma_m =
    sigma_a (1 + R) / (1 - R). The Goodman line through the ultimate strength
    then gives sigma_ar = sigma_a / (1 - sigma_m / S_u) (Shigley's Mechanical
    Engineering Design, 9th ed., section 6-12, eq. 6-41 solved for S_e).

    Args:
        datum_MPa: the datum (MPa), > 0.
        datum_stress: ``"amplitude"`` or ``"maximum"``.
        R_ratio: stress ratio sigma_min / sigma_max of the datum's test, -1 <= R < 1.
        ultimate_MPa: ultimate tensile strength S_u (MPa), above the cycle's mean stress.

    Returns:
        the fully reversed amplitude (MPa); the datum itself at R = -1.

    Raises:
        ValueError: an unknown ``datum_stress``, R outside [-1, 1), or a mean
            stress at or above the ultimate strength.
    """
    if datum_stress not in FATIGUE_DATUM_STRESSES:
        raise ValueError(f"fatigue datum stress must be one of {', '.join(FATIGUE_DATUM_STRESSES)}; "
                         f"got {datum_stress!r}")
    if not -1.0 <= R_ratio < 1.0:
        raise ValueError(f"fatigue R ratio must be -1 <= R < 1; got {R_ratio!r}")
    if datum_stress == "maximum":
        amplitude, mean = datum_MPa * (1 - R_ratio) / 2, datum_MPa * (1 + R_ratio) / 2
    else:
        amplitude, mean = datum_MPa, datum_MPa * (1 + R_ratio) / (1 - R_ratio)
    if not mean < ultimate_MPa:
        raise ValueError(f"the fatigue datum's mean stress {mean:.4g} MPa is not below the "
                         f"ultimate strength {ultimate_MPa:.4g} MPa")
    return amplitude / (1 - mean / ultimate_MPa)


def _fatigue_datum(name: str, t: Mapping[str, Any]) -> dict[str, Any]:
    # each grade states its fatigue datum one way (which stress, R, cycles, specimen, source)
    for key in FATIGUE_DATUM_KEYS + ("ultimate_strength_MPa",):
        if key not in t:
            raise DesignError(f"grades.{name}.{key}", None, "the fatigue datum stated one way: "
                              + ", ".join(FATIGUE_DATUM_KEYS) + " and ultimate_strength_MPa")
    for key in ("fatigue_datum_MPa", "ultimate_strength_MPa"):
        if not t.get("sources", {}).get(key):
            raise DesignError(f"grades.{name}.sources.{key}", None, "the document it comes from")
    kind = t["fatigue_datum_stress"]
    if kind not in FATIGUE_DATUM_STRESSES:
        raise DesignError(f"grades.{name}.fatigue_datum_stress", kind,
                          " or ".join(FATIGUE_DATUM_STRESSES))
    datum = _number(f"grades.{name}.fatigue_datum_MPa", t["fatigue_datum_MPa"],
                    *STRENGTH_RANGE_MPA, "MPa")
    r_ratio = _number(f"grades.{name}.fatigue_R_ratio", t["fatigue_R_ratio"], -1.0, 0.99, "")
    return {"fatigue_datum_MPa": datum, "fatigue_datum_stress": kind,
            "fatigue_specimen": str(t["fatigue_specimen"]),
            "fatigue_strength_MPa": fully_reversed_amplitude(datum, kind, r_ratio,
                                                             float(t["ultimate_strength_MPa"]))}


def _grade_from_table(name: str, t: Mapping[str, Any]) -> MaterialGrade:
    # every grade carries its CTE and the document it comes from (the thermal drift needs it)
    cte = _number(f"grades.{name}.cte_ppm_per_K", t.get("cte_ppm_per_K"), *CTE_RANGE_PPM_PER_K,
                  "ppm/K")
    if not t.get("sources", {}).get("cte_ppm_per_K"):
        raise DesignError(f"grades.{name}.sources.cte_ppm_per_K", None, "the document the CTE "
                          "comes from")
    fatigue = _fatigue_datum(name, t)
    sources = dict(t["sources"])
    sources["fatigue_strength_MPa"] = (
        f"fully reversed amplitude {fatigue['fatigue_strength_MPa']:.4g} MPa converted (Goodman, "
        f"S_u {t['ultimate_strength_MPa']:g} MPa) from the {fatigue['fatigue_datum_stress']} "
        f"{fatigue['fatigue_datum_MPa']:g} MPa at R = {t['fatigue_R_ratio']:g}: "
        + sources["fatigue_datum_MPa"])
    return MaterialGrade(name=name, description=t["description"], family=t.get("family", ""),
                         cte_ppm_per_K=cte, youngs_modulus_tc_per_K=_grade_modulus_tc(name, t),
                         unsourced=tuple(sorted(t.get("unsourced", {}).items())),
                         fatigue_cycles=float(t["fatigue_cycles"]),
                         fatigue_R_ratio=float(t["fatigue_R_ratio"]),
                         sources=tuple(sorted(sources.items())),
                         **fatigue,
                         **{k: float(t[k]) for k in _GRADE_FIELDS})


def _gauge_from_table(name: str, t: Mapping[str, Any]) -> StrainGauge:
    return StrainGauge(name=name, description=t["description"], alloy=t["alloy"],
                       bridge=t["bridge"], fatigue_cycles=float(t["fatigue_cycles"]),
                       sources=tuple(sorted(t["sources"].items())),
                       **{k: float(t[k]) for k in _GAUGE_FIELDS})


@functools.lru_cache(maxsize=1)
def material_grades() -> dict[str, MaterialGrade]:
    """Every grade of the library by name (file order)."""
    return {n: _grade_from_table(n, t) for n, t in _library()["grades"].items()}


@functools.lru_cache(maxsize=1)
def strain_gauges() -> dict[str, StrainGauge]:
    """Every strain gauge of the library by name (file order)."""
    return {n: _gauge_from_table(n, t) for n, t in _library()["gauges"].items()}


def match_name(entries: Mapping[str, Any], text: Any) -> str | None:
    """The entry ``text`` names: exact, else without regard to case, else the one
    entry whose name starts with it (``ti-6al`` -> ``Ti-6Al-4V-annealed``); None when
    none or several match."""
    if not isinstance(text, str):
        return None
    if text in entries:
        return text
    folded = text.strip().casefold()
    if not folded:
        return None
    for rule in (lambda n: n.casefold() == folded,
                 lambda n: n.casefold().startswith(folded)):
        found = [n for n in entries if rule(n)]
        if found:
            return found[0] if len(found) == 1 else None
    return None


def candidates(entries: Mapping[str, Any], text: str) -> list[str]:
    """Every entry ``text`` could mean (case-insensitive name prefix)."""
    folded = text.strip().casefold()
    return [n for n in entries if folded and n.casefold().startswith(folded)]


def _lookup(entries: Mapping[str, Any], name: Any, field: str):
    found = match_name(entries, name)
    if found is None:
        several = candidates(entries, name) if isinstance(name, str) else []
        why = (f"ambiguous: {', '.join(several)} fit" if len(several) > 1 else
               "names of the library (tactcad materials), matched without regard to case "
               "where only one fits")
        raise DesignError(field, name, "one of " + ", ".join(entries), why)
    return entries[found]


def material_grade(name: str, field: str = "material.grade") -> MaterialGrade:
    """The library grade ``name`` (matched as :func:`match_name` does).

    Raises:
        DesignError: unknown grade, naming ``field`` and the allowed grades.
    """
    return _lookup(material_grades(), name, field)


def strain_gauge(name: str, field: str = "strength.gauge") -> StrainGauge:
    """The library strain gauge ``name``.

    Raises:
        DesignError: unknown gauge, naming ``field`` and the allowed gauges.
    """
    return _lookup(strain_gauges(), name, field)


def default_strength_settings() -> StrengthSettings:
    """Safety factor 1.5 on yield and the paper's constantan foil gauge."""
    return StrengthSettings(DEFAULT_SAFETY_FACTOR, strain_gauge(DEFAULT_GAUGE))


def _number(field: str, value: Any, lo: float, hi: float, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or not lo <= value <= hi:
        raise DesignError(field, value, f"a number {lo:g} ... {hi:g}{' ' + unit if unit else ''}")
    return float(value)


def material_fields(table: Mapping[str, Any]) -> dict[str, Any]:
    """Strength fields of a design's ``[material]`` table, resolved.

    With ``grade`` the library supplies yield, ultimate and fatigue strength
    (the grade's datum converted to the fully reversed amplitude, so R = -1),
    fatigue cycles and density; the table's own ``yield_strength_MPa``,
    ``fatigue_strength_MPa`` (read as a fully reversed amplitude of a smooth
    specimen) or ``density_g_per_cm3`` override them. Without a grade only
    the table's own values are known (others are None).

    Returns:
        keyword arguments for :class:`tactcad.design.Material` beyond name, E
        and nu: grade, yield_strength_MPa, ultimate_strength_MPa,
        fatigue_strength_MPa, fatigue_cycles, fatigue_R_ratio,
        density_g_per_cm3, sources.

    Raises:
        DesignError: unknown grade (naming the allowed grades) or a value
            outside its range.
    """
    out: dict[str, Any] = {"grade": None, "yield_strength_MPa": None,
                           "ultimate_strength_MPa": None, "fatigue_strength_MPa": None, "fatigue_cycles": None,
                           "fatigue_R_ratio": None, "density_g_per_cm3": None, "sources": ()}
    sources: dict[str, str] = {}
    if "grade" in table:
        g = material_grade(table["grade"])
        out.update(grade=g.name, yield_strength_MPa=g.yield_strength_MPa,
                   ultimate_strength_MPa=g.ultimate_strength_MPa,
                   fatigue_strength_MPa=g.fatigue_strength_MPa, fatigue_cycles=g.fatigue_cycles,
                   fatigue_R_ratio=-1.0, density_g_per_cm3=g.density_g_per_cm3)
        sources.update(g.sources)
    for key, (lo, hi), unit in (("yield_strength_MPa", STRENGTH_RANGE_MPA, "MPa"),
                                ("fatigue_strength_MPa", STRENGTH_RANGE_MPA, "MPa"),
                                ("density_g_per_cm3", DENSITY_RANGE, "g/cm^3")):
        if key in table:
            out[key] = _number(f"material.{key}", table[key], lo, hi, unit)
            sources[key] = "design file"
            if key == "fatigue_strength_MPa":
                out["fatigue_cycles"] = out["fatigue_R_ratio"] = None
    for key in _CORE_MATERIAL_KEYS[1:]:
        if key in table:
            sources[key] = "design file"
    out["sources"] = tuple(sorted(sources.items()))
    return out


def strength_settings(table: Any) -> StrengthSettings:
    """A design's optional ``[strength]`` table; ``None`` gives the defaults.

    Raises:
        DesignError: not a table, an unknown key, a safety factor outside
            1 ... 10, or an unknown gauge (naming the allowed gauges).
    """
    if table is None:
        return default_strength_settings()
    if not isinstance(table, Mapping):
        raise DesignError("strength", table, "a [strength] table with keys " + ", ".join(STRENGTH_KEYS))
    for key in table:
        if key not in STRENGTH_KEYS:
            raise DesignError(f"strength.{key}", table[key], "keys " + ", ".join(STRENGTH_KEYS),
                              "unknown key")
    sf = DEFAULT_SAFETY_FACTOR
    if "safety_factor" in table:
        sf = _number("strength.safety_factor", table["safety_factor"], *SAFETY_FACTOR_RANGE, "")
    return StrengthSettings(sf, strain_gauge(table.get("gauge", DEFAULT_GAUGE)))


