"""The reference pages generated from tactcad's own declarations at build time.

Each page is MyST Markdown written from the one place its facts are declared,
so the site cannot drift from the code:

* ``cli.md``: every command and option, from the argument parser
  (:func:`tactcad.cli.build_parser`, walked by :func:`tactcad.commands.options.options_of`);
* ``schema.md``: every key of the design, rigs and scenes files with its unit,
  range and reason, from the pydantic schema (``DesignFile``, ``RigsFile``,
  ``ScenesFile``; the ranges are the :class:`tactcad.vocabulary.schema.Limits`
  that also word the validator's refusals);
* ``export_kinds.md`` and ``check_groups.md``: the registries
  :data:`tactcad.export.kinds.EXPORT_KINDS` and :data:`tactcad.checks.groups.CHECK_GROUPS`;
* ``processes.md``: the cut processes of :data:`tactcad.vocabulary.process.CUT_PROCESSES`,
  each rule's figure at example sheets with the rule and its source;
* ``materials.md``: the material grades and strain gauges of
  ``src/tactcad/data/materials.toml`` and the force gauges of
  ``src/tactcad/data/force_gauges.toml``, each value with its source.

The pages are written into ``docs/_generated/`` (ignored by git) when Sphinx
starts (``builder-inited``) and included by the hand-written reference pages.
The functions are pure (text out), so ``tests/docs`` reads the same text.
"""

from __future__ import annotations

import argparse
import math
import re
import types
import typing
from pathlib import Path
from typing import Any, Iterator

from pydantic import BaseModel
from pydantic_core import PydanticUndefined

#: ASCII punctuation that CommonMark lets a backslash escape: free text from the
#: code (help strings, reasons, sources) is escaped whole, so ``<part>`` or
#: ``a*b`` is printed as written, never read as markup.
_MARKUP = re.compile(r"([\\`*_{}\[\]<>()#+\-.!|~\"'$&^=:;,?@/%])")


def text(s: Any) -> str:
    """``s`` as literal Markdown text on one line (markup characters escaped)."""
    return _MARKUP.sub(r"\\\1", " ".join(str(s).split()))


#: A reStructuredText role or a literal in a docstring (``:mod:`x` ``, ````x````).
_DOC_CODE = re.compile(r"(?::[\w:]+:)?`{1,2}([^`]+?)`{1,2}")


def docstring(s: str) -> str:
    """A docstring's text as Markdown on one line: its roles and literals as inline
    code, the rest escaped."""
    s = " ".join(s.split())
    out, at = [], 0
    for m in _DOC_CODE.finditer(s):
        out += [_MARKUP.sub(r"\\\1", s[at:m.start()]), code(m.group(1).lstrip("~"))]
        at = m.end()
    return "".join(out + [_MARKUP.sub(r"\\\1", s[at:])])


def code(s: Any) -> str:
    """``s`` as inline code (a backtick inside is doubled around)."""
    s = " ".join(str(s).split())
    return f"`` {s} ``" if "`" in s else f"`{s}`"


def table(header: list[str], rows: list[list[str]]) -> str:
    """A Markdown table; cells are Markdown already (escaped by the caller)."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_cell(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def _cell(markdown: str) -> str:
    """A table cell: a ``|`` not escaped yet (one in inline code) escaped, so it does
    not end the cell."""
    return re.sub(r"(?<!\\)\|", r"\\|", markdown) or " "


def number(x: float) -> str:
    """A library value as the pages print it (6 significant digits)."""
    return "–" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.6g}"


# ---------------------------------------------------------------------------
# Command line
# ---------------------------------------------------------------------------
def command_parsers() -> list[tuple[tuple[str, ...], argparse.ArgumentParser]]:
    """Every command that runs something (``("bench", "export")``) and its parser, in
    the parser's order."""
    from tactcad import cli
    from tactcad.commands.options import options_of

    return list(options_of(cli.build_parser()))


def _summary(parser: argparse.ArgumentParser, path: tuple[str, ...],
             top: argparse.ArgumentParser) -> str:
    """The one-line help a command has in its parent's list under ``top`` (else its
    description)."""
    parent = top
    for word in path[:-1]:
        parent = _subparsers(parent).choices[word]
    for choice in _subparsers(parent)._choices_actions:
        if choice.dest == path[-1] and choice.help:
            return choice.help
    return parser.description or ""


