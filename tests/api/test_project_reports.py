"""A metal array's read-out, thermal drift, K_obj budget, crosstalk, grasp and tolerance Monte
Carlo from the Python API:
the same numbers as the commands' ``--json``, and refusals naming the keyword."""

from __future__ import annotations

import json

import pytest

from conftest import run_cli

import tactcad
from tactcad.design.array_plan import EXAMPLES
from tactcad.errors import DesignError

DESIGN = EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml"


def command_json(*argv: str) -> dict:
    r = run_cli(*argv, "--design", str(DESIGN), "--json")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def without_seconds(record):
    """A record less its wall times, which no two runs share, and the warnings the
    command line adds to every --json (the API raises them as Python warnings)."""
    if isinstance(record, dict):
        return {k: without_seconds(v) for k, v in record.items()
                if k not in ("seconds", "wall_time_s", "warnings")}
    if isinstance(record, list):
        return [without_seconds(v) for v in record]
    return record


@pytest.mark.parametrize("method, command, kwargs, argv", [
    ("readout", "readout", {}, ()),
    ("thermal", "thermal", {"element": 2}, ("--element", "2")),
    ("budget", "budget", {"delta_T_K": 3.0}, ("--delta-T-K", "3")),
    ("budget", "budget", {"force_N": 0.05, "delta_T_K": 3.0},
     ("--force-N", "0.05", "--delta-T-K", "3")),
    ("crosstalk", "crosstalk", {}, ()),
    ("grasp", "grasp", {}, ()),
    ("grasp", "grasp", {"force_N": 0.2, "slab_thickness_mm": 4.0, "profile": "slab"},
     ("--force-N", "0.2", "--slab-thickness-mm", "4", "--profile", "slab")),
    ("tolerance", "tolerance", {"samples": 2000}, ("--samples", "2000")),
    ("strength", "strength", {}, ()),
    ("strength", "strength", {"model": "beam"}, ("--model", "beam")),
    ("modes", "modal", {}, ()),
    ("modes", "modal", {"element": 4, "bare": True, "tip_mass_mg": 12.5},
     ("--element", "4", "--bare", "--tip-mass-mg", "12.5")),
    ("tolerance", "tolerance",
     {"samples": 2000, "seed": 3, "arm_tol": 0.05, "distribution": "uniform", "reference": 5},
     ("--samples", "2000", "--seed", "3", "--arm-tol", "0.05", "--distribution", "uniform",
      "--reference", "5")),
])
def test_the_apis_reports_are_the_commands_json(method, command, kwargs, argv):
    project = tactcad.load(str(DESIGN))
    given = getattr(project, method)(**kwargs)
    printed = command_json(command, *argv)
    assert json.loads(json.dumps(without_seconds(given))) == without_seconds(printed)


@pytest.mark.parametrize("method, kwargs, named", [
    ("budget", {"force_N": -1.0}, "force_N"),
    ("budget", {"delta_T_K": 500}, "delta_T_K"),
    ("thermal", {"element": 99}, "element"),
    ("thermal", {"element": "2"}, "element"),
    ("grasp", {"force_N": 0.0}, "force_N"),
    ("grasp", {"pivot_mm": [1.0]}, "pivot_mm"),
    ("grasp", {"pivot_mm": (400.0, 0.0)}, "pivot_mm"),  # the pin past the last tip
    ("grasp", {"pin_to_tip_mm": 1.5}, "pin_to_tip_mm"),  # short of the tips
    ("grasp", {"force_N": 0.1, "angle_deg": 3.0}, "force_N"),
    ("grasp", {"coupling": "glue"}, "coupling"),
    ("tolerance", {"samples": 1}, "samples"),
    ("tolerance", {"samples": 2000.0}, "samples"),
    ("tolerance", {"seed": -1}, "seed"),
    ("tolerance", {"kobj": [2.0, 0.0]}, "kobj"),
    ("tolerance", {"distribution": "gauss"}, "distribution"),
    ("tolerance", {"reference": 7}, "reference"),  # the design has six elements
    ("tolerance", {"samples": 2000, "reference": 1}, "reference"),  # softer than element 2
    ("tolerance", {"modulus_tol": 0.6}, "modulus_tol"),
    ("tolerance", {"samples": 2000, "arm_tol": 9.0}, "arm_tol"),  # lets the arm vanish
    ("modes", {"element": 7}, "element"),
    ("modes", {"modes": 0}, "modes"),
    ("modes", {"modes": 2.5}, "modes"),
    ("modes", {"tip_mass_mg": -1.0}, "tip_mass_mg"),
    ("modes", {"tip_mass_mg": float("nan")}, "tip_mass_mg"),
    ("modes", {"tip_mass_mg": "12"}, "tip_mass_mg"),
    ("modes", {"tip_mass_mg": 10 ** 400}, "tip_mass_mg"),
    ("modes", {"bare": "no"}, "bare"),
])
def test_the_apis_reports_refuse_naming_the_keyword(method, kwargs, named):
    project = tactcad.load(str(DESIGN))
    with pytest.raises(DesignError) as caught:
        getattr(project, method)(**kwargs)
    assert caught.value.field == named


