"""STEP AP214 writer: labelled, coloured parts and flat instanced assemblies in mm.

Written through OpenCascade's XCAF document directly so that a repeated part
is stored once (one product) and placed many times (one component each), the
assembly is one flat level (nested compounds can lose their labels in
importers), and the header time stamp is fixed (the same design writes the
same bytes).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import build123d as bd
from OCP.APIHeaderSection import APIHeaderSection_MakeHeader
from OCP.IFSelect import IFSelect_ReturnStatus
from OCP.Interface import Interface_Static
from OCP.Message import Message, Message_Gravity
from OCP.Quantity import Quantity_Color, Quantity_TypeOfColor
from OCP.STEPCAFControl import STEPCAFControl_Controller, STEPCAFControl_Writer
from OCP.STEPControl import STEPControl_Controller, STEPControl_StepModelType
from OCP.TCollection import TCollection_ExtendedString, TCollection_HAsciiString
from OCP.TDataStd import TDataStd_Name
from OCP.TDocStd import TDocStd_Document
from OCP.XCAFApp import XCAFApp_Application
from OCP.XCAFDoc import XCAFDoc_ColorType, XCAFDoc_DocumentTool
from OCP.XSControl import XSControl_WorkSession

from tactcad.atomic import write_atomic, write_failed

FIXED_TIMESTAMP = "2000-01-01T00:00:00"
_TIMESTAMP_RE = re.compile(rb"FILE_NAME\('([^']*)','[^']*'")


@dataclass(frozen=True)
class StepPart:
    name: str
    solid: bd.Shape
    color: tuple[float, float, float]


@dataclass(frozen=True)
class StepInstance:
    name: str
    part: str
    location: bd.Location


def _quiet() -> None:
    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)


def _new_document() -> TDocStd_Document:
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    app = XCAFApp_Application.GetApplication_s()
    app.NewDocument(TCollection_ExtendedString("MDTV-XCAF"), doc)
    app.InitDocument(doc)
    XCAFDoc_DocumentTool.SetLengthUnit_s(doc, 0.001)  # document unit: mm
    return doc


def _name(label, text: str) -> None:
    TDataStd_Name.Set_s(label, TCollection_ExtendedString(text))


def _write_doc(doc: TDocStd_Document, path: Path, product_name: str) -> None:
    _quiet()
    STEPCAFControl_Controller.Init_s()
    STEPControl_Controller.Init_s()
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    Interface_Static.SetCVal_s("write.step.product.name", product_name)
    writer = STEPCAFControl_Writer(XSControl_WorkSession(), False)
    writer.SetColorMode(True)
    writer.SetNameMode(True)
    writer.SetLayerMode(False)
    header = APIHeaderSection_MakeHeader(writer.Writer().Model())
    header.SetName(TCollection_HAsciiString(product_name))
    header.SetTimeStamp(TCollection_HAsciiString(FIXED_TIMESTAMP))
    header.SetOriginatingSystem(TCollection_HAsciiString("tactcad"))
    if not writer.Transfer(doc, STEPControl_StepModelType.STEPControl_AsIs):
        raise RuntimeError(f"STEP transfer failed for {product_name}")
    if writer.Write(str(path)) != IFSelect_ReturnStatus.IFSelect_RetDone:
        raise write_failed(path, "STEP write")  # OpenCascade says no more than that
    _normalise(path)


_NAUO_RE = re.compile(rb"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('[^']*'")


_NAUO_ENTITY_RE = re.compile(rb"NEXT_ASSEMBLY_USAGE_OCCURRENCE\(.*?\);", re.S)


def _normalise(path: Path) -> None:
    """Fix what OpenCascade varies between runs: the header time stamp, and the
    assembly-usage ids, which come from a process-wide counter. Those entities
    are first put on one line each: OpenCascade wraps long lines, and where it
    wrapped depends on how many digits the old id had."""
    data = path.read_bytes()
    data = _TIMESTAMP_RE.sub(lambda m: m.group(0).replace(
        m.group(0).split(b"','")[1].rstrip(b"'"), FIXED_TIMESTAMP.encode()), data, count=1)
    data = _NAUO_ENTITY_RE.sub(lambda m: re.sub(rb"\r?\n\s*", b"", m.group(0)), data)
    counter = iter(range(1, 1 << 30))
    data = _NAUO_RE.sub(lambda m: b"NEXT_ASSEMBLY_USAGE_OCCURRENCE('%d'" % next(counter), data)
    path.write_bytes(_canonical_styles(data))


_ENTITY_RE = re.compile(rb"^#(\d+) = (.*?);\s*$", re.S | re.M)
_REF_RE = re.compile(rb"#(\d+)")
_STYLE_START = b"MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION"


def _canonical_styles(data: bytes) -> bytes:
    """Put the colour (styled item) groups in a fixed order and renumber them.

    OpenCascade writes one group per coloured part, starting at a
    MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION, in an order that
    varies between runs. The groups are sorted by the shape representation
    they style (whose id is stable) and renumbered. This assumes groups share
    no entities, which holds when every part has its own colour (checked).
    """
    pos = data.find(_STYLE_START)
    if pos < 0:
        return data
    first = data.rfind(b"\n#", 0, pos) + 1
    end = data.find(b"ENDSEC;", first)
    region = data[first:end]
    entities = [(int(m.group(1)), m.group(2)) for m in _ENTITY_RE.finditer(region)]
    groups: list[list[tuple[int, bytes]]] = []
    for ent in entities:
        if ent[1].startswith(_STYLE_START) or not groups:
            groups.append([])
        groups[-1].append(ent)
    ids = {i for i, _ in entities}
    for g in groups:  # a reference into another group would make the order matter
        own = {i for i, _ in g}
        for _, body in g:
            if any(int(r) in ids - own for r in _REF_RE.findall(body)):
                return data
    key = lambda g: int(_REF_RE.findall(g[0][1])[-1])  # the styled shape representation
    ordered = [e for g in sorted(groups, key=key) for e in g]
    base = min(ids)
    new_id = {old: base + k for k, (old, _) in enumerate(ordered)}
    renum = lambda m: b"#%d" % new_id.get(int(m.group(1)), int(m.group(1)))
    body = b"".join(b"#%d = %s;\n" % (new_id[i], _REF_RE.sub(renum, txt)) for i, txt in ordered)
    return data[:first] + body + data[end:]


def write_step(path: str | Path, parts: Sequence[StepPart],
               instances: Sequence[StepInstance] | None = None, assembly_name: str = "") -> Path:
    """Write a STEP AP214 file (mm) atomically.

    Args:
        path: target ``.step`` file.
        parts: distinct parts, each stored once with its name and colour.
        instances: placements of parts in a flat assembly; ``None`` writes the
            single part of ``parts`` as one labelled product.
        assembly_name: label of the assembly root (defaults to the file stem).

    Raises:
        ValueError: an instance names an unknown part, or ``instances`` is None
            with more than one part.
        RuntimeError: OpenCascade failed to transfer the shapes.
        OSError: the file could not be written (ENOSPC when its disk is full).
    """
    path = Path(path)
    name = assembly_name or path.stem
    doc = _new_document()
    shape_tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    color_tool = XCAFDoc_DocumentTool.ColorTool_s(doc.Main())

    def add_part(p: StepPart):
        label = shape_tool.AddShape(p.solid.wrapped, False)
        _name(label, p.name)
        r, g, b = p.color
        color_tool.SetColor(label, Quantity_Color(r, g, b, Quantity_TypeOfColor.Quantity_TOC_RGB),
                            XCAFDoc_ColorType.XCAFDoc_ColorSurf)
        return label

    if instances is None:
        if len(parts) != 1:
            raise ValueError("a single-part STEP needs exactly one part")
        add_part(parts[0])
    else:
        root = shape_tool.NewShape()
        _name(root, name)
        labels = {p.name: add_part(p) for p in parts}
        for inst in instances:
            if inst.part not in labels:
                raise ValueError(f"instance {inst.name} names unknown part {inst.part}")
            comp = shape_tool.AddComponent(root, labels[inst.part], inst.location.wrapped)
            _name(comp, inst.name)
        shape_tool.UpdateAssemblies()
    return write_atomic(path, lambda tmp: _write_doc(doc, tmp, name))


def read_step_summary(path: str | Path) -> dict:
    """What a reviewer sees on re-import of a STEP file: solid count, total
    volume (mm^3), exact bounding box (mm) and part labels.

    Raises:
        Exception: whatever OpenCascade raises on an unreadable file (an
            unparsable one reads as an empty shape: 0 solids).
    """
    from tactcad.kernel.inspect import bbox_tuple

    shape = bd.import_step(str(path))
    solids = shape.solids()
    labels = sorted({ch.label for ch in shape.children} if shape.children else {shape.label})
    return {"solids": len(solids), "volume_mm3": sum(s.volume for s in solids),
            "bbox_mm": list(bbox_tuple(shape)), "labels": labels}
