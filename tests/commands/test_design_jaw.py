"""``tactcad design --jaw``: the constructions that seat in a jaw searched, the design and its
scenes written, its kernel-free checks passed; clear refusals."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import pytest
from conftest import run_cli

from tactcad.partlib.grasper_jaw import class_jaw_file_table

GRASPER_CASE = ["design", "--kr-over-km", "10", "--kobj-range", "0.5", "5", "--material",
                "Ti-6Al-4V-annealed", "--columns", "6"]


@pytest.mark.slow  # a whole design search
def test_the_grasper_case_writes_a_comb_and_its_scenes_that_check(tmp_path):
    out = tmp_path / "insert.toml"
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10", "--out", str(out),
                "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["construction"] == "monolithic-comb"
    assert any(line.startswith("stacked:") for line in d["left_out"])
    assert d["max_full_scale_force_N"] > 0.05  # the largest it designs at, as a stacked design's
    assert all(not c["failed"] for c in d["checks"].values()), d["checks"]
    assert {"requirements", "hard stops", "grasper"} <= set(d["checks"])
    # every cut process judged on the rows: wire EDM cuts webs far thinner than the sheet,
    # etching and laser cutting (a minimum web near the sheet's thickness) do not
    assert d["processes"]["wire-edm"] == []
    assert any("flexure web" in line for line in d["processes"]["laser-cutting"])
    assert (tmp_path / "insert-scenes.toml").exists()
    assert 'scenes = "insert-scenes.toml"' in out.read_text(encoding="utf-8")


@pytest.mark.slow  # a whole design search
def test_the_rows_cut_process_is_searched_refused_by_its_own_limits_and_written(tmp_path):
    """``--jaw --process``: each sheet's refusal quotes the process's limit; the force
    pasted from the refusal designs rows the process cuts, written as the rows' process."""
    out = tmp_path / "etched.toml"
    ask = [*GRASPER_CASE, "--jaw", "10", "--process", "photochemical-etching", "--out", str(out),
           "--json"]
    r = run_cli(*ask, "--full-scale-force", "0.05")
    assert r.returncode == 2 and not out.exists(), r.stderr
    err = json.loads(r.stdout)["error"]
    assert "photochemical-etching holds in a" in err["message"], err["message"]
    assert "wire" not in err["message"].split("\n", 1)[1]  # no wire EDM rule binds an etched comb
    pasted = err["alternatives"][0]["option"].split()
    assert "--full-scale-force" in pasted  # with the columns that carry it where 6 do not
    r = run_cli(*ask, *pasted)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["processes"]["photochemical-etching"] == []
    assert all(not c["failed"] for c in d["checks"].values()), d["checks"]
    written = tomllib.loads(out.read_text(encoding="utf-8"))
    assert written["element"]["process"] == "photochemical-etching"
    # an etched web is no thinner than the foil it is etched from
    assert min(written["comb"]["web_thicknesses_mm"]) >= written["sheet"]["thickness_mm"]


def full_scale_force_verdict(path: Path) -> str:
    """The closed form's verdict on a written design's full-scale force."""
    from tactcad.assembly.inventory import array_envelope_mm
    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies.verification import verification_matrix
    from tactcad.vocabulary.schema import read_toml

    plan = plan_from_dict(read_toml(path, "design file"), source=str(path))
    return next(r["verdict"] for r in verification_matrix(plan, "closed-form",
                                                          envelope_mm=array_envelope_mm(plan))
                if r["requirement"] == "full_scale_force_N")


@pytest.mark.slow  # three refusals, each bracketing its force by whole searches
def test_a_comb_refusals_force_is_the_searchs_frontier_whatever_was_asked(tmp_path):
    """Asked 0.2 N or 0.3 N, the refusal names one force, the largest a comb carries as the
    closed form decides it: pasted, it designs a comb whose force passes and which reports
    that force as its largest; 1 % above it, a comb's force is no longer decided (or none
    is designed)."""
    def asked(force, out):
        r = run_cli(*GRASPER_CASE, "--jaw", "10", "--full-scale-force", force, "--out",
                    str(tmp_path / out), "--json")
        return r.returncode, json.loads(r.stdout)
    named = {asked(f, "x.toml")[1]["error"]["allowed"] for f in ("0.2", "0.3")}
    assert len(named) == 1, named
    frontier = float(named.pop().split()[-1])
    code, at = asked(f"{frontier:g}", "at.toml")
    assert code == 0 and full_scale_force_verdict(tmp_path / "at.toml") == "pass"
    assert at["max_full_scale_force_N"] == frontier  # the design's largest, the same rule
    code, _ = asked(f"{frontier * 1.01:.4g}", "above.toml")
    assert code == 2 or full_scale_force_verdict(tmp_path / "above.toml") != "pass"


def design_for_jaw_file(folder, name: str, table: str) -> tuple[dict, dict]:
    """(the report, the written design) of the grasper case at 0.05 N for the jaw file
    ``name`` whose ``[grasper_jaw]`` holds ``table`` (TOML lines)."""
    jaw = folder / name
    keys = {**class_jaw_file_table("10"), **tomllib.loads(table)}  # the 10 mm class's jaw
    jaw.write_text("[grasper_jaw]\n" + "".join(f"{k} = {json.dumps(v)}\n" for k, v in keys.items()),
                   encoding="utf-8")
    out = folder / "insert.toml"
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", str(jaw), "--out",
                str(out), "--json")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout), tomllib.loads(out.read_text(encoding="utf-8"))


@pytest.mark.slow  # a whole comb search through the command line
def test_a_labs_own_jaw_from_a_file_bounds_the_search_and_goes_into_the_design(tmp_path):
    d, written = design_for_jaw_file(tmp_path, "our_jaw.toml", "pocket_width_mm = 5.0\n"
                                     "pocket_length_mm = 27.0\nopening_angle_deg = 40.0\n")
    assert d["jaw"]["jaw"] == "10 mm-shaft jaw of our_jaw.toml"
    assert (d["jaw"]["pocket_across_mm"], d["jaw"]["pocket_along_mm"]) == pytest.approx((4.8, 26.8))
    assert d["jaw"]["height_mm"] == round(d["jaw"]["height_mm"], 6)  # no float noise
    assert d["pitch_mm"] * 6 <= 26.8 and all(not c["failed"] for c in d["checks"].values())
    assert written["grasper_jaw"]["pocket_width_mm"] == 5.0
    # no reason carried over from the template names the template's own jaw
    assert not any("8 mm jaw" in why for why in written["assumptions"].values())
    assert written["grasper_jaw"]["opening_angle_deg"] == 40.0


@pytest.mark.parametrize("content, words", [
    (None, "nor an existing file"),
    ('[grasper_shaft]\nlength_mm = 300.0\n', "no [grasper_jaw] table"),
    ('[grasper_jaw]\npocket_width_mm = 9.0\n', "grasper_jaw.length_mm (not given)"),
    ('[grasper_jaw\n', "valid TOML"),
])
def test_a_jaw_file_that_states_no_jaw_is_refused_by_name(tmp_path, content, words):
    jaw = tmp_path / "jaw.toml"
    if content is not None:
        jaw.write_text(content, encoding="utf-8")
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", str(jaw), "--out",
                str(tmp_path / "x.toml"))
    assert r.returncode == 2 and words in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert not (tmp_path / "x.toml").exists()