def test_the_apis_strength_and_modes_refuse_an_unknown_level_naming_the_levels():
    from tactcad.mechanics.ladder import UnknownModelError
    from tactcad.mechanics.modal_ladder import UnknownModalModelError

    project = tactcad.load(str(DESIGN))
    with pytest.raises(UnknownModalModelError, match="closed-form, fem2d, fem3d"):
        project.modes(model="beam")
    for model in ("no-such-level", 3):
        with pytest.raises(UnknownModelError, match="closed-form, beam, fem2d, fem3d"):
            project.strength(model=model)


def test_the_apis_crosstalk_refuses_an_unknown_level_naming_the_levels():
    from tactcad.mechanics.stack_crosstalk import UnknownCrosstalkModelError, crosstalk_models

    with pytest.raises(UnknownCrosstalkModelError) as caught:
        tactcad.load(str(DESIGN)).crosstalk(model="no-such-level")
    assert "'no-such-level'" in str(caught.value)
    assert all(level in str(caught.value) for level in crosstalk_models())


COMB = EXAMPLES / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


def test_the_apis_crosstalk_answers_for_a_comb_as_the_command_does():
    comb = tactcad.load(str(COMB))
    given = comb.crosstalk()
    assert given["model"] == "comb-beam" and len(given["elements"]) == 12
    r = run_cli("crosstalk", "--design", str(COMB), "--json")
    assert r.returncode == 0, r.stderr
    assert json.loads(json.dumps(without_seconds(given))) == without_seconds(json.loads(r.stdout))
    # a stacked array's level on a comb: refused naming the keyword and the comb's levels
    with pytest.raises(DesignError) as caught:
        comb.crosstalk(model="stack-beam")
    assert caught.value.field == "model" and "comb-beam" in caught.value.allowed



def test_a_pin_past_the_last_tip_is_refused_naming_the_pin():
    """The jaw's length follows from a given pin: a pin past the last tip is the pin's
    error, not the length's the user never gave."""
    r = run_cli("grasp", "--design", str(DESIGN), "--pivot-mm", "400", "0")
    assert r.returncode == 2
    assert "--pivot-mm" in r.stderr and "--pin-to-tip-mm" not in r.stderr


def test_a_grasp_whose_leads_do_not_fit_the_channel_warns_and_does_not_pass():
    r = run_cli("grasp", "--design", str(DESIGN), "--lead-channel-mm", "0.1", "--json")
    assert r.returncode == 1, r.stderr
    record = json.loads(r.stdout)
    assert record["passed"] is False and not record["leads"]["fits"]
    assert any("lead channel" in w for w in record["warnings"])
    assert run_cli("grasp", "--design", str(DESIGN)).returncode == 0  # the default fits


def test_the_apis_numbers_take_numpys_reals_and_refuse_a_bool():
    import numpy as np

    project = tactcad.load(str(DESIGN))
    assert project.grasp(force_N=np.float32(0.2))["passed"] is True
    with pytest.raises(DesignError) as caught:
        project.grasp(force_N=True)
    assert caught.value.field == "force_N"


def test_the_metal_and_the_dies_tolerance_records_share_the_keys_of_what_both_give():
    from conftest import DIE_EXAMPLE

    metal = tactcad.load(str(DESIGN)).tolerance(samples=200, kobj=[2.0, 1000.0])
    die = tactcad.load(DIE_EXAMPLE).tolerance(samples=200)
    both = {"design", "source", "samples", "seed", "tolerances", "units", "warnings",
            "kobj_range_N_per_mm"}  # what each record says of its own design and draw
    assert both <= set(metal) and both <= set(die)
    # the glossary's name, as grasp and budget print it; the old one a declared duplicate
    for record in (metal, die):
        assert record["deprecated_keys"] == {"K_obj_range_N_per_mm": "kobj_range_N_per_mm"}
        assert record["K_obj_range_N_per_mm"] == record["kobj_range_N_per_mm"]
    lo, hi = metal["kobj_range_N_per_mm"]
    assert lo < 2.0 < hi < 1000.0  # one K_obj asked inside the range, one outside
    assert len(metal["warnings"]) == 1 and "--kobj 1000" in metal["warnings"][0]
    assert die["warnings"] == []  # the die's default K_obj lie in its range
