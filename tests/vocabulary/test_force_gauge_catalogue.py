"""The force gauge catalogue: real models with their makers' range and
resolution, each naming its document."""

from __future__ import annotations

import pytest

from tactcad.vocabulary import force_gauge_catalogue as cat

from conftest import EXAMPLE_DESIGN as EXAMPLE


def test_every_gauge_names_its_document_and_reads_below_its_range():
    gauges = cat.force_gauges()
    assert len(gauges) >= 4 and "Sauter FH 5" in {g.model for g in gauges}
    for g in gauges:
        assert g.model.split()[-1] in g.source and "data sheet" in g.source
        assert 0 < g.resolution_N < g.range_N and g.stiffness_N_per_mm > 0
    assert [g.range_N for g in gauges] == sorted(g.range_N for g in gauges)


def test_a_bad_entry_is_refused_naming_model_and_field():
    with pytest.raises(ValueError, match=r"'X'.range_N = -1: allowed a number > 0"):
        cat._gauge("X", {"maker": "m", "range_N": -1, "resolution_N": 1, "stiffness_N_per_mm": 1,
                         "length_mm": 1, "width_mm": 1, "depth_mm": 1, "shaft_diameter_mm": 1,
                         "shaft_length_mm": 1, "source": "s"})
    with pytest.raises(ValueError, match="has no resolution_N"):
        cat._gauge("X", {"maker": "m", "range_N": 1})


def test_a_new_projects_rigs_quote_the_catalogues_gauge_not_the_papers_measurement():
    """The rigs file a new project gets (:func:`tactcad.project_folder.companion_texts`, what
    ``design --out DIR`` and ``new`` write) for a design whose samples need the Sauter FH 5
    (0.3 N over 2 ... 20 N/mm: a 3 N sample force) quotes the catalogue's gauge, not the
    paper's measured FH 5 (57.04 N/mm, the macro array's calibration)."""
    from tactcad.api import load
    from tactcad.mechanics.calibration import K_SENSOR_N_PER_MM
    from tactcad.project_folder import companion_texts

    for g in cat.force_gauges():
        assert g.stiffness_N_per_mm != K_SENSOR_N_PER_MM
        assert "macro" not in g.source.lower() and "paper" not in g.source.lower()
    plan = load(str(EXAMPLE), set={"requirements.kobj_range_N_per_mm": [2.0, 20.0],
                                   "requirements.full_scale_force_N": 0.3}).plan
    rigs = companion_texts(plan)["rigs"]
    assert 'model = "Sauter FH 5"' in rigs
    assert "57.04" not in rigs and "macro" not in rigs.lower() and "to be measured" in rigs


# a whole design search through the command line; the rigs it writes are
# test_a_new_projects_rigs_quote_the_catalogues_gauge_not_the_papers_measurement's (fast)
@pytest.mark.slow
def test_a_new_designs_gauge_stiffness_is_the_catalogues_not_the_papers_measurement(
        tmp_path, monkeypatch):
    # a designed project's rigs quoted "57.04 N/mm as measured ... (the macro array's
    # calibration)": the paper's own FH 5, measured in its lab
    from tactcad.cli import main
    from tactcad.mechanics.calibration import K_SENSOR_N_PER_MM

    for g in cat.force_gauges():
        assert g.stiffness_N_per_mm != K_SENSOR_N_PER_MM
        assert "macro" not in g.source.lower() and "paper" not in g.source.lower()
    monkeypatch.chdir(tmp_path)
    assert main(["design", "--kr-over-km", "5", "--kobj-range", "2", "20", "--full-scale-force",
                 "0.3", "--material", "7075-T6", "--columns", "4", "--out", "al7075",
                 "--verify", "none", "--quiet"]) == 0
    rigs = (tmp_path / "al7075" / "rigs.toml").read_text(encoding="utf-8")
    assert 'model = "Sauter FH 5"' in rigs  # the gauge the report was about
    assert "57.04" not in rigs and "macro" not in rigs.lower() and "to be measured" in rigs


def test_a_catalogue_model_typed_in_another_case_is_still_held_to_its_datasheet():
    """"mark-10  m5-05" is the Mark-10 M5-05: a range stated for another gauge fails by
    name whatever the letter case or spacing; a lab's own model is left alone."""
    from tactcad.vocabulary.force_gauge_catalogue import (catalogue_gauge, catalogue_mismatches,
                                                          force_gauges)

    gauge = force_gauges()[0]
    typed = "  ".join(gauge.model.lower().split())
    assert catalogue_gauge(typed) == gauge
    found = catalogue_mismatches(typed, gauge.range_N * 2, gauge.resolution_N)
    assert found == [f"range_N = {gauge.range_N * 2:g} N, the catalogue's {gauge.model} reads "
                     f"{gauge.range_N:g} N"]
    assert catalogue_mismatches("our own load cell", 1.0, 0.001) == []
