"""What changed between two exports, read from their manifests.

:func:`compare` reads the two ``manifest.json`` files and reports

* parts added, removed and changed (quantity, process, material, volume,
  bounding box, or the bytes of the part's STEP file);
* elements whose part, arm, stiffness K or strength changed, before and after, paired by
  their row and column where both manifests record them (an element's number follows from
  the columns: a column removed is "row R column C removed", not every later element
  renumbered into its neighbour's place; those only renumbered are one line a row,
  ``row 2: elements 7-11 renumbered 6-10``), by their number otherwise; a silicon
  die's rows (its manifest's "rows": row 1 reference, row 2 measuring) likewise, each named
  by its number and role and with its own rated force;
* the closed-form verification (the manifest's ``requirements.closed_form_matrix``): each
  requirement whose target, prediction, error, margin, verdict or binding limit changed,
  the rated full-scale force's binding element force limit, margin and verdict among them;
* derived dimensions whose value changed; a product's values its design file states (a
  silicon die's ``[die]`` keys, :data:`PRODUCT_STATED_KEYS`) listed apart, as stated; a
  metal design's stated values (its manifest's ``stated``: every key its design file
  states, by dotted key, ``comb.web_thicknesses_mm``) likewise;
* the bill of materials (each export's ``bom.csv``): items added, removed and whose
  quantity changed;
* drawing sheets added, removed and changed; a new sheet that replaces the
  old sheet of the same element (the element's part was renamed when its arm
  changed) is compared with that sheet;
* the count of every file that differs (the assemblies, scenes, DXF sheets,
  BOM and PDF follow from the parts).

:func:`render_sheets` draws, for each changed sheet only, an overlay (old in
red, new in blue, unchanged lines black) and the two side by side as PNG.
Sheets are rasterised through the drawings' own path: SVG to PDF
(:mod:`tactcad.drawings.pdf`), PDF to pixels (PDFium).

Numbers are compared to a relative tolerance of :data:`REL_TOL`.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

from tactcad.catalogue.files import MANIFEST
from tactcad.errors import DesignError

REL_TOL = 1e-9
#: Element fields compared (manifest "strength" records), with their units.
ELEMENT_FIELDS = {
    "part_name": "", "arm_length_mm": "mm", "stiffness_N_per_mm": "N/mm",
    "stress_MPa_per_N": "MPa/N", "full_scale_force_N": "N", "yield_limited_force_N": "N",
    # the fatigue limits, which bind a thin web before yield (strength --json's names)
    "fatigue_force_N": "N", "gauge_fatigue_force_N": "N",
    "yield_safety_factor_at_full_scale": "", "gauge_strain_at_full_scale": "",
    "tip_deflection_mm_at_full_scale": "mm",
    # a silicon die's beams in a manifest written before its rows were named "rows"
    "stress_MPa_at_full_scale": "MPa", "strength_over_stress_at_rating": "",
}
#: The fields of a closed-form verification record compared (the manifest's
#: ``requirements.closed_form_matrix``, verify's names): the rated full-scale force's row
#: carries the binding element force limit (``predicted``), its margin and its verdict.
REQUIREMENT_FIELDS = ("target", "predicted", "error_estimate_rel", "margin_rel", "verdict",
                      "binding_words", "binding_element")
#: A silicon die's row fields compared (its manifest's "rows", one a row's beam), with their
#: units: the force is the row's own rated force, not the die's full-scale force.
ROW_FIELDS = {
    "role": "", "part_name": "", "arm_length_mm": "mm", "stiffness_N_per_mm": "N/mm",
    "rated_force_N": "N", "stress_MPa_per_N": "MPa/N", "stress_MPa_at_rated_force": "MPa",
    "strength_over_stress_at_rating": "",
}
#: A product's own table of derived values in its manifest (a silicon die's "die"), compared
#: value by value as the array's "derived" list is.
PRODUCT_SECTIONS = ("die",)
#: The keys of a product section that its design file states (a silicon die's ``[die]``
#: table: what the lab asked, or the key's default where the file leaves it out), listed by
#: the diff as stated, not derived.
PRODUCT_STATED_KEYS = {"die": ("kr_over_km", "kobj_range_N_per_mm", "full_scale_force_N",
                               "columns", "pitch_um", "kobj_resolution_rel",
                               "kobj_accuracy_rel", "max_grasp_force_N", "root_fillet_um")}
#: Units read from a derived value's name ending (the house's unit suffixes).
_UNIT_SUFFIXES = (("_N_per_mm", "N/mm"), ("_per_Pa", "1/Pa"), ("_um2", "um^2"), ("_um", "um"),
                  ("_mm", "mm"), ("_MPa", "MPa"), ("_N", "N"), ("_Hz", "Hz"), ("_K", "K"),
                  ("_V", "V"))
PART_FIELDS = ("kind", "process", "material", "quantity", "volume_mm3", "bbox_mm")
SHEET_KINDS = ("drawing-svg", "drawing-assembly")
OLD_RGB, NEW_RGB = (220, 30, 30), (30, 80, 230)
SHEET_DPI = 90


def read_manifest(folder: str | Path) -> dict:
    """The manifest of the export in ``folder``.

    Raises:
        DesignError: no readable ``manifest.json`` (naming the folder).
    """
    path = Path(folder) / MANIFEST
    try:
        man = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise DesignError("export", str(folder), f"a tactcad export folder with a readable "
                                                 f"{MANIFEST}", f"{type(exc).__name__}: {exc}") from None
    if not isinstance(man, dict) or not isinstance(man.get("files"), list):
        raise DesignError("export", str(folder), f"a tactcad export folder ({MANIFEST} with "
                                                 f"\"files\")")
    _check_records(man, folder)
    return man


#: Manifest lists compared by key: section -> (key field, its type).
_KEYED = {"files": ("path", str), "strength": ("element", int), "elements": ("element", int),
          "rows": ("row", int), "derived": ("name", str)}


_TYPE_WORDS = {str: "text", int: "an integer"}


def _check_records(man: dict, folder: str | Path) -> None:
    """Refuse a manifest whose compared sections are not as tactcad writes them.

    Raises:
        DesignError: naming the section, the record and what is allowed.
    """
    for section, (key, kind) in _KEYED.items():
        records = man.get(section, [])
        for k, r in enumerate(records if isinstance(records, list) else [records]):
            if not isinstance(r, dict) or not isinstance(r.get(key), kind) \
                    or isinstance(r.get(key), bool):
                raise DesignError(f"{MANIFEST}: {section}[{k}]", r,
                                  f"a record with \"{key}\" ({_TYPE_WORDS[kind]})",
                                  f"in {folder}: not a manifest tactcad wrote")
    if not isinstance(man.get("stated", {}), dict):
        raise DesignError(f"{MANIFEST}: stated", man["stated"],
                          "a table of the design file's values by dotted key",
                          f"in {folder}: not a manifest tactcad wrote")
    parts = man.get("parts", {})
    if not isinstance(parts, dict) or not all(isinstance(v, dict) for v in parts.values()):
        raise DesignError(f"{MANIFEST}: parts", parts, "a table of part records by name",
                          f"in {folder}: not a manifest tactcad wrote")


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) \
            and not isinstance(a, bool) and not isinstance(b, bool):
        return math.isclose(a, b, rel_tol=REL_TOL, abs_tol=1e-12)
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return all(_same(x, y) for x, y in zip(a, b))
    return a == b


def _changes(old: Mapping, new: Mapping, fields) -> dict[str, dict]:
    """{field: {"before", "after"}} of the fields whose values differ."""
    return {f: {"before": old.get(f), "after": new.get(f)} for f in fields
            if not _same(old.get(f), new.get(f))}


@dataclass
class Diff:
    """The differences between two exports (see the module doc); JSON-ready."""

    old: str
    new: str
    parts: dict = field(default_factory=dict)  # added, removed, changed
    elements: list = field(default_factory=list)
    rows: list = field(default_factory=list)  # a silicon die's rows
    requirements: list = field(default_factory=list)  # the closed-form verification's records
    derived: list = field(default_factory=list)
    stated: list = field(default_factory=list)  # a product's values its design file states
    sheets: list = field(default_factory=list)
    bom: dict = field(default_factory=dict)  # added, removed, changed (bom.csv's items)
    files: dict = field(default_factory=dict)  # changed, added, removed (paths)
    #: (older, newer) product where the two exports are of different products, else None
    products: tuple | None = None

    @property
    def changed(self) -> bool:
        """True when anything differs, the bytes of any file included."""
        return bool(any(self.parts.values()) or self.elements or self.rows or self.requirements
                    or self.derived
                    or self.stated or self.sheets or any(self.bom.values())
                    or any(self.files.values()))

    def as_json(self) -> dict:
        return {"old": self.old, "new": self.new, "changed": self.changed, "parts": self.parts,
                "elements": self.elements, "rows": self.rows,
                "requirements": self.requirements, "derived": self.derived,
                "stated": self.stated, "sheets": self.sheets, "bom": self.bom,
                "files": self.files}

    def lines(self) -> list[str]:
        """The report as text, one finding a line."""
        out = [products_line(*self.products)] if self.products else []
        for name in self.parts.get("added", []):
            out.append(f"part added    {name}")
        for name in self.parts.get("removed", []):
            out.append(f"part removed  {name}")
        for name, ch in self.parts.get("changed", {}).items():
            out.append(f"part changed  {name}: " + _fields_text(ch))
        out += element_lines(self.elements)
        for r in self.rows:
            out.append(f"{row_words(r)}  " + _fields_text(r["changes"], ROW_FIELDS))
        for r in self.requirements:
            out.append(f"requirement   {r['requirement']}: " + _requirement_text(r["changes"]))
        for kind, values in (("stated", self.stated), ("derived", self.derived)):
            for d in values:
                out.append(f"{kind:<13} {d['name']}: {_value(d['before'])} -> "
                           f"{_value(d['after'])} {d.get('unit') or ''}".rstrip())
        for s in self.sheets:
            text = f"sheet {s['status']:<8}{s['sheet']}"
            if s.get("compared_with") and s["compared_with"] != s["sheet"]:
                text += f" (against {s['compared_with']})"
            for key in ("overlay", "side_by_side"):
                if s.get(key):
                    text += f"  {key.replace('_', '-')}: {s[key]}"
            out.append(text)
        out += bom_lines(self.bom)
        f = self.files
        if any(f.values()):
            out.append(f"files         {len(f['changed'])} changed, {len(f['added'])} added, "
                       f"{len(f['removed'])} removed")
        out.append("changed" if self.changed else "no change")
        return out


def _value(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, list):
        return compact_list(v)
    return "-" if v is None else str(v)


def compact_list(values: list) -> str:
    """A list with each run of equal values once and its count:
    ``[0.164 x6, 0.08 x6]`` for six 0.164 then six 0.08."""
    runs: list[list] = []
    for v in values:
        if runs and _same(runs[-1][0], v):
            runs[-1][1] += 1
        else:
            runs.append([v, 1])
    return "[" + ", ".join(_value(v) + (f" x{n}" if n > 1 else "") for v, n in runs) + "]"


def element_line(record: Mapping[str, Any]) -> str:
    """An element's finding as text: ``row 1 column 6 removed (element 6)`` for an element
    only one export has, else ``element 6 (row 2 column 1)  element 7 -> 6, K ...`` (the
    place where the manifests record it); :func:`element_lines` groups those only
    renumbered by row."""
    changes = dict(record["changes"])
    place = (f"row {record['row']} column {record['column']}"
             if record.get("row") is not None and record.get("column") is not None else "")
    present = changes.get("present")
    if place and present:
        return f"{place} {'added' if present['after'] else 'removed'} " \
               f"(element {record['element']})"
    if place:
        return f"element {record['element']} ({place})  " + _fields_text(changes)
    return f"element {record['element']:<4} " + _fields_text(changes)


def only_renumbered(record: Mapping[str, Any]) -> bool:
    """Whether an element's finding is its number alone, at a place both manifests record
    (a column removed or added before it in the numbering).

    Args:
        record: one of :attr:`Diff.elements`.

    Returns:
        True for a renumbered element whose part, arm, K and strength are as they were.
    """
    return (record.get("row") is not None and record.get("column") is not None
            and list(record["changes"]) == ["element"])


def number_runs(pairs: list[tuple[int, int]]) -> list[tuple[int, int, int, int]]:
    """(old, new) element numbers in runs of consecutive numbers moved by the same step:
    ``[(7, 6), (8, 7), (9, 8)]`` -> ``[(7, 9, 6, 8)]``.

    Args:
        pairs: (number before, number after), in the order of their places.

    Returns:
        (first before, last before, first after, last after) for each run.
    """
    runs: list[list[int]] = []
    for old, new in pairs:
        last = runs[-1] if runs else None
        if last and old == last[1] + 1 and new == last[3] + 1:
            last[1], last[3] = old, new
        else:
            runs.append([old, old, new, new])
    return [tuple(r) for r in runs]


def run_words(first: int, last: int, first_after: int, last_after: int) -> str:
    """A run of renumbered elements: ``elements 7-11 renumbered 6-10`` (``element 7
    renumbered 6`` for one)."""
    if first == last:
        return f"element {first} renumbered {first_after}"
    return f"elements {first}-{last} renumbered {first_after}-{last_after}"


def element_lines(elements: list[Mapping[str, Any]]) -> list[str]:
    """The elements' findings as text: each element added, removed or changed a line
    (:func:`element_line`) first, then one line a row for the elements only renumbered
    (``row 2: elements 7-11 renumbered 6-10``), so that a removed column is read before
    the numbering it moves.

    Args:
        elements: :attr:`Diff.elements`, in the order of their places.

    Returns:
        The lines.
    """
    out = [element_line(e) for e in elements if not only_renumbered(e)]
    rows: dict[int, list[tuple[int, int]]] = {}
    for e in elements:
        if only_renumbered(e):
            ch = e["changes"]["element"]
            rows.setdefault(e["row"], []).append((ch["before"], ch["after"]))
    for row, pairs in rows.items():
        out.append(f"row {row}: " + ", ".join(run_words(*r) for r in number_runs(pairs)))
    return out


def bom_lines(bom: Mapping[str, Any]) -> list[str]:
    """The bill of materials' findings as text, one item a line."""
    out = [f"bom added     {r['item']} x{_value(r['quantity'])}" for r in bom.get("added", [])]
    out += [f"bom removed   {r['item']} x{_value(r['quantity'])}"
            for r in bom.get("removed", [])]
    out += [f"bom quantity  {r['item']}: {_value(r['before'])} -> {_value(r['after'])}"
            for r in bom.get("changed", [])]
    return out


