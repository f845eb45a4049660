"""tactcad's public Python API: a design file in, parts, assemblies,
stiffness, strength, exports and checks out.

    >>> import tactcad
    >>> project = tactcad.load(set={"element.web_thickness_mm": 0.3})
    >>> project.element(8).stiffness().stiffness_N_per_mm  # doctest: +SKIP
    39.4...

Everything here is validated exactly as the command line validates it (the
CLI's commands call these functions), and refusals raise
:class:`~tactcad.errors.DesignErrors` whose ``.errors`` lists every one, each
naming file, field, value and allowed range. Importing this module loads
neither the CAD kernel nor a FEM library: solids are built on first use
(:attr:`Project.parts`), each distinct part once per :class:`Project`.

Units: mm, N, MPa, N/mm, s.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from contextvars import ContextVar
from dataclasses import dataclass, replace
from functools import cached_property
from os import PathLike
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Iterator, Sequence, TypeVar, cast

if TYPE_CHECKING:  # types only: importing them at run time would load the kernel
    from tactcad.checks.check_result import CheckResult
    from tactcad.design.array_plan import ElementGeometry, ElementSlot, Plan
    from tactcad.design.project import Project as ValidatedProject
    from tactcad.design.rig_plan import RigDesign
    from tactcad.design.scene_specs import SceneSpec
    from tactcad.kernel.shapes import Compound, Solid
    from tactcad.export.run import ExportResult
    from tactcad.mechanics.stiffness_result import StiffnessResult
    from tactcad.mechanics.modal_result import ModalResult
    from tactcad.mechanics.element_strength import StrengthRecord

__all__ = ["load", "load_die", "Project", "DieProject", "Element", "CheckReport"]

Progress = Callable[[str], None]
#: An API method (:func:`keyword_errors` keeps its signature for a type checker).
Method = TypeVar("Method", bound=Callable[..., Any])


def _quiet(line: str) -> None:
    """Progress sink that prints nothing."""


def plain(value: Any) -> Any:
    """An API result as plain Python: every NumPy scalar its Python number or bool, every
    array a list, walked through dicts, lists and tuples; so ``json.dumps`` takes what the
    command prints with ``--json``, the same numbers.

    Args:
        value: a result (dicts, lists, tuples, numbers, NumPy values, text, None).

    Returns:
        The same structure with no NumPy type left, every infinite or NaN number None and
        every tuple a list, as the command's JSON writes them (a named tuple and other
        objects, such as a dataclass, as they are).
    """
    import math

    import numpy as np

    if isinstance(value, Mapping):
        return {plain(k): plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [plain(v) for v in value]
    if type(value) is tuple:  # as JSON writes it; a named tuple is left as it is
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, np.generic):
        return plain(value.item())
    if isinstance(value, float) and not math.isfinite(value):
        return None  # as the command's --json writes it (JSON has no inf or NaN)
    return value


def option_name(keyword: str) -> str:
    """The command-line option a keyword argument answers to (``force_N`` -> ``--force-N``)."""
    return "--" + keyword.replace("_", "-")


def with_keyword_names(exc: Exception, keywords: Iterable[str]) -> Exception:
    """``exc`` with each command-line option that answers to one of ``keywords``
    (:func:`option_name`) named as that keyword argument: the field ``--force-N`` as
    ``force_N``, ``--force-N 0.5`` in a text as ``force_N=0.5``; a refusal raised through a
    command's code, read in the API.

    Args:
        exc: the refusal (a :class:`~tactcad.errors.DesignError`, its list
            :class:`~tactcad.errors.DesignErrors`, or another error of one message).
        keywords: the keyword arguments of the API call.

    Returns:
        The refusal renamed (``exc`` itself where no option of the call is named).
    """
    import re

    from tactcad.errors import DesignError, DesignErrors

    options = {option_name(k): k for k in keywords}
    if not options:
        return exc
    # an option, then its value where one follows (a number, quoted text or a path)
    pattern = re.compile(r"(?<![\w-])(" + "|".join(map(re.escape, sorted(options, key=len,
                                                                          reverse=True)))
                         + r")(?![\w-])(?: (?=[-+\d.'\"/~]|\S*/))?")

    def text(words: Any) -> Any:
        return pattern.sub(lambda m: options[m.group(1)] + "=", words) \
            if isinstance(words, str) else words

    def named(e: DesignError) -> bool:
        words = [e.field, e.allowed, e.why, *(v for a in e.alternatives for v in a.values())]
        return any(isinstance(w, str) and pattern.search(w) for w in words)

    def error(e: DesignError) -> DesignError:
        if not named(e):
            return e
        alternatives = [{k: text(v) for k, v in a.items()} for a in e.alternatives]
        return DesignError(options.get(e.field, text(e.field)), e.value, text(e.allowed),
                           text(e.why), e.file, alternatives=alternatives)

    if isinstance(exc, DesignErrors):
        return DesignErrors([error(e) for e in exc.errors]) if any(map(named, exc.errors)) \
            else exc
    if isinstance(exc, DesignError):
        return error(exc)
    if len(exc.args) == 1 and isinstance(exc.args[0], str) and pattern.search(exc.args[0]):
        return type(exc)(text(exc.args[0]))
    return exc


#: Set while an API method runs: a method it calls leaves the warnings to it, so one call
#: gives one record of them.
_API_CALL: "ContextVar[bool]" = ContextVar("tactcad_api_call", default=False)


def with_warnings(result: Any, said: Sequence[str]) -> tuple[Any, list[str]]:
    """``result`` with the warnings ``said`` during its call joined to its own, each once:
    a dict's ``warnings`` list (made where it has none, empty where none was said, as
    ``--json`` adds it to the command's object), a dataclass's ``warnings`` field.

    Args:
        result: an API method's plain result.
        said: the call's warnings, one line each (alike ones folded, as a command says them).

    Returns:
        (the result with its warnings, the lines it has no place for).
    """
    import dataclasses

    if isinstance(result, dict):
        own = result.get("warnings", [])
        if isinstance(own, list):
            return {**result, "warnings": own + [w for w in said if w not in own]}, []
    if not said:
        return result, []
    if dataclasses.is_dataclass(result) and not isinstance(result, type):
        field = {f.name: f for f in dataclasses.fields(result)}.get("warnings")
        own = getattr(result, "warnings", None)
        if field is not None and field.init and isinstance(own, (tuple, list)):
            joined = [*own, *(w for w in said if w not in own)]
            return replace(result, warnings=type(own)(joined)), []
    return result, list(said)


def plain_warning(text: str, category: type[Warning]) -> Warning:
    """A warning of ``category`` that says ``text`` (a ``UserWarning`` where the category
    takes no text alone)."""
    try:
        return category(text)
    except Exception:  # a library's category may want more than a message
        return UserWarning(text)


def keyword_errors(method: Method) -> Method:
    """An API method whose refusals name its keyword arguments, not the command-line
    options its work shares with a command (:func:`with_keyword_names`), whose result
    is plain Python (:func:`plain`), and whose warnings are the result's, as a command's
    ``--json`` gives them: each warning the work issues is said once, alike ones folded
    into one line (:class:`tactcad.commands.notices.WarningLines`), and joined to the
    result's ``warnings`` (:func:`with_warnings`); a result with no place for them (a
    stiffness, an export) has each line issued once as a warning of the caller's line.
    None reaches the console with tactcad's own file and source line.

    Args:
        method: the method; its parameters are the keyword arguments named.

    Returns:
        The method wrapped, its signature kept.

    Raises:
        TactcadError: the method's refusal, renamed where it names an option of the call.
    """
    import functools
    import inspect
    import warnings

    from tactcad.commands.notices import WarningLines
    from tactcad.errors import COMMAND_LINE_RUN, TactcadError

    keywords = [k for k in inspect.signature(method).parameters if k != "self"]

    def answered(*args: Any, **kwargs: Any) -> Any:
        try:
            return plain(method(*args, **kwargs))
        except TactcadError as exc:
            if COMMAND_LINE_RUN.get():  # a command's refusal names its options
                raise
            renamed = with_keyword_names(exc, keywords)
            if renamed is exc:
                raise
            raise renamed from None

    @functools.wraps(method)
    def called(*args: Any, **kwargs: Any) -> Any:
        if COMMAND_LINE_RUN.get() or _API_CALL.get():  # the command or the outer call says them
            return answered(*args, **kwargs)
        notes = WarningLines(echo=False)
        running = _API_CALL.set(True)
        try:
            with notes.capture():
                result = answered(*args, **kwargs)
        except BaseException:
            # a refusal after warnings: they are said before it, as a command says them
            for text in notes.lines:
                warnings.warn(plain_warning(text, notes.categories[text]), stacklevel=2)
            raise
        finally:
            _API_CALL.reset(running)
        result, left = with_warnings(result, notes.lines)
        for text in left:
            warnings.warn(plain_warning(text, notes.categories[text]), stacklevel=2)
        return result

    return cast(Method, called)


def array_keywords(name: str) -> dict[str, Any]:
    """The keyword arguments the metal array's :class:`Project` method ``name`` takes, each
    with its default (none where the array has no such method)."""
    import inspect

    method = getattr(Project, name, None)
    if method is None:
        return {}
    return {k: p.default for k, p in inspect.signature(method).parameters.items()
            if k != "self"}


def _is_default(value: Any, default: Any) -> bool:
    """``value`` is the array keyword's default (as the command takes an option left at its
    default on a die's file: not given)."""
    try:
        return value is default or bool(value == default)
    except (TypeError, ValueError):  # an array's == answers elementwise
        return False


