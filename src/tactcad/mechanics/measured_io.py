"""Measured calibration readings from the files a lab has on disk.

Formats (chosen by the file's suffix, else by its first bytes):

* **CSV** as Excel, LabVIEW or a script saves it: with or without a UTF-8
  byte order mark, comma-, semicolon- or tab-separated, decimal point or
  decimal comma (both detected and reported in :class:`ReadInfo`), UTF-8 or
  UTF-16 with a byte order mark, any other encoding by name (``encoding``);
  a file that is not valid text in its encoding is refused with the line and
  column of the first bad byte.
* **LabVIEW LVM** (text, "LabVIEW Measurement" header; separator and decimal
  separator from its header), read by the maintained ``lvm_read`` package;
  every segment's rows are readings. Its X column is channel ``X_Value``.
* **TDMS** (NI's binary format), read by ``npTDMS``; channels are named
  ``group/channel``, a bare channel name where it is unique in the file.

Each reading needs the five columns of :data:`COLUMNS` (element number, run
number, Z travel in um, force in N, bridge signal in V). A CSV names them in
its header; LVM and TDMS name channels, so a mapping ``column -> channel``
(``--map signal_V=Dev1/ai1,force_N=Dev1/ai0``) says which channel is which
column; a column not mapped is read from the channel (or CSV header) of its
own name. Every refusal names the file, the line (or TDMS row) and the column.
"""

from __future__ import annotations

import codecs
import contextlib
import csv
import logging
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable, Iterator, Mapping

import numpy as np

from tactcad.errors import short_repr

from tactcad.mechanics.calibration import CSV_COLUMNS as COLUMNS
from tactcad.mechanics.calibration import CSV_SENSOR_KEY as SENSOR_KEY
from tactcad.mechanics.calibration import (K_SENSOR_N_PER_MM, CalibrationData,
                                                 CalibrationError)
#: Largest data file read (bytes): far above any calibration run, small enough
#: that a wrong file (a video, a disk image) is refused at once.
MAX_BYTES = 64 * 2**20
FORMATS = ("csv", "lvm", "tdms")
#: Largest magnitude of a reading per column, with its unit: far beyond any
#: bench rig (1 m of travel, 100 kN, 10 kV), so a value past it is a damaged
#: cell, and the fit's sums of squares stay finite.
LIMITS = {"element": (1e9, ""), "run": (1e9, ""), "z_um": (1e6, "um"), "force_N": (1e5, "N"),
          "signal_V": (1e4, "V")}
#: Longest excerpt of a header or channel list echoed in a refusal (characters).
MAX_SHOWN_CHARS = 200
_SEPARATORS = {",": "comma", ";": "semicolon", "\t": "tab"}
_BOMS = ((codecs.BOM_UTF8, "utf-8-sig"), (codecs.BOM_UTF16_LE, "utf-16"),
         (codecs.BOM_UTF16_BE, "utf-16"))
_DECIMAL_COMMA = re.compile(r"^[+-]?\d*,\d+(?:[eE][+-]?\d+)?$")


@dataclass(frozen=True)
class ReadInfo:
    """How a data file was read (stated in tactcad's output).

    Attributes:
        path: the file.
        format: ``csv``, ``lvm`` or ``tdms``.
        encoding: the text encoding (None for TDMS); ``utf-8-sig`` means
            UTF-8 with a byte order mark.
        separator: the column separator (None for TDMS).
        decimal: ``.`` or ``,`` (None for TDMS).
        mapping: column -> the CSV header, LVM or TDMS channel it was read from.
        readings: number of readings.
        places: element -> where each of its readings is in the file (``line 12``, or
            ``row 12`` of a TDMS file), in the order of its readings.
    """

    path: str
    format: str
    encoding: str | None = None
    separator: str | None = None
    decimal: str | None = None
    mapping: Mapping[str, str] = field(default_factory=dict)
    readings: int = 0
    places: Mapping[int, tuple[str, ...]] = field(default_factory=dict)

    def describe(self) -> str:
        """One phrase, e.g. ``csv, utf-8 with byte order mark, semicolon-separated, decimal comma``."""
        parts = [self.format]
        if self.encoding:
            parts.append("utf-8 with byte order mark" if self.encoding == "utf-8-sig"
                         else self.encoding)
        if self.separator:
            parts.append(f"{_SEPARATORS.get(self.separator, repr(self.separator))}-separated")
        if self.decimal:
            parts.append("decimal comma" if self.decimal == "," else "decimal point")
        renamed = [f"{c}={s}" for c, s in self.mapping.items() if c != s]
        if renamed:
            parts.append("columns " + ",".join(renamed))
        return ", ".join(parts) + f", {self.readings} readings"

    def as_dict(self) -> dict:
        return {"path": self.path, "format": self.format, "encoding": self.encoding,
                "separator": self.separator, "decimal": self.decimal,
                "mapping": dict(self.mapping), "readings": self.readings}


