"""Every option naming a file or folder a command writes keeps one rule, before any work
(:func:`tactcad.atomic.refuse_output_path`): no system folder, no missing folder made in a
system folder or in one that takes none, an existing folder that is not writable said as
such; each refusal names the option, the value and what is allowed (exit 2)."""

from __future__ import annotations

import argparse
import json
import os
import tempfile
from pathlib import Path

import pytest

from tactcad import cli
from tactcad.design.array_plan import DEFAULT_DESIGN
from tactcad.errors import DesignError

#: Options naming a file or folder a command reads, not writes.
INPUT_OPTIONS = {"--design", "--data", "--flat", "--calibration", "--points", "--jaw",
                 "--project", "--coupled-design", "--from-design", "--example", "--samples",
                 "OLD", "NEW"}
#: What a command needs besides the option tried to get past its parser.
NEEDS = {
    ("design",): ["--kr-over-km", "5", "--kobj-range", "0.2", "1.5", "--full-scale-force",
                  "0.05", "--jaw", "10", "--out", "d"],
    ("atlas",): ["--jaw", "10"],
    ("diff",): ["old.toml", "new.toml"],
    ("new",): ["proj"],
    ("lumped",): ["--km", "1", "--kr", "5", "--kobj", "1"],
    ("calibrate",): ["--simulate"],
}


def leaves(parser: argparse.ArgumentParser, path=()):
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield path, parser
        return
    for name, sub in subs[0].choices.items():
        yield from leaves(sub, path + (name,))


def written_options() -> list[tuple[tuple[str, ...], str, str]]:
    """(command, option, file or folder) of every option whose value names a path the
    command writes: a path metavar that is no input."""
    found = []
    for path, p in leaves(cli.build_parser()):
        for action in p._actions:
            metavar = action.metavar if isinstance(action.metavar, str) else ""
            name = max(action.option_strings, key=len) if action.option_strings else metavar
            if name in INPUT_OPTIONS or not any(word in metavar for word in
                                                ("DIR", "FILE", "PNG", "CSV", ".toml")):
                continue
            found.append((path, name, "a file" if metavar in ("FILE", "PNG", "CSV")
                          else "a folder"))
    return found


def command_line(path, option: str, value: str) -> list[str]:
    needs = list(NEEDS.get(path, []))
    if option == "--out" and "--out" in needs:
        del needs[needs.index("--out"):needs.index("--out") + 2]
    if not option.startswith("-"):  # a positional folder (new DIR)
        return [*path, value]
    return [*path, *needs, option, value]


def test_every_written_path_option_is_found():
    found = {(path, option) for path, option, _ in written_options()}
    assert {(("budget",), "--out"), (("stiffness",), "--vtk"), (("check",), "--junit"),
            (("check",), "--out"), (("modal",), "--vtu"), (("export",), "--out"),
            (("evaluate",), "--plot"), (("calibrate",), "--write-csv"),
            (("bench", "review"), "--screenshot"), (("new",), "DIR"),
            (("stiffness",), "--cache"), (("sweep", "refit"), "--out")} <= found


@pytest.mark.parametrize("path, option, what", written_options(),
                         ids=lambda x: " ".join(x) if isinstance(x, tuple) else x)
def test_a_written_path_in_a_system_folder_is_refused_before_any_work(path, option, what):
    """`budget --out /etc/b.json`, `stiffness --vtk /etc/vtkx`, `check --junit
    /etc/junit.xml` wrote into /etc (exit 0); every such option keeps the rule `--out` of
    design, atlas and export kept."""
    value = "/etc/tactcad-out" + (".png" if "plot" in option or "screenshot" in option
                                  else ".csv" if "csv" in option
                                  else ".json" if what == "a file" else "")
    with pytest.raises(DesignError) as exc:
        cli.parse_checked(command_line(path, option, value))
    assert exc.value.field == option and exc.value.value == value
    assert "outside the system folders" in exc.value.allowed
    assert not os.path.exists(value)


@pytest.mark.parametrize("argv", [
    ["budget", "--out", "/tactcad-no-such-folder/dir/b.json"],
    ["stiffness", "--element", "1", "--model", "fem2d", "--vtk", "/tactcad-no-such-folder/v"],
    ["check", "--junit", "/tactcad-no-such-folder/junit.xml"],
    ["export", "--out", "/tactcad-no-such-folder/exports"]])
def test_a_missing_folder_is_not_made_in_a_system_folder(argv):
    """`budget --out /nonexistent/dir/b.json` made /nonexistent at the root."""
    with pytest.raises(DesignError) as exc:
        cli.parse_checked(argv)
    assert exc.value.field == argv[-2] and exc.value.value == argv[-1]
    assert "/tactcad-no-such-folder does not exist and would be made in /, a system folder" \
        in str(exc.value)
    assert not os.path.exists("/tactcad-no-such-folder")


