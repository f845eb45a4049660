"""The rigs check group: a rig that loads an element beyond the design's rated
full-scale force fails, naming the rig, the part, the load and the rating; the
force gauge must read the rigs' range to 1 % of the rating; the sample kit must
span the design's K_obj range."""

from __future__ import annotations

from pathlib import Path

import pytest

import tactcad
from tactcad.checks.groups import CHECK_GROUPS, CheckContext
from tactcad.checks.rig_checks import rig_checks, rig_group
from tactcad.design.rig_plan import default_rigs_data, rigs_from_dict

EXAMPLE = Path(__file__).resolve().parents[2] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"


def _rigs_with(project, **tables):
    from tactcad.vocabulary.schema import read_toml

    data = read_toml(EXAMPLE.parent / "rigs.toml", "rigs file")
    for table, values in tables.items():
        data[table] = {**data.get(table, {}), **values}
        if values == {}:
            data.pop(table)
    return rigs_from_dict(data, project.plan)


def test_the_group_runs_before_any_export():
    group = CHECK_GROUPS["rigs"]
    assert not group.on_export and "rated full-scale force" in group.checks


def test_the_ti_example_rigs_pass_and_the_papers_weights_on_it_fail():
    project = tactcad.load(EXAMPLE)
    context = CheckContext(project.plan, Path("."), None, project.validated)
    [(label, results)] = list(rig_group(context))
    assert label == "rigs" and all(r.passed for r in results), [r.line() for r in results]
    # the paper's rig on this design: its 3.235 N axis and three 100 g weights
    rigs = _rigs_with(project, weights={"mass_g": 100.0, "diameter_mm": 25.0, "count": 3},
                      evaluation={"preload_N": 3.235},
                      force_gauge={"model": "Sauter FH 5", "range_N": 5.0, "resolution_N": 0.001})
    load, gauge, _ = rig_checks(project.plan, rigs)
    assert not load.passed and load.check == "rig load"
    assert load.subject == "array evaluation rig: weight_100g"
    assert "6.177 N puts" in load.detail and "rated full-scale force 0.1 N" in load.detail
    assert "EXCEEDS the rating" in load.detail
    assert gauge.passed  # 1 mN is 1 % of 0.1 N: just enough


def test_a_0p077_N_design_fails_the_papers_gauge():
    values = {"requirements.full_scale_force_N": 0.077}
    project = tactcad.load(EXAMPLE, set=values)
    rigs = _rigs_with(project, force_gauge={"model": "Sauter FH 5", "range_N": 5.0,
                                            "resolution_N": 0.001})
    _, gauge, _ = rig_checks(project.plan, rigs)
    assert not gauge.passed and gauge.subject == "calibration and sample rigs: force_gauge"
    assert "resolution 0.001 N > 0.00077 N" in gauge.detail and "Mark-10" in gauge.detail


def test_a_rating_finer_than_any_catalogue_gauge_resolves_is_undecided_not_failed():
    """At 5 mN no gauge of the catalogue resolves 1 % of the rating: the rig that
    holds the finest of the needed range is undecided (the lab's call), a coarser
    one the catalogue could replace fails."""
    project = tactcad.load(EXAMPLE, set={"requirements.full_scale_force_N": 0.005})
    finest = {"model": "Mark-10 M5-012", "range_N": 0.5, "resolution_N": 0.0001}
    _, gauge, _ = rig_checks(project.plan, _rigs_with(project, force_gauge=finest))
    assert gauge.passed and gauge.undecided and "finest gauge" in gauge.detail
    coarse = {"model": "Sauter FH 5", "range_N": 5.0, "resolution_N": 0.001}
    _, gauge, _ = rig_checks(project.plan, _rigs_with(project, force_gauge=coarse))
    assert not gauge.passed and not gauge.undecided


def test_a_rig_without_its_preload_fails_naming_the_field():
    project = tactcad.load(EXAMPLE)
    rigs = _rigs_with(project, evaluation={})
    load, _, _ = rig_checks(project.plan, rigs)
    assert not load.passed and "[evaluation] preload_N is not stated" in load.detail


def test_the_papers_rig_exceeds_the_papers_rating_and_says_why_it_is_kept():
    """The paper's rig loads its elements beyond the rating tactcad derives
    for the paper's design (the 8 mm arms' fatigue limit); the check says so
    and passes only by the reason its rigs file states, which holds: every
    element stays below its yield-limited force."""
    from tactcad.paper.paper_load import strength_summary
    from tactcad.studies.rig_sizing import element_loads_per_newton

    project = tactcad.load()
    rigs = project.validated.rigs
    load, gauge, _ = rig_checks(project.plan, rigs)
    assert load.passed and gauge.passed
    assert "EXCEEDS the rating" in load.detail and "kept: the paper's evaluation rig" in load.detail
    data = default_rigs_data()
    del data["evaluation"]["beyond_rating_reason"]
    bare, _, _ = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert not bare.passed
    top = rigs.evaluation_preload_N + rigs.part("weights").count * 0.980665
    per_newton = element_loads_per_newton(project.plan, rigs.sample_stiffness_N_per_mm)
    for r in strength_summary(project.plan):
        assert top * per_newton[r["element"]] < r["yield_limited_force_N"]