def parse_mapping(texts: Iterable[str] | None) -> dict[str, str]:
    """``["signal_V=Dev1/ai1,force_N=Dev1/ai0"]`` -> ``{"signal_V": "Dev1/ai1", ...}``.

    Raises:
        CalibrationError: a pair without ``=``, an unknown column, a column
            given twice or an empty channel name.
    """
    out: dict[str, str] = {}
    for text in texts or ():
        for pair in text.split(","):
            column, sep, source = (s.strip() for s in pair.partition("="))
            if not sep or column not in COLUMNS or not source:
                allowed = (f"COLUMN=CHANNEL pairs, comma-separated, with COLUMN one of "
                           f"{', '.join(COLUMNS)}, e.g. signal_V=Dev1/ai1")
                raise CalibrationError(f"--map = {pair!r}: allowed {allowed}", "--map", pair,
                                       allowed)
            if column in out:
                raise CalibrationError(f"--map = {text!r}: column {column} given twice",
                                       "--map", text, "each column once")
            out[column] = source
    return out


# ---------------------------------------------------------------------------
# Entry point
# ---------------------------------------------------------------------------
def read_measured(path, encoding: str | None = None, mapping: Mapping[str, str] | None = None,
                  fmt: str | None = None, default_k_sensor: float = K_SENSOR_N_PER_MM
                  ) -> tuple[dict[int, CalibrationData], ReadInfo]:
    """Read calibration readings from a CSV, LVM or TDMS file.

    Args:
        path: the data file.
        encoding: text encoding by name (Python's codec names: ``cp1252``,
            ``latin-1``, ``utf-16`` ...); None reads UTF-8 (or what a byte
            order mark says). Ignored for TDMS.
        mapping: column -> channel (see the module doc); None maps each
            column to the channel of its own name.
        fmt: ``csv``, ``lvm`` or ``tdms``; None chooses by suffix, then content.
        default_k_sensor: the force gauge's stiffness (N/mm) where the file
            states none (``k_sensor_N_per_mm``): the design's rigs give it.

    Returns:
        ({element: :class:`CalibrationData`} in order of first appearance,
        :class:`ReadInfo`).

    Raises:
        CalibrationError: the file cannot be read, is too large, is not text in
            its encoding, or any column, value or count is out of range; the
            message names the file, the line (TDMS: row) and the column.
    """
    p = Path(path)
    where = str(p)
    if encoding is not None:
        _check_encoding(encoding)
    try:
        size = p.stat().st_size
        if not p.is_file():
            raise CalibrationError(f"{where}: not a file: allowed a CSV, LVM or TDMS file")
        if size > MAX_BYTES:
            raise CalibrationError(f"{where}: {size} bytes: allowed at most {MAX_BYTES} bytes "
                                   "for a calibration data file")
        raw = p.read_bytes()
    except OSError as exc:
        raise CalibrationError(f"{where}: cannot be read ({exc.strerror or exc})") from None
    if fmt != "tdms":
        _refuse_workbook(raw, where)
    fmt = fmt or _format_of(p, raw)
    mapping = dict(mapping or {})
    if fmt == "tdms":
        return _read_tdms(p, mapping, default_k_sensor)
    text, used = decode(raw, encoding, where)
    if fmt == "lvm":
        return _read_lvm(text, used, where, mapping, default_k_sensor)
    _check_reads_as(raw, text, used, where, mapping)
    return parse_csv_text(text, where, mapping, used, default_k_sensor)


#: First bytes of a spreadsheet workbook: a zip archive (xlsx, ods) or an OLE2 compound file
#: (xls).
ZIP_MAGIC = (b"PK\x03\x04", b"PK\x05\x06", b"PK\x07\x08")
OLE_MAGIC = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"
#: What a refusal of a workbook allows: the formats the reader takes.
READ_FORMATS = ("a CSV file (comma, semicolon or tab separated, as a spreadsheet saves it), "
                "a LabVIEW .lvm or a .tdms file")


class WorkbookError(CalibrationError):
    """A data file that is a spreadsheet workbook (xlsx, xls, ods), not text: its message
    starts with the file, so the option that named it can head it."""


def workbook_kind(raw: bytes) -> str | None:
    """The kind of spreadsheet workbook ``raw`` (a file's first bytes or all of it) is, in
    words, by its magic bytes: an Excel .xlsx or OpenDocument .ods workbook (a zip archive),
    an Excel 97-2003 .xls workbook (an OLE2 compound file); None for any other file.

    Args:
        raw: the file's bytes.

    Returns:
        The kind in words, or None.
    """
    if raw.startswith(OLE_MAGIC):
        return "an Excel 97-2003 .xls workbook (an OLE2 compound file)"
    if not raw.startswith(ZIP_MAGIC):
        return None
    import io
    import zipfile

    try:
        with zipfile.ZipFile(io.BytesIO(raw)) as z:
            names = z.namelist()
            mimetype = (z.read("mimetype")[:100].decode("ascii", "replace")
                        if "mimetype" in names else "")
    except (zipfile.BadZipFile, OSError, ValueError, RuntimeError):
        names, mimetype = [], ""
    if any(n.startswith("xl/") for n in names):
        return "an Excel .xlsx workbook (a zip archive)"
    if "opendocument.spreadsheet" in mimetype:
        return "an OpenDocument .ods spreadsheet (a zip archive)"
    return "a zip archive (as an .xlsx or .ods spreadsheet workbook is), not text"


