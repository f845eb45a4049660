"""``tactcad check --junit FILE``: one test case per check, grouped by part,
sheet, array and scene, a failed check a ``<failure>``; valid against the
essentials of the JUnit schema (tests/data/junit_essentials.xsd)."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import xmlschema

from tactcad import cli
from tactcad.checks.junit import junit_report, suite_of
from tactcad.checks.check_result import CheckResult

SCHEMA = xmlschema.XMLSchema(Path(__file__).parents[1] / "data" / "junit_essentials.xsd")
PARTS = ["element_a4mm", "spacer", "cart"]


def groups_with_one_failure():
    return [
        ("parts", [CheckResult("volume", "element_a4mm", True, "rel 0"),
                   CheckResult("step_volume", "step/element_a4mm.step", True),
                   CheckResult("volume", "spacer", False, "12 mm3 vs 10 (rel 2e-01)")]),
        ("dxf", [CheckResult("dxf_area", "element_a4mm_qty2.dxf", True),
                 CheckResult("sheet_gap", "sheet_aluminium_3mm.dxf", True),
                 CheckResult("dxf_area", "sheet_aluminium_3mm.dxf: element_a4mm at (3.3, 2)",
                             True)]),
        ("array interference", [CheckResult("interference", "28 parts", True)]),
        ("scene array", [CheckResult("is_valid", "cart", True),
                         CheckResult("tips_coplanar", "array", True)]),
    ]


def test_suites_are_parts_sheets_array_and_scenes():
    got = [suite_of(g, r, PARTS) for g, found in groups_with_one_failure() for r in found]
    assert got == ["part:element_a4mm", "part:element_a4mm", "part:spacer", "part:element_a4mm",
                   "sheet:sheet_aluminium_3mm", "sheet:sheet_aluminium_3mm", "array",
                   "part:cart", "scene:array"]


def test_report_counts_each_check_once_and_a_failure_is_a_failure_element():
    groups = groups_with_one_failure()
    xml = junit_report(groups, PARTS)
    SCHEMA.validate(xml.decode())
    root = ET.fromstring(xml)
    cases = root.findall("testsuite/testcase")
    assert len(cases) == int(root.get("tests")) == sum(len(r) for _, r in groups)
    assert sum(int(s.get("tests")) for s in root.findall("testsuite")) == len(cases)
    assert int(root.get("failures")) == 1
    failed = [c for c in cases if c.find("failure") is not None]
    assert [c.get("name") for c in failed] == ["volume: spacer"]
    bad = groups[0][1][2]
    assert failed[0].find("failure").get("message") == bad.line()  # as the terminal prints it
    suite = root.find("testsuite[@name='part:spacer']")
    assert suite.get("failures") == "1" and suite.get("tests") == "1"


def test_report_keeps_odd_subjects_as_text():
    groups = [("parts", [CheckResult("volume", 'a <b> & "c" \u00e9\u4e2d', False, "x\ty")])]
    root = ET.fromstring(junit_report(groups, PARTS))
    assert root.find("testsuite/testcase").get("name") == 'volume: a <b> & "c" \u00e9\u4e2d'


def test_check_junit_refuses_a_path_in_no_folder(tmp_path, capsys):
    code = cli.main(["check", "--junit", str(tmp_path / "no" / "r.xml"), "--json"])
    error = json.loads(capsys.readouterr().out)["error"]
    assert code == 2 and error["field"] == "--junit"


@pytest.mark.slow
def test_check_junit_matches_the_checks_run_and_a_failure_fails(tmp_path, capsys, monkeypatch,
                                                                verified_store):
    from conftest import warm_store_copy
    from tactcad.checks import scene_checks as scenes

    out, report = tmp_path / "out", tmp_path / "report.xml"
    store = warm_store_copy(verified_store, tmp_path / "store")  # the export's and verify's
    args = ["check", "--scene", "wirecut", "--out", str(out), "--cache", str(store),
            "--junit", str(report), "--json"]
    assert cli.main(args) == 0
    checks = json.loads(capsys.readouterr().out)["checks"]
    SCHEMA.validate(str(report))
    root = ET.parse(report).getroot()
    assert int(root.get("tests")) == len(root.findall("testsuite/testcase")) == len(checks) > 0
    assert root.get("failures") == "0"
    assert {s.get("name") for s in root.findall("testsuite")} >= {"scene:wirecut"}

    # one check made to fail: exit 1, one <failure> with the terminal's line
    broken = CheckResult("tips_coplanar", "array", False, "height spread 1.0e-01 mm")
    monkeypatch.setattr(scenes, "check_scene_sanity", lambda scene, shapes: [broken])
    args[args.index(str(out))] = str(tmp_path / "out2")  # a scenes-only export has no manifest
    assert cli.main(args) == 1
    capsys.readouterr()
    root = ET.parse(report).getroot()
    failures = root.findall("testsuite/testcase/failure")
    assert root.get("failures") == "1" and len(failures) == 1
    assert failures[0].get("message") == broken.line()


def test_an_undecided_requirement_is_its_own_status_in_the_line_the_counts_and_junit():
    """`check` printed ``PASS requirement full_scale_force_N undecided`` and JUnit
    passed it: undecided is neither, a ``<skipped>`` with its reason in JUnit."""
    from tactcad.checks.check_result import counts_text, status_counts

    found = [CheckResult("requirement", "full_scale_force_N", True, "undecided: margin +0.2 %",
                         undecided=True),
             CheckResult("requirement", "kr_over_km", True, "pass: margin +5 %"),
             CheckResult("requirement", "footprint_mm", False, "fail: margin -3 %")]
    assert [r.line().split()[0] for r in found] == ["UNDECIDED", "PASS", "FAIL"]
    counts = status_counts(found)
    assert counts == {"passed": 1, "undecided": 1, "failed": 1, "info": 0}
    assert counts_text(counts) == "1 passed, 1 undecided, 1 failed"
    assert counts_text(status_counts(found[1:])) == "1 passed, 1 failed"
    root = ET.fromstring(junit_report([("requirements", found)], PARTS))
    SCHEMA.validate(junit_report([("requirements", found)], PARTS).decode())
    assert root.get("tests") == "3" and root.get("skipped") == "1" and root.get("failures") == "1"
    case = next(c for c in root.iter("testcase") if c.get("name").endswith("full_scale_force_N"))
    skipped = case.find("skipped")
    assert skipped is not None and "margin +0.2 %" in skipped.get("message")
    assert case.find("failure") is None
