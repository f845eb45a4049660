"""A silicon die's design file: the ``[die]`` table a sensor folder keeps for ``tactcad die
--design FILE``, and what ``tactcad design --jaw`` writes when only a die fits the jaw.

The file states the targets and the jaw; the die itself (device layer, beams, resistors) is
derived from them each time (:func:`tactcad.products.silicon_die.design.mems_die.die_plan`), as an array's
derived dimensions are from its design file. A jaw given as a file is read relative to the
die file's folder and must lie in it (a sensor folder reads nothing from outside itself).

Units: N/mm, N, um.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from tactcad.products.silicon_die.design.mems_die import (COLUMNS_RANGE, DEFAULT_COLUMNS,
                                                          DEFAULT_DIE_ATTACH,
                                                          DEFAULT_DIE_NAME,
                                                          DEFAULT_KOBJ_RESOLUTION_REL,
                                                          DEFAULT_PITCH_UM,
                                                          FULL_SCALE_FORCE_WORDS, LEAST_PITCH_UM,
                                                          ROOT_FILLET_RANGE_UM, DieAttach,
                                                          WeibullPair)
from tactcad.products.silicon_die.vocabulary.soi_process import DRIE_MIN_RADIUS_UM
from tactcad.design.requirements_section import (MAX_FULL_SCALE_FORCE_N, MAX_GRASP_FORCE_N,
                                                 MAX_KOBJ_N_PER_MM, MIN_FULL_SCALE_FORCE_N,
                                                 MIN_KOBJ_N_PER_MM)
from tactcad.design.file_kind import DIE_TABLE, is_die_file  # noqa: F401 (is_die_file re-exported)
from tactcad.design.file_kind import refuse_jaw_file
from tactcad.errors import DesignError
from tactcad.vocabulary.schema import (Problems, Section, Text, described_text, integer,
                                       listing, number, reason_as_read, read_toml,
                                       stale_reasons, validate, with_written_values)

#: The die's largest failure probability a ``[strength]`` table accepts when it states none
#: (assumption: one die in a thousand).
DEFAULT_FAILURE_PROBABILITY_MAX = 1e-3


class DieSection(Section):
    """``[die]``: the targets and the jaw of a silicon die (N/mm, N, um)."""

    jaw: described_text('a trocar class as text (jaw = "5") or a jaw file in the design\'s '
                        'folder', "the jaw whose pocket the die fills")
    kr_over_km: number(1.0, 1000.0, lo_open=True, unit="",
                       why="the reference beam stiffer than the measuring one")
    kobj_range_N_per_mm: listing(number(MIN_KOBJ_N_PER_MM, MAX_KOBJ_N_PER_MM, unit="N/mm"), 2, 2,
                                 f"[LO, HI] with {MIN_KOBJ_N_PER_MM:g} <= LO < HI <= "
                                 f"{MAX_KOBJ_N_PER_MM:g} N/mm",
                                 "object stiffnesses the die must read")
    full_scale_force_N: number(MIN_FULL_SCALE_FORCE_N, MAX_FULL_SCALE_FORCE_N, unit="N",
                               why=FULL_SCALE_FORCE_WORDS)
    columns: integer(*COLUMNS_RANGE, why="units along the die") = DEFAULT_COLUMNS
    pitch_um: number(LEAST_PITCH_UM, 5000.0, unit="um",
                     why="the units' spacing along the die: each beam's three bond pads and its "
                         "reference resistor lie on the frame within one pitch") = DEFAULT_PITCH_UM
    name: str = DEFAULT_DIE_NAME
    kobj_resolution_rel: number(0.0, 1.0, lo_open=True, unit="",
                                why="the K_obj error the read-out noise may leave anywhere in "
                                    "the range (1 sigma; left out, the die is sized to the "
                                    "default and verify reports it, not judged)"
                                ) = DEFAULT_KOBJ_RESOLUTION_REL
    kobj_accuracy_rel: number(0.0, 10.0, lo_open=True, unit="",
                              why="the largest K_obj error the die may read with over its "
                                  "range: the worst root sum square of its K_obj budget "
                                  "(tactcad budget; not judged when left out)") = None
    max_grasp_force_N: number(0.0, MAX_GRASP_FORCE_N, lo_open=True, unit="N",
                              why="the largest grasp force the die must survive in its jaw: "
                                  "at it no beam past its breaking force, a hard stop taking "
                                  "the rest, each post and the cavity floor under it within "
                                  "its strength (not judged when left out)") = None
    root_fillet_um: number(ROOT_FILLET_RANGE_UM[0], ROOT_FILLET_RANGE_UM[1], lo_open=True,
                           unit="um",
                           why="the fillet where each beam's sidewalls meet the frame, drawn "
                               "into the device etch; its K_t raises the root's peak stress "
                               "(default: the smallest radius the etch draws reliably)"
                           ) = DRIE_MIN_RADIUS_UM


class DieStrengthSection(Section):
    """``[strength]``, optional: a Weibull pair for the fracture strength of the lab's own
    etched silicon, from its fab's test structures (:class:`tactcad.products.silicon_die.design.mems_die.
    WeibullPair`), replacing the design default; without it the die is designed and
    judged by :data:`tactcad.products.silicon_die.design.mems_die.DESIGN_STRENGTH` (m 5,
    sigma_0 2000 MPa on 1200 um^2, from the mean strength of Bosch-etched bars)."""

    weibull_modulus: number(1.0, 100.0, lo_open=True, unit="",
                            why="m of the fracture strength's Weibull distribution")
    characteristic_strength_MPa: number(100.0, 20000.0, unit="MPa",
                                        why="sigma_0: 63.2 % of the test structures break by it")
    reference_area_um2: number(1.0, 1e9, unit="um^2",
                               why="the test structures' effective area the pair is for")
    source: Text
    failure_probability_max: number(0.0, 0.5, lo_open=True, unit="",
                                    why="the die's largest failure probability accepted"
                                    ) = DEFAULT_FAILURE_PROBABILITY_MAX


class DieAttachSection(Section):
    """``[attach]``, optional: the film bonding the die to its carrier, from its data sheet
    (:class:`tactcad.products.silicon_die.design.mems_die.DieAttach`); without it the die's mount and crosstalk
    take :data:`tactcad.products.silicon_die.design.mems_die.DEFAULT_DIE_ATTACH` (an assumption)."""

    material: Text
    modulus_MPa: number(1.0, 200000.0, unit="MPa",
                        why="the cured film's Young's modulus: a silicone's few MPa to a "
                            "solder's tens of GPa")
    thickness_um: number(2.0, 500.0, unit="um", why="the cured bond line")
    source: Text
    poisson: number(0.0, 0.5, hi_open=True, unit="",
                    why="the film's Poisson's ratio") = DEFAULT_DIE_ATTACH.poisson


class DieFile(Section):
    """A die's design file: ``[die]``, optionally ``[strength]`` and ``[attach]``, and its
    ``[assumptions]`` (reasons, by key)."""

    die: DieSection
    strength: DieStrengthSection = None
    attach: DieAttachSection = None
    assumptions: dict[str, str] = {}


@dataclass(frozen=True)
class DieDesign:
    """A validated die design file.

    Attributes:
        die: its ``[die]`` table.
        jaw: ``--jaw``'s value for the die command (a trocar class, or the jaw file's path
            resolved in the design's folder).
        source: the file.
        strength: the file's Weibull pair, or None.
        attach: the file's die attach, or None (the mount's assumption).
        stated: the ``[die]`` keys the file (with its overrides) states; a key left out
            takes its default.
        assumptions: the file's reasons under ``[assumptions]`` as the outputs show them,
            (key, text) in the file's order (:func:`die_assumptions`).
        stale: the reasons among them that no longer apply, key -> text (a value edited
            since ``tactcad design`` wrote them; :func:`tactcad.vocabulary.schema.stale_reasons`).
    """

    die: DieSection
    jaw: str
    source: Path
    strength: WeibullPair | None = None
    attach: DieAttach | None = None
    stated: frozenset = frozenset()
    assumptions: tuple = ()
    stale: Mapping[str, str] = field(default_factory=dict)


def die_assumptions(data: Mapping[str, Any]) -> tuple[tuple[str, str], ...]:
    """A die file's reasons under ``[assumptions]`` as the outputs show them: each as the
    file words it, and where ``tactcad design`` recorded the value it was written for and
    the file (with its ``--set`` values) now states another, marked as no longer applying
    (:func:`tactcad.vocabulary.schema.reason_as_read`, the arrays' rule). A reason that is
    not a text is left out (the file's schema refuses it).

    Args:
        data: the die file's tables, its overrides applied.

    Returns:
        (key, text shown) pairs in the file's order; empty without ``[assumptions]``.
    """
    why = data.get("assumptions") if isinstance(data, Mapping) else None
    if not isinstance(why, Mapping):
        return ()
    return tuple((key, reason_as_read(key, reason.strip(), data)[0])
                 for key, reason in why.items() if isinstance(reason, str))


def load_die_design(path: str | Path, overrides: Mapping[str, Any] | None = None) -> DieDesign:
    """The die design file at ``path`` with ``overrides`` (``{"die.key": value}``, from
    ``--set``) applied, validated.

    Raises:
        DesignError: not a readable TOML file, a jaw file, or no ``[die]`` table.
        DesignErrors: a field out of range; a jaw file outside the design's folder or
            missing; LO >= HI.
    """
    source = Path(path)
    data = read_toml(source, "design file")
    refuse_jaw_file(data, source)  # a jaw file named as such, not as an array's design
    if not is_die_file(data):
        raise DesignError("design file", str(source), f"a file with a [{DIE_TABLE}] table",
                          "an array's design file is read by the other commands")
    if overrides:
        from tactcad.design.array_plan import with_overrides

        data = with_overrides(data, overrides)
    problems = Problems(source.name)
    model = validate(DieFile, data, problems)
    if model is None:
        problems.raise_if_any()
    die = model.die
    lo, hi = die.kobj_range_N_per_mm
    if not lo < hi:
        problems.add("die.kobj_range_N_per_mm", [lo, hi], "LO < HI")
    jaw = _jaw(die.jaw, source, problems)
    if not is_cell_name(die.name):
        cleaned = suggested_cell_name(die.name)
        # to paste as the file writes it; a --set of the key turns it into that option
        # (DesignErrors.sourced), as design.name's refusal does
        problems.extend([DesignError("die.name", die.name, f"{CELL_NAME_WORDS}, e.g. {cleaned}",
                                     "the name ends up in the GDSII cell and the die's file "
                                     "names", problems.file,
                                     alternatives=[{"option": f'die.name = "{cleaned}"',
                                                    "words": CLEANED_CELL_NAME_WORDS}])])
    problems.raise_if_any()
    return DieDesign(die, jaw, source, weibull_of(model.strength), attach_of(model.attach),
                     frozenset(data.get(DIE_TABLE) or {}), die_assumptions(data),
                     stale_reasons(data))


def attach_of(section: DieAttachSection | None) -> DieAttach | None:
    """The ``[attach]`` table as a :class:`~tactcad.products.silicon_die.design.mems_die.DieAttach` (None without
    one)."""
    if section is None:
        return None
    return DieAttach(section.material, section.modulus_MPa, section.poisson,
                     section.thickness_um, section.source, stated=True)


def weibull_of(section: DieStrengthSection | None) -> WeibullPair | None:
    """The ``[strength]`` table as a :class:`~tactcad.products.silicon_die.design.mems_die.WeibullPair` (None
    without one)."""
    if section is None:
        return None
    return WeibullPair(section.weibull_modulus, section.characteristic_strength_MPa,
                       section.reference_area_um2, section.source,
                       section.failure_probability_max)


#: What a die's name may be: it names the GDSII cell and the die's files.
CELL_NAME_WORDS = "a letter, then up to 31 letters, digits or _ (a GDSII cell name)"


def is_cell_name(text: str) -> bool:
    """True when ``text`` may name the die (:data:`CELL_NAME_WORDS`)."""
    import re

    return re.fullmatch(r"[A-Za-z][A-Za-z0-9_]{0,31}", text or "") is not None


#: What :func:`suggested_cell_name` does to a name, in a refusal's words.
CLEANED_CELL_NAME_WORDS = ("the name with accents dropped, other characters as _ and a letter "
                           "first")


def suggested_cell_name(text: str) -> str:
    """A die name (:data:`CELL_NAME_WORDS`) close to ``text`` for a user to paste: as a
    design's name is cleaned (:func:`tactcad.vocabulary.schema.suggested_name`: accents
    dropped, other characters as ``_``), its ``.`` and ``-`` as ``_`` too, ``die_`` before
    a name that starts with no letter, cut to 32 characters; the default die name when
    nothing of ``text`` is left."""
    import re

    from tactcad.vocabulary.schema import suggested_name

    name = re.sub(r"[^A-Za-z0-9_]+", "_", suggested_name(str(text), fallback=""))
    if name and not name[0].isalpha():
        name = "die_" + name
    name = name[:32].rstrip("_")
    return name if is_cell_name(name) else DEFAULT_DIE_NAME


def _jaw(value: str, source: Path, problems: Problems) -> str:
    """``--jaw``'s value of the file's ``jaw``: a trocar class as it is, a file name
    resolved in the design's folder (refused outside it or missing)."""
    from tactcad.partlib.grasper_jaw import SHAFT_CLASSES_MM

    classes = tuple(SHAFT_CLASSES_MM)
    if value in classes:
        return value
    folder = source.resolve().parent
    path = (folder / value).resolve()
    if not path.is_relative_to(folder):
        problems.add("die.jaw", value, "a trocar class (" + ", ".join(classes) + ") or a "
                     "jaw file in the design's folder", "a sensor folder reads nothing outside it")
    elif not path.is_file():
        problems.add("die.jaw", value, "a trocar class (" + ", ".join(classes) + ") or an "
                     "existing jaw file in the design's folder", f"no file {path.name} beside "
                     f"{source.name}")
    return str(path)


def die_file_text(jaw: str, kr_over_km: float, kobj_range: tuple[float, float],
                  full_scale_force_N: float, columns: int, pitch_um: float, name: str,
                  command: str, reasons: Mapping[str, str] = {},
                  max_grasp_force_N: float | None = None,
                  kobj_accuracy_rel: float | None = None) -> str:
    """A die design file's text (TOML) for these targets, headed by the command that made
    it and with the reasons of its values under ``[assumptions]``, each ending with the
    value it is written for (:func:`tactcad.vocabulary.schema.with_written_values`, as an
    array's design file: a later hand edit of the value shows its reason stale).

    Args:
        jaw: the jaw as the file states it (a trocar class or a jaw file's name).
        kr_over_km: K_r / K_m. kobj_range: (LO, HI), N/mm. full_scale_force_N: N.
        columns: units along the die. pitch_um: their spacing, um. name: the die's name.
        command: the command that made it (its header). reasons: key -> reason.
        max_grasp_force_N: N, or None (left out). kobj_accuracy_rel: relative, or None.

    Returns:
        The file's text.
    """
    import tomli_w

    from tactcad.version import VERSION

    data = {DIE_TABLE: {"jaw": jaw, "kr_over_km": float(kr_over_km),
                        "kobj_range_N_per_mm": [float(v) for v in kobj_range],
                        "full_scale_force_N": float(full_scale_force_N), "columns": int(columns),
                        "pitch_um": float(pitch_um), "name": name}}
    if max_grasp_force_N is not None:
        data[DIE_TABLE]["max_grasp_force_N"] = float(max_grasp_force_N)
    if kobj_accuracy_rel is not None:
        data[DIE_TABLE]["kobj_accuracy_rel"] = float(kobj_accuracy_rel)
    if reasons:
        data["assumptions"] = dict(reasons)
    return (f"# Written by tactcad {VERSION}: `{command}`.\n"
            "# A silicon die: `tactcad die --design THIS_FILE` derives the die, writes its "
            "masks, STEP and traveller and checks them.\n# Units: N/mm, N, um.\n\n"
            + tomli_w.dumps(with_written_values(data)))
