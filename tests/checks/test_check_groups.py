"""Check groups are declared once (tactcad.checks.groups): a group registered
by a module of its own runs in ``tactcad check``, is listed by ``--help``, gets
its JUnit suite and its table on the review page."""

from __future__ import annotations

import json

import pytest

from tactcad import cli
from tactcad.checks import groups as registry
from tactcad.checks.groups import CheckGroup, groups_to_run, register_check_group
from tactcad.checks.junit import junit_report
from tactcad.checks.check_result import CheckResult
from tactcad.checks.review_results import checks_script

DUMMY = CheckGroup("tip marks", "every element's tip mark is legible", __name__, "tip_marks")


def tip_marks(context):
    """The dummy group's checks: one result per element of the plan."""
    yield "tip marks", [CheckResult("tip_mark", f"element_{s.number}", s.number != 3,
                                    "legible" if s.number != 3 else "worn off")
                        for s in context.plan.slots]


@pytest.fixture
def with_dummy(monkeypatch):
    monkeypatch.setattr(registry, "CHECK_GROUPS", dict(registry.CHECK_GROUPS))
    register_check_group(DUMMY)
    return DUMMY


def test_registering_a_taken_name_or_an_unknown_suite_rule_is_refused(with_dummy):
    with pytest.raises(ValueError, match="registered already"):
        register_check_group(DUMMY)
    with pytest.raises(ValueError, match="suite 'per part' is not one of"):
        register_check_group(CheckGroup("x", "y", __name__, "tip_marks", suite="per part"))


def test_the_groups_run_in_order_and_scenes_keep_the_design_only_groups(with_dummy):
    assert [g.name for g in groups_to_run()][-1] == "tip marks"
    only_scenes = [g.name for g in groups_to_run(["array"])]
    assert only_scenes == ["requirements", "hard stops", "rigs", "process", "grasper",
                           "export files", "scenes"]
    without_project = [g.name for g in groups_to_run(project=False)]
    assert "scenes" not in without_project and "tip marks" in without_project


def test_help_junit_and_page_read_the_registry(with_dummy, capsys):
    with pytest.raises(SystemExit):
        cli.main(["check", "--help"])
    assert "tip marks (every element's tip mark is legible)" in " ".join(
        capsys.readouterr().out.split())
    found = [("tip marks", [CheckResult("tip_mark", "element_3", False, "worn off")])]
    assert b'<testsuite name="tip marks"' in junit_report(found, ["element_a4mm"])
    doc = json.loads(checks_script("ff", found).removeprefix("window.TACTCAD_CHECKS = ")
                     .rstrip(";\n"))
    assert {"name": "tip marks", "checks": DUMMY.checks} in doc["groups"]
    assert doc["checks"][0]["group"] == "tip marks" and doc["failed"] == 1


@pytest.mark.slow
def test_a_registered_group_runs_in_check(with_dummy, exported, verified_store, tmp_path):
    import tactcad

    from conftest import warm_store_copy

    out, _ = exported
    # the requirements' solves read back from the run's store, not solved again here
    report = tactcad.load().check(out, cache=warm_store_copy(verified_store, tmp_path / "s"))
    labels = [label for label, _ in report.groups]
    assert labels[:8] == ["requirements", "rigs", "process", "export files", "parts", "dxf",
                          "array interference", "array STEP"]
    assert labels[-1] == "tip marks" and any(label.startswith("scene ") for label in labels)
    marks = dict(report.groups)["tip marks"]
    assert [r.subject for r in marks if not r.passed] == ["element_3"]
    assert not report.passed
