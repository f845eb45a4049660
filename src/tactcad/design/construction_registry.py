"""The array's constructions, one registry: how a validated design becomes parts.

A construction is a way of making the array: ``stacked`` (separate wire-cut
element sheets stacked on bolts with spacers and clamp plates, the paper's)
and ``monolithic-comb`` (one row's elements cut from one thin sheet on a
shared spine, rows on dowel pins and ISO screws, small enough for a grasper's
jaw). The design file chooses one with ``[array] construction`` (``stacked``
when left out).

Each entry names the module that owns the construction: its schema (the
design file's tables), its rules (every refusal at once), its derivation
(validated design -> :class:`~tactcad.design.array_plan.Plan`, each derived
dimension with its reason) and the array part modules its parts come from
(:mod:`tactcad.partlib.array`). The module is imported by name only when the
construction is asked for, as the estimator ladders do
(:mod:`tactcad.mechanics.level_registry`): a caller asks this registry and
never names a construction.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Any, Callable, Mapping

from tactcad.errors import DesignError

#: The construction of a design file that names none.
DEFAULT_CONSTRUCTION = "stacked"


@dataclass(frozen=True)
class Construction:
    """One way of making the array.

    Attributes:
        name: the value of ``[array] construction``.
        summary: one line for help texts and the reference page.
        module: the module that owns it; it defines ``validate_tables(data,
            file) -> (model | None, Problems)`` and ``derive_plan(model, data, source) -> Plan``.
        parts: the keys of the array part modules (:func:`tactcad.partlib.registry.array_parts_lib`)
            that make its parts, in the part list's order.
        scales_to_mm: the smallest row length it reaches (mm) and why, for the reference page.
        test_rigs: True when the test rigs' bracket can hold it (its plan has
            the clamp plate's mounting holes the bracket bolts to).
        jaw_design: ``"module:function"`` of its search to a grasper's jaw (``design
            --jaw``: ``(targets, room, columns, base_tables, **options) -> design``); empty
            when it does not seat in a jaw.
        jaw_template: the shipped example (relative to the examples folder) whose fixed
            details its jaw designs take.
        jaw_fit: ``"module:function"`` of its screen against a jaw before the search
            (``(room, columns, base_tables, targets, grade, process) -> list of
            misfits``, each a dict with ``words``, the dimension that binds against the
            jaw's key, and ``option`` to paste or ""; empty when its smallest build fits
            the room); empty: no screen.

    The module also places its parts: ``placed_parts(plan)`` gives every placed
    part but the strain gauges as (instance name, part name, placement),
    ``touching(plan)`` the instance pairs in face contact, ``mount_frames(plan)``
    the frames the test rigs' bracket mates with, and
    ``element_holder(plan, slot)`` the instance that carries an element (its
    gauge is bonded to it); the gauges are placed for any construction by
    :func:`tactcad.catalogue.array_catalogue.array_instances`.
    """

    name: str
    summary: str
    module: str
    parts: tuple[str, ...]
    scales_to_mm: str = ""
    test_rigs: bool = False
    jaw_design: str = ""
    jaw_template: str = ""
    jaw_fit: str = ""

    def jaw_screen(self) -> Callable[..., Any] | None:
        """Its screen against a jaw (:attr:`jaw_fit`), or None."""
        if not self.jaw_fit:
            return None
        module, function = self.jaw_fit.split(":")
        return getattr(importlib.import_module(module), function)

    def jaw_search(self) -> Callable[..., Any] | None:
        """Its search to a grasper's jaw (:attr:`jaw_design`), or None."""
        if not self.jaw_design:
            return None
        module, function = self.jaw_design.split(":")
        return getattr(importlib.import_module(module), function)

    def _function(self, name: str) -> Callable[..., Any]:
        return getattr(importlib.import_module(self.module), name)

    def validate(self, data: Mapping[str, Any], file: str = "") -> tuple[Any, Any]:
        """The design file's model under this construction and every refusal
        (:class:`~tactcad.vocabulary.schema.Problems`)."""
        return self._function("validate_tables")(data, file)

    def derive(self, model: Any, data: Mapping[str, Any], source: str) -> Any:
        """The plan of a design that passed :meth:`validate`."""
        return self._function("derive_plan")(model, data, source)

    def placed_parts(self, plan: Any) -> tuple[tuple[str, str, Any], ...]:
        """(instance name, part name, :class:`~tactcad.design.array_plan.Placement`) of
        every placed part of ``plan`` but the strain gauges (array frame, mm)."""
        return tuple(self._function("placed_parts")(plan))

    def touching(self, plan: Any) -> set[frozenset[str]]:
        """Instance pairs of :meth:`placed_parts` in face contact (zero volume)."""
        return set(self._function("touching")(plan))

    def mount_frames(self, plan: Any) -> dict[str, Any]:
        """The array's joint frames the test rigs' bracket mates with (name ->
        :class:`~tactcad.geometry.frames.Frame`, array frame); empty for a
        construction without a mount for the test rigs."""
        return dict(self._function("mount_frames")(plan))

    def element_holder(self, plan: Any, slot: Any) -> str:
        """The instance of :meth:`placed_parts` that carries element ``slot``."""
        return self._function("element_holder")(plan, slot)


CONSTRUCTIONS: dict[str, Construction] = {}


def register_construction(construction: Construction) -> None:
    """Add a construction to the registry.

    Raises:
        ValueError: one of that name is registered already.
    """
    if construction.name in CONSTRUCTIONS:
        raise ValueError(f"a construction {construction.name!r} is registered already")
    CONSTRUCTIONS[construction.name] = construction


def construction_names() -> tuple[str, ...]:
    """Every construction's name, in order of registration."""
    return tuple(CONSTRUCTIONS)


