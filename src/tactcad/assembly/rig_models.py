"""Rig models, kernel-free: the array, its wire-cut profiles and the paper's
three test rigs as kinematic trees of nodes and joints, and the scenes that
show groups of them (solved by :mod:`tactcad.assembly.scene_solver`).

A scene (``hardware/scenes.toml``) names its rig, the groups of parts it
shows and their level of detail. A rig is a kinematic tree of nodes (parts
or sub-assemblies such as the array) joined by

* rigid mates: a child's joint frame, flipped, onto a parent's joint frame
  (face on face: tip contact face on sample top, bearing tread on groove
  floor, bolt head on bracket ...), solved with build123d ``RigidJoint``;
* slides: a child moving along the x axis of a parent's frame (the cart
  rolling in its grooves, the micro-stages, the Z axis, the linear block),
  solved with build123d ``LinearJoint``. A slide has a range; its position
  is given or solved so that a point of the moving side reaches a target
  point on the other side along the slide axis (the loop closures of the
  rig: indenter on the element tip, tips on the sample ...). A position
  outside the slide's range raises :class:`SceneError`.

Joint frames are data of the parts (:mod:`tactcad.catalogue.rig_catalogue`, from the
plan for the array), so placing a scene never builds a part; building a
scene builds only the parts of its shown groups, once each per level of
detail (counted in :data:`tactcad.solids.build.BUILD_COUNTS`). Scene frame: mm,
y up (the array frame's convention).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, Mapping

from tactcad.catalogue.array_catalogue import (PartSpec, array_contacts, array_instances, array_parts,
                                     bolt_name, nut_name)
from tactcad.catalogue.rig_catalogue import bolt_frames, nut_frames, rig_parts, seat_frame
from tactcad.design.array_plan import Placement, Plan
from tactcad.design.construction_registry import construction_of
from tactcad.design.project import Project
from tactcad.design.rig_plan import RigDesign
from tactcad.design.scene_specs import RIGS, SceneSpec
from tactcad.errors import DesignError, SceneError
from tactcad.geometry.frames import Frame
from tactcad.partlib.cart import wheel_tag
from tactcad.partlib.registry import rig_parts_lib
from tactcad.partlib.sample import sample_name

SOLVE_TOL_MM = 1e-9

WORLD_Y_UP = Frame((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))  # part z -> scene y
IDENTITY = Frame((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0))


@dataclass(frozen=True)
class Member:
    """A part placed inside a sub-assembly node, in the node's frame."""

    name: str
    part: str
    placement: Placement
    group: str


@dataclass(frozen=True)
class Node:
    """A part (``part`` set) or a sub-assembly (``members``), with joint frames."""

    name: str
    group: str
    frames: Mapping[str, Frame]
    part: str | None = None
    members: tuple[Member, ...] = ()


@dataclass(frozen=True)
class Mate:
    """Rigid: ``child.child_frame`` (flipped) onto ``parent.parent_frame``."""

    child: str
    child_frame: str
    parent: str
    parent_frame: str
    contact: bool = True


@dataclass(frozen=True)
class Slide:
    """Prismatic: the child's frame (flipped) moves along the parent frame's x
    axis, ``position`` within ``range``; ``solve = ((node, frame), (node, frame))``
    moves the first point (on the child's side) onto the second along the axis."""

    name: str
    child: str
    child_frame: str
    parent: str
    parent_frame: str
    range: tuple[float, float]
    position: float | None = None
    solve: tuple[tuple[str, str], tuple[str, str]] | None = None
    contact: bool = True


