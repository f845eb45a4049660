"""The forms of a part written as one module (:mod:`tactcad.partlib`).

A rig part module holds everything about one rig part and exposes it as one
:class:`RigPart` named ``PART``:

* ``section``: its ``rigs.toml`` table (a :class:`~tactcad.vocabulary.schema.Section`;
  when every field has a default a rigs file without the table stays valid);
* ``derive``: the validated table, the array's plan and the parts it needs
  -> :class:`PartData` (the spec: name, kind, typed process, material,
  colour, expected volume and box, the geometry its builder reads, derived
  dimensions with their reasons, its joint frames, its seat and the seat on
  its host, the screws it is fixed with, its companion parts), refusals added
  to the file's problems;
* ``build``: geometry -> solid in the part frame, written in the modelling
  verbs of :mod:`tactcad.kernel.shapes` (which load the kernel only when
  called, so this layer stays kernel-free), and ``companion_builders`` for
  its companions;
* ``drawing``: a :class:`DrawingRecord` (pure data) for a made part, ``None``
  for a bought one (no drawing);
* ``host``: the rig node it is mounted on; it is shown with its host's group,
  mated seat on seat and declared touching it (empty: the rig's own joints
  in :mod:`tactcad.assembly.rig_models` place it, e.g. on a slide);
* ``needs``: the part modules whose derived data its derivation reads; the
  parts are derived in that order (a circle is refused);
* ``order``: its place among the rig parts: in the list of derived
  dimensions (manifest), in the rigs file's schema, in the derivation (among
  parts free to go either way) and in a rig's placement, so that output
  order is written down rather than taken from module names.

The layers above read the registry (:func:`tactcad.partlib.registry.rig_parts_lib`):
``design.rigs`` adds the tables to the rigs file schema and derives each part,
``catalogue.rigs`` turns :class:`PartData` into a spec, ``solids.build``
runs ``build``, ``assembly.rigs`` places it, ``drawings.part_sets`` draws it.

The array's parts (:mod:`tactcad.partlib.array`) are written in the same
manner as :class:`ArrayPart`: builder, drawing and spec data under one key,
their dimensions read from the plan of the array's one coupled derivation
(:mod:`tactcad.design.array_plan`), which ``specs`` turns into :class:`PartData`
(``catalogue.array`` makes the specs). Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field, make_dataclass
from typing import Any, Callable, Mapping

from tactcad.vocabulary.process import Process
from tactcad.vocabulary.schema import Derived, Problems, Section

Vec3 = tuple[float, float, float]
Bbox = tuple[float, float, float, float, float, float]  # xmin, ymin, zmin, xmax, ymax, zmax (mm)
RGB = tuple[float, float, float]


@dataclass(frozen=True)
class Seat:
    """A joint frame as plain numbers (mm): a face's point, its outward
    normal and the in-face x direction. Two seats mate face on face."""

    origin: Vec3
    normal: Vec3
    x_dir: Vec3


@dataclass(frozen=True)
class Fastener:
    """A bought socket head cap screw (ISO 4762) a part is fixed with: listed
    as a part of its own (``bolt_M3x10``) unless a rig part listed before
    already has it, which then keeps its colour."""

    bolt: Any  # tactcad.vocabulary.standards.BoltSpec
    length_mm: float
    color: RGB


@dataclass(frozen=True)
class PartData:
    """What a part module derives: the spec of the part and where it sits.

    Attributes:
        geometry: frozen dataclass the builder reads (fixes the solid).
        seat: the part's own mating face, in its part frame (joint frame
            ``seat``); None for a part the rig's joints place.
        host_seat: the face of the host it sits on, in the host's part frame;
            None without a host.
        derived: dimensions the part derives, each with its reason.
        attributes: data carried into manifest and GLB.
        frames: further named joint frames in the part frame (``top``,
            ``bottom`` ...), for the rig's joints and for parts it hosts.
        builder: the builder key of this spec when it is one of the
            module's :attr:`RigPart.companion_builders` (empty: the module's
            own builder).
        companions: further parts the module makes, each a spec of its own
            (the Z stage's carriage beside its body, the rail's block ...).
        fasteners: the screws the part is fixed with (:class:`Fastener`).
        profile: the planar profile of an extruded part (its DXF and drawing
            read it), None for any other.
        thickness_mm: the extruded part's thickness (mm), 0 for any other.
    """

    name: str
    kind: str  # "fabricated" or "purchased"
    process: Process
    material: str
    color: RGB
    expected_volume_mm3: float
    expected_bbox_mm: Bbox
    geometry: Any
    seat: Seat | None = None
    host_seat: Seat | None = None
    derived: tuple[Derived, ...] = ()
    attributes: Mapping[str, Any] = field(default_factory=dict)
    frames: Mapping[str, Seat] = field(default_factory=dict)
    builder: str = ""
    companions: tuple["PartData", ...] = ()
    fasteners: tuple[Fastener, ...] = ()
    profile: Any = None  # tactcad.geometry.profile.Profile of a prism (sketch plane z = 0)
    thickness_mm: float = 0.0  # the prism's extrusion along +z


@dataclass(frozen=True)
class DrawingRecord:
    """A made part's shop drawing beyond the common sheet.

    The part module draws with the pen the drawings layer hands it
    (:data:`tactcad.drawings.part_sets.PEN`: ``dim``, ``hole_marks``,
    ``generic_dims``, ``fmt_mm`` ...), so it imports nothing of that layer;
    ``drawing`` is the :class:`tactcad.drawings.drawing.Drawing` being made
    (its views, sheet, spec), ``solid`` the part's solid.

    Attributes:
        notes: notes before the process note.
        hole_table: whether many holes go in a coordinate table.
        dimensions: ``(drawing, solid, pen) -> None``, the dimension set;
            None: the general set (overall sizes, thickness, holes).
        section: ``(drawing, solid, pen) -> None`` adding a section view, or None.
        notes_after: ``(geometry, pen) -> [sentence]``, notes after the
            process note, or None.
        view_from: fixed view directions (the front view's direction, its
            up), or None (by the bounding box).
        notes_of: ``(drawing, pen) -> [sentence]``, every note before the
            general tolerance note, in place of ``notes``, the process note
            and ``notes_after`` (a note that reads the plan: ``drawing.plan``),
            or None.
        detail: ``geometry -> ((x, y), radius)`` of a detail view in model mm, or None.
        plan_values: ``(plan, spec, pen) -> tuple`` of the plan values the
            notes and dimensions print beyond the spec (part of the drawing's
            hash), or None (none).
    """

    notes: tuple[str, ...] = ()
    hole_table: bool = True
    dimensions: Callable[[Any, Any, Any], None] | None = None
    section: Callable[[Any, Any, Any], None] | None = None
    notes_after: Callable[[Any, Any], list[str]] | None = None
    view_from: tuple[Vec3, Vec3] | None = None
    notes_of: Callable[[Any, Any], list[str]] | None = None
    detail: Callable[[Any], tuple] | None = None
    plan_values: Callable[[Any, Any, Any], tuple] | None = None


def _no_text(book: Any) -> tuple[str, ...]:
    return ()


@dataclass(frozen=True)
class BuildStep:
    """The build-book step that consumes a part module's parts, and what the
    module says of assembling them (:mod:`tactcad.assembly.build_steps`
    gathers the steps from the modules).

    Attributes:
        key: the step (``array-gauges``, ``array-stack`` ...).
        title: the step's title, from the module that leads it ("" otherwise).
        tools: ``book -> tools`` the step needs for these parts.
        notes: ``book -> instructions`` (one sentence each, units in the text).
            ``book`` is the build book's context
            (:class:`tactcad.assembly.build_steps.BookContext`).
        companions: builder keys of the module's companion parts the step
            consumes too (the clamp bolt's nut).
    """

    key: str
    title: str = ""
    tools: Callable[[Any], tuple[str, ...]] = _no_text
    notes: Callable[[Any], tuple[str, ...]] = _no_text
    companions: tuple[str, ...] = ()  # companion builders consumed in the same step


class Builds:
    """What every part module's part has: its own builder under
    :attr:`builder_key` and its companions' builders."""

    def builders(self) -> dict[str, Callable[[Any], Any]]:
        """Every builder of the module by builder key: its own and its companions'."""
        return {self.builder_key: self.build, **self.companion_builders}


@dataclass(frozen=True)
class RigPart(Builds):
    """One rig part written as one module (see the module doc).

    Attributes:
        key: the ``rigs.toml`` table name and the registry key.
        host: the rig node the part mounts on (``cart``, ``array_bracket`` ...);
            the part is placed in every rig that has it. Empty: the rig's
            joints place it.
        derive: ``(section, context, problems) -> PartData``; ``context`` has
            ``plan`` (the array's :class:`tactcad.design.array_plan.Plan`),
            ``part(key)`` and ``table(key)``, the derived data and the
            validated table of a part module named in ``needs``.
        needs: keys of the part modules ``derive`` reads (derived first).
        order: place in the derived dimensions, the rigs file's schema, the
            derivation and the placement (smaller first; ties by key).
        builder: the spec's builder key when it is not ``key`` (a made part's
            builder key is part of its drawing's hash, so a part moved into
            this form keeps the key it had).
        companion_builders: builder key -> builder of the companions'
            specs (:attr:`PartData.companions`), geometry -> solid.
        assembly: the build-book step that consumes the part (:class:`BuildStep`);
            None: the step of the rig that first shows it.
    """

    key: str
    section: type[Section]
    host: str
    derive: Callable[[Section, Any, Problems], PartData]
    build: Callable[[Any], Any]
    drawing: DrawingRecord | None = None
    needs: tuple[str, ...] = ()
    order: int = 1000
    builder: str = ""
    companion_builders: Mapping[str, Callable[[Any], Any]] = field(default_factory=dict)
    assembly: BuildStep | None = None

    @property
    def builder_key(self) -> str:
        """The key of :attr:`build` among the builders (``PartSpec.builder``)."""
        return self.builder or self.key

    @property
    def table_required(self) -> bool:
        """Whether ``rigs.toml`` must give the table (a field without default)."""
        return any(f.is_required() for f in self.section.model_fields.values())


@dataclass(frozen=True)
class ArrayContext:
    """What an array part module's ``specs`` reads: the plan the array's one
    coupled derivation made (:func:`tactcad.design.array_plan.plan_from_model`)
    and the values derived above this layer.

    Attributes:
        plan: the array's :class:`tactcad.design.array_plan.Plan`.
        materials: material name of the clamp plates and spacers by part key
            (``clamp_plate``, ``spacer``; :func:`tactcad.catalogue.array_catalogue.part_material_names`).
        gauge: the strain gauge's body (:class:`tactcad.partlib.array.strain_gauge.GaugeBody`).
        tables: the validated design-file table of each module that has one
            (:attr:`ArrayPart.section`), by key, for the tables the design gives.
    """

    plan: Any
    materials: Mapping[str, str]
    gauge: Any
    tables: Mapping[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class ArrayPart(Builds):
    """One part family of the clamped array written as one module
    (:mod:`tactcad.partlib.array`): the element, the spacer, the clamp plate,
    the strain gauge's body, the bolts and nuts.

    The array's dimensions are one coupled derivation (element, clamp and bolt
    pattern) in :mod:`tactcad.design.array_plan`, which sits above this layer; a
    module reads its part's dimensions from the plan through ``specs``.

    Attributes:
        key: the builder key of :attr:`build` (``PartSpec.builder``) and the
            registry key.
        build: geometry -> solid in the part frame (kernel modelling verbs).
        specs: ``ArrayContext -> (PartData, ...)``, the family's distinct
            parts (one per arm length for the element, none for a spacer of a
            one-column array).
        drawing: a made part's :class:`DrawingRecord`, None for a bought one.
        order: its place in the array's part list (smaller first; ties by key).
        companion_builders: builder key -> builder of the specs the module
            makes under another key (:attr:`PartData.builder`).
        section: the design file's table ``[key]`` the module reads (every
            field with its range; the table may be left out), or None.
        replaces: a variant's family: the key of the module it stands in for
            when the design gives the variant's table (its parts keep the
            family's part names, so the array places them alike); a variant
            whose table is left out makes no part. Empty: no variant.
        assembly: the build-book step that consumes the module's parts
            (:class:`BuildStep`).
    """

    key: str
    build: Callable[[Any], Any]
    specs: Callable[[ArrayContext], tuple[PartData, ...]]
    drawing: DrawingRecord | None = None
    order: int = 1000
    companion_builders: Mapping[str, Callable[[Any], Any]] = field(default_factory=dict)
    section: type[Section] | None = None
    replaces: str = ""
    assembly: BuildStep | None = None

    @property
    def builder_key(self) -> str:
        """The key of :attr:`build` among the builders: :attr:`key`."""
        return self.key


def table_values(section: type[Section], **extra: Any) -> type:
    """A frozen dataclass holding a table's values, field for field in the
    table's order, then ``extra`` fields (name=type) a derivation adds; a part
    whose builder reads its table as it is subclasses it for its geometry
    (``class CarrierGeometry(table_values(CarrierSection))``) instead of
    writing the fields again. Build one with :func:`values_from`."""
    fields = [(name, info.annotation) for name, info in section.model_fields.items()]
    return make_dataclass(f"{section.__name__}Values", fields + list(extra.items()), frozen=True)


def values_from(cls: type, table: Section, **extra: Any) -> Any:
    """An instance of ``cls`` (made by :func:`table_values`) from a validated
    ``table`` and the ``extra`` values (which may replace a table value the
    derivation filled in, e.g. a size left out of the file)."""
    return cls(**{**{name: getattr(table, name) for name in type(table).model_fields}, **extra})

