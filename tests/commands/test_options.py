"""Every option of every command is checked up front: drawn values (by
introspecting the parser, so a new option is covered without a line here)
are accepted or refused in one line naming the option; never a traceback."""

from __future__ import annotations

import argparse
import json
import os
import signal

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cli_strategies import COMMANDS, LONG, command_lines, option_actions
from tactcad import cli
from tactcad.errors import TactcadError

def test_every_command_and_option_is_found_by_introspection():
    assert {("lumped",), ("calibrate",), ("bench", "export"), ("sweep", "grid")} <= set(COMMANDS)
    names = {max(a.option_strings, key=len) for p in COMMANDS.values() for a in option_actions(p)}
    assert {"--sigma-r", "--design", "--material", "--encoding", "--map", "--seed"} <= names


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(command_lines())
@pytest.mark.slow  # a whole chain through the command line or an export
def test_drawn_options_are_checked_or_refused_in_one_line(argv):
    try:
        args = cli.parse_checked(argv)
    except TactcadError as exc:
        assert "\n" not in str(exc).strip(), argv
        return
    for value in vars(args).values():  # what passes the checks is finite, non-empty, never -0
        for v in value if isinstance(value, (list, tuple)) else [value]:
            if isinstance(v, float):
                assert v == v and abs(v) != float("inf") and str(v) != "-0.0", argv
            if isinstance(v, str):
                assert v.strip(), argv


class _TimeUp(BaseException):
    pass


def test_warnings_alike_fold_into_the_first_and_one_closing_count(capsys):
    import warnings

    from tactcad.commands.notices import WarningLines
    from tactcad.mechanics.gauge_strain import GaugeStrainRangeWarning

    notes = WarningLines(echo=True)
    with notes.capture():
        for error in (0.02, 0.03, 0.025, 0.03):  # the last repeats a text: counted once
            warnings.warn(GaugeStrainRangeWarning(f"gauge strain: b/t at {error}", error))
        warnings.warn(UserWarning("another kind"))
    err = capsys.readouterr().err.splitlines()
    assert err == ["tactcad: warning: gauge strain: b/t at 0.02",
                   "tactcad: warning: another kind",
                   f"tactcad: warning: {GaugeStrainRangeWarning.fold_as}: 2 more alike, "
                   "estimated error up to 3.0 %"]
    assert notes.lines == [line.removeprefix("tactcad: warning: ") for line in err]


