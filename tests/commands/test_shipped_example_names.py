"""Every command reads a shipped example's name as ``--design`` (or its DESIGN word) in any
folder, as ``design --design macro_array`` does; a local file or folder of that name wins."""

from __future__ import annotations

from pathlib import Path

import pytest

from tactcad.cli import main, parse_checked
from tactcad.project_folder import die_examples, examples


@pytest.mark.parametrize("argv", [["verify", "--design", "macro_array"],
                                  ["verify", "macro_array"],
                                  ["evaluate", "--design", "macro_array"],
                                  ["check", "macro_array"]])
def test_a_shipped_example_name_is_read_by_every_command(argv, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert Path(parse_checked(argv).design) == examples()["macro_array"]


def test_a_die_example_name_is_read_too(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    name = next(iter(die_examples()))
    assert Path(parse_checked(["verify", name]).design) == die_examples()[name]


def test_a_local_file_or_folder_of_that_name_wins(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "macro_array").write_text("[element]\n", encoding="utf-8")
    assert parse_checked(["verify", "macro_array"]).design == "macro_array"
    (tmp_path / "macro_array").unlink()
    (tmp_path / "macro_array").mkdir()
    (tmp_path / "macro_array" / "mine.toml").write_bytes(examples()["macro_array"].read_bytes())
    assert Path(parse_checked(["evaluate", "--design", "macro_array"]).design) == \
        Path("macro_array") / "mine.toml"


def test_evaluate_runs_on_an_example_named_in_an_empty_folder(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["evaluate", "--design", "macro_array", "--json"]) == 0
    assert "No such file" not in capsys.readouterr().out


def test_an_unknown_name_is_still_named_as_a_missing_file(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["evaluate", "--design", "no_such_design"]) == 2
    assert "design file = 'no_such_design'" in capsys.readouterr().err


def test_a_local_toml_of_that_name_wins_over_the_example(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "macro_array.toml").write_text("[element]\n", encoding="utf-8")
    assert parse_checked(["verify", "macro_array"]).design == "macro_array.toml"


def test_a_misspelt_example_name_is_refused_naming_the_examples(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["verify", "macro_arrayy", "--model", "closed-form"]) == 2
    err = capsys.readouterr().err
    assert "macro_arrayy" in err and "did you mean macro_array?" in err
    assert "Traceback" not in err