def row_words(record: Mapping[str, Any]) -> str:
    """A die's row as the die's commands name it: ``row 2 (measuring)``."""
    role = record.get("role")
    return f"row {record['row']}" + (f" ({role})" if role else "")


def presence_word(changes: Mapping[str, Mapping]) -> str | None:
    """"added" or "removed" for a record only one export has (its ``present`` change),
    else None.

    Args:
        changes: a record's changes ({field: {"before", "after"}}).

    Returns:
        The word, or None where both exports have the record.
    """
    present = changes.get("present")
    if not isinstance(present, Mapping):
        return None
    return "added" if present.get("after") else "removed"


def _fields_text(changes: Mapping[str, Mapping], units: Mapping[str, str] = ELEMENT_FIELDS
                 ) -> str:
    if (word := presence_word(changes)) is not None:
        return word
    parts = []
    for k, ch in changes.items():
        unit = units.get(k, "")
        parts.append(f"{k} {_value(ch['before'])} -> {_value(ch['after'])}"
                     + (f" {unit}" if unit else ""))
    return ", ".join(parts)


def _requirement_text(changes: Mapping[str, Mapping]) -> str:
    """A requirement's changes, a margin in per cent (``margin_rel +1.4 % -> -9.1 %``)."""
    def shown(key: str, v: Any) -> str:
        if key == "margin_rel" and isinstance(v, (int, float)) and not isinstance(v, bool):
            return f"{100 * v:+.3g} %"
        return _value(v)

    if (word := presence_word(changes)) is not None:
        return word
    return ", ".join(f"{k} {shown(k, ch['before'])} -> {shown(k, ch['after'])}"
                     for k, ch in changes.items())