def refuses_array_keywords(method: Method) -> Method:
    """A :class:`DieProject` method that refuses, by name, a keyword argument the array's
    method of the same name takes and the die's does not (``tolerance(arm_tol=...)``: a die
    has no arms), as ``tactcad tolerance --arm-tol`` on a die's file refuses the option,
    rather than Python's bare "unexpected keyword argument"; one given at the array's
    default is taken as not given, as the command takes an option left at its default.

    Args:
        method: the die's method; its parameters are the keywords it takes.

    Returns:
        The method wrapped, its signature kept.

    Raises:
        DesignError: an array's keyword, naming it, its value and the die's keywords.
    """
    import functools
    import inspect

    own = [k for k in inspect.signature(method).parameters if k != "self"]

    @functools.wraps(method)
    def called(self: "DieProject", *args: Any, **kwargs: Any) -> Any:
        from tactcad.errors import DesignError

        array = array_keywords(method.__name__)
        array_only = [k for k in kwargs if k not in own and k in array]
        refused = [k for k in array_only if not _is_default(kwargs[k], array[k])]
        if refused:
            keyword = refused[0]
            takes = ", ".join(own) if own else "no keyword"
            raise DesignError(keyword, kwargs[keyword],
                              f"no value for a die's design ({self.source.name}); a die's "
                              f"{method.__name__}() takes {takes}",
                              f"{keyword} chooses among a metal array's figures; a silicon "
                              "die has its own")
        return method(self, *args, **{k: v for k, v in kwargs.items() if k not in array_only})

    return cast(Method, called)


def load(path: str | Path | None = None, set: Mapping[str, Any] | None = None) -> "Project":
    """Read and validate a design file with its rigs and scenes files (those its
    ``[files]`` table names, else ``rigs.toml`` and ``scenes.toml`` beside it;
    where it has none, ones made for it: samples over its own K_obj range). Another
    product's design file (a silicon die's ``[die]`` file) gives that product's object
    (:class:`DieProject`), through its registry entry (:mod:`tactcad.products`).

    Args:
        path: TOML design file, or a project folder holding one design file;
            ``None`` means the one design file of the working folder (a project
            folder), else the shipped example ``macro_array`` (the paper's 2 x 5 array).
        set: design values to override, by dotted key of the design file,
            e.g. ``{"element.web_thickness_mm": 0.3}`` (mm) or
            ``{"arms.lengths_mm": [4, 5, 6, 7, 8, 4, 5, 6, 7, 8]}``; checked
            like the file (the CLI's ``--set``).

    Returns:
        The validated :class:`Project`; no geometry is built yet. A die's design file gives
        its :class:`DieProject` (typed as the array's :class:`Project` here, which most
        scripts load: a typed script that loads a die calls :func:`load_die`).

    Raises:
        DesignErrors: every refusal of the three files at once (``.errors``),
            an unknown ``set`` key included; nothing is built.
        DesignError: an unreadable file, a ``path`` that is no path, a folder with no
            design file or several, or a ``set`` key that is not ``section.key``.
    """
    from tactcad.design.array_plan import with_overrides
    from tactcad.design.file_kind import read_array_tables
    from tactcad.errors import DesignError
    from tactcad.project_folder import product_of
    from tactcad.project_folder import default_design

    if path is not None and not isinstance(path, (str, PathLike)):
        raise DesignError("path", path, "a design file's path (str or pathlib.Path) or None")
    design = Path(path) if path is not None else default_design()
    if design.is_dir():  # a project folder: its one design file
        from tactcad.project_folder import design_in_folder

        design = design_in_folder(design, "path")
    overrides = _checked_overrides(set)
    product = product_of(design)
    if not product.is_default:  # another product's object (a die's DieProject)
        loaded: Any = product.hook("load")(design, overrides)
        return loaded
    data = with_overrides(read_array_tables(design), overrides)
    return Project(_validated(data, design, overrides), data, design)


def _validated(data: Mapping[str, Any], design: Path,
               overrides: Iterable[str] = ()) -> "ValidatedProject":
    """The design tables with their rigs and scenes validated together; a
    design with no rigs or scenes file gets ones made for it. A refused value
    of a key in ``overrides`` (``set``) is named as set, not as the file's."""
    from tactcad.design.project import project_with_design_data
    from tactcad.errors import DesignErrors
    from tactcad.project_folder import companion_tables

    try:
        validated = project_with_design_data(data, design, companions=companion_tables,
                                             set_keys=tuple(overrides))
        check_references_stiffer(validated.plan)
        return validated
    except DesignErrors as exc:
        raise exc.sourced({key: "set" for key in overrides}) from None


def check_references_stiffer(plan: "Plan") -> None:
    """Refuse a design whose reference is not stiffer than the elements read against it
    (:func:`tactcad.mechanics.readout_chain.soft_reference_errors`, K at the closed form:
    a few milliseconds): it cannot read K_obj. A named reference softer than one of its
    elements, or a row whose stiffest element (its reference, none named) has a twin.

    Warns nothing: K only orders the elements here, and the reports that give K and the
    gauge strain say where their fits are left.

    Raises:
        DesignErrors: one refusal per such reference, naming the stiffnesses and the rule.
    """
    import warnings

    from tactcad.errors import DesignErrors
    from tactcad.mechanics.evaluation import ladder_stiffness_by_element
    from tactcad.mechanics.readout_chain import soft_reference_errors

    with warnings.catch_warnings():  # a fit left by a few % orders no reference differently
        warnings.simplefilter("ignore")
        stiffness = ladder_stiffness_by_element(plan)
    errors = soft_reference_errors(plan, stiffness)
    if errors:
        raise DesignErrors(errors)


def _checked_overrides(values: Mapping[str, Any] | None) -> dict[str, Any]:
    """``set`` as a dict, every key ``section.key`` (the design validator judges the rest)."""
    from tactcad.errors import DesignError

    if values is None:
        return {}
    if not isinstance(values, Mapping):
        raise DesignError("set", values, "a mapping of dotted design keys to values, "
                                         "e.g. {'element.web_thickness_mm': 0.3}")
    for key in values:
        section, dot, name = key.partition(".") if isinstance(key, str) else ("", "", "")
        if not (section and dot and name):
            raise DesignError("set", key, "a dotted key of the design file, "
                                          "e.g. 'element.web_thickness_mm'")
    return dict(values)


