"""The crosstalk export kind: decoupling CSV and JSON agree and invert the sensitivity,
for the stacked array at stack-timoshenko and a monolithic comb at its own comb-beam;
a construction no crosstalk level describes has none, and the manifest says why."""

import json
from types import SimpleNamespace

import numpy as np
import pytest

import tactcad
from tactcad.export.crosstalk_files import (CSV_NAME, JSON_NAME, crosstalk_jobs,
                                            write_crosstalk_files)
from tactcad.export.kinds import EXPORT_KINDS
from tactcad.export.manifest import left_out_section
from tactcad.mechanics import crosstalk_ladder
from tactcad.mechanics.crosstalk_ladder import CROSSTALK_LEVELS, plan_crosstalk
from tactcad.store import content_key

TI = "src/tactcad/examples/ti_array_2x3/ti_array_2x3.toml"
COMB = "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml"


@pytest.fixture(scope="module")
def comb():
    return tactcad.load(COMB).plan


def without_the_combs_levels() -> dict:
    """The crosstalk levels but the comb's, in their order (a construction none describes)."""
    return {n: lv for n, lv in CROSSTALK_LEVELS.items() if lv.construction != "monolithic-comb"}


def _matrices(folder):
    """(the JSON, the CSV's decoupling matrix) of the files written into ``folder``."""
    d = json.loads((folder / JSON_NAME).read_text())
    rows = (folder / CSV_NAME).read_text().splitlines()
    return d, np.array([[float(v) for v in row.split(",")[1:]] for row in rows[1:]])


def test_files_of_the_ti_example(tmp_path):
    plan = tactcad.load(TI).plan
    records = write_crosstalk_files(plan, tmp_path, lambda s: None)
    assert [r["path"] for r in records] == [CSV_NAME, JSON_NAME]
    d = json.loads((tmp_path / JSON_NAME).read_text())
    rows = (tmp_path / CSV_NAME).read_text().splitlines()
    D = np.array([[float(v) for v in row.split(",")[1:]] for row in rows[1:]])
    assert np.allclose(D, d["decoupling"])
    S = np.array(d["sensitivity_strain_per_N"])
    assert np.allclose(D @ (S / np.diag(S)[:, None]), np.eye(len(S)), atol=1e-12)
    assert "crosstalk" in EXPORT_KINDS and EXPORT_KINDS["crosstalk"].in_full_export
    assert {r["model"] for r in records} == {"stack-timoshenko"} == {d["model"]}


def test_a_comb_writes_them_at_its_own_level_keyed_by_its_plan(comb, tmp_path):
    # the comb's export wrote no decoupling files: the manifest left them out
    jobs = crosstalk_jobs(SimpleNamespace(plan=comb), [])
    assert [(j.name, j.key) for j in jobs] == [("crosstalk", content_key("crosstalk", comb))]
    records = write_crosstalk_files(comb, tmp_path, lambda s: None)
    assert [r["path"] for r in records] == [CSV_NAME, JSON_NAME]
    assert {r["model"] for r in records} == {"comb-beam"} and {r["items"] for r in records} == {12}
    d, D = _matrices(tmp_path)
    r = plan_crosstalk(comb, "comb-beam")
    assert d["model"] == "comb-beam" and d["elements"] == list(range(1, 13))
    assert d["error_estimate_rel"] == pytest.approx(r.error_estimate_rel, rel=1e-10)
    assert d["units"] == {"sensitivity": "strain per N", "compliance": "mm per N",
                          "decoupling": "1"}
    assert np.allclose(D, d["decoupling"]) and D.shape == (12, 12)
    S = np.array(d["sensitivity_strain_per_N"])
    assert np.allclose(D @ (S / np.diag(S)[:, None]), np.eye(12), atol=1e-10)
    assert not any("crosstalk" in item["what"] for item in left_out_section(comb) or [])


def test_the_same_comb_writes_the_same_bytes(comb, tmp_path):
    first, second = tmp_path / "a", tmp_path / "b"
    for folder in (first, second):
        write_crosstalk_files(comb, folder, lambda s: None)
    for name in (CSV_NAME, JSON_NAME):
        assert (first / name).read_bytes() == (second / name).read_bytes()


def test_a_construction_no_level_describes_has_no_files_and_the_manifest_says_why(
        comb, monkeypatch):
    monkeypatch.setattr(crosstalk_ladder, "CROSSTALK_LEVELS", without_the_combs_levels())
    assert crosstalk_jobs(SimpleNamespace(plan=comb), []) == []
    left = {item["what"].split(",")[0]: item["reason"] for item in left_out_section(comb)}
    assert "monolithic-comb" in left["crosstalk/decoupling.csv"]