def _matrix(man: dict) -> dict[str, dict]:
    """The manifest's closed-form verification records by requirement (none: empty)."""
    req = man.get("requirements")
    records = req.get("closed_form_matrix") if isinstance(req, Mapping) else None
    return {r["requirement"]: r for r in records or []
            if isinstance(r, Mapping) and isinstance(r.get("requirement"), str)}


def _requirements(old: dict, new: dict) -> list[dict]:
    """The closed-form verification records whose :data:`REQUIREMENT_FIELDS` differ:
    ``{"requirement", "changes"}``, in the newer manifest's order (a record only one has:
    ``present`` before / after)."""
    a, b = _matrix(old), _matrix(new)
    out = []
    for name in list(b) + [n for n in a if n not in b]:
        if name not in a or name not in b:
            out.append({"requirement": name,
                        "changes": {"present": {"before": name in a, "after": name in b}}})
            continue
        ch = _changes(a[name], b[name], REQUIREMENT_FIELDS)
        if ch:
            out.append({"requirement": name, "changes": ch})
    return out


def compare(old_dir: str | Path, new_dir: str | Path) -> Diff:
    """Compare the exports in two folders from their manifests (no geometry is built).

    Raises:
        DesignError: a folder without a readable manifest.
    """
    old, new = read_manifest(old_dir), read_manifest(new_dir)
    diff = Diff(str(old_dir), str(new_dir))
    old_files = {f["path"]: f for f in old["files"]}
    new_files = {f["path"]: f for f in new["files"]}
    diff.files = {"changed": sorted(p for p in old_files.keys() & new_files.keys()
                                    if old_files[p].get("sha256") != new_files[p].get("sha256")),
                  "added": sorted(new_files.keys() - old_files.keys()),
                  "removed": sorted(old_files.keys() - new_files.keys())}
    diff.parts = _parts(old, new, old_files, new_files)
    diff.elements = _elements(old, new)
    diff.rows = _rows(old, new)
    diff.requirements = _requirements(old, new)
    changed = _derived(old, new)
    diff.stated = _stated(old, new) + [d for d in changed if _is_stated(d["name"])]
    diff.derived = [d for d in changed if not _is_stated(d["name"])]
    diff.sheets = _sheets(old, new, old_files, new_files)
    diff.bom = _bom(read_bom(old_dir, old_files), read_bom(new_dir, new_files))
    return only_shared(diff, old.get("product"), new.get("product"))


