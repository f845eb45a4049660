"""One schema mechanism for the three design files (design, rigs, scenes).

Each file is a pydantic v2 model of sections (:class:`Section`: unknown keys
refused, strict types: no bool for a number, no text for a number, finite
numbers only). A field's static range and its physical reason are declared
once, with :func:`number` / :func:`integer`, and the same declaration writes
the message when a value falls outside it. Rules that tie fields together
(a range that depends on another field) run after the types are known and
add to the same list (:class:`Problems`), so one pass reports every error,
each as ``file: field = value: allowed ... (reason)``.

Also here, one copy each: reading a TOML file, the content hash, number
formatting and the ``[assumptions]`` table.

Units: mm, N, MPa, N/mm, g as each field's name says.
"""

from __future__ import annotations

import copy
import functools
import hashlib
import json
import re
import tomllib
import types
import typing
import unicodedata
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Annotated, Any, Mapping

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, ValidationError
from pydantic.fields import FieldInfo

from tactcad.errors import UNKNOWN_SECTION, DesignError, DesignErrors

#: Deepest nesting of arrays/tables a design file may have; deeper input is
#: refused before it reaches a recursive reader.
MAX_NESTING = 16
#: Safe names for designs and scenes: they end up in file names, DXF headers and SVG.
NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,63}$"
NAME_ALLOWED = "1-64 characters A-Z a-z 0-9 _ . -, starting with a letter or digit"
#: Letters NFKD does not take apart, spelt in ASCII for a suggested name.
ASCII_SPELLING = {"ø": "o", "Ø": "O", "æ": "ae", "Æ": "AE", "œ": "oe", "Œ": "OE", "ß": "ss",
                  "đ": "d", "Đ": "D", "ł": "l", "Ł": "L", "þ": "th", "Þ": "Th"}


def suggested_name(text: str, fallback: str = "sensor") -> str:
    """A name of :data:`NAME_PATTERN` close to ``text`` for a user to paste: accents
    dropped (``ü`` -> ``u``), every other character outside the allowed ones (a space,
    say) an ``_``, cut to 64 characters.

    Args:
        text: the name asked for.
        fallback: the name when nothing of ``text`` is left.

    Returns:
        A name :data:`NAME_PATTERN` matches.
    """
    spelt = "".join(ASCII_SPELLING.get(c, c) for c in text)
    folded = unicodedata.normalize("NFKD", spelt).encode("ascii", "ignore").decode()
    name = re.sub(r"[^A-Za-z0-9_.-]+", "_", folded).strip("_.-")[:64].rstrip("_.-")
    return name if re.fullmatch(NAME_PATTERN, name) else fallback
#: Closed limits that depend on other fields are met within this much (mm), so a
#: value equal to its limit in decimals is not refused for binary rounding.
LIMIT_TOLERANCE_MM = 1e-9
#: Longest free text (descriptions, materials, models) in characters.
MAX_TEXT = 500


def copy_tables(tables: Any) -> Any:
    """A copy of a design file's tables (TOML: tables, arrays and scalars) that shares
    nothing mutable with them: every table and array copied, scalars as they are. Four
    times faster than :func:`copy.deepcopy` on a design's tables, which the design searches
    copy for every candidate they try.

    Args:
        tables: a table (dict), an array (list or tuple) or a scalar.

    Returns:
        The copy (dicts, lists and sets new; tuples new where they hold a table or array).
    """
    kind = type(tables)
    # a scalar entry is taken as it is without a call for it: most entries are scalars,
    # and a call each was half the copy's time
    if kind is dict:
        return {k: v if type(v) in _SCALARS else copy_tables(v) for k, v in tables.items()}
    if kind is list:
        return [v if type(v) in _SCALARS else copy_tables(v) for v in tables]
    if kind in _SCALARS:
        return tables
    if kind is tuple:
        return tuple(v if type(v) in _SCALARS else copy_tables(v) for v in tables)
    return copy.deepcopy(tables)  # anything else TOML does not make: copied as it was


#: The scalar types :func:`copy_tables` shares rather than copies (immutable).
_SCALARS = frozenset((str, int, float, bool, type(None)))