class Project:
    """A validated design with its rigs and scenes, and everything made from it.

    Build with :func:`load`. The validated data are immutable; solids are
    built on first use and kept (one build per distinct part).

    Attributes:
        validated: the validated design files, one immutable
            :class:`tactcad.design.project.Project` (plan, rigs, scenes, hashes).
        source: the design file's path.
    """

    def __init__(self, validated: "ValidatedProject", data: Mapping[str, Any], source: Path):
        self.validated = validated
        self.source = Path(source)
        self._data = data
        self._report: Progress = _quiet  # where long part builds are reported

    # --- the validated files ---
    def _validated_field(self, name: str) -> Any:
        """One field of the validated :class:`tactcad.design.project.Project`."""
        return getattr(self.validated, name)

    @property
    def plan(self) -> "Plan":
        """The array's :class:`~tactcad.design.array_plan.Plan` (mm, N, MPa)."""
        return self._validated_field("plan")

    @property
    def rigs(self) -> "RigDesign":
        """The rig plan (:class:`~tactcad.design.rig_plan.RigDesign`) derived against the array."""
        return self._validated_field("rigs")

    @property
    def scenes(self) -> dict[str, "SceneSpec"]:
        """The scenes by name (:class:`~tactcad.design.scene_specs.SceneSpec`)."""
        return dict(self._validated_field("scenes"))

    @property
    def name(self) -> str:
        """The design's name (``[design] name``)."""
        return self.plan.name

    @property
    def design_hash(self) -> str:
        """sha256 of the design's content, as in the export's manifest."""
        return self.plan.design_hash

    def with_values(self, set: Mapping[str, Any]) -> "Project":
        """A new project: this design file with more values overridden.

        Args:
            set: as for :func:`load`; applied over this project's overrides.

        Raises:
            DesignErrors: as :func:`load`.
        """
        from tactcad.design.array_plan import with_overrides

        overrides = _checked_overrides(set)
        data = with_overrides(self._data, overrides)
        return Project(_validated(data, self.source, overrides), data, self.source)

    # --- solids ---
    @cached_property
    def _cache(self):
        """The project's part cache: each solid built once, a long build reported."""
        from tactcad.export.selection import ReportingParts

        return ReportingParts(self.plan, lambda line: self._report(line))

    @cached_property
    def _specs(self) -> dict:
        from tactcad.assembly.inventory import design_assemblies

        return design_assemblies(self.validated)[0]

    @property
    def parts(self) -> "Parts":
        """Every distinct part of the design (array and scenes) by name, as a
        read-only mapping of name -> build123d ``Solid`` (part frame, mm),
        each built on first access."""
        return Parts(self)

    @keyword_errors
    def assembly(self, scene: str = "array") -> "Compound":
        """A scene as one labelled build123d ``Compound`` (mm, the scene's frame).

        Each child is a placed copy of its part's solid, labelled with the
        instance name (``element_1``, ``spacer_1``, ``bolt_1`` ...) and
        coloured as in the STEP export; the compound is labelled ``scene``.

        Args:
            scene: a scene of the scenes file (``array``, ``wirecut``,
                ``calibration-rig`` ...; see :attr:`scenes`).

        Raises:
            SceneError: unknown scene (the message lists them).
        """
        from tactcad.assembly.scene_solver import build_scene
        from tactcad.kernel.objects import labelled_compound, rgb_colour
        from tactcad.kernel.locations import placed

        solved, solids = build_scene(self.validated, scene, self._cache)
        children = []
        for inst in solved.instances:
            child = placed(solids[inst.part], inst.location)
            child.label = inst.name
            child.color = rgb_colour(solved.specs[inst.part].color)
            children.append(child)
        return labelled_compound(children, scene)

    # --- elements ---
    def element(self, number: int) -> "Element":
        """Sensing element ``number`` (1-based, the design's numbering).

        Raises:
            DesignError: ``number`` not an integer (a bool, a float or a text is none),
                or no such element (the message gives the range).
        """
        return Element(self, self.plan.element(element_number(number, len(self.plan.slots))))

    @property
    def elements(self) -> list["Element"]:
        """Every sensing element, in order of number."""
        return [Element(self, slot) for slot in self.plan.slots]

    # --- files ---
    @keyword_errors
    def export(self, out: str | Path = "exports", only: Sequence[str] | str | None = None,
               part: Sequence[str] | str | None = None, cache: str | Path | None | bool = True,
               dxf_version: str | None = None,
               progress: Progress | None = None) -> "ExportResult":
        """Write the design's files (STEP, DXF, scenes, drawings, BOM, manifest) into ``out``.

        The files are written as one set (the folder is swapped in one
        step) and are the bytes ``tactcad export`` writes.

        Args:
            out: the export folder; refused if it is a system, home or
                working folder or holds files but no ``manifest.json``.
            only: kinds of file to write (``step``, ``dxf``, ``scenes``,
                ``review``, ``drawings``, ``images``, ``bom``); the manifest
                then says ``"partial"``.
            part: part names whose own files (STEP, drawing) to write.
            cache: the store of finished jobs: ``True`` the default
                ``.tactcad-cache`` of the working folder, a path, or
                ``False``/``None`` to build everything.
            dxf_version: ``"R2010"`` (default) or ``"R12"``.
            progress: called with one line per job run.

        Returns:
            :class:`~tactcad.export.run.ExportResult` (files with sha256,
            seconds, jobs run and reused, builds).

        Raises:
            DesignError: an unknown kind or part (the message lists the allowed ones).
            ExportPathError: ``out`` refused (see above).
            OSError: the files cannot be written; ``out`` is left as it was.
        """
        from tactcad.export.run import export
        from tactcad.export.kinds import parse_only
        from tactcad.export.selection import partial_record, select_jobs, with_progress

        kinds = parse_only([only] if isinstance(only, str) else only)
        names = [part] if isinstance(part, str) else list(part or ())
        report = progress or _quiet
        partial: dict[str, Any] | None = {} if kinds or names else None

        def select(jobs):
            chosen = select_jobs(jobs, kinds, names) if partial is not None else list(jobs)
            if partial is not None:
                partial.update(partial_record(kinds, names, chosen))
            return with_progress(chosen, report)

        self._report = report
        try:
            return export(self.validated, out, log=_quiet, store=_store(cache), parts=self._cache,
                          dxf_version=dxf_version, select=select, partial=partial)
        finally:
            self._report = _quiet

    @keyword_errors
    def readout(self, model: str = "closed-form") -> dict:
        """Every element's read-out chain, as ``tactcad readout --json`` gives it: gauge
        strain over the grid (1/N), K_v (V/N), K_v/K (V/mm), the force resolution (N)
        and the K_obj resolution (relative).

        Args:
            model: ladder level of K and the strain field (``closed-form``, ``beam``,
                ``fem2d``, ``fem3d``).

        Raises:
            UnknownModelError: ``model`` is not a ladder level.
        """
        from tactcad.paper.table1 import with_measured_sensitivities
        from tactcad.studies.project_reports import readout_record

        report = readout_record(self.plan, model, self._report)
        return with_measured_sensitivities(report, self.plan, model).as_json()

    @keyword_errors
    def thermal(self, model: str = "closed-form", element: int | None = None) -> dict:
        """Every element's (or one element's) zero and span drift per kelvin, self-heating
        offset and K_obj error per kelvin, as ``tactcad thermal --json`` gives them.

        Args:
            model: ladder level. element: one element's number (None: all).

        Raises:
            DesignError: ``element`` not an element of the design.
        """
        from tactcad.studies.project_reports import thermal_record

        if element is not None:
            element = element_number(element, len(self.plan.slots), "element")
        return thermal_record(self.plan, model, element).as_json()

    @keyword_errors
    def budget(self, model: str = "closed-form", force_N: float | None = None,
               delta_T_K: float | None = None, calibration: "str | PathLike | None" = None
               ) -> dict:
        """The K_obj error budget of every sensing unit and of the array, as
        ``tactcad budget --json`` gives it (relative errors, 1 sigma; N, K).

        Args:
            model: ladder level of K and the gauge strain. force_N: force on the reference
                at the reading (N; None: the design's full-scale force). delta_T_K:
                temperature step between tare and reading (K; None: the budget's default).
            calibration: a calibration data file (CSV, LVM or TDMS), as ``tactcad budget
                --calibration``: read and audited as ``tactcad calibrate --data`` does, its
                fitted standard errors taken, each flag of its audit in ``warnings``; None:
                the expected errors of the calibration ``calibrate`` drives.

        Raises:
            DesignError: ``force_N`` or ``delta_T_K`` out of range.
            CalibrationError: the calibration file cannot be read or fitted, or names an
                element the design does not have (named ``calibration``).
        """
        from tactcad.errors import DesignError
        from tactcad.paper.calibration_audit import budget_calibration
        from tactcad.studies.project_reports import budget_record

        # the options' own ranges (``budget --force-N``, ``--delta-T-K``), named as keywords
        for name, value, (lo, hi), lo_open in (("--force-N", force_N, (0.0, 1000.0), True),
                                               ("--delta-T-K", delta_T_K, (0.0, 100.0), False)):
            if value is None:
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not lo <= value <= hi or (lo_open and value <= lo):
                raise DesignError(name, value, f"{lo:g} {'<' if lo_open else '<='} value "
                                               f"<= {hi:g} ({'N' if lo_open else 'K'})")
        read = (budget_calibration(self.plan, calibration, model, "calibration")
                if calibration is not None else None)
        return budget_record(self.plan, model, force_N, delta_T_K, calibration=read)[0]

    @keyword_errors
    def strength(self, model: str = "closed-form",
                 cache: str | Path | None | bool = True) -> dict:
        """Every distinct element's peak stress per newton, yield-limited force and its
        stress, gauge strain and tip deflection at the rated full-scale force, and the
        rating judged against every element force limit, as ``tactcad strength --json``
        gives them (MPa, N, mm; ``requirement["verdict"]``: pass, fail or undecided, as
        verify's ``full_scale_force_N`` row).

        Args:
            model: a ladder level (``closed-form``, the default as the command's, ``beam``,
                ``fem2d``, ``fem3d``) or ``auto`` (the closed form, and for a rating it leaves
                undecided the level verify's climb decides it at,
                :func:`tactcad.studies.project_reports.strength_auto`).
            cache: the store that keeps FEM results under ``auto``, as for :meth:`verify`.

        Raises:
            UnknownModelError: ``model`` is neither ``auto`` nor a ladder level.
            DesignError: the material has no yield strength.
        """
        from tactcad.assembly.inventory import array_envelope_mm
        from tactcad.studies.project_reports import AUTO, strength_auto, strength_record

        from tactcad.store import keeping_results

        if model == AUTO:
            with keeping_results(_store(cache)):
                return strength_auto(self.plan, array_envelope_mm(self.plan))[0]
        return strength_record(self.plan, model)[0]

    @keyword_errors
    def modes(self, model: str = "closed-form", modes: int = 3, element: int | None = None,
              bare: bool = False, tip_mass_mg: float = 0.0) -> dict:
        """The lowest natural frequencies of every distinct element (or one), clamped as in
        the stiffness model, as ``tactcad modal --json`` gives them (Hz, g, mm, s).

        Args:
            model: modal level (``closed-form``, ``fem2d``, ``fem3d``). modes: modes per
                element, 1 ... 20 (FEM levels). element: one element's number (None: every
                distinct element). bare: leave out the gauge installation's mass.
            tip_mass_mg: a further mass at the contact centre, 0 ... 10000 mg.

        Raises:
            UnknownModalModelError: ``model`` is no modal level.
            DesignError: ``element``, ``modes`` or ``tip_mass_mg`` out of range.
        """
        import numbers

        import numpy as np

        from tactcad.errors import DesignError
        from tactcad.studies.project_reports import modes_record

        if element is not None:
            element = element_number(element, len(self.plan.slots), "element")
        if isinstance(modes, bool) or not isinstance(modes, numbers.Integral):
            raise DesignError("modes", modes, "a whole number 1 ... 20")
        if isinstance(tip_mass_mg, bool) or not isinstance(tip_mass_mg, numbers.Real) \
                or not 0.0 <= tip_mass_mg <= 10_000.0:  # NaN and a huge int fail here too
            raise DesignError("tip_mass_mg", tip_mass_mg, "a number 0 ... 10000 mg")
        if not isinstance(bare, (bool, np.bool_)):
            raise DesignError("bare", bare, "True or False")
        return modes_record(self.plan, model, int(modes), element, bool(bare),
                            float(tip_mass_mg))[0]

    @keyword_errors
    def crosstalk(self, model: str | None = None) -> dict:
        """The array's crosstalk, as ``tactcad crosstalk --json`` gives it (without
        ``--sweep``): the stacked array's clamped stack or a monolithic comb's row sheets;
        the n x n gauge sensitivity (1/N), the tip displacements (mm/N), ``crosstalk_rel``,
        the decoupling matrix and, at the rated force, each gauge's crosstalk in newtons
        against its force resolution.

        Args:
            model: a crosstalk level of the design's construction (``stack-beam`` ...,
                ``comb-beam``, ``comb-fem2d``; ``tactcad crosstalk --help``); None: its
                construction's cheapest (``stack-beam``, ``comb-beam``).

        Raises:
            UnknownCrosstalkModelError: ``model`` is no crosstalk level.
            DesignError: ``model`` is a level of another construction (naming the design's
                own), refused before anything is solved.
        """
        from tactcad.studies.project_reports import crosstalk_record

        return crosstalk_record(self.plan, model)[0]

    @keyword_errors
    def grasp(self, force_N: float | None = None, angle_deg: float | None = None,
              kobj: float | None = None, coupling: str = "layer", profile: str | None = None,
              pivot_mm: Sequence[float] | None = None, pin_to_tip_mm: float | None = None,
              opening_deg: float | None = None, slab_thickness_mm: float | None = None,
              lead_channel_mm: float | None = None, model: str = "closed-form") -> dict:
        """The design's jaw closed on tissue, as ``tactcad grasp --json`` gives it: each
        sensing unit's R and K_obj read as laid out and paired, every element's force
        against its rating and overload limit, the leads through the shaft, ``warnings``
        and ``passed`` (mm, N, N/mm, degrees; each argument as the command's option, None:
        its default, whose reason the record's ``reasons`` give).

        Args:
            force_N, angle_deg: the grasp force (N, 1e-6 <= F <= 1000: ``MIN_GRASP_FORCE_N`` of
                :mod:`tactcad.studies.grasp_report` and up) or the closing angle
                (degrees, 0 ... the jaw's opening); at most one.
            kobj: the tissue's true stiffness under one tip (N/mm, 1e-6 ... 1e4: the K_obj
                a design file's range may state).
            coupling: ``layer``, ``halfspace`` or ``none``. profile: ``wedge`` or ``slab``.
            pivot_mm: the pin (X, Y) from the first tip (mm). pin_to_tip_mm, opening_deg,
                slab_thickness_mm, lead_channel_mm: the jaw's sizes and the tissue's (mm,
                degrees). model: ladder level of the elements' K.

        Raises:
            DesignError: a value out of its range or not taken by the grasp, named by its
                keyword argument.
            UnknownModelError: ``model`` is not a ladder level.
        """
        from tactcad.commands.options import grasp_option_error
        from tactcad.errors import DesignError
        from tactcad.in_use.grasp_experiment import COUPLINGS, DEFAULT_PROFILE, PROFILES
        from tactcad.mechanics.ladder import UnknownModelError, models
        from tactcad.studies.grasp_report import GraspAsked, grasp_record

        given = {"force_N": force_N, "angle_deg": angle_deg, "kobj": kobj,
                 "pivot_mm": pivot_mm, "pin_to_tip_mm": pin_to_tip_mm,
                 "opening_deg": opening_deg, "slab_thickness_mm": slab_thickness_mm,
                 "lead_channel_mm": lead_channel_mm}
        checked = {k: v for k, v in _grasp_numbers(given).items() if v is not None}
        for option, value, allowed in (("coupling", coupling, COUPLINGS),
                                       ("profile", profile or DEFAULT_PROFILE, PROFILES)):
            if value not in allowed:
                raise DesignError(option, value, " or ".join(allowed))
        if model not in models():
            raise UnknownModelError(model)
        asked = GraspAsked(model=model, coupling=coupling, profile=profile or DEFAULT_PROFILE,
                           **checked)
        try:
            return grasp_record(self.plan, asked)
        except DesignError as exc:
            raise grasp_option_error(exc, asked) from None

    @keyword_errors
    def tolerance(self, samples: int | None = None, seed: int | None = None,
                  kobj: Sequence[float] | None = None, reference: int | None = None,
                  distribution: str | None = None, notch_radius_tol: float | None = None,
                  arm_tol: float | None = None, modulus_tol: float | None = None) -> dict:
        """The Monte Carlo of the design's manufacturing tolerances, as ``tactcad tolerance
        --json`` gives it: K per element, R and the reported K_obj per sensing unit (mean,
        std, 95 % interval), the web tolerance for a +/-5 % K band, the tolerances used and
        whether the K band holds ``[requirements] k_tolerance_rel`` (mm, N/mm; one
        computation with the command, :func:`tactcad.studies.project_reports.tolerance_record`;
        the paper's measured spread of equal-arm elements for the paper's design, as the
        command adds it).

        Args:
            samples: as-built arrays drawn (2 ... 10^7; None: 10 000, as ``verify``).
            seed: seed of the draw (0 ... 2^32 - 1; None: 0).
            kobj: true object stiffnesses to report (N/mm, each > 0; None: the ends and
                middle of the design's K_obj range, the paper's samples for its design).
            reference: one of the design's reference elements for every unit (None: each
                unit the nearest).
            distribution: ``normal`` (tolerance = 3 sigma, the default) or ``uniform``.
            notch_radius_tol, arm_tol: what-if +/- notch radius and arm length (mm, 0 ...
                10) instead of the design's ``[tolerances]``. modulus_tol: what-if +/-
                relative Young's modulus (0 ... 0.5).

        Raises:
            DesignError: a value out of its range, a what-if tolerance that lets its
                feature vanish, or an element that is none of the design's references,
                named by the keyword argument.
        """
        from tactcad.errors import DesignError
        from tactcad.paper.table1 import with_equal_arm_spread
        from tactcad.studies.project_reports import tolerance_record

        samples, seed, kobj, distribution = _tolerance_asked(samples, seed, kobj, distribution)
        if reference is not None:
            reference = element_number(reference, len(self.plan.slots), "reference")
        given = {"notch_radius_tol": notch_radius_tol, "arm_tol": arm_tol,
                 "modulus_tol": modulus_tol}
        what_if = _what_if_tolerances(given)
        try:
            report, fields, _ = tolerance_record(self.plan, samples, seed, kobj, reference,
                                                 distribution, what_if)
        except DesignError as exc:  # a what-if too large for its feature
            raise _what_if_named(exc, given) from None
        report = with_equal_arm_spread(report, self.plan)
        return {**report.as_json(), **fields}

    @keyword_errors
    def verify(self, model: str = "auto", progress: Progress | None = None,
               cache: str | Path | None | bool = True) -> "Verification":
        """The verification matrix of the design's requirements.

        Args:
            model: a ladder level, or ``auto``: the cheapest level that decides
                each requirement (the closed form first, higher levels only
                while one is undecided).
            progress: called with a line per element a level evaluates.
            cache: the store that keeps FEM results (:func:`tactcad.store.kept_result`),
                as for :meth:`export`: a level's solve is reused by the next
                ``verify``, ``check`` or command with the same store.

        Returns:
            :class:`Verification`: the records (``requirement``, ``target``,
            ``predicted``, ``error_estimate_rel``, ``margin_rel``, ``model``,
            ``verdict``: pass, fail or undecided, ...), the seconds per level,
            and ``passed`` (no requirement fails).

        Raises:
            UnknownModelError: ``model`` is neither ``auto`` nor a ladder level.
            DesignError: the material has no yield strength.
        """
        from tactcad.mechanics.ladder import UnknownModelError, models
        from tactcad.store import keeping_results

        if model != "auto" and model not in models():
            raise UnknownModelError(model, also=("auto",))
        with keeping_results(_store(cache)):
            return self._verify(model, progress)

    def _verify(self, model: str, progress: Progress | None) -> "Verification":
        from tactcad.assembly.inventory import array_envelope_mm
        from tactcad.studies.verification import (requirements_of, verification_auto,
                                                    verification_matrix)
        from tactcad.studies.strength_studies import element_stress

        plan = self.plan
        req = requirements_of(plan)
        envelope = array_envelope_mm(plan)
        if model == "auto":
            records, levels = verification_auto(plan, progress, req, stress=element_stress,
                                                envelope_mm=envelope)
        else:
            records = verification_matrix(plan, model, progress, req, stress=element_stress,
                                          envelope_mm=envelope)
            levels = []
        return Verification(model, tuple(plain(records)), tuple(plain(levels)),
                            plain(req.as_json()))

    @keyword_errors
    def check(self, out: str | Path | None = None, scenes: Sequence[str] | None = None,
              cache: str | Path | None | bool = True, progress: Progress | None = None,
              on_group: Callable[[str, list], None] | None = None) -> "CheckReport":
        """Run every check of ``tactcad check`` on the design's export.

        Args:
            out: an export folder. It is checked as it is when its manifest
                names this design (:func:`tactcad.export.reuse.export_state`): a
                file changed or removed by hand since is left as it is, one failing
                check of the ``export files`` group; otherwise (another design, no
                export, an export older than an edit of the rigs, scenes or another
                file it was made from: :func:`tactcad.export.reuse.changed_inputs`)
                the design is exported there first. ``None``: a temporary
                folder, removed afterwards.
            scenes: check only these scenes (interference, sanity, STEP and
                GLB read-back); ``None`` checks the array and every scene.
            cache: the store of finished jobs, as for :meth:`export`; it keeps
                the FEM results of the checks too (as :meth:`verify`).
            progress: called with a line on the export (one per job run).
            on_group: called as ``on_group(label, results)`` when each group
                of checks finishes: the groups of
                :data:`tactcad.checks.groups.CHECK_GROUPS` in order
                (``requirements``: the design's verification matrix with the
                verdicts :meth:`verify` gives by default, ``parts``, ``dxf``,
                ``array interference``, ``array STEP``, then ``scene <name>`` per scene).

        Returns:
            :class:`CheckReport`: every result with its group.

        Raises:
            SceneError: an unknown scene.
            ExportPathError, OSError: as :meth:`export`.
        """
        import tempfile

        from tactcad.assembly.rig_models import get_scene_spec
        from tactcad.checks.groups import CheckContext, groups_to_run, run_groups
        from tactcad.export.reuse import reuse_state
        from tactcad.export.export_owner import default_product_name, refuse_another_designs_export
        from tactcad.export.run import check_out_dir, export, export_scenes
        from tactcad.export.selection import with_progress
        from tactcad.store import keeping_results

        report = progress or _quiet
        groups: list[tuple[str, list]] = []

        def done(group: str, found: list) -> None:
            groups.append((group, list(found)))
            if on_group is not None:
                on_group(group, list(found))

        for name in scenes or ():  # an unknown scene is refused before any check runs
            get_scene_spec(self.validated, name)
        self._report = report
        to_run = groups_to_run(scenes)
        context = CheckContext(self.plan, Path("."), self._cache, self.validated, scenes)
        if out is not None and reuse_state(self.plan, Path(out), self.validated).refusal \
                is not None:
            check_out_dir(out)  # a folder no export can be written to: refused before any solve
            if not scenes:  # nor one holding another design's export, which export refuses
                refuse_another_designs_export(Path(out), default_product_name(), self.plan.name)
        # what reads the design alone (the verification matrix) runs before any export
        with keeping_results(_store(cache)):
            run_groups([g for g in to_run if not g.on_export], context, done)
        try:
            with tempfile.TemporaryDirectory() as tmp:
                folder = Path(out) if out is not None else Path(tmp)
                state = reuse_state(self.plan, folder, self.validated)
                refusal = state.refusal
                edited: dict[str, str] | None = state.edited
                stale = state.stale
                if refusal is None:
                    report(f"checking the export in {folder} as it is "
                           f"({_edits_said(state.edited, stale)})")
                elif scenes:
                    report(f"exporting the scenes to {folder} first: {refusal}")
                    export_scenes(self.validated, folder, scenes, log=_quiet, store=_store(cache),
                                  parts=self._cache)
                    edited, stale = None, ()  # the manifest is left as it was: not compared
                else:
                    report(f"exporting to {folder} first: {refusal}" if out is not None else
                           f"exporting to the temporary folder {folder} first (no out)")
                    export(self.validated, folder, log=_quiet, store=_store(cache), parts=self._cache,
                           select=lambda jobs: with_progress(jobs, report))
                    stale = ()  # written from the project's files now
                run_groups([g for g in to_run if g.on_export],
                           replace(context, folder=folder, edited=edited, stale=stale), done)
        finally:
            self._report = _quiet
        # a temporary folder held no export to refuse: only a given out's refusal is said
        return CheckReport(tuple((g, tuple(r)) for g, r in groups), refusal is None,
                           None if out is None else refusal, None if out is None else str(out))