def products_line(old: Any, new: Any) -> str:
    """The line saying two exports are of different products (named as their manifests
    name them), said once at the top of the report."""
    return (f"products      the two exports are of different products ({old} -> {new}): "
            "only what both record is compared")


def only_shared(diff: Diff, old: Any, new: Any) -> Diff:
    """``diff`` where the manifests name different products (``old``, ``new``): its
    elements, rows, requirements and stated values only one export records left out (one
    product's records are not the other's removed or added) and the products noted;
    ``diff`` itself where they are the same or either names none.

    Args:
        diff: the comparison. old, new: the manifests' ``product``.

    Returns:
        The comparison (the same object, changed in place).
    """
    if not old or not new or old == new:
        return diff
    diff.products = (old, new)
    diff.elements = [e for e in diff.elements if presence_word(e["changes"]) is None]
    diff.rows = [r for r in diff.rows if presence_word(r["changes"]) is None]
    diff.requirements = [r for r in diff.requirements if presence_word(r["changes"]) is None]
    diff.stated = [d for d in diff.stated if d["before"] is not None and d["after"] is not None]
    return diff


def _stated(old: dict, new: dict) -> list[dict]:
    """The design file's stated values (the manifest's ``stated``: dotted key -> value) that
    differ: ``{"name", "before", "after", "unit"}``, in the newer manifest's order (a key
    only one file states: None on the other side); none when either manifest records none."""
    a, b = old.get("stated"), new.get("stated")
    if not isinstance(a, Mapping) or not isinstance(b, Mapping):
        return []
    return [{"name": k, "before": a.get(k), "after": b.get(k), "unit": _unit_of(k)}
            for k in list(b) + [k for k in a if k not in b] if not _same(a.get(k), b.get(k))]