def test_a_new_papers_array_edited_does_not_pass_on_the_papers_kept_overload(tmp_path):
    """A lab's `new --example macro_array`, its K_obj range and arms edited (thinner
    sheet, longer arms: a lower rating): check passed the paper's rig kept by the paper's
    reason, 234 % over the new rating. The reason keeps only the overload it was judged
    for: the check fails naming it, the values it accepted and those now."""
    import re

    from tactcad.project_folder import new_project

    made = new_project(tmp_path / "stack6", example="macro_array")
    text = made.design.read_text(encoding="utf-8")
    text = re.sub(r"kobj_range_N_per_mm = \[[^\]]*\]", "kobj_range_N_per_mm = [0.8, 6.0]", text)
    text = re.sub(r"thickness_mm = 3\.0 ", "thickness_mm = 2.5 ", text, count=1)
    text = re.sub(r"lengths_mm = \[[^\]]*\]",
                  "lengths_mm = [4.5, 5.0, 6.0, 7.0, 7.5, 6.0, 7.5, 7.0, 6.5, 5.5]", text)
    made.design.write_text(text, encoding="utf-8")
    project = tactcad.load(made.design).validated
    load = rig_checks(project.plan, project.rigs)[0]
    assert "EXCEEDS the rating" in load.detail
    assert not load.passed, load.detail
    rigs = project.rigs
    assert "beyond_rating_reason of rigs.toml" in load.detail
    assert f"judged for {rigs.beyond_rating_load_N:g} N on an element, rated " \
           f"{rigs.beyond_rating_rated_N:g} N" in load.detail
    rated = float(re.search(r"rated full-scale force ([\d.]+) N", load.detail).group(1))
    assert rated < rigs.beyond_rating_rated_N
    assert f"the rating is {rated:g} N now" in load.detail
    assert "beyond_rating_load_N = " in load.detail.split("; ")[-1]  # what to state


def test_a_kept_overload_bound_to_no_load_fails_naming_what_to_state():
    project = tactcad.load()
    data = default_rigs_data()
    del data["evaluation"]["beyond_rating_load_N"]
    load = rig_checks(project.plan, rigs_from_dict(data, project.plan))[0]
    assert not load.passed
    assert "bound to no load" in load.detail and "beyond_rating_rated_N = 0.3" in load.detail


def test_a_kept_overload_fails_once_the_load_exceeds_what_it_accepted():
    project = tactcad.load()
    data = default_rigs_data()
    data["evaluation"]["beyond_rating_load_N"] = 0.8
    load = rig_checks(project.plan, rigs_from_dict(data, project.plan))[0]
    assert not load.passed
    assert "beyond the 0.8 N it accepted" in load.detail


@pytest.mark.parametrize("value", [-1.0, "heavy"])
def test_a_bad_preload_is_refused_naming_the_field(value):
    from tactcad.errors import DesignError

    data = default_rigs_data()
    data["evaluation"]["preload_N"] = value
    with pytest.raises(DesignError, match="evaluation.preload_N"):
        rigs_from_dict(data, tactcad.load().plan)


def test_a_kit_that_no_longer_spans_the_edited_kobj_range_fails_naming_what_to_state(tmp_path):
    # `tactcad new lab2`, K_obj 20 ... 80 N/mm in its design: check passed the
    # example's 1 ... 5 N/mm samples while evaluate ran over 20 ... 80
    import re

    from tactcad.project_folder import new_project
    from tactcad.studies.design_loads import design_samples
    from tactcad.studies.verification import requirements_of

    made = new_project(tmp_path / "lab2")
    text = made.design.read_text(encoding="utf-8")
    made.design.write_text(re.sub(r"kobj_range_N_per_mm = \[[^\]]*\]",
                                  "kobj_range_N_per_mm = [20.0, 80.0]", text), encoding="utf-8")
    project = tactcad.load(made.design).validated
    assert requirements_of(project.plan).kobj_range_N_per_mm == (20.0, 80.0)
    context = CheckContext(project.plan, Path("."), None, project)
    [(label, results)] = list(rig_group(context))
    [kit] = [r for r in results if r.check == "rig sample kit"]
    assert not kit.passed
    assert kit.subject.endswith("sample_k5, sample_k2p24, sample_k1")
    assert "20 ... 80 N/mm (stated)" in kit.detail and "does not span" in kit.detail
    assert "rigs.toml [sample] stiffness_N_per_mm" in kit.detail
    suggested = sorted(design_samples(project.plan), reverse=True)
    assert "[" + ", ".join(f"{k:g}" for k in suggested) + "]" in kit.detail