def _refuse_workbook(raw: bytes, where: str, allowed: str = READ_FORMATS) -> None:
    """Refuse a spreadsheet workbook (:func:`workbook_kind`) by name, before it is read as
    text (its first binary byte would be refused as a wrong encoding); ``allowed``: the
    formats the reader takes, in words."""
    kind = workbook_kind(raw)
    if kind is not None:
        raise WorkbookError(f"{where}: a spreadsheet workbook, {kind}: allowed {allowed}; "
                            "save the sheet as CSV (File > Save As > CSV UTF-8) and give that "
                            "file", None, None, allowed)


def _format_of(p: Path, raw: bytes) -> str:
    suffix = p.suffix.lower()
    if suffix in (".tdms", ".lvm"):
        return suffix[1:]
    if raw.startswith(b"TDSm"):
        return "tdms"
    head = raw[:64].lstrip(codecs.BOM_UTF8)
    return "lvm" if head.startswith(b"LabVIEW Measurement") else "csv"


def _check_encoding(name: str) -> None:
    try:
        info = codecs.lookup(name)
    except (LookupError, ValueError, TypeError):
        info = None
    if info is None or not getattr(info, "_is_text_encoding", True):
        allowed = "a text encoding name such as utf-8, utf-8-sig, cp1252, latin-1, utf-16"
        raise CalibrationError(f"--encoding = {name!r}: allowed {allowed}", "--encoding", name,
                               allowed)


def decode(raw: bytes, encoding: str | None, where: str) -> tuple[str, str]:
    """The text of ``raw`` and the encoding used: a byte order mark wins, then
    ``encoding``, then UTF-8.

    Raises:
        CalibrationError: a byte that is not valid in the encoding (its line
            and column named), or a NUL character (a binary file).
    """
    used = encoding or "utf-8"
    for bom, name in _BOMS:
        if raw.startswith(bom):
            used = name
            break
    try:
        text = raw.decode(used)
    except UnicodeDecodeError as exc:
        before = raw[:exc.start]
        line = before.count(b"\n") + 1
        column = exc.start - (before.rfind(b"\n") + 1) + 1
        bad = raw[exc.start:exc.start + 1].hex().upper()
        hint = "give the file's encoding with --encoding (e.g. cp1252 or latin-1 for Excel on " \
               "Windows)" if encoding is None else "give the file's own encoding with --encoding"
        raise CalibrationError(f"{where}: line {line}, column {column}: byte 0x{bad} is not "
                               f"{used} text: allowed {used}; {hint}") from None
    except UnicodeError as exc:  # e.g. utf-16 with an odd byte count
        raise CalibrationError(f"{where}: line 1, column 1: not {used} text ({exc})") from None
    nul = text.find("\0")
    if nul >= 0:
        line = text.count("\n", 0, nul) + 1
        column = nul - (text.rfind("\n", 0, nul) + 1) + 1
        raise CalibrationError(f"{where}: line {line}, column {column}: a NUL character: allowed "
                               "text (CSV or LVM); is this a binary file?")
    if used == "utf-8-sig":
        return text, used
    return text.lstrip("\ufeff"), used


#: Encodings tried on a CSV file whose header holds no column in the encoding asked for.
_OTHER_ENCODINGS = ("utf-8", "utf-16", "cp1252")


def _header_line(text: str) -> str:
    """The first line that is neither blank nor a ``#`` comment ("" if none)."""
    return next((line for line in text.splitlines()
                 if line.strip() and not line.strip().startswith("#")), "")


def _names_a_column(line: str, mapping: Mapping[str, str]) -> bool:
    return any(mapping.get(c, c) in line for c in COLUMNS)


def _check_reads_as(raw: bytes, text: str, used: str, where: str,
                    mapping: Mapping[str, str]) -> None:
    """Refuse a CSV text whose header holds no column while another encoding of the same
    bytes gives one: the encoding asked for is the wrong one (its text is mojibake)."""
    if _names_a_column(_header_line(text), mapping):
        return
    for other in _OTHER_ENCODINGS:
        if other == used:
            continue
        try:
            candidate = raw.decode(other).lstrip("\ufeff")
        except UnicodeError:
            continue
        if _names_a_column(_header_line(candidate), mapping):
            found = short_repr(_header_line(text))
            allowed = f"the file's own encoding, e.g. {other}"
            raise CalibrationError(
                f"{where} does not read as {used.upper()}: its header line reads {found}, "
                f"which names none of the columns {', '.join(COLUMNS)}; try --encoding {other}",
                "--encoding", used, allowed)