def fmt(x: float) -> str:
    """A number as the messages and reasons print it (6 significant digits)."""
    return f"{x:.6g}"


def name_number(x: float) -> str:
    """A number as part and file names carry it: ``%g`` with ``p`` for the decimal point
    (1.5 -> ``1p5``), since STEP labels, DXF and file names keep no dots."""
    return f"{x:g}".replace(".", "p")


# ---------------------------------------------------------------------------
# Field declarations
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Limits:
    """A field's static range, its unit and the physical reason, kept as
    pydantic metadata so that a refusal can be worded from it."""

    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    unit: str = "mm"
    why: str = ""
    kind: str = "number"  # number, integer, text, file, name, choice, list, described

    def text(self) -> str:
        """The allowed range in words, e.g. ``0.15 <= value <= 0.4 mm``."""
        return range_text(self.lo, self.hi, self.lo_open, self.hi_open, self.unit)


def range_text(lo: float | None, hi: float | None, lo_open: bool = False, hi_open: bool = False,
               unit: str = "mm") -> str:
    """``lo <= value <= hi unit`` with ``<`` for open ends; one-sided when a bound is None."""
    u = f" {unit}" if unit else ""
    if lo is not None and hi is not None:
        return f"{fmt(lo)} {'<' if lo_open else '<='} value {'<' if hi_open else '<='} {fmt(hi)}{u}"
    if lo is not None:
        return f"value {'>' if lo_open else '>='} {fmt(lo)}{u}"
    if hi is not None:
        return f"value {'<' if hi_open else '<='} {fmt(hi)}{u}"
    return "a finite number"


def number(lo: float | None = None, hi: float | None = None, *, lo_open: bool = False,
           hi_open: bool = False, unit: str = "mm", why: str = "") -> Any:
    """A finite float field in ``[lo, hi]`` (open ends as asked). Integers are
    taken as numbers; booleans and text are not."""
    bounds: dict[str, float] = {}
    if lo is not None:
        bounds["gt" if lo_open else "ge"] = lo
    if hi is not None:
        bounds["lt" if hi_open else "le"] = hi
    return Annotated[float, Field(**bounds), Limits(lo, hi, lo_open, hi_open, unit, why)]


def integer(lo: int, hi: int, why: str = "") -> Any:
    """An integer field in ``lo ... hi`` (booleans refused)."""
    return Annotated[int, Field(ge=lo, le=hi), Limits(lo, hi, unit="", why=why, kind="integer")]


#: One line of printable text with something in it: texts end up in DXF headers,
#: SVG drawings and the BOM, where a newline or control character breaks the file.
TEXT_PATTERN = r"^[^\x00-\x1f\x7f]*[^\x00-\x1f\x7f\s][^\x00-\x1f\x7f]*$"
Text = Annotated[str, Field(min_length=1, max_length=MAX_TEXT, pattern=TEXT_PATTERN),
                 Limits(kind="text", unit="")]
Name = Annotated[str, Field(pattern=NAME_PATTERN), Limits(kind="name", unit="")]

#: What a character that ``str.isprintable`` refuses is, by Unicode general category.
_UNPRINTABLE_KINDS = {"Cc": "a control character", "Cf": "an invisible format character",
                      "Cs": "a surrogate", "Co": "a private-use character",
                      "Cn": "an unassigned code point", "Zs": "a space other than U+0020",
                      "Zl": "a line separator", "Zp": "a paragraph separator"}


def unprintable(text: str) -> str | None:
    """The first character of ``text`` that does not print as itself
    (``str.isprintable``: controls, invisible format characters such as U+200B,
    U+202E or U+FEFF, spaces other than U+0020 such as U+00A0, surrogates,
    private-use and unassigned code points such as U+FFFF), or None."""
    return next((c for c in text if not c.isprintable()), None)


def unprintable_text(char: str) -> str:
    """``U+200B, an invisible format character``: a refused character as a message names it."""
    kind = _UNPRINTABLE_KINDS.get(unicodedata.category(char), "a character that does not print")
    return f"U+{ord(char):04X}, {kind}"


def _printable(text: str) -> str:
    if unprintable(text) is not None:
        raise ValueError("a character that does not print")
    return text


