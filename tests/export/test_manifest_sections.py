"""The manifest's sections come from registries: its own (parts, strength,
requirements ...) and each export kind's (the DXF kind's ``shop``); a new
section is one registration, a taken key is refused."""

from __future__ import annotations

import warnings

import pytest

from tactcad.design.array_plan import EXAMPLES, load_design, plan_from_dict, with_overrides
from tactcad.export import kinds, manifest
from tactcad.export.manifest import (HEAD, MANIFEST_SECTIONS, ManifestSection, design_facts,
                                     register_section)
from tactcad.vocabulary.schema import read_toml

TI = str(EXAMPLES / "ti_array_2x3" / "ti_array_2x3.toml")
#: The Ti example's sections: no maximum grasp force stated, so no grasp section (a
#: section with nothing to say is left out).
KEYS = ["parts", "assemblies", "strength", "requirements", "thermal", "kobj_budget",
        "tissue_coupling", "derived", "assumptions", "stated"]


def front_matter(plan) -> str:
    return f"{plan.name}: {len(plan.slots)} elements"


def test_the_manifest_keeps_its_keys_in_order_and_adds_the_shop():
    facts = design_facts(load_design(TI))
    assert list(facts) == list(HEAD) + KEYS + ["shop"]
    assert facts["shop"]["element_a6p196mm"]["process"] == "wire-edm"


def test_an_arrays_manifest_names_its_product_as_a_dies_does():
    # one layout for every product's manifest: a script reads "product" from each
    from tactcad.products import products

    facts = design_facts(load_design(TI))
    default = next(p.name for p in products() if p.is_default)
    assert list(facts)[:2] == ["design", "product"] and facts["product"] == default


def test_a_registered_section_and_a_kind_section_appear(monkeypatch):
    monkeypatch.setattr(manifest, "MANIFEST_SECTIONS", dict(MANIFEST_SECTIONS))
    register_section(ManifestSection("summary", f"{__name__}:front_matter"))
    plan = load_design(TI)
    design_facts.cache_clear()
    try:
        facts = design_facts(plan)
    finally:
        design_facts.cache_clear()
    assert facts["summary"] == "ti_array_2x3: 6 elements"
    dxf = kinds.EXPORT_KINDS["dxf"]
    assert dxf.manifest_section[0] == "shop" and list(facts)[-1] == "shop"


def test_the_facts_are_kept_in_the_store_and_a_new_section_is_not_missed(monkeypatch,
                                                                        tmp_path):
    from tactcad.store import Store, counting_results, keeping_results

    plan = load_design(TI)
    design_facts.cache_clear()
    try:
        with keeping_results(Store(tmp_path)), counting_results() as first:
            kept = design_facts(plan)
        design_facts.cache_clear()
        with keeping_results(Store(tmp_path)), counting_results() as again:
            assert design_facts(plan) == kept  # a later run: read back, nothing solved
        assert first.computed["manifest facts"] == 1 and again.solved() == 0
        monkeypatch.setattr(manifest, "MANIFEST_SECTIONS", dict(MANIFEST_SECTIONS))
        register_section(ManifestSection("summary", f"{__name__}:front_matter"))
        design_facts.cache_clear()
        with keeping_results(Store(tmp_path)):
            assert design_facts(plan)["summary"] == "ti_array_2x3: 6 elements"
    finally:
        design_facts.cache_clear()


@pytest.mark.parametrize("key", ["parts", "files", "design"])
def test_a_taken_key_is_refused(key):
    with pytest.raises(ValueError, match="registered already"):
        register_section(ManifestSection(key, f"{__name__}:front_matter"))


@pytest.mark.slow  # a whole chain through the command line or an export
def test_the_shop_section_states_the_etch_compensation_with_its_source():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plan = plan_from_dict(with_overrides(read_toml(TI, "design file"), {
            "element.process": "photochemical-etching", "sheet.thickness_mm": 0.3,
            "element.web_tolerance_mm": 0.045, "readout.grid_width_mm": 0.3}))
        shop = design_facts(plan)["shop"]
    element = shop["element_a6p196mm"]
    comp = element["figures"]["compensation_per_side_mm"]
    assert element["process"] == "photochemical-etching"
    assert comp["value_mm"] == pytest.approx(0.06) and "etch factor" in comp["rule"]
    assert "Kohken" in comp["source"]
    assert element["tabs"]["count"] == 0 and element["cut_order"] == []
    assert shop["spacer"]["process"] == "wire-edm" and shop["spacer"]["tabs"]["count"] > 0
