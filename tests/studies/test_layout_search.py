"""``tactcad design`` searches the free layout (sheet, bolt, pitch, tip) before
it refuses; a refusal names the asked targets that bind, with options to
paste that work; the file written records the command that made it.

The cases are not the paper's: the 2 x 6 Ti-6Al-4V grasper insert (K_r/K_m
10 over 0.5-5 N/mm) and a 2 x 4 CuBe array."""

from __future__ import annotations

import json
import math
import re
import shlex
import tomllib

import pytest

from tactcad.cli import main
from tactcad.design.array_plan import load_design
from tactcad.studies.inverse_design import start_tables
from tactcad.studies.layout_search import (FREE_FIELDS, candidate_layouts, layout_of,
                                           stack_fits)

pytestmark = pytest.mark.filterwarnings(
    "ignore::tactcad.mechanics.correction.CorrectionRangeWarning")

GRASPER = ["design", "--kr-over-km", "10", "--kobj-range", "0.5", "5", "--material",
           "Ti-6Al-4V-annealed", "--columns", "6", "--verify", "none"]


def _run(argv, capsys) -> tuple[int, dict]:
    code = main([*argv, "--json"])
    return code, json.loads(capsys.readouterr().out)


def _with(argv: list[str], option: str) -> list[str]:
    """``argv`` with the options of ``option`` (pasted text) replacing their old values."""
    words = shlex.split(option)
    out = list(argv)
    i = 0
    while i < len(words):
        flag, j = words[i], i + 1
        while j < len(words) and not words[j].startswith("--"):
            j += 1
        if flag in out:
            k = out.index(flag)
            n = 1
            while k + n < len(out) and not out[k + n].startswith("--"):
                n += 1
            del out[k:k + n]
        out += words[i:j]
        i = j
    return out


@pytest.mark.slow  # a whole design search
def test_the_shipped_bolt_does_not_refuse_more_columns_the_search_holds(tmp_path, capsys):
    """The base design's M2 cannot clamp six 3 mm sheets; the search changes the
    layout instead of refusing with the base design's bolt rule."""
    code, doc = _run([*GRASPER, "--full-scale-force", "0.05", "--out",
                      str(tmp_path / "g.toml")], capsys)
    assert code == 0, doc
    text = (tmp_path / "g.toml").read_text(encoding="utf-8")
    plan = load_design(tmp_path / "g.toml")
    assert plan.columns == 6
    base = load_design()
    tip = plan.element(1).geometry.tip_width_mm
    changed = [f for f, a, b in ((FREE_FIELDS[0], plan.sheet_thickness_mm,
                                  base.sheet_thickness_mm),
                                 (FREE_FIELDS[1], plan.bolt.size, base.bolt.size),
                                 (FREE_FIELDS[2], plan.pitch_mm, base.pitch_mm),
                                 (FREE_FIELDS[3], tip, base.element(1).geometry.tip_width_mm))
               if a != b]
    assert changed  # the base layout cannot hold the stack
    assert [c["field"] for c in doc["layout_changes"]] == changed
    why = tomllib.loads(text)["assumptions"]
    for field in changed:
        assert " in the base design (the shipped default example);" in why[field], field
    assert "tactcad design" in text.splitlines()[0]


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_refusal_names_the_asked_targets_and_its_alternatives_paste(tmp_path, capsys):
    argv = [*GRASPER, "--full-scale-force", "2", "--footprint", "30", "8",
            "--out", str(tmp_path / "g")]
    code, doc = _run(argv, capsys)
    err = doc["error"]
    assert code == 2 and err["field"] == "--full-scale-force" and err["value"] == 2.0
    assert re.match(r"at most [0-9.]+ N", err["allowed"])
    fields = [e["field"] for e in err["errors"]]
    assert fields == ["--full-scale-force", "--footprint"]
    assert "array.columns" not in err["message"] and ".toml" not in err["message"]
    assert err["alternatives"] and all(a["option"].startswith("--") for a in err["alternatives"])
    force = float(re.match(r"at most ([0-9.]+)", err["allowed"])[1])
    joint = next(a for a in err["alternatives"] if "--footprint" in a["option"])
    assert float(shlex.split(joint["option"])[1]) <= force  # no more than any layout carries
    code, doc = _run(_with(argv, joint["option"]), capsys)
    assert code == 0, doc
    assert not (tmp_path / "g" / "g.toml").read_text(encoding="utf-8").count("macro_array")


