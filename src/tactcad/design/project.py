"""The three design files validated together, before any geometry is built.

A design file (``macro_array.toml``) comes with a rigs file and a scenes file,
its companions: those its ``[files]`` table names, relative to its folder,
else ``rigs.toml`` and ``scenes.toml`` beside it (:func:`companion_files`).
Nothing outside the design's folder is read. A design with neither is
refused, unless the caller hands a ``companions`` maker that writes them for
the plan (the command line and :func:`tactcad.load` do). :func:`load_project`
reads all three, checks each with its schema and the files against each other
(the rigs against the array's size, every scene's sample stiffness against the
rigs' samples) and reports every refusal at once, each as
``file: field = value: allowed ... (reason)``.

What it returns, a :class:`Project`, is what the rest of the run works from:
one immutable object carried from validation to the last writer. Nothing
below the command line opens a design, rigs or scenes file again, so a file
edited after validation cannot change what a run writes.
"""

from __future__ import annotations

import errno
from dataclasses import dataclass, replace
from pathlib import Path
from string import Template
from typing import Any, Callable, Iterable, Iterator, Mapping

from tactcad.design.array_plan import (DEFAULT_DESIGN, Plan, plan_from_model,
                                       rigs_bracket_ear, stacked_columns_error,
                                       stated_ear_mm, validate_design)
from tactcad.design.construction_registry import construction_of
from tactcad.design.rig_plan import DEFAULT_RIGS, RigDesign, validate_rigs
from tactcad.vocabulary.schema import Problems, content_hash, fmt, read_toml, unprintable
from tactcad.design.scene_specs import DEFAULT_SCENES, SceneSpec, validate_scenes
from tactcad.errors import DesignError

#: The companion files of a design, with the name each has when ``[files]`` leaves it out.
COMPANIONS = {"rigs": "rigs.toml", "scenes": "scenes.toml"}

#: Why a project has no test rigs (the manifest and the checks state it).
NO_TEST_RIGS = ("no test rigs: the construction {construction} has no mount for the rigs' "
                "bracket, and the design has no rigs file")


def has_test_rigs(project: "Project") -> bool:
    """True when the project has test rigs (its rigs file was validated)."""
    return project.rigs is not None


def no_test_rigs_reason(project: "Project") -> str:
    """Why ``project`` has no test rigs (one sentence naming its construction)."""
    return NO_TEST_RIGS.format(construction=project.plan.construction)
#: Makes the companions' raw tables for a plan that has none: kind -> tables.
CompanionMaker = Callable[[Plan], Mapping[str, Mapping[str, Any]]]


class FrozenScenes(Mapping[str, SceneSpec]):
    """The validated scenes by name, in file order; read-only."""

    def __init__(self, scenes: Mapping[str, SceneSpec]):
        self._items = tuple(scenes.items())

    def __getitem__(self, name: str) -> SceneSpec:
        for key, spec in self._items:
            if key == name:
                return spec
        raise KeyError(name)

    def __iter__(self) -> Iterator[str]:
        return (key for key, _ in self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __hash__(self) -> int:
        return hash(self._items)

    def __repr__(self) -> str:
        return f"FrozenScenes({', '.join(self)})"


@dataclass(frozen=True)
class Project:
    """The three design files validated together, immutable: what a run works from.

    Attributes:
        plan: the array's :class:`~tactcad.design.array_plan.Plan`.
        rigs: the rigs' :class:`~tactcad.design.rig_plan.RigDesign`, derived against ``plan``;
            None for a construction without a mount for the test rigs (its
            project has no test rigs: :data:`NO_TEST_RIGS` says why).
        scenes: the scenes by name (:class:`~tactcad.design.scene_specs.SceneSpec`), in file order.
        design_sha256, rigs_sha256, scenes_sha256: sha256 of each file's
            validated tables (canonical JSON; the design's after ``--set``), so
            a run can name exactly what it was made from.
        rigs_file, scenes_file: the paths the rigs and scenes were read from
            (the design's is ``plan.source``).
    """

    plan: Plan
    rigs: RigDesign | None
    scenes: Mapping[str, SceneSpec]
    design_sha256: str
    rigs_sha256: str
    scenes_sha256: str
    rigs_file: str = ""
    scenes_file: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.scenes, FrozenScenes):
            object.__setattr__(self, "scenes", FrozenScenes(self.scenes))

    @property
    def hashes(self) -> dict[str, str]:
        """{"design", "rigs", "scenes": sha256 of each file's validated tables}."""
        return {"design": self.design_sha256, "rigs": self.rigs_sha256,
                "scenes": self.scenes_sha256}