@dataclass
class RigModel:
    """Nodes, joints and declared contacts of one rig (kernel-free)."""

    rig: str
    nodes: dict[str, Node]
    roots: dict[str, Frame]
    steps: list
    solve_order: list[str]
    extra_contacts: set[frozenset[str]]
    specs: dict[str, PartSpec]
    checks: dict[str, Any] = field(default_factory=dict)
    empty_groups: tuple[str, ...] = ()  # groups the rig has, with no part this time

    def instances(self) -> list[tuple[str, str, str]]:
        """Every leaf instance as (instance name, part name, group), in order."""
        out = []
        for n in self.nodes.values():
            if n.part is not None:
                out.append((n.name, n.part, n.group))
            out += [(m.name, m.part, m.group) for m in n.members]
        return out

    def groups(self) -> dict[str, list[tuple[str, str]]]:
        """Group -> [(instance, part)], every group of the rig (possibly empty)."""
        out: dict[str, list[tuple[str, str]]] = {g: [] for g in self.empty_groups}
        for name, part, group in self.instances():
            out.setdefault(group, []).append((name, part))
        return out

    def contacts(self) -> set[frozenset[str]]:
        """Instance pairs declared touching: every contact mate and slide, plus
        the rig's extra contacts (loop closures, threads, rolling wheels)."""
        pairs = set(self.extra_contacts)
        for s in self.steps:
            if s.contact:
                a = self.nodes[s.child].frames[s.child_frame].owner or s.child
                b = self.nodes[s.parent].frames[s.parent_frame].owner or s.parent
                pairs.add(frozenset({a, b}))
        return pairs


def _array_node(plan: Plan, name: str = "array", group: str = "array") -> Node:
    """The array as one sub-assembly (array frame) with its joint frames: the
    mount its construction declares for the test rigs (the stacked array's
    ``mount`` and ``nut_k``; none for a construction without one),
    ``tip_n`` (element n's contact face centre, on the instance that carries
    it) and ``tips`` (centroid of the tip plane)."""
    made = construction_of(plan)
    frames: dict[str, Frame] = dict(made.mount_frames(plan))
    tips = []
    for s in plan.slots:
        p = s.tip_centre_world_mm
        tips.append(p)
        frames[f"tip_{s.number}"] = Frame(p, (1, 0, 0), (0, 1, 0), made.element_holder(plan, s))
    cz = sum(p[2] for p in tips) / len(tips)
    cx = sum(p[0] for p in tips) / len(tips)
    frames["tips"] = Frame((cx, tips[0][1], cz), (1, 0, 0), (0, 1, 0))
    members = tuple(Member(i.name, i.part, i.placement, group) for i in array_instances(plan))
    return Node(name, group, frames, members=members)


def _leaf(name: str, spec: PartSpec, group: str, frames: Mapping[str, Frame] | None = None) -> Node:
    return Node(name, group, frames if frames is not None else getattr(spec, "frames", {}),
                part=spec.name)


