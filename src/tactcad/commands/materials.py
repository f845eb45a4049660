"""``tactcad materials``: the material grades and strain gauges of the library."""

from __future__ import annotations

import argparse

from tactcad.commands import add_output_args
from tactcad.commands.finite_json import dumps


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "materials", help="list the material grades and strain gauges a design may name",
        description="The library behind [material] grade and [strength] gauge: each grade's "
                    "Young's modulus (MPa), Poisson ratio, yield and fatigue strength (MPa, with "
                    "cycles and stress ratio), density (g/cm^3) and the document each value "
                    "comes from; each gauge's resistance, gauge factor and strain limits. A "
                    "design names a grade exactly, without regard to case or by a prefix only "
                    "one grade has.")
    add_output_args(p, "print one JSON object: grades and gauges")
    p.set_defaults(func=run)


def library() -> dict:
    """The library as JSON-ready records."""
    from tactcad.vocabulary.material_library import material_grades, strain_gauges
    from tactcad.vocabulary.process import ELEMENT_PROCESS

    grades = [{"grade": g.name, "description": g.description,
               "youngs_modulus_MPa": g.youngs_modulus_MPa, "poisson_ratio": g.poisson_ratio,
               "yield_strength_MPa": g.yield_strength_MPa,
               "ultimate_strength_MPa": g.ultimate_strength_MPa,
               "fatigue_datum_MPa": g.fatigue_datum_MPa,
               "fatigue_datum_stress": g.fatigue_datum_stress, "fatigue_cycles": g.fatigue_cycles,
               "fatigue_R_ratio": g.fatigue_R_ratio, "fatigue_specimen": g.fatigue_specimen,
               "fatigue_strength_MPa": g.fatigue_strength_MPa,
               "wire_edm_surface_factor": ELEMENT_PROCESS.surface.factor(g.ultimate_strength_MPa),
               "density_g_per_cm3": g.density_g_per_cm3,
               "cte_ppm_per_K": g.cte_ppm_per_K,
               "youngs_modulus_tc_per_K": g.youngs_modulus_tc_per_K,
               "sources": dict(g.sources), "unsourced": dict(g.unsourced)}
              for g in material_grades().values()]
    gauges = [{"gauge": g.name, "description": g.description, "alloy": g.alloy,
               "resistance_ohm": g.resistance_ohm, "gauge_factor": g.gauge_factor,
               "bridge": g.bridge, "max_strain": g.max_strain, "fatigue_strain": g.fatigue_strain,
               "fatigue_cycles": g.fatigue_cycles, "sources": dict(g.sources)}
              for g in strain_gauges().values()]
    return {"grades": grades, "gauges": gauges}


def run(args: argparse.Namespace) -> int:
    lib = library()
    if args.json:
        print(dumps(lib, indent=1))
        return 0
    print("| grade | E MPa | nu | yield MPa | ultimate MPa | fatigue datum MPa (stress, R, "
          "cycles) | fully reversed MPa | wire-EDM k_a | density g/cm^3 | CTE ppm/K | "
          "dE/E dT 1/K | description |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for g in lib["grades"]:
        print(f"| {g['grade']} | {g['youngs_modulus_MPa']:g} | {g['poisson_ratio']:g} | "
              f"{g['yield_strength_MPa']:g} | {g['ultimate_strength_MPa']:g} | "
              f"{g['fatigue_datum_MPa']:g} ({g['fatigue_datum_stress']}, R {g['fatigue_R_ratio']:g}, "
              f"{g['fatigue_cycles']:.0e}) | {g['fatigue_strength_MPa']:.4g} | "
              f"{g['wire_edm_surface_factor']:.2f} | "
              f"{g['density_g_per_cm3']:g} | {g['cte_ppm_per_K']:g} | "
              f"{g['youngs_modulus_tc_per_K']:.3g}"
              f"{' (unsourced)' if 'youngs_modulus_tc_per_K' in g['unsourced'] else ''} | "
              f"{g['description']} |")
    print()
    print("| gauge | ohm | GF | max strain | fatigue strain (cycles) | description |")
    print("| --- | --- | --- | --- | --- | --- |")
    for g in lib["gauges"]:
        print(f"| {g['gauge']} | {g['resistance_ohm']:g} | {g['gauge_factor']:g} | "
              f"{g['max_strain']:g} | {g['fatigue_strain']:g} ({g['fatigue_cycles']:.0e}) | "
              f"{g['description']} |")
    print()
    print("sources: tactcad materials --json")
    return 0