@pytest.mark.parametrize("args, option", [
    (["--construction", "stacked", "--jaw", "10"], "--construction"),
    (["--construction", "monolithic-comb"], "--jaw"),
    (["--jaw", "7"], "--jaw"),
    (["--jaw", "10", "--rows", "3"], "--rows"),
    # options the jaw decides itself are refused, not dropped unsaid
    (["--jaw", "10", "--footprint", "30", "8"], "--footprint = '30 8': allowed only without --jaw"),
    (["--jaw", "10", "--pitch", "4"], "--pitch"),
    (["--jaw", "10", "--set", "array.pitch_mm=4"], "--set"),
    (["--jaw", "10", "--verify", "beam"], "--verify"),
    (["--process", "plasma"], "--process"),
])
def test_a_jaw_design_asked_wrongly_names_the_option(tmp_path, args, option):
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", *args, "--out",
                str(tmp_path / "x.toml"))
    assert r.returncode == 2 and option in r.stderr and "Traceback" not in r.stderr
    assert not (tmp_path / "x.toml").exists()


@pytest.mark.parametrize("name", ["insert.TOML", "insert.json", "insert.tml"])
def test_an_out_name_that_names_a_file_is_not_made_a_folder(tmp_path, name):
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10", "--out",
                str(tmp_path / name))
    assert r.returncode == 2 and "--out" in r.stderr and "ending in .toml" in r.stderr, r.stderr
    assert not list(tmp_path.iterdir())


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_jaw_design_into_a_folder_is_a_project_without_test_rigs_that_verifies(tmp_path):
    folder = tmp_path / "our-insert"
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10",
                "--tissue-poisson", "0.45", "--out", str(folder), "--quiet")
    assert r.returncode == 0, r.stderr
    assert sorted(p.name for p in folder.iterdir()) == [
        ".github", ".gitignore", "README.md", "our_insert.toml", "purchased-parts.md", "scenes.toml"]
    text = (folder / "our_insert.toml").read_text(encoding="utf-8")
    header = text.splitlines()[0]
    # the header's command makes the same design: the jaw and the tissue are in it
    assert "--jaw 10" in header and "--tissue-poisson 0.45" in header, header
    assert tomllib.loads(text)["files"] == {"scenes": "scenes.toml"}
    assert "no mount for the test rigs" in (folder / "README.md").read_text(encoding="utf-8")
    r = run_cli("verify", "--design", str(folder / "our_insert.toml"), "--quiet")
    assert r.returncode == 0, r.stderr


@pytest.mark.slow  # a whole design search
def test_a_refused_jaw_design_writes_nothing_and_gives_a_pasteable_force(tmp_path):
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.3", "--jaw", "10", "--out",
                str(tmp_path / "x.toml"))
    assert r.returncode == 2 and "--full-scale-force 0." in r.stderr
    assert not list(tmp_path.iterdir())


@pytest.mark.slow
def test_the_written_jaw_design_exports_and_passes_check(tmp_path):
    out = tmp_path / "insert.toml"
    assert run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10", "--out",
                   str(out)).returncode == 0
    x = tmp_path / "x"
    r = run_cli("export", "--design", str(out), "--out", str(x), "--quiet")
    assert r.returncode == 0, r.stderr
    r = run_cli("check", "--design", str(out), "--out", str(x), "--quiet")
    assert r.returncode == 0, r.stdout[-3000:]
    assert (x / "scenes" / "grasper-closed.step").exists()


def test_a_jaw_too_small_for_any_comb_names_the_sizes_that_bind_and_the_jaw_that_holds_it(
        tmp_path):
    """Screened before any search: the smallest comb's height and width against the 5 mm
    jaw's, each naming the jaw's keys, and the class whose jaw holds it to paste."""
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "5", "--out",
                str(tmp_path / "x.toml"))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    line = next(x for x in r.stderr.splitlines() if "monolithic-comb: does not fit" in x)
    assert line.strip().startswith("monolithic-comb: does not fit: height 5.79 mm (the 0.5 mm "
                                   "sheet's comb"), line
    assert "vs the jaw's 2.6 mm (thickness_mm + tip_proud_mm)" in line
    assert "width 4.2 mm" in line and "vs the pocket's 2.1 mm" in line
    assert "silicon die: not tried: --material is a metal's option" in r.stderr  # the die
    assert "to paste: --construction mems-die" in r.stderr  # takes none, and keeps this jaw
    assert r.stderr.splitlines()[-1].strip().startswith("to paste: --jaw 10")
    assert not list(tmp_path.iterdir())


#: a lab's 8 mm grasper whose jaw (3 mm, beside a 3 mm opposing jaw) holds no comb: no
#: thicker jaw of the 8 mm shaft passes it closed at any width
PALP8_JAW = ("[grasper_jaw]\nshaft_diameter_mm = 8.0\nwidth_mm = 4.8\nlength_mm = 20.0\n"
             "thickness_mm = 3.0\nopposing_jaw_mm = 3.0\npin_diameter_mm = 1.5\n"
             "pin_inset_mm = 1.3\nopening_angle_deg = 40.0\npocket_depth_mm = 1.0\n")


def test_a_comb_asked_by_name_in_a_jaw_too_small_is_refused_for_its_size(tmp_path):
    """``--construction monolithic-comb`` is screened against the jaw as auto is: its refusal
    names --jaw, the height limit and the class's jaw that holds it, not a sheet's arm for
    --full-scale-force; the lab's file gets no key that would pass no 8 mm shaft, but the
    shaft it needs."""
    from tactcad.vocabulary.binding_limits import HEIGHT

    jaw = tmp_path / "palp8_jaw.toml"
    jaw.write_text(PALP8_JAW, encoding="utf-8")
    r = run_cli("design", "--jaw", str(jaw), "--construction", "monolithic-comb",
                "--kr-over-km", "10", "--kobj-range", "0.5", "5", "--full-scale-force", "0.01",
                "--columns", "4", "--material", "Ti-6Al-4V-annealed", "--out",
                str(tmp_path / "comb8"), "--json")
    assert r.returncode == 2, r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"], error["limit"]) == ("--jaw", str(jaw), HEIGHT)
    assert "height 5.79 mm" in error["message"] and "vs the jaw's 3.3 mm" in error["message"]
    assert "width 4.2 mm" in error["message"] and "pocket's 3.6 mm" in error["message"]
    assert "a shaft of at least" in error["message"]
    assert [a["option"] for a in error["alternatives"]] == ["--jaw 10"]
    assert not (tmp_path / "comb8").exists()


def test_a_jaw_files_paste_is_never_a_jaw_its_shaft_refuses(tmp_path):
    """The lab's 8 mm jaw once got ``thickness_mm = 5.5 and width_mm = 0`` to paste; every
    key it is offered now reads back through the jaw's own rules."""
    jaw = tmp_path / "palp8_jaw.toml"
    jaw.write_text(PALP8_JAW, encoding="utf-8")
    r = run_cli("design", "--jaw", str(jaw), "--kr-over-km", "10", "--kobj-range", "0.5", "5",
                "--full-scale-force", "0.5", "--columns", "4", "--out", str(tmp_path / "hi"),
                "--json")
    assert r.returncode == 2, r.stderr
    error = json.loads(r.stdout)["error"]
    assert not [a for a in error["alternatives"] if "grasper_jaw." in a["option"]], error
    assert "no jaw of the 8 mm shaft holds it" in error["message"]
    assert "--jaw 10" in [a["option"] for a in error["alternatives"]]