def _wirecut_model(plan: Plan) -> RigModel:
    specs = dict(array_parts(plan))
    gap = 3.0  # between profiles on the sheet, mm
    members = []
    el_w = max(specs[s.geometry.part_name].expected_bbox_mm[3] for s in plan.slots)
    el_h = max(specs[s.geometry.part_name].expected_bbox_mm[4] for s in plan.slots)
    for s in plan.slots:
        x0, y0 = specs[s.geometry.part_name].expected_bbox_mm[:2]
        members.append(Member(f"element_{s.number}", s.geometry.part_name,
                              Placement(s.row * (el_w + gap) - x0,
                                        (plan.columns - 1 - s.column) * (el_h + gap) - y0, 0.0),
                              "elements"))
    for k in range(len(plan.spacer_placements)):
        sp = specs["spacer"].expected_bbox_mm
        per_col = max(1, int((plan.columns * (el_h + gap)) // (sp[4] - sp[1] + gap)))
        col, row = divmod(k, per_col)
        members.append(Member(f"spacer_{k + 1}", "spacer",
                              Placement(plan.rows * (el_w + gap) + col * (sp[3] - sp[0] + gap) - sp[0],
                                        row * (sp[4] - sp[1] + gap) - sp[1], 0.0), "spacers"))
    sheet = Node("sheet", "elements", {}, members=tuple(members))
    used = {m.part for m in members}
    return RigModel("wirecut", {"sheet": sheet}, {"sheet": WORLD_Y_UP}, [], [], set(),
                    {n: s for n, s in specs.items() if n in used},
                    empty_groups=() if plan.spacer_placements else ("spacers",))


def _array_model(plan: Plan) -> RigModel:
    return RigModel("array", {"array": _array_node(plan)}, {"array": IDENTITY}, [], [],
                    set(array_contacts(plan)), dict(array_parts(plan)), {"tips": "array"})


def _grasper_model(plan: Plan, scene: SceneSpec | None) -> RigModel:
    """The insert in a grasper's jaw above a tissue slab (:mod:`tactcad.assembly.grasper_rig`):
    the array's ``jaw_seat`` frame mated, flipped, onto the jaw's ``insert`` frame; closed
    (angle 0), the row sheets touch the slab.

    Raises:
        SceneError: the construction gives the array no seat for a jaw.
        DesignErrors: the jaw cannot take the insert.
    """
    from tactcad.assembly.grasper_rig import grasper_layout

    array = _array_node(plan)
    if "jaw_seat" not in array.frames:
        raise SceneError(f"rig grasper: the {plan.construction} construction gives the array no "
                         "seat for a grasper's jaw (a construction that does: monolithic-comb)")
    lay = grasper_layout(plan, scene)
    groups = {"grasper_jaw": "jaw", "tissue_slab": "tissue", "grasper_shaft": "shaft"}
    nodes = {name: _leaf(name, spec, groups[name]) for name, spec in lay.specs.items()}
    nodes["array"] = array
    contacts = set(array_contacts(plan))
    if lay.angle_deg == 0.0:  # closed: every contact face on the slab's top face
        contacts |= {frozenset({construction_of(plan).element_holder(plan, s), "tissue_slab"})
                     for s in plan.slots}
    return RigModel("grasper", nodes, dict(lay.roots),
                    [Mate("array", "jaw_seat", "grasper_jaw", "insert", contact=False)], [],
                    contacts, lay.specs | dict(array_parts(plan)), {"jaw_angle_deg": lay.angle_deg})


class _Builder:
    """Collects nodes and joints of a rig in topological order."""

    def __init__(self, plan: Plan, rigs: RigDesign):
        self.plan, self.rigs = plan, rigs
        self.rp = rig_parts(plan, rigs)
        self.ap = array_parts(plan)
        self.nodes: dict[str, Node] = {}
        self.steps: list = []
        self.contacts: set[frozenset[str]] = set()
        self.specs: dict[str, PartSpec] = {}

    def leaf(self, name: str, part: str, group: str, frames=None) -> str:
        spec = self.rp.get(part) or self.ap[part]
        self.specs[spec.name] = spec
        self.nodes[name] = _leaf(name, spec, group, frames)
        return name

    def mate(self, child: str, cf: str, parent: str, pf: str, contact: bool = True) -> None:
        self.steps.append(Mate(child, cf, parent, pf, contact))

    def slide(self, name, child, cf, parent, pf, rng, position=None, solve=None, contact=True):
        self.steps.append(Slide(name, child, cf, parent, pf, (float(rng[0]), float(rng[1])),
                                position, solve, contact))

    def touch(self, a: str, b: str) -> None:
        self.contacts.add(frozenset({a, b}))

    # --- groups shared by the rigs ---
    def base_and_column(self) -> None:
        self.leaf("base_plate", "base_plate", "base_plate")
        self.leaf("column", "column", "column")
        self.mate("column", "foot", "base_plate", "column_seat")

    def z_axis_and_gauge(self, target: tuple[str, str]) -> None:
        r = self.rigs
        self.leaf("z_stage_body", "z_stage_body", "z_axis")
        self.leaf("z_stage_carriage", "z_stage_carriage", "z_axis")
        self.leaf("force_gauge", "force_gauge", "force_gauge")
        self.leaf("indenter", "indenter", "indenter")
        z = r.part("z_axis")
        self.slide("z_mount", "z_stage_body", "back", "column", "front",
                   (0.0, r.part("column").height_mm - z.body_height_mm),
                   solve=(("indenter", "contact"), target))
        lo = z.carriage_height_mm / 2
        self.slide("z_travel", "z_stage_carriage", "back", "z_stage_body", "front",
                   (lo, lo + z.travel_mm), position=lo + z.position_mm)
        self.mate("force_gauge", "back", "z_stage_carriage", "front")
        self.mate("indenter", "mount", "force_gauge", "shaft_end")
        self.touch("indenter", target[0] if target[0] != "array" else
                   self.nodes["array"].frames[target[1]].owner)

    def bracket(self, parent: str, parent_frame: str) -> None:
        br = self.rigs.part("bracket")
        self.leaf("array_bracket", "array_bracket", "bracket")
        self.mate("array_bracket", "foot", parent, parent_frame)
        self.nodes["array"] = _array_node(self.plan)
        for i in self.nodes["array"].members:
            self.specs[i.part] = self.ap[i.part]
        self.mate("array", "mount", "array_bracket", "array_mount")
        bolt = bolt_name(br.bolt, br.bolt_length_mm)
        nut = nut_name(br.bolt)
        for k in (1, 2):
            self.leaf(f"bracket_bolt_{k}", bolt, "bracket", bolt_frames())
            self.leaf(f"bracket_nut_{k}", nut, "bracket", nut_frames())
            self.mate(f"bracket_bolt_{k}", "seat", "array_bracket", f"bolt_{k}")
            self.mate(f"bracket_nut_{k}", "seat", "array", f"nut_{k}")
            self.touch(f"bracket_bolt_{k}", f"bracket_nut_{k}")  # thread
        self.contacts |= array_contacts(self.plan)

    def cart(self, target: tuple[str, str], sample_k: float) -> None:
        r = self.rigs
        k = r.part("cart")
        for sx in (-1, 1):
            for sy in (-1, 1):
                t = wheel_tag(sx, sy)
                self.leaf(f"wheel_{t}", f"bearing_{k.bearing.designation}", "cart")
                self.leaf(f"wheel_spacer_{t}", "wheel_spacer", "cart")
                self.leaf(f"wheel_bolt_{t}", bolt_name(k.axle_bolt, k.axle_bolt_length_mm), "cart")
        self.leaf("cart", "cart", "cart")
        L = r.part("base_plate").length_mm
        # the first wheel (-x, -y) rolls in the -y groove; the cart hangs on it
        lo = -L / 2 + k.length_mm / 2 - k.axle_x_mm
        hi = L / 2 - k.length_mm / 2 - k.axle_x_mm
        sample = sample_name(sample_k)
        self.leaf("sample", sample, "sample")
        self.slide("cart_roll", "wheel_mm", "tread", "base_plate", "groove_m", (lo, hi),
                   solve=(("sample", "top"), target))
        self.mate("wheel_spacer_mm", "wheel_side", "wheel_mm", "inner")
        self.mate("cart", "axle_mm", "wheel_spacer_mm", "cart_side")
        for t in ("mp", "pm", "pp"):
            self.mate(f"wheel_spacer_{t}", "cart_side", "cart", f"axle_{t}")
            self.mate(f"wheel_{t}", "inner", f"wheel_spacer_{t}", "wheel_side")
            self.touch(f"wheel_{t}", "base_plate")  # rolls on the groove floor
        for t in ("mm", "mp", "pm", "pp"):
            self.mate(f"wheel_bolt_{t}", "seat", f"wheel_{t}", "outer")
            self.touch(f"wheel_bolt_{t}", "cart")  # thread in the tapped hole
        h = r.part("sample_holder")
        self.leaf("sample_holder", "sample_holder", "sample_holder")
        self.mate("sample_holder", "bottom", "cart", "top")
        for i in (1, 2):
            self.leaf(f"holder_bolt_{i}", bolt_name(h.screw, h.screw_length_mm), "sample_holder")
            self.mate(f"holder_bolt_{i}", "seat", "sample_holder", f"screw_{i}")
            self.touch(f"holder_bolt_{i}", "cart")
        self.mate("sample", "bottom", "cart", "top")

    def library_parts(self) -> None:
        """Each part module's part (:mod:`tactcad.partlib`) whose host is in this
        rig: in the host's group, its seat mated on the host's seat, touching it."""
        for key, part in rig_parts_lib().items():
            host = self.nodes.get(part.host)
            if host is None or host.part is None or self.rigs.library[key].host_seat is None:
                continue
            data = self.rigs.library[key]
            host_frame = f"{key}_seat"
            self.nodes[part.host] = replace(
                host, frames={**host.frames, host_frame: seat_frame(data.host_seat)})
            self.leaf(key, data.name, host.group)
            self.mate(key, "seat", part.host, host_frame)

    def model(self, rig: str, solve_order: list[str], checks: dict,
              empty_groups: tuple[str, ...] = ()) -> RigModel:
        self.library_parts()
        return RigModel(rig, self.nodes, {"base_plate": WORLD_Y_UP}, self.steps, solve_order,
                        self.contacts, self.specs, checks, empty_groups)


def _sample_k(rigs: RigDesign, scene: SceneSpec | None) -> float:
    given = scene.sample_stiffness_N_per_mm if scene is not None else None
    k = rigs.sample_stiffness_N_per_mm[0] if given is None else given
    if k not in rigs.sample_stiffness_N_per_mm:
        raise DesignError(f"scene.{scene.name if scene else '?'}.sample_stiffness_N_per_mm", k,
                          "one of " + ", ".join(f"{v:g}" for v in rigs.sample_stiffness_N_per_mm),
                          "the measured samples of rigs.toml")
    return k


def _calibration_model(plan: Plan, rigs: RigDesign) -> RigModel:
    b = _Builder(plan, rigs)
    n = rigs.calibration_element
    b.base_and_column()
    xy = rigs.part("xy_stage")
    L = rigs.part("base_plate").length_mm
    half = xy.travel_mm / 2
    b.leaf("xy_lower_base", "xy_stage_base", "xy_stage")
    b.leaf("xy_lower_table", "xy_stage_table", "xy_stage")
    b.leaf("xy_upper_base", "xy_stage_base", "xy_stage")
    b.leaf("xy_upper_table", "xy_stage_table", "xy_stage")
    b.slide("stage_mount", "xy_lower_base", "bottom", "base_plate", "top",
            (-L / 2 + xy.size_mm / 2, L / 2 - xy.size_mm / 2),
            solve=(("array", "tips"), ("indenter", "contact")))
    b.slide("stage_x", "xy_lower_table", "bottom", "xy_lower_base", "top", (-half, half),
            solve=(("array", f"tip_{n}"), ("indenter", "contact")))
    b.mate("xy_upper_base", "bottom", "xy_lower_table", "top_rot")
    b.slide("stage_y", "xy_upper_table", "bottom", "xy_upper_base", "top", (-half, half),
            solve=(("array", f"tip_{n}"), ("indenter", "contact")))
    b.bracket("xy_upper_table", "top_rot_neg")  # array towards the column, stages clear of it
    b.z_axis_and_gauge(("array", f"tip_{n}"))
    return b.model("calibration", ["stage_mount", "stage_x", "stage_y", "z_mount"],
                   {"tips": "array", "indenter": ("indenter", f"element_{n}")})


def _sample_model(plan: Plan, rigs: RigDesign, scene: SceneSpec | None) -> RigModel:
    b = _Builder(plan, rigs)
    b.base_and_column()
    b.z_axis_and_gauge(("sample", "top"))
    b.cart(("indenter", "contact"), _sample_k(rigs, scene))
    return b.model("sample-stiffness", ["cart_roll", "z_mount"],
                   {"indenter": ("indenter", "sample"), "bearings": _wheels(), "base": "base_plate"})


def _evaluation_model(plan: Plan, rigs: RigDesign, scene: SceneSpec | None) -> RigModel:
    b = _Builder(plan, rigs)
    b.base_and_column()
    axis = rigs.library["linear_axis"]
    la = axis.geometry
    rail = b.leaf("rail", axis.name, "linear_axis")
    block = b.leaf("block", axis.companions[0].name, "linear_axis")
    b.mate(rail, "bottom", "column", "rail_seat")
    b.slide("block_travel", block, "rail_seat", rail, "top",
            (la.block_length_mm / 2, la.rail_length_mm - la.block_length_mm / 2),
            solve=(("array", "tips"), ("sample", "top")))
    b.leaf("axis_carrier", "axis_carrier", "carrier")
    b.mate("axis_carrier", "back", block, "top")
    b.leaf("hanger_bar", "hanger_bar", "hanger_bar")
    b.mate("hanger_bar", "top", "axis_carrier", "shelf_bottom")
    w = rigs.library["weights"].name
    below = ("axis_carrier", "shelf_top")
    for i in range(1, rigs.part("weights").count + 1):
        b.leaf(f"weight_{i}", w, "weights")
        b.mate(f"weight_{i}", "bottom", *below)
        below = (f"weight_{i}", "top")
    b.bracket("hanger_bar", "bottom")
    b.cart(("array", "tips"), _sample_k(rigs, scene))
    for s in plan.slots:
        b.touch(f"element_{s.number}", "sample")  # every tip rests on the sample
    return b.model("array-evaluation", ["cart_roll", "block_travel"],
                   {"tips": "array", "tips_on": "sample", "bearings": _wheels(), "base": "base_plate"},
                   empty_groups=() if rigs.part("weights").count else ("weights",))


def _wheels() -> list[str]:
    return [f"wheel_{wheel_tag(sx, sy)}" for sx in (-1, 1) for sy in (-1, 1)]


def rig_model(plan: Plan, rig: str, rigs: RigDesign | None = None,
              scene: SceneSpec | None = None) -> RigModel:
    """The kernel-free model (nodes, joints, contacts) of ``rig``.

    Args:
        rigs: the validated rigs (:attr:`Project.rigs <tactcad.design.project.Project>`);
            needed by every rig but ``wirecut`` and ``array``.

    Raises:
        SceneError: unknown rig, or a test rig asked without ``rigs``.
        DesignError: a scene option outside the rig file's values.
    """
    if rig == "wirecut":
        return _wirecut_model(plan)
    if rig == "array":
        return _array_model(plan)
    if rig == "grasper":
        return _grasper_model(plan, scene)
    if rigs is None and rig in RIGS:
        raise SceneError(f"rig {rig} needs the validated rigs of the project (rigs.toml)")
    if rig == "calibration":
        return _calibration_model(plan, rigs)
    if rig == "sample-stiffness":
        return _sample_model(plan, rigs, scene)
    if rig == "array-evaluation":
        return _evaluation_model(plan, rigs, scene)
    raise SceneError(f"unknown rig {rig!r}; rigs: {', '.join(RIGS)}")



def scene_names(project: Project) -> list[str]:
    """The project's scene names, in file order."""
    return list(project.scenes)


def get_scene_spec(project: Project, name: str) -> SceneSpec:
    """The scene ``name`` of the project's scenes.

    Raises:
        SceneError: unknown name; the message lists the scenes and their groups.
    """
    scenes = project.scenes
    if name not in scenes:
        lines = [f"  {s.name:<22} ({s.rig}): {', '.join(s.groups)}" for s in scenes.values()]
        raise SceneError(f"unknown scene {name!r}; scenes:\n" + "\n".join(lines))
    return scenes[name]


def scene_model(plan: Plan, spec: SceneSpec, rigs: RigDesign | None = None) -> RigModel:
    """The rig model of a scene, with its groups checked against the rig.

    Raises:
        SceneError: the scene names a group its rig does not have.
    """
    model = rig_model(plan, spec.rig, rigs, spec)
    groups = model.groups()
    unknown = [g for g in spec.groups if g not in groups]
    if unknown:
        raise SceneError(f"scene {spec.name}: unknown group(s) {', '.join(unknown)}; rig "
                         f"{spec.rig} has groups {', '.join(groups)}")
    return model


def shown_instances(model: RigModel, spec: SceneSpec) -> list[tuple[str, str, str]]:
    """(instance, part, group) of every instance the scene shows, in rig order."""
    shown = set(spec.groups)
    return [i for i in model.instances() if i[2] in shown]


def scene_summaries(project: Project) -> list[dict]:
    """Every scene: name, rig, description, parts placed and, per group, each
    part with its quantity and level of detail. Needs no CAD kernel."""
    out = []
    for spec in project.scenes.values():
        model = scene_model(project.plan, spec, project.rigs)
        groups = model.groups()
        listed = {}
        for g in spec.groups:
            counts: dict[str, int] = {}
            for _, part in groups[g]:
                counts[part] = counts.get(part, 0) + 1
            listed[g] = [{"part": p, "quantity": c, "detail": spec.detail[model.specs[p].kind]}
                         for p, c in counts.items()]
        out.append({"name": spec.name, "rig": spec.rig, "description": spec.description,
                    "parts_placed": sum(len(groups[g]) for g in spec.groups), "groups": listed})
    return out


def describe(project: Project) -> list[str]:
    """Lines listing every scene, its groups and parts (name x quantity, level).
    Needs no CAD kernel."""
    lines = []
    for scene in scene_summaries(project):
        lines.append(f"{scene['name']}  [{scene['rig']}]  {scene['parts_placed']} parts placed - "
                     f"{scene['description']}")
        for g, items in scene["groups"].items():
            lines.append(f"    {g}: " + ", ".join(f"{i['part']} x{i['quantity']} ({i['detail']})"
                                                 for i in items))
    return lines