def _subparsers(parser: argparse.ArgumentParser) -> argparse._SubParsersAction:
    return next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))


def option_rows(parser: argparse.ArgumentParser) -> list[list[str]]:
    """One row per argument: its names, its value, its help (defaults expanded)."""
    formatter = parser._get_formatter()
    rows = []
    for action in parser._actions:
        if isinstance(action, argparse._HelpAction):
            continue
        names = ", ".join(code(s) for s in action.option_strings) or code(action.dest)
        if action.choices is not None:
            value = " \\| ".join(code(c) for c in action.choices)
        elif action.nargs == 0:
            value = ""
        else:
            metavar = formatter._format_args(action, action.dest.upper())
            value = code(metavar)
        if action.required or not action.option_strings:
            value = (value + " (required)").strip()
        help_text = formatter._expand_help(action) if action.help else ""
        if getattr(action, "renamed_to", None):  # an earlier name, hidden from --help
            help_text = (f"deprecated: the earlier name of {action.renamed_to}, still taken "
                         f"(a line on stderr says so); not shown by --help")
        rows.append([names, value, text(help_text)])
    return rows


def cli_markdown() -> str:
    """The command-line reference: every command, its usage and every option."""
    from tactcad import __version__, cli

    top = cli.build_parser()
    out = [f"Generated from the argument parser of tactcad {text(__version__)} when the site "
           "was built: each command with its usage and every option it takes. "
           "`tactcad COMMAND --help` prints the same.\n",
           table(["option", "value", "help"], option_rows(top))]
    for path, parser in command_parsers():
        words = " ".join(path)
        out.append(f"### `tactcad {words}`\n")
        summary = _summary(parser, path, top)  # the parser is built once: it costs ~50 ms
        out.append(text(summary) + "\n")
        if parser.description and parser.description != summary:
            out.append(text(parser.description) + "\n")
        usage = " ".join(parser.format_usage().split()).removeprefix("usage: ")
        out.append("Usage: " + code(usage) + "\n")
        out.append(table(["option", "value", "help"], option_rows(parser)))
    return "\n".join(out)


# ---------------------------------------------------------------------------
# Design, rigs and scenes files
# ---------------------------------------------------------------------------
def _section_of(annotation: Any) -> tuple[type[BaseModel] | None, bool]:
    """(the Section model a field holds, keyed by name?) or (None, False) for a value."""
    args = typing.get_args(annotation)
    origin = typing.get_origin(annotation)
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation, False
    if origin in (dict, typing.Mapping) and len(args) == 2 and isinstance(args[1], type) \
            and issubclass(args[1], BaseModel):
        return args[1], True
    if origin in (typing.Union, types.UnionType):
        for arg in args:
            model, keyed = _section_of(arg)
            if model is not None:
                return model, keyed
    return None, False


def _type_words(info: Any) -> str:
    """What a value is (number, integer, text, list ...) when its Limits do not say."""
    from tactcad.vocabulary.schema import _limits

    limits = _limits(info)
    if limits is not None:
        if limits.kind == "number":
            return "number, " + limits.text()
        if limits.kind == "integer":
            return f"integer, {limits.lo} ... {limits.hi}"
        if limits.kind == "text":
            return "one line of text"
        if limits.kind == "name":
            return "a name: 1-64 characters A-Z a-z 0-9 _ . -"
        if limits.kind == "choice" and _text_choices(info):  # written quoted, as TOML reads
            return "text, one of " + ", ".join(f'"{c}"' for c in _text_choices(info))
        return limits.unit
    ann = info.annotation
    words = {float: "number", int: "integer", str: "text", bool: "true or false"}
    for arg in (ann, *typing.get_args(ann)):
        if arg in words:
            return words[arg]
        if typing.get_origin(arg) in (list, tuple):
            return "a list"
        if typing.get_origin(arg) is dict or arg is dict:
            return "a table of any keys"
    return "a value"


def _text_choices(info: Any) -> tuple[str, ...]:
    """The texts a choice key takes (``typing.Literal`` of str), else ()."""
    for arg in (info.annotation, *typing.get_args(info.annotation)):
        if typing.get_origin(arg) is typing.Literal:
            values = typing.get_args(arg)
            return values if all(isinstance(v, str) for v in values) else ()
    return ()


