"""``tactcad budget``: both shipped examples, a non-paper design, the options and their refusals."""

import json
from pathlib import Path

import pytest
from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
TI = str(ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")
MACRO = str(ROOT / "hardware" / "macro_array" / "macro_array.toml")
SOURCES = {"readout_noise", "thermal_zero", "thermal_span", "manufacturing_tolerance",
           "crosstalk", "tissue_coupling", "gauge_model", "calibration", "tip_coplanarity",
           "gauge_creep", "gauge_hysteresis"}


@pytest.mark.parametrize("design", [MACRO, TI])
def test_both_examples_have_every_source_at_every_kobj(design):
    r = run_cli("budget", "--design", design, "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["units"] and len(d["K_obj_N_per_mm"]) == 7
    for u in d["units"]:
        assert set(u["sources"]) - set(d["deprecated_keys"]) == SOURCES
        assert all(len(v["after_rel"]) == 7 for v in u["sources"].values())
        # a unit alone resolving K_obj worse than required reads none there (as verify's
        # readable range judges): its sums are unreadable, None
        assert len(u["reads_kobj"]) == 7
        assert all((x is not None and x > 0) == reads
                   for x, reads in zip(u["rss_rel"], u["reads_kobj"]))
    assert len(d["array"]["dominant"]) == 7
    assert all(x is not None and x > 0 for x in d["array"]["rss_rel"])


def test_force_and_temperature_step_reach_the_budget():
    base = json.loads(run_cli("budget", "--design", TI, "--json", "--delta-T-K", "2").stdout)
    more = json.loads(run_cli("budget", "--design", TI, "--json", "--delta-T-K", "4",
                              "--force-N", "0.05").stdout)
    assert base["force_N"] == 0.1 and more["force_N"] == 0.05 and more["delta_T_K"] == 4
    a, b = base["units"][0]["sources"], more["units"][0]["sources"]
    # the span scales with the step; the zero with the step over the force (to first order:
    # the thermal model changes R exactly)
    assert b["thermal_span"]["after_rel"][0] == pytest.approx(
        2 * a["thermal_span"]["after_rel"][0], rel=1e-2)
    assert b["thermal_zero"]["after_rel"][0] == pytest.approx(
        4 * a["thermal_zero"]["after_rel"][0], rel=2e-2)


def test_a_non_paper_design_of_four_columns_and_the_text_output(tmp_path):
    out = tmp_path / "budget.md"
    r = run_cli("budget", "--design", TI, "--set", "array.columns=4", "--set",
                "arms.lengths_mm=[19.605,6.196,19.605,19.605,19.605,6.196,19.605,19.605]",
                "--out", str(out), "--points", "5")
    assert r.returncode == 0, r.stderr
    assert "| RSS |" in r.stdout and "tissue coupling" in r.stdout and "N/mm" in r.stdout
    assert out.read_text().strip() == r.stdout.strip()
    assert r.stdout.count("\nunit ") == 6  # two rows, three measuring elements each


@pytest.mark.parametrize("option, value, words", [("--delta-T-K", "150", "0 ... 100 (K)"),
                                                   ("--force-N", "0", ">0 ... 1000 (N)"),
                                                   ("--points", "1", "2 ... 101"),
                                                   ("--out", "b.txt", ".json or .md")])
def test_bad_options_name_the_option_the_value_and_the_range(option, value, words):
    r = run_cli("budget", "--design", TI, option, value, "--json")
    assert r.returncode == 2
    msg = json.loads(r.stdout)["error"]["message"]
    assert option in msg and value in msg and words in msg


def test_a_calibration_file_of_another_design_is_refused(tmp_path):
    cal = tmp_path / "cal.csv"
    cal.write_text("element,run,z_um,force_N,signal_V\n" + "".join(
        f"9,1,{z},{0.01 * z:.4f},{-0.001 * z:.4f}\n" for z in (0, 25, 50, 75)))
    r = run_cli("budget", "--design", TI, "--calibration", str(cal), "--json")
    assert r.returncode != 0
    msg = json.loads(r.stdout)["error"]["message"]
    assert "--calibration" in msg and "element 9" in msg and "1 ... 6" in msg


@pytest.mark.slow  # a whole chain through the command line or an export
def test_verify_reports_the_budget_and_judges_a_stated_accuracy():
    r = run_cli("verify", "--design", TI, "--model", "closed-form", "--set",
                "requirements.kobj_accuracy_rel=0.001", "--json")
    d = json.loads(r.stdout)
    assert r.returncode == 1  # 0.1 % is beyond what the budget allows
    rec = [x for x in d["matrix"] if x["requirement"] == "kobj_accuracy_rel"]
    assert rec and rec[0]["verdict"] == "fail"
    assert d["kobj_budget"]["units"] and d["kobj_budget"]["model"] == "closed-form"
    text = run_cli("verify", "--design", TI, "--model", "closed-form").stdout
    assert "K_obj error budget, array" in text and "| RSS |" in text
    assert "kobj_accuracy_rel" not in text  # not stated: reported, not judged


def test_a_material_of_unknown_cte_is_named_by_budget_and_reported_by_verify(tmp_path):
    import re
    import shutil

    text = Path(TI).read_text(encoding="utf-8")
    text = re.sub(r"\[material\][^\[]*", "[material]\nname = \"custom titanium\"\n"
                  "youngs_modulus_MPa = 110000.0\npoisson_ratio = 0.34\nyield_strength_MPa = "
                  "880.0\nfatigue_strength_MPa = 500.0\ndensity_g_per_cm3 = 4.43\n\n", text, count=1)
    design = tmp_path / "custom.toml"
    design.write_text(text, encoding="utf-8")
    for name in ("rigs.toml", "scenes.toml"):
        shutil.copy(Path(TI).parent / name, tmp_path / name)
    r = run_cli("budget", "--design", str(design), "--json")
    assert r.returncode != 0
    assert "readout.substrate_cte_ppm_per_K" in json.loads(r.stdout)["error"]["message"]
    v = run_cli("verify", "--design", str(design), "--model", "closed-form")
    assert v.returncode == 0, v.stderr
    assert "K_obj error budget not evaluated: readout.substrate_cte_ppm_per_K" in v.stdout


COMB = str(ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")


def test_a_force_past_the_rating_or_an_overload_limit_is_warned_in_the_text_and_json():
    from tactcad.design.array_plan import load_design
    from tactcad.studies.verification import requirements_of

    rated = requirements_of(load_design(COMB)).full_scale_force_N

    def warned(force):
        r = run_cli("budget", "--design", COMB, "--force-N", force, "--json")
        assert r.returncode == 0, r.stderr
        return json.loads(r.stdout)["warnings"]

    assert warned(f"{rated:g}") == []
    past = warned(f"{1.2 * rated:g}")
    assert len(past) == 1 and past[0].startswith(f"--force-N = {1.2 * rated:g} N")
    assert f"rated full-scale force {rated:g} N" in past[0] and "overload" not in past[0]
    broken = warned("1000")
    assert len(broken) == 1 and "--force-N = 1000 N" in broken[0]
    assert "overload limit" in broken[0] and "damaged" in broken[0]
    text = run_cli("budget", "--design", COMB, "--force-N", "1000")
    assert "warning: --force-N = 1000 N" in text.stdout and "warning: --force-N" in text.stderr


def test_a_combs_zero_terms_read_0_not_minus_0(tmp_path):
    # a comb of one material has no thermal zero: its terms are -0.0, printed "-0 %"
    made = run_cli("design", "--kr-over-km", "8", "--kobj-range", "0.4", "4",
                   "--full-scale-force", "0.06", "--material", "17-4PH-H900", "--columns", "5",
                   "--jaw", "10", "--out", "c", "--quiet", cwd=tmp_path)
    assert made.returncode == 0, made.stdout + made.stderr
    r = run_cli("budget", cwd=tmp_path / "c")
    assert r.returncode == 0, r.stderr
    assert "| thermal zero | 0 % |" in r.stdout and "-0 %" not in r.stdout


def test_the_texts_notes_read_as_words_not_python_values():
    """The text's notes say yes / no / none and round their numbers; --json keeps the
    values (True, null, every digit)."""
    import re

    design = str(Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3"
                 / "ti_array_2x3.toml")
    text = run_cli("budget", "--design", design)
    assert text.returncode == 0, text.stderr
    notes = [line for line in text.stdout.splitlines() if re.match(r"  [a-z_]+: ", line)]
    assert notes
    assert not [n for n in notes if re.search(r": (None|True|False)$", n)]
    assert not [n for n in notes if re.search(r"\d\.\d{6,}", n)]
    doc = json.loads(run_cli("budget", "--design", design, "--json").stdout)
    assert doc["notes"]["calibration_gauge_fits"] is True



def command_help(command: str) -> str:
    """``tactcad COMMAND --help``'s text, from the command's own parser."""
    import argparse

    from tactcad import cli

    sub = next(a for a in cli.build_parser([command])._actions
               if isinstance(a, argparse._SubParsersAction))
    return sub.choices[command].format_help()


def test_force_and_step_are_named_with_their_units_as_grasps_force_N():
    """budget's force and temperature step carry their units in their names, as grasp's
    --force-N does (design --force and new --force mean "overwrite")."""
    assert "--force-N FORCE_N" in command_help("grasp")
    helptext = command_help("budget")
    assert "--force-N FORCE_N" in helptext and "--delta-T-K DELTA_T_K" in helptext


@pytest.mark.parametrize("old, new, value", [("--force", "--force-N", "0.05"),
                                             ("--delta-T", "--delta-T-K", "4")])
def test_the_earlier_names_still_work_hidden_and_said_renamed_on_one_line(old, new, value):
    """--force and --delta-T, the earlier names: not in --help, still taken (the same
    budget as the new name), and said renamed, naming the new one: one line on stderr,
    none with --quiet, and with --json an entry of the JSON's ``warnings`` (stderr empty,
    so stdout and stderr together are the JSON alone); no Python warning, no traceback."""
    import re

    assert not re.search(rf"{re.escape(old)}(?![-\w])", command_help("budget"))
    by_new = run_cli("budget", "--design", TI, "--points", "2", new, value, "--json")
    by_old = run_cli("budget", "--design", TI, "--points", "2", old, value, "--json")
    assert by_old.returncode == 0 == by_new.returncode, by_old.stdout + by_old.stderr
    said = json.loads(by_old.stdout)
    renamed = [w for w in said["warnings"] if "renamed" in w]
    assert len(renamed) == 1 and old in renamed[0] and new in renamed[0], said["warnings"]
    assert {**said, "warnings": [w for w in said["warnings"] if w not in renamed]} == \
        json.loads(by_new.stdout)
    assert by_new.stderr == "" == by_old.stderr, by_old.stderr
    text = run_cli("budget", "--design", TI, "--points", "2", old, value)
    lines = [line for line in text.stderr.splitlines() if "renamed" in line]
    assert text.returncode == 0 and len(lines) == 1, text.stderr  # beside the progress line
    assert old in lines[0] and new in lines[0] and "renamed" in lines[0]
    assert lines[0].startswith("tactcad: warning: ")
    assert "Traceback" not in text.stderr and "DeprecationWarning" not in text.stderr
    # given twice: still one line; with --quiet none; a bad value refused in its own name
    twice = run_cli("budget", "--design", TI, "--points", "2", old, value, old, value)
    assert twice.returncode == 0 and twice.stderr.count("renamed") == 1, twice.stderr
    quiet = run_cli("budget", "--design", TI, "--points", "2", old, value, "--quiet")
    assert quiet.returncode == 0 and quiet.stderr == "", quiet.stderr
    bad = run_cli("budget", "--design", TI, old, "-1", "--json")
    assert bad.returncode == 2 and old in json.loads(bad.stdout)["error"]["message"]


def test_a_combs_crosstalk_term_has_a_neutral_key_and_the_old_one_deprecated():
    """A monolithic comb has no stack: its crosstalk term is keyed ``crosstalk`` (and its
    notes ``crosstalk_N_per_N``, ``crosstalk_basis``). The old ``stack_crosstalk`` keys are
    still written, the same values, listed in ``deprecated_keys`` (old -> new), and no sum
    counts the term twice."""
    import math

    r = run_cli("budget", "--design", COMB, "--points", "3", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["deprecated_keys"] == {"stack_crosstalk": "crosstalk",
                                    "stack_crosstalk_N_per_N": "crosstalk_N_per_N",
                                    "stack_crosstalk_basis": "crosstalk_basis"}
    keys = [s["key"] for s in d["sources"]]
    assert "crosstalk" in keys and "stack_crosstalk" not in keys
    assert "(comb-beam)" in d["notes"]["crosstalk_basis"] and d["notes"]["crosstalk_N_per_N"] > 0
    for old, new in d["deprecated_keys"].items():
        if old in d["notes"]:
            assert d["notes"][old] == d["notes"][new]
    for u in d["units"]:
        term = u["sources"]["crosstalk"]
        assert min(term["before_rel"]) > 0 and u["sources"]["stack_crosstalk"] == term
        after = [u["sources"][k]["after_rel"] for k in keys]
        for i, rss in enumerate(u["rss_rel"]):  # every source once: crosstalk not twice
            if rss is not None:
                assert rss == pytest.approx(math.sqrt(sum(a[i] ** 2 for a in after)), rel=1e-5)
                assert u["worst_case_rel"][i] == pytest.approx(
                    sum(abs(a[i]) for a in after), rel=1e-5)
        assert "stack_crosstalk" not in u["dominant"]
    text = run_cli("budget", "--design", COMB, "--points", "3").stdout
    assert "| crosstalk (comb-beam) |" in text and "stack crosstalk" not in text
    assert "  crosstalk_basis: " in text and "stack_crosstalk" not in text


@pytest.mark.parametrize("design, level, other", [(COMB, "comb-beam", "stack"),
                                                  (TI, "stack-timoshenko", "comb")])
def test_the_crosstalk_term_is_named_for_the_constructions_own_level(design, level, other):
    """A comb's crosstalk row, its ``sources`` words and a dominant crosstalk read "crosstalk
    (comb-beam)", as ``tactcad crosstalk`` names the model; the stacked array's its own."""
    from tactcad.commands.budget import render
    from tactcad.in_use.kobj_budget import SOURCES

    d = json.loads(run_cli("budget", "--design", design, "--points", "2", "--json").stdout)
    words = {s["key"]: s["words"] for s in d["sources"]}
    assert words["crosstalk"] == f"crosstalk ({level})"
    assert not any(other in w for w in words.values())
    assert {k: w for k, w in words.items() if k != "crosstalk"} == {
        s.key: s.words for s in SOURCES if s.key != "crosstalk"}
    text = run_cli("budget", "--design", design, "--points", "2").stdout
    assert f"| crosstalk ({level}) |" in text and "| crosstalk |" not in text
    # a dominant crosstalk term is named so in the text's dominant rows
    from tactcad.api import load
    from tactcad.studies.project_reports import budget_record

    _, budget = budget_record(load(design).plan, points=2)
    budget.units[0]["dominant"][0] = "crosstalk"
    assert f"| dominant | crosstalk ({level}) |" in render(budget)
