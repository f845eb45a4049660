"""A requirement the lab never stated (a K band the design file leaves out, a K_obj
resolution derived from the very prediction it is tested against) is reported, not judged:
one convention in every output that shows it. Verify's matrix and its JSON say verdict
``info`` with no target, no margin and no pass; ``check`` says INFO, status ``info``, not
counted as passed, a ``<skipped>`` of type ``info`` in JUnit; the review page INFO with
``not stated`` and ``n/a``; ``tolerance --json``'s ``k_tolerance_check`` verdict ``info``. A
value the design file carries, even one ``tactcad design`` wrote from its own prediction,
stays judged: it guards later edits."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from tactcad import cli
from tactcad.checks.check_result import counts_text, status_counts
from tactcad.checks.junit import junit_report
from tactcad.checks.review_results import checks_script
from tactcad.design.array_plan import default_design_data, plan_from_dict
from tactcad.design.requirements_section import DERIVED_BY_DESIGN
from tactcad.export.review_page import verification_row
from tactcad.studies.verification import (UNREADABLE_RESOLUTION_REL, Requirements,
                                          matrix_passed, matrix_table, requirements_of,
                                          verification_matrix)

#: The rows of the paper's design (which states neither a K band nor a K_obj resolution)
#: reported, not judged.
UNSTATED = ("k_tolerance_rel", "k_tolerance_rel_toleranced", "kobj_resolution_rel")
MACRO = Path(__file__).resolve().parents[2] / "hardware" / "macro_array" / "macro_array.toml"


@pytest.fixture(scope="module")
def records():
    plan = plan_from_dict(default_design_data())
    return {r["requirement"]: r for r in verification_matrix(plan, "closed-form")}


def test_a_row_the_lab_never_stated_has_verdict_info_no_target_no_margin_no_pass(records):
    for key in UNSTATED:
        r = records[key]
        assert r["verdict"] == "info" and r["informational"], key
        assert r["pass"] is None and r["target"] is None and r["margin_rel"] is None, key
        assert r["reference_value"] > 0 and r["predicted"] > 0, key
        assert not r["stated"]
    assert records["full_scale_force_N"]["verdict"] in ("pass", "fail", "undecided")
    assert matrix_passed(list(records.values())) == all(
        r["verdict"] != "fail" for r in records.values())
    table = matrix_table(list(records.values())).splitlines()
    for key in UNSTATED:
        row = next(line for line in table if line.startswith(f"| {key} |"))
        cells = [c.strip() for c in row.split("|")[1:-1]]
        assert cells[1] == "not stated" and cells[4] == "n/a" and cells[6] == "INFO", row


def test_verify_json_says_info_with_null_target_margin_and_pass(capsys):
    assert cli.main(["verify", "--design", str(MACRO), "--model", "closed-form",
                     "--json"]) in (0, 1)
    rows = {r["requirement"]: r for r in json.loads(capsys.readouterr().out)["matrix"]}
    for key in UNSTATED:
        assert rows[key]["verdict"] == "info", key
        assert rows[key]["target"] is None and rows[key]["margin_rel"] is None, key
        assert rows[key]["pass"] is None and rows[key]["informational"] is True, key


def test_check_reports_info_neither_passed_nor_failed_and_junit_skips_it(records):
    from tactcad.checks.requirement_checks import requirement_check

    found = [requirement_check(records[key]) for key in UNSTATED]
    found.append(requirement_check(records["kr_over_km"]))
    for r in found[:3]:
        assert r.status == "info" and r.passed and r.line().split()[0] == "INFO"
        assert "target" not in r.detail and "margin" not in r.detail
        assert r.detail.startswith("info: not stated, not judged")
    counts = status_counts(found)
    judged = found[3].status
    assert counts["info"] == 3 and counts["passed"] == (judged == "pass")
    assert counts_text(counts).endswith(", 3 info")
    xml = junit_report([("requirements", found)], [])
    root = ET.fromstring(xml)
    assert root.get("failures") == ("1" if judged == "fail" else "0")
    for case in root.iter("testcase"):
        if case.get("name").split(": ")[1] in UNSTATED:
            skipped = case.find("skipped")
            assert skipped is not None and skipped.get("type") == "info"
            assert skipped.get("message").startswith("INFO")
    page = json.loads(checks_script("abc", [("requirements", found)])
                      .removeprefix("window.TACTCAD_CHECKS = ").rstrip().rstrip(";"))
    assert page["info"] == 3 and page["passed"] == counts["passed"]
    assert [c["status"] for c in page["checks"]][:3] == ["info"] * 3
    # neither passed nor failed: the page's rows say so as verify's JSON does
    assert [c["passed"] for c in page["checks"]][:3] == [None] * 3
    assert page["checks"][3]["passed"] is (judged != "fail")


def test_check_json_rows_reported_not_judged_have_passed_null():
    from tactcad.checks.check_result import CheckResult, reported_passed

    assert reported_passed(CheckResult("requirement", "k_tolerance_rel", True, info=True)) is None
    assert reported_passed(CheckResult("requirement", "kr_over_km", True, undecided=True))
    assert reported_passed(CheckResult("requirement", "kr_over_km", False)) is False


def test_check_failures_only_leaves_info_out():
    from tactcad.commands.check import SHOWN_IN_FULL_ONLY

    assert "info" in SHOWN_IN_FULL_ONLY and "undecided" not in SHOWN_IN_FULL_ONLY


def test_the_review_page_shows_info_with_no_target_and_no_margin(records):
    for key in UNSTATED:
        row = verification_row(records[key])
        assert (row["verdict"], row["target"], row["margin"]) == ("INFO", "not stated", "n/a")
    # a manifest written before: the row judged against the design's own padded band
    old = {"requirement": "k_tolerance_rel", "target": 0.14, "predicted": 0.1285,
           "error_estimate_rel": 0.074, "margin_rel": 0.09, "model": "closed-form",
           "pass": True, "verdict": "pass", "informational": True}
    row = verification_row(old)
    assert (row["verdict"], row["target"], row["margin"]) == ("INFO", "not stated", "n/a")


def test_tolerance_k_band_check_says_info_when_the_band_is_not_stated(capsys):
    from tactcad.commands.tolerance import print_check
    from tactcad.studies.project_reports import k_tolerance_check

    band = {"requirement": "k_tolerance_rel", "target": 0.14, "predicted_band_rel": 0.09254,
            "worst_element": 7, "pass": True, "tighten": []}
    info = k_tolerance_check(band, stated=False)
    assert info["verdict"] == "info" and info["stated"] is False
    assert info["target"] is None and info["pass"] is None and info["reference_value"] == 0.14
    judged = k_tolerance_check(band, stated=True)
    assert judged["verdict"] == "pass" and judged["target"] == 0.14 and judged["pass"] is True
    assert k_tolerance_check({**band, "pass": False}, stated=True)["verdict"] == "fail"
    print_check({}, info)
    said = capsys.readouterr().out
    assert "reported, not judged" in said and "14 %" in said and "holds" not in said


def test_a_k_obj_resolution_design_wrote_from_its_prediction_stays_judged():
    """The value guards later edits: judged (here failed: a resolution no design reaches),
    its reason saying so."""
    from tactcad.studies.verification import GUARDS_LATER_EDITS

    data = default_design_data()
    data["requirements"] = {**data.get("requirements", {}), "kobj_resolution_rel": 0.0001}
    data["assumptions"] = {**data.get("assumptions", {}), "requirements.kobj_resolution_rel":
                           f"{DERIVED_BY_DESIGN}: the worst K_obj resolution, padded."}
    plan = plan_from_dict(data)
    req = requirements_of(plan)
    assert "kobj_resolution_rel" in req.written and "kobj_resolution_rel" not in req.stated
    assert req.reasons["kobj_resolution_rel"].startswith(DERIVED_BY_DESIGN)
    assert req.reasons["kobj_resolution_rel"].endswith(GUARDS_LATER_EDITS)
    assert "guards later edits" in GUARDS_LATER_EDITS
    row = next(r for r in verification_matrix(plan, "closed-form", reported=False)
               if r["requirement"] == "kobj_resolution_rel")
    assert row["verdict"] == "fail" and row["target"] == 0.0001 and row["pass"] is False
    assert not row.get("informational")


def test_a_derived_resolution_stopped_at_the_largest_a_design_may_state_stays_judged():
    from tactcad.studies.verification import informational_requirements

    def req(resolution, written=frozenset()):
        return Requirements(full_scale_force_N=1.0, kobj_range_N_per_mm=(1.0, 2.0),
                            kr_over_km=10.0, k_tolerance_rel=0.1,
                            kobj_resolution_rel=resolution, written=written)

    assert "kobj_resolution_rel" in informational_requirements(req(0.02))
    # a design reading worse than the largest a design may state fails it
    assert "kobj_resolution_rel" not in informational_requirements(
        req(UNREADABLE_RESOLUTION_REL))
    written = informational_requirements(req(0.02, frozenset({"kobj_resolution_rel",
                                                              "k_tolerance_rel"})))
    assert written == frozenset()


def test_the_apis_verification_lists_the_info_rows_apart_from_the_judged(tmp_path):
    import tactcad

    v = tactcad.load(MACRO).verify(model="closed-form", cache=tmp_path / "store")
    assert sorted(v.info) == sorted(UNSTATED)
    assert not set(v.info) & set(v.failed + v.undecided)
    assert v.passed == (not v.failed)