def toml_value(value: Any) -> str:
    """``value`` as a TOML file writes it (a text quoted: ``shaft_class_mm = "10"``)."""
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _default_words(info: Any) -> str:
    if info.is_required():
        return "required"
    default = info.default
    if default is PydanticUndefined or default is None:
        return "optional"
    if isinstance(default, BaseModel):
        return "its keys' defaults"
    return code(toml_value(default)) if default not in ({}, []) else "empty"


def schema_keys(model: type[BaseModel], prefix: str = "") -> Iterator[tuple[str, Any, type | None]]:
    """Every key a file of ``model`` accepts, dotted (``element.web_thickness_mm``;
    a table of free names as ``scene.<name>``): (key, FieldInfo, the section model a
    table key holds or None for a value)."""
    for name, info in model.model_fields.items():
        key = f"{prefix}{name}"
        section, keyed = _section_of(info.annotation)
        if section is None:
            yield key, info, None
            continue
        yield key, info, section
        yield from schema_keys(section, f"{key}.<name>." if keyed else f"{key}.")


def _file_models() -> list[tuple[str, str, type[BaseModel], str]]:
    """(title, anchor, schema, the paper's example file of that kind)."""
    from tactcad.design.array_plan import DesignFile
    from tactcad.design.rig_plan import RigsFile
    from tactcad.design.scene_specs import ScenesFile

    from tactcad.products.silicon_die.design.die_file import DieFile

    return [("The design file", "design", DesignFile, "macro_array.toml"),
            ("rigs.toml", "rigs", RigsFile, "rigs.toml"),
            ("scenes.toml", "scenes", ScenesFile, "scenes.toml"),
            # the last column of a die's keys: the shipped 5 mm die's values
            ("A silicon die's design file (tactcad die --design)", "die", DieFile,
             "../grasper_jaw_5mm_mems/grasper_jaw_5mm_mems.toml")]


def example_values(file: str) -> tuple[dict[str, Any], dict[str, str]]:
    """The paper's example file (shipped as ``tactcad/examples/macro_array``): its values
    by dotted key and its ``[assumptions]``, the reason for each value the paper does
    not give."""
    import tomllib

    import tactcad

    path = Path(tactcad.__file__).parent / "examples" / "macro_array" / file
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    assumptions = {re.sub(r"\[\d+\]$", "", k): v for k, v in data.pop("assumptions", {}).items()}

    def flat(table: dict, prefix: str = "") -> Iterator[tuple[str, Any]]:
        for key, value in table.items():
            if isinstance(value, dict):
                yield from flat(value, f"{prefix}{key}.")
            else:
                yield prefix + key, value
    return dict(flat(data)), assumptions


def _example_cell(key: str, values: dict[str, Any], assumptions: dict[str, str]) -> str:
    if key not in values:
        return ""
    reason = assumptions.get(key)
    return code(values[key]) + (f": {text(reason)}" if reason else "")


def schema_markdown() -> str:
    """Every key of the three files, one table per section: type and range with
    unit, default, and the reason the schema declares."""
    from tactcad.vocabulary.schema import _limits

    out = ["Generated from the schema the validator reads when the site was built. Each "
           "key is written `section.key` (a table of names, such as the scenes, as "
           "`scene.<name>.key`); *range* is what the validator allows, with its unit, "
           "*default* what a file that leaves the key out gets, *reason* why the range "
           "is what it is, where the schema states one. A value outside its range is "
           "refused with the same range and reason (exit 2). The last column gives the "
           "value in the files of the paper's array (`hardware/macro_array`) and, for a "
           "value the paper does not give, the reason it was chosen (the files' "
           "`[assumptions]`).\n"]
    header = ["key", "range", "default", "reason", "the paper's array (why, where the paper is silent)"]
    for title, anchor, model, example in _file_models():
        values, assumptions = example_values(example)
        out.append(f"({anchor}-keys)=\n### {text(title)}\n")
        rows: list[list[str]] = []
        for key, info, section in schema_keys(model):
            if section is not None:
                if rows:
                    out.append(table(header, rows))
                    rows = []
                out.append(f"#### `[{key}]`\n")
                if section.__doc__ and "BaseModel" not in section.__doc__:
                    out.append(docstring(section.__doc__) + "\n")
                out.append(f"Table: {_default_words(info)}.\n")
                continue
            limits = _limits(info)
            rows.append([code(key), text(_type_words(info)), _default_words(info),
                         text(limits.why) if limits and limits.why else "",
                         _example_cell(key, values, assumptions)])
        if rows:
            out.append(table(header, rows))
    return "\n".join(out)


