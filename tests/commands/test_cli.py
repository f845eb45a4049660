"""The command line as a user meets it: ./tactcad, --set, --json (errors
included), progress on stderr, export --only/--part, check reusing an export."""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest

import tactcad
from conftest import run_cli, warm_store_copy, with_default_companions
from tactcad import cli
from tactcad.design.array_plan import DEFAULT_DESIGN
from tactcad.commands import parse_override, plan_from_args, progress_from_args
from tactcad.errors import DesignError, DesignErrors
from tactcad.export.job import Job
from tactcad.export.kinds import full_export_kinds
from tactcad.export.kinds import parse_only
from tactcad.export.selection import (job_kind, job_part, select_jobs,
                                      with_progress)

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src"


def leaf_parsers(parser: argparse.ArgumentParser, path=()):
    """(command words, parser) of every command that runs something."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield path, parser
        return
    for name, sub in subs[0].choices.items():
        yield from leaf_parsers(sub, path + (name,))


def options(parser: argparse.ArgumentParser) -> set[str]:
    return {s for a in parser._actions for s in a.option_strings}


# --- every command: --json, --quiet, and --set wherever --design is -----------------------------
def test_every_command_has_json_and_quiet_and_set_with_design():
    leaves = list(leaf_parsers(cli.build_parser()))
    assert len(leaves) >= 20  # export ... sweep refit: the whole tree was walked
    for path, p in leaves:
        opts = options(p)
        assert {"--json", "--quiet"} <= opts, path
        if "--design" in opts:
            assert "--set" in opts, path


def test_set_values_are_toml_values():
    assert parse_override("element.web_thickness_mm=0.3") == ("element.web_thickness_mm", 0.3)
    assert parse_override("arms.lengths_mm=[4,5,6]") == ("arms.lengths_mm", [4, 5, 6])
    assert parse_override('design.name = "x"') == ("design.name", "x")
    assert parse_override("array.columns=5") == ("array.columns", 5)


@pytest.mark.parametrize("text, field", [("web=0.3", "--set"), ("element.web_thickness_mm", "--set"),
                                         (".x=1", "--set"),
                                         ("element.web_thickness_mm=abc", "element.web_thickness_mm")])
def test_set_refuses_bad_syntax_naming_the_field(text, field):
    with pytest.raises(DesignError) as err:
        parse_override(text)
    assert err.value.field == field and err.value.allowed


def test_plan_from_args_applies_every_set_in_order():
    args = argparse.Namespace(design=None, overrides=[
        "element.web_thickness_mm=0.2", "element.web_thickness_mm=0.3",
        "arms.lengths_mm=[4,5,6,7,8,4,5,6,7,7.5]"])
    plan = plan_from_args(args)
    base = plan_from_args(argparse.Namespace(design=None, overrides=[]))
    assert plan.element(1).geometry.web_thickness_mm == 0.3
    assert plan.element(10).geometry.arm_length_mm == 7.5
    assert plan.design_hash != base.design_hash
    assert plan.source == base.source  # rigs and scenes are still found beside the file


def test_unknown_set_key_is_a_json_error_with_field_value_allowed(capsys):
    code = cli.main(["stiffness", "--element", "1", "--set", "element.web_thicknes_mm=0.3",
                     "--json"])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["exit_code"] == 2
    assert err["field"] == "element.web_thicknes_mm" and err["value"] == 0.3
    assert "web_thickness_mm" in err["allowed"]


def test_a_set_of_an_unknown_table_is_refused_as_the_set_not_the_file(capsys):
    code = cli.main(["strength", "--set", "nope.x=1"])
    out = capsys.readouterr()
    assert code == 2
    assert out.err.startswith("tactcad: error: --set nope.x=1: nope = ")
    assert "unknown section" in out.err


def test_out_of_range_set_is_refused_as_text_without_json(capsys):
    code = cli.main(["strength", "--set", "element.web_thickness_mm=3"])
    out = capsys.readouterr()
    assert code == 2 and out.out == ""
    assert out.err.startswith("tactcad: error: --set element.web_thickness_mm=3: "
                              "element.web_thickness_mm = 3: allowed")


def test_a_refused_set_value_is_named_as_set_and_the_files_own_as_the_files(tmp_path, capsys):
    design = tmp_path / "d.toml"
    text = DEFAULT_DESIGN.read_text(encoding="utf-8").replace("[edm]\nwire_diameter_mm = 0.25",
                                                              "[edm]\nwire_diameter_mm = 9.0")
    design.write_text(text, encoding="utf-8")
    with_default_companions(design)
    code = cli.main(["strength", "--design", str(design), "--set", "element.web_thickness_mm=0.3",
                     "--set", "element.web_thickness_mm=3", "--set", "arms.lengths_mm=[1]"])
    err = capsys.readouterr().err
    assert code == 2
    assert "--set element.web_thickness_mm=3: element.web_thickness_mm = 3: allowed" in err
    assert "--set arms.lengths_mm=[1]: arms.lengths_mm[1] = 1: allowed" in err  # an item of it
    assert "d.toml: edm.wire_diameter_mm = 9.0: allowed" in err  # the file's own value
    assert "d.toml: element.web_thickness_mm" not in err


def test_the_api_names_a_refused_set_value_as_set():
    with pytest.raises(DesignErrors) as err:
        tactcad.load(set={"element.web_thickness_mm": 3.0})
    assert [e.file for e in err.value.errors] == ["set"]
    assert str(err.value).startswith("set: element.web_thickness_mm = 3.0: allowed")


def test_json_error_never_writes_nan(capsys):
    code = cli.main(["strength", "--json", "--set", "element.web_thickness_mm=nan"])
    text = capsys.readouterr().out
    assert code == 2 and "NaN" not in text
    err = json.loads(text)["error"]
    assert err["field"] == "element.web_thickness_mm" and err["value"] is None


def test_usage_errors_are_json_too(capsys):
    assert cli.main(["stiffness", "--json"]) == 2  # --element missing
    err = json.loads(capsys.readouterr().out)["error"]
    assert "--element" in err["message"] and err["exit_code"] == 2
    assert cli.main(["stiffness"]) == 2
    assert "--element (not given): allowed a value" in capsys.readouterr().err


@pytest.mark.parametrize("argv, field, value, allowed", [
    (["stiffness"], "--element", None, "a value"),
    (["stiffness", "--element", "1", "--model", "fem9"], "--model", "fem9", "one of "),
    (["design", "--rows", "many"], "--rows", "many", "an integer 1 ... 100"),
    (["design", "--footprint", "3"], "--footprint", None, "2 values after it"),
    (["stiffness", "--element", "1", "--elem", "2"], "--elem", "--elem", "an option of this "),
    (["nonsense"], "COMMAND", "nonsense", "one of new, export"),
])
def test_a_usage_error_in_json_names_its_field_value_and_allowed(capsys, argv, field, value,
                                                                 allowed):
    assert cli.main([*argv, "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert (err["field"], err["value"]) == (field, value)
    assert err["allowed"].startswith(allowed)


def test_a_line_missing_several_arguments_and_holding_an_unknown_one_names_them_all(capsys):
    """argparse stops at the first kind of fault; the refusal names every missing argument
    and every option the command does not know, each in the JSON's errors."""
    assert cli.main(["design", "--jaw", "5", "--bogus", "3", "--kobj-range", "1", "5",
                     "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    named = {e["field"]: e["allowed"] for e in err["errors"]}
    assert list(named) == ["--kr-over-km", "--full-scale-force", "--out", "--bogus"]
    assert named["--bogus"].startswith("an option of this command")
    assert err["field"] == "--kr-over-km" and "--bogus" in err["message"]
    # a negative number is a value, not an unknown option; one missing argument alone
    assert cli.main(["lumped", "--km", "-1", "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert "unrecognized" not in err["message"]


@pytest.mark.parametrize("repeat", [["--model", "fem2d", "--model", "beam"],
                                    ["--model=fem2d", "--model", "beam"]])
def test_an_option_of_one_value_given_twice_takes_the_last_and_says_so(capsys, repeat):
    """Not silent: the warning names every value and the one taken (the last, so that an
    alternative a refusal names can be pasted at the end of the command line)."""
    assert cli.main(["stiffness", "--element", "1", *repeat, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["model"] == "beam"
    assert "--model given 2 times (fem2d, beam): the last, beam, is taken" in doc["warnings"]
    # an option that gathers may repeat without a word, but a --set key set twice is said
    assert cli.main(["stiffness", "--element", "1", "--set", "element.web_thickness_mm=0.3",
                     "--set", "element.notch_radius_mm=1.0", "--json"]) == 0
    assert not [w for w in json.loads(capsys.readouterr().out)["warnings"] if "given" in w]
    assert cli.main(["stiffness", "--element", "1", "--set", "element.web_thickness_mm=0.3",
                     "--set", "element.web_thickness_mm=0.31", "--json"]) == 0
    assert ("--set element.web_thickness_mm given 2 times (0.3, 0.31): the last, 0.31, is "
            "taken") in json.loads(capsys.readouterr().out)["warnings"]


def test_an_out_folder_under_a_file_is_json_with_exit_2(capsys, tmp_path):
    """A folder that cannot be made is the option's fault (exit 2), said in the JSON error
    with the option and the file in the way."""
    blocker = tmp_path / "file"
    blocker.write_text("x")
    code = cli.main(["export", "--json", "--only", "bom", "--no-cache",
                     "--out", str(blocker / "sub")])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["exit_code"] == 2 and str(blocker) in err["message"]
    assert "--out" in err["message"] and not (blocker / "sub").exists()


#: What a command needs besides --cache to get past its parser (the rest take defaults).
CACHE_COMMAND_NEEDS = {
    ("design",): ["--kr-over-km", "5", "--kobj-range", "0.2", "1.5", "--full-scale-force",
                  "0.05", "--jaw", "10", "--out", "d"],
    ("atlas",): ["--jaw", "10", "--points", "8", "--seed", "4", "--material",
                 "Ti-6Al-4V-annealed", "--out", "a10x"],
    ("diff",): ["old.toml", "new.toml"],
}


def cache_commands() -> list[tuple[str, ...]]:
    return [path for path, p in leaf_parsers(cli.build_parser()) if "--cache" in options(p)]


@pytest.mark.parametrize("path", cache_commands(), ids=" ".join)
@pytest.mark.parametrize("where", ["afile", "afile/store"])
def test_a_cache_that_is_a_file_or_under_one_is_refused_before_any_work(tmp_path, path,
                                                                        where):
    """An atlas judged every point and then failed `afile/atlas/81: Not a directory`
    (exit 3, nothing written); an export ran without a store. Every command refuses it first."""
    (tmp_path / "afile").write_text("x")
    before = sorted(tmp_path.iterdir())
    r = run_cli(*path, *CACHE_COMMAND_NEEDS.get(path, []), "--cache", where, "--json",
                cwd=tmp_path)
    error = json.loads(r.stdout)["error"]
    assert r.returncode == 2 and error["field"] == "--cache" and error["value"] == where
    assert "writable folder" in error["allowed"] and "Traceback" not in r.stderr
    assert sorted(tmp_path.iterdir()) == before  # nothing judged, built or written


def test_a_cache_folder_without_write_access_is_refused(tmp_path, monkeypatch):
    import os

    from tactcad.commands import usable_cache_folder

    locked = tmp_path / "locked"
    locked.mkdir()
    real_access = os.access
    monkeypatch.setattr(os, "access", lambda p, mode, **kw: Path(p) != locked
                        and real_access(p, mode, **kw))
    for given in (locked, locked / "new" / "store"):
        with pytest.raises(DesignError) as exc:
            usable_cache_folder(str(given))
        assert exc.value.field == "--cache" and "not writable" in str(exc.value)
    assert usable_cache_folder(str(tmp_path / "new" / "store")) == tmp_path / "new" / "store"
    assert not (tmp_path / "new").exists()  # checked, not made


@pytest.mark.parametrize("argv, what", [
    (["export", "--only", "bom", "--no-cache"], "a folder"),
    (["design", "--kr-over-km", "5", "--kobj-range", "0.2", "1.5", "--full-scale-force",
      "0.05", "--jaw", "10"], "a folder")])
def test_an_out_name_too_long_for_the_file_system_is_a_bad_out(capsys, tmp_path, argv, what):
    """A 300-byte name was the file system's error: the whole path as the field, no allowed
    range, exit 3; it is a bad --out with the file system's limit (exit 2)."""
    long = str(tmp_path / ("x" * 300))
    code = cli.main([*argv, "--json", "--out", long])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["exit_code"] == 2 and err["field"] == "--out"
    assert err["allowed"].startswith(f"{what} whose every name is at most ")
    assert "bytes (the file system's limit)" in err["allowed"]


@pytest.mark.parametrize("command", ["stiffness", "modal", "thermal"])
def test_an_element_the_design_has_not_is_refused_as_the_option(capsys, command):
    """`--element 99` was refused as `number = 99` (the API's argument), not the option."""
    code = cli.main([command, "--element", "99", "--json"])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["field"] == "--element" and err["value"] == 99
    assert err["message"].startswith("--element = 99: allowed an integer 1 ... ")


@pytest.mark.parametrize("command", ["stiffness", "modal", "thermal"])
@pytest.mark.parametrize("value", ["2.5", "x", "1e3"])
def test_an_element_that_is_no_integer_names_the_designs_numbers(capsys, command, value):
    """`--element 2.5` was refused by the parser as "an integer 1 ... 10000" where the design
    has ten elements: it is refused with the design's own numbers, as 99 is."""
    code = cli.main([command, "--element", value, "--json"])
    err = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and err["field"] == "--element" and err["value"] == value
    assert err["allowed"] == "an integer 1 ... 10 (the design's element numbers)"


@pytest.mark.parametrize("argv", [["scenes"], ["scenes", "array"], ["strength"],
                                  ["stiffness", "--element", "3"], ["table1"],
                                  ["tolerance", "--samples", "200"],
                                  ["lumped", "--km", "15.25", "--kr", "80.38", "--kobj", "3.85"]])
def test_json_output_parses_and_nothing_goes_to_stderr(argv, capsys):
    assert cli.main([*argv, "--json"]) == 0
    out = capsys.readouterr()
    assert json.loads(out.out) and out.err == ""


def test_scenes_json_holds_what_the_text_lists(capsys):
    assert cli.main(["scenes", "--json"]) == 0
    scenes = json.loads(capsys.readouterr().out)
    assert cli.main(["scenes"]) == 0
    text = capsys.readouterr().out
    for s in scenes:
        assert f"{s['name']}  [{s['rig']}]  {s['parts_placed']} parts placed" in text
        assert sum(i["quantity"] for items in s["groups"].values() for i in items) == \
            s["parts_placed"]


# --- progress --------------------------------------------------------------------------------
def test_progress_goes_to_stderr_unless_json_or_quiet(capsys):
    progress_from_args(argparse.Namespace(json=False, quiet=False))("step 1")
    progress_from_args(argparse.Namespace(json=True, quiet=False))("step 2")
    progress_from_args(argparse.Namespace(json=False, quiet=True))("step 3")
    out = capsys.readouterr()
    assert out.err == "step 1\n" and out.out == ""


def test_fem2d_reports_each_mesh_level(capsys):
    # --no-cache: a solve kept by an earlier test would report its reuse instead
    assert cli.main(["stiffness", "--element", "1", "--model", "fem2d", "--no-cache"]) == 0
    err = capsys.readouterr().err
    assert [int(m) for m in re.findall(r"fem2d element_a4mm: mesh (\d)/3", err)] == [1, 2, 3]
    assert cli.main(["stiffness", "--element", "1", "--model", "fem2d", "--quiet",
                     "--no-cache"]) == 0
    assert "mesh" not in capsys.readouterr().err


def _job(name: str, after=()) -> Job:
    return Job(name, "key-" + name, lambda run: [{"path": name, "part": "-", "kind": "x"}],
               after=tuple(after))


JOBS = [_job("step:element_a4mm"), _job("step:cart"), _job("step:array"), _job("dxf:shop"),
        _job("scene:array"), _job("review:array"), _job("drawing:element_a4mm"),
        _job("drawing:cart"), _job("drawings:pdf", ["drawing:element_a4mm", "drawing:cart"]),
        _job("drawings:png", ["drawings:pdf"]), _job("image:array")]
JOBS.append(_job("bom", [j.name for j in JOBS]))
JOBS.append(_job("crosstalk"))
JOBS.append(_job("instructions"))


def test_with_progress_counts_and_times_each_job_run():
    lines: list[str] = []
    jobs = with_progress(JOBS[:3], lines.append)
    records = [j.make(None) for j in jobs]
    assert [r[0]["path"] for r in records] == [j.name for j in JOBS[:3]]
    assert [re.sub(r"\d+\.\d s$", "T", line) for line in lines] == [
        "[1/3] step:element_a4mm T", "[2/3] step:cart T", "[3/3] step:array T"]


# --- export --only / --part --------------------------------------------------------------------
def test_job_kinds_and_parts():
    assert {job_kind(j.name) for j in JOBS} == set(full_export_kinds())
    assert job_kind("drawings:pdf") == job_kind("drawing:cart") == "drawings"
    assert job_part("drawing:cart") == job_part("step:cart") == "cart"
    assert job_part("dxf:shop") is None and job_part("bom") is None


def test_only_and_part_filter_the_jobs():
    names = [j.name for j in select_jobs(JOBS, ["step", "drawings"], ["cart"])]
    assert names == ["step:cart", "drawing:cart"]
    names = [j.name for j in select_jobs(JOBS, parse_only(["dxf,bom"]))]
    assert names == ["dxf:shop", "bom"]


def test_a_job_reading_left_out_files_gets_its_own_key():
    by_name = {j.name: j for j in select_jobs(JOBS, ["dxf", "bom"])}
    assert by_name["bom"].key != "key-bom"  # the BOM of a full export lists other files
    assert by_name["dxf:shop"].key == "key-dxf:shop"
    full = {j.name: j for j in select_jobs(JOBS, ["drawings"])}
    assert full["drawings:pdf"].key == "key-drawings:pdf"  # every page it reads is there


def test_part_cuts_a_job_of_many_parts_down_to_the_parts_own_files():
    """A job of many parts that can write one part's files alone (the shop DXF's
    profiles) stands, with --part, for one such job per named part it has files of."""
    own = {"cart": _job("dxf:cart")}
    jobs = [j if j.name != "dxf:shop" else replace(j, for_part=own.get) for j in JOBS]
    names = [j.name for j in select_jobs(jobs, ["dxf"], ["cart"])]
    assert names == ["dxf:cart"]
    names = [j.name for j in select_jobs(jobs, [], ["cart", "element_a4mm"])]
    assert names == ["step:element_a4mm", "step:cart", "dxf:cart", "drawing:element_a4mm",
                     "drawing:cart"]
    assert [j.name for j in select_jobs(jobs, ["dxf"])] == ["dxf:shop"]  # no --part: whole
    with pytest.raises(DesignError) as err:
        select_jobs(jobs, ["dxf"], ["element_a4mm"])  # no profile of its own: nothing left
    assert "DXF profile" in str(err.value) and "not the nested sheets" in str(err.value)


def test_export_part_writes_the_parts_own_dxf_profile_as_a_full_export_does(tmp_path):
    from tactcad.export.dxf_sheet import shop_profiles, write_shop_dxf_files

    plan = tactcad.load().plan
    profile = shop_profiles(plan)[0]
    out = tmp_path / "ex"
    assert cli.main(["export", "--no-cache", "--quiet", "--out", str(out), "--only", "dxf",
                     "--part", profile.part]) == 0
    whole = tmp_path / "whole"
    write_shop_dxf_files(plan, whole, lambda line: None)
    written = sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file())
    assert written == sorted([profile.file_name, "manifest.json"])  # no nested sheet
    assert (out / profile.file_name).read_bytes() == (whole / profile.file_name).read_bytes()
    man = json.loads((out / "manifest.json").read_text())
    assert man["partial"]["jobs"] == [f"dxf:{profile.part}"]
    assert [f["kind"] for f in man["files"]] == ["dxf-profile"]


def test_bad_selections_name_the_allowed_values():
    with pytest.raises(DesignError) as err:
        parse_only(["step,stp"])
    assert err.value.value == "stp" and "drawings" in err.value.allowed
    with pytest.raises(DesignError) as err:
        select_jobs(JOBS, [], ["carts"])
    assert err.value.field == "--part" and "cart" in err.value.allowed
    with pytest.raises(DesignError):
        select_jobs(JOBS, ["bom"], ["cart"])  # nothing left


@pytest.mark.slow
def test_partial_export_manifest_lists_only_what_was_written(tmp_path):
    out, store = tmp_path / "out", tmp_path / "store"
    proc = run_cli("export", "--only", "dxf,bom", "--out", str(out), "--cache", str(store))
    assert proc.returncode == 0, proc.stderr
    assert re.search(r"^\[1/2\] dxf:shop \d+\.\d s$", proc.stderr, re.M)
    man = json.loads((out / "manifest.json").read_text())
    paths = [f["path"] for f in man["files"]]
    assert paths and all(p.startswith("dxf/") or p.startswith("bom.") for p in paths)
    assert sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file()) == \
        sorted(paths + ["manifest.json"])
    assert man["partial"]["only"] == ["dxf", "bom"] and man["partial"]["jobs"] == ["dxf:shop", "bom"]
    bom = (out / "bom.csv").read_text(encoding="utf-8-sig")
    assert "dxf/" in bom and ".step" not in bom  # names only the files written

    proc = run_cli("export", "--part", "element_a4mm", "--only", "step", "--out", str(out),
                   "--cache", str(store), "--json")
    assert proc.returncode == 0 and proc.stderr == ""
    written = json.loads(proc.stdout)
    # what ran now, then the same design's earlier files, kept and listed as they were
    assert written["files"][0]["path"] == "step/element_a4mm.step"
    assert sorted(written["kept"]) == sorted(paths)
    man = json.loads((out / "manifest.json").read_text())
    assert sorted(f["path"] for f in man["files"]) == sorted(paths + ["step/element_a4mm.step"])
    assert (out / "bom.csv").read_text(encoding="utf-8-sig") == bom


# --- check reuses the export it checks ---------------------------------------------------------
#: The ``--set`` making the other design whose export check refuses to reuse: its clamp
#: plates 2.5 mm (mm) where the default's are 3 mm.
OTHER_DESIGN_SET = "clamp.plate_thickness_mm=2.5"


def test_the_other_design_checked_differs_and_keeps_the_defaults_elements():
    """The design whose export check refuses is another design, yet its elements are the
    default's: their fem3d solves are the verified store's, so the check solves none."""
    default = plan_from_args(argparse.Namespace(design=None, overrides=[]))
    other = plan_from_args(argparse.Namespace(
        design=None, overrides=[OTHER_DESIGN_SET]))
    assert other.design_hash != default.design_hash and other.clamp != default.clamp
    assert other.distinct_elements == default.distinct_elements


@pytest.mark.slow
def test_check_reuses_a_current_export_and_leaves_a_hand_edit(tmp_path, verified_store):
    out, store = tmp_path / "out", warm_store_copy(verified_store, tmp_path / "store")
    assert run_cli("export", "--out", str(out), "--cache", str(store), "--quiet").returncode == 0
    proc = run_cli("check", "--scene", "wirecut", "--out", str(out), "--cache", str(store),
                   "--json")
    report = json.loads(proc.stdout)
    assert proc.returncode == 0 and report["reused_export"] and report["failed"] == 0
    # a requirement the design does not state is reported, not judged: counted apart
    assert report["passed"] + report["undecided"] + report["info"] == len(report["checks"]) > 0
    assert all((c["passed"] is None) == (c["status"] == "info") for c in report["checks"])

    # an export of another design: its clamp plates thinner, its elements the default's, so
    # its check reads their fem3d solves from the verified store (a thinner web made a new
    # element, whose fem3d solves took most of this test and were not what it asserts)
    other = tmp_path / "other"
    shutil.copytree(out, other)
    proc = run_cli("check", "--scene", "wirecut", "--out", str(other), "--cache", str(store),
                   "--set", OTHER_DESIGN_SET, "--json")
    report = json.loads(proc.stdout)
    assert not report["reused_export"] and "another design" in report["export_refusal"]

    with open(out / "scenes" / "wirecut.glb", "ab") as fh:
        fh.write(b"\0")
    edited = (out / "scenes" / "wirecut.glb").read_bytes()
    proc = run_cli("check", "--scene", "wirecut", "--out", str(out), "--cache", str(store))
    assert proc.returncode == 1  # a hand edit is left as it is and fails
    assert "1 file(s) changed or removed by hand since the export" in proc.stderr
    assert re.search(r"^FAIL  export_file\s+scenes/wirecut.glb\s+edited since the export",
                     proc.stdout, re.M)
    assert (out / "scenes" / "wirecut.glb").read_bytes() == edited


# --- ./tactcad -----------------------------------------------------------------------------------
def launcher_checkout(tmp_path: Path) -> Path:
    """A copy of the launcher, Makefile, pyproject.toml and constraints.txt with a set-up .venv
    whose tactcad runs this source tree."""
    for name in ("tactcad", "Makefile", "pyproject.toml", "constraints.txt"):
        shutil.copy2(ROOT / name, tmp_path / name)
    bin_dir = tmp_path / ".venv" / "bin"
    bin_dir.mkdir(parents=True)
    exe = bin_dir / "tactcad"
    exe.write_text(f"#!/bin/sh\nPYTHONPATH={SRC} exec {sys.executable} -m tactcad.cli \"$@\"\n")
    exe.chmod(0o755)
    (tmp_path / ".venv" / ".installed-stamp").touch()
    return tmp_path


@pytest.mark.slow  # a new interpreter through the launcher
def test_launcher_runs_the_checkouts_venv(tmp_path):
    root = launcher_checkout(tmp_path)
    proc = subprocess.run([str(root / "tactcad"), "lumped", "--km", "15.25", "--kr", "80.38",
                           "--kobj", "3.85", "--json"], capture_output=True, text=True,
                          cwd="/")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["r"] > 1 and proc.stderr == ""
    proc = subprocess.run([str(root / "tactcad"), "stiffness", "--json"], capture_output=True,
                          text=True)
    assert proc.returncode == 2 and json.loads(proc.stdout)["error"]["exit_code"] == 2


def test_launcher_without_venv_says_how_to_set_up(tmp_path):
    root = launcher_checkout(tmp_path)
    shutil.rmtree(root / ".venv")
    tools = tmp_path / "bin"  # a PATH without make: nothing can set .venv up
    tools.mkdir()
    (tools / "dirname").symlink_to(shutil.which("dirname"))
    proc = subprocess.run(["/bin/sh", str(root / "tactcad"), "--version"], capture_output=True,
                          text=True, env={"PATH": str(tools)})
    assert proc.returncode == 3 and "run 'make env'" in proc.stderr


def test_ctrl_c_while_the_kernel_loads_is_one_line(monkeypatch, capsys):
    """An interrupt during a compiled module's initialisation arrives as an
    ImportError caused by KeyboardInterrupt: still exit 130 and one line."""
    from tactcad import cli as cli_mod
    from tactcad.commands import scenes as scenes_cmd

    def interrupted_import(args):
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as exc:
            raise ImportError("initialization failed") from exc

    monkeypatch.setattr(scenes_cmd, "run", interrupted_import)
    assert cli_mod.main(["scenes"]) == cli_mod.EXIT_INTERRUPTED == 130
    err = capsys.readouterr().err
    assert err.strip() == "tactcad: interrupted; the previous files are left as they were"

    def broken_import(args):
        raise ImportError("no module named nothing")

    monkeypatch.setattr(scenes_cmd, "run", broken_import)
    with pytest.raises(ImportError, match="nothing"):
        cli_mod.main(["scenes"])


def test_every_options_help_gives_its_default_and_no_literal_percent():
    """An option with a default says it (``%(default)s`` or in words); help and
    descriptions never print argparse's escape ``%%``."""
    silent = (argparse._HelpAction, argparse._StoreTrueAction, argparse._VersionAction)
    missing = []
    for path, parser in leaf_parsers(cli.build_parser()):
        assert "%%" not in parser.format_help(), path
        for action in parser._actions:
            if not action.option_strings or isinstance(action, silent):
                continue
            if action.default is None or action.default is False or action.default == [] \
                    or action.help == argparse.SUPPRESS:
                continue
            if "%(default)" not in (action.help or "") and "default" not in (action.help or ""):
                missing.append((" ".join(path), action.option_strings[0], action.default))
    assert missing == []


def test_a_stop_before_the_watch_has_begun_is_its_normal_end(capsys):
    """A Ctrl-C or SIGTERM while the command line is still being read (the
    command modules load) ends ``watch`` as a stop at any later moment does
    (README: exit 0, "stopped"); other commands say they were interrupted."""
    from tactcad.cli import command_of, report_interrupt
    from tactcad.errors import Terminated

    assert command_of(["--quiet", "watch", "--out", "x"]) == "watch"
    assert report_interrupt(Terminated(15), False, "watch") == 0
    assert capsys.readouterr().err == "watch: stopped\n"
    assert report_interrupt(KeyboardInterrupt(), False, "export") == 130
    assert "interrupted" in capsys.readouterr().err


def test_json_says_when_it_worked_on_the_shipped_example(tmp_path):
    """Text output heads stderr with the shipped example's name; --json carries the same
    line as a notice, so a script does not read the paper's array as its own."""
    from conftest import run_cli

    r = run_cli("stiffness", "--element", "1", "--json", cwd=tmp_path)
    assert r.returncode == 0 and r.stderr == ""
    notices = json.loads(r.stdout)["notices"]
    assert len(notices) == 1 and "shipped example macro_array" in notices[0]
    (tmp_path / "p").mkdir()
    assert run_cli("new", str(tmp_path / "p" / "q"), cwd=tmp_path).returncode == 0
    own = run_cli("stiffness", "--element", "1", "--json", cwd=tmp_path / "p" / "q")
    assert "notices" not in json.loads(own.stdout)


def test_each_command_module_registers_the_commands_the_table_gives_it():
    import importlib

    parser = cli.Parser(prog="tactcad")
    sub = parser.add_subparsers(dest="command")
    registered = {}
    for name in cli.COMMAND_MODULES:
        before = set(sub.choices)
        importlib.import_module(name).register(sub)
        registered.update({command: name for command in set(sub.choices) - before})
    assert registered == cli.COMMANDS


def test_a_command_line_imports_only_its_own_command_module():
    code = ("import sys; from tactcad import cli; cli.build_parser(['lumped', '--help']); "
            "print(sorted(m for m in sys.modules if m.startswith('tactcad.commands.') "
            "and m.count('.') == 2 and m != 'tactcad.commands.options'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    loaded = set(eval(out))
    assert "tactcad.commands.lumped" in loaded
    assert not loaded & {"tactcad.commands.grasp", "tactcad.commands.export",
                         "tactcad.commands.bench", "tactcad.commands.watch"}, loaded
    # a word that is no command still gets the full list to choose from
    full = cli.build_parser(["exprt"])
    sub = next(a for a in full._actions if isinstance(a, argparse._SubParsersAction))
    assert set(sub.choices) == set(cli.COMMANDS)


def test_stiffness_says_which_strain_is_a_magnitude_and_which_is_signed(capsys):
    """The face strain (a magnitude) beside the grid strain (signed) must not read as two
    signs of one face: the text says which is which, as the JSON's values are."""
    assert cli.main(["stiffness", "--element", "1", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert cli.main(["stiffness", "--element", "1"]) == 0
    lines = {line.split()[0] + " " + line.split()[1]: line
             for line in capsys.readouterr().out.splitlines() if "strain" in line}
    assert doc["face_strain_per_N"] > 0 and "magnitude" in lines["face strain"]
    assert doc["grid_strain_per_N"] < 0 and "signed" in lines["grid strain"]
    assert "magnitude" not in lines["grid strain"]


def test_an_arrays_stiffness_without_element_pastes_its_first_element(capsys):
    assert cli.main(["stiffness", "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["field"] == "--element" and "1 ... 10" in err["allowed"]  # the 2 x 5 example
    assert err["alternatives"][0]["option"] == "--element 1"
    assert cli.main(["stiffness", *err["alternatives"][0]["option"].split(), "--json"]) == 0


def test_a_commands_extra_word_points_to_that_commands_help(capsys):
    # the first word is lumped's DESIGN (its K_m and K_r when not given); the second is extra
    assert cli.main(["lumped", "--kr", "5.842", "--km", "0.7303", "--kobj", "0.5", "5", "6"]) == 2
    assert "(see tactcad lumped --help)" in capsys.readouterr().err


def test_a_set_name_refused_pastes_the_cleaned_name_as_a_set(capsys):
    import shlex

    assert cli.main(["scenes", "--set", 'design.name="Zélé"', "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert "e.g. Zele" in err["allowed"]
    paste = err["alternatives"][0]["option"]
    assert paste == """--set 'design.name="Zele"'"""
    assert cli.main(["scenes", *shlex.split(paste), "--json"]) == 0


@pytest.mark.parametrize("typed, pasted", [("Zélé", "Zele"), ("Zele", "Zele")])
def test_a_set_name_whose_quotes_the_shell_ate_pastes_it_quoted(capsys, typed, pasted):
    """``--set design.name="Zélé"`` typed in bash reaches tactcad as ``design.name=Zélé``, no
    TOML value: the refusal pastes the quoted option, the name cleaned where its own rule
    refuses it, and the paste runs."""
    import shlex

    assert cli.main(["scenes", "--set", f"design.name={typed}", "--json"]) == 2
    err = json.loads(capsys.readouterr().out)["error"]
    assert err["field"] == "design.name" and "a TOML value" in err["allowed"]
    paste = err["alternatives"][0]["option"]
    assert paste == f"""--set 'design.name="{pasted}"'"""
    assert cli.main(["scenes", *shlex.split(paste), "--json"]) == 0


def test_a_set_value_of_no_bare_word_offers_no_quoted_paste():
    with pytest.raises(DesignError) as err:
        parse_override("element.web_thickness_mm=0,3")
    assert err.value.alternatives == []
    with pytest.raises(DesignError) as err:
        parse_override("element.process=wire-edm")
    assert err.value.alternatives[0]["option"] == """--set 'element.process="wire-edm"'"""


@pytest.mark.parametrize("text, allowed", [
    ("element.web_thickness_mm=abc", "a number (mm), 0.05 <= value <= 1 mm"),
    ("array.columns=abc", "an integer 1 ... 12"),
    ("die.full_scale_force_N=abc", "a number (N), "),
])
def test_a_word_for_a_number_key_offers_no_string_paste(text, allowed):
    """``--set element.web_thickness_mm=abc`` offered ``--set
    'element.web_thickness_mm="abc"'``, which the key refuses again as not a number: the
    refusal says the key takes a number, with its range, and pastes nothing."""
    with pytest.raises(DesignError) as err:
        parse_override(text)
    assert err.value.field == text.partition("=")[0] and err.value.value == "abc"
    assert err.value.allowed.startswith(allowed)
    assert err.value.alternatives == []
    # a key that takes text keeps its paste
    with pytest.raises(DesignError) as err:
        parse_override("element.material=abc")
    assert err.value.alternatives[0]["option"] == """--set 'element.material="abc"'"""
