"""A designed file's reasons: each quotes the values written beside it, a changed value
says why it changed, and the correction's range check holds its ends."""

from __future__ import annotations

import math
import os
import re
import tomllib
import warnings
from contextlib import redirect_stdout
from dataclasses import replace
from io import StringIO

import pytest

from tactcad.cli import main
from tactcad.design.array_plan import DEFAULT_DESIGN, plan_from_dict, read_toml
from tactcad.in_use.kobj_budget import web_tolerance_k_change
from tactcad.mechanics.correction import CorrectionRangeWarning
from tactcad.mechanics.ladder import estimate

#: Two designs whose web, notch radius, arm height and overall length the search changes:
#: a thicker web than the base's notch radius; a stiffer material on a narrower grid.
DESIGNS = {
    "thick_web": ["--kr-over-km", "6", "--kobj-range", "5", "50", "--full-scale-force", "0.5"],
    "steel_4_columns": ["--kr-over-km", "6", "--kobj-range", "5", "50", "--full-scale-force",
                        "0.5", "--material", "17-4PH", "--columns", "4"],
}

#: The tests that read :func:`designed`, run on one xdist worker (``--dist loadgroup``): a
#: module fixture is made once per worker, and each worker ran both design searches.
ONE_WORKER = pytest.mark.xdist_group("design-reasons")

#: A dimension a reason quotes: "19.953 mm", the last of "2 x 3 mm".
_QUOTED_MM = re.compile(r"(\d+(?:\.\d+)?)\s*mm\b")


@pytest.fixture(scope="module")
def designed(tmp_path_factory):
    """{name: (written tables, printed summary)} of :data:`DESIGNS`, each run in an empty
    folder (the shipped design its base)."""
    out = {}
    for name, argv in DESIGNS.items():
        folder = tmp_path_factory.mktemp(name)
        here = os.getcwd()
        os.chdir(folder)
        try:
            printed = StringIO()
            with warnings.catch_warnings(), redirect_stdout(printed):
                warnings.simplefilter("ignore")
                assert main(["design", *argv, "--out", f"{name}.toml", "--verify", "none"]) == 0
        finally:
            os.chdir(here)
        path = folder / f"{name}.toml"
        if not path.is_file():  # a grid other than the base's is written as a project folder
            path = folder / name / f"{name}.toml"
        out[name] = (tomllib.loads(path.read_text(encoding="utf-8")), printed.getvalue())
    return out


def _value(data, key: str):
    section, _, field = key.partition(".")
    table = data.get(section)
    return table.get(field) if isinstance(table, dict) else None


def _numbers(data) -> list[float]:
    """Every number the design's tables (not its reasons) write."""
    def walk(v):
        if isinstance(v, dict):
            for k, x in v.items():
                if k != "assumptions":
                    yield from walk(x)
        elif isinstance(v, list):
            for x in v:
                yield from walk(x)
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            yield float(v)
    return list(walk(data))


@pytest.mark.slow  # two whole design searches
@ONE_WORKER
@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_every_dimension_a_reason_quotes_is_one_the_design_writes(designed, name):
    data, _ = designed[name]
    written = _numbers(data)
    for key, reason in data["assumptions"].items():
        for quoted in _QUOTED_MM.findall(reason):
            assert any(math.isclose(float(quoted), v, rel_tol=1e-9) for v in written), \
                (key, quoted, reason)
        own = _value(data, key)
        said = re.match(r"(?:tactcad design: )?(?:[Rr]aised to )?(\d+(?:\.\d+)?) mm", reason)
        if said and isinstance(own, (int, float)):  # a reason that states its value
            assert float(said.group(1)) == pytest.approx(own, rel=1e-9), (key, reason)


@pytest.mark.slow
@ONE_WORKER
@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_the_longest_arm_a_reason_quotes_is_the_written_one(designed, name):
    data, _ = designed[name]
    longest = max(data["arms"]["lengths_mm"])
    for key in ("element.arm_height_mm", "element.overall_length_mm"):
        quoted = re.search(r"longest arm \((\d+(?:\.\d+)?) mm\)", data["assumptions"].get(key, ""))
        if quoted:
            assert float(quoted.group(1)) == longest, key


@pytest.mark.slow
@ONE_WORKER
@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_a_value_the_design_changed_is_not_kept_from_the_base(designed, name):
    data, printed = designed[name]
    base = read_toml(DEFAULT_DESIGN, "design")
    changed = [key for key in data["assumptions"]
               if isinstance(_value(data, key), (int, float))
               and isinstance(_value(base, key), (int, float))
               and not math.isclose(_value(data, key), _value(base, key), rel_tol=1e-9)]
    for key in changed:
        assert not data["assumptions"][key].startswith("Kept from the base design"), key
    notch = data["element"]["notch_radius_mm"]
    marked = f"notch radius {notch:g} mm (changed)" in printed
    assert marked == ("element.notch_radius_mm" in changed)


@pytest.mark.slow
@ONE_WORKER
def test_a_notch_radius_that_follows_a_thicker_web_says_so(designed):
    data, _ = designed["thick_web"]
    el = data["element"]
    base = read_toml(DEFAULT_DESIGN, "design")["element"]
    # the case: a web thicker than the base's radius, which the radius follows
    assert el["web_thickness_mm"] > base["notch_radius_mm"]
    assert el["notch_radius_mm"] == el["web_thickness_mm"]
    assert "web" in data["assumptions"]["element.notch_radius_mm"]


def _at_t_over_r_one(design_data, web_mm: float, notch_radius_mm: float):
    data = {**design_data, "element": {**design_data["element"], "web_thickness_mm": web_mm,
                                       "notch_radius_mm": notch_radius_mm}}
    return plan_from_dict(data, source="<t/R = 1>")


@pytest.mark.parametrize("web, radius", [(0.535, 0.535), (0.3, 0.1 + 0.2), (0.1 + 0.2, 0.3)])
def test_an_element_at_t_over_r_one_is_inside_the_corrections_range(design_data, web, radius):
    plan = _at_t_over_r_one(design_data, web, radius)
    g, mat = plan.element(1).geometry, plan.material
    with warnings.catch_warnings():
        warnings.simplefilter("error", CorrectionRangeWarning)
        estimate("closed-form", g, mat)  # the range's end is inside it, to the ulp


def test_a_range_warning_at_the_web_tolerances_end_names_that_web_and_its_t_over_r(design_data):
    """An element drawn at t/R = 1 is inside the range; its web + tolerance is not, and
    the warning says it is that web, not the drawn one."""
    plan = _at_t_over_r_one(design_data, 0.535, 0.535)
    g, mat = plan.element(1).geometry, plan.material
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always", CorrectionRangeWarning)
        web_tolerance_k_change(replace(g, web_tolerance_mm=0.02), mat)
    texts = [str(w.message) for w in said if issubclass(w.category, CorrectionRangeWarning)]
    assert texts
    thick = 0.535 + 0.02
    for text in texts:
        assert f"web {thick:g} mm, drawn 0.535 mm" in text
        assert f"{thick / 0.535:.4g}, fitted" in text  # the t/R it took, then the range