#: The bill of materials an export writes, and its columns naming an item and its quantity
#: (an array's ``part``/``quantity``; a die's ``item``/``qty``).
BOM_FILE = "bom.csv"
BOM_ITEM_COLUMNS = ("part", "item")
BOM_QUANTITY_COLUMNS = ("quantity", "qty")


def read_bom(folder: str | Path, files: Mapping[str, dict]) -> dict[str, Any] | None:
    """The export's bill of materials as {item: quantity} (pcs, or the row's unit), each
    item's rows summed; None when its manifest lists no ``bom.csv`` or it cannot be read.

    Raises:
        DesignError: a ``bom.csv`` path leading out of the export, or one whose sha256 is
            not the one the manifest records of it (:func:`bom_unchanged`).
    """
    import csv

    if BOM_FILE not in files:
        return None
    path = _inside(folder, BOM_FILE)
    bom_unchanged(path, files[BOM_FILE])
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError):
        return None
    rows = list(csv.DictReader(text.splitlines()))
    if not rows:
        return {}
    item = next((c for c in BOM_ITEM_COLUMNS if c in rows[0]), None)
    qty = next((c for c in BOM_QUANTITY_COLUMNS if c in rows[0]), None)
    if item is None or qty is None:
        return None
    out: dict[str, Any] = {}
    for r in rows:
        n = _number(r.get(qty))
        was = out.get(r[item])
        out[r[item]] = n if was is None else (
            was + n if isinstance(was, (int, float)) and isinstance(n, (int, float)) else n)
    return out


def bom_unchanged(path: Path, record: Mapping[str, Any]) -> None:
    """Refuse an export's ``bom.csv`` that is not the file its manifest records: its sha256
    (hex) differs from the manifest's (edited or damaged since the export). A record
    without a digest, or a file that cannot be read, is let through.

    Args:
        path: the export's ``bom.csv``. record: the manifest's record of it.

    Raises:
        DesignError: the digests differ.
    """
    from tactcad.atomic import file_sha256

    digest = record.get("sha256") if isinstance(record, Mapping) else None
    try:
        actual = file_sha256(path) if isinstance(digest, str) else None
    except OSError:
        return
    if actual is not None and actual != digest:
        raise DesignError(f"{MANIFEST}: files", str(path),
                          f"the {BOM_FILE} whose sha256 the manifest records",
                          f"{path} is not the file the export wrote (edited or damaged since); "
                          "export again, or compare another export")


def _number(text: Any) -> Any:
    """A quantity's text as an int or float; the text itself when it is neither."""
    for kind in (int, float):
        try:
            return kind(text)
        except (TypeError, ValueError):
            pass
    return text


def _bom(old: Mapping[str, Any] | None, new: Mapping[str, Any] | None) -> dict:
    """The bill of materials' items added, removed and whose quantity changed:
    ``{"added": [{"item", "quantity"}], "removed": [...], "changed": [{"item", "before",
    "after"}]}`` in the newer BOM's order; empty when either export has no BOM."""
    if old is None or new is None:
        return {}
    return {"added": [{"item": k, "quantity": v} for k, v in new.items() if k not in old],
            "removed": [{"item": k, "quantity": v} for k, v in old.items() if k not in new],
            "changed": [{"item": k, "before": old[k], "after": v} for k, v in new.items()
                        if k in old and not _same(old[k], v)]}


def _step_sha(files: Mapping[str, dict], part: str) -> str | None:
    rec = files.get(f"step/{part}.step")
    return rec.get("sha256") if rec else None


def _parts(old: dict, new: dict, old_files, new_files) -> dict:
    a, b = old.get("parts", {}), new.get("parts", {})
    changed = {}
    for name in [n for n in a if n in b]:
        ch = _changes(a[name], b[name], PART_FIELDS)
        if _step_sha(old_files, name) != _step_sha(new_files, name) and not ch:
            ch["step"] = {"before": "STEP file", "after": "STEP file with other bytes"}
        if ch:
            changed[name] = ch
    return {"added": [n for n in b if n not in a], "removed": [n for n in a if n not in b],
            "changed": changed}


