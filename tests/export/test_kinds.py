"""The kinds of export file are declared once (:data:`tactcad.export.kinds.EXPORT_KINDS`):
a new format is one job function plus one registration, and the run's job
list, ``--only``'s choices and help, the selection and the manifest take it."""

from __future__ import annotations

import json

import pytest

from tactcad.cli import build_parser, main
from tactcad.design.array_plan import DEFAULT_DESIGN
from tactcad.export import kinds
from tactcad.export.job import Job, Run
from tactcad.export.jobs import all_jobs
from tactcad.export.kinds import parse_only
from tactcad.export.selection import job_kind
from tactcad.store import content_key

ARMS_CSV = "points/arms.csv"


def arm_table_jobs(run: Run, before: list[Job]) -> list[Job]:
    """A stand-in format: each element's arm length (mm) as CSV, kernel-free."""
    def make(run: Run) -> list[dict]:
        path = run.staging / ARMS_CSV
        path.parent.mkdir(parents=True, exist_ok=True)
        rows = [f"{s.number},{s.geometry.arm_length_mm}" for s in run.plan.slots]
        path.write_text("element,arm_length_mm\n" + "\n".join(rows) + "\n", encoding="utf-8")
        return [{"path": ARMS_CSV, "part": "array", "kind": "points-csv", "rows": len(rows)}]
    return [Job("points:arms", content_key("points-arms", run.plan), make)]


@pytest.fixture
def points_kind():
    kinds.register_kind(kinds.ExportKind("points", ("points",), ARMS_CSV, __name__,
                                         "arm_table_jobs"))
    try:
        yield
    finally:
        del kinds.EXPORT_KINDS["points"]


def _only_help() -> str:
    sub = next(a for a in build_parser()._actions if a.__class__.__name__ == "_SubParsersAction")
    return next(a.help for a in sub.choices["export"]._actions if "--only" in a.option_strings)


def test_every_built_in_kind_is_in_the_help_and_the_choices():
    text = _only_help()
    for name, kind in kinds.EXPORT_KINDS.items():
        assert f"{name} ({kind.writes}" in text
    assert parse_only([",".join(kinds.EXPORT_KINDS)]) == list(kinds.EXPORT_KINDS)


def test_a_taken_name_or_prefix_is_refused():
    with pytest.raises(ValueError, match="registered already"):
        kinds.register_kind(kinds.EXPORT_KINDS["step"])
    with pytest.raises(ValueError, match="belong to another kind"):
        kinds.register_kind(kinds.ExportKind("pictures", ("image",), "x", __name__, "f"))


@pytest.mark.slow  # a whole chain through an export
def test_a_registered_kind_is_planned_selected_and_written(points_kind, project, tmp_path,
                                                          capsys):
    assert "points (points/arms.csv)" in _only_help()
    run = Run(project, tmp_path / "staging")
    names = [j.name for j in all_jobs(run)]
    assert names[-1] == "points:arms" and job_kind("points:arms") == "points"
    out = tmp_path / "exports"
    assert main(["export", "--design", str(DEFAULT_DESIGN), "--only", "points",
                 "--out", str(out), "--no-cache"]) == 0
    capsys.readouterr()
    rows = (out / ARMS_CSV).read_text(encoding="utf-8").splitlines()
    assert rows[0] == "element,arm_length_mm"
    assert len(rows) == 1 + len(project.plan.slots)
    manifest = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    assert [f["path"] for f in manifest["files"]] == [ARMS_CSV]
    assert manifest["partial"]["only"] == ["points"]


def test_an_unknown_kind_is_refused_naming_the_registered_ones(points_kind, capsys):
    assert main(["export", "--only", "pointz", "--json"]) == 2
    error = json.loads(capsys.readouterr().out)["error"]
    assert error["field"] == "--only" and error["value"] == "pointz"
    assert "points" in error["allowed"] and "step" in error["allowed"]


def test_a_kind_outside_the_full_export_is_planned_only_when_asked(project, tmp_path):
    kinds.register_kind(kinds.ExportKind("points", ("points",), ARMS_CSV, __name__,
                                         "arm_table_jobs", in_full_export=False))
    try:
        run = Run(project, tmp_path / "staging")
        assert "points" not in kinds.full_export_kinds()
        assert "points:arms" not in [j.name for j in all_jobs(run)]
        assert [j.name for j in all_jobs(run, ["points"])][-1] == "points:arms"
        assert "points (points/arms.csv, only when asked)" in _only_help()
    finally:
        del kinds.EXPORT_KINDS["points"]


def test_a_selection_keeps_jobs_another_kind_plans(project, tmp_path):
    """``--only review`` writes the FreeCAD review files, which the scenes plan."""
    from tactcad.export.selection import select_jobs

    run = Run(project, tmp_path / "staging")
    names = [j.name for j in select_jobs(all_jobs(run, ["review"]), ["review"])]
    assert "review:page" in names and any(n.startswith("review:") and n != "review:page"
                                          for n in names)
