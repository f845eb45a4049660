"""The invariant at its root: every design ``tactcad design`` writes exports and
passes its own ``check``; every refusal exits 2 naming the field, what is allowed
and a pasteable alternative (or why none exists), and writes nothing.

Targets are drawn by hypothesis (K_r/K_m, the K_obj range, the full-scale force,
columns, material, a footprint or none) and run through the command line as a lab
runs it: ``design --out DIR``, then ``export`` and ``check`` inside DIR. The lab
cases that once broke this (the palpation strip, a lab's 12 mm jaw) are pinned as
regression tests."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, assume, given, seed, settings
from hypothesis import strategies as st

from depth import draws
from tactcad import cli

MATERIALS = ("7075-T6", "6061-T6", "Ti-6Al-4V-annealed", "17-4PH-H900", "CuBe-C17200-TF00")
#: Draws per slow test; the slow set runs three such tests (3 in all in ``make test``, one
#: fresh design per worker at about a minute each; 30 in ``make test-deep``).
DRAWS = draws(1, 10)


@st.composite
def design_targets(draw) -> list[str]:
    """A ``design`` command line's targets: K_r/K_m 4-12, K_obj from 0.1-3 N/mm over a
    3-20 x span, 0.01-1 N, 2-8 columns, a library material; a footprint, the 10 mm class's
    jaw, a lab's own jaw (a table: shaft 9-14 mm, its width and height passing it, the pivot
    in the jaw or behind its heel, 30-60 degrees open) or none; wire EDM, etching or laser
    cutting."""
    low = draw(st.floats(0.1, 3.0).map(lambda v: round(v, 2)))
    span = draw(st.floats(3.0, 20.0))
    args = ["--kr-over-km", f"{draw(st.floats(4.0, 12.0)):.2f}",
            "--kobj-range", f"{low:g}", f"{round(low * span, 2):g}",
            "--full-scale-force", f"{draw(st.floats(0.01, 1.0)):.3g}",
            "--columns", str(draw(st.integers(2, 8))),
            "--material", draw(st.sampled_from(MATERIALS))]
    jaw = draw(st.sampled_from(("none", "none", "class", "file")))
    if jaw == "class":
        args += ["--jaw", "10"]
    elif jaw == "file":  # a lab's own jaw: shaft, width, height and pivot drawn
        shaft = draw(st.floats(9.0, 14.0).map(lambda v: round(v, 1)))
        height = draw(st.floats(5.5, 7.0).map(lambda v: round(v, 2)))
        width = round(min(draw(st.floats(6.0, 11.0)),
                          (shaft ** 2 - (height + 1.5) ** 2) ** 0.5 - 0.01), 2)
        args += ["--jaw", {"shaft_diameter_mm": shaft, "width_mm": width, "thickness_mm": height,
                           "length_mm": draw(st.floats(28.0, 40.0).map(lambda v: round(v, 1))),
                           "pin_inset_mm": draw(st.sampled_from((2.5, -6.0))),
                           "opening_angle_deg": draw(st.sampled_from((30.0, 45.0, 60.0)))}]
    elif draw(st.booleans()):
        args += ["--footprint", str(draw(st.integers(30, 120))), str(draw(st.integers(15, 60)))]
    process = draw(st.sampled_from((None, None, None, "photochemical-etching", "laser-cutting")))
    if process is not None:  # the rows' or the elements' cut process, searched as the sheet
        args += ["--process", process]
    return args


def run_cli(argv: list[str], capsys) -> tuple[int, str]:
    code = cli.main(argv)
    return code, capsys.readouterr().out


def jaw_file_written(targets: list, folder: Path) -> list[str]:
    """``targets`` with a drawn jaw (a table after ``--jaw``) written as a lab's jaw file
    beside ``folder``; a design to a jaw takes no ``--verify`` (its checks need no kernel)."""
    if "--jaw" not in targets:
        return [*targets, "--verify", "none"]
    i = targets.index("--jaw") + 1
    if isinstance(targets[i], dict):
        jaw = folder.parent / "lab_jaw.toml"
        jaw.write_text("[grasper_jaw]\n" + "".join(f"{k} = {v!r}\n" for k, v in
                                                  targets[i].items()), encoding="utf-8")
        targets = [*targets[:i], str(jaw), *targets[i + 1:]]
    return targets


def designed_or_refused(targets: list, folder: Path, capsys) -> None:
    """Design ``targets`` into ``folder``; a refusal is judged as one, a design is exported
    and checked in its own folder (as ``cd DIR && tactcad check``)."""
    targets = jaw_file_written(targets, folder)
    code, out = run_cli(["design", *targets, "--out", str(folder), "--json"], capsys)
    if code == 2:
        error = json.loads(out)["error"]
        assert error["field"] and error["allowed"], error
        assert error["alternatives"] or "none" in error["message"].lower(), error
        for alt in error["alternatives"]:  # an option, or the jaw file's keys to write
            assert alt["option"].startswith("--") or "grasper_jaw." in alt["option"], alt
        assert not folder.exists(), f"a refused design left {sorted(os.listdir(folder))}"
        return
    assert code == 0, out
    report = json.loads(out)
    if report.get("construction") == "mems-die":  # only a silicon die fits the jaw
        made, record = run_cli(["die", "--design", report["design"], "--out",
                                str(folder / "die"), "--json"], capsys)
        assert made == 0, f"design {' '.join(map(str, targets))} wrote a die failing its checks:\n{record}"
        return
    checked, report = exported_and_checked(folder, capsys)
    assert checked == 0, f"design {' '.join(targets)} failed its own check:\n{report}"


def exported_and_checked(folder: Path, capsys) -> tuple[int, str]:
    """(check's exit code, its failures) of the project in ``folder`` exported there, as a
    lab runs ``cd DIR && tactcad export && tactcad check``."""
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        assert run_cli(["export", "--out", "exports", "--quiet"], capsys)[0] == 0
        return run_cli(["check", "--out", "exports", "--failures-only"], capsys)
    finally:
        os.chdir(cwd)


@pytest.mark.slow
def test_a_long_armed_comb_rows_lead_ins_lie_outside_it(tmp_path, capsys):
    # found by a draw: two columns in the 10 mm jaw, 14.3 mm elements; the outer cut entered
    # from a slot under an arm narrower than the lead-in, so its start lay in the part
    folder = tmp_path / "long"
    targets = ["--kr-over-km", "5.04", "--kobj-range", "0.93", "13.35", "--full-scale-force",
               "0.133", "--columns", "2", "--material", "17-4PH-H900", "--jaw", "10"]
    assert run_cli(["design", *targets, "--out", str(folder), "--quiet"], capsys)[0] == 0
    checked, report = exported_and_checked(folder, capsys)
    assert checked == 0, report


def _property(tmp_path_factory, capsys, targets) -> None:
    designed_or_refused(targets, tmp_path_factory.mktemp("design") / "strip", capsys)


def first_drawn(strategy):
    """The example Hypothesis draws first from ``strategy`` (its simplest, whatever the
    seed): drawn, not run."""
    drawn = []

    @settings(max_examples=1, database=None, phases=(Phase.generate,))
    @given(strategy)
    def keep(example):
        drawn.append(example)

    keep()
    return drawn[0]


#: No shrinking: one draw takes about a minute, and the failing targets are printed as drawn.
SETTINGS = settings(max_examples=DRAWS, deadline=None, database=None,
                    phases=(Phase.explicit, Phase.generate),
                    suppress_health_check=list(HealthCheck))


@pytest.mark.slow
@pytest.mark.parametrize("part", range(3), ids=lambda p: f"draws{p * DRAWS + 1}-{(p + 1) * DRAWS}")
def test_every_written_design_passes_its_own_check(part, tmp_path_factory, capsys):
    # three parts run on separate workers; each draws its own targets (a seed per part).
    # Hypothesis tries the simplest targets first whatever the seed, so with one draw a
    # part every part ran the same design: the parts after the first pass it over (no
    # design is run for it) and draw from their seeds
    simplest = first_drawn(design_targets())

    @seed(7919 * (part + 1))
    @SETTINGS
    @given(targets=design_targets())
    def prop(targets):
        assume(part == 0 or targets != simplest)
        _property(tmp_path_factory, capsys, targets)

    prop()


@pytest.mark.slow
def test_an_etched_comb_for_the_10_mm_jaw_designs_and_passes_its_check(tmp_path, capsys):
    # its rows were laid out for wire EDM whatever the process; foil rows took stock dowel
    # pins longer than the stack, which the jaw's checks did not see
    # (refused, a lab pastes the alternative the refusal names: the etched rows' gauges
    # stiffen their thin webs, so fewer columns or a lighter force may be what designs)
    targets = ["--kr-over-km", "10", "--kobj-range", "0.5", "5", "--material",
               "Ti-6Al-4V-annealed", "--columns", "6", "--full-scale-force", "0.0196",
               "--jaw", "10", "--process", "photochemical-etching"]
    code, out = run_cli(["design", *targets, "--out", str(tmp_path / "asked"), "--json"], capsys)
    if code == 2:
        targets += json.loads(out)["error"]["alternatives"][0]["option"].split()
    designed_or_refused(targets, tmp_path / "etched", capsys)
    assert (tmp_path / "etched" / "etched.toml").is_file()


@pytest.mark.slow
def test_the_palpation_strip_designs_and_passes_its_check(tmp_path, capsys):
    # a 2 x 8 strip in 7075-T6 on a 63 x 18 mm footprint: its 0.2 mm spacers were judged
    # by the flexure's sheet range, its slot map covered the plan view, its terminal
    # board's hole labels overlapped at 2:1
    # (the lab asked 0.0395 N; refused, it pastes the force the refusal names, as a lab does)
    targets = ["--kr-over-km", "8", "--kobj-range", "0.2", "2", "--full-scale-force", "0.0395",
               "--footprint", "63", "18", "--material", "7075-T6", "--columns", "8"]
    code, out = run_cli(["design", *targets, "--out", str(tmp_path / "asked"), "--json"], capsys)
    if code == 2:
        option = json.loads(out)["error"]["alternatives"][0]["option"].split()
        assert option[0] == "--full-scale-force", option
        targets[targets.index("--full-scale-force") + 1] = option[1]
        assert not (tmp_path / "asked").exists()
    designed_or_refused(targets, tmp_path / "palp", capsys)
    assert (tmp_path / "palp" / "palp.toml").is_file()
    # and at the top of the ladder: it was written at a gauge-fatigue margin of +0.1 % on the
    # closed form, whose grid strain fem3d read 4.7 % higher (a thin sheet outside its fit)
    cwd = os.getcwd()
    os.chdir(tmp_path / "palp")
    try:
        verified, record = run_cli(["verify", "--model", "fem3d"], capsys)
    finally:
        os.chdir(cwd)
    assert verified == 0, record


#: the lab's own 12 mm grasper (36 mm jaw, 7 x 26 mm pocket, pivot 6 mm behind the heel,
#: 45 degrees open) at the height and width its first refusal asked for
LAB_JAW = {"shaft_diameter_mm": 12.0, "width_mm": 9.74, "length_mm": 36.0, "thickness_mm": 5.5,
           "pin_inset_mm": -6.0, "opening_angle_deg": 45.0, "pocket_width_mm": 7.0,
           "pocket_length_mm": 26.0}
LAB_TARGETS = ["--kr-over-km", "8", "--kobj-range", "0.3", "3", "--max-grasp-force", "20",
               "--columns", "5", "--material", "CuBe-C17200-TF00"]


@pytest.mark.slow  # a whole design search
def test_the_labs_12_mm_jaw_too_low_is_refused_with_the_keys_to_write(tmp_path, capsys):
    targets = jaw_file_written([*LAB_TARGETS, "--full-scale-force", "0.099", "--jaw",
                                {**LAB_JAW, "thickness_mm": 3.2, "width_mm": 11.0}],
                               tmp_path / "lab")
    code, out = run_cli(["design", *targets, "--out", str(tmp_path / "lab"), "--json"], capsys)
    error = json.loads(out)["error"]
    assert code == 2 and error["field"] == "--jaw", error
    options = [a["option"] for a in error["alternatives"]]
    assert options[0] == "grasper_jaw.thickness_mm = 5.5 and grasper_jaw.width_mm = 9.74 in " \
                         "lab_jaw.toml" and "--jaw 10" in options, options
    assert not (tmp_path / "lab").exists()


@pytest.mark.slow
def test_the_labs_12_mm_jaw_designs_and_passes_its_check(tmp_path, capsys):
    # its open scene put the jaw into the tissue slab at 45 degrees; its pocket and shaft
    # could not be stated (0.08 N: a force its combs carry as the closed form decides; at
    # 0.099 N the best predicts 0.089 N, which no longer counts)
    designed_or_refused([*LAB_TARGETS, "--full-scale-force", "0.08", "--jaw", LAB_JAW],
                        tmp_path / "lab", capsys)
    written = (tmp_path / "lab" / "lab.toml").read_text(encoding="utf-8")
    assert "shaft_diameter_mm = 12.0" in written and "pin_inset_mm = -6.0" in written


@pytest.mark.slow
def test_a_refusals_frontier_is_the_searchs_whatever_force_was_asked(tmp_path, capsys):
    # K_r/K_m 10 over 1-5 N/mm in 7075-T6, 2 x 3: 50 N was told "at most 0.155 N", 0.3 N
    # "at most 0.183 N", yet 0.163 N designed
    case = ["design", "--kr-over-km", "10", "--kobj-range", "1", "5", "--material", "7075-T6",
            "--columns", "3", "--verify", "none", "--json"]

    def frontier(force: float) -> float:
        code, out = run_cli([*case, "--full-scale-force", f"{force:g}", "--out",
                             str(tmp_path / "x.toml")], capsys)
        assert code == 2, out
        alts = json.loads(out)["error"]["alternatives"]
        return next(float(a["option"].split()[-1]) for a in alts
                    if a["option"].startswith("--full-scale-force"))

    most = frontier(50.0)
    assert frontier(0.3) == most
    assert frontier(round(most * 1.05, 4)) == most
    code, out = run_cli([*case, "--full-scale-force", f"{most * 0.9:.4g}", "--out",
                         str(tmp_path / "y.toml")], capsys)
    assert code == 0, out