def _edits_said(edited: Mapping[str, str], stale: Sequence[str] = ()) -> str:
    """What a check says of an export's hand edits (and of the inputs it is older than, which
    an export with hand edits is checked despite) as it starts reading it."""
    from tactcad.export.reuse import stale_said

    if not edited:
        return "same design, every file as listed"
    older = f"; {stale_said(tuple(stale))}, failing the export files check too" if stale else ""
    return (f"same design; {len(edited)} file(s) changed or removed by hand since the export, "
            f"left as they are and failing the export files check{older}")


def element_number(number: Any, count: int, field: str = "number") -> int:
    """``number`` checked as an element's number: an integer (not a bool) in 1 ... ``count``.

    Args:
        number: the value given. count: the design's elements. field: the argument that
            gave it, named in the refusal.

    Raises:
        DesignError: naming ``field``, the value and "an integer 1 ... N".
    """
    import numbers

    from tactcad.errors import DesignError

    allowed = f"an integer 1 ... {count} (the design's element numbers)"
    if isinstance(number, bool) or not isinstance(number, numbers.Integral):
        raise DesignError(field, number, allowed)
    if not 1 <= int(number) <= count:
        raise DesignError(field, number, allowed)
    return int(number)


def _checked_number(option: str, value: Any, lo: float, hi: float, unit: str, lo_open: bool,
                    count: int | None = None) -> Any:
    """``value`` when it is a finite number in ``lo ... hi`` (``lo`` excluded when
    ``lo_open``), or ``count`` of them (a tuple then), as the command's option of that
    range takes it (:func:`tactcad.commands.options.number`).

    Raises:
        DesignError: a value out of range, not a number, or not ``count`` of them, named by
            ``option`` (the API's refusal names the keyword argument).
    """
    import argparse
    import math
    import numbers

    from tactcad.commands.options import number
    from tactcad.errors import DesignError

    parse = number(lo, hi, unit, lo_open=lo_open)
    allowed = (f"{count} numbers " if count else "a number ") + \
        f"{'>' if lo_open else ''}{lo:g} ... {hi:g} ({unit})"
    items = value if count else [value]
    if count and (isinstance(value, (str, bytes)) or not hasattr(value, "__len__")
                  or len(value) != count):
        raise DesignError(option, value, allowed)
    for x in items:  # any real number (numpy's too), not a bool
        if isinstance(x, bool) or not isinstance(x, numbers.Real) or not math.isfinite(x):
            raise DesignError(option, value, allowed)
        try:
            parse(repr(float(x)))
        except argparse.ArgumentTypeError:
            raise DesignError(option, value, allowed) from None
    return tuple(float(x) for x in items) if count else float(value)