@pytest.mark.slow  # a whole design search
def test_a_value_the_user_sets_is_kept_and_errors_name_it_as_written(tmp_path, capsys):
    """A ``--set`` fixes its field: the search keeps it; a bad one is named as ``--set``."""
    out = tmp_path / "g.toml"
    code, doc = _run([*GRASPER, "--full-scale-force", "0.05", "--set",
                      'clamp.bolt_size="M2.5"', "--out", str(out)], capsys)
    assert code == 0, doc
    assert load_design(out).bolt.size == "M2.5"
    code, doc = _run([*GRASPER, "--full-scale-force", "0.05", "--set",
                      "sheet.thickness_mm=20", "--out", str(tmp_path / "h.toml")], capsys)
    assert code == 2 and doc["error"]["message"].startswith("--set: sheet.thickness_mm = 20")


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_derived_requirement_is_refused_as_the_option_that_set_it(tmp_path, capsys):
    """A tiny force read through a weak chain (amplifier gain 1, +/-5 V range) gives a K_obj
    resolution no requirement may state: refused as --full-scale-force, with the
    force that meets it, which then designs."""
    argv = ["design", "--kr-over-km", "8", "--kobj-range", "3", "30", "--full-scale-force", "0.002",
            "--material", "CuBe-C17200-TF00", "--columns", "4", "--verify", "none",
            "--set", "readout.amplifier_gain=1", "--set", "readout.daq_range_V=5",
            "--out", str(tmp_path / "c.toml")]
    code, doc = _run(argv, capsys)
    err = doc["error"]
    assert code == 2 and err["field"] == "--full-scale-force", err
    assert "requirements." not in err["message"]
    option = err["alternatives"][0]["option"]
    assert float(shlex.split(option)[1]) > 0.01
    code, doc = _run(_with(argv, option), capsys)
    assert code == 0, doc