def jaw_file_rows() -> list[list[str]]:
    """One row per key of a lab's jaw file (``[grasper_jaw]``,
    :class:`tactcad.partlib.grasper_jaw.GrasperJawSection`): the key, whether the file must
    state it (:data:`tactcad.partlib.grasper_jaw.JAW_FILE_KEYS`: a key, or one of a pair),
    its range with its unit, what leaving it out gives, and its reason."""
    from tactcad.partlib.grasper_jaw import JAW_FILE_KEYS, GrasperJawSection
    from tactcad.vocabulary.schema import _limits

    required: dict[str, str] = {}
    for entry in JAW_FILE_KEYS:
        pair = entry if isinstance(entry, tuple) else (entry,)
        for key in pair:
            others = [code(k) for k in pair if k != key]
            required[key] = ("required" if not others
                             else "required: this or " + " or ".join(others))
    rows = []
    for key, info in GrasperJawSection.model_fields.items():
        limits = _limits(info)
        if key in required:
            left_out = "refused by its name" if required[key] == "required" else \
                "the other key of the pair"
        else:
            left_out = _default_words(info)
            if left_out == "optional":  # None: the class's, derived, or nothing
                said = limits.why if limits and limits.why else ""
                left_out = "as the reason says" if "left out" in said else "none"
        why = limits.why if limits and limits.why else ""
        rows.append([code(key), required.get(key, "optional"), text(_type_words(info)),
                     left_out, text(_jaw_file_reason(why, key in required))])
    return rows


def _jaw_file_reason(why: str, required: bool) -> str:
    """A ``[grasper_jaw]`` key's reason as a jaw file reads it: a key the file must state
    loses the schema's "left out: ..." clause, which holds for a design file's own
    ``[grasper_jaw]`` table (the class's value) and not for a jaw file (refused)."""
    if not required:
        return why
    return why.split("; left out:")[0].removesuffix(", left out")

def jaw_file_markdown() -> str:
    """A lab's own jaw file (``tactcad design --jaw FILE``, a die's ``die.jaw``): every key
    of its ``[grasper_jaw]`` table, whether it must be stated, its range and unit."""
    return ("Generated from the schema the validator reads (`[grasper_jaw]`) and the keys a "
            "jaw file must state (`tactcad.partlib.grasper_jaw.JAW_FILE_KEYS`). A jaw file "
            "holds one `[grasper_jaw]` table. A *required* key left out is refused by its "
            "name (a class's own jaw needs no file: `--jaw 5` or `--jaw 10`); of a pair, "
            "state one (both are taken where they agree). The trocar class is text, quoted as TOML writes it "
            "(`shaft_class_mm = \"5\"`); every size is a number in mm, the opening in "
            "degrees. A value outside its range is refused with the range and the reason "
            "(exit 2), every error of the file at once.\n\n"
            + table(["key", "must the file state it", "range", "left out", "reason"],
                    jaw_file_rows()))


# ---------------------------------------------------------------------------
# Registries and the material library
# ---------------------------------------------------------------------------
def export_kinds_markdown() -> str:
    """The export kinds (``--only`` words) in run order, from their registry."""
    from tactcad.export.kinds import EXPORT_KINDS

    rows = [[code(k.name), text(k.writes), "yes" if k.in_full_export else "only with --only",
             code(k.part_prefix) if k.part_prefix else ""] for k in EXPORT_KINDS.values()]
    return ("Generated from the registry `tactcad.export.kinds.EXPORT_KINDS`, in the order "
            "an export runs them.\n\n"
            + table(["kind (`--only`)", "writes", "in a full export", "one part (`--part`)"], rows))


