"""The K_obj budget's reading terms against the whole coupled chain: each term's perturbation
made on the coupled sample (every tip pressing), its R inverted by the coupled inversion and
the K_obj read compared with the true one. Eq. 3's slope at eq. 2's R misses these by as much
as 36 % on the paper's macro array."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tactcad.in_use import kobj_budget as kb

ROOT = Path(__file__).resolve().parents[2]
DESIGNS = {"ti": ROOT / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml",
           "grasper": ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml",
           "macro": ROOT / "hardware" / "macro_array" / "macro_array.toml"}
#: The budget against the finite difference of the coupled chain (relative).
AGREEMENT_REL = 0.02
#: Beyond this relative K_obj error a first-order term departs from the chain by more than
#: the agreement (the chain's curvature); there the slope is checked at 1 % of the size.
FIRST_ORDER_LIMIT_REL = 0.3
#: The reference force (N) where a design states none (the paper's macro array).
FORCE_N = 0.3


class Chain:
    """One design's coupled chain: R on the coupled sample of perturbed deflections or
    springs, read back by the coupled inversion."""

    def __init__(self, name: str):
        from tactcad.api import load
        from tactcad.in_use.tissue_coupling import coupled_sample
        from tactcad.mechanics.ladder import estimate
        from tactcad.mechanics.readout_chain import row_units
        from tactcad.studies.verification import calibration_gauge

        self.plan = plan = load(str(DESIGNS[name])).plan
        req = plan.raw["requirements"]
        est = {n: estimate("closed-form", g, plan.material)
               for n, g in plan.distinct_elements.items()}
        force = req.get("full_scale_force_N", FORCE_N)
        self.ctx = kb.Context(plan, "closed-form",
                              {n: e.stiffness_N_per_mm for n, e in est.items()},
                              {n: e.error_estimate_rel for n, e in est.items()}, force, 5.0,
                              force_gauge=calibration_gauge(plan))
        self.k_obj = kb.kobj_grid(tuple(req["kobj_range_N_per_mm"]), 3)
        self.sample = coupled_sample(plan)
        self.k = {s.number: self.ctx.k_of(s.number) for s in plan.slots}
        self.units = [kb.Unit(r.number, m.number) for r, m in row_units(plan, dict(self.ctx.k))]

    def op(self, unit):
        return kb.operating_point(self.ctx.k_of(unit.measuring), self.ctx.k_of(unit.reference),
                                  self.k_obj, self.ctx.force_N)

    def ratio(self, unit, k=None) -> np.ndarray:
        from tactcad.in_use.tissue_coupling import coupled_ratio

        return np.atleast_1d(coupled_ratio(self.sample, k or self.k,
                                           (unit.measuring, unit.reference), self.k_obj))

    def read_rel(self, unit, r) -> np.ndarray:
        """K_obj the coupled inversion reads from ``r`` (one per grid point) over the true."""
        from tactcad.in_use.tissue_coupling import coupled_object_stiffness

        pair = (unit.measuring, unit.reference)
        return np.array([coupled_object_stiffness(self.sample, self.k, pair, float(x))
                         for x in r]) / self.k_obj - 1.0

    def deflections(self, unit):
        """(e_m, e_r) on the coupled sample at the reference force (mm)."""
        e_r = self.ctx.force_N / self.k[unit.reference]
        return self.ratio(unit) * e_r, e_r

    def of_deflections(self, unit, de_m=0.0, de_r=0.0) -> np.ndarray:
        """The read error when e_m and e_r are off by de_m and de_r (mm), together: half
        the difference of the errors at + and - (a central difference, as first order as
        the budget; a gauge-model error of some percent bends the chain visibly)."""
        e_m, e_r = self.deflections(unit)
        return (self.read_rel(unit, (e_m + de_m) / (e_r + de_r))
                - self.read_rel(unit, (e_m - de_m) / (e_r - de_r))) / 2

    def of_springs(self, unit, scale: dict, central: bool = True) -> np.ndarray:
        """The read error when the true K of the elements in ``scale`` are that factor of
        the K the reading takes (central: half the difference of that and the opposite
        factor's)."""
        def read(sign: float) -> np.ndarray:
            true = {n: k * (1 + sign * (scale.get(n, 1.0) - 1)) for n, k in self.k.items()}
            return self.read_rel(unit, self.ratio(unit, true))

        return (read(1.0) - read(-1.0)) / 2 if central else read(1.0)


@pytest.fixture(scope="module", params=list(DESIGNS))
def chain(request):
    return Chain(request.param)


def _agrees(budget, chain_value):
    assert np.all(np.isfinite(chain_value)) and np.all(np.abs(chain_value) > 0)
    assert np.asarray(budget) == pytest.approx(np.asarray(chain_value), rel=AGREEMENT_REL)


def test_gauge_creep_through_the_coupled_chain(chain):
    for unit in chain.units:
        got = kb.gauge_creep(chain.ctx, unit, chain.op(unit))
        e_m, e_r = chain.deflections(unit)
        for creep, budget in ((kb.GAUGE_CREEP_REL, got.before),
                              (kb.COMPENSATED_CREEP_REL, got.after)):
            _agrees(budget, np.hypot(chain.of_deflections(unit, de_m=creep * e_m),
                                     chain.of_deflections(unit, de_r=creep * e_r)))


def test_gauge_hysteresis_through_the_coupled_chain(chain):
    h, _ = kb.gauge_hysteresis_rel(chain.ctx)
    for unit in chain.units:
        got = kb.gauge_hysteresis(chain.ctx, unit, chain.op(unit))
        e_m, e_r = chain.deflections(unit)
        _agrees(got.after, np.hypot(chain.of_deflections(unit, de_m=h * e_m),
                                    chain.of_deflections(unit, de_r=h * e_r)))


def test_readout_noise_and_quantisation_through_the_coupled_chain(chain):
    from tactcad.mechanics.readout_chain import element_force_resolution_N

    df = element_force_resolution_N(chain.plan)
    part = lambda n: chain.plan.element(n).geometry.part_name  # noqa: E731
    for unit in chain.units:
        got = kb.readout_noise(chain.ctx, unit, chain.op(unit)).after
        d_m = df[part(unit.measuring)]["dF"] / chain.k[unit.measuring]
        d_r = df[part(unit.reference)]["dF"] / chain.k[unit.reference]
        _agrees(got, np.hypot(chain.of_deflections(unit, de_m=d_m),
                              chain.of_deflections(unit, de_r=d_r)))


def test_gauge_model_through_the_coupled_chain(chain):
    """A 2.6 % strain error reads K_obj some 90 % off on the macro array's stiffest-ratio
    units at 2.34 N/mm: there the first-order term is checked on 1 % of it, scaled up."""
    err = kb.gauge_model_error_rel(chain.plan, "closed-form")
    part = lambda n: chain.plan.element(n).geometry.part_name  # noqa: E731
    for unit in chain.units:
        got = kb.gauge_model(chain.ctx, unit, chain.op(unit)).before
        e_m, e_r = chain.deflections(unit)

        def through_chain(size: float) -> np.ndarray:
            return np.hypot(
                chain.of_deflections(unit, de_m=size * err[part(unit.measuring)] * e_m),
                chain.of_deflections(unit, de_r=size * err[part(unit.reference)] * e_r)) / size

        full = through_chain(1.0)
        _agrees(got, np.where(full < FIRST_ORDER_LIMIT_REL, full, through_chain(0.01)))


def test_calibration_through_the_coupled_chain(chain):
    se = kb._calibration_stderr(chain.ctx)
    for unit in chain.units:
        got = kb.calibration(chain.ctx, unit, chain.op(unit)).after
        (km, kvm), (kr, kvr) = se[unit.measuring], se[unit.reference]
        e_m, e_r = chain.deflections(unit)
        parts = [chain.of_deflections(unit, de_m=kvm * e_m),
                 chain.of_deflections(unit, de_r=kvr * e_r),
                 chain.of_springs(unit, {unit.measuring: 1 + km}),
                 chain.of_springs(unit, {unit.reference: 1 + kr})]
        _agrees(got, np.sqrt(sum(p ** 2 for p in parts)))


def test_thermal_zero_through_the_coupled_chain(chain):
    from tactcad.mechanics.thermal_drift import thermal_report

    class Needs:
        full_scale_force_N = chain.ctx.force_N
        kobj_range_N_per_mm = (float(chain.k_obj[0]), float(chain.k_obj[-1]))

    f = {r["element"]: r["apparent_force_N_per_K"]
         for r in thermal_report(chain.plan, Needs()).records}
    if not any(f.values()):
        pytest.skip("a dummy gauge: no thermal zero")
    dT = chain.ctx.delta_T_K
    for unit in chain.units:
        got = kb.thermal_zero(chain.ctx, unit, chain.op(unit)).after
        want = chain.of_deflections(unit, de_m=f[unit.measuring] * dT / chain.k[unit.measuring],
                                    de_r=f[unit.reference] * dT / chain.k[unit.reference])
        assert got == pytest.approx(want, rel=AGREEMENT_REL)


def test_crosstalk_through_the_coupled_chain(chain):
    term = kb._crosstalk(chain.ctx)  # the comb's at comb-beam, the stack's at stack-timoshenko
    numbers, per_newton = term.numbers, term.per_newton
    if not np.any(per_newton):
        pytest.skip("no crosstalk model for this construction")
    for unit in chain.units:
        op = chain.op(unit)
        got = kb.crosstalk(chain.ctx, unit, op).before
        k = np.array([chain.k[n] for n in numbers])
        seen = per_newton @ (k[:, None] * op.k_obj * op.travel / (k[:, None] + op.k_obj))
        i_m, i_r = numbers.index(unit.measuring), numbers.index(unit.reference)
        want = chain.of_deflections(unit, de_m=seen[i_m] / chain.k[unit.measuring],
                                    de_r=seen[i_r] / chain.k[unit.reference])
        # the smallest crosstalk is a few 1e-6 of K_obj: the inversion's last bits count
        assert got == pytest.approx(np.abs(want), rel=AGREEMENT_REL, abs=1e-8)


def test_thermal_span_is_the_same_through_the_coupled_chain(chain):
    from tactcad.mechanics.thermal_drift import spring_stiffness_scale, thermal_setting

    s = spring_stiffness_scale(thermal_setting(chain.plan), chain.ctx.delta_T_K)
    for unit in chain.units[:2]:
        got = kb.thermal_span(chain.ctx, unit, chain.op(unit)).after
        want = chain.of_springs(unit, {n: s for n in chain.k}, central=False)
        assert got == pytest.approx(want, rel=1e-6)


def test_eq3s_slope_misses_the_macro_arrays_creep():
    """The review's case: unit 1/3 of the macro array at 2.34 N/mm read 0.36 % by eq. 3's
    slope against 0.57 % through the coupled chain; the budget now gives the latter."""
    chain = Chain("macro")
    unit = kb.Unit(1, 3)
    op = chain.op(unit)
    got = kb.gauge_creep(chain.ctx, unit, op).after
    e_m, e_r = chain.deflections(unit)
    c = kb.COMPENSATED_CREEP_REL
    want = np.hypot(chain.of_deflections(unit, de_m=c * e_m),
                    chain.of_deflections(unit, de_r=c * e_r))
    p = kb.eq3_partials(op)
    eq3 = np.hypot(p["de_m"] * c * op.e_m, p["de_r"] * c * op.e_r) / op.k_obj
    assert np.all(want > 1.3 * eq3)
    assert got == pytest.approx(want, rel=AGREEMENT_REL)