def test_a_kit_suggestion_names_each_scenes_sample_to_set_and_pasted_the_kit_passes(tmp_path):
    """The suggestion said "each scene's sample_stiffness_N_per_mm one of them" without the
    key's file, table or value: it names them, and the project pasted with them loads (every
    scene's sample one of the rigs') and passes the kit."""
    import re

    from tactcad.project_folder import new_project

    made = new_project(tmp_path / "lab2")
    text = made.design.read_text(encoding="utf-8")
    made.design.write_text(re.sub(r"kobj_range_N_per_mm = \[[^\]]*\]",
                                  "kobj_range_N_per_mm = [20.0, 80.0]", text), encoding="utf-8")
    project = tactcad.load(made.design).validated
    context = CheckContext(project.plan, Path("."), None, project)
    [(_, results)] = list(rig_group(context))
    [kit] = [r for r in results if r.check == "rig sample kit"]
    assert not kit.passed
    named = dict(re.findall(r"\[scene\.([\w-]+)\] sample_stiffness_N_per_mm = ([\d.e+-]+)",
                            kit.detail))
    stating = [n for n, s in project.scenes.items() if s.sample_stiffness_N_per_mm is not None]
    assert stating and sorted(named) == sorted(stating), kit.detail
    assert "set scenes.toml [scene." in kit.detail
    samples = kit.detail.split("e.g. [")[1].split("]")[0]
    rigs_file = made.design.parent / "rigs.toml"
    table = r"(?:(?!\n\[).)*?"  # within the table: up to the next table's header
    rigs_file.write_text(re.sub(rf"(\n\[sample\]{table}\nstiffness_N_per_mm = )\[[^\]]*\]",
                                rf"\g<1>[{samples}]", rigs_file.read_text(encoding="utf-8"),
                                flags=re.S), encoding="utf-8")
    scenes_file = made.design.parent / "scenes.toml"
    scenes = scenes_file.read_text(encoding="utf-8")
    for name, value in named.items():
        scenes = re.sub(rf"(\[scene\.{re.escape(name)}\]{table}\nsample_stiffness_N_per_mm = )\S+",
                        rf"\g<1>{value}", scenes, flags=re.S)
    scenes_file.write_text(scenes, encoding="utf-8")
    pasted = tactcad.load(made.design).validated  # every scene's sample one of the kit's
    assert {n: s.sample_stiffness_N_per_mm for n, s in pasted.scenes.items()
            if n in named} == {n: float(v) for n, v in named.items()}
    [(_, results)] = list(rig_group(CheckContext(pasted.plan, Path("."), None, pasted)))
    [kit] = [r for r in results if r.check == "rig sample kit"]
    assert kit.passed, kit.detail


def test_the_designs_own_samples_span_its_range_though_cast_to_3_digits():
    # the paper's range ends at 10.01 N/mm; its own samples, to 3 digits, at 10.0
    from tactcad.studies.design_loads import design_samples

    project = tactcad.load()
    data = default_rigs_data()
    data["sample"]["stiffness_N_per_mm"] = design_samples(project.plan)
    *_, kit = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert kit.passed and kit.check == "rig sample kit"
    data["sample"]["stiffness_N_per_mm"] = design_samples(project.plan)[1:]  # the softest dropped
    *_, kit = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert not kit.passed


def _pasted(data: dict, detail: str) -> dict:
    """The rigs tables with every `[table] key = value, ...` a check's detail says to set
    pasted in (the values read as TOML, as a user pastes them into the file)."""
    import re
    import tomllib

    for table, keys in re.findall(r"\[(\w+)\] ((?:\w+ = [^,;]+(?:, |$))+)", detail):
        pasted = tomllib.loads("\n".join(keys.split(", ")))
        data[table] = {**data[table], **pasted}
    return data


