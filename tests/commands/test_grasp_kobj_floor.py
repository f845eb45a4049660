"""``tactcad grasp --kobj`` far below any tissue: ``--kobj 1e-300`` ended in a
ZeroDivisionError (a unit's true K_obj, the geometric mean of its two tips', underflowed to
0) on the comb, the die and through the API, and ``--kobj 1e-30`` printed round-off as
readings (1e-15 N/mm read against 1e-30). The grasp takes the K_obj a design file's range
may state, 1e-06 ... 10000 N/mm, on every construction and in the API, and refuses the rest
naming the option (the API: the keyword), the value and that range."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from conftest import DIE_EXAMPLE, run_cli

ROOT = Path(__file__).resolve().parents[2]
COMB = ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
TI = ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
SOFT = ["1e-300", "1e-200", "1e-30", "5e-7"]


def _range() -> str:
    from tactcad.design.requirements_section import MAX_KOBJ_N_PER_MM, MIN_KOBJ_N_PER_MM

    return f"{MIN_KOBJ_N_PER_MM:g} ... {MAX_KOBJ_N_PER_MM:g}"


@pytest.mark.parametrize("kobj", SOFT)
@pytest.mark.parametrize("design", [COMB, DIE_EXAMPLE], ids=["comb", "die"])
def test_a_kobj_too_soft_to_read_is_refused_naming_the_option_and_range(design, kobj, tmp_path):
    folder = tmp_path / design.stem
    folder.mkdir()
    (folder / design.name).write_bytes(design.read_bytes())
    r = run_cli("grasp", "--kobj", kobj, cwd=folder)
    assert r.returncode == 2, r.stdout + r.stderr
    assert "Traceback" not in r.stderr and "ZeroDivisionError" not in r.stderr
    assert f"--kobj: '{kobj}': allowed a number {_range()} (N/mm)" in r.stderr
    j = run_cli("grasp", "--kobj", kobj, "--json", cwd=folder)
    error = json.loads(j.stdout)["error"]
    assert j.returncode == 2 and error["field"] == "--kobj" and error["value"] == kobj


@pytest.mark.parametrize("kobj", [1e-300, 1e-200, 1e-30])
@pytest.mark.parametrize("design", [COMB, DIE_EXAMPLE], ids=["comb", "die"])
def test_the_api_refuses_a_kobj_too_soft_by_its_keyword(design, kobj):
    import tactcad
    from tactcad.errors import DesignError

    with pytest.raises(DesignError) as exc:
        tactcad.load(design).grasp(kobj=kobj)
    assert exc.value.field == "kobj" and exc.value.value == kobj
    assert _range() in exc.value.allowed and "--" not in str(exc.value)


def test_the_grasp_itself_refuses_a_kobj_too_soft_not_dividing_by_zero():
    """Below the commands and the API: the grasp and the die's grasp refuse the field, which
    a command names as its --kobj (it was a ZeroDivisionError past the option's check)."""
    import argparse

    from tactcad.commands.options import grasp_option_error
    from tactcad.errors import DesignError
    from tactcad.in_use.grasp_experiment import check_kobj, design_grasp_at_force
    from tactcad.products.silicon_die.design.die_mount import die_mount
    from tactcad.products.silicon_die.in_use.die_grasp import die_grasp, die_jaw
    from tactcad.studies.verification import requirements_of
    from tactcad.api import load

    plan = load(TI).plan
    with pytest.raises(DesignError) as exc:  # the design's own grasp, its range's mean
        design_grasp_at_force(plan, 0.1, requirements_of(plan).full_scale_force_N,
                              (1e-300, 1e-300))
    assert exc.value.field == "k_obj_N_per_mm"
    for k in (1e-300, 1e-200, 0.0, -1.0, float("nan"), 2e4):
        with pytest.raises(DesignError) as exc:
            check_kobj(k)
        assert exc.value.field == "k_obj_N_per_mm"
        named = grasp_option_error(exc.value, argparse.Namespace(kobj=k))
        assert named.field == "--kobj" and _range() in named.allowed
    die = load(DIE_EXAMPLE).plan
    mount = die_mount(die, {})
    with pytest.raises(DesignError) as exc:
        die_grasp(die, mount, die_jaw(mount, mount.opening_angle_deg), 1e-300, angle_deg=0.0)
    assert exc.value.field == "k_obj_N_per_mm" and _range() in exc.value.allowed


def test_the_softest_kobj_taken_reads_above_round_off():
    """At the floor the tissue is still far above the elements' rounding: uncoupled (eq. 1
    exact), each corrected reading is the true K_obj to 1e-8."""
    import tactcad

    d = tactcad.load(TI).grasp(kobj=1e-6, coupling="none")
    units = [u for u in d["as_laid_out"]["units"] if u["error_corrected_rel"] is not None]
    assert units and all(abs(u["error_corrected_rel"]) < 1e-8 for u in units)