# ---------------------------------------------------------------------------
# Readings -> CalibrationData (one set of rules for every format)
# ---------------------------------------------------------------------------
class _Readings:
    """Readings collected row by row and checked as they come; ``where(col)``
    names the file, line and column of a value."""

    def __init__(self) -> None:
        self.by_element: dict[int, list[tuple[float, float, float]]] = {}
        self.places: dict[int, list[str]] = {}
        self.count = 0

    def add(self, values: Mapping[str, float], where: Callable[[str], str], place: str) -> None:
        """Add one reading; ``place`` says where it is (``line 12``, ``row 12``)."""
        for c in COLUMNS:
            if not np.isfinite(values[c]):
                raise CalibrationError(f"{where(c)} = {values[c]!r}: allowed a finite number",
                                       c, values[c], "a finite number")
            if abs(values[c]) > LIMITS[c][0]:
                allowed = f"|value| <= {LIMITS[c][0]:g} {LIMITS[c][1]}".rstrip()
                raise CalibrationError(f"{where(c)} = {values[c]!r}: allowed {allowed}",
                                       c, values[c], allowed)
        element = _integer(values["element"], where("element"), "element")
        _integer(values["run"], where("run"), "run")
        if values["z_um"] < 0:
            raise CalibrationError(f"{where('z_um')} = {values['z_um']!r}: allowed >= 0 um",
                                   "z_um", values["z_um"], ">= 0 um")
        self.by_element.setdefault(element, []).append(
            (values["z_um"], values["force_N"], values["signal_V"]))
        self.places.setdefault(element, []).append(place)
        self.count += 1

    def places_of(self) -> dict[int, tuple[str, ...]]:
        """Element -> the places of its readings (for :class:`ReadInfo`)."""
        return {e: tuple(p) for e, p in self.places.items()}

    def result(self, where: str, k_sensor: float) -> dict[int, CalibrationData]:
        if not self.count:
            raise CalibrationError(f"{where}: readings = 0: allowed >= 3 readings per element",
                                   "readings", 0, ">= 3 readings per element")
        out = {}
        for element, rows in self.by_element.items():
            if len(rows) < 3:
                raise TooFewReadings(f"{where}: element {element}: readings = {len(rows)}: "
                                     "allowed >= 3", "readings", len(rows),
                                     ">= 3 readings per element", self.places_of())
            z, f, v = (np.array(c, dtype=float) for c in zip(*rows))
            for a in (z, f, v):
                a.flags.writeable = False
            out[element] = CalibrationData(z, f, v, float(k_sensor))
        return out


class TooFewReadings(CalibrationError):
    """An element with fewer than 3 readings; ``places`` holds every element's places in the
    file (element -> ``line 12`` ...), so that an element the design has not is refused
    first (:func:`tactcad.mechanics.calibration_file.read_calibration`)."""

    def __init__(self, message: str, field: str, value: object, allowed: str,
                 places: dict[int, tuple[str, ...]]):
        super().__init__(message, field, value, allowed)
        self.places = places


def _integer(x: float, where: str, column: str | None = None) -> int:
    if not (x == int(x) and 1 <= x <= 1e9):
        raise CalibrationError(f"{where} = {x!r}: allowed an integer >= 1", column, x,
                               "an integer >= 1")
    return int(x)


def _sensor_stiffness(value: str, where: str, decimal: str = ".") -> float:
    k = _number(value, where, decimal, SENSOR_KEY)
    if not (np.isfinite(k) and k > 0):
        raise CalibrationError(f"{where} = {value.strip()!r}: allowed a number > 0 (N/mm)",
                               SENSOR_KEY, value.strip(), "a number > 0 (N/mm)")
    return k


def _number(text: str, where: str, decimal: str = ".", column: str | None = None) -> float:
    cell = text.strip()
    if decimal == ",":
        if "." in cell:
            raise CalibrationError(f"{where} = {cell!r}: allowed a number with a decimal comma "
                                   "like the rest of the file", column, cell,
                                   "a number with a decimal comma like the rest of the file")
        cell = cell.replace(",", ".")
    try:
        x = float(cell)
    except ValueError:
        raise CalibrationError(f"{where} = {text.strip()[:40]!r}: allowed a number", column,
                               text.strip()[:40], "a number") from None
    if not np.isfinite(x):
        raise CalibrationError(f"{where} = {text.strip()!r}: allowed a finite number", column,
                               text.strip(), "a finite number")
    return x


