"""A command reads its design as ``--design`` gives it or as its one word, a file or a
project folder (``tactcad strength d/d.toml``, ``tactcad strength d``,
``tactcad.load("d")``): the same design, the same answer; a folder naming no design, or
several, and two designs at once are refused by name."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

import tactcad
from conftest import run_cli
from tactcad.errors import DesignError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "hardware" / "ti_array_2x3"


@pytest.fixture
def project(tmp_path) -> Path:
    folder = tmp_path / "probe"
    shutil.copytree(EXAMPLE, folder, ignore=shutil.ignore_patterns(".tactcad-cache"))
    return folder


def test_the_design_as_a_word_a_folder_or_an_option_is_one_answer(project):
    design = project / "ti_array_2x3.toml"
    answers = [run_cli("strength", *given, "--json")
               for given in (["--design", design], [design], [project], ["--design", project])]
    assert [a.returncode for a in answers] == [0, 0, 0, 0], [a.stdout[-300:] for a in answers]
    figures = [json.loads(a.stdout)["elements"] for a in answers]
    assert all(f == figures[0] for f in figures[1:])
    assert tactcad.load(project).source == tactcad.load(design).source == design


def test_a_folder_of_several_designs_or_none_is_refused_naming_them(project, tmp_path):
    shutil.copy(project / "ti_array_2x3.toml", project / "variant.toml")
    several = json.loads(run_cli("strength", project, "--json").stdout)["error"]
    assert several["field"] == "--design" and "variant.toml" in several["allowed"]
    assert "ti_array_2x3.toml" in several["allowed"]
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "notes.toml").write_text("broken = [", encoding="utf-8")
    none = run_cli("readout", "--design", empty)
    assert none.returncode == 2 and "notes.toml" in none.stderr and "Traceback" not in none.stderr
    with pytest.raises(DesignError) as refused:
        tactcad.load(empty)
    assert refused.value.field == "path"


def test_two_designs_at_once_are_refused_not_one_chosen(project):
    other = project / "other.toml"
    refused = run_cli("strength", "--design", project / "ti_array_2x3.toml", other, "--json")
    error = json.loads(refused.stdout)["error"]
    assert refused.returncode == 2 and error["field"] == "--design" and "other.toml" in error["allowed"]


@pytest.mark.parametrize("command", ["strength", "stiffness"])
def test_a_die_project_is_read_as_its_word_or_folder_like_an_array(tmp_path, command):
    # the die's views refuse an array's options on a die; the design's word is no such option
    folder = tmp_path / "die"
    shutil.copytree(ROOT / "hardware" / "grasper_jaw_5mm_mems", folder,
                    ignore=shutil.ignore_patterns(".tactcad-cache"))
    design = folder / "grasper_jaw_5mm_mems.toml"
    by_option = run_cli(command, "--design", design, "--json")
    assert by_option.returncode == 0, by_option.stdout[-400:]
    for given in (design, folder):
        answer = run_cli(command, given, "--json")
        assert answer.returncode == 0, answer.stdout[-400:]
        assert json.loads(answer.stdout) == json.loads(by_option.stdout)


def test_a_labs_jaw_file_is_copied_into_the_project_with_its_comments(tmp_path):
    # the jaw table was written again from its values: the lab's notes on where each value
    # comes from (its drawing's number) were lost on the way into the project
    lab = tmp_path / "lab jaw.toml"
    source = (ROOT / "hardware" / "robotic_jaw_8mm_mems" / "robotic_jaw_8mm_mems_jaw.toml")
    lab.write_text("# our drawing PP-8-002, rev C\n" + source.read_text(encoding="utf-8"),
                   encoding="utf-8")
    made = run_cli("design", "--jaw", lab, "--construction", "mems-die", "--kr-over-km", "10",
                   "--kobj-range", "0.3", "3", "--full-scale-force", "0.0098", "--columns", "8",
                   "--out", tmp_path / "probe", "--quiet")
    assert made.returncode == 0, made.stderr[-500:]
    copied = tmp_path / "probe" / "probe_jaw.toml"
    assert copied.read_text(encoding="utf-8") == lab.read_text(encoding="utf-8")
    assert run_cli("strength", tmp_path / "probe", "--quiet").returncode == 0


def test_a_design_name_too_long_for_the_system_is_refused_by_name_not_raised(tmp_path):
    # --design's folder test asked the system about the name and raised its OSError
    result = run_cli("strength", "--design", "a" * 300, "--json")
    assert result.returncode in (2, 3) and json.loads(result.stdout)["error"]["message"]
    assert "Traceback" not in result.stderr
