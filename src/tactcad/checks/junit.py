"""Check results as a JUnit XML report, the format CI systems read.

One ``<testcase>`` per check, named ``check: subject``; a failed check holds
a ``<failure>`` whose message is the line ``tactcad check`` prints for it, an
undecided one (a requirement whose margin lies inside its model's error) a
``<skipped>`` with that line as its reason, so CI counts it apart from a pass. An
info one (a figure reported, not judged: a requirement the lab never stated) is a
``<skipped>`` of type ``info`` too: every JUnit reader counts a skipped case as not
failed and apart from the passed ones, as ``check`` counts it (not among the passed).
Test cases are grouped into ``<testsuite>`` elements by what they check,
as each check group declares (:mod:`tactcad.checks.groups`):

* ``part:<name>``: a part's solid checks, its STEP file and its DXF;
* ``sheet:<name>``: a nested DXF sheet;
* ``array``: the array's interference and its STEP assembly;
* ``scene:<name>``: a scene's interference, sanity, STEP and GLB checks;
* the group's name for any other group (``requirements``).

Written with junitparser (a maintained reader and writer of the format).
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterable, Sequence

from tactcad.atomic import write_bytes_atomic
from tactcad.checks.groups import group_of
from tactcad.checks.check_result import CheckResult

Group = tuple[str, Sequence[CheckResult]]


def suite_of(label: str, result: CheckResult, part_names: Iterable[str]) -> str:
    """The test suite of one result of a check group: the registered group's
    rule (:meth:`tactcad.checks.groups.CheckGroup.suite_of`); a label no group
    has is its own suite."""
    try:
        group = group_of(label)
    except KeyError:
        return label
    return group.suite_of(label, result, set(part_names))


def junit_report(groups: Sequence[Group], part_names: Iterable[str],
                 name: str = "tactcad check") -> bytes:
    """The JUnit XML document (UTF-8 bytes) of the check groups, in the order run.

    Args:
        groups: (group name, results) as :meth:`tactcad.api.Project.check` returns them.
        part_names: the design's part names, to give each part its suite.
        name: the report's name (the ``<testsuites>`` element's).
    """
    from junitparser import Failure, JUnitXml, Skipped, TestCase, TestSuite

    names = list(part_names)
    suites: dict[str, TestSuite] = {}
    for group, results in groups:
        for r in results:
            key = suite_of(group, r, names)
            suite = suites.get(key)
            if suite is None:
                suite = suites[key] = TestSuite(key)
            case = TestCase(f"{r.check}: {r.subject}", classname=key, time=0.0)
            if not r.passed:
                case.result = [Failure(r.line(), type_=r.check)]
            elif getattr(r, "info", False):  # reported, not judged: not failed, not passed
                case.result = [Skipped(r.line(), type_="info")]
            elif getattr(r, "undecided", False):  # neither a pass nor a failure: its reason
                case.result = [Skipped(r.line(), type_="undecided")]
            if r.detail:
                case.system_out = r.detail
            suite.add_testcase(case)
    xml = JUnitXml(name)
    for suite in suites.values():
        suite.update_statistics()
        xml.add_testsuite(suite)
    xml.update_statistics()
    return xml.tostring()


def write_junit(path: str | Path, groups: Sequence[Group], part_names: Iterable[str]) -> Path:
    """Write :func:`junit_report` to ``path`` atomically (whole or not at all).

    Raises:
        OSError: the file cannot be written.
    """
    target = Path(path)
    write_bytes_atomic(target, junit_report(groups, part_names))
    return target