def _resolve(names: list[str], mapping: Mapping[str, str], where: str,
             kind: str) -> dict[str, int]:
    """Column -> index into ``names`` (a header or channel list), by ``mapping``."""
    unknown = [c for c in mapping if c not in COLUMNS]
    if unknown:
        raise CalibrationError(f"--map: column {unknown[0]!r}: allowed {', '.join(COLUMNS)}")
    out, missing = {}, []
    for c in COLUMNS:
        source = mapping.get(c, c)
        hits = [i for i, n in enumerate(names) if n == source]
        if len(hits) > 1:
            raise CalibrationError(f"{where}: {kind} {source!r} appears {len(hits)} times: "
                                   "allowed once", c, source, f"one {kind} named {source!r}")
        if hits:
            out[c] = hits[0]
        else:
            missing.append(c if source == c else f"{c} (mapped to {source!r})")
    if missing:
        shown = short_repr([n for n in names if n][:20], MAX_SHOWN_CHARS)
        allowed = (f"{kind}s named {', '.join(COLUMNS)}, or a --map COLUMN={kind.upper()} for "
                   "each other name")
        raise CalibrationError(f"{where}: {kind}s = {shown}: missing {', '.join(missing)}; "
                               f"allowed {allowed}", missing[0].split(" ")[0], shown, allowed)
    return out


# ---------------------------------------------------------------------------
# CSV
# ---------------------------------------------------------------------------
def parse_csv_text(text: str, source: str = "<csv>", mapping: Mapping[str, str] | None = None,
                   encoding: str | None = None, default_k_sensor: float = K_SENSOR_N_PER_MM
                   ) -> tuple[dict[int, CalibrationData], ReadInfo]:
    """Calibration readings of a CSV text (see the module doc).

    A header line names the columns (in any order, extra columns ignored
    only when ``mapping`` names the ones used); lines starting with ``#`` are
    comments, ``# k_sensor_N_per_mm = 57.04`` sets the force sensor's stiffness
    (N/mm; default the paper's 57.04). The separator is the one of ``,``,
    ``;``, tab that splits the header into the columns; the decimal separator
    is ``,`` when a value is written with a decimal comma (never with a comma
    separator), else ``.``.

    Raises:
        CalibrationError: see :func:`read_measured`.
    """
    mapping = dict(mapping or {})
    sensor_line, lines = None, []
    for n, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if stripped.startswith("#"):
            body = stripped.lstrip("#").strip()
            if body.startswith(SENSOR_KEY) and "=" in body:
                sensor_line = (n, body.split("=", 1)[1])
        elif stripped.strip(",;\t"):
            lines.append((n, line))
    if not lines:
        raise CalibrationError(f"{source}: line 1: no header and no readings; allowed a header "
                               f"{','.join(COLUMNS)} and >= 3 readings per element")
    header_n, header_line = lines[0]
    separator, header = _split_header(header_line, mapping)
    header = _without_trailing_empty(header)  # a spreadsheet's separator at each line's end
    if len(set(header)) != len(header):
        dup = next(h for h in header if header.count(h) > 1)
        raise CalibrationError(f"{source}: line {header_n}, column {dup!r}: appears twice in the "
                               "header: allowed once", dup, f"{dup} twice", "each column once")
    if not mapping:  # without a mapping the header is exactly the five columns
        missing = [c for c in COLUMNS if c not in header]
        unknown = [c for c in header if c not in COLUMNS]
        if missing or unknown:
            allowed = (f"exactly {list(COLUMNS)}, separated by comma, semicolon or tab, or "
                       "--map COLUMN=HEADER for other names")
            raise CalibrationError(
                f"{source}: line {header_n}: columns = {short_repr(header, MAX_SHOWN_CHARS)}: "
                f"allowed exactly {list(COLUMNS)} (missing {missing}, unknown "
                f"{short_repr(unknown, MAX_SHOWN_CHARS)}), separated by comma, semicolon or tab, "
                "or --map COLUMN=HEADER for other names", missing[0] if missing else None,
                short_repr(header, MAX_SHOWN_CHARS), allowed)
    index = _resolve(header, mapping, f"{source}: line {header_n}", "column")
    decimal = _decimal_of(lines[1:], separator)
    k_sensor = default_k_sensor if sensor_line is None else _sensor_stiffness(
        sensor_line[1], f"{source}: line {sensor_line[0]}, column {SENSOR_KEY}", decimal)
    readings = _Readings()
    for n, line in lines[1:]:
        cells = next(csv.reader([line], delimiter=separator))
        if len(cells) > len(header) and not "".join(cells[len(header):]).strip():
            cells = cells[:len(header)]  # the empty cells after a trailing separator
        if len(cells) != len(header):
            raise CalibrationError(f"{source}: line {n}, column {min(len(cells), len(header)) + 1}:"
                                   f" {len(cells)} values: allowed {len(header)} "
                                   f"({separator.join(header)})")
        values = {c: _number(cells[i], f"{source}: line {n}, column {c}", decimal, c)
                  for c, i in index.items()}
        readings.add(values, lambda c, n=n: f"{source}: line {n}, column {c}", f"line {n}")
    data = readings.result(source, k_sensor)
    return data, ReadInfo(source, "csv", encoding, separator, decimal,
                          {c: header[i] for c, i in index.items()}, readings.count,
                          readings.places_of())