@pytest.mark.slow  # two whole design searches
def test_the_recorded_command_makes_the_same_file_again(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    argv = [*GRASPER, "--full-scale-force", "0.05", "--set", 'clamp.bolt_size="M2.5"',
            "--set", "element.tip_height_mm=1.2", "--out", "g.toml"]
    assert main(argv) == 0
    first = (tmp_path / "g.toml").read_bytes()
    line = first.decode("utf-8").splitlines()[0]
    command = re.search(r"`tactcad (design .*)`", line)[1]
    assert "--set 'clamp.bolt_size=\"M2.5\"'" in command and "--out g.toml" in command
    (tmp_path / "g.toml").unlink()
    capsys.readouterr()
    assert main(shlex.split(command)) == 0
    assert (tmp_path / "g.toml").read_bytes() == first


def test_fixed_fields_stay_and_candidates_come_nearest_first():
    data = start_tables(load_design().raw, "x", columns=6)
    start = layout_of(data)
    every = candidate_layouts(start, frozenset())
    assert every[0] == start  # nothing changed comes first
    assert [len(c.changed(start)) for c in every] == sorted(len(c.changed(start)) for c in every)
    kept = candidate_layouts(start, frozenset(FREE_FIELDS[:2]))
    assert {(c.sheet_mm, c.bolt) for c in kept} == {(start.sheet_mm, start.bolt)}
    assert not stack_fits(data, start)  # six 3 mm sheets at 4 mm need more than an M2
    assert any(stack_fits(data, c) for c in every)


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_stack_no_bolt_holds_is_refused_as_columns_with_the_most_that_do(tmp_path, capsys):
    """A fixed 3 mm sheet: twelve columns need a longer bolt than the ISO table's;
    the refusal offers the most columns any bolt holds, which then designs."""
    argv = [*_with(GRASPER, "--columns 12"), "--full-scale-force", "0.05", "--set",
            "sheet.thickness_mm=3", "--out", str(tmp_path / "c.toml")]
    code, doc = _run(argv, capsys)
    err = doc["error"]
    assert code == 2 and err["field"] == "--columns" and err["value"] == 12, err
    option = err["alternatives"][0]["option"]
    most = int(option.split()[1])
    assert 1 <= most < 12 and err["allowed"] == f"at most {most}"
    code, doc = _run(_with(argv, option), capsys)
    assert code == 0, doc
    plan = load_design(tmp_path / "c.toml")
    assert (plan.columns, plan.sheet_thickness_mm) == (most, 3.0)


def test_values_fixed_against_each_other_are_refused_as_the_user_wrote_them(tmp_path, capsys):
    """A tip wider than the fixed pitch allows: no free value mends it, so the
    refusal names the --set, not a field of the base design."""
    code, doc = _run([*GRASPER, "--full-scale-force", "0.05", "--set", "element.tip_width_mm=5",
                      "--pitch", "4", "--out", str(tmp_path / "t.toml")], capsys)
    err = doc["error"]
    assert code == 2 and err["field"] == "element.tip_width_mm", err
    assert err["message"].startswith("--set: element.tip_width_mm = 5")
    code, doc = _run([*GRASPER, "--full-scale-force", "0.05", "--set", "nosuch.key=1",
                      "--out", str(tmp_path / "t.toml")], capsys)
    assert code == 2 and doc["error"]["message"].startswith("--set: nosuch"), doc


@pytest.mark.slow  # a whole chain through the command line or an export
def test_a_roomy_footprint_is_not_named_and_the_force_within_it_designs(tmp_path, capsys):
    argv = [*GRASPER, "--full-scale-force", "2", "--footprint", "100", "100",
            "--out", str(tmp_path / "r.toml")]
    code, doc = _run(argv, capsys)
    err = doc["error"]
    assert code == 2 and err["field"] == "--full-scale-force" and "errors" not in err, err
    assert "--footprint =" not in err["message"]
    option = err["alternatives"][0]["option"]
    assert option.startswith("--full-scale-force ")
    code, doc = _run(_with(argv, option), capsys)
    assert code == 0, doc


@pytest.mark.parametrize("bolt", ["M1.6", "M2", "M2.5", "M3"])
def test_every_iso_bolt_gets_the_dimensions_it_needs_under_the_tallest_arm(bolt):
    """A larger bolt under a 5 mm arm needs a taller base and a wider spacing than
    the shipped M2 design has; the layout's tables are raised to them and validate."""
    from tactcad.design.array_plan import plan_from_dict
    from tactcad.studies.layout_search import FreeLayout, with_layout

    data = start_tables(load_design().raw, "x", columns=2)
    data["element"]["arm_height_mm"] = 5.0
    start = layout_of(data)
    tables = with_layout(data, FreeLayout(start.sheet_mm, start.pitch_mm, start.tip_width_mm,
                                          bolt))
    plan = plan_from_dict(tables)
    assert plan.bolt.size == bolt
    assert plan.element(1).geometry.base_height_mm >= 5.0 + plan.bolt.clearance_hole_mm + 2.0


# a whole design search through the command line; the layout's tables it writes are
# test_a_layouts_sheet_thinner_than_the_default_grid_gets_a_grid_that_fits's (fast)
@pytest.mark.slow
def test_a_searched_sheet_thinner_than_the_default_grid_gets_a_grid_that_fits(tmp_path, capsys):
    """Photochemical etching's sheets are thinner than the library default's gauge grid: the
    search writes a grid as wide as its sheet, with the gauge to bond as its reason, so the
    written design keeps the grid on the element's face (it wrote the default's 1 mm grid on a
    0.4 mm sheet)."""
    from tactcad.design.readout_section import DEFAULTS

    out = tmp_path / "pce.toml"
    code, doc = _run(["design", "--kr-over-km", "8", "--kobj-range", "0.5", "4",
                      "--full-scale-force", "0.05", "--process", "photochemical-etching",
                      "--material", "7075-T6", "--verify", "none", "--out", str(out)], capsys)
    assert code == 0, doc
    written = tomllib.loads(out.read_text(encoding="utf-8"))
    sheet = written["sheet"]["thickness_mm"]
    assert sheet < DEFAULTS["grid_width_mm"][0]
    assert written["readout"]["grid_width_mm"] <= sheet
    assert "bond a gauge" in written["assumptions"]["readout.grid_width_mm"]
    assert load_design(out).sheet_thickness_mm == sheet  # the rule passes it


def test_a_layouts_sheet_thinner_than_the_default_grid_gets_a_grid_that_fits():
    """The tables the search judges and writes for a layout (:func:`with_layout`) on a
    photochemical-etching sheet thinner than the library default's grid, at both ends of
    the sheets that take a fitted grid (the narrowest grid allowed up to the default's
    width): a grid as wide as the sheet, the gauge to bond as its reason, and the grid rule
    passes them (the search wrote the default's 1 mm grid on a 0.4 mm sheet)."""
    from tactcad.design.array_plan import plan_from_dict
    from tactcad.design.readout_section import DEFAULTS, GRID_WIDTH_RANGE_MM
    from tactcad.studies.layout_search import FreeLayout, process_sheets_mm, with_layout

    data = start_tables(load_design().raw, "x", grade="7075-T6", columns=2)
    data["element"]["process"] = "photochemical-etching"
    fitted = [s for s in process_sheets_mm("photochemical-etching")
              if GRID_WIDTH_RANGE_MM[0] <= s < DEFAULTS["grid_width_mm"][0]]
    start = layout_of(data)
    for sheet in (fitted[0], fitted[-1]):
        tables = with_layout(data, FreeLayout(sheet, start.pitch_mm, start.tip_width_mm,
                                              start.bolt))
        assert tables["readout"]["grid_width_mm"] == sheet
        assert "bond a gauge" in tables["assumptions"]["readout.grid_width_mm"]
        plan = plan_from_dict(tables)  # the grid rule passes it
        assert plan.sheet_thickness_mm == sheet


@pytest.mark.parametrize("whole, estimate", [(0.08159, 0.07), (0.0, 0.08158)])
def test_a_force_refusal_never_allows_the_force_it_refuses(whole, estimate):
    """A largest force just under the force asked is not rounded up to it: the refusal
    says less than the force asked, never "at most" that force."""
    from tactcad.studies.layout_search import force_refusal

    asked = 0.0816
    e = force_refusal(asked, whole, estimate, "the targets", "bound by a limit")
    assert e is not None and e.field == "--full-scale-force"
    numbers = [float(x) for x in re.findall(r"\d+\.\d+", e.allowed)]
    assert numbers and (e.allowed.startswith("less than") or numbers[0] < asked), e.allowed


def test_a_force_whole_designs_meet_is_not_refused_as_the_binding_force():
    """When whole designs meet the force asked, the refusal does not name the force (another
    rule refused the layouts), so it never reads "at most" the force asked."""
    from tactcad.studies.layout_search import force_refusal

    assert force_refusal(0.0816, 0.0816, 0.07, "the targets", "bound by a limit") is None
    e = force_refusal(0.0816, 0.0731, 0.07, "the targets", "bound by a limit")
    assert e.allowed.startswith("at most 0.0731 N")


@pytest.mark.parametrize("carried_N", [0.5431, 0.5, 0.5805])
def test_a_refusals_force_is_the_largest_judged_force_on_the_grid(carried_N):
    """The force a refusal offers is one the search was asked and designed at, and the next
    force up the 3-digit grid was refused; none is offered when nothing near designs."""
    from tactcad.studies.layout_search import force_frontier
    from tactcad.vocabulary.rounding import round_down

    judged: dict[float, bool] = {}

    def designed(force: float) -> str | None:
        judged[force] = force <= carried_N
        return "layout" if judged[force] else None

    force, layout = force_frontier(designed, 0.5805)
    assert layout == "layout" and judged[force]
    step = 10.0 ** (math.floor(math.log10(force)) - 2)
    assert round_down(force + step, 3) > carried_N  # the next grid force up is not carried
    assert force_frontier(lambda f: None, 0.5805) is None


def test_a_refusals_force_grows_above_a_start_that_designs():
    """The start is the best layout's own largest force by whole designs (0.281 N on an
    8 mm sheet, CuBe 2 x 3), but the layout the search reaches (6 mm) designs up to 0.2849 N:
    the refusal offered 0.281 N while the design at it reported 0.2849 N."""
    from tactcad.studies.layout_search import force_frontier

    carried = 0.2849
    force, layout = force_frontier(lambda f: "layout" if f <= carried else None, 0.281)
    assert layout == "layout" and force == 0.284  # the largest grid force carried
    for start in (0.1, 0.2, 0.284, 0.3, 0.5):  # one figure, wherever it starts
        assert force_frontier(lambda f: "layout" if f <= carried else None, start)[0] == 0.284


def test_a_refusals_force_is_found_far_below_the_best_layouts_own_force():
    """On a soft K_obj range the search may design only far below the best layout's own
    largest force (0.004826 N against 0.0254 N): the steps down do not stop at a few per
    cent, and the force found is the largest on the grid that designs, rounded down."""
    from tactcad.studies.layout_search import force_frontier
    from tactcad.vocabulary.rounding import round_down

    carried = 0.004826
    judged: list[float] = []

    def designed(force: float) -> str | None:
        judged.append(force)
        return "layout" if force <= carried else None

    force, layout = force_frontier(designed, 0.0254)
    assert layout == "layout" and force <= carried
    assert round_down(force + 1e-5, 3) > carried  # 0.00482: the next grid force is not carried
    assert len(judged) < 40  # whole design searches, each a second or more
    assert force_frontier(lambda f: None, 0.0254) is None


@pytest.mark.slow  # two whole design searches through the command line
def test_a_soft_range_refusal_offers_a_force_that_designs_far_below_the_best_layouts(
        tmp_path, capsys, monkeypatch):
    """A soft K_obj range (0.02-0.2 N/mm) whose best layout's own largest force is far above
    any the search designs at (its estimate made five times too large here) still offers a
    force to paste, and pasted it designs."""
    import tactcad.studies.layout_search as layout_search

    real = layout_search.largest_feasible_force
    monkeypatch.setattr(layout_search, "largest_feasible_force",
                        lambda *a, **k: 5.0 * real(*a, **k))
    monkeypatch.chdir(tmp_path)
    argv = ["design", "--kr-over-km", "10", "--kobj-range", "0.02", "0.2", "--verify", "none"]
    code, doc = _run([*argv, "--full-scale-force", "5", "--out", "asked.toml"], capsys)
    assert code == 2 and doc["error"]["field"] == "--full-scale-force", doc
    offers = [a["option"] for a in doc["error"]["alternatives"]
              if a["option"].startswith("--full-scale-force ")]
    assert offers, doc["error"]
    offered = float(offers[0].split()[1])
    assert f"at most {offered:g} N" in doc["error"]["allowed"]
    code, doc = _run(_with([*argv, "--full-scale-force", "5", "--out", "pasted.toml"],
                           offers[0]), capsys)
    assert code == 0, doc
    written = tomllib.loads((tmp_path / "pasted.toml").read_text(encoding="utf-8"))
    assert written["requirements"]["full_scale_force_N"] == offered


@pytest.mark.slow  # four whole design searches through the command line
def test_the_refusals_force_pastes_and_is_the_same_for_any_force_asked_above_it(
        tmp_path, capsys, monkeypatch):
    """The search tries only the layouts nearest the base design, so the best layout's own
    largest force could be refused when pasted ("none of the first layouts tried met every
    rule"), and moved with the force asked. A cap of 3 layouts brings that about on a fast
    case (K_r/K_m 6 over 5-50 N/mm without the tissue coupling)."""
    import tactcad.studies.layout_search as layout_search

    monkeypatch.setattr(layout_search, "MAX_DESIGNS", 3)
    monkeypatch.chdir(tmp_path)  # a design written here would be the next one's base
    argv = ["design", "--kr-over-km", "6", "--kobj-range", "5", "50", "--tissue-coupling", "off",
            "--verify", "none"]
    offers = []
    for asked in ("1", "2"):
        code, doc = _run([*argv, "--full-scale-force", asked, "--out", f"{asked}.toml"], capsys)
        assert code == 2 and doc["error"]["field"] == "--full-scale-force", doc
        offers.append(doc["error"]["alternatives"][0]["option"])
    assert offers[0] == offers[1] and offers[0].startswith("--full-scale-force ")
    offered = float(offers[0].split()[1])
    assert f"at most {offered:g} N" in doc["error"]["allowed"]
    code, doc = _run(_with([*argv, "--full-scale-force", "2", "--out", "pasted.toml"],
                           offers[0]), capsys)
    assert code == 0, doc
    written = tomllib.loads((tmp_path / "pasted.toml").read_text(encoding="utf-8"))
    assert written["requirements"]["full_scale_force_N"] == offered


@pytest.mark.parametrize("limit", [0.004826, 0.0049999, 0.12058, 3.14159])
def test_a_force_refusals_at_most_is_rounded_down_never_past_the_limit(limit):
    """The "at most" a refusal names is a force at or below the largest the designs carry,
    so pasted it is not refused again for the force (0.004826 N was said as 0.00483 N)."""
    from tactcad.studies.layout_search import force_refusal

    e = force_refusal(5.0 * limit, limit, 0.0, "the targets", "bound by a limit")
    said = float(re.match(r"at most (\S+) N", e.allowed).group(1))
    assert limit * 0.99 <= said <= limit


@pytest.mark.slow  # a whole design search through the command line
def test_a_ratio_near_one_is_refused_as_the_ratio_not_as_a_force_not_given(tmp_path, capsys):
    """K_r/K_m 1.0000001 was refused as "--full-scale-force (not given): ... no layout's
    elements could be weighed" although the force was given: the tissue-coupled centring
    refused every layout's tips, and the refusal names the ratio and why."""
    code = main(["design", "--kr-over-km", "1.0000001", "--kobj-range", "1", "10",
                 "--full-scale-force", "0.1", "--out", str(tmp_path / "d"), "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and error["field"] == "--kr-over-km" and error["value"] == 1.0000001
    assert "changes with K_obj through the tissue" in error["allowed"]
    assert "outside 0.01 ... 100" in error["message"] and not (tmp_path / "d").exists()