def project_of(plan: Plan, rigs: RigDesign | None, scenes: Mapping[str, SceneSpec],
               scenes_data: Mapping[str, Any] | None = None, scenes_file: str = "") -> Project:
    """A :class:`Project` of parts already validated (a plan, its rigs, scenes),
    e.g. a design made in code; ``scenes_data``: the scenes file's tables, for its hash."""
    scenes_hash = content_hash(scenes_data if scenes_data is not None
                               else {n: repr(s) for n, s in scenes.items()})
    if rigs is None:
        return Project(plan, None, scenes, plan.design_hash, "", scenes_hash, "", scenes_file)
    # the rigs' force gauge goes with the plan: every figure of its calibration reads it
    if plan.rigs_force_gauge != rigs.part("force_gauge"):
        plan = replace(plan, rigs_force_gauge=rigs.part("force_gauge"))
    return Project(plan, rigs, scenes, plan.design_hash, rigs.rigs_hash, scenes_hash,
                   rigs.source, scenes_file)


def _read(path: Path, what: str, problems: Problems) -> Mapping[str, Any] | None:
    try:
        return read_toml(path, what)
    except DesignError as exc:
        exc.file = path.name
        problems.extend([DesignError(exc.field, exc.value, exc.allowed, exc.why, path.name)])
        return None


def _rigs_ear_mm(rigs_file: Path | None) -> float | None:
    """The bracket ear (mm) the rigs file at ``rigs_file`` states
    (:func:`~tactcad.design.array_plan.stated_ear_mm`), read before the design is
    validated; None when there is no file or it states none (its own refusal comes when
    the rigs are validated)."""
    if rigs_file is None:
        return None
    return stated_ear_mm(_read(rigs_file, "rigs file", Problems(rigs_file.name)))


def _check_sample_stiffness(scenes: Mapping[str, SceneSpec], rigs: RigDesign,
                            problems: Problems, scenes_file: str) -> None:
    known = rigs.sample_stiffness_N_per_mm
    for s in scenes.values():
        k = s.sample_stiffness_N_per_mm
        if k is not None and k not in known:
            problems.add(f"scene.{s.name}.sample_stiffness_N_per_mm", k,
                         "one of " + ", ".join(fmt(v) for v in known),
                         "the measured samples of the rigs file (sample.stiffness_N_per_mm)",
                         file=scenes_file)


#: The words a scene's ``description`` may hold (``$grid``), filled from the design
#: (and its rigs) each time the project is read, so a description that counts or
#: names the design's parts follows every edit of it.
SCENE_WORDS = {"name": "the design's name", "grid": "the array's rows x columns (2 x 3)",
               "n_elements": "the number of elements", "n_spacers": "the number of spacers"}
#: The words only a project with test rigs has (its rigs file gives them).
RIG_SCENE_WORDS = {"gauge_model": "the rigs' force gauge model",
                   "indenter": "the indenter's contact face, width x depth in mm (2 x 3)"}


def scene_words(plan: Plan, rigs: RigDesign | None) -> dict[str, str]:
    """The value of every word of :data:`SCENE_WORDS` (and of :data:`RIG_SCENE_WORDS`
    where the project has test rigs) for ``plan`` and its ``rigs``.

    Returns:
        word -> text (counts as digits, sizes in mm).
    """
    words = {"name": plan.name, "grid": f"{plan.rows} x {plan.columns}",
             "n_elements": f"{len(plan.slots)}", "n_spacers": f"{len(plan.spacer_placements)}"}
    if rigs is None:
        return words
    tip = rigs.part("indenter")
    return words | {"gauge_model": rigs.part("force_gauge").model,
                    "indenter": f"{tip.contact_width_mm:g} x {tip.contact_depth_mm:g}"}