def _without_trailing_empty(header: list[str]) -> list[str]:
    """The header's cells without the empty ones at its end: a spreadsheet saving a CSV
    may end every line with a separator, which names no column."""
    end = len(header)
    while end > 0 and not header[end - 1]:
        end -= 1
    return header[:end]


def _split_header(line: str, mapping: Mapping[str, str]) -> tuple[str, list[str]]:
    """The separator that splits the header into the wanted columns, and the header's cells."""
    wanted = {mapping.get(c, c) for c in COLUMNS}
    best = None
    for sep in _SEPARATORS:
        cells = [h.strip() for h in next(csv.reader([line], delimiter=sep))]
        score = (len(wanted & set(cells)), len(cells))
        if best is None or score > best[0]:
            best = (score, sep, cells)
    return best[1], best[2]


def _decimal_of(lines: list[tuple[int, str]], separator: str) -> str:
    if separator == ",":
        return "."
    for _, line in lines[:50]:
        if any(_DECIMAL_COMMA.match(c.strip()) for c in line.split(separator)):
            return ","
    return "."


# ---------------------------------------------------------------------------
# LabVIEW LVM (text)
# ---------------------------------------------------------------------------
def _read_lvm(text: str, encoding: str, where: str, mapping: Mapping[str, str],
              default_k_sensor: float = K_SENSOR_N_PER_MM):
    import lvm_read

    try:
        lvm = lvm_read.read_str(text)
    except (ValueError, SyntaxError, KeyError, IndexError, TypeError) as exc:
        raise CalibrationError(f"{where}: line 1, column 1: not a LabVIEW measurement file "
                               f"lvm_read can read ({str(exc)[:120]})") from None
    decimal = lvm.get("Decimal_Separator", ".") or "."
    separator = _lvm_separator(text)
    rows_at = _lvm_data_lines(text, separator)
    readings = _Readings()
    used: dict[str, str] = {}
    k_sensor = default_k_sensor
    if SENSOR_KEY in lvm:
        k_sensor = _sensor_stiffness(str(lvm[SENSOR_KEY]), f"{where}: header {SENSOR_KEY}", decimal)
    empty_heads: list[int] = []  # header lines of segments with no readings below them
    for s in range(int(lvm.get("Segments", 0))):
        seg = lvm[s]
        names = [n.strip() for n in seg.get("Channel names", [])]
        if "data" not in seg or not names:
            continue
        line_of = rows_at[s] if s < len(rows_at) else None
        head_line = (line_of[0] - 1) if line_of else _lvm_header_line(text, separator, s)
        index = _resolve(names, mapping, f"{where}: line {head_line}", "channel")
        used = {c: names[i] for c, i in index.items()}
        if np.size(seg["data"]) == 0:  # a header the logger wrote before any reading
            empty_heads.append(head_line)
            continue
        data = np.asarray(seg["data"], dtype=float).reshape(len(seg["data"]), -1)
        for r, row in enumerate(data):
            n = line_of[r] if line_of and r < len(line_of) else head_line + 1 + r
            values = {}
            for c, i in index.items():
                x = row[i] if i < row.size else np.nan
                if not np.isfinite(x):
                    cell = _lvm_cell(text, n, i, separator)
                    allowed = f"a finite number (decimal {decimal!r})"
                    raise CalibrationError(f"{where}: line {n}, column {c} (channel {names[i]!r}): "
                                           f"{cell!r}: allowed {allowed}", c, cell, allowed)
                values[c] = float(x)
            readings.add(values, lambda c, n=n: f"{where}: line {n}, column {c}", f"line {n}")
    if not readings.count and empty_heads:
        raise CalibrationError(f"{where}: line {empty_heads[0]}: no readings below the header: "
                               "allowed >= 3 readings per element below the X_Value line",
                               allowed=">= 3 readings per element below the X_Value line")
    if not readings.count:
        raise CalibrationError(f"{where}: line 1: no data segment with channel names: allowed a "
                               "LabVIEW measurement file with an X_Value header line and readings")
    return readings.result(where, k_sensor), ReadInfo(where, "lvm", encoding, separator, decimal,
                                                      used, readings.count, readings.places_of())


def _lvm_separator(text: str) -> str:
    for line in text.splitlines()[:25]:
        if line.startswith("Separator") and len(line.rstrip("\r\n")) > 9:
            return {"Tab": "\t", "Comma": ",", "Semicolon": ";"}.get(line[9:].strip(), line[9])
    return "\t"


def _lvm_data_lines(text: str, separator: str) -> list[list[int]]:
    """Line numbers (1-based) of each segment's data rows, as lvm_read reads them."""
    out: list[list[int]] = []
    current: list[int] | None = None
    for n, line in enumerate(text.splitlines(), start=1):
        if line.split(separator)[0] == "X_Value":
            current = []
            out.append(current)
        elif current is not None:
            if line.strip(separator + " \r") == "":
                current = None
            else:
                current.append(n)
    return out