def check_groups_markdown() -> str:
    """The check groups in run order, from their registry."""
    from tactcad.checks.groups import CHECK_GROUPS

    def runs_on(g) -> str:
        return "each scene" if g.per_scene else ("the export" if g.on_export else "the design")

    rows = [[code(g.name), text(g.checks), runs_on(g), code(g.suite)]
            for g in CHECK_GROUPS.values()]
    return ("Generated from the registry `tactcad.checks.groups.CHECK_GROUPS`, in the order "
            "`tactcad check` runs them.\n\n"
            + table(["group", "checks", "runs on", "JUnit suite"], rows))


def constructions_markdown() -> str:
    """The constructions (``[array] construction``), from their registry."""
    from tactcad.design.construction_registry import CONSTRUCTIONS, DEFAULT_CONSTRUCTION
    from tactcad.mechanics.crosstalk_ladder import construction_levels, verify_level

    def crosstalk(c) -> str:
        levels = ", ".join(code(n) for n in construction_levels(c.name)) or "none"
        used = verify_level(c.name)
        return levels + (f" (decoupling files and K_obj budget: {code(used)})" if used else
                         " (no decoupling files, manifest `left_out`)")

    rows = [[code(c.name) + (" (default)" if c.name == DEFAULT_CONSTRUCTION else ""),
             text(c.summary), ", ".join(code(k) for k in c.parts), text(c.scales_to_mm),
             "yes" if c.test_rigs else "none (no rigs file, no rig scenes)",
             crosstalk(c), code(c.module)] for c in CONSTRUCTIONS.values()]
    from tactcad.partlib.array.comb_sheet import CombSection
    from tactcad.vocabulary.schema import _limits

    comb_rows = [[code(f"comb.{key}"), text(_type_words(info)), _default_words(info),
                  text(_limits(info).why) if _limits(info) and _limits(info).why else ""]
                 for key, info, section in schema_keys(CombSection) if section is None]
    return ("Generated from the registry `tactcad.design.construction_registry.CONSTRUCTIONS`; "
            "a design file chooses one with `[array] construction`.\n\n"
            + table(["construction", "how the array is made", "part modules", "how small",
                     "test rigs", "crosstalk levels", "derivation"], rows)
            + "\n\nThe `monolithic-comb`'s table `[comb]` (in place of `[clamp]`; its "
            "`[element]` leaves out `base_height_mm` and `overall_length_mm`, which it derives):\n\n"
            + table(["key", "range", "default", "reason"], comb_rows))


def _sources(entry: Any) -> str:
    return "\n".join(f"- {code(field)}: {text(doc)}" for field, doc in entry.sources) + "\n"


def materials_markdown() -> str:
    """The material grades, strain gauges and force gauges, each value with its document."""
    from tactcad.vocabulary.force_gauge_catalogue import force_gauges
    from tactcad.vocabulary.material_library import material_grades, strain_gauges

    grades = material_grades()
    gauges = strain_gauges()
    out = ["Generated from `src/tactcad/data/materials.toml` when the site was built.\n",
           "### Material grades\n",
           table(["grade", "E MPa", "ν", "yield MPa", "fatigue MPa (cycles, R)", "density g/cm³",
                  "CTE ppm/K"],
                 [[code(g.name), number(g.youngs_modulus_MPa), number(g.poisson_ratio),
                   number(g.yield_strength_MPa),
                   f"{number(g.fatigue_strength_MPa)} ({number(g.fatigue_cycles)}, "
                   f"{number(g.fatigue_R_ratio)})", number(g.density_g_per_cm3),
                   number(g.cte_ppm_per_K)] for g in grades.values()])]
    for g in grades.values():
        out.append(f"#### `{g.name}`\n")
        out.append(text(g.description) + (f" (family: {text(g.family)})" if g.family else "")
                   + "\n")
        out.append(_sources(g))
    out.append("### Strain gauges\n")
    out.append(table(["gauge", "alloy", "R Ω", "gauge factor", "bridge", "max strain",
                      "fatigue strain (cycles)"],
                     [[code(s.name), text(s.alloy), number(s.resistance_ohm),
                       number(s.gauge_factor), text(s.bridge), number(s.max_strain),
                       f"{number(s.fatigue_strain)} ({number(s.fatigue_cycles)})"]
                      for s in gauges.values()]))
    for s in gauges.values():
        out.append(f"#### `{s.name}`\n")
        out.append(text(s.description) + "\n")
        out.append(_sources(s))
    out.append("### Force gauges of the rigs\n")
    out.append("Generated from `src/tactcad/data/force_gauges.toml`: the catalogue the rigs "
               "made for a design take their gauge from (`tactcad.studies.rig_sizing`).\n")
    out.append(table(["model", "maker", "range N", "resolution N", "stiffness N/mm", "source"],
                     [[code(g.model), text(g.maker), number(g.range_N), number(g.resolution_N),
                       number(g.stiffness_N_per_mm), text(g.source)] for g in force_gauges()]))
    return "\n".join(out)