def _by_element(man: dict) -> dict[int, dict]:
    """The element records: an array's "strength" list; a die's "elements" (its beams, in a
    manifest written before they were its "rows")."""
    records = man.get("strength") or man.get("elements") or []
    return {r["element"]: r for r in records if "element" in r}


def _unit_of(name: str) -> str:
    """The unit a dotted name gives: the innermost part ending in a unit suffix
    (``cavity_depths_um.reference``: um), else a unit word inside it
    (``root_peak_stress_MPa_at_rated_force``: MPa); "" for none."""
    for part in reversed(name.split(".")):
        found = next((unit for suffix, unit in _UNIT_SUFFIXES if part.endswith(suffix)), "")
        if found:
            return found
        words = [w for w in part.split("_") if w in ("MPa", "um", "mm", "Hz")]
        if words:
            return words[-1]
    return ""


def _flat_values(table: Mapping, prefix: str = "") -> dict[str, Any]:
    """A product table's numbers (and lists of numbers) by dotted name, nested tables
    flattened; texts (sources, notes) are left out: the files' bytes report those."""
    out: dict[str, Any] = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(_flat_values(value, name + "."))
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            out[name] = value
        elif isinstance(value, list) and value and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            out[name] = value
    return out


def _derived_records(man: dict) -> list[dict]:
    """The manifest's derived values: its "derived" list, and each product section's
    numbers (:data:`PRODUCT_SECTIONS`) named ``section.key`` with the unit their name gives."""
    records = list(man.get("derived", []))
    for section in PRODUCT_SECTIONS:
        table = man.get(section)
        if isinstance(table, Mapping):
            records += [{"name": f"{section}.{k}", "value": v, "unit": _unit_of(k)}
                        for k, v in _flat_values(table).items()]
    return records


def _place(record: Mapping[str, Any]) -> tuple[int, int] | None:
    """(row, column) of an element record (1-based); None when it records neither."""
    r, c = record.get("row"), record.get("column")
    ok = all(isinstance(v, int) and not isinstance(v, bool) for v in (r, c))
    return (r, c) if ok else None


def element_pairs(old: dict, new: dict) -> list[tuple[dict | None, dict | None]]:
    """The two exports' element records paired: by (row, column) when every record of both
    records its place, else by element number; (old, None) for an element only the older
    export has, (None, new) for one only the newer has; in the order of their places."""
    a, b = _by_element(old), _by_element(new)
    placed = a and b and all(_place(r) for r in [*a.values(), *b.values()])
    if placed:
        a = {_place(r): r for r in a.values()}
        b = {_place(r): r for r in b.values()}
    return [(a.get(k), b.get(k)) for k in sorted(a.keys() | b.keys())]


def _elements(old: dict, new: dict) -> list[dict]:
    """The elements whose :data:`ELEMENT_FIELDS` (or number, where they are paired by their
    place) differ: ``{"element", "changes"}`` (the newer export's number, the older's for an
    element it lacks), with ``row`` and ``column`` where both manifests record them."""
    out = []
    for ra, rb in element_pairs(old, new):
        rec = rb or ra
        head = {"element": rec["element"]}
        if all(_place(r) for r in (ra, rb) if r is not None):  # both record it
            head.update(row=_place(rec)[0], column=_place(rec)[1])
        if ra is None or rb is None:
            out.append({**head, "changes": {"present": {"before": ra is not None,
                                                        "after": rb is not None}}})
            continue
        ch = _changes(ra, rb, ("element",) if ra["element"] != rb["element"] else ())
        ch.update(_changes(ra, rb, ELEMENT_FIELDS))
        if ch:
            out.append({**head, "changes": ch})
    return out


def _rows(old: dict, new: dict) -> list[dict]:
    """A die's rows (its manifest's "rows") whose fields differ: ``{"row", "role",
    "changes"}``, the role the newer manifest's (the older's for a row it lacks)."""
    a = {r["row"]: r for r in old.get("rows") or []}
    b = {r["row"]: r for r in new.get("rows") or []}
    out = []
    for n in sorted(a.keys() | b.keys()):
        role = (b.get(n) or a.get(n)).get("role")
        if n not in a or n not in b:
            out.append({"row": n, "role": role,
                        "changes": {"present": {"before": n in a, "after": n in b}}})
            continue
        ch = _changes(a[n], b[n], ROW_FIELDS)
        if ch:
            out.append({"row": n, "role": role, "changes": ch})
    return out


def _is_stated(name: str) -> bool:
    """Whether the derived record ``name`` (``section.key...``) is a value its product's
    design file states (:data:`PRODUCT_STATED_KEYS`)."""
    section, _, key = name.partition(".")
    return key.split(".")[0] in PRODUCT_STATED_KEYS.get(section, ())


def _derived(old: dict, new: dict) -> list[dict]:
    a = {d["name"]: d for d in _derived_records(old)}
    b = {d["name"]: d for d in _derived_records(new)}
    out = []
    for name in list(a) + [n for n in b if n not in a]:
        before, after = a.get(name, {}).get("value"), b.get(name, {}).get("value")
        if not _same(before, after):
            out.append({"name": name, "before": before, "after": after,
                        "unit": (b.get(name) or a.get(name)).get("unit")})
    return out