def _grasp_numbers(given: Mapping[str, Any]) -> dict[str, Any]:
    """A grasp's keyword numbers, each checked with its option's range
    (:data:`tactcad.studies.grasp_report.GRASP_NUMBERS`; ``pivot_mm`` two of them), None
    left as given.

    Raises:
        DesignError: a value out of its range or not a number, named by its option.
    """
    from tactcad.studies.grasp_report import GRASP_NUMBERS

    import math
    import numbers

    from tactcad.errors import DesignError

    def checked(k: str, v: Any) -> Any:
        if k != "angle_deg":
            return _checked_number(option_name(k), v, *GRASP_NUMBERS[k],
                                   count=2 if k == "pivot_mm" else None)
        # the closing angle's range is the jaw's own (0 ... its opening), checked against
        # the jaw as the command's --angle-deg is: here only that it is a finite number
        if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(v):
            raise DesignError(option_name(k), v, "a number 0 ... the jaw's opening (degrees)")
        return float(v)

    return {k: None if v is None else checked(k, v) for k, v in given.items()}


def _checked_integer(option: str, value: Any, lo: int, hi: int, what: str) -> int:
    """``value`` when it is an integer (not a bool) in ``lo ... hi``, as the command's
    option of that range takes it (:func:`tactcad.commands.options.count`).

    Raises:
        DesignError: not such an integer, named by ``option`` (the API's refusal names the
            keyword argument).
    """
    import numbers

    from tactcad.errors import DesignError

    if isinstance(value, bool) or not isinstance(value, numbers.Integral) \
            or not lo <= int(value) <= hi:
        raise DesignError(option, value, f"an integer {lo} ... {hi} ({what})")
    return int(value)