#: A file name (relative path) of the project, e.g. ``[files] rigs``: one line of
#: printable characters, so that the name a user reads is the name on disk.
FileName = Annotated[str, Field(min_length=1, max_length=MAX_TEXT, pattern=TEXT_PATTERN),
                     AfterValidator(_printable), Limits(kind="file", unit="")]
FILE_NAME_ALLOWED = f"a file name of 1 ... {MAX_TEXT} printable characters, not all spaces"
#: A calendar date, ISO 8601 ``YYYY-MM-DD`` (a design revision's date).
DateText = Annotated[str, Field(pattern=r"^[0-9]{4}-(0[1-9]|1[0-2])-(0[1-9]|[12][0-9]|3[01])$"),
                     Limits(kind="choice", unit="a date YYYY-MM-DD (ISO 8601)")]


class Section(BaseModel):
    """One ``[section]`` of a design file: unknown keys refused, strict types,
    finite numbers, immutable."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


# ---------------------------------------------------------------------------
# Errors: pydantic's, worded the tactcad way, plus the cross-field rules'
# ---------------------------------------------------------------------------
class Problems:
    """Collects every refusal of one validation pass.

    Cross-field rules call :meth:`add` or :meth:`within`; :meth:`raise_if_any`
    raises one :class:`DesignErrors` listing them all.
    """

    def __init__(self, file: str = ""):
        self.file = file
        self.errors: list[DesignError] = []

    def __bool__(self) -> bool:
        return bool(self.errors)

    def add(self, field: str, value: Any, allowed: str, why: str = "", file: str | None = None) -> None:
        """One refusal; ``file`` names another file than this pass's (a design
        field that makes a rig impossible)."""
        self.errors.append(DesignError(field, value, allowed, why, self.file if file is None else file))

    def extend(self, errors: list[DesignError]) -> None:
        self.errors.extend(errors)

    def within(self, field: str, value: float, lo: float | None = None, hi: float | None = None,
               *, lo_open: bool = False, hi_open: bool = False, unit: str = "mm",
               why: str = "") -> float:
        """Record a refusal when ``value`` leaves the range; return ``value`` either way
        (so that later rules still see a number)."""
        # closed limits computed from other fields allow for rounding (0.7 - 0.2 < 0.5)
        low = lo is not None and (value <= lo if lo_open else value < lo - LIMIT_TOLERANCE_MM)
        high = hi is not None and (value >= hi if hi_open else value > hi + LIMIT_TOLERANCE_MM)
        if low or high:
            self.add(field, value, range_text(lo, hi, lo_open, hi_open, unit), why)
        return value

    def raise_if_any(self) -> None:
        if self.errors:
            raise DesignErrors(self.errors)


def _limits(info: Any) -> Limits | None:
    """The :class:`Limits` of a field (FieldInfo) or of a type, looking inside
    ``Annotated`` and ``Optional``."""
    if isinstance(info, FieldInfo):
        found = [m for m in info.metadata if isinstance(m, Limits)]
        return found[0] if found else _limits(info.annotation)
    origin = typing.get_origin(info)
    if origin is Annotated:
        found = [m for m in typing.get_args(info)[1:] if isinstance(m, Limits)]
        return found[0] if found else None
    if origin in (typing.Union, types.UnionType):
        for arg in typing.get_args(info):
            found = _limits(arg)
            if found is not None:
                return found
    return None


def _field_at(model: type[BaseModel], loc: tuple) -> tuple[str, Limits | None, type | None]:
    """Dotted field name (list items as ``[n]``, 1-based) and the declaration at ``loc``."""
    name, limits, cls, ann = "", None, model, None
    for part in loc:
        if isinstance(part, int):
            name += f"[{part + 1}]"
            item_type = _list_item(ann) if ann is not None else None
            if item_type is not None:  # a list of lists: the next index reads this item's
                limits = _limits(item_type) or limits
                ann = item_type
            continue
        name = f"{name}.{part}" if name else str(part)
        fields = getattr(cls, "model_fields", {}) if cls is not None else {}
        info = fields.get(part)
        if info is None:
            cls, ann, limits = None, None, None
            continue
        ann = info.annotation
        limits = _limits(info)
        origin = typing.get_origin(ann)
        if isinstance(ann, type) and issubclass(ann, BaseModel):
            cls = ann
        elif origin in (dict, Mapping) and issubclass(typing.get_args(ann)[1], BaseModel):
            cls = _KeyedModel(typing.get_args(ann)[1])
        else:
            cls = None
    return name, limits, cls


def field_limits(model: type[BaseModel], key: str) -> Limits | None:
    """The declared :class:`Limits` of a dotted key (``element.web_thickness_mm``) of
    ``model``.

    Args:
        model: the file's model. key: the dotted key, as ``--set`` names it.

    Returns:
        The key's limits; None when ``model`` has no such key or it declares none.
    """
    parts = tuple(key.split("."))
    fields = model.model_fields.get(parts[0]) if parts else None
    if fields is None:
        return None
    _, limits, _ = _field_at(model, parts)
    return limits


def _list_item(ann: Any) -> Any:
    """The item type of a list field's annotation, through ``Optional`` and ``Annotated``
    (``list[float]`` -> ``float``); None when ``ann`` is no list."""
    origin = typing.get_origin(ann)
    if origin is Annotated:
        return _list_item(typing.get_args(ann)[0])
    if origin in (typing.Union, types.UnionType):
        found = [_list_item(a) for a in typing.get_args(ann) if a is not type(None)]
        return next((f for f in found if f is not None), None)
    if origin in (list, tuple):
        args = typing.get_args(ann)
        return args[0] if args else None
    return None


class _KeyedModel:
    """Stand-in for ``dict[str, Model]``: any key leads to ``Model``'s fields."""

    def __init__(self, model: type[BaseModel]):
        self.model_fields = _AnyKey(model)


