"""The crosstalk export kind: decoupling CSV and JSON agree and invert the sensitivity."""

import json

import numpy as np

import tactcad
from tactcad.export.crosstalk_files import CSV_NAME, JSON_NAME, write_crosstalk_files
from tactcad.export.kinds import EXPORT_KINDS

TI = "src/tactcad/examples/ti_array_2x3/ti_array_2x3.toml"


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
