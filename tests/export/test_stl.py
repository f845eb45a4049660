"""``tactcad export --only stl``: every part of the design as binary STL, the
mesh closed and of the part's volume, the same bytes on a second run, and no
STL in a full export."""

from __future__ import annotations

import json

import pytest
import trimesh

from tactcad.cli import main
from tactcad.design.array_plan import DEFAULT_DESIGN
from tactcad.export.job import Run
from tactcad.export.kinds import full_export_kinds
from tactcad.export.stl import stl_name

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def stl_export(tmp_path_factory):
    out = tmp_path_factory.mktemp("stl") / "exports"
    assert main(["export", "--design", str(DEFAULT_DESIGN), "--only", "stl", "--out", str(out),
                 "--no-cache", "--quiet"]) == 0
    return out


@pytest.mark.xdist_group("stl-export")  # stl_export: made once, on one worker
def test_every_part_is_a_closed_mesh_of_its_volume(stl_export, project):
    specs, _ = Run(project, None).inventory  # every distinct part of the design
    manifest = json.loads((stl_export / "manifest.json").read_text(encoding="utf-8"))
    files = {f["part"]: f["path"] for f in manifest["files"]}
    assert files == {name: stl_name(name) for name in specs}
    for name, spec in specs.items():
        mesh = trimesh.load(stl_export / files[name], file_type="stl")
        assert mesh.is_watertight, name
        assert mesh.volume == pytest.approx(spec.expected_volume_mm3, rel=5e-3), name


@pytest.mark.xdist_group("stl-export")  # stl_export: made once, on one worker
def test_a_second_run_writes_the_same_bytes(stl_export, tmp_path):
    again = tmp_path / "again"
    assert main(["export", "--design", str(DEFAULT_DESIGN), "--only", "stl", "--part",
                 "spacer", "--out", str(again), "--no-cache", "--quiet"]) == 0
    name = stl_name("spacer")
    assert (again / name).read_bytes() == (stl_export / name).read_bytes()


def test_a_full_export_writes_no_stl():
    assert "stl" not in full_export_kinds()