@pytest.mark.slow
@settings(max_examples=int(os.environ.get("TACTCAD_OPTION_EXAMPLES", 40)), deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(argv=command_lines(tuple(c for c in COMMANDS if c not in LONG)), as_json=st.booleans())
def test_drawn_command_lines_end_in_a_known_exit_code_without_traceback(
        argv, as_json, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("TACTCAD_WORKERS", "0")
    argv = argv + (["--json"] if as_json and "--json" not in argv else [])
    as_json = "--json" in argv  # also when drawn as a value

    def time_up(*_):
        raise _TimeUp

    old = signal.signal(signal.SIGALRM, time_up)
    # refusals answer at once; a valid line that runs a long study (an export, a
    # check) proves nothing more past a few seconds here: make fuzz gives each line a minute
    signal.alarm(6)
    try:
        code = cli.main(argv)
    except _TimeUp:  # a valid line that simply takes long: no verdict
        return
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    out = capsys.readouterr()
    assert code in (0, 1, 2, 3), (argv, code, out.err[-500:])
    assert "Traceback" not in out.err and "Traceback" not in out.out, argv
    errors = [ln for ln in out.err.splitlines() if ": error: " in ln]
    assert len(errors) <= 1, (argv, out.err)
    assert not [ln for ln in out.err.splitlines() if "Warning:" in ln or "warnings.warn" in ln], \
        (argv, out.err)  # no warning in Python's format
    if as_json:
        doc = json.loads(out.out)
        assert code == 0 or doc["error"]["exit_code"] == code
    elif code:
        assert len(errors) == 1 or code == 1, (argv, out.err)


# ---------------------------------------------------------------------------
# The cases the checks were written for
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("argv,needle", [
    (["design", "--kr-over-km", "10", "--kobj-range", "1", "10", "--full-scale-force", "2",
      "--material", "Titanium", "--out", "x.toml"],
     "argument --material: 'Titanium': allowed one of 6061-T6, 7075-T6, 17-4PH-H900"),
    (["stiffness", "--element", "1", "--design", ""], "--design = '': allowed a non-empty value"),
    (["lumped", "--km", "1", "--kr", "2", "--kobj", "nan"], "--kobj = nan: allowed a finite number"),
    (["evaluate", "--poisson", "0.7"], "argument --poisson: '0.7': allowed a number 0 ... 0.5"),
    (["tolerance", "--samples", "1e9"], "argument --samples: '1e9': allowed an integer"),
    (["calibrate", "--data", "x.csv", "--encoding", "klingon"], "--encoding = 'klingon'"),
    # digits of another script (full-width) are refused as `--set` refuses them, not read
    (["stiffness", "--element", "\uff13"], "--element = '\uff13': allowed an integer 1 ... "),
    (["design", "--jaw", "10", "--columns", "\uff12"],
     "argument --columns: '\uff12': allowed an integer 1 ... "),
    (["tolerance", "--samples", "\uff15"], "argument --samples: '\uff15': allowed an integer"),
    (["lumped", "--unit", "\uff13"], "argument --unit: invalid int value: '\uff13'"),
    (["design", "--full-scale-force", "\uff10.\uff12"],
     "argument --full-scale-force: '\uff10.\uff12': allowed a number"),
    (["lumped", "--km", "\uff13", "--kr", "9", "--r", "2"],
     "argument --km: invalid float value: '\uff13'"),
    (["calibrate", "--data", "x.csv", "--gain", "\uff13"],
     "argument --gain: invalid float value: '\uff13'"),
])
def test_bad_option_values_are_refused_naming_the_option(argv, needle, capsys, tmp_path):
    (tmp_path / "x.csv").write_text("element,run,z_um,force_N,signal_V\n")
    old = os.getcwd()
    os.chdir(tmp_path)
    try:
        assert cli.main(argv) == 2
    finally:
        os.chdir(old)
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1, err


def test_material_grade_matches_without_case_where_unambiguous(monkeypatch):
    from tactcad.commands.options import material_grade_name
    from tactcad.vocabulary import material_library as materials

    assert material_grade_name("ti-6al-4v-annealed") == "Ti-6Al-4V-annealed"
    assert material_grade_name("17-4ph") == "17-4PH-H900"
    assert material_grade_name("7075-t6") == "7075-T6"
    with pytest.raises(argparse.ArgumentTypeError, match="allowed one of"):
        material_grade_name("Titanium")
    monkeypatch.setattr(materials, "material_grades", lambda: {"Al-1": 1, "AL-2": 2})
    with pytest.raises(argparse.ArgumentTypeError, match="ambiguous"):
        material_grade_name("al")


def test_minus_zero_is_never_printed(capsys):
    assert cli.main(["lumped", "--km", "15.25", "--kr", "80.38", "--kobj", "3.85",
                     "--sigma-r", "-0.0"]) == 0
    text = capsys.readouterr().out
    assert "-0 " not in text and "-0.0" not in text and "sigma_R = 0" in text
    assert cli.main(["lumped", "--km", "15.25", "--kr", "80.38", "--kobj", "3.85",
                     "--sigma-r", "-0.0", "--json"]) == 0
    assert "-0.0" not in capsys.readouterr().out


def test_a_design_of_the_fewest_columns_is_not_told_to_use_fewer_columns(capsys):
    code = cli.main(["scenes", "--set", "array.columns=2", "--set", "arms.lengths_mm=[4,5,4,5]",
                     "--set", "clamp.plate_thickness_mm=10", "--set", "sheet.thickness_mm=10",
                     "--set", "array.pitch_mm=12"])
    err = capsys.readouterr().err
    assert code == 2 and "array.columns = 2: allowed clamp plates 1.5 mm thick or thinner" in err
    assert "fewer columns" not in err


def test_warnings_are_one_line_each_once_in_json_and_silenced_by_quiet(capsys):
    argv = ["stiffness", "--element", "1", "--set", "material.poisson_ratio=0.45"]
    assert cli.main(argv) == 0
    err = capsys.readouterr().err.splitlines()
    # no design named here: the shipped example, said first
    assert err.pop(0).startswith("tactcad: design: the shipped example macro_array")
    # two fits left (the stiffness correction's and the gauge strain's), each said once;
    # the correction's range, said once for the whole run, when it ends
    assert len(err) == 2 and err[1].startswith("tactcad: warning: closed-form stiffness "
                                               "correction used outside its fitted range")
    assert err[0].startswith("tactcad: warning: gauge strain of element_a4mm (web 0.25 mm): "
                             "the material's Poisson ratio, nu outside")
    assert cli.main(argv + ["--quiet"]) == 0
    assert capsys.readouterr().err == ""
    assert cli.main(argv + ["--json"]) == 0
    out = capsys.readouterr()
    doc = json.loads(out.out)
    assert out.err == "" and len(doc["warnings"]) == 2
    assert all("poisson_ratio" in w or "Poisson ratio" in w for w in doc["warnings"])


@pytest.mark.parametrize("command", [
    ["scenes"],
    ["design", "--kr-over-km", "6", "--kobj-range", "5", "50", "--full-scale-force", "0.1",
     "--verify", "none"]])
def test_a_refusal_prints_the_warnings_issued_before_it_once_each_even_quiet(
        command, capsys, tmp_path):
    """A design that warns (a --set key given twice) and is then refused (its last value out
    of range): the warning led to the refusal, so it is printed before it on stderr, once,
    with --quiet too (which kept it back, and printed only the refusal)."""
    argv = [*command, "--set", "element.web_thickness_mm=0.2",
            "--set", "element.web_thickness_mm=99"]
    if command[0] == "design":
        argv += ["--out", str(tmp_path / "d.toml")]
    warned = ("tactcad: warning: --set element.web_thickness_mm given 2 times (0.2, 99): "
              "the last, 99, is taken")
    for quiet in ([], ["--quiet"]):
        assert cli.main([*argv, *quiet]) == 2
        err = capsys.readouterr().err.splitlines()
        assert err.count(warned) == 1, err
        refused = [i for i, line in enumerate(err) if line.startswith("tactcad: error: ")]
        assert refused and err.index(warned) < refused[0], err
        if quiet:  # no heads: the warning, then the refusal
            assert err[0] == warned, err
    assert cli.main([*argv, "--json"]) == 2
    out = capsys.readouterr()
    assert out.err == "" and json.loads(out.out)["warnings"] == [warned.split("warning: ")[1]]


@pytest.mark.slow
def test_the_input_fuzz_runs_and_counts_tracebacks():
    import subprocess
    import sys
    from pathlib import Path

    script = Path(__file__).parents[2] / "scripts" / "fuzz_inputs.py"
    proc = subprocess.run([sys.executable, str(script), "--data", "30", "--options", "8",
                           "--quiet"], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0].startswith("fuzz data files: 30 tried") and "0 tracebacks" in lines[0]
    assert lines[1].startswith("fuzz options: ") and "0 tracebacks" in lines[1]


def test_a_key_set_twice_is_said_as_a_repeated_option_is():
    # a repeated --kobj-range warned which value is taken; a repeated --set key said nothing
    from tactcad.commands import parse_overrides
    from tactcad.errors import RepeatedOptionWarning

    with pytest.warns(RepeatedOptionWarning, match=r"--set element.web_thickness_mm given 2 "
                                                   r"times \(0.3, 0.35\): the last, 0.35"):
        taken = parse_overrides(["element.web_thickness_mm=0.3", "array.pitch_mm=4.0",
                                 "element.web_thickness_mm = 0.35"])
    assert taken == {"element.web_thickness_mm": 0.35, "array.pitch_mm": 4.0}
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parse_overrides(["element.web_thickness_mm=0.3", "array.pitch_mm=4.0"])  # no word


def test_the_clamp_bolt_refusal_offers_only_changes_that_mend_it(capsys):
    """A stack too long for the M2 clamp bolt: every change the refusal offers to paste
    passes once pasted, and the bolt sizes and plates it does not offer do not."""
    import shlex

    arms = "arms.lengths_mm=[4.5,5,6,7,7.5,6,6,7.5,7,6.5,5.5,5]"
    base = ["scenes", "--set", "array.columns=6", "--set", arms]
    assert cli.main(base) == 2
    err = capsys.readouterr().err
    assert "array.columns = 6: allowed" in err and "thinner clamp plates" not in err
    pastes = [line.split("to paste: ", 1)[1].rsplit(" (", 1)[0]
              for line in err.splitlines() if "to paste: " in line]
    assert any("clamp.plate_thickness_mm" in p for p in pastes), err
    assert any("array.columns=5" in p for p in pastes), err
    for paste in pastes:
        assert cli.main(base + shlex.split(paste)) == 0, paste
        capsys.readouterr()
    for size in ("M1.6", "M2.5", "M3"):  # not offered: each still refused
        assert size not in err
        assert cli.main(base + ["--set", f'clamp.bolt_size="{size}"']) == 2
        capsys.readouterr()


def test_stiffness_help_says_which_levels_a_die_and_a_comb_take(capsys):
    """A die refuses beam and fem2d, a comb's element takes every level of the ladder: the
    help of --model says both, from the ladder and the die's levels."""
    from tactcad.mechanics.ladder import models
    from tactcad.products.silicon_die.mechanics import DIE_STIFFNESS_LEVELS

    with pytest.raises(SystemExit):
        cli.main(["stiffness", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert ("a stacked array's and a monolithic comb's element: "
            + ", ".join(models())) in text
    assert "a silicon die's beams: " + ", ".join(DIE_STIFFNESS_LEVELS) + " (not beam, fem2d)" \
        in text