def _tolerance_asked(samples: Any, seed: Any, kobj: Any, distribution: Any,
                     die: bool = False) -> tuple[int, int, tuple[float, ...] | None, str | None]:
    """The options ``tactcad tolerance`` shares between a metal design and a die, checked
    with the command's ranges and defaults (:mod:`tactcad.commands.tolerance`).

    Args:
        samples: as-built designs drawn (None: 10 000). seed: the draw's seed (None: 0).
        kobj: true object stiffnesses (N/mm, each > 0; None: the design's default).
        distribution: ``normal``, ``uniform`` or None (the product's default).
        die: a silicon die's Monte Carlo (``samples`` in its range, dies drawn), else a
            metal array's.

    Returns:
        (samples, seed, kobj as a tuple or None, distribution).

    Raises:
        DesignError: a value out of its range, named by its option (the API's refusal names
            the keyword argument).
    """
    from tactcad.commands.tolerance import KOBJ_RANGE, SEED_RANGE
    from tactcad.errors import DesignError
    from tactcad.products.silicon_die.studies.die_tolerance import DIE_SAMPLES_RANGE
    from tactcad.studies.tolerance_montecarlo import (MONTE_CARLO_SAMPLES, MONTE_CARLO_SEED,
                                                      SAMPLES_RANGE)

    # the product's own range, in the command's words (tactcad.commands.tolerance)
    samples = _checked_integer("--samples", MONTE_CARLO_SAMPLES if samples is None else samples,
                               *(DIE_SAMPLES_RANGE if die else SAMPLES_RANGE),
                               "dies drawn" if die else "arrays drawn")
    seed = _checked_integer("--seed", MONTE_CARLO_SEED if seed is None else seed, *SEED_RANGE,
                            "a seed")
    if kobj is not None:
        if isinstance(kobj, (str, bytes)) or not isinstance(kobj, Iterable) or not list(kobj):
            raise DesignError("--kobj", kobj, "a list of one or more numbers "
                                              f">{KOBJ_RANGE[0]:g} ... {KOBJ_RANGE[1]:g} (N/mm)")
        kobj = tuple(_checked_number("--kobj", k, *KOBJ_RANGE, "N/mm", True) for k in kobj)
    if distribution not in (None, "normal", "uniform"):
        raise DesignError("--distribution", distribution, "normal or uniform")
    return samples, seed, kobj, distribution


def _what_if_tolerances(given: Mapping[str, Any]) -> dict[str, float]:
    """The what-if tolerances given (keyword -> value, None: not given) as the
    :class:`~tactcad.studies.tolerance_montecarlo.Tolerances` fields they replace, each
    checked with its option's range (mm, or relative for ``modulus_tol``).

    Raises:
        DesignError: a value out of its range, named by its option.
    """
    from tactcad.commands.tolerance import WHAT_IF_OPTIONS

    out = {}
    for key, value in given.items():
        field, lo, hi, unit = WHAT_IF_OPTIONS[key]
        if value is not None:
            out[field] = _checked_number(option_name(key), value, lo, hi, unit or "relative",
                                         False)
    return out


def _what_if_named(exc: Exception, given: Mapping[str, Any]) -> Exception:
    """A refusal of a what-if tolerance (``tolerance.<field>``, too large for its feature)
    named by the option that gave it; any other refusal as it is."""
    from tactcad.commands.tolerance import WHAT_IF_OPTIONS
    from tactcad.errors import DesignError

    fields = {f"tolerance.{field}": key for key, (field, *_) in WHAT_IF_OPTIONS.items()
              if given.get(key) is not None}
    if type(exc) is not DesignError or exc.field not in fields:
        return exc
    return DesignError(option_name(fields[exc.field]), exc.value, exc.allowed, exc.why,
                       exc.file, exc.alternatives, exc.limit)


def load_die(path: str | Path | None = None,
             set: Mapping[str, Any] | None = None) -> "DieProject":
    """A silicon die's design file as a :class:`DieProject`, planned now (the die product's
    ``load`` hook, :mod:`tactcad.products.silicon_die`; :func:`load` calls it for a die's
    file).

    Args:
        path: the die's design file (a ``[die]`` table), or a project folder holding it (as
            :func:`load` takes one); ``None`` means the one design file of the working
            folder, which must be a die's (:func:`_die_design_path`: no shipped die stands
            in, as the array example stands in for :func:`load`).
        set: values to override by dotted key (``{"die.columns": 4}``), checked like the file.

    Raises:
        DesignErrors, DesignError: as ``tactcad die --design`` refuses the file or a value;
            a folder with no design file or several, or none given where the working folder
            holds no die's design file (naming ``path``).
    """
    project = DieProject(_die_design_path(path), _checked_overrides(set))
    project.plan  # planned now: a refusal at load, as an array's
    return project


def _die_design_path(path: str | Path | None) -> Path:
    """The die design file :func:`load_die` reads for ``path``.

    Args:
        path: a die's design file, a project folder holding one design file, or None (the
            working folder's one design file).

    Returns:
        The design file's path (a folder's one design file; the file as given otherwise,
        which the die's loader reads and refuses when it holds no ``[die]`` table).

    Raises:
        DesignError: ``path`` neither a str, a path nor None; a folder with no design file or
            several; None where the working folder holds no design file, or an array's.
    """
    from tactcad.design.array_plan import DEFAULT_DESIGN, read_toml
    from tactcad.errors import DesignError
    from tactcad.products.silicon_die.design.die_file import is_die_file
    from tactcad.project_folder import default_design, design_in_folder

    allowed = "a die design file's path (str or pathlib.Path) or a project folder holding one"
    if path is not None and not isinstance(path, (str, PathLike)):
        raise DesignError("path", path, allowed + ", or None (the working folder's)")
    if path is not None:
        given = Path(path)
        return design_in_folder(given, "path") if given.is_dir() else given
    design = default_design()
    if design == DEFAULT_DESIGN or not is_die_file(read_toml(design, "path")):
        why = (f"the working folder's design file {design.name} is an array's: "
               "tactcad.load() reads it" if design != DEFAULT_DESIGN else
               "the working folder holds no design file (tactcad.load() then reads the array "
               "example; no die stands in)")
        raise DesignError("path", None, allowed + "; left out only in a die's project folder",
                          why)
    return design