class _AnyKey(dict):
    def __init__(self, model: type[BaseModel]):
        super().__init__()
        self.model = model

    def get(self, key, default=None):
        return FieldInfo(annotation=self.model)


def _keys_of(model: type[BaseModel] | None) -> str:
    return ", ".join(model.model_fields) if model is not None and hasattr(model, "model_fields") \
        and not isinstance(model.model_fields, _AnyKey) else ""


def _allowed_words(limits: Limits) -> str:
    """A field's allowed values in the words its refusal of a wrong value uses (a missing
    key is refused with them too)."""
    if limits.kind == "text":
        return f"one line of text, 1 ... {MAX_TEXT} characters, no control characters"
    if limits.kind == "file":
        return FILE_NAME_ALLOWED
    if limits.kind == "name":
        return NAME_ALLOWED
    if limits.kind in ("choice", "list", "described"):
        return limits.unit
    if limits.kind == "integer":
        return f"an integer {limits.lo} ... {limits.hi}"
    return limits.text()


def wording(err: Mapping[str, Any], model: type[BaseModel], file: str) -> DesignError:
    """One pydantic error as a :class:`DesignError` with field, value, allowed range, reason."""
    loc = tuple(err["loc"])
    field, limits, section = _field_at(model, loc)
    value = err.get("input")
    kind = err["type"]
    why = limits.why if limits else ""
    if kind == "missing":  # a whole table, or one key of a table: what it may hold
        wanted = (f"a [{field}] table" if section is not None else
                  _allowed_words(limits) if limits is not None else "a value")
        return DesignError(field, None, wanted, "missing", file)
    if kind == "extra_forbidden":
        parent_name, _, parent = _field_at(model, loc[:-1]) if len(loc) > 1 else ("", None, model)
        keys = _keys_of(parent)
        if len(loc) == 1:
            return DesignError(field, "<table>" if isinstance(value, Mapping) else value,
                               "sections " + keys, UNKNOWN_SECTION, file)
        return DesignError(field, value, "keys " + keys if keys else "known keys", "unknown key",
                           file)
    if kind in ("model_type", "dict_type"):  # a table's place holds a value
        keys = _keys_of(section)
        return DesignError(field, value, f"the table [{field}]" + (f" of keys {keys}" if keys else ""),
                           why, file)
    if limits is None:
        return DesignError(field, value, err["msg"].lower().replace("input should be ", ""), why,
                           file)
    if limits.kind == "text":
        return DesignError(field, value, f"one line of text, 1 ... {MAX_TEXT} characters, no control "
                           "characters", why or "texts end up in DXF headers, drawings and the BOM",
                           file)
    if limits.kind == "file":
        bad = unprintable(value) if isinstance(value, str) else None
        found = f" (found {unprintable_text(bad)})" if bad is not None else ""
        return DesignError(field, value, FILE_NAME_ALLOWED + found,
                           why or "the name a user reads must be the file's name on disk", file)
    if limits.kind == "name":
        cleaned = suggested_name(str(value))
        # to paste as the design file writes it; a --set of the key turns it into that option
        # (DesignErrors.sourced)
        return DesignError(field, value, f"{NAME_ALLOWED}, e.g. {cleaned}",
                           "names end up in file names, DXF headers and drawings", file,
                           alternatives=[{"option": f'{field} = "{cleaned}"',
                                          "words": "the name with accents dropped and other "
                                                   "characters as _"}])
    if limits.kind == "choice":
        if not isinstance(value, str) and not isinstance(value, bool) \
                and f"{value}" in limits.unit.removeprefix("one of ").split(", "):
            # 10 for "10": the names are text, so say how to write the one meant
            return DesignError(field, value, limits.unit + " as text",
                               f'write {field.rsplit(".", 1)[-1]} = "{value}"', file)
        return DesignError(field, value, limits.unit, why, file)
    if limits.kind in ("list", "described"):  # the allowed values in words
        return DesignError(field, value, limits.unit, why, file)
    if limits.kind == "integer":
        if kind in ("greater_than_equal", "less_than_equal"):
            return DesignError(field, value, f"{limits.lo} ... {limits.hi}", why, file)
        return DesignError(field, value, f"an integer {limits.lo} ... {limits.hi}", why, file)
    allowed = limits.text()
    if kind in ("float_type", "finite_number", "float_parsing", "int_type"):
        allowed = "a finite number, " + allowed
    return DesignError(field, value, allowed, why, file)