def test_the_suggestions_of_one_report_pass_when_all_are_pasted_together():
    """K_obj 0.5 ... 5 N/mm at 0.122 N on the example's 1 ... 5 N/mm kit and 0.5 N gauge:
    the gauge the report names must fit the suggested kit (its softest 0.5 N/mm doubles
    the sample rig's force), not the old one, and name every key to set."""
    from tactcad.studies.rig_sizing import gauge_need
    from tactcad.vocabulary.force_gauge_catalogue import choose_force_gauge
    from tactcad.vocabulary.schema import read_toml

    project = tactcad.load(EXAMPLE, set={"requirements.kobj_range_N_per_mm": [0.5, 5.0],
                                         "requirements.full_scale_force_N": 0.122})
    data = read_toml(EXAMPLE.parent / "rigs.toml", "rigs file")
    _, gauge, kit = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert not gauge.passed and not kit.passed
    old_fit, _ = choose_force_gauge(gauge_need(0.122, data["sample"]["stiffness_N_per_mm"]))
    assert f'model = "{old_fit.model}"' not in gauge.detail  # sized for the old kit: fails again
    for key in ("model", "range_N", "resolution_N"):
        assert f"[force_gauge] {key} = " in gauge.detail or f", {key} = " in gauge.detail
    data["sample"]["stiffness_N_per_mm"] = [float(k) for k in
                                            kit.detail.split("e.g. [")[1].split("]")[0].split(", ")]
    data = _pasted(data, gauge.detail)
    results = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert all(r.passed for r in results), [r.line() for r in results]


def test_a_kit_suggestion_names_the_gauge_its_samples_need_where_the_rigs_does_not_fit_them():
    # the 0.5 N gauge reads the 1 ... 5 N/mm kit at 0.09 N (0.45 N) but not 0.5 ... 5 N/mm
    project = tactcad.load(EXAMPLE, set={"requirements.kobj_range_N_per_mm": [0.5, 5.0],
                                         "requirements.full_scale_force_N": 0.09})
    from tactcad.vocabulary.schema import read_toml

    data = read_toml(EXAMPLE.parent / "rigs.toml", "rigs file")
    _, gauge, kit = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert gauge.passed and not kit.passed
    assert "with them the force gauge needs range >= 0.9 N" in kit.detail
    data["sample"]["stiffness_N_per_mm"] = [0.5, 5.0]
    results = rig_checks(project.plan, rigs_from_dict(_pasted(data, kit.detail), project.plan))
    assert all(r.passed for r in results), [r.line() for r in results]


def test_a_catalogue_model_with_another_models_range_fails_naming_the_key():
    # `model = "Mark-10 M5-025"` pasted over the 0.5 N gauge's range and resolution
    project = tactcad.load(EXAMPLE)
    rigs = _rigs_with(project, force_gauge={"model": "Mark-10 M5-025"})
    _, gauge, _ = rig_checks(project.plan, rigs)
    assert not gauge.passed
    assert "range_N = 0.5 N, the catalogue's Mark-10 M5-025 reads 1 N" in gauge.detail
    assert "resolution_N = 0.0001 N, the catalogue's Mark-10 M5-025 reads 0.0002 N" in gauge.detail
    assert 'model = "Mark-10 M5-025", range_N = 1.0, resolution_N = 0.0002' in gauge.detail
    lab_own = _rigs_with(project, force_gauge={"model": "our lab's 0.5 N gauge"})
    assert rig_checks(project.plan, lab_own)[1].passed  # not in the catalogue: its values stand


def test_a_kit_whose_stiffer_samples_overload_the_rig_names_the_weights_to_set():
    # K_obj 5 ... 50 N/mm: the suggested, stiffer kit loads the most loaded element more
    # per newton, and the example's 4 x 5 g reach the 0.1 N rating with the old kit already
    from tactcad.vocabulary.schema import read_toml

    project = tactcad.load(EXAMPLE, set={"requirements.kobj_range_N_per_mm": [5.0, 50.0]})
    data = read_toml(EXAMPLE.parent / "rigs.toml", "rigs file")
    load, gauge, kit = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert load.passed and not kit.passed
    assert "with them the evaluation rig's top load puts" in kit.detail
    data["sample"]["stiffness_N_per_mm"] = [float(k) for k in
                                            kit.detail.split("e.g. [")[1].split("]")[0].split(", ")]
    data = _pasted(_pasted(data, kit.detail), gauge.detail)
    results = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert all(r.passed for r in results), [r.line() for r in results]


def test_an_overloading_rigs_suggested_weights_pass_when_pasted():
    project = tactcad.load(EXAMPLE)
    from tactcad.vocabulary.schema import read_toml

    data = read_toml(EXAMPLE.parent / "rigs.toml", "rigs file")
    data["weights"] = {**data["weights"], "mass_g": 100.0, "diameter_mm": 25.0, "count": 3}
    data["evaluation"] = {**data["evaluation"], "preload_N": 3.235}
    load, _, _ = rig_checks(project.plan, rigs_from_dict(data, project.plan))
    assert not load.passed and "[weights] mass_g = " in load.detail
    results = rig_checks(project.plan, rigs_from_dict(_pasted(data, load.detail), project.plan))
    assert all(r.passed for r in results), [r.line() for r in results]