@pytest.mark.slow  # a whole comb search through the command line
def test_a_jaw_file_of_any_name_is_read_as_toml(tmp_path):
    d, written = design_for_jaw_file(tmp_path, "our_jaw.cfg", "pocket_width_mm = 5.0\n")
    assert d["jaw"]["jaw"] == "10 mm-shaft jaw of our_jaw.cfg"
    assert written["grasper_jaw"]["pocket_width_mm"] == 5.0


@pytest.mark.slow  # a whole comb search through the command line
def test_a_jaw_file_whose_name_has_a_space_is_quoted_wherever_its_command_is_written(tmp_path):
    """The header and the reasons both write ``tactcad design --jaw FILE``: each pastes into a
    shell as one word for the file, and the design stays valid TOML."""
    import shlex

    _, written = design_for_jaw_file(tmp_path, "lab jaw.cfg", "pocket_width_mm = 5.0\n")
    reason = written["assumptions"]["sheet.thickness_mm"]
    command = reason.split(":", 1)[0]
    assert shlex.split(command) == ["tactcad", "design", "--jaw", "lab jaw.cfg"], reason
    header = (tmp_path / "insert.toml").read_text(encoding="utf-8").splitlines()[0]
    words = shlex.split(header.split("`")[1])
    assert words[words.index("--jaw") + 1] == str(tmp_path / "lab jaw.cfg")


@pytest.mark.slow  # a whole comb search through the command line
def test_a_tapered_jaws_outline_bounds_each_sheets_comb(tmp_path):
    d, written = design_for_jaw_file(tmp_path, "taper.toml", "pocket_outline_mm = [[4.0, -2.75], "
                                     "[33.0, -2.25], [33.0, 2.25], [4.0, 2.75]]\n")
    # only a sheet whose comb is no wider than the taper's tip (4.5 mm less clearances) fits
    assert d["sheet_mm"] == 0.5 and all(not c["failed"] for c in d["checks"].values())
    assert any("no stretch" in (c["binding"] or [""])[0] for c in d["candidates"]
               if c["sheet_mm"] >= 1.2)
    assert len(written["grasper_jaw"]["pocket_outline_mm"]) == 4


def test_more_columns_than_the_jaw_holds_names_the_most_that_fit(tmp_path):
    r = run_cli(*GRASPER_CASE[:-1], "7", "--full-scale-force", "0.05", "--jaw", "10", "--out",
                str(tmp_path / "x.toml"))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "length 30.1 mm (7 columns at its least pitch 4.3 mm) vs the pocket's 29.1 mm" \
        in r.stderr
    assert r.stderr.splitlines()[-1].strip().startswith("to paste: --columns 6"), r.stderr[-400:]
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("construction", ["auto", "monolithic-comb"])
def test_more_columns_than_the_pocket_holds_name_the_columns_and_the_sheet_either_way(
        tmp_path, construction):
    """With the die not tried, auto is the comb alone: its screen's refusal names the same
    option and limit code as the comb's own search, and the columns it offers design."""
    r = run_cli(*GRASPER_CASE[:-1], "7", "--full-scale-force", "0.05", "--jaw", "10",
                "--construction", construction, "--out", str(tmp_path / "x.toml"), "--json")
    assert r.returncode == 2, r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"], error["limit"]) == ("--columns", 7, "sheet")
    assert [a["option"] for a in error["alternatives"]] == ["--columns 6"]


@pytest.mark.parametrize("columns", ["13", "50"])
def test_more_columns_than_any_comb_takes_pastes_the_most_the_pocket_holds(tmp_path, columns):
    """Past the grid's range (1 ... 12) the comb's refusal still pastes a column count: the
    most whose comb the pocket holds (the grasper case's 6, which designs), not nothing."""
    r = run_cli(*GRASPER_CASE[:-1], columns, "--full-scale-force", "0.05", "--jaw", "10",
                "--construction", "monolithic-comb", "--out", str(tmp_path / "x.toml"),
                "--json")
    assert r.returncode == 2, r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == ("--columns", int(columns))
    # the range that binds is the pocket's (6 columns), not the grid's 1 ... 12 the refusal
    # stated before pasting 6
    assert error["allowed"] == (f"1 ... {GRASPER_CASE[-1]} for a monolithic comb in this "
                                "jaw's pocket")
    assert "the grid's range (array.columns) is 1 ... 12" in error["message"]
    assert [a["option"] for a in error["alternatives"]] == [f"--columns {GRASPER_CASE[-1]}"]
    assert "the pocket holds" in error["alternatives"][0]["words"]
    assert not list(tmp_path.iterdir())


def test_a_comb_asked_too_few_columns_pastes_the_fewest_it_takes():
    from tactcad.design.array_plan import EXAMPLES, read_toml
    from tactcad.errors import DesignError
    from tactcad.partlib.grasper_jaw import jaw_room
    from tactcad.studies.comb_design import check_comb_columns
    from tactcad.studies.inverse_design import Targets

    base = read_toml(EXAMPLES / "grasper_jaw_10mm/grasper_jaw_10mm.toml", "design file")
    targets = Targets(kr_over_km=10.0, k_obj_range_N_per_mm=(0.5, 5.0), full_scale_force_N=0.05)
    with pytest.raises(DesignError) as refused:
        check_comb_columns(0, jaw_room("10"), base, targets)
    assert [a["option"] for a in refused.value.alternatives] == ["--columns 1"]


def test_a_comb_as_the_layout_searchs_base_is_refused_naming_the_jaw_option(tmp_path):
    comb = "hardware/grasper_jaw_10mm/grasper_jaw_10mm.toml"
    out = tmp_path / "x.toml"
    r = run_cli("design", "--design", comb, "--kr-over-km", "3", "--kobj-range", "5", "20",
                "--full-scale-force", "0.3", "--verify", "none", "--out", str(out))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "--design" in r.stderr and "monolithic-comb" in r.stderr
    assert f"--jaw {comb}" in r.stderr and not out.exists()


@pytest.mark.parametrize("name", ["mein Einsatz", "-dash", "ü"])
def test_an_out_that_is_no_design_name_is_refused_before_the_search(tmp_path, name):
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10",
                "--out", str(tmp_path / name))
    assert r.returncode == 2 and "--out" in r.stderr and "starting with a letter" in r.stderr
    assert not (tmp_path / name).exists()