def choice(options: Mapping[str, Any] | tuple[str, ...], why: str = "") -> Any:
    """A text field naming one of ``options`` (e.g. a bolt size of a standard)."""
    names = tuple(options)
    return Annotated[typing.Literal[names], Limits(kind="choice", unit="one of " + ", ".join(names),
                                                   why=why)]


def described_text(allowed: str, why: str = "") -> Any:
    """A text field whose allowed values a loader checks itself, refused by type in the
    words ``allowed``."""
    return Annotated[str, Limits(kind="described", unit=allowed, why=why)]


def listing(item: Any, lo: int, hi: int, allowed: str, why: str = "") -> Any:
    """A list of ``lo ... hi`` items of type ``item``."""
    return Annotated[list[item], Field(min_length=lo, max_length=hi),
                     Limits(kind="list", unit=allowed, why=why)]


def validate(model: type[BaseModel], data: Any, problems: Problems) -> BaseModel | None:
    """``model`` from ``data``, or None with every refusal added to ``problems``."""
    if not isinstance(data, Mapping):
        problems.add("<file>", type(data).__name__, "a TOML table")
        return None
    depth = nesting(data)
    if depth > MAX_NESTING:
        problems.add("<file>", f"{depth} levels", f"arrays and tables nested at most {MAX_NESTING} deep")
        return None
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        problems.extend([wording(e, model, problems.file) for e in exc.errors()])
        return None


#: Types neither a table nor an array (:func:`nesting` skips them without asking further).
_SCALARS = frozenset({str, int, float, bool, type(None)})


def nesting(value: Any, limit: int = MAX_NESTING + 1) -> int:
    """Depth of nested lists/tables in ``value`` (stops counting past ``limit``)."""
    depth, level = 0, [value]
    while level and depth <= limit:
        nxt = []
        for v in level:
            kind = type(v)  # TOML's own types first: an ABC check costs a microsecond each
            if kind is dict:
                nxt.extend(v.values())
            elif kind is list:
                nxt.extend(v)
            elif kind in _SCALARS:
                continue
            elif isinstance(v, Mapping):
                nxt.extend(v.values())
            elif isinstance(v, list):
                nxt.extend(v)
        if not nxt:
            break
        depth += 1
        level = nxt
    return depth