def _worded_scenes(scenes: Mapping[str, SceneSpec], words: Mapping[str, str],
                   problems: Problems, scenes_file: str) -> dict[str, SceneSpec]:
    """The scenes with the words of their descriptions filled in (``$$`` is a ``$``);
    a word that is not one of ``words`` is refused into ``problems``."""
    out = {}
    for name, spec in scenes.items():
        template = Template(spec.description)
        unknown = [w for w in template.get_identifiers() if w not in words]
        if unknown:
            problems.add(f"scene.{name}.description", "$" + unknown[0],
                         "words " + ", ".join("$" + w for w in words) + " (or $$ for a $)",
                         "a description's words are filled in from the design", file=scenes_file)
            out[name] = spec
            continue
        out[name] = replace(spec, description=template.safe_substitute(words))
    return out


def _check_scenes_without_rigs(scenes: Mapping[str, SceneSpec], plan: Plan, problems: Problems,
                               scenes_file: str) -> None:
    """Refuse a scene of a test rig in a project without test rigs."""
    from tactcad.design.scene_specs import RIGS_WITHOUT_TEST_RIGS

    for s in scenes.values():
        if s.rig not in RIGS_WITHOUT_TEST_RIGS:
            problems.add(f"scene.{s.name}.rig", s.rig, "one of " + ", ".join(
                RIGS_WITHOUT_TEST_RIGS), NO_TEST_RIGS.format(construction=plan.construction),
                file=scenes_file)


def _plan_of(design: Mapping[str, Any] | None, source: str, problems: Problems,
             set_keys: Iterable[str] = ()) -> Plan | None:
    if design is None:
        return None
    from tactcad.design.construction_registry import warn_jaw_not_judged
    from tactcad.partlib.tissue_slab import stated_grasper_errors

    model, found = validate_design(design, Path(source).name)
    too_few = stacked_columns_error(design, Path(source).name)  # a row must hold a pair
    problems.extend([too_few, *found.errors] if too_few else found.errors)
    if found or too_few:
        return None
    plan = plan_from_model(model, design, source)
    # the jaw the design states takes its insert (the rules its part applies), refused here
    # rather than first by the command that builds it
    problems.extend(stated_grasper_errors(plan, Path(source).name, tuple(set_keys)))
    warn_jaw_not_judged(plan, Path(source).name)  # a jaw a stacked array passes over, said
    return plan


def _companions_of(plan: Plan | None, rigs: Mapping[str, Any] | None,
                   scenes: Mapping[str, Any] | None, problems: Problems, rigs_file: str,
                   scenes_file: str) -> tuple[RigDesign | None, dict[str, SceneSpec]]:
    rig_design = None
    if rigs is not None and plan is not None:
        rig_design, found = validate_rigs(rigs, plan, rigs_file)
        problems.extend(found.errors)
    specs: dict[str, SceneSpec] = {}
    if scenes is not None:
        specs, found = validate_scenes(scenes, scenes_file)
        problems.extend(found.errors)
    if rig_design is not None and specs:
        _check_sample_stiffness(specs, rig_design, problems, scenes_file)
    # a project whose rigs were refused has no rig words: its scenes wait for the rigs
    if plan is not None and (rig_design is not None or not construction_of(plan).test_rigs):
        specs = _worded_scenes(specs, scene_words(plan, rig_design), problems, scenes_file)
    if rigs is None and plan is not None and not construction_of(plan).test_rigs:
        _check_scenes_without_rigs(specs, plan, problems, scenes_file)
    return rig_design, specs


def project_from_data(design: Mapping[str, Any] | None, rigs: Mapping[str, Any] | None,
                      scenes: Mapping[str, Any] | None, problems: Problems, *,
                      source: str = "<dict>", rigs_file: str = "rigs.toml",
                      scenes_file: str = "scenes.toml"):
    """Validate the three files' raw tables together (a table that could not be
    read is None; its error is already in ``problems``).

    Returns:
        (plan, rigs, scenes), any of them None when refused; every refusal is
        added to ``problems``.
    """
    with rigs_bracket_ear(stated_ear_mm(rigs)):  # a clamp's offers clamp these rigs' ear
        plan = _plan_of(design, source, problems)
    return (plan, *_companions_of(plan, rigs, scenes, problems, rigs_file, scenes_file))


