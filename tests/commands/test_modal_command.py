"""``tactcad modal``: every distinct element by default, one with --element,
JSON, mode shapes to VTU, bad options refused in one line."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

from conftest import run_cli

TI = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def test_every_distinct_element_and_the_lowest_first_frequency():
    done = run_cli("modal", "--design", TI, "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    parts = [r["part"] for r in out["elements"]]
    assert len(parts) == len(set(parts)) == 2  # the Ti example has two arm lengths
    assert sorted(n for r in out["elements"] for n in r["elements"]) == [1, 2, 3, 4, 5, 6]
    assert out["lowest_first_Hz"] == min(r["first_Hz"] for r in out["elements"])
    assert out["families"] == ["in-plane"]


def test_one_element_with_its_mode_shapes(tmp_path):
    done = run_cli("modal", "--element", "4", "--model", "fem2d", "--modes", "2",
                   "--vtu", tmp_path, "--json", "--quiet")
    assert done.returncode == 0, done.stderr
    (rec,) = json.loads(done.stdout)["elements"]
    assert rec["elements"] == [4] and len(rec["modes"]) == 2
    assert Path(rec["vtu"]).is_file() and Path(rec["vtu"]).parent == tmp_path
    text = run_cli("modal", "--element", "4").stdout
    assert "element_a8mm (element 4)" in text and "first out-of-plane one estimated" in text
    assert "(out-of-plane +/- " in text and "without the" in text  # the gauge installation's mass
    bare = run_cli("modal", "--element", "4", "--bare").stdout
    assert "without the gauge installation's mass" in bare and " Hz without the " not in bare


def test_bad_options_are_refused_in_one_line(tmp_path):
    for argv, words in ((["--modes", "0"], "--modes"), (["--model", "beam"], "--model"),
                        (["--element", "99"], "element"),
                        (["--vtu", str(tmp_path)], "--model fem2d or fem3d"),
                        (["--tip-mass-mg", "-3"], "--tip-mass-mg"),
                        # not finite: the refusal still gives the range
                        (["--tip-mass-mg", "nan"], "0 ... 10000 (mg)"),
                        (["--tip-mass-mg", "1e400"], "0 ... 10000 (mg)")):
        done = run_cli("modal", *argv)
        assert done.returncode == 2, argv
        assert words in done.stderr and "Traceback" not in done.stderr
        assert len(done.stderr.strip().splitlines()) == 1, done.stderr


def test_a_material_without_density_is_refused_naming_the_field(tmp_path):
    import shutil

    folder = tmp_path / "ti"
    shutil.copytree(TI.parent, folder)
    design = folder / TI.name
    text = design.read_text().replace('grade = "Ti-6Al-4V-annealed"',
                                      "youngs_modulus_MPa = 113800.0\npoisson_ratio = 0.342")
    design.write_text(text)
    done = run_cli("modal", "--design", design, "--json")
    assert done.returncode == 2
    assert json.loads(done.stdout)["error"]["field"] == "material.density_g_per_cm3"
    # the manifest's report says why it has no frequencies instead of failing the export
    from tactcad.design.array_plan import load_design
    from tactcad.studies.resonance import resonance_summary

    assert "density" in resonance_summary(load_design(design))["unavailable"]


def test_an_out_of_plane_error_above_100_percent_is_said_as_bounds(tmp_path, thin_web_designed):
    """A 17-4PH array's 0.105 mm web in a 5 mm sheet: the closed form's out-of-plane
    bounds lie a factor 6.8 apart, its error estimate 161 %, printed as "1352.9
    (out-of-plane +/- 161.4 %)"; the JSON keeps the estimate and adds the bounds, the text
    gives the bounds and the level that computes the mode."""
    shutil.copytree(thin_web_designed[0], tmp_path / "ph4")  # conftest's THIN_WEB_DESIGN
    done = run_cli("modal", "--json", cwd=tmp_path / "ph4")
    assert done.returncode == 0, done.stderr
    modes = [m for r in json.loads(done.stdout)["elements"] for m in r["modes"]]
    wide = [m for m in modes if m["frequency_Hz_error_rel"] > 1]
    assert wide and all(m["family"] == "out-of-plane" for m in wide)
    for m in wide:
        lo, hi = m["frequency_Hz_bounds"]
        e = m["frequency_Hz_error_rel"]
        assert 0 < lo < m["frequency_Hz"] < hi
        assert abs(lo * (1 + e) / m["frequency_Hz"] - 1) < 1e-9
        assert abs(hi / (1 + e) / m["frequency_Hz"] - 1) < 1e-9
    text = run_cli("modal", cwd=tmp_path / "ph4").stdout
    assert "(out-of-plane between " in text and "--model fem3d computes this mode" in text
    assert not [e for e in re.findall(r"\+/- ([\d.]+) %", text) if float(e) > 100]
    assert "(in-plane +/- " in text