def unknown_construction(name: Any) -> DesignError:
    """The refusal of a construction no entry has (names every allowed one)."""
    return DesignError("array.construction", name, "one of " + ", ".join(construction_names()),
                       "the constructions tactcad can derive, make and check")


def construction(name: str) -> Construction:
    """The registered construction ``name``.

    Raises:
        DesignError: no construction has that name (the message lists the allowed ones).
    """
    found = CONSTRUCTIONS.get(name) if isinstance(name, str) else None
    if found is None:
        raise unknown_construction(name)
    return found


def construction_name(data: Mapping[str, Any]) -> Any:
    """The construction a design file's tables choose: ``[array] construction``,
    :data:`DEFAULT_CONSTRUCTION` when left out (the value as given otherwise,
    so that a wrong one is refused with its name)."""
    array = data.get("array") if isinstance(data, Mapping) else None
    if isinstance(array, Mapping) and "construction" in array:
        return array["construction"]
    return DEFAULT_CONSTRUCTION


def construction_of(plan: Any) -> Construction:
    """The construction a plan was derived by."""
    return construction(plan.construction)


def left_out(plan: Any) -> list[dict[str, str]]:
    """What an export of ``plan`` leaves out because its construction does not
    declare it, each as ``{"what": ..., "reason": ...}`` (the manifest's
    ``left_out`` section, with what the crosstalk ladder leaves out; empty for the
    stacked array)."""
    made, out = construction_of(plan), []
    if not made.test_rigs:
        out.append({"what": "test rigs: their scenes, parts, drawings, BOM rows and build steps",
                    "reason": f"the construction {plan.construction} has no mount for the "
                              "test rigs' bracket (it bolts to the stacked array's clamp plate)"})
    return out


def check_test_rigs(plan: Any, problems: Any, file: str) -> bool:
    """Refuse (in ``problems``) a plan whose construction the test rigs cannot
    hold; True when they can.

    Args:
        plan: the design's plan.
        problems: the rig file's :class:`~tactcad.vocabulary.schema.Problems`.
        file: the design file's name (the refusal names its field).
    """
    if construction_of(plan).test_rigs:
        return True
    held = ", ".join(c.name for c in CONSTRUCTIONS.values() if c.test_rigs)
    problems.add("array.construction", plan.construction, f"one of {held} for a project with "
                 "test rigs", "the rigs' bracket bolts to the clamp plate's mounting holes; "
                 f"{plan.construction} has no mount for the test rigs yet", file=file)
    return False


register_construction(Construction(
    "stacked",
    "separate wire-cut element sheets stacked on bolts with spacers between and clamp "
    "plates outside (the paper's array)",
    "tactcad.design.array_plan",
    ("element", "spacer", "clamp_plate", "gauge", "bolt"),
    "each row is as long as an element (>= 10 mm) and the stack is columns x pitch; "
    "M2 bolts, 3 mm plates: about 60 x 14 mm at the least", test_rigs=True))

register_construction(Construction(
    "monolithic-comb",
    "one row's elements cut from one thin sheet on a shared spine with a stop ledge under "
    "every arm; the rows face each other across a thin spacer on ISO 8734 dowel pins and "
    "M1.2/M1.6 screws (fits a grasper's jaw)",
    "tactcad.design.comb_plan",
    ("comb_sheet", "comb_hardware", "gauge"),
    "each element is post + notch + arm + half the tip long (arms >= 2 mm): about "
    "columns x 4 mm along the row and 6 mm across two 1 mm rows",
    jaw_design="tactcad.studies.comb_design:comb_for_jaw",
    jaw_template="grasper_jaw_10mm/grasper_jaw_10mm.toml",
    jaw_fit="tactcad.studies.comb_design:comb_misfit"))


def jaw_not_judged(plan, file: str = "") -> str | None:
    """What a design that states ``[grasper_jaw]`` is told when its construction is not
    judged against a jaw (the stacked array: no jaw search in its construction's entry and
    no kernel-free envelope, so :func:`stated_grasper_errors` passes the jaw over); None
    when no jaw is stated or the construction seats in it.

    Args:
        plan: the design's plan (``plan.raw`` its tables, ``--set`` values included).
        file: the design file's name, for the message.

    Returns:
        One line naming the file and table, the construction and those judged against a
        jaw, or None.
    """
    from tactcad.partlib.grasper_jaw import insert_envelope_mm

    raw = getattr(plan, "raw", None) or {}
    if "grasper_jaw" not in raw or insert_envelope_mm(plan) is not None:
        return None
    made = construction_of(plan)
    if made.jaw_design:
        return None
    seated = [f'array.construction = "{c.name}"' for c in CONSTRUCTIONS.values()
              if c.jaw_design]
    where = f"{file}: " if file else ""
    return (f"{where}[grasper_jaw] stated, but a {made.name} array "
            f'(array.construction = "{made.name}") is not judged against a jaw: its '
            "construction does not seat in one, so the jaw's fit (its pocket, pivot and "
            "window, the closed jaws in the shaft) is not checked; a stated jaw is judged for "
            f"a monolithic comb ({', '.join(seated)}) and a silicon die (a [die] file, "
            "`tactcad design --jaw`)")


def warn_jaw_not_judged(plan, file: str = "") -> None:
    """Issue :func:`jaw_not_judged`'s line, where there is one, as a
    :class:`~tactcad.errors.JawNotJudgedWarning` (a command says it once on stderr,
    ``--quiet`` silences it, ``--json`` lists it under ``warnings``).

    Args:
        plan: the design's plan.
        file: the design file's name, for the message.
    """
    import warnings

    from tactcad.errors import JawNotJudgedWarning

    text = jaw_not_judged(plan, file)
    if text is not None:
        warnings.warn(JawNotJudgedWarning(text), stacklevel=3)
