"""Shared fixtures: the default plan, and one export of it per test session."""

from __future__ import annotations

import pytest

from tactcad.design.array import default_design_data, load_design


@pytest.fixture(scope="session")
def plan():
    return load_design()


@pytest.fixture
def design_data():
    """A fresh, mutable copy of the default design's raw tables."""
    return default_design_data()


@pytest.fixture(scope="session")
def exported(plan, tmp_path_factory):
    """The default design exported once: (out_dir, ExportResult)."""
    from tactcad.export.run import export

    out = tmp_path_factory.mktemp("exports")
    return out, export(plan, out, log=lambda s: None)