def _sheets(old: dict, new: dict, old_files, new_files) -> list[dict]:
    a = {p: f for p, f in old_files.items() if f.get("kind") in SHEET_KINDS}
    b = {p: f for p, f in new_files.items() if f.get("kind") in SHEET_KINDS}
    # a part renamed by its element's change: its new sheet replaces the old one
    renamed = {}
    for ra, rb in element_pairs({"strength": old.get("strength", [])},
                                {"strength": new.get("strength", [])}):
        was = ra.get("part_name") if ra else None
        if rb and was and was != rb.get("part_name"):
            renamed.setdefault(f"drawings/{rb['part_name']}.svg", f"drawings/{was}.svg")
    out = []
    for path in sorted(a.keys() | b.keys(), key=lambda p: (p == "drawings/assembly.svg", p)):
        if path in a and path in b:
            if a[path].get("sha256") != b[path].get("sha256"):
                out.append({"sheet": path, "status": "changed", "compared_with": path})
        elif path in b:
            against = renamed.get(path)
            out.append({"sheet": path, "status": "added",
                        "compared_with": against if against in a else None})
        else:
            out.append({"sheet": path, "status": "removed", "compared_with": None})
    return out


# --- pictures of the changed sheets ----------------------------------------------------------
def render_sheets(diff: Diff, old_dir: str | Path, new_dir: str | Path, out_dir: str | Path,
                  dpi: int = SHEET_DPI) -> list[Path]:
    """For each changed sheet (or new sheet with one to compare against):
    ``<sheet>_overlay.png`` and ``<sheet>_side_by_side.png`` in ``out_dir``;
    the paths are also set on the diff's sheet records. Unchanged sheets are
    not rendered.

    Raises:
        OSError: a sheet cannot be read or a picture written.
        ValueError: a sheet's SVG cannot be parsed.
    """
    from tactcad.atomic import write_atomic

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for s in diff.sheets:
        if not s.get("compared_with"):
            continue
        before = sheet_pixels(_inside(old_dir, s["compared_with"]), dpi)
        after = sheet_pixels(_inside(new_dir, s["sheet"]), dpi)
        stem = Path(s["sheet"]).stem
        for key, image in (("overlay", overlay(before, after)),
                           ("side_by_side", side_by_side(before, after))):
            target = out / f"{stem}_{key}.png"
            write_atomic(target, lambda tmp, im=image: _save_png(im, tmp))
            s[key] = str(target)
            written.append(target)
    return written


#: The record a diff's ``--out`` folder holds of the pictures that diff wrote there: how a
#: later diff into the folder knows which files are an earlier comparison's (replaced) and
#: which are the lab's (never deleted).
DIFF_RECORD = "diff.json"
#: What the record says wrote it.
DIFF_WRITER = "tactcad diff"


def earlier_diff_files(out_dir: str | Path) -> set[str]:
    """The files in ``out_dir`` an earlier diff wrote (its :data:`DIFF_RECORD` and the
    pictures it lists), names relative to the folder; empty for a new or empty folder.

    Raises:
        DesignError: ``out_dir`` holds anything else (files no diff recorded, a folder, or a
            record no diff wrote): a diff's pictures would be mixed with them.
    """
    out = Path(out_dir)
    present = {p.name for p in out.iterdir()} if out.is_dir() else set()
    if not present:
        return set()
    listed = _recorded(out / DIFF_RECORD)
    ours = {DIFF_RECORD} | listed if listed is not None else set()
    foreign = sorted(n for n in present if n not in ours or not (out / n).is_file())
    if foreign:
        raise DesignError("--out", str(out), "a new or empty folder, or one holding an "
                          f"earlier diff's pictures (listed in its {DIFF_RECORD}, replaced)",
                          unknown_files_reason(out, foreign, listed is not None,
                                               DIFF_RECORD in present))
    return ours & present


def unknown_files_reason(out: Path, foreign: list[str], recorded: bool,
                         record_present: bool) -> str:
    """Why a diff's ``--out`` folder is refused, and what to do.

    Args:
        out: the folder. foreign: the names in it no diff record lists (sorted).
        recorded: True where the folder holds a :data:`DIFF_RECORD` a diff wrote.
        record_present: True where it holds a file of that name at all.

    Returns:
        The reason: the files a diff's record does not list where it has one, else that it
        has none a diff wrote (so its files, an older diff's pictures say, cannot be told
        from a lab's); and to empty the folder or name another.
    """
    names = f"{', '.join(foreign[:5])}{' ...' if len(foreign) > 5 else ''}"
    todo = "empty it, or name another folder"
    if recorded:
        return (f"{out} holds files its {DIFF_RECORD} does not list ({names}): this "
                f"comparison's pictures would be mixed with them; {todo}")
    which = (f"a {DIFF_RECORD} no diff wrote" if record_present
             else f"no {DIFF_RECORD} (the record a diff keeps of the pictures it wrote)")
    return (f"{out} holds {which}, so its files ({names}) cannot be told from a lab's "
            f"and none is deleted; {todo}")


