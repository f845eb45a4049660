"""A command without --design outside a project names the design it uses before
anything else (a folder without a design silently reported the paper's array), and
no message prints a value as ``None``."""

from __future__ import annotations

from tactcad import cli
from tactcad.errors import DesignError


def test_outside_a_project_the_first_line_names_the_shipped_example(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["readout"]) == 0
    first = capsys.readouterr().err.splitlines()[0]
    assert "macro_array" in first and "tactcad new" in first
    assert cli.main(["readout", "--element", "99"]) == 2  # an error stays one line
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


def test_inside_a_project_its_own_design_is_used_without_a_notice(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["new", "fingertip", "--quiet"]) == 0
    monkeypatch.chdir(tmp_path / "fingertip")
    capsys.readouterr()
    assert cli.main(["readout"]) == 0
    assert "shipped example" not in capsys.readouterr().err


def test_a_value_not_given_reads_as_such_never_as_none():
    text = str(DesignError("--design", None, "one of a.toml, b.toml"))
    assert text == "--design (not given): allowed one of a.toml, b.toml" and "None" not in text
