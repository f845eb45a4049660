"""The command line's start-up: ``tactcad --version`` and ``tactcad --help`` import no
command module and no numerical library, a command's ``--help`` none of the heavy ones.
Asserted on the modules a fresh interpreter holds after the parse, not on seconds (those
are ``tactcad bench check``'s start-up line)."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys

import pytest

from tactcad import cli

#: Libraries a parse never needs: the CAD kernel, the FEM and plotting stack, Dask.
HEAVY = ("build123d", "OCP", "scipy", "skfem", "matplotlib", "dask")
#: What the command list needs neither: the design model and what it is built on.
DESIGN_MODEL = ("numpy", "pydantic", "tactcad.design.array_plan")


def modules_after(argv: list[str]) -> tuple[int, str, list[str]]:
    """(exit code, stdout, the modules loaded) of ``tactcad ARGV`` in a fresh interpreter."""
    code = ("import json, sys\n"
            "from tactcad import cli\n"
            "try:\n"
            f"    exit_code = cli.main({argv!r})\n"
            "except SystemExit as stop:\n"
            "    exit_code = stop.code or 0\n"
            "print('\\nMODULES ' + json.dumps([exit_code, sorted(sys.modules)]))\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          check=True)
    head, _, tail = done.stdout.rpartition("\nMODULES ")
    exit_code, modules = json.loads(tail)
    return exit_code, head, modules


def loaded(modules: list[str], roots: tuple[str, ...]) -> list[str]:
    """The modules of ``modules`` that are one of ``roots`` or inside one."""
    return [m for m in modules if any(m == r or m.startswith(r + ".") for r in roots)]


@pytest.mark.parametrize("argv", [["--version"], ["--help"], ["-h"]])
def test_version_and_help_load_no_command_and_no_numerical_library(argv):
    exit_code, out, modules = modules_after(argv)
    assert exit_code == 0
    assert ("tactcad " in out) if argv == ["--version"] else ("grasp" in out and "bench" in out)
    assert loaded(modules, HEAVY + DESIGN_MODEL) == []
    commands = {m for m in modules if m in cli.COMMAND_MODULES}
    assert commands == set(), commands


def test_a_commands_help_loads_no_heavy_library_and_not_the_design_model():
    exit_code, out, modules = modules_after(["grasp", "--help"])
    assert exit_code == 0 and "--slab-thickness-mm" in out and "--lead-channel-mm" in out
    assert loaded(modules, HEAVY + ("pydantic", "tactcad.design.array_plan")) == []


def test_the_command_list_says_what_each_module_registers():
    """The top-level help lists the commands from :data:`tactcad.cli.SUMMARIES` without
    importing their modules: each summary is the one its module registers."""
    full = cli.build_parser()
    sub = next(a for a in full._actions if isinstance(a, argparse._SubParsersAction))
    registered = {action.dest: action.help for action in sub._choices_actions}
    assert registered == cli.SUMMARIES
    light = cli.build_parser(["--help"])
    assert light.format_help() == full.format_help()


def test_a_bad_source_date_epoch_is_still_refused_before_the_parse(monkeypatch, capsys):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "yesterday")
    assert cli.main(["--version"]) == 2
    err = capsys.readouterr().err
    assert "SOURCE_DATE_EPOCH" in err and "yesterday" in err and "253402300799" in err