def _recorded(record: Path) -> set[str] | None:
    """The picture names a diff record lists; None when ``record`` is not one a diff wrote
    (missing, unreadable, another writer's, or naming a path outside its folder)."""
    try:
        data = json.loads(record.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("written_by") != DIFF_WRITER:
        return None
    files = data.get("files")
    if not isinstance(files, list) or not all(
            isinstance(f, str) and f == Path(f).name and f not in ("", ".", "..", DIFF_RECORD)
            for f in files):
        return None
    return set(files)


def clear_earlier_diff(out_dir: str | Path) -> list[str]:
    """Delete the files an earlier diff wrote in ``out_dir`` (:func:`earlier_diff_files`),
    so the folder holds only the coming comparison's; returns their names.

    Raises:
        DesignError: the folder holds files no diff wrote (nothing is deleted then).
        OSError: a file cannot be deleted.
    """
    out = Path(out_dir)
    names = sorted(earlier_diff_files(out), key=lambda n: n == DIFF_RECORD)  # record last
    for name in names:
        (out / name).unlink(missing_ok=True)
    return names


def write_diff_record(diff: Diff, written: list[Path], out_dir: str | Path) -> Path:
    """Write :data:`DIFF_RECORD` into ``out_dir``: the comparison (``old``, ``new``) and the
    pictures it wrote there (``files``, names; empty where nothing changed, so a later diff
    still knows the folder as a diff's).

    Args:
        diff: the comparison. written: the pictures it wrote. out_dir: the ``--out`` folder.

    Returns:
        The record's path.

    Raises:
        OSError: the record cannot be written.
    """
    from tactcad.atomic import write_bytes_atomic

    Path(out_dir).mkdir(parents=True, exist_ok=True)
    record = {"written_by": DIFF_WRITER, "old": diff.old, "new": diff.new,
              "files": sorted(Path(p).name for p in written)}
    return write_bytes_atomic(Path(out_dir) / DIFF_RECORD,
                              (json.dumps(record, indent=1) + "\n").encode("utf-8"))


def _inside(folder: str | Path, rel: str) -> Path:
    """``folder / rel``, refused when a manifest's path would lead out of the export.

    Raises:
        DesignError: an absolute path or one leaving ``folder``.
    """
    base = Path(folder).resolve()
    path = (base / rel).resolve()
    if Path(rel).is_absolute() or not path.is_relative_to(base):
        raise DesignError(f"{MANIFEST}: files", rel, "a path inside the export folder",
                          f"in {folder}: not a manifest tactcad wrote")
    return path


def _save_png(image, path: Path) -> None:
    from PIL import Image

    Image.fromarray(image).save(path, format="PNG", optimize=False)


def sheet_pixels(svg: Path, dpi: int = SHEET_DPI):
    """A drawing sheet as grey levels, (rows, columns) uint8, 0 ink ... 255 paper."""
    import tempfile

    import numpy as np
    import pypdfium2 as pdfium

    from tactcad.drawings.pdf import svgs_to_pdf

    text = svg.read_text(encoding="utf-8")
    with tempfile.TemporaryDirectory() as tmp:
        pdf = Path(tmp) / "sheet.pdf"
        svgs_to_pdf([text], pdf)
        doc = pdfium.PdfDocument(str(pdf))
        try:
            image = doc[0].render(scale=dpi / 72.0).to_pil().convert("L")
            return np.asarray(image, dtype=np.uint8).copy()
        finally:
            doc.close()


def _padded(a, shape):
    import numpy as np

    out = np.full(shape, 255, dtype=np.uint8)
    out[: a.shape[0], : a.shape[1]] = a
    return out


def overlay(before, after, threshold: int = 160):
    """RGB (rows, columns, 3) uint8: ink only in ``before`` red, only in
    ``after`` blue, in both black, neither white."""
    import numpy as np

    shape = (max(before.shape[0], after.shape[0]), max(before.shape[1], after.shape[1]))
    a, b = _padded(before, shape) < threshold, _padded(after, shape) < threshold
    image = np.full(shape + (3,), 255, dtype=np.uint8)
    image[a & ~b] = OLD_RGB
    image[b & ~a] = NEW_RGB
    image[a & b] = (0, 0, 0)
    return image


def side_by_side(before, after, gap_px: int = 12):
    """RGB (rows, columns, 3) uint8: ``before`` on the left, ``after`` on the right."""
    import numpy as np

    rows = max(before.shape[0], after.shape[0])
    left = _padded(before, (rows, before.shape[1]))
    right = _padded(after, (rows, after.shape[1]))
    grey = np.hstack([left, np.full((rows, gap_px), 128, dtype=np.uint8), right])
    return np.repeat(grey[:, :, None], 3, axis=2)
