"""The generated reference says what the code does: every command and option the
parser knows, every key the validator accepts (found by asking the validator,
not the schema walk that writes the page), the registries and the library;
and every command line of the pages and README names a real command."""

from __future__ import annotations

import argparse
import re
import tomllib

import pytest

from doc_pages import DOCS, README, ROOT, pages, reference_extension
from tactcad import cli
from tactcad.design.array_plan import DesignFile
from tactcad.design.rig_plan import RigsFile
from tactcad.design.scene_specs import ScenesFile
from tactcad.vocabulary.schema import Problems, validate

REF = reference_extension()
UNKNOWN = "zz_not_a_key"


def leaf_commands(parser: argparse.ArgumentParser, path=()):
    """(words, parser) of every command that runs something, walked here on argparse's own
    structures (not with the helper the page is written from)."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield path, parser
    for sub in subs:
        for name, child in sub.choices.items():
            yield from leaf_commands(child, (*path, name))


def sections_of(markdown: str, heading: str) -> dict[str, str]:
    """Text under each ``heading`` line (``### `tactcad export```) up to the next one."""
    parts = re.split(rf"^{re.escape(heading)}(.+)$", markdown, flags=re.M)
    return {parts[i].strip(): parts[i + 1] for i in range(1, len(parts) - 1, 2)}


# --- the command line -------------------------------------------------------------------------
def test_cli_reference_lists_every_command_and_option():
    page = REF.cli_markdown()
    documented = sections_of(page, "### ")
    leaves = [path for path, _ in leaf_commands(cli.build_parser()) if path]
    assert len(leaves) >= 20
    for path, parser in leaf_commands(cli.build_parser()):
        if not path:
            continue
        title = f"`tactcad {' '.join(path)}`"
        assert title in documented, f"{title} missing from the command reference"
        options = {s for a in parser._actions for s in a.option_strings} - {"-h", "--help"}
        cells = set(re.findall(r"`(-[-\w]+)`", documented[title]))
        assert options <= cells, f"{title}: options missing: {sorted(options - cells)}"
        positionals = {a.dest for a in parser._actions if not a.option_strings}
        assert positionals <= cells | set(re.findall(r"`(\w+)`", documented[title])), title
    assert set(documented) == {f"`tactcad {' '.join(p)}`" for p in leaves}  # nothing stale


def test_help_lists_the_commands_the_reference_has():
    """`tactcad --help` and the reference name the same top-level commands."""
    helptext = cli.build_parser().format_help()
    listed = set(re.findall(r"^    ([a-z][a-z0-9-]*)\s", helptext, re.M))
    documented = {t.split()[1].strip("`") for t in sections_of(REF.cli_markdown(), "### ")}
    assert listed and listed == documented


# --- the design, rigs and scenes files ----------------------------------------------------------
def accepted_keys(model, path: tuple[str, ...]) -> set[str]:
    """The keys the validator accepts in the table at ``path``, read from its refusal of
    an unknown key (``allowed keys a, b, c``; at the top ``allowed sections ...``)."""
    table: dict = {UNKNOWN: 1}
    for part in reversed(path):
        table = {part: table}
    problems = Problems("x.toml")
    validate(model, table, problems)
    wanted = ".".join((*path, UNKNOWN))
    refusal = next(e for e in problems.errors if e.field == wanted)
    return set(re.sub(r"^(keys|sections) ", "", refusal.allowed).split(", "))


def documented_tables(model) -> dict[tuple[str, ...], set[str]]:
    """Each table of the reference (``("scene", "<name>")``) with the keys it lists."""
    out: dict[tuple[str, ...], set[str]] = {(): set()}
    for key, _, _ in REF.schema_keys(model):
        *table, name = key.split(".")
        out.setdefault(tuple(table), set()).add(name)
    return out


@pytest.mark.parametrize("model", [DesignFile, RigsFile, ScenesFile], ids=lambda m: m.__name__)
def test_schema_reference_lists_every_key_the_validator_accepts(model):
    page = REF.schema_markdown()
    tables = documented_tables(model)
    assert len(tables) > 3
    for table, keys in tables.items():
        asked = tuple("x" if t == "<name>" else t for t in table)  # a table of free names
        assert keys == accepted_keys(model, asked), table
        for name in keys:
            dotted = ".".join((*table, name))
            assert f"`{dotted}`" in page or f"`[{dotted}]`" in page, dotted


def flat_keys(data: dict, prefix: str = "") -> set[str]:
    out = set()
    for key, value in data.items():
        out.add(prefix + key)
        if isinstance(value, dict):
            out |= flat_keys(value, f"{prefix}{key}.")
    return out


@pytest.mark.parametrize("file", ["macro_array/macro_array.toml", "macro_array/rigs.toml",
                                  "macro_array/scenes.toml", "ti_array_2x3/ti_array_2x3.toml",
                                  "grasper_jaw_5mm_mems/grasper_jaw_5mm_mems.toml"])
def test_every_key_of_the_shipped_files_is_in_the_reference(file):
    """The shipped examples' keys, as written (scene names as ``<name>``, the free
    ``[assumptions]`` keys left out)."""
    page = REF.schema_markdown()
    listed = set(re.findall(r"^\| `([^`]+)` \|", page, re.M)) | \
        set(re.findall(r"^#### `\[([^\]]+)\]`", page, re.M))
    documented = {".".join(k.split(".")[:n]) for k in listed for n in range(1, k.count(".") + 2)}
    data = tomllib.loads((ROOT / "hardware" / file).read_text(encoding="utf-8"))
    keys = {re.sub(r"^scene\.[^.]+", "scene.<name>", k) for k in flat_keys(data)
            if not k.startswith("assumptions.")}
    assert keys - {"assumptions"} <= documented, sorted(keys - documented)


def test_the_jaw_file_table_lists_every_key_and_what_a_jaw_file_must_state():
    """A lab's jaw file: every ``[grasper_jaw]`` key the validator accepts, each one a jaw
    file must state marked required (found by leaving it out of a jaw file), the trocar
    class quoted as TOML takes it, its unit on each size."""
    from tactcad.partlib.grasper_jaw import GrasperJawSection, missing_jaw_file_keys

    page = REF.jaw_file_markdown()
    rows = {m.group(1): m.group(2) for m in re.finditer(r"^\| `([^`]+)` \| ([^|]+) \|",
                                                         page, re.M)}
    assert set(rows) == accepted_keys(DesignFile, ("grasper_jaw",))
    must = {k for one in missing_jaw_file_keys({}) for k in one.split(" or ")}
    assert {k for k, said in rows.items() if said.startswith("required")} == must
    assert {"pin_inset_mm", "opening_angle_deg"} <= must
    for key in must:  # refused when left out: the table says nothing else of leaving it out
        line = next(x for x in page.splitlines() if x.startswith(f"| `{key}` |"))
        assert "left out:" not in line.replace("\\", ""), line
    assert 'one of \\"5\\"\\, \\"10\\"' in page  # text: shaft_class_mm = "5"
    for key in GrasperJawSection.model_fields:
        line = next(x for x in page.splitlines() if x.startswith(f"| `{key}` |"))
        assert key in ("material", "shaft_class_mm") or re.search(r"\bmm\b|degrees", line), line
    schema = REF.schema_markdown()
    assert '| `grasper_jaw.shaft_class_mm` |' in schema and '`"10"`' in schema


# --- registries and the library -----------------------------------------------------------------
def test_export_kinds_check_groups_and_library_are_listed():
    from tactcad.checks.groups import CHECK_GROUPS
    from tactcad.export.kinds import EXPORT_KINDS
    from tactcad.vocabulary.force_gauge_catalogue import force_gauges
    from tactcad.vocabulary.material_library import material_grades, strain_gauges

    kinds, groups, library = (REF.export_kinds_markdown(), REF.check_groups_markdown(),
                              REF.materials_markdown())
    assert all(f"| `{k}` |" in kinds for k in EXPORT_KINDS) and len(EXPORT_KINDS) >= 8
    assert all(f"| `{g}` |" in groups for g in CHECK_GROUPS) and len(CHECK_GROUPS) >= 5
    for name, grade in material_grades().items():
        assert f"#### `{name}`" in library and f"| `{name}` | {grade.youngs_modulus_MPa:.6g} |" \
            in library
    assert all(f"#### `{name}`" in library for name in strain_gauges())
    assert all(f"| `{g.model}` | " in library for g in force_gauges()) and len(force_gauges()) >= 2


def test_every_cut_process_is_listed_with_its_sources():
    from tactcad.vocabulary.process import CUT_PROCESSES

    page = REF.processes_markdown()
    for name, process in CUT_PROCESSES.items():
        assert f"### `{name}`" in page
        assert all(REF.text(s) in page for s in process.sources), name
    assert "| `compensation_per_side_mm` |" in page and "| `min_web_mm` |" in page


def test_free_text_is_escaped_not_read_as_markup():
    assert REF.text("drawings/<part>.svg | *x*") == r"drawings\/\<part\>\.svg \| \*x\*"
    assert REF.table(["a"], [[REF.code("x|y")], [REF.text("p|q")]]).splitlines()[2:] == \
        [r"| `x\|y` |", r"| p\|q |"]


# --- command lines of the pages and README ------------------------------------------------------
def test_command_lines_of_the_pages_name_real_commands():
    """Command lines in code blocks and inline code (``tactcad COMMAND``) of every page
    and README."""
    commands = {path[0] for path, _ in leaf_commands(cli.build_parser()) if path}
    used = set()
    for text in [p.read_text(encoding="utf-8") for p in pages()] + [README.read_text("utf-8")]:
        for block in re.findall(r"^```[a-z]*\n(.*?)^```", text, re.S | re.M):
            used |= set(re.findall(r"(?:^|&& |^\$ )(?:\.\.?/)*(?:\./)?tactcad ([a-z][\w-]*)",
                                   block, re.M))
        used |= set(re.findall(r"`(?:\./)?tactcad ([a-z][\w-]*)", text))
    assert len(used) > 20 and used <= commands, sorted(used - commands)


def test_readme_fits_a_screen_and_starts_with_the_two_commands():
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 150
    first_block = re.search(r"```sh\n(.*?)```", text, re.S).group(1).splitlines()
    assert first_block[0].startswith("make export") and first_block[1].startswith("make test")
    assert text.index("```sh") < text.index("\n## ")  # at the top, before any section
    assert "make docs" in text and "docs/" in text


def test_every_page_is_in_the_site():
    """Each hand-written page is reachable from a toctree (Sphinx warns otherwise too)."""
    listed = set()
    for page in pages():
        for block in re.findall(r"```\{toctree\}\n(.*?)```", page.read_text(encoding="utf-8"),
                                re.S):
            for line in block.splitlines():
                if line and not line.startswith(":"):
                    listed.add((page.parent / f"{line}.md").resolve())
    assert {p.resolve() for p in pages() if p.name != "index.md" or p.parent != DOCS} <= listed


# --- the API page's examples ------------------------------------------------------------------
def test_the_api_pages_examples_run():
    """The docstring examples (``>>>``) of every module the API page documents run as shown."""
    import doctest
    import importlib

    page = (DOCS / "reference" / "api.md").read_text(encoding="utf-8")
    targets = re.findall(r"^\.\. auto(?:module|class|function|method):: ([\w.]+)", page, re.M)

    def module_of(target: str) -> str:
        """The module a documented name lives in (``a.b.Class.method`` -> ``a.b``)."""
        while True:
            try:
                importlib.import_module(target)
                return target
            except ModuleNotFoundError:
                target = target.rsplit(".", 1)[0]

    modules = {module_of(t) for t in targets}
    assert {"tactcad.api", "tactcad.errors"} <= modules
    attempted = 0
    for name in sorted(modules):
        result = doctest.testmod(importlib.import_module(name),
                                 optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
        assert result.failed == 0, name
        attempted += result.attempted
    assert attempted >= 4


# --- the Python page's quoted refusals -----------------------------------------------------------
def test_the_python_pages_quoted_refusals_are_what_the_api_raises(tmp_path, monkeypatch):
    """Each "`CALL` raises `MESSAGE`" of docs/how-to/python.md: CALL, run with ``die`` a
    die's project (the shipped die's file as ``die.toml``), raises exactly MESSAGE."""
    import shutil

    import tactcad
    from tactcad.errors import TactcadError

    text = " ".join((DOCS / "how-to" / "python.md").read_text(encoding="utf-8").split())
    quoted = re.findall(r"`([^`]+\))` raises `([^`]+)`", text)
    assert len(quoted) >= 2, quoted  # the page was read: the die's grasp and its load's set
    shutil.copy(ROOT / "hardware" / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml",
                tmp_path / "die.toml")
    monkeypatch.chdir(tmp_path)
    names = {"tactcad": tactcad, "die": tactcad.load("die.toml")}
    for call, message in quoted:
        with pytest.raises(TactcadError) as err:
            eval(call, names)  # noqa: S307 (the page's own example call)
        assert str(err.value) == message, call
