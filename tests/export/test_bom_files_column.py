"""The BOM's files column is read from the export kinds: a kind registered
with ``part_files`` adds its files to every part it describes, in its rank."""

from __future__ import annotations

from tactcad.catalogue.array_catalogue import array_parts
from tactcad.export import kinds
from tactcad.export.bom import part_files
from tactcad.export.kinds import ExportKind, bom_file_kinds, register_kind


def notes_jobs(run, before):
    return []


def notes_files(plan, assemblies):
    return lambda part, found: [f"notes/{part}.txt"]


def test_the_files_column_follows_the_kinds_ranks_and_names_only_files_written(
        monkeypatch, tmp_path, plan):
    assert [k.name for k in bom_file_kinds()][:3] == ["drawings", "dxf", "step"]
    monkeypatch.setattr(kinds, "EXPORT_KINDS", dict(kinds.EXPORT_KINDS))
    register_kind(ExportKind("notes", ("notes",), "notes/<part>.txt", __name__, "notes_jobs",
                             in_full_export=False, part_files="notes_files", bom_rank=0))
    for rel in ("notes/spacer.txt", "drawings/spacer.svg", "step/spacer.step",
                "scenes/array.step"):
        (tmp_path / rel).parent.mkdir(exist_ok=True)
        (tmp_path / rel).write_text("x")
    files = part_files(plan, tmp_path, {"array": [], "cart": []})
    spacer = array_parts(plan)["spacer"]
    assert files(spacer) == ["notes/spacer.txt", "drawings/spacer.svg", "step/spacer.step"]
    clamp = array_parts(plan)["clamp_plate"]
    assert files(clamp) == []  # nothing of it written here