def test_the_out_help_says_a_name_with_other_characters_is_refused_with_its_cleaned_name(
        tmp_path):
    """The help promised such characters "made '_'"; the name is refused, offering the
    cleaned one, and the help's example is the refusal's own."""
    from tactcad import cli
    from tactcad.vocabulary.schema import NAME_ALLOWED

    design = cli.build_parser(["design"])._subparsers._group_actions[0].choices["design"]
    help_text = next(a.help for a in design._actions if "--out" in a.option_strings)
    assert "may not hold made '_'" not in help_text and NAME_ALLOWED in help_text
    assert "is refused, offering it cleaned to paste (--out pince_ete for 'pince été')" \
        in help_text
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10",
                "--out", "pince été", "--json", cwd=tmp_path)
    error = json.loads(r.stdout)["error"]
    assert r.returncode == 2 and error["field"] == "--out"
    assert error["alternatives"][0]["option"] == "--out pince_ete"
    assert not list(tmp_path.iterdir())


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_grasp_to_survive_is_judged_on_the_comb_and_written_as_its_requirement(tmp_path):
    out = tmp_path / "insert.toml"
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10",
                "--max-grasp-force", "15", "--out", str(out))
    assert r.returncode == 0, r.stderr
    written = tomllib.loads(out.read_text(encoding="utf-8"))
    assert written["requirements"]["max_grasp_force_N"] == 15.0
    assert written["assumptions"]["requirements.max_grasp_force_N"].startswith("Asked")
    assert "--max-grasp-force 15" in out.read_text(encoding="utf-8").splitlines()[0]
    r = run_cli("verify", "--design", str(out), "--json")
    assert r.returncode == 0, r.stderr
    grasp = [x for x in json.loads(r.stdout)["matrix"] if x["requirement"] == "max_grasp_force_N"]
    assert grasp and grasp[0]["verdict"] == "pass"


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_grasp_beyond_the_jaws_reach_is_refused_by_its_option(tmp_path):
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10",
                "--max-grasp-force", "100", "--out", str(tmp_path / "x.toml"))
    assert r.returncode == 2 and "--max-grasp-force" in r.stderr and "out of reach" in r.stderr
    assert not (tmp_path / "x.toml").exists()
    r = run_cli("design", "--kr-over-km", "3", "--kobj-range", "5", "20", "--full-scale-force",
                "0.3", "--max-grasp-force", "10", "--out", str(tmp_path / "y.toml"))
    assert r.returncode == 2 and "--max-grasp-force" in r.stderr and "only with --jaw" in r.stderr


@pytest.mark.slow  # a comb search and its grasps, twice
def test_a_grasp_beyond_the_jaws_reach_offers_the_most_it_reaches_which_designs(tmp_path):
    """The jaw closed flat on its slab puts 53.78 N on the preferred comb: a 100 N grasp is
    refused with that grasp rounded down to three digits to paste, and its limit code."""
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10",
                "--max-grasp-force", "100", "--out", str(tmp_path / "x.toml"), "--json")
    assert r.returncode == 2, r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "--max-grasp-force" and error["limit"] == "strength"
    assert [a["option"] for a in error["alternatives"]] == ["--max-grasp-force 53.7"]
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10",
                "--max-grasp-force", "53.7", "--out", str(tmp_path / "y.toml"))
    assert r.returncode == 0, r.stderr


@pytest.mark.parametrize("option, value, limit", [("--kobj-range", ["1000", "20000"], "10000"),
                                                  ("--kr-over-km", ["2000"], "1000"),
                                                  ("--full-scale-force", ["2000"], "1000")])
def test_a_target_beyond_what_a_design_file_states_is_refused_by_its_option(
        tmp_path, option, value, limit):
    args = {"--kr-over-km": ["10"], "--kobj-range": ["0.5", "5"], "--full-scale-force": ["0.05"]}
    args[option] = value
    argv = ["design", *[w for k, v in args.items() for w in (k, *v)],
            "--out", str(tmp_path / "x.toml")]
    r = run_cli(*argv)
    assert r.returncode == 2 and f"argument {option}" in r.stderr and f"... {limit}" in r.stderr


def test_process_is_the_elements_cut_process_of_the_search():
    import argparse

    from tactcad.commands.design import set_keys

    args = argparse.Namespace(process="photochemical-etching", overrides=["sheet.thickness_mm=0.3"])
    assert set_keys(args) == {"element.process": "photochemical-etching",
                              "sheet.thickness_mm": 0.3}
    assert set_keys(argparse.Namespace(process=None, overrides=None)) == {}


def test_design_keeps_its_fem_results_in_the_project_it_writes(tmp_path):
    # verify run in the project right after design solves nothing again
    import argparse

    from tactcad.commands import store_from_args
    from tactcad.commands.design import project_store

    def store(out, cache=None):
        return store_from_args(argparse.Namespace(no_cache=False, cache=cache, out=str(out),
                                                  default_store=project_store)).root

    # a new folder is not made for the store: the folder it would be made in keeps it, as
    # for a design file written there (a refused design then leaves it for its rerun)
    assert store(tmp_path / "palp") == tmp_path / ".tactcad-cache"
    (tmp_path / "palp").mkdir()
    assert store(tmp_path / "palp") == tmp_path / "palp" / ".tactcad-cache"
    assert store(tmp_path / "d" / "new.toml") == tmp_path / "d" / ".tactcad-cache"
    assert store(tmp_path / "palp", cache=str(tmp_path / "c")) == tmp_path / "c"
    assert store_from_args(argparse.Namespace(no_cache=False, cache=None)).root != \
        tmp_path / "palp" / ".tactcad-cache"  # other commands: the working folder's


@pytest.mark.slow  # a whole design search
def test_a_design_stopped_after_its_solves_began_leaves_no_folder_it_made(tmp_path, monkeypatch,
                                                                         capsys):
    """A new --out DIR gets the store of the FEM solves made for it as they run; a refusal
    or a Ctrl-C after that leaves no folder behind (an existing folder is left as it was)."""
    from tactcad import cli
    from tactcad.commands import design as cmd
    from tactcad.errors import DesignError

    def stopped(result, verify, progress=None, margins=None):
        (tmp_path / "strip" / ".tactcad-cache").mkdir(parents=True, exist_ok=True)
        raise DesignError("--full-scale-force", 1.0, "a force the verify level finds carried")
    monkeypatch.setattr(cmd, "design_report", stopped)
    args = ["design", "--kr-over-km", "8", "--kobj-range", "0.2", "2", "--full-scale-force",
            "0.03", "--out", str(tmp_path / "strip")]
    assert cli.main(args) == 2
    assert not (tmp_path / "strip").exists()
    (tmp_path / "strip").mkdir()
    (tmp_path / "strip" / "notes.txt").write_text("mine", encoding="utf-8")
    assert cli.main(args) == 2
    assert (tmp_path / "strip" / "notes.txt").read_text(encoding="utf-8") == "mine"


HARDWARE = Path(__file__).resolve().parents[2] / "hardware"
JAW_TARGETS = ["--jaw", "5", "--kr-over-km", "10", "--kobj-range", "0.5", "5"]


