"""Hypothesis strategies for command lines, drawn by introspecting tactcad's
argument parser (so a new command or option is drawn without a line here);
used by tests/commands/test_options.py and scripts/fuzz_inputs.py."""

from __future__ import annotations

import argparse

from hypothesis import strategies as st

from tactcad import cli
from tactcad.commands.options import options_of

PARSER = cli.build_parser()
COMMANDS = dict(options_of(PARSER))
#: Valid values for required options, so a draw reaches the command's own checks.
VALID = {"--km": ["15.25"], "--kr": ["80.38"], "--kobj": ["3.85"], "--element": ["3"],
         "--kr-over-km": ["10"], "--kobj-range": ["1", "10"], "--full-scale-force": ["2"],
         "--out": ["new.toml"]}
#: Commands whose handlers take minutes (CAD export, FEM, Dask clusters) or
#: never end (a file watcher): the end-to-end test stops at their checks.
LONG = {("export",), ("check",), ("design",), ("watch",), ("verify",)} | \
    {c for c in COMMANDS if c[0] in ("bench", "sweep")}
SPECIAL = ["", " ", "-0", "-0.0", "nan", "inf", "-inf", "1e308", "1e-320", "-1", "0",
           "99999999999999999999", "x", "/", ".", "/nonexistent/file.toml", "exports",
           "hardware/macro_array.toml", "hardware", "Ti", "ü€.toml", "a" * 300, "K=V", "a,b",
           "--json"]


def option_actions(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    return [a for a in parser._actions if a.option_strings
            and not isinstance(a, (argparse._HelpAction, argparse._VersionAction))]


def value_strategy(action: argparse.Action) -> st.SearchStrategy[str]:
    text = st.text(st.characters(blacklist_categories=("Cs",), blacklist_characters="\0"),
                   max_size=12)
    base = st.sampled_from(SPECIAL) | text
    if action.choices:
        base = st.sampled_from([str(c) for c in action.choices]) | base
    if action.type in (float,) or getattr(action.type, "__name__", "") == "number":
        base = st.floats(allow_nan=True, allow_infinity=True).map(repr) | base
    if action.type in (int,) or getattr(action.type, "__name__", "") == "integer":
        base = st.integers(-2**70, 2**70).map(str) | base
    return base


@st.composite
def command_lines(draw, commands=tuple(COMMANDS)):
    """A command, some of its options with drawn values, the required ones valid."""
    path = draw(st.sampled_from(sorted(commands)))
    parser = COMMANDS[path]
    actions = option_actions(parser)
    chosen = draw(st.lists(st.sampled_from(actions), max_size=3, unique_by=id)) if actions else []
    argv = list(path)
    for action in chosen:
        argv.append(max(action.option_strings, key=len))
        n = action.nargs
        if n == 0:
            continue
        count = n if isinstance(n, int) else draw(st.integers(1, 3)) if n in ("+", "*") else 1
        argv += [draw(value_strategy(action)) for _ in range(count)]
    for action in parser._actions:  # positionals (diff OLD NEW, scenes [NAME])
        if action.option_strings or isinstance(action, argparse._SubParsersAction):
            continue
        if action.nargs == "?" and draw(st.booleans()):
            continue
        n = action.nargs if isinstance(action.nargs, int) else 1
        argv += [draw(value_strategy(action)) for _ in range(n)]
    for action in actions:
        name = max(action.option_strings, key=len)
        if action.required and action not in chosen:
            argv += [name] + VALID.get(name, ["1"] * (action.nargs if isinstance(action.nargs, int)
                                                      else 1))
    for group in parser._mutually_exclusive_groups:
        if group.required and not any(a in chosen for a in group._group_actions):
            first = group._group_actions[0]
            name = max(first.option_strings, key=len)
            argv += [name] + ([] if first.nargs == 0 else VALID.get(name, ["1"]))
    return argv