def _is_file(path: Path) -> bool:
    try:
        return path.is_file()
    except OSError:  # a name too long for the file system, say
        return False


def _loops(path: Path) -> bool:
    """True when following ``path``'s symbolic links never ends (ELOOP)."""
    try:
        path.stat()
    except OSError as exc:
        return exc.errno == errno.ELOOP
    return False


def _inside(folder: Path, name: str) -> bool:
    """True when ``name`` is a relative path that stays inside ``folder``."""
    rel = Path(name)
    if rel.is_absolute() or ".." in rel.parts or not rel.parts:
        return False
    try:
        return (folder / rel).resolve().is_relative_to(folder.resolve())
    except (OSError, ValueError, RuntimeError):  # a name the file system cannot hold; a link loop
        return False


def _refusal(folder: Path, name: str, kind: str, design_name: str) -> tuple[str, str] | None:
    """(allowed, why) when ``name``, a companion's name in the design's
    ``[files]`` table, cannot be read as its ``kind`` file; None when it can."""
    if _loops(folder / name):  # before resolving: Python 3.11's resolve raises on a loop
        return (f"an existing {kind} file in the design file's folder",
                f"{name} is a symbolic link loop")
    if not _inside(folder, name):
        return ("a relative path inside the design file's folder",
                "a sensor project reads no file outside its folder")
    if not _is_file(folder / name):
        return (f"an existing {kind} file in the design file's folder",
                f"no file {name} beside {design_name}")
    return None


def _named(design: Mapping[str, Any] | None) -> dict[str, Any]:
    """kind -> what the design's ``[files]`` table gives for it (None when nothing)."""
    table = design.get("files") if isinstance(design, Mapping) else None
    return {kind: table.get(kind) if isinstance(table, Mapping) else None for kind in COMPANIONS}


def companion_paths(design_file: Path, design: Mapping[str, Any] | None) -> dict[str, Path]:
    """kind -> where the design's rigs and scenes files are to be: the path its
    ``[files]`` table names (relative to its folder), else the default name
    beside it; neither checked nor read (see :func:`companion_files`)."""
    return {kind: design_file.parent / (name if isinstance(name, str) and name
                                         else COMPANIONS[kind])
            for kind, name in _named(design).items()}


def companion_files(design_file: Path, design: Mapping[str, Any] | None,
                    problems: Problems) -> dict[str, Path | None]:
    """The rigs and scenes files of the design file at ``design_file``: the
    ones its ``[files]`` table names (relative to its folder), else
    ``rigs.toml`` and ``scenes.toml`` beside it.

    Returns:
        kind ("rigs", "scenes") -> the file, or None where the design names
        none and none lies beside it (or the name it gives was refused).
        A named file that is absolute, leaves the design's folder or does not
        exist is refused into ``problems`` (``files.rigs = ...: allowed ...``).
    """
    folder = design_file.parent
    out: dict[str, Path | None] = {}
    for kind, name in _named(design).items():
        if name is None:
            beside = folder / COMPANIONS[kind]
            if design_file.name and _loops(beside):
                problems.add(f"files.{kind}", COMPANIONS[kind], f"a {kind} file, or none, beside "
                             f"{design_file.name}", f"{COMPANIONS[kind]} is a symbolic link loop")
            out[kind] = beside if design_file.name and _is_file(beside) else None
            continue
        out[kind] = None
        if not isinstance(name, str) or not name or unprintable(name) is not None:
            continue  # a wrong type, or characters that do not print: the schema says so
        refused = _refusal(folder, name, kind, design_file.name)
        if refused is not None:
            problems.add(f"files.{kind}", name, *refused)
        else:
            out[kind] = folder / name
    return out


