"""The grasp's tissue on a stated base: the grasper example under its wedge, each unit's
K_obj bias on a bonded base against an independent bonded-base punch model's, the base
read from the design's ``[tissue_slab]`` and named in the record."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from tactcad.design.array_plan import load_design, plan_from_dict
from tactcad.in_use.grasp_experiment import (DEFAULT_TISSUE_BASE, TISSUE_POISSON_RATIO,
                                             default_jaw, grasp, tips_as_laid_out,
                                             tissue_base_of)
from tactcad.mechanics.contact import BASES, unit_punch_compliance
from tactcad.mechanics.evaluation import ladder_stiffness_by_element
from tactcad.mechanics.readout_chain import row_units
from tactcad.partlib import tissue_slab

GRASPER = Path(__file__).parents[2] / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"
#: A review's K_obj bias per unit, inner to outer (%), of the grasper example under its
#: wedge (K_obj 1 N/mm, the default grasp force) from a bonded-base punch model of its
#: own (nu 0.5), each unit on its local wedge thickness.
REVIEW_BONDED_BIAS_PCT = (-7.87, -4.79, 0.72, 6.16, 10.74, 14.28)


def example():
    plan = load_design(str(GRASPER))
    k = ladder_stiffness_by_element(plan)
    units = [(r.number, m.number)
             for r, m in row_units(plan, {s.geometry.part_name: k[s.number] for s in plan.slots})]
    return plan, k, units


def test_the_bonded_base_reads_each_unit_as_the_reviews_bonded_model_within_2_points():
    plan, k, units = example()
    assert tissue_base_of(plan) == DEFAULT_TISSUE_BASE == "bonded"
    rated = 0.05
    g = grasp(plan, default_jaw(plan), k, units, 1.0, rated, profile="wedge",
              force_N=0.5 * rated * len(plan.slots), tissue_base="bonded")
    read = sorted(g.as_laid_out.units, key=lambda u: u["r_reference_mm"])
    bias_pct = [100 * u["error_rel"] for u in read]
    assert bias_pct == pytest.approx(REVIEW_BONDED_BIAS_PCT, abs=2.0)
    assert g.as_json()["tissue_base"] == "bonded" and "bonded" in g.notes["base"]


def test_on_the_thinnest_tissue_a_bonded_base_couples_the_units_tips_more_than_steinbrenner():
    """The innermost unit's two tips on its 0.576 mm of tissue: the review's coupling
    C12/C11 is -0.088 on a bonded base against -0.058 by Steinbrenner's approximation (an
    incompressible layer gripped at its base bulges beside a pressed tip)."""
    plan, k, units = example()
    tips = tips_as_laid_out(plan, default_jaw(plan), k)
    ref, meas = units[0]
    faces = [tips.punches[tips.labels.index(n)] for n in (ref, meas)]
    coupling = {base: unit_punch_compliance(faces, TISSUE_POISSON_RATIO, 0.576, base)
                for base in ("bonded", "steinbrenner")}
    kappa = {base: c[0, 1] / c[0, 0] for base, c in coupling.items()}
    assert kappa["bonded"] == pytest.approx(-0.088, abs=0.01)
    assert kappa["steinbrenner"] == pytest.approx(-0.058, abs=0.01)


def test_the_design_states_its_tissues_base_and_the_grasp_names_it():
    data = tomllib.loads(GRASPER.read_text(encoding="utf-8"))
    # one default and one set of words, named by the part and solved by the contact model
    assert tissue_slab.DEFAULT_BASE == DEFAULT_TISSUE_BASE and tissue_slab.BASES == BASES
    plan = plan_from_dict({**data, "tissue_slab": {**data.get("tissue_slab", {}),
                                                   "base": "frictionless"}})
    assert tissue_base_of(plan) == "frictionless"
    bare = plan_from_dict({key: v for key, v in data.items()
                           if key not in ("grasper_jaw", "assumptions")})
    assert tissue_base_of(bare) == DEFAULT_TISSUE_BASE  # no grasper stated: the default


def test_a_frictionless_base_is_softer_than_a_bonded_one_under_the_same_tip():
    plan, k, _ = example()
    face = tips_as_laid_out(plan, default_jaw(plan), k).punches[:1]
    c = [unit_punch_compliance(face, TISSUE_POISSON_RATIO, 0.576, b)[0, 0]
         for b in ("bonded", "steinbrenner", "frictionless")]
    assert c[0] < c[1] < c[2] and np.isfinite(c).all()


def test_verifys_grasp_row_names_the_base_and_judges_on_the_slab():
    from tactcad.studies.verification import (element_figures, max_grasp_force_record,
                                              requirements_of)

    plan = load_design(str(GRASPER))
    fig = element_figures(plan)
    row = max_grasp_force_record(plan, fig, requirements_of(plan, fig))
    assert row["grasp"]["tissue_base"] == "bonded" and row["grasp"]["profile"] == "slab"
    assert "slab on a bonded base" in row["binding_words"]