@pytest.mark.parametrize("argv, option, least", [
    # a die's cavity depth rounded to zero below about 1e-13 N: ZeroDivisionError
    (["design", *JAW_TARGETS, "--full-scale-force", "1e-13"], "--full-scale-force", "1e-09"),
    (["die", *JAW_TARGETS, "--full-scale-force", "1e-14"], "--full-scale-force", "1e-09"),
    (["design", "--jaw", "10", "--kr-over-km", "10", "--kobj-range", "1e-20", "5",
      "--full-scale-force", "0.14"], "--kobj-range", "1e-06"),
    (["verify", "--design", str(HARDWARE / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml"),
      "--set", "die.full_scale_force_N=1e-20"], "die.full_scale_force_N", "1e-09"),
    # K_obj lost in K_m + K_obj's rounding: eq. 3 had no answer (NaN)
    (["verify", "--design", str(HARDWARE / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"),
      "--model", "closed-form", "--set", "requirements.kobj_range_N_per_mm=[1e-20,5]"],
     "requirements.kobj_range_N_per_mm", "1e-06"),
])
def test_a_force_or_stiffness_below_the_least_a_design_takes_is_refused_naming_it(
        tmp_path, argv, option, least):
    r = run_cli(*argv, *(["--out", str(tmp_path / "x")] if argv[0] != "verify" else []))
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert option in r.stderr and f"{least} " in r.stderr
    assert not (tmp_path / "x").exists()


def written_resolution(design: Path) -> float:
    """The K_obj resolution requirement (relative) the written design file verifies."""
    import tactcad
    from tactcad.studies.verification import requirements_of

    return requirements_of(tactcad.load(design).plan).kobj_resolution_rel


@pytest.mark.parametrize("ratio", ["1.05", "1.01"])
def test_a_ratio_near_one_on_the_comb_designs_where_a_candidates_k_error_spans_it(tmp_path, ratio):
    # a candidate whose K error could make its measuring element as stiff as its reference
    # stopped the search on NaN ("cannot convert float NaN to integer")
    out = tmp_path / "q9"
    r = run_cli("design", "--jaw", "10", "--kr-over-km", ratio, "--kobj-range", "0.5", "5",
                "--full-scale-force", "0.005", "--out", str(out))
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
    written = tomllib.loads((out / "q9.toml").read_text("utf-8"))
    assert written["requirements"]["kr_over_km"] == float(ratio)
    # a resolution written over 100 % is said: the lab learns the design barely reads K_obj
    coarse = written_resolution(out / "q9.toml") > 1.0
    said = "a reading does not tell a tissue from one twice or half as stiff" in r.stderr
    assert said == coarse, r.stderr


def test_a_design_that_reads_k_obj_coarser_than_its_size_is_written_with_a_warning(tmp_path):
    out = tmp_path / "q9"
    r = run_cli("design", "--jaw", "10", "--kr-over-km", "1.0000001", "--kobj-range", "0.5", "5",
                "--full-scale-force", "0.02", "--out", str(out), "--json")
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
    assert written_resolution(out / "q9.toml") > 1.0
    warned = [w for w in json.loads(r.stdout)["warnings"] if "twice or half" in w]
    assert len(warned) == 1 and "--kr-over-km" in warned[0]
    fine = run_cli("design", "--jaw", "10", "--kr-over-km", "10", "--kobj-range", "0.5", "5",
                   "--full-scale-force", "0.02", "--out", str(tmp_path / "fine"), "--json")
    assert fine.returncode == 0
    assert not [w for w in json.loads(fine.stdout)["warnings"] if "twice or half" in w]


def test_several_constructions_refusing_offer_each_ones_nearest_the_nearest_first():
    """Two constructions refuse a force: each one's own lighter force is offered with its
    ``--construction``, the larger force (the nearer the asked one) first, and the headline
    is that construction's refusal, whatever order they were tried in."""
    import argparse

    from tactcad.commands.design import constructions_refusal
    from tactcad.errors import DesignError
    from tactcad.vocabulary.binding_limits import STOP, STRENGTH

    args = argparse.Namespace(full_scale_force=1.0, kobj_range=[0.5, 5.0], columns=None)
    low = DesignError("--full-scale-force", 1.0, "at most 0.03 N", "the die's roots",
                      alternatives=[{"option": "--full-scale-force 0.03", "words": "lighter"}],
                      limit=STRENGTH)
    high = DesignError("--full-scale-force", 1.0, "at most 0.14 N", "the comb's stops",
                       alternatives=[{"option": "--full-scale-force 0.14", "words": "largest"}],
                       limit=STOP)
    for tried in ([("mems-die", "silicon die", low), ("monolithic-comb", "comb", high)],
                  [("monolithic-comb", "comb", high), ("mems-die", "silicon die", low)]):
        err = constructions_refusal(tried, args)
        assert [a["option"] for a in err.alternatives] == [
            "--construction monolithic-comb --full-scale-force 0.14",
            "--construction mems-die --full-scale-force 0.03"]
        assert err.field == "--full-scale-force" and err.limit == STOP
        assert str(err).startswith("--full-scale-force = 1.0: allowed at most 0.14 N (comb")
        assert str(err).index("comb: ") < str(err).index("silicon die: ")


def test_a_pasted_options_distance_is_its_numbers_log_ratio_to_the_asked_ones():
    import argparse
    import math

    from tactcad.commands.design import paste_distance

    args = argparse.Namespace(full_scale_force=1.0, kobj_range=[0.5, 5.0], columns=None,
                              jaw="10")
    assert paste_distance("--full-scale-force 0.14", args) < \
        paste_distance("--full-scale-force 0.03", args)
    assert paste_distance("--construction mems-die --kobj-range 1 5", args) == \
        pytest.approx(math.log(2))
    assert paste_distance("--jaw 12", args) == math.inf  # a jaw is no number
    assert paste_distance("--columns 5", args) == math.inf  # the columns were not asked


@pytest.mark.slow  # a comb search and a die plan, then the pasted comb designed
def test_auto_refused_by_comb_and_die_leads_with_the_force_that_designs(tmp_path):
    """The 10 mm jaw at 1 N: the comb carries 0.14 N, the die 0.03 N; the comb's force is
    offered first with --construction monolithic-comb (the die's led, with no --construction),
    and pasted, it designs."""
    argv = ["design", "--jaw", "10", "--kr-over-km", "10", "--kobj-range", "0.5", "5",
            "--out", str(tmp_path / "q.toml")]
    r = run_cli(*argv, "--full-scale-force", "1", "--json")
    assert r.returncode == 2 and not (tmp_path / "q.toml").exists()
    error = json.loads(r.stdout)["error"]
    options = [a["option"].split() for a in error["alternatives"]]
    assert [o[:2] for o in options] == [["--construction", "monolithic-comb"],
                                        ["--construction", "mems-die"]]
    forces = [float(o[o.index("--full-scale-force") + 1]) for o in options]
    assert forces == sorted(forces, reverse=True)
    assert f"{forces[0]:g}" in error["allowed"]
    r = run_cli(*argv, *options[0], "--json")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["construction"] == "monolithic-comb"


def test_a_check_groups_undecided_result_is_counted_undecided_not_passed():
    from tactcad.checks.check_result import CheckResult
    from tactcad.commands.design import check_group_summary

    results = [CheckResult("requirement", "kr_over_km", True, "pass"),
               CheckResult("requirement", "footprint_mm", True, "undecided", undecided=True),
               CheckResult("requirement", "full_scale_force_N", False, "fail"),
               CheckResult("requirement", "k_tolerance_rel", True, "not stated", info=True)]
    summary = check_group_summary(results)
    assert summary["passed"] == 1 and summary["info"] == 1  # as check counts them
    assert summary["undecided"] == [results[1].line()]
    assert summary["failed"] == [results[2].line()]


def test_design_reports_the_requirements_verify_leaves_undecided_as_undecided(tmp_path):
    """A comb whose rated force lies within the closed form's error of its fatigue limit:
    design's requirements check counts it undecided, as verify and check do for the file it
    wrote, and the design is written (an undecided row fails nothing)."""
    out = tmp_path / "a.toml"
    r = run_cli("design", "--jaw", "10", "--construction", "monolithic-comb", "--kr-over-km",
                "18.423", "--kobj-range", "0.3441", "1.4272", "--full-scale-force",
                "0.0681", "--columns", "5", "--material", "Ti-6Al-4V-annealed", "--out",
                str(out), "--json")
    assert r.returncode == 0, r.stderr
    designed = json.loads(r.stdout)["checks"]["requirements"]
    v = run_cli("verify", "--design", str(out), "--model", "closed-form", "--json")
    matrix = json.loads(v.stdout)["matrix"]
    open_ = sorted(x["requirement"] for x in matrix if x["verdict"] == "undecided")
    assert open_, "the case no longer leaves a requirement undecided"
    assert sorted(line.split()[2] for line in designed["undecided"]) == open_
    assert designed["passed"] == sum(x["verdict"] == "pass" for x in matrix)
    assert not designed["failed"]


@pytest.mark.slow  # a whole comb search
def test_a_missed_kobj_accuracy_names_the_accuracy_asked_and_reached_not_a_force(tmp_path):
    """A --kobj-accuracy the comb cannot meet: the refusal names the option, the accuracy
    asked and the best reached (relative and in %), and pastes one that the same design
    meets; it never names a force."""
    out = tmp_path / "insert.toml"
    ask = [*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10", "--out", str(out)]
    r = run_cli(*ask, "--kobj-accuracy", "0.01", "--json")
    assert r.returncode == 2 and not out.exists(), r.stderr
    err = json.loads(r.stdout)["error"]
    assert err["field"] == "--kobj-accuracy"
    assert "asked 0.01 (1 %)" in err["message"], err["message"]
    assert " N " not in err["message"] and "at most" not in err["message"]
    reached = float(err["message"].split("reaches is ")[1].split()[0])
    assert reached > 0.01
    assert f"({100 * reached:.3g} %)" in err["message"]
    paste = err["alternatives"][0]["option"].split()
    assert paste[0] == "--kobj-accuracy" and float(paste[1]) >= reached
    r = run_cli(*ask, *paste, "--json")
    assert r.returncode == 0, r.stdout + r.stderr


def test_a_missed_kobj_accuracy_in_a_stacked_design_says_what_it_reaches():
    """The stacked design's report on a failed kobj_accuracy_rel names the accuracy asked,
    the best reached in % and the option to paste."""
    from tactcad.commands.design import verification_lines

    lines = verification_lines({"asked": "auto", "level": "closed-form", "passed": False,
                                "requirements": [{"requirement": "kobj_accuracy_rel",
                                                  "verdict": "fail", "margin_rel": -0.5,
                                                  "decided_by": "closed-form",
                                                  "target": 0.01, "predicted": 0.0234}]})
    text = "\n".join(lines)
    assert "asked 0.01 (1 %)" in text and "0.0234 (2.34 %)" in text
    assert "to paste: --kobj-accuracy 0.024" in text


def test_design_columns_name_each_products_own_range(tmp_path):
    """--columns is held to the range of the product asked for, named with it: a comb's and a
    stacked array's are the grid's (array.columns), a die's its own, and the option takes
    the widest of them, so a die of more columns than a comb takes is not refused."""
    from tactcad.commands.design import MIN_PAIRED_COLUMNS
    from tactcad.design.array_plan import COLUMNS_RANGE
    from tactcad.products.silicon_die.design.mems_die import COLUMNS_RANGE as DIE_COLUMNS

    lo, hi = COLUMNS_RANGE
    r = run_cli(*GRASPER_CASE[:-2], "--full-scale-force", "0.05", "--columns", str(hi + 1),
                "--jaw", "10", "--construction", "monolithic-comb", "--out",
                str(tmp_path / "c.toml"))
    assert r.returncode == 2 and not (tmp_path / "c.toml").exists()
    # the 10 mm jaw's pocket binds first: its count is the range stated, the grid's the reason
    assert (f"--columns = {hi + 1}: allowed {lo} ... 6 for a monolithic comb in this jaw's "
            f"pocket (the pocket holds no longer comb; the grid's range (array.columns) is "
            f"{lo} ... {hi})") in r.stderr, r.stderr
    r = run_cli("design", "--kr-over-km", "10", "--kobj-range", "0.5", "5",
                "--full-scale-force", "0.05", "--columns", str(hi + 1), "--out",
                str(tmp_path / "s.toml"), cwd=tmp_path)
    assert r.returncode == 2 and not (tmp_path / "s.toml").exists()
    assert (f"--columns = {hi + 1}: allowed {MIN_PAIRED_COLUMNS} ... {hi} for a stacked array"
            in r.stderr), r.stderr
    assert f"--columns {hi}" in r.stderr  # the nearest to paste
    r = run_cli(*JAW_TARGETS, "--full-scale-force", "0.001", "--columns", str(hi + 8),
                "--construction", "mems-die", "--out", str(tmp_path / "d.toml"), cwd=tmp_path)
    assert "--columns" not in r.stderr, r.stderr  # a die of 20 columns is the die's to judge
    r = run_cli(*GRASPER_CASE[:-2], "--full-scale-force", "0.05", "--columns",
                str(DIE_COLUMNS[1] + 1), "--out", str(tmp_path / "x.toml"))
    assert r.returncode == 2 and f"1 ... {DIE_COLUMNS[1]}" in r.stderr, r.stderr
    assert "Traceback" not in r.stderr


def test_design_one_column_on_a_stacked_array_names_the_columns_and_why(tmp_path):
    """A stacked array of one column: refused as --columns (each row pairs a reference with
    a measuring element), not as an unrelated target."""
    from tactcad.commands.design import MIN_PAIRED_COLUMNS

    r = run_cli("design", "--kr-over-km", "10", "--kobj-range", "0.5", "5",
                "--full-scale-force", "0.05", "--columns", "1", "--out",
                str(tmp_path / "x.toml"), "--json", cwd=tmp_path)
    assert r.returncode == 2 and not (tmp_path / "x.toml").exists()
    err = json.loads(r.stdout)["error"]
    assert err["field"] == "--columns" and err["value"] == 1, err
    assert err["allowed"].startswith(f"{MIN_PAIRED_COLUMNS} ... "), err
    assert "measure" in err["message"]
    assert err["alternatives"][0]["option"] == f"--columns {MIN_PAIRED_COLUMNS}"


def test_a_written_design_keeps_lengths_to_a_nanometre_not_float_noise():
    """A length the search computes in steps (43 x 0.001 mm) is written 0.043, not with the
    float's noise; what is no length (a force) is written as it is."""
    from tactcad.commands.design import WRITTEN_MM_PLACES, design_text

    noisy = 43 * 0.001
    assert repr(noisy) != "0.043"  # the noise the file must not show
    force = 0.1 + 0.2
    tables = {"comb": {"stop_gaps_mm": [noisy, 0.02], "web_thicknesses_mm": [noisy]},
              "array": {"pitch_mm": 4 * 1.2, "columns": 6},
              "requirements": {"full_scale_force_N": force},
              "assumptions": {"comb.stop_gaps_mm": "why"}}
    text = design_text("# header\n", tables)
    assert text.startswith("# header\n") and repr(noisy) not in text
    written = tomllib.loads(text)
    assert written["comb"]["stop_gaps_mm"] == [round(noisy, WRITTEN_MM_PLACES), 0.02]
    assert written["comb"]["web_thicknesses_mm"] == [round(noisy, WRITTEN_MM_PLACES)]
    assert written["array"] == {"pitch_mm": round(4 * 1.2, WRITTEN_MM_PLACES), "columns": 6}
    assert written["requirements"]["full_scale_force_N"] == force  # not a length: as computed
    assert tables["comb"]["stop_gaps_mm"][0] == noisy  # the tables themselves untouched


def test_a_jaw_designs_file_and_report_carry_no_float_noise(tmp_path):
    """Every length of the grasper case's written design and its report's webs and stop
    gaps are held to the written resolution."""
    from tactcad.commands.design import WRITTEN_MM_PLACES

    out = tmp_path / "insert.toml"
    r = run_cli(*GRASPER_CASE, "--full-scale-force", "0.05", "--jaw", "10", "--out", str(out),
                "--json")
    assert r.returncode == 0, r.stderr
    report = json.loads(r.stdout)
    for key in ("webs_mm", "stop_gaps_mm", "arms_mm"):
        assert all(v == round(v, WRITTEN_MM_PLACES) for v in report[key]), report[key]

    def lengths(value, key=""):
        if isinstance(value, dict):
            for k, v in value.items():
                yield from lengths(v, k)
        elif isinstance(value, list):
            for v in value:
                yield from lengths(v, key)
        elif isinstance(value, float) and key.endswith("_mm"):
            yield value

    written = list(lengths(tomllib.loads(out.read_text(encoding="utf-8"))))
    assert written and all(v == round(v, WRITTEN_MM_PLACES) for v in written)


def test_a_jaw_reports_each_kind_of_element_with_its_own_arm_web_and_stop_gap():
    """The report's arms, webs and stop gaps are paired by position in element order: the
    stiff references' short arm with their thick web, not the webs sorted apart."""
    from tactcad.commands.design import distinct_elements_lengths

    d = {"arms": {"lengths_mm": [2.0, 2.0, 4.0, 4.0]},
         "comb": {"web_thicknesses_mm": [0.116, 0.116, 0.084, 0.084],
                  "stop_gaps_mm": [0.02, 0.02, 0.033, 0.033]}}
    assert distinct_elements_lengths(d) == {"arms_mm": [2.0, 4.0], "webs_mm": [0.116, 0.084],
                                            "stop_gaps_mm": [0.02, 0.033]}


def test_a_refusal_in_a_5_mm_jaw_says_each_thing_once(tmp_path):
    """Only the silicon die fits a 5 mm jaw and refuses a 0.05 N rating: the refusal named
    the option, the value and the allowed rating twice and the die's failure probability
    once per loading; now each once, the comb's misfit after the die's reasons."""
    r = run_cli("design", "--jaw", "5", "--kr-over-km", "5", "--kobj-range", "0.2", "1.5",
                "--full-scale-force", "0.05", "--columns", "6", "--out", "die", cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    line = r.stderr.split("\n  to paste:")[0]  # the refusal, each construction on its line
    assert line.startswith("tactcad: error: --full-scale-force = 0.05: allowed at most ")
    for words in ("--full-scale-force = 0.05", "allowed at most", "silicon die",
                  "failure probability", "Weibull pair"):
        assert line.count(words) == 1, (words, line)
    assert "every beam at its rated force and every beam on its deepest stop" in line
    assert line.index("silicon die: past") < line.index("monolithic-comb: does not fit")
    assert line.endswith(")") and "to paste:" in r.stderr
    # one line per construction, as the refusal of the constructions that do not fit
    said = line.splitlines()
    assert said[0].endswith("(each against this jaw:") and len(said) == 3, said
    assert said[1].startswith("  silicon die: past") and "monolithic-comb" not in said[1]
    assert said[2].startswith("  monolithic-comb: does not fit")


def test_several_constructions_refusing_one_option_name_it_and_its_value_once():
    import argparse

    from tactcad.commands.design import constructions_refusal
    from tactcad.errors import DesignError

    args = argparse.Namespace(full_scale_force=1.0, kobj_range=[0.5, 5.0], columns=None)
    low = DesignError("--full-scale-force", 1.0, "at most 0.03 N", "the die's roots",
                      alternatives=[{"option": "--full-scale-force 0.03", "words": "lighter"}])
    high = DesignError("--full-scale-force", 1.0, "at most 0.14 N", "the comb's stops",
                       alternatives=[{"option": "--full-scale-force 0.14", "words": "largest"}])
    text = str(constructions_refusal([("mems-die", "silicon die", low),
                                      ("monolithic-comb", "comb", high)], args))
    assert text.count("--full-scale-force = 1.0") == 1 and text.count("0.14 N") == 1
    assert "comb: the comb's stops" in text and "silicon die: allowed at most 0.03 N" in text
    assert text.splitlines()[1:] == ["  comb: the comb's stops",
                                     "  silicon die: allowed at most 0.03 N (the die's roots))"]


def test_a_die_too_long_for_the_pocket_pastes_the_columns_and_the_rating_they_take(tmp_path):
    """50 columns do not fit the 5 mm jaw's pocket: the refusal pasted `--columns 27` alone,
    which the die then refused for its rating. The paste now names every target that binds
    at the columns offered, and pasting it designs."""
    from tactcad.vocabulary.rounding import round_down

    asked = ["design", "--kr-over-km", "5", "--kobj-range", "0.2", "2", "--full-scale-force",
             "0.005", "--jaw", "5", "--construction", "mems-die", "--columns", "50", "--out", "d"]
    r = run_cli(*asked, "--json", cwd=tmp_path)
    assert r.returncode == 2 and not (tmp_path / "d").exists(), r.stdout + r.stderr
    pasted = json.loads(r.stdout)["error"]["alternatives"][0]["option"].split()
    assert pasted[:2] == ["--columns", "27"], pasted
    assert "--full-scale-force" in pasted, pasted
    force = float(pasted[pasted.index("--full-scale-force") + 1])
    assert force < 0.005 and force == round_down(force, 3)
    r = run_cli(*asked, *pasted, "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert json.loads(r.stdout)["die"]["columns"] == 27


def test_a_pasted_die_change_sets_only_the_targets_it_names():
    from tactcad.commands.design import pasted_targets
    from tactcad.studies.inverse_design import Targets

    asked = Targets(5.0, (0.2, 2.0), 0.005)
    changed, options = pasted_targets("--kobj-range 0.3 3 --full-scale-force 0.004", asked)
    assert changed == Targets(5.0, (0.3, 3.0), 0.004)
    assert options == {"--kobj-range": "0.3 3", "--full-scale-force": "0.004"}
    assert pasted_targets("--jaw 10", asked) is None  # not a target: no die of it to plan


def test_a_grade_whose_comb_carries_no_force_pastes_another_grade(tmp_path):
    """design --jaw in 6061-T6 at K_r/K_m 20, K_obj 5 ... 50 N/mm: no comb of that grade
    carries a force at any column count; the refusal keeps its force option and offers
    another grade with the force its comb of the same columns carries, which designs."""
    common = ["design", "--jaw", "10", "--construction", "monolithic-comb", "--kr-over-km",
              "20", "--kobj-range", "5", "50", "--columns", "2", "--json"]
    r = run_cli(*common, "--material", "6061-T6", "--full-scale-force", "2", "--out",
                str(tmp_path / "x.toml"))
    assert r.returncode == 2 and not list(tmp_path.iterdir())
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "--full-scale-force" and "none to paste" not in error["message"]
    offered = [a["option"] for a in error["alternatives"]]
    assert len(offered) == 1 and offered[0].startswith("--material ")
    assert "6061-T6" not in offered[0] and f"nearest: {offered[0]}" in error["message"]
    r = run_cli(*common, *offered[0].split(), "--out", str(tmp_path / "pasted.toml"))
    assert r.returncode == 0, r.stdout + r.stderr
    written = tomllib.loads((tmp_path / "pasted.toml").read_text(encoding="utf-8"))
    assert written["material"]["grade"] == offered[0].split()[1]


JAW7 = ("[grasper_jaw]\nshaft_diameter_mm = 7.0\nwidth_mm = 5.5\nlength_mm = 16.0\n"
        "thickness_mm = 2.1\nopposing_jaw_mm = 2.1\npin_diameter_mm = 1.5\n"
        "pin_inset_mm = 1.1\nopening_angle_deg = 45.0\n")


def test_the_shaft_refusal_names_the_combs_need_apart_from_the_jaws_value(tmp_path):
    """A 7 mm jaw 5.5 mm wide: the comb needs a 5.5 mm thick jaw, once said "the closed jaws
    (5.5 mm (thickness_mm) + 2.1 mm ...)", read as the jaw's own size (its width is 5.5 mm);
    each size is now the comb's need or the jaw's value, by name."""
    jaw = tmp_path / "jaw7.toml"
    jaw.write_text(JAW7, encoding="utf-8")
    r = run_cli("design", "--jaw", str(jaw), "--construction", "monolithic-comb",
                "--kr-over-km", "10", "--kobj-range", "0.5", "5", "--full-scale-force", "0.01",
                "--columns", "4", "--material", "Ti-6Al-4V-annealed", "--out",
                str(tmp_path / "comb7"), "--json")
    assert r.returncode == 2, r.stderr
    message = json.loads(r.stdout)["error"]["message"]
    assert "the closed jaws (5.5 mm (thickness_mm)" not in message
    assert ("no jaw of the 7 mm shaft holds it: it needs closed jaws 5.5 mm thick "
            "(thickness_mm; this jaw's 2.1 mm) + 2.1 mm (opposing_jaw_mm, this jaw's)") in message
    assert "wide (width_mm; this jaw's 5.5 mm)" in message
    assert "(shaft_diameter_mm; this jaw's 7 mm)" in message


#: a lab's 7 mm grasper jaw (the new-lab review's): it holds no comb, a silicon die designs in it
LAB7_JAW = ("[grasper_jaw]\nshaft_diameter_mm = 7.0\nwidth_mm = 4.5\nlength_mm = 26.0\n"
            "thickness_mm = 2.6\nopposing_jaw_mm = 2.6\npin_diameter_mm = 1.5\n"
            "pin_inset_mm = 1.6\nopening_angle_deg = 40.0\n")
LAB7_TARGETS = ["--kr-over-km", "8", "--kobj-range", "0.2", "4", "--full-scale-force", "0.5"]


def test_a_jaw_file_with_a_metals_material_pastes_the_die_that_keeps_the_labs_jaw(tmp_path):
    """``--material`` keeps the die from being tried; the refusal still offers the die in the
    lab's own jaw, naming --material to leave out, and that paste designs; the refusal's
    lines open and close its parenthesis once."""
    jaw = tmp_path / "jaw7.toml"
    jaw.write_text(LAB7_JAW, encoding="utf-8")
    asked = ["design", "--jaw", str(jaw), *LAB7_TARGETS, "--out", str(tmp_path / "lab7")]
    r = run_cli(*asked, "--material", "17-4PH-H900", "--json")
    assert r.returncode == 2, r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "--jaw"
    die = error["alternatives"][0]
    assert die["option"].startswith("--construction mems-die") and \
        die["without"] == ["--material"], error["alternatives"]
    assert "--material 17-4PH-H900 left out" in die["words"]
    assert "--jaw 10" in [a["option"] for a in error["alternatives"]]
    message = error["message"]
    assert "(\n" not in message and "))" not in message.splitlines()[-1], message
    assert message.count("(") == message.count(")"), message
    assert "without --material the die designs in this jaw" in message
    r = run_cli(*asked, *die["option"].split(), "--quiet")  # the paste, without --material
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "lab7" / "lab7.toml").exists()


def test_a_bad_jaw_file_is_refused_before_an_existing_output_folder(tmp_path):
    """The inputs first: a jaw file's bad key is the refusal, not the folder it would go
    to (which was said alone, and the jaw's error only once that was mended)."""
    jaw = tmp_path / "j10.toml"
    jaw.write_text(LAB7_JAW.replace("length_mm = 26.0", "length_mm = 3.0"), encoding="utf-8")
    folder = tmp_path / "o_x"
    folder.mkdir()
    (folder / "o_x.toml").write_text("[design]\nname = \"o_x\"\n", encoding="utf-8")
    r = run_cli("design", "--jaw", str(jaw), *LAB7_TARGETS, "--out", str(folder), "--json")
    assert r.returncode == 2, r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "grasper_jaw.length_mm" and error["value"] == 3.0, error
    r = run_cli("design", "--jaw", str(jaw.with_name("none.toml")), *LAB7_TARGETS, "--out",
                str(folder), "--json")
    assert json.loads(r.stdout)["error"]["field"] == "--jaw"


#: the new-lab review's comb for the 10 mm jaw, whose 7.8 mm arms lie past the closed
#: form's fitted arm/arm height (0.99 ... 4)
LONG_ARMED_COMB = ["design", "--jaw", "10", "--construction", "monolithic-comb",
                   "--kr-over-km", "12.1472", "--kobj-range", "0.395847", "4.17276",
                   "--full-scale-force", "0.135702", "--columns", "3", "--material",
                   "17-4PH-H900"]


@pytest.mark.slow  # a whole comb search through the command line
def test_a_jaw_designs_range_warning_is_said_in_text_as_in_json_once(tmp_path):
    """The warning --json lists (and readout, verify, strength say of the written file) is
    said once on stderr by the text run that writes the file; --quiet keeps it back."""
    said = "closed-form stiffness correction used outside its fitted range"
    r = run_cli(*LONG_ARMED_COMB, "--out", str(tmp_path / "a.toml"), "--json")
    assert r.returncode == 0, r.stderr
    assert any(said in w for w in json.loads(r.stdout)["warnings"]), r.stdout[-2000:]
    r = run_cli(*LONG_ARMED_COMB, "--out", str(tmp_path / "b.toml"))
    assert r.returncode == 0, r.stderr
    lines = [x for x in r.stderr.splitlines() if said in x]
    assert len(lines) == 1 and lines[0].startswith("tactcad: warning: "), r.stderr
    r = run_cli(*LONG_ARMED_COMB, "--out", str(tmp_path / "c.toml"), "--quiet")
    assert r.returncode == 0 and said not in r.stderr, r.stderr