def test_a_missing_folder_below_a_writable_one_is_made(tmp_path, capsys):
    out = tmp_path / "new" / "deeper" / "b.json"
    assert cli.main(["budget", "--design", str(DEFAULT_DESIGN), "--out", str(out),
                     "--quiet"]) == 0
    assert json.loads(out.read_text())


def test_a_budget_under_proc_names_out_with_exit_2(capsys):
    """`budget --out /proc/budget.json` was "No such file or directory" (exit 3)."""
    code = cli.main(["budget", "--design", str(DEFAULT_DESIGN), "--out", "/proc/budget.json",
                     "--json"])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["field"] == "--out" and err["value"] == "/proc/budget.json"
    assert "outside the system folders" in err["allowed"]


@pytest.fixture
def read_only(tmp_path, monkeypatch):
    """``tmp_path/x`` and ``tmp_path/x/ro``, neither writable by this user (as an unprivileged
    user sees a folder of root's): the system's access check and a probe folder refuse."""
    locked = tmp_path / "x"
    (locked / "ro").mkdir(parents=True)
    real_access, real_mkdtemp = os.access, tempfile.mkdtemp

    def access(p, mode, *a, **kw):
        inside = Path(os.path.abspath(p)) == locked or locked in Path(os.path.abspath(p)).parents
        return not (inside and mode & os.W_OK) and real_access(p, mode, *a, **kw)

    def mkdtemp(*a, dir=None, **kw):
        if dir is not None and (Path(dir) == locked or locked in Path(dir).parents):
            raise PermissionError(13, "Permission denied", str(dir))
        return real_mkdtemp(*a, dir=dir, **kw)

    monkeypatch.setattr(os, "access", access)
    monkeypatch.setattr(tempfile, "mkdtemp", mkdtemp)
    return locked


def test_an_existing_read_only_folder_is_said_to_be_not_writable(read_only, capsys):
    """`export --out /tmp/x/ro` (ro there, mode 555) said "the folder cannot be made"."""
    ro = read_only / "ro"
    code = cli.main(["export", "--only", "bom", "--no-cache", "--json", "--out", str(ro)])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["field"] == "--out" and err["value"] == str(ro)
    assert err["allowed"] == "a writable folder (new or existing)"
    assert f"{ro} exists and is not writable: permission denied" in err["message"]
    assert "cannot be made" not in err["message"]


def test_a_file_in_a_read_only_folder_names_the_option(read_only, capsys):
    """`budget --out /tmp/x/ro/b.json` was "error: /tmp/x/ro/b.json: permission denied"."""
    target = read_only / "ro" / "b.json"
    code = cli.main(["budget", "--design", str(DEFAULT_DESIGN), "--out", str(target),
                     "--json"])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["field"] == "--out" and err["value"] == str(target)
    assert err["allowed"] == "a file in a writable folder"
    assert f"{read_only / 'ro'} exists and is not writable" in err["message"]
    with pytest.raises(DesignError, match="no folder can be made in .*x: it is not writable"):
        cli.parse_checked(["budget", "--out", str(read_only / "new" / "b.json")])


def test_an_export_folder_whose_parent_takes_no_folder_is_said_to_exist(read_only):
    """The default ``--out`` (not checked by the parser) of a writable folder in a read-only
    one: it exists, the export built beside it is what cannot be made."""
    from tactcad.errors import ExportPathError
    from tactcad.export.run import check_out_dir

    inner = read_only / "ro" / "exports"
    inner.mkdir()
    os_access = os.access
    os.access = lambda p, mode, *a, **kw: Path(p) == inner or os_access(p, mode, *a, **kw)
    try:
        with pytest.raises(ExportPathError, match=f"{inner} exists, but the new export is "
                           "built beside it"):
            check_out_dir(inner)
    finally:
        os.access = os_access


def test_the_api_cache_keeps_the_rule():
    from tactcad.store import usable_cache_folder

    with pytest.raises(DesignError, match="outside the system folders"):
        usable_cache_folder("/etc/tactcad-cache", "cache")


@pytest.mark.parametrize("argv, option", [
    (["design", "--jaw", "5", "--kr-over-km", "8", "--kobj-range", "0.4", "4",
      "--full-scale-force", "0.008", "--out", os.fsdecode(b"bad\xffname")], "--out"),
    (["stiffness", "--element", "1", "--design", os.fsdecode(b"\xff.toml")], "--design")])
def test_a_byte_that_is_not_utf8_is_not_called_a_control_character(argv, option):
    """An undecodable byte reached the option as U+DCFF (os.fsdecode's surrogateescape) and
    was refused as "text without control characters (found U+DCFF)"."""
    with pytest.raises(DesignError) as exc:
        cli.parse_checked(argv)
    assert exc.value.field == option
    assert "a byte that is not UTF-8 (0xFF)" in exc.value.allowed
    assert "U+DCFF" not in str(exc.value) and "control character" not in str(exc.value)


def test_a_control_character_is_still_one():
    with pytest.raises(DesignError, match=r"found U\+0001"):
        cli.parse_checked(["budget", "--out", "b\x01.json"])