# ---------------------------------------------------------------------------
# Files
# ---------------------------------------------------------------------------
def read_toml(path: Path, what: str) -> dict[str, Any]:
    """Parse a TOML file (UTF-8; a leading byte order mark, as some editors write one, is
    read past).

    Raises:
        DesignError: naming ``what`` (e.g. "design file") and the path, when the
            file cannot be read, is not UTF-8, is not valid TOML or nests too deep.
    """
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise DesignError(what, str(path), "a readable TOML file", exc.strerror or str(exc)) from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise DesignError(what, str(path), "a UTF-8 text file",
                          f"byte {exc.start} is not UTF-8") from None
    try:
        return copy.deepcopy(_parsed_toml(text))
    except tomllib.TOMLDecodeError as exc:
        raise DesignError(what, str(path), "valid TOML", str(exc)) from None
    except RecursionError:
        raise DesignError(what, str(path), f"arrays and tables nested at most {MAX_NESTING} deep",
                          "nesting too deep to read") from None


@functools.lru_cache(maxsize=64)
def _parsed_toml(text: str) -> dict[str, Any]:
    # a design command reads the same few files (its design, the base design, the rigs,
    # the shipped examples) many times over; parsing is pure Python, a deep copy of the
    # parsed tables a tenth of it. Keyed by the text, so an edited file is parsed anew.
    return tomllib.loads(text)


@dataclass(frozen=True)
class ResolvedSection:
    """An optional design table resolved to a value for every key, with each
    value's source: "design file" or the default's reason
    (:func:`section_with_defaults`). Subclasses list the values as fields;
    ``sources`` is keyword-only so they may come first."""

    sources: tuple[tuple[str, str], ...] = field(default=(), kw_only=True)

    def source(self, key: str) -> str:
        """Where ``key``'s value came from ("" for a key with no record)."""
        return dict(self.sources).get(key, "")

    def derived_json(self) -> dict[str, Any]:
        """Figures computed from the values, reported after them in :meth:`as_json`."""
        return {}

    def as_json(self) -> dict[str, Any]:
        """Every value by key, the derived figures, then ``sources`` by key."""
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "sources"}
        return {**out, **self.derived_json(), "sources": dict(self.sources)}


def section_with_defaults(raw: Mapping[str, Any], section: str,
                          defaults: Mapping[str, tuple[Any, str]]
                          ) -> tuple[dict[str, Any], dict[str, str]]:
    """(values, sources) of an optional section whose keys all have defaults:
    ``defaults`` maps a key to (value, reason); a key the file gives has the
    source "design file". The file's tables are validated before."""
    table = raw.get(section) if isinstance(raw, Mapping) else None
    table = table if isinstance(table, Mapping) else {}
    values = {k: v for k, (v, _) in defaults.items()}
    sources = {k: why for k, (_, why) in defaults.items()}
    for key, value in table.items():
        values[key], sources[key] = value, "design file"
    return values, sources