def _lvm_header_line(text: str, separator: str, segment: int) -> int:
    """Line number (1-based) of segment ``segment``'s X_Value header line (1 if none)."""
    heads = [n for n, line in enumerate(text.splitlines(), start=1)
             if line.split(separator)[0] == "X_Value"]
    return heads[segment] if segment < len(heads) else 1


def _lvm_cell(text: str, line: int, index: int, separator: str) -> str:
    lines = text.splitlines()
    cells = lines[line - 1].split(separator) if 0 < line <= len(lines) else []
    return cells[index][:40] if index < len(cells) else ""


# ---------------------------------------------------------------------------
# TDMS (binary)
# ---------------------------------------------------------------------------
class MeasuredDataWarning(UserWarning):
    """A data file read with a doubt the reader raised (e.g. a TDMS file cut short)."""


@contextlib.contextmanager
def _tdms_log_as_warnings(where: str) -> Iterator[None]:
    """npTDMS logs what it repairs to stderr in its own format; within this,
    each distinct message becomes one warning naming the file."""
    from nptdms.log import log_manager

    messages: list[str] = []

    class Collect(logging.Handler):
        def emit(self, record: logging.LogRecord) -> None:
            messages.append(record.getMessage())

    collect = Collect(logging.WARNING)
    loggers = list(log_manager.loggers.values())
    for log in loggers:
        log.removeHandler(log_manager.console_handler)
        log.addHandler(collect)
    try:
        yield
    finally:
        for log in loggers:
            log.removeHandler(collect)
            log.addHandler(log_manager.console_handler)
        for text in dict.fromkeys(messages):
            short = text if len(text) <= 160 else text[:160] + "..."
            warnings.warn(f"{where}: npTDMS: {short}", MeasuredDataWarning, stacklevel=3)


def _read_tdms(p: Path, mapping: Mapping[str, str], default_k_sensor: float = K_SENSOR_N_PER_MM):
    import nptdms

    where = str(p)
    try:
        with _tdms_log_as_warnings(where):
            tdms = nptdms.TdmsFile.read(p)
            channels = {f"{g.name}/{c.name}": c for g in tdms.groups() for c in g.channels()}
            arrays = {path: np.asarray(c[:]) for path, c in channels.items()}
            props = {**tdms.properties,
                     **{k: v for g in tdms.groups() for k, v in g.properties.items()}}
    except CalibrationError:
        raise
    except Exception as exc:  # npTDMS raises ValueError, KeyError, struct.error... on a bad file
        raise CalibrationError(f"{where}: row 0, column -: not a TDMS file npTDMS can read "
                               f"({type(exc).__name__}: {str(exc)[:120]})") from None
    short: dict[str, list[str]] = {}
    for path in channels:
        short.setdefault(path.split("/", 1)[1], []).append(path)
    names = list(channels)
    resolved = {}
    for c in COLUMNS:
        source = mapping.get(c, c)
        if source not in channels and len(short.get(source, [])) == 1:
            source = short[source][0]
        elif source not in channels and len(short.get(source, [])) > 1:
            raise _ambiguous_channel(where, c, source, short[source])
        resolved[c] = source
    index = _resolve(names, resolved, where, "channel")
    used = {c: names[i] for c, i in index.items()}
    lengths = {c: arrays[used[c]].size for c in COLUMNS}
    if len(set(lengths.values())) > 1:
        raise CalibrationError(f"{where}: channel lengths {lengths}: allowed equal lengths "
                               "(one value per reading in every channel)")
    k_sensor = default_k_sensor
    if SENSOR_KEY in props:
        k_sensor = _sensor_stiffness(str(props[SENSOR_KEY]), f"{where}: property {SENSOR_KEY}")
    readings = _Readings()
    for r in range(lengths["element"]):
        values = {}
        for c in COLUMNS:
            try:
                values[c] = float(arrays[used[c]][r])
            except (TypeError, ValueError):
                cell = str(arrays[used[c]][r])[:40]
                raise CalibrationError(f"{where}: row {r + 1}, column {c} (channel {used[c]!r}) = "
                                       f"{cell!r}: allowed a number", c, cell, "a number") from None
        readings.add(values, lambda c, r=r: f"{where}: row {r + 1}, column {c} "
                                            f"(channel {used[c]!r})", f"row {r + 1}")
    return readings.result(where, k_sensor), ReadInfo(where, "tdms", mapping=used,
                                                      readings=readings.count,
                                                      places=readings.places_of())


def _ambiguous_channel(where: str, column: str, name: str, paths: list[str]) -> CalibrationError:
    """The refusal of a bare channel name that more than one TDMS group holds."""
    groups = [p.split("/", 1)[0] for p in paths]
    listed = ", ".join(groups[:-1]) + f" and {groups[-1]}"
    allowed = (f"one channel per column: choose one with --map {column}={paths[0]} "
               f"(or another of {', '.join(paths)}), or keep one group in the file")
    return CalibrationError(f"{where}: column {column}: channel {name!r} is ambiguous: it is in "
                            f"groups {listed}: allowed {allowed}", column, name, allowed)