#: Sheets (mm) at which the processes page states each rule's figure.
PROCESS_SHEETS_MM = (0.1, 0.3, 1.0)


def processes_markdown() -> str:
    """The cut processes a design chooses from (``[element] process``), from their
    registry: sheet range, each rule's figure at :data:`PROCESS_SHEETS_MM` (wire
    EDM at the paper design's 0.25 mm wire and 0.025 mm spark gap), the rule and
    its source, the shop file, tabs, cut order and surface."""
    from tactcad.design.array_plan import EdmRules
    from tactcad.vocabulary.process import CUT_PROCESSES, DEFAULT_CUT_PROCESS

    wire = EdmRules(0.25, 0.025, 0.8)
    out = ["Generated from the registry `tactcad.vocabulary.process.CUT_PROCESSES`. A design "
           f"chooses its elements' process with `[element] process` (`{DEFAULT_CUT_PROCESS}` "
           "when left out); the `process` check group holds every cut part to its rules and "
           "the DXF kind writes what its shop receives. The figures are vendors' design-guide "
           "values, to confirm with the shop.\n"]
    for p in CUT_PROCESSES.values():
        lo, hi = p.sheet_range_mm
        out.append(f"### `{p.name}`\n")
        out.append(f"{text(p.text)}; sheet {number(lo)}-{number(hi)} mm ({text(p.sheet_source)}).\n")
        sheets = [t for t in PROCESS_SHEETS_MM if lo <= t <= hi] or [lo]
        limits = [p.limits(t, wire, "stainless steel") for t in sheets]
        rows = [[code(name)] + [number(lim.figures()[name].value_mm) for lim in limits]
                + [text(fig.rule), text(fig.source)]
                for name, fig in limits[0].figures().items()]
        out.append(table(["figure"] + [f"{number(t)} mm sheet" for t in sheets]
                         + ["rule", "source"], rows))
        shop = p.shop
        out.append(f"Shop file: {text(shop.kind)}"
                   + ("; outline offset by the compensation" if shop.offset_outline else "")
                   + (f"; holding tabs (layer `TAB`): {text(shop.tabs.text())} "
                      f"({text(shop.tabs.source)})" if shop.tabs else "; no tabs")
                   + ".\n")
        if shop.cut_order:
            out.append("Cut order: " + "; ".join(text(s) for s in shop.cut_order) + ".\n")
        out.append("Notes: " + " ".join(text(n) for n in shop.notes) + "\n")
        out.append(f"Surface: {text(p.surface)}.\n")
    return "\n".join(out)


#: The generated pages: file name -> the function that writes it.
PAGES = {"cli.md": cli_markdown, "schema.md": schema_markdown,
         "jaw_file.md": jaw_file_markdown,
         "export_kinds.md": export_kinds_markdown, "check_groups.md": check_groups_markdown,
         "processes.md": processes_markdown, "constructions.md": constructions_markdown,
         "materials.md": materials_markdown}


def write_pages(folder: Path) -> list[Path]:
    """Write every generated page into ``folder`` (a page whose text is unchanged is
    left alone, so Sphinx does not read its includers again)."""
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for name, make in PAGES.items():
        path = folder / name
        content = make()
        if not path.is_file() or path.read_text(encoding="utf-8") != content:
            path.write_text(content, encoding="utf-8")
        written.append(path)
    return written


def _on_builder_inited(app) -> None:
    write_pages(Path(app.srcdir) / "_generated")


def setup(app):
    app.connect("builder-inited", _on_builder_inited)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