def load_project(design: str | Path | None = None) -> Project:
    """Read and validate a design file with its rigs and scenes files.

    Args:
        design: TOML design file; ``None`` means ``hardware/macro_array.toml``.

    Returns:
        The :class:`Project`: the array's plan, the rig plan derived against
        it, the scenes by name and the three files' hashes.

    Raises:
        DesignErrors: every refusal of the three files (``.errors``), each naming
            its file, field, value and allowed range; nothing is built.
    """
    path = Path(design) if design is not None else DEFAULT_DESIGN
    problems = Problems(path.name)
    return project_with_design_data(_read(path, "design file", problems), path, problems)


def project_with_design_data(data: Mapping[str, Any] | None, path: Path,
                             problems: Problems | None = None,
                             companions: CompanionMaker | None = None,
                             set_keys: Iterable[str] = ()) -> Project:
    """:func:`load_project` for design tables already read (and perhaps
    changed, e.g. by ``--set``) from the design file at ``path``: its rigs and
    scenes files (:func:`companion_files`) are read and every file is
    validated together.

    Args:
        companions: makes the raw tables of a companion the design has no file
            for, from its plan (e.g. :func:`tactcad.project_folder.companion_tables`);
            None refuses such a design, naming the file it lacks.
        set_keys: the dotted keys ``data`` takes from elsewhere than the file (``--set``):
            a rule between keys of the grasper's jaw names the one set
            (:func:`tactcad.partlib.tissue_slab.stated_grasper_errors`).

    Raises:
        DesignErrors: as :func:`load_project`.
    """
    problems = problems if problems is not None else Problems(path.name)
    files = companion_files(path, data, problems)
    named = _named(data)
    with rigs_bracket_ear(_rigs_ear_mm(files["rigs"])):  # a clamp's offers clamp its ear
        plan = _plan_of(data, str(path), problems, set_keys)
    if plan is not None and not construction_of(plan).test_rigs and named["rigs"] is None:
        # nothing to hold them: a rigs.toml that only lies beside it (another
        # design's, in a shared folder) is not this project's
        files["rigs"] = None
    tables = {kind: _read(f, f"{kind} file", problems) if f is not None else None
              for kind, f in files.items()}
    labels = {kind: f.name if f is not None else f"{COMPANIONS[kind]} (made for {path.name})"
              for kind, f in files.items()}
    absent = [k for k, f in files.items() if f is None and named[k] is None]
    if plan is not None and "rigs" in absent and not construction_of(plan).test_rigs:
        absent.remove("rigs")  # nothing to hold it: the project has no test rigs
    if absent and plan is not None:
        if companions is None:
            for kind in absent:
                problems.add(f"files.{kind}", None, f"a {kind} file: {COMPANIONS[kind]} beside "
                             f"{path.name}, or one named in its [files] table",
                             "`tactcad new DIR --from-design` writes them")
        else:
            made = companions(plan)
            tables.update({kind: made[kind] for kind in absent})
    rigs, scenes = _companions_of(plan, tables["rigs"], tables["scenes"], problems,
                                  labels["rigs"], labels["scenes"])
    problems.raise_if_any()
    return project_of(plan, replace(rigs, source=labels["rigs"]) if rigs is not None else None,
                      scenes, tables["scenes"], labels["scenes"])


def project_for_plan(plan: Plan, rigs_file: str | Path | None = None,
                     scenes_file: str | Path | None = None) -> Project:
    """A :class:`Project` of a plan made in code (e.g. ``plan_from_dict``):
    the rigs and scenes files named (``None``: those of the default design,
    the shipped paper example) are read and validated against ``plan``.

    Raises:
        DesignErrors: every refusal of the rigs and scenes files.
    """
    rigs_path = Path(rigs_file) if rigs_file is not None else DEFAULT_RIGS
    scenes_path = Path(scenes_file) if scenes_file is not None else DEFAULT_SCENES
    problems = Problems(rigs_path.name)
    rigs_data = _read(rigs_path, "rigs file", problems)
    scenes_data = _read(scenes_path, "scenes file", problems)
    rigs, scenes = _companions_of(plan, rigs_data, scenes_data, problems, rigs_path.name,
                                  scenes_path.name)
    problems.raise_if_any()
    return project_of(plan, replace(rigs, source=rigs_path.name), scenes, scenes_data,
                      scenes_path.name)