class DieProject:
    """A silicon die's validated design and what tactcad computes for it: the same reports
    (the same numbers) ``tactcad stiffness``, ``strength``, ``readout``, ``modal``,
    ``budget``, ``verify``, ``thermal``, ``crosstalk``, ``grasp`` and ``tolerance`` print
    with ``--json`` on its file, its :attr:`design_hash` (the export manifest's), and its
    export and check.

    Build with :func:`load`. Units: um for the die's dimensions, N/mm, N, MPa, Hz.

    Attributes:
        source: the die design file's path.
    """

    def __init__(self, source: Path, overrides: Mapping[str, Any]):
        self.source = Path(source)
        self._overrides = dict(overrides)

    def _args(self, **options: Any):
        """The namespace the die's views read (as the CLI parses it), ``set`` as ``--set``."""
        import argparse

        import tomli_w

        texts = [f"{k}={tomli_w.dumps({'v': v}).partition('=')[2].strip()}"
                 for k, v in self._overrides.items()]
        return argparse.Namespace(design=str(self.source), overrides=texts, json=True,
                                  quiet=True, option_defaults={}, **options)

    @cached_property
    def planned(self):
        """The die planned from its file (:class:`tactcad.commands.die.PlannedDie`: plan,
        the jaw's room, the jaw as mounted).

        Raises:
            DesignErrors: the file's refusals, a refused ``set`` value named as ``set`` (as
                :func:`load` names an array's), not as the command's ``--set``.
        """
        from tactcad.commands.die import _die_args, die_asked, plan_of
        from tactcad.errors import DesignErrors
        from tactcad.products.silicon_die.design.die_file import load_die_design

        if self._overrides:  # the file with the set values first, refused in the API's words
            try:
                load_die_design(self.source, self._overrides)
            except DesignErrors as exc:
                raise exc.sourced({key: "set" for key in self._overrides}) from None
        with _working_folder_store():  # the plan's own solves (its tissue coupling) kept too
            return plan_of(die_asked(_die_args(self.source, self._args(), Path("."))))

    @property
    def plan(self):
        """The die's :class:`~tactcad.products.silicon_die.design.mems_die.DiePlan` (um, N/mm, N, MPa), every
        derived dimension with its reason (``plan.reasons``)."""
        return self.planned.plan

    @property
    def name(self) -> str:
        """The die's name (``[die] name``): its GDS cell and file names."""
        return self.plan.name

    def _report(self, command: str, **options: Any) -> dict:
        """The die view ``command``'s record. Its solves are kept in and read from the
        working folder's result store, as the command's are (``--cache`` left out), unless
        the caller opened a store of its own (:func:`tactcad.store.keeping_results`)."""
        from tactcad.products import product_named

        view = product_named("silicon-die").view(command)
        assert view is not None, command  # the die's registry entry names each one used here
        with _working_folder_store():
            return view(self.source, self._args(**options))[0]

    @keyword_errors
    def stiffness(self, model: str = "closed-form") -> dict:
        """Each row's beam K on its frame at ``model`` (``closed-form`` or ``fem3d``), as
        ``tactcad stiffness --json`` gives it (N/mm, relative errors).

        Raises:
            DesignError: another model.
        """
        return self._report("stiffness", model=model)

    @keyword_errors
    @refuses_array_keywords
    def strength(self) -> dict:
        """Each row's root stress at the force it carries against the strength of etched
        silicon, and the rated-force requirement, as ``tactcad strength --json`` (MPa, N)."""
        return self._report("strength", model="closed-form")

    @keyword_errors
    @refuses_array_keywords
    def readout(self) -> dict:
        """The piezoresistive read-out, as ``tactcad readout --json`` (ohm, V/N, N)."""
        return self._report("readout")

    @keyword_errors
    @refuses_array_keywords
    def modes(self, model: str = "closed-form") -> dict:
        """Each row's first resonance at ``model``, as ``tactcad modal --model MODEL --json``
        gives it (Hz, relative errors, s): ``closed-form`` (Rayleigh, milliseconds) or
        ``fem3d`` (each row's beam on its frame, the solve ``tactcad die --fem3d`` makes,
        about a minute and a half; kept in the result store, so a second call solves
        nothing).

        Args:
            model: the die's modal level, ``closed-form`` or ``fem3d``.

        Returns:
            The report: ``rows`` (per row ``first_Hz``, ``first_Hz_error_rel``,
            ``wall_time_s``, ``reused``), ``lowest_first_Hz``, ``resonance_Hz``.

        Raises:
            DesignError: another model, naming ``model`` and the die's levels.
        """
        return self._report("modal", model=model)

    @keyword_errors
    @refuses_array_keywords
    def budget(self) -> dict:
        """The K_obj error budget, as ``tactcad budget --json`` (relative, 1 sigma)."""
        return self._report("budget")

    @keyword_errors
    @refuses_array_keywords
    def verify(self) -> dict:
        """The verification matrix, as ``tactcad verify --json`` (``passed``, ``matrix``)."""
        return self._report("verify")

    @keyword_errors
    @refuses_array_keywords
    def thermal(self) -> dict:
        """The die's thermal drift, as ``tactcad thermal --json``."""
        return self._report("thermal")

    @keyword_errors
    @refuses_array_keywords
    def crosstalk(self) -> dict:
        """Each beam's reading under a force on every post, as ``tactcad crosstalk
        --json``."""
        return self._report("crosstalk")

    @keyword_errors
    @refuses_array_keywords
    def grasp(self, force_N: float | None = None, angle_deg: float | None = None,
              kobj: float | None = None, coupling: str = "layer",
              profile: str | None = None, slab_thickness_mm: float | None = None,
              opening_deg: float | None = None) -> dict:
        """The die's jaw closed on tissue, as ``tactcad grasp --json`` on its file (mm, N,
        N/mm, degrees); each option as the command's (None: its default).

        Raises:
            DesignError: a value out of range, or both a force and an angle (named by the
                keyword argument).
        """
        from tactcad.errors import DesignError
        from tactcad.in_use.grasp_experiment import DEFAULT_PROFILE

        if force_N is not None and angle_deg is not None:  # the command's options exclude it
            raise DesignError("force_N / angle_deg", (force_N, angle_deg), "one of them, or "
                              "neither (the default grasp force)")
        given = {"force_N": force_N, "angle_deg": angle_deg, "kobj": kobj,
                 "slab_thickness_mm": slab_thickness_mm, "opening_deg": opening_deg}
        # the ranges the command's options take (a die's grasp reads the same options)
        return self._report("grasp", coupling=coupling, profile=profile or DEFAULT_PROFILE,
                            **_grasp_numbers(given))

    @keyword_errors
    @refuses_array_keywords
    def tolerance(self, samples: int | None = None, seed: int | None = None,
                  kobj: Sequence[float] | None = None, distribution: str | None = None) -> dict:
        """The Monte Carlo of the die's process tolerances (device layer thickness, the
        masks' alignment to the cavities) as its budget states them, as ``tactcad tolerance
        --json`` gives it on the die's file: each row's beam K, each unit's R and the K_obj
        it reads, and the spread against the budget's terms (N/mm; um for the die).

        Args:
            samples: as-built dies drawn (2 ... 10^6; None: 10 000). seed: seed of the draw
                (0 ... 2^32 - 1; None: 0). kobj: true object stiffnesses to report (N/mm,
                each > 0; None: the die's default). distribution: ``uniform`` (the
                default, as the budget takes a +- bound) or ``normal``.

        Raises:
            DesignError: a value out of its range, named by the keyword argument.
        """
        samples, seed, kobj, distribution = _tolerance_asked(samples, seed, kobj, distribution,
                                                             die=True)
        return self._report("tolerance", samples=samples, seed=seed,
                            kobj=None if kobj is None else list(kobj), distribution=distribution)

    @property
    def design_hash(self) -> str:
        """sha256 of the die's design file, as in its export's manifest (a die asked by
        options has no file: the manifest's stand-in). The jaw file the design names is
        not in it: it is one of the die's :attr:`inputs`, as an array's rigs.toml is one of
        its export's."""
        from tactcad.products.silicon_die.export.die_review import design_head

        return design_head(self.name, self.planned.source)["design"]["sha256"]

    @property
    def inputs(self) -> dict:
        """What the die's export is made from, as its manifest's ``inputs`` records it: the
        design file and the jaw file it names (none for a trocar class), each
        ``{"role", "file", "sha256"}``. ``tactcad check`` exports again an export whose
        record differs (:func:`tactcad.products.silicon_die.export.die_inputs.changed_die_inputs`)."""
        return self.planned.inputs or {"files": []}

    @keyword_errors
    @refuses_array_keywords
    def check(self, out: str | Path | None = None,
              progress: Progress | None = None) -> "CheckReport":
        """Run every check of ``tactcad check`` on the die's export, as the command does
        (:func:`tactcad.commands.die.die_check`).

        Args:
            out: an export folder. It is checked as it is when it holds an export of this
                design, as an array's (:func:`tactcad.export.reuse.export_state`): a file
                changed or removed by hand since is left as it is, one failing check;
                otherwise the die is exported there first. ``None``: a temporary folder,
                removed afterwards.
            progress: told whether the export was reused or written first.

        Returns:
            :class:`CheckReport`: one group, ``die NAME``, with every result in order.

        Raises:
            DesignError: ``out`` holds another design's export or files no export wrote.
        """
        from tactcad.commands.die import die_check

        found = die_check(self.source, self._args(out=None if out is None else str(out),
                                                  junit=None, scene=None),
                          progress or _quiet)
        return CheckReport(((f"die {found.name}", found.checks),), found.export_refusal is None,
                           found.export_refusal, None if out is None else str(out))

    @keyword_errors
    @refuses_array_keywords
    def export(self, out: str | Path = "exports", cache: Any = None,
               progress: Progress | None = None) -> int:
        """Write the die's files into ``out`` (masks, wafer, STEP, traveller, drawing, BOM,
        scene, review page, manifest), as ``tactcad export`` does; the exit code (1: a check
        failed).

        Args:
            out: the export folder (new, empty or this die's).
            cache: the store of finished jobs and solves, as an array's export takes it
                (``None``: the working folder's, or the caller's open
                :func:`tactcad.store.keeping_results` block).
            progress: told when the export starts and ends.

        Raises:
            DesignError: ``out`` holds another design's export or files no export wrote;
                ``cache`` names no folder the store could be kept in.
        """
        import contextlib
        import io

        from tactcad.commands.die import export_die
        from tactcad.store import keeping_results

        kept = _working_folder_store() if cache is None else keeping_results(_store(cache))
        report = progress or _quiet
        report(f"exporting die {self.name} to {out}")
        with kept, contextlib.redirect_stdout(io.StringIO()):
            code = export_die(self.source, self._args(out=str(out)))
        report(f"exported die {self.name} to {out}")
        return code


def _working_folder_store():
    """A block keeping results in the working folder's store, as a command run without
    ``--cache`` does; the caller's own block where one is open
    (:func:`tactcad.store.keeping_results`)."""
    import contextlib

    from tactcad.store import active_store, keeping_results

    if active_store() is not None:
        return contextlib.nullcontext()
    return keeping_results(_store(True))