def content_hash(data: Mapping[str, Any]) -> str:
    """sha256 of a file's content (canonical JSON), independent of comments and layout."""
    canonical = json.dumps(data, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(canonical.encode()).hexdigest()


_ASSUMPTION_KEY = re.compile(r"^([a-z_]+)\.([A-Za-z0-9_]+)(\[\d+\])?$")


def _section_model(annotation: Any) -> Any:
    """The section model of a field, an optional section (``X | None``) included."""
    for arg in typing.get_args(annotation) or (annotation,):
        if isinstance(arg, type) and issubclass(arg, BaseModel):
            return arg
    return annotation


@functools.lru_cache(maxsize=1024)
def names_a_field(model: type[BaseModel], key: str) -> bool:
    """Whether an ``[assumptions]`` key (``section.key`` or ``section.key[i]``) names a
    field of one of ``model``'s sections: a question of the model and the key alone, so
    answered once per process (every validation of a search reads the same keys).

    Args:
        model: the file's model. key: the assumption's key.

    Returns:
        True when the section is one of the model's and the key one of its fields.
    """
    m = _ASSUMPTION_KEY.match(key)
    section = model.model_fields.get(m.group(1)) if m else None
    sub = _section_model(section.annotation) if section is not None else None
    return bool(isinstance(sub, type) and issubclass(sub, BaseModel)
                and m.group(2) in sub.model_fields)


def read_assumptions(data: Mapping[str, Any], model: type[BaseModel], problems: Problems,
                     example: str) -> tuple[tuple[str, str], ...]:
    """The ``[assumptions]`` table: ``"section.key" = "one-line reason"`` pairs,
    each key naming a field of ``model``; refusals go to ``problems``."""
    table = data.get("assumptions", {}) if isinstance(data, Mapping) else {}
    if not isinstance(table, Mapping):
        problems.add("assumptions", table, "a table of 'section.key' = \"reason\"")
        return ()
    out = []
    for key, reason in table.items():
        if not names_a_field(model, key):
            problems.add(f"assumptions.{key}", reason,
                         f"keys naming a field of this file, e.g. '{example}'")
        elif not isinstance(reason, str) or not reason.strip():
            problems.add(f"assumptions.{key}", reason, "a one-line reason (non-empty string)")
        else:  # a reason whose value has since been edited says so
            out.append((key, reason_as_read(key, reason.strip(), data)[0]))
    return tuple(out)


@dataclass(frozen=True)
class Derived:
    """A dimension the plan derives, with the reason it has that value."""

    name: str
    value: float
    unit: str
    reason: str


#: The per-element lists of a design file: rows x columns values each.
PER_ELEMENT_LISTS = ("arms.lengths_mm", "comb.stop_gaps_mm", "comb.web_thicknesses_mm")


def stated_grid(data: Mapping[str, Any]) -> tuple[int, int] | None:
    """(rows, columns) a design file's ``[array]`` states, or None where either is not a
    whole number of at least 1.

    Args:
        data: the design file's tables.

    Returns:
        The grid, or None.
    """
    table = data.get("array") if isinstance(data, Mapping) else None
    if not isinstance(table, Mapping):
        return None
    rows, columns = table.get("rows"), table.get("columns")
    whole = all(isinstance(v, int) and not isinstance(v, bool) and v >= 1 for v in (rows, columns))
    return (rows, columns) if whole else None


def counted(error: DesignError, grid: tuple[int, int] | None) -> DesignError:
    """``error`` naming the count of values a per-element list takes (``rows x columns``
    becomes ``rows x columns: 2 x 5 = 10 values``) where it refuses such a list and the
    file states its grid; ``error`` itself otherwise.

    Args:
        error: one refusal. grid: :func:`stated_grid` of the file.

    Returns:
        The refusal, with the number where it lacked it.
    """
    words = "rows x columns"
    if grid is None or error.field not in PER_ELEMENT_LISTS or words not in error.allowed:
        return error
    rows, columns = grid
    return DesignError(error.field, error.value,
                       f"{error.allowed}: {rows} x {columns} = {rows * columns} values",
                       error.why, error.file, error.alternatives, error.limit)


def with_counts(problems: Problems, data: Mapping[str, Any]) -> None:
    """Name the count of values in every refusal of a per-element list in ``problems``
    (:func:`counted`), in place.

    Args:
        problems: this pass's refusals. data: the design file's tables.
    """
    grid = stated_grid(data)
    problems.errors = [counted(e, grid) for e in problems.errors]


#: How ``tactcad design`` records, at the end of each reason under ``[assumptions]``, the
#: value the reason was written for (``... by the web rule [written for 0.2]``); a file
#: without it (written before, or by hand) reads as it always did. It matches the last
#: record only: its value holds no further ``[written for`` (a list's brackets may be in it).
WRITTEN_FOR = re.compile(r"\s*\[written for ((?:(?!\[written for ).)*)\]\Z", re.DOTALL)

_KEY_PARTS = re.compile(r"^([a-z_]+)\.([A-Za-z0-9_]+)(?:\[(\d+)\])?$")


def value_text(value: Any) -> str | None:
    """A design file's value as a reason's record of it: a text as it is, a number as
    its shortest form to 12 digits, a list in brackets; None for a table or another type.

    Args:
        value: the value (TOML's types).

    Returns:
        The text, or None.
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return value
    if isinstance(value, (int, float)):
        return format(value, ".12g")
    if isinstance(value, (list, tuple)):
        items = [value_text(v) for v in value]
        return None if None in items else "[" + ", ".join(items) + "]"
    return None


def keyed_value(data: Mapping[str, Any], key: str) -> Any:
    """The value an ``[assumptions]`` key names in ``data`` (``section.key`` or
    ``section.key[i]``, i from 1), or None where the file leaves it out.

    Args:
        data: the design file's tables. key: the assumption's key.

    Returns:
        The value, or None.
    """
    m = _KEY_PARTS.match(key)
    table = data.get(m.group(1)) if m and isinstance(data, Mapping) else None
    value = table.get(m.group(2)) if isinstance(table, Mapping) else None
    if value is None or m.group(3) is None:
        return value
    i = int(m.group(3))  # element order, from 1, as the refusals name them
    return value[i - 1] if isinstance(value, list) and 1 <= i <= len(value) else None


def plain_reason(reason: str) -> tuple[str, str | None]:
    """(a reason without its record of the value, that record or None where it has none).

    The value is the last record's (:data:`WRITTEN_FOR`); records before it at the end of
    the reason (a file written twice over, or mangled by hand) are dropped from the words.

    Args:
        reason: a reason as the file gives it.

    Returns:
        The reason's words (empty where the reason is only records) and the value text it
        was written for.
    """
    m = WRITTEN_FOR.search(reason)
    if m is None:
        return reason, None
    words = reason[:m.start()]
    while (earlier := WRITTEN_FOR.search(words)) is not None:
        words = words[:earlier.start()]
    return words.rstrip(), m.group(1)


def reason_as_read(key: str, reason: str, data: Mapping[str, Any]) -> tuple[str, bool]:
    """A reason as the outputs show it, and whether it still applies: the reason's own
    words where the file states the value it was written for (or it records none), else
    those words and ``(written for 0.2; the file now states 0.25: the reason no longer
    applies)`` (an edit of the file since ``tactcad design`` wrote it).

    Args:
        key: the assumption's key. reason: its text in the file. data: the file's tables.

    Returns:
        (the text shown, True while the reason applies to the file's value).
    """
    words, written = plain_reason(reason)
    if written is None:
        return words, True
    now = value_text(keyed_value(data, key))
    if now == written:
        return words, True
    stated = "leaves it out" if now is None else f"states {now}"
    return (f"{words} (written for {written}; the file now {stated}: the reason no longer "
            "applies)"), False


def with_written_values(data: Mapping[str, Any]) -> dict:
    """``data`` with each reason under ``[assumptions]`` ending with the value it is
    written for (:data:`WRITTEN_FOR`), so that a later edit of the value shows the reason
    as no longer applying (:func:`reason_as_read`); a record already there is replaced.

    Args:
        data: the tables about to be written.

    Returns:
        A copy of the tables (the same where there is no ``[assumptions]``).
    """
    why = data.get("assumptions")
    if not isinstance(why, Mapping) or not why:
        return dict(data)
    marked = {}
    for key, reason in why.items():
        text = value_text(keyed_value(data, key))
        words = plain_reason(reason)[0] if isinstance(reason, str) else reason
        marked[key] = words if text is None or not isinstance(words, str) else \
            f"{words} [written for {text}]"
    return {**data, "assumptions": marked}


def stale_reasons(data: Mapping[str, Any]) -> dict[str, str]:
    """The reasons under a design file's ``[assumptions]`` that no longer apply: each
    written by ``tactcad design`` for a value the file has since changed
    (:func:`reason_as_read`), as the outputs show it.

    Args:
        data: the design file's tables.

    Returns:
        Key -> the reason as shown (empty where every one applies).
    """
    why = data.get("assumptions") if isinstance(data, Mapping) else None
    if not isinstance(why, Mapping):
        return {}
    read = {key: reason_as_read(key, reason, data) for key, reason in why.items()
            if isinstance(reason, str)}
    return {key: text for key, (text, applies) in read.items() if not applies}
