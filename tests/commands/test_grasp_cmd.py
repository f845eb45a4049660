"""``tactcad grasp``: both designs, paired vs as laid out, the leads, the refusals."""

import json
from pathlib import Path

import pytest
from comb_variants import ROW_PAIRED
from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
TI = str(ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml")
COMB = str(ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml")


def row_paired_sets() -> list[str]:
    """``--set`` options that pair the shipped comb along its rows (:data:`ROW_PAIRED`)."""
    out = []
    for key, value in ROW_PAIRED.items():
        out += ["--set", f"{key}={json.dumps(value)}"]
    return out


@pytest.mark.slow  # contact solves of whole grasps
def test_the_comb_paired_along_its_rows_reads_farther_than_at_equal_radius():
    r = run_cli("grasp", "--design", COMB, *row_paired_sets(), "--profile", "wedge", "--kobj", "1",
                "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    laid, paired = d["as_laid_out"]["units"], d["paired"]["units"]
    assert len(laid) == 10 and len(paired) == 6
    assert all(abs(u["radius_ratio"] - 1) <= 0.02 for u in paired)
    assert not any(abs(u["radius_ratio"] - 1) <= 0.02 for u in laid)
    assert max(abs(u["error_rel"]) for u in paired) < min(abs(u["error_rel"]) for u in laid)
    assert d["leads"]["leads"] == 36 and d["leads"]["fits"]


@pytest.mark.slow  # a whole chain through the command line
def test_the_shipped_comb_reads_every_unit_at_equal_radius_as_laid_out():
    r = run_cli("grasp", "--design", COMB, "--profile", "wedge", "--kobj", "1", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    laid, paired = d["as_laid_out"]["units"], d["paired"]["units"]
    assert len(laid) == 6 and all(abs(u["radius_ratio"] - 1) <= 0.02 for u in laid)
    assert [u["R_read"] for u in laid] == pytest.approx([u["R_read"] for u in paired])


@pytest.mark.slow  # a whole chain through the command line or an export
def test_the_jaw_and_shaft_the_design_states_are_the_grasps_and_said_so():
    r = run_cli("grasp", "--design", COMB, "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["jaw"]["opening_angle_deg"] == 30.0  # the example's [grasper_jaw], not 60
    assert d["reasons"]["pivot"] == "the design's [grasper_jaw]"
    assert d["leads"]["channel_diameter_mm"] == 9.0  # the 10 mm shaft's bore, as check reads it
    # the example states its jaw only: the shaft and slab are their tables' defaults, said so
    assert "[grasper_shaft] defaults" in d["reasons"]["lead_channel_mm"]
    assert "[tissue_slab] defaults" in d["reasons"]["slab_thickness_mm"]
    r = run_cli("grasp", "--design", COMB, "--set", "tissue_slab.thickness_mm=4", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["reasons"]["slab_thickness_mm"] == "the design's [tissue_slab]"
    assert d["jaw"]["slab_thickness_mm"] == 4.0
    # a stacked design's stated jaw cannot seat its insert without the kernel: said, not used
    r = run_cli("grasp", "--design", TI, "--set", 'grasper_jaw.shaft_class_mm="10"', "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert "is not used" in d["reasons"]["pivot"] and d["jaw"]["opening_angle_deg"] == 60.0
    r = run_cli("grasp", "--design", TI, "--json")
    assert json.loads(r.stdout)["leads"]["channel_diameter_mm"] == 3.0  # no grasper: assumed


@pytest.mark.slow  # contact solves of whole grasps
def test_the_pivot_and_the_angle_reach_the_grasp():
    r = run_cli("grasp", "--design", TI, "--pivot-mm", "-10", "0", "--angle-deg", "10",
                "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["jaw"]["pivot_u_mm"] == -10 and d["as_laid_out"]["angle_deg"] == 10
    assert min(u["r_reference_mm"] for u in d["as_laid_out"]["units"]) == pytest.approx(14.0)


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_non_paper_design_and_the_text_table():
    r = run_cli("grasp", "--design", TI, "--set", "array.columns=4", "--set",
                "arms.lengths_mm=[19.605,6.196,19.605,19.605,19.605,6.196,19.605,19.605]",
                "--lead-channel-mm", "1")
    assert r.returncode == 1, r.stderr  # the leads do not fit: a grasp that does not pass
    assert "| unit | r_r mm |" in r.stdout and "paired:" in r.stdout
    assert "does NOT fit" in r.stdout and "do not fit the 1 mm lead channel" in r.stdout


@pytest.mark.parametrize("options, words", [(["--force-N", "0"], "--force-N"),
                                            (["--pivot-mm", "3", "0"], "--pivot-mm"),
                                            # the jaw's limit is a grasp solved in full
                                            pytest.param(["--force-N", "900"], "--force-N",
                                                         marks=pytest.mark.slow),
                                            (["--angle-deg", "80", "--opening-deg", "30"],
                                             "--angle-deg"),
                                            (["--slab-thickness-mm", "-1"],
                                             "--slab-thickness-mm"),
                                            (["--pin-to-tip-mm", "1"], "--pin-to-tip-mm")])
def test_bad_options_name_the_option_the_value_and_the_range(options, words):
    r = run_cli("grasp", "--design", TI, *options)
    assert r.returncode == 2
    assert words in r.stderr and "allowed" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.parametrize("force", ["1e-300", "5e-7"])
def test_a_force_too_small_to_deflect_above_round_off_is_refused_with_its_range(force):
    """--force-N 1e-300 reported round-off as readings (a grasp force of 6.972e-16 N,
    deflections of 2.22e-16 mm) and passed."""
    import tactcad
    from tactcad.errors import DesignError

    r = run_cli("grasp", "--design", TI, "--force-N", force)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert f"--force-N: '{force}': allowed a number 1e-06 ... 1000 (N)" in r.stderr
    with pytest.raises(DesignError) as exc:  # the API's keyword takes the option's range
        tactcad.load(TI).grasp(force_N=float(force))
    assert "1e-06 ... 1000" in str(exc.value)


def test_the_smallest_grasp_force_reads_as_a_heavier_one():
    """At the floor the tips deflect far above round-off: the readings are those of a
    grasp a thousand times heavier (the model is linear)."""
    light = json.loads(run_cli("grasp", "--design", TI, "--force-N", "1e-6", "--json").stdout)
    heavy = json.loads(run_cli("grasp", "--design", TI, "--force-N", "1e-3", "--json").stdout)
    assert light["as_laid_out"]["total_force_N"] == pytest.approx(1e-6, rel=1e-9)
    for a, b in zip(light["as_laid_out"]["units"], heavy["as_laid_out"]["units"], strict=True):
        assert a["error_rel"] == pytest.approx(b["error_rel"], rel=1e-6, abs=1e-9)


def test_an_option_of_two_values_is_refused_with_both_as_given():
    """--pivot-mm 0 0 was said "--pivot-mm = 0.0", one coordinate of the two."""
    r = run_cli("grasp", "--design", TI, "--pivot-mm", "0", "0")
    assert r.returncode == 2
    assert r.stderr.startswith("tactcad: error: --pivot-mm = [0.0, 0.0]: allowed ")


def test_a_default_grasp_lighter_than_the_open_jaw_allows_is_the_jaw_fully_open():
    # the example's jaw opens 30 degrees: a 3 mm slab near its pin is pressed already
    r = run_cli("grasp", "--design", COMB, "--profile", "slab", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["as_laid_out"]["angle_deg"] == d["jaw"]["opening_angle_deg"]
    assert d["reasons"]["force_N"].startswith("the jaw at its full opening")
    # past the rating is not past the overload limit: each tip carries its own limit
    tips = d["as_laid_out"]["tips"]
    assert all(t["overload_limit_N"] > d["rated_force_N"] for t in tips)
    assert any(t["over_rating"] for t in tips) and not any(t["over_overload_limit"] for t in tips)
    # asked for, the same force is refused with the range the jaw reaches
    r = run_cli("grasp", "--design", COMB, "--profile", "slab", "--force-N", "0.3")
    assert r.returncode == 2 and "--force-N" in r.stderr


def test_a_paired_design_is_set_against_its_units_laid_along_the_rows():
    r = run_cli("grasp", "--design", COMB, "--kobj", "1", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["profile"] == "wedge"  # the default: every tip touches, every unit reads
    assert d["paired_layout"]["as_laid_out"] and not d["along_rows_layout"]["as_laid_out"]
    paired, along = d["paired"]["units"], d["along_rows"]["units"]
    assert all(u["valid"] for u in paired + along)
    assert all(u["radius_ratio"] > 1.02 for u in along)
    # along the rows the travel ratio enters R; the travel correction takes most of it out
    worst_paired = max(abs(u["error_rel"]) for u in paired)
    assert min(abs(u["error_rel"]) for u in along) > 2 * worst_paired
    # corrected for each tip's travel and tissue (the wedge's thinner tissue is stiffer),
    # every unit reads nearer than read; the coupling left is stated with its size
    assert all(abs(u["error_corrected_rel"]) < abs(u["error_rel"]) for u in along)
    left = d["along_rows"]["correction_residual"]
    assert left["largest_rel"] == max((u["error_corrected_rel"] for u in along), key=abs)
    text = run_cli("grasp", "--design", COMB, "--kobj", "1").stdout
    assert "paired: the design's own layout" in text and "along the rows: angle" in text
    assert ("along the rows: the corrected K_obj is still off by" in text
            and f"(largest {100 * left['largest_rel']:+.3g} %, unit {left['unit']})" in text)


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_default_grasp_heavier_than_the_closed_jaw_allows_is_the_jaw_closed_flat():
    # a thin wedge of soft tissue (the thinnest the contact solves take is about 0.52 mm at
    # the last tip here): closed flat, the jaw presses less than the default grasp asks
    r = run_cli("grasp", "--design", COMB, "--slab-thickness-mm", "0.6", "--kobj", "0.01",
                "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["as_laid_out"]["angle_deg"] == 0.0
    assert 0 < d["as_laid_out"]["total_force_N"] < 0.5 * d["rated_force_N"] * 12
    assert d["reasons"]["force_N"].startswith("the jaw closed flat")


def test_a_jaw_too_short_is_refused_for_the_length_its_farthest_tip_needs():
    r = run_cli("grasp", "--design", COMB, "--pin-to-tip-mm", "1")
    assert r.returncode == 2 and "--pivot-mm" not in r.stderr
    assert "--pin-to-tip-mm = 1" in r.stderr and "at least 29.7 mm from the pin" in r.stderr


def test_a_kobj_outside_the_designs_range_is_warned_and_not_read():
    """`--kobj` outside the design's K_obj range: a warning naming the option, the value and
    the range, and no unit claims to read it."""
    r = run_cli("grasp", "--design", COMB, "--kobj", "1000")
    assert r.returncode == 0, r.stdout + r.stderr
    lines = r.stdout.splitlines()
    warning = next(line for line in lines if line.startswith("warning:"))
    assert "--kobj 1000 N/mm" in warning and "K_obj range" in warning
    d = json.loads(run_cli("grasp", "--design", COMB, "--kobj", "1000", "--json").stdout)
    lo, hi = d["kobj_range_N_per_mm"]
    assert f"{lo:g} ... {hi:g} N/mm" in warning
    assert not any(u["reads"] for u in d["as_laid_out"]["units"])
    assert all("outside the design's range" in u["out_of_range"]
               for u in d["as_laid_out"]["units"])
    inside = json.loads(run_cli("grasp", "--design", COMB, "--json").stdout)
    assert not inside["warnings"]


def test_the_options_earlier_name_is_refused_with_its_new_one():
    """--jaw-length-mm was the pin-to-tip length under the jaw's own length's name: it is
    refused, naming --pin-to-tip-mm and the value to give it, not as an unknown argument."""
    import subprocess
    import sys

    r = subprocess.run([sys.executable, "-m", "tactcad", "grasp", "--jaw-length-mm", "30"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--pin-to-tip-mm 30" in r.stderr, r.stderr
    assert "unrecognized" not in r.stderr and "Traceback" not in r.stderr


def test_an_earlier_names_value_is_pasted_as_one_shell_word_on_one_line():
    """A value with a newline or a space (drawn by the options' property test) was pasted
    raw: the refusal broke over two lines and the paste was two words."""
    import argparse
    import shlex

    from tactcad.commands.options import renamed_option

    parse = renamed_option("--jaw-length-mm", "--pin-to-tip-mm", "pin to tip")
    for value in ("\n", "3 0", "30"):
        with pytest.raises(argparse.ArgumentTypeError) as exc:
            parse(value)
        message = str(exc.value)
        assert "\n" not in message, message
        pasted = message.split("give --pin-to-tip-mm ", 1)[1]
        assert len(shlex.split(pasted)) == 1, message


def test_a_grasp_past_the_overload_limit_is_warned_its_readings_marked_and_it_fails():
    """At 5 N the stacked example's elements 2, 3, 5, 6 pass their overload limit: the grasp
    said so in a warning naming the force and the sites, gave no K_obj from their units (in
    the JSON nor the table) and exited 1, as a failed check; at the default force, nothing."""
    r = run_cli("grasp", "--design", TI, "--force-N", "5", "--json")
    assert r.returncode == 1, r.stderr
    d = json.loads(r.stdout)
    laid = d["as_laid_out"]
    over = [t["site"] for t in laid["tips"] if t["over_overload_limit"]]
    assert over and d["passed"] is False
    warning = next(w for w in d["warnings"] if w.startswith("warning: as laid out"))
    assert "5 N" in warning and f"sites {', '.join(map(str, over))}" in warning
    hit = [u for u in laid["units"] if {u["reference"], u["measuring"]} & set(over)]
    assert hit and all(u["overloaded"] and not u["valid"] and not u["reads"] for u in hit)
    assert all(u["K_obj_read_N_per_mm"] is None and u["K_obj_corrected_N_per_mm"] is None
               for u in hit)
    assert "overload limit" in hit[0]["why"]
    text = run_cli("grasp", "--design", TI, "--force-N", "5")
    assert text.returncode == 1
    rows = [line for line in text.stdout.splitlines() if line.startswith(f"| {hit[0]['unit']} |")]
    assert rows and rows[0].count("| overloaded |") >= 1 and "overload limit" in rows[0]
    safe = run_cli("grasp", "--design", TI, "--json")
    assert safe.returncode == 0 and json.loads(safe.stdout)["warnings"] == []