# ---------------------------------------------------------------------------
# Readings on a rigid flat (tip zeroing): element, step, deflection_um
# ---------------------------------------------------------------------------
#: The columns of a rigid-flat zeroing file: element number, the flat's step (one position
#: of the flat, every tip read at it) and the element's deflection there (um, from its
#: calibrated signal).
FLAT_COLUMNS = ("element", "step", "deflection_um")
#: Largest |deflection| read on a flat (um): far past any flexure's travel, so a value past
#: it is a damaged cell.
FLAT_DEFLECTION_LIMIT_UM = 1e5


def read_flat_readings(path, encoding: str | None = None
                       ) -> tuple[dict[int, dict[int, float]], ReadInfo]:
    """Each element's deflection at each step of a rigid flat pressed on every tip, from a
    CSV file (header ``element,step,deflection_um`` in any order; comma, semicolon or tab;
    decimal point or comma; ``#`` comments; encodings as :func:`read_measured`).

    Args:
        path: the file.
        encoding: its text encoding by name; None: UTF-8 or what a byte order mark says.

    Returns:
        ({step: {element: deflection (mm)}} in the file's order, :class:`ReadInfo`).

    Raises:
        CalibrationError: the file cannot be read or is too large, a column is missing or
            repeated, a value is not a number or out of range, an element is read twice in
            one step; the message names the file, the line and the column.
    """
    p = Path(path)
    where = str(p)
    if encoding is not None:
        _check_encoding(encoding)
    try:
        if not p.is_file():
            raise CalibrationError(f"{where}: not a file: allowed a CSV file of "
                                   f"{','.join(FLAT_COLUMNS)}")
        size = p.stat().st_size
        if size > MAX_BYTES:
            raise CalibrationError(f"{where}: {size} bytes: allowed at most {MAX_BYTES} bytes")
        raw = p.read_bytes()
    except OSError as exc:
        raise CalibrationError(f"{where}: cannot be read ({exc.strerror or exc})") from None
    _refuse_workbook(raw, where, f"a CSV file of {','.join(FLAT_COLUMNS)}")
    text, used = decode(raw, encoding, where)
    lines = [(n, line) for n, line in enumerate(text.splitlines(), start=1)
             if line.strip().strip(",;\t") and not line.strip().startswith("#")]
    if not lines:
        raise CalibrationError(f"{where}: line 1: no header and no readings; allowed a header "
                               f"{','.join(FLAT_COLUMNS)} and one reading per element and step")
    header_n, header_line = lines[0]
    separator, header = max(
        ((sep, [h.strip() for h in next(csv.reader([header_line], delimiter=sep))])
         for sep in _SEPARATORS), key=lambda sc: len(set(FLAT_COLUMNS) & set(sc[1])))
    missing = [c for c in FLAT_COLUMNS if c not in header]
    repeated = sorted({h for h in header if header.count(h) > 1})
    if missing or repeated:
        raise CalibrationError(f"{where}: line {header_n}: columns = {header}: allowed "
                               f"{list(FLAT_COLUMNS)} once each (missing {missing}, repeated "
                               f"{repeated}), separated by comma, semicolon or tab")
    index = {c: header.index(c) for c in FLAT_COLUMNS}
    decimal = _decimal_of(lines[1:], separator)
    steps: dict[int, dict[int, float]] = {}
    for n, line in lines[1:]:
        cells = next(csv.reader([line], delimiter=separator))
        if len(cells) > len(header) and not "".join(cells[len(header):]).strip():
            cells = cells[:len(header)]  # the empty cells after a trailing separator
        if len(cells) != len(header):
            raise CalibrationError(f"{where}: line {n}: {len(cells)} values: allowed "
                                   f"{len(header)} ({separator.join(header)})")
        at = lambda c, n=n: f"{where}: line {n}, column {c}"  # noqa: E731
        values = {c: _number(cells[i], at(c), decimal) for c, i in index.items()}
        element, step = _integer(values["element"], at("element")), _integer(values["step"],
                                                                             at("step"))
        if abs(values["deflection_um"]) > FLAT_DEFLECTION_LIMIT_UM:
            raise CalibrationError(f"{at('deflection_um')} = {values['deflection_um']!r}: "
                                   f"allowed |value| <= {FLAT_DEFLECTION_LIMIT_UM:g} um")
        row = steps.setdefault(step, {})
        if element in row:
            raise CalibrationError(f"{at('element')} = {element}: read twice in step {step}: "
                                   "allowed once per step")
        row[element] = 1e-3 * values["deflection_um"]
    if not steps:
        raise CalibrationError(f"{where}: readings = 0: allowed one reading per element and "
                               "step")
    count = sum(len(row) for row in steps.values())
    return steps, ReadInfo(where, "csv", used, separator, decimal,
                           {c: c for c in FLAT_COLUMNS}, count)
