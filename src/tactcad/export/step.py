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

from .atomic import write_atomic

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
        raise RuntimeError(f"STEP write failed: {path}")
    _normalise(path)


_NAUO_RE = re.compile(rb"NEXT_ASSEMBLY_USAGE_OCCURRENCE\('[^']*'")


def _normalise(path: Path) -> None:
    """Fix what OpenCascade varies between runs: the header time stamp, and the
    assembly-usage ids, which come from a process-wide counter."""
    data = path.read_bytes()
    data = _TIMESTAMP_RE.sub(lambda m: m.group(0).replace(
        m.group(0).split(b"','")[1].rstrip(b"'"), FIXED_TIMESTAMP.encode()), data, count=1)
    counter = iter(range(1, 1 << 30))
    data = _NAUO_RE.sub(lambda m: b"NEXT_ASSEMBLY_USAGE_OCCURRENCE('%d'" % next(counter), data)
    path.write_bytes(data)


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
        RuntimeError: OpenCascade failed to transfer or write.
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
