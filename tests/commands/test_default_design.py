"""A command without --design outside a project names the design it uses before
anything else (a folder without a design silently reported the paper's array), and
no message prints a value as ``None``."""

from __future__ import annotations

import json
import re

import pytest

from conftest import run_cli
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


def test_a_simulated_calibration_takes_the_noise_of_the_designs_own_rig(tmp_path, monkeypatch,
                                                                         capsys):
    """calibrate --simulate added the paper rig's 0.001 N (the FH 5's) to a design whose rig
    reads 0.0001 N: the noise is the rigs' force gauge's and the design's read-out chain's."""
    import json

    from tactcad.api import load
    from tactcad.mechanics.readout_chain import noise_budget_V, readout_chain

    monkeypatch.chdir(tmp_path)
    assert cli.main(["new", "fingertip", "--quiet"]) == 0
    monkeypatch.chdir(tmp_path / "fingertip")
    project = load()  # the project folder's one design
    gauge = project.validated.rigs.part("force_gauge")
    capsys.readouterr()
    assert cli.main(["calibrate", "--simulate", "--json"]) == 0
    noise = json.loads(capsys.readouterr().out)["simulated_noise"]
    assert noise["force_N"] == gauge.resolution_N and gauge.model in noise["force_source"]
    assert noise["signal_V"] == noise_budget_V(readout_chain(project.plan))["reading"]
    assert cli.main(["calibrate", "--simulate", "--json", "--noise-force", "0.002"]) == 0
    assert json.loads(capsys.readouterr().out)["simulated_noise"]["force_N"] == 0.002


def test_design_in_a_die_folder_starts_from_the_shipped_example_and_says_so(tmp_path,
                                                                           monkeypatch, capsys):
    """design of a stacked array in a die's project folder read the die's file as an array's
    base: fifteen errors naming die5.toml's missing tables."""
    from tactcad.commands.design import base_design
    from tactcad.commands.notices import print_heads
    from tactcad.design.array_plan import DEFAULT_DESIGN

    monkeypatch.chdir(tmp_path)
    assert cli.main(["new", "die5", "--example", "grasper_jaw_5mm_mems", "--quiet"]) == 0
    monkeypatch.chdir(tmp_path / "die5")
    capsys.readouterr()
    assert base_design(None) == DEFAULT_DESIGN
    said = " ".join(print_heads(echo=False))
    assert "starts from the shipped example" in said and "not die5.toml" in said
    # a refusal before the search is the user's own value, once, not the die file's tables
    assert cli.main(["design", "--kr-over-km", "10", "--kobj-range", "1", "5",
                     "--full-scale-force", "0.1", "--out", "arr.toml", "--verify", "none",
                     "--set", "sheet.thickness_mm=-1"]) == 2
    err = capsys.readouterr().err
    assert "die5.toml" not in err and "errors in" not in err and "sheet.thickness_mm" in err


def test_an_unreadable_toml_of_the_folder_is_passed_over_by_design_and_named(tmp_path,
                                                                             monkeypatch, capsys):
    """One *.toml that is no text (or no TOML) in the working folder refused `design --out`,
    which needs no design file of the folder; a command that looks for the folder's design
    says the file was read because no --design was given, and how to name one."""
    import pytest

    from tactcad.commands.design import base_design
    from tactcad.commands.notices import print_heads
    from tactcad.design.array_plan import DEFAULT_DESIGN
    from tactcad.project_folder import default_design

    monkeypatch.chdir(tmp_path)
    (tmp_path / "notes.toml").write_bytes(b"\xff\xfe")
    (tmp_path / "broken.toml").write_text("a = [\n", encoding="utf-8")
    print_heads(echo=False)
    assert base_design(None) == DEFAULT_DESIGN
    said = " ".join(print_heads(echo=False))
    assert "passed over broken.toml (not valid TOML" in said and "notes.toml (not a UTF-8" in said
    with pytest.raises(DesignError) as refused:
        default_design()
    text = str(refused.value)
    assert "broken.toml" in text and "no --design was given" in text and "--design FILE" in text
    assert refused.value.alternatives[0]["option"] == "--design FILE"
    assert cli.main(["readout"]) == 2
    err = capsys.readouterr().err
    assert "no --design was given" in err and "Traceback" not in err


def test_a_jaw_file_loaded_as_a_design_is_named_a_jaw_file(tmp_path, monkeypatch, capsys):
    """tactcad.load of a jaw file ([grasper_jaw] alone) listed eight missing design tables."""
    import pytest

    import tactcad

    jaw = tmp_path / "jaw12.toml"
    jaw.write_text('[grasper_jaw]\nshaft_class_mm = "10"\nwidth_clearance_mm = 3.5\n'
                   "length_mm = 34.0\nthickness_mm = 5.6\npin_inset_mm = 2.5\n"
                   "opening_angle_deg = 30.0\n", encoding="utf-8")
    with pytest.raises(DesignError) as refused:
        tactcad.load(jaw)
    text = str(refused.value)
    assert "jaw file" in text and "--jaw" in text and "errors in" not in text
    assert refused.value.alternatives[0]["option"] == f"--jaw {jaw}"
    monkeypatch.chdir(tmp_path)
    assert cli.main(["verify", "--design", "jaw12.toml"]) == 2
    err = capsys.readouterr().err
    assert "jaw file" in err and "design --jaw jaw12.toml" in err
    assert cli.main(["design", "--design", "jaw12.toml", "--kr-over-km", "8", "--kobj-range",
                     "0.3", "3", "--full-scale-force", "0.05", "--out", "x.toml"]) == 2
    err = capsys.readouterr().err
    assert "--design = 'jaw12.toml'" in err and "jaw file" in err and "errors in" not in err


@pytest.mark.parametrize("text, fault", [
    ("", "empty"),  # a copy the full disk cut short
    ("hello = 1\n", "no table"),
    ('[design]\nname = "probe"\n', "[design]"),
])
def test_a_hollow_design_file_is_refused_not_swapped_for_the_example(tmp_path, monkeypatch,
                                                                    text, fault):
    import tactcad

    (tmp_path / "probe.toml").write_text(text, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    result = run_cli("budget", "--json")
    error = json.loads(result.stdout)["error"]
    assert result.returncode == 2 and error["value"] == "probe.toml" and fault in error["message"]
    with pytest.raises(DesignError, match=re.escape(fault)):
        tactcad.load()
    assert not (tmp_path / "exports").exists()


def test_another_tools_toml_beside_no_design_leaves_the_example_announced(tmp_path, monkeypatch):
    (tmp_path / "pyproject.toml").write_text('[tool.ruff]\nline-length = 99\n', encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    result = run_cli("readout")
    assert result.returncode == 0 and "shipped example" in result.stderr