def _store(cache: str | Path | None | bool):
    """The :class:`~tactcad.store.Store` that ``cache`` names.

    Raises:
        DesignError: naming ``cache``: neither True, False, None nor a path, or a folder the
            store could not be kept in (:func:`tactcad.store.usable_cache_folder`).
    """
    from tactcad.errors import DesignError
    from tactcad.store import CACHE_ALLOWED, DEFAULT_STORE, Store, usable_cache_folder

    if cache is True:
        return Store(DEFAULT_STORE)
    if cache is False or cache is None:
        return Store(None)
    if not isinstance(cache, (str, Path)) or not str(cache).strip():
        raise DesignError("cache", cache, f"True, False, None or a path: {CACHE_ALLOWED}")
    return Store(usable_cache_folder(str(cache), "cache"))


class Parts(Mapping):
    """Part name -> build123d ``Solid`` (part frame, mm), built on first access."""

    def __init__(self, project: Project):
        self._project = project

    def __getitem__(self, name: str):
        specs = self._project._specs
        if name not in specs:
            raise KeyError(f"{name!r}: not a part of design {self._project.name}; "
                           f"parts: {', '.join(specs)}")
        return self._project._cache.solid(specs[name])

    def __iter__(self) -> Iterator[str]:
        return iter(self._project._specs)

    def __len__(self) -> int:
        return len(self._project._specs)

    def __repr__(self) -> str:
        return f"<parts of {self._project.name}: {', '.join(self)}>"


@dataclass(frozen=True)
class Element:
    """One sensing element of a project: its geometry, solid, stiffness, natural
    frequencies and strength.

    Attributes:
        number: the element's number (1-based).
        slot: its :class:`~tactcad.design.array_plan.ElementSlot` (geometry and placement).
    """

    project: Project
    slot: "ElementSlot"

    @property
    def number(self) -> int:
        return self.slot.number

    @property
    def geometry(self) -> "ElementGeometry":
        """The element's :class:`~tactcad.design.array_plan.ElementGeometry` (mm)."""
        return self.slot.geometry

    @property
    def part_name(self) -> str:
        """Its part's name (``element_a4mm``: elements of equal geometry share it)."""
        return self.slot.geometry.part_name

    @property
    def solid(self) -> "Solid":
        """The element's build123d ``Solid`` (element frame, mm): the wire-cut
        profile extruded by the sheet thickness along +z."""
        return self.project.parts[self.part_name]

    @keyword_errors
    def stiffness(self, model: str = "closed-form", **options: Any) -> "StiffnessResult":
        """Tip stiffness K for a force normal to the contact face.

        Args:
            model: ladder level: ``closed-form`` (1 ms), ``beam``, ``fem2d``
                (about 1 s), ``fem3d`` (about 30 s).
            **options: the level's own options (e.g. ``progress`` for FEM).

        Returns:
            :class:`~tactcad.mechanics.stiffness_result.StiffnessResult`: K (N/mm), face
            strain per newton (1/N), relative error estimate, wall time (s) and, for an
            element carrying a gauge, the grid strain per newton at ``model`` (1/N,
            signed, negative where the grid shortens; ``tactcad stiffness``'s, ``readout``'s
            and ``thermal``'s ``grid_strain_per_N``).

        Raises:
            UnknownModelError: ``model`` is not a ladder level.
        """
        from tactcad.mechanics.ladder import estimate

        plan = self.project.plan
        result = estimate(model, self.geometry, plan.material, element=self.number, **options)
        if result.grid_strain_per_N is not None or self.geometry.gauge is None:
            return result
        # the closed form and the beam level mesh no layer: the read-out's grid strain
        from tactcad.mechanics.readout_chain import grid_strain_per_N, readout_chain

        read = grid_strain_per_N(self.geometry, plan.material, readout_chain(plan), model)
        return replace(result, grid_strain_per_N=float(read["grid"]))

    @keyword_errors
    def modes(self, model: str = "closed-form", modes: int = 3,
              **options: Any) -> "ModalResult":
        """The lowest natural frequencies of the element as clamped in the stiffness model.

        Args:
            model: modal level: ``closed-form`` (a few ms, the first in-plane
                mode), ``fem2d`` (about 1 s, in-plane modes), ``fem3d``
                (10-60 s, in-plane and out-of-plane modes).
            modes: how many (the closed form gives one).
            **options: the level's own (``progress``, ``keep_shapes`` for FEM).

        Returns:
            :class:`~tactcad.mechanics.modal_result.ModalResult`: frequencies
            (Hz) with their families, error estimate of the first, wall time (s).

        Raises:
            UnknownModalModelError: ``model`` is not a modal level.
            DesignError: the material has no density.
        """
        from tactcad.mechanics.modal_ladder import estimate_modes

        return estimate_modes(model, self.geometry, self.project.plan.material,
                              element=self.number, modes=modes, **options)

    @keyword_errors
    def strength(self, model: str = "closed-form") -> "StrengthRecord":
        """Peak stress per newton at the hinge, this element's yield-limited
        force and its figures at the design's rated full-scale force.

        Args:
            model: ladder level, as for :meth:`stiffness`.

        Returns:
            :class:`~tactcad.mechanics.element_strength.StrengthRecord` (MPa/N, N,
            strain, mm, and the limits exceeded in ``warnings``):
            ``full_scale_force_N`` is the design's rating (the same as
            ``verify``'s and every element's), ``yield_limited_force_N`` this
            element's own limit from yield.

        Raises:
            UnknownModelError: ``model`` is not a ladder level.
            DesignError: the material has no yield strength.
        """
        from tactcad.mechanics.element_strength import at_the_grid, strength_record
        from tactcad.mechanics.ladder import UnknownModelError, models
        from tactcad.studies.reference_loads import reference_load_of
        from tactcad.studies.strength_studies import element_stress
        from tactcad.studies.verification import rated_full_scale_force

        if model not in models():
            raise UnknownModelError(model)

        plan = self.project.plan
        stress = at_the_grid(element_stress(self.geometry, plan.material, model),
                             self.geometry, plan)
        return strength_record(self.number, self.geometry, plan.material, plan.strength, stress,
                               rated_full_scale_force(plan), reference_load_of(plan))


@dataclass(frozen=True)
class Verification:
    """Results of :meth:`Project.verify`.

    Attributes:
        model: the level asked for (``auto`` or a ladder level).
        records: one dict per requirement, in the matrix's order.
        levels: ``{"model", "seconds", "undecided_before", "elements_kept",
            "stresses_kept"}`` per level run (``auto``; ``elements_kept``: the parts whose
            lower-level figures it kept; ``stresses_kept``: those whose K it solved and
            whose lower-level stresses it kept).
        requirements: the requirement values with their reasons.
        warnings: what the levels warned of, one line each (alike ones folded), as
            ``tactcad verify --json`` lists them.
    """

    model: str
    records: tuple[dict, ...]
    levels: tuple[dict, ...]
    requirements: dict
    warnings: tuple[str, ...] = ()

    @property
    def passed(self) -> bool:
        """True when no requirement's verdict is ``fail``."""
        return not self.failed

    @property
    def failed(self) -> list[str]:
        """The requirements whose verdict is ``fail``."""
        return [r["requirement"] for r in self.records if r["verdict"] == "fail"]

    @property
    def undecided(self) -> list[str]:
        """The requirements no level decided (margin inside the error estimate)."""
        return [r["requirement"] for r in self.records if r["verdict"] == "undecided"]

    @property
    def info(self) -> list[str]:
        """The requirements reported, not judged (verdict ``info``: the design file states
        no value for them, so no target, margin or pass; ``check`` counts them apart)."""
        return [r["requirement"] for r in self.records if r["verdict"] == "info"]

    @property
    def seconds(self) -> float:
        """Wall time of the levels run (s)."""
        return sum(level["seconds"] for level in self.levels)


@dataclass(frozen=True)
class CheckReport:
    """Results of :meth:`Project.check`.

    Attributes:
        groups: (group name, its :class:`~tactcad.checks.check_result.CheckResult` s)
            in the order they ran.
        reused_export: the export folder was checked as it was.
        export_refusal: why the export in ``out`` was not (None when reused, and when
            ``out`` was None: a temporary folder holds no export to refuse).
        out: the folder checked (None: a temporary one).
        warnings: what the export and the checks warned of, one line each (alike ones
            folded), as ``tactcad check`` says them.
    """

    groups: tuple[tuple[str, tuple["CheckResult", ...]], ...]
    reused_export: bool
    export_refusal: str | None
    out: str | None
    warnings: tuple[str, ...] = ()

    @property
    def results(self) -> list["CheckResult"]:
        """Every result in order."""
        return [r for _, found in self.groups for r in found]

    @property
    def failures(self) -> list["CheckResult"]:
        """The results that failed."""
        return [r for r in self.results if not r.passed]

    @property
    def passed(self) -> bool:
        """True when every check passed."""
        return not self.failures

    def __len__(self) -> int:
        return len(self.results)
