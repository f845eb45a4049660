"""The results of ``tactcad check`` for the export's review page:
``review/checks.js`` beside ``review/index.html`` (``window.TACTCAD_CHECKS``),
which the page shows, one table per check group, when they are for the design
its manifest names."""

from __future__ import annotations

from pathlib import Path
from typing import Iterable

from tactcad.atomic import write_bytes_atomic
from tactcad.checks import groups as check_groups
from tactcad.checks.check_result import reported_passed, status_of
from tactcad.export.review_page import CHECKS_SCRIPT, REVIEW_PAGE, json_in_html


def checks_script(design_sha256: str, groups: Iterable[tuple[str, Iterable]]) -> str:
    """``review/checks.js``: the check results for the page (``window.TACTCAD_CHECKS``),
    each with its group's label and its status (pass, fail, undecided or info: an undecided
    requirement passes but the page does not show it as a pass; an info one, reported, not
    judged, is neither); ``groups`` lists every
    registered check group (:data:`tactcad.checks.groups.CHECK_GROUPS`) with what it
    checks, in run order.

    Args:
        design_sha256: the design the results are for (the page shows them only
            when its manifest names the same design).
        groups: (label, results) in the order run, as
            :attr:`tactcad.api.CheckReport.groups`.
    """
    checks = []
    for label, results in groups:
        try:
            name = check_groups.group_of(label).name
        except KeyError:
            name = label
        checks += [{"group": name, "label": label, "check": r.check, "subject": r.subject,
                    "passed": reported_passed(r), "status": status_of(r), "detail": r.detail}
                   for r in results]
    statuses = [c["status"] for c in checks]
    doc = {"design_sha256": design_sha256, "passed": statuses.count("pass"),
           "undecided": statuses.count("undecided"), "failed": statuses.count("fail"),
           "info": statuses.count("info"),
           "groups": [{"name": g.name, "checks": g.checks}
                      for g in check_groups.CHECK_GROUPS.values()],
           "checks": checks}
    return "window.TACTCAD_CHECKS = " + json_in_html(doc) + ";\n"


def write_checks_script(out_dir: Path, design_sha256: str,
                        groups: Iterable[tuple[str, Iterable]]) -> Path | None:
    """Write ``review/checks.js`` into an export that has a review page; its path, or
    None when there is no page to show it.

    Raises:
        OSError: the file cannot be written.
    """
    page = Path(out_dir) / REVIEW_PAGE
    if not page.is_file():
        return None
    path = Path(out_dir) / CHECKS_SCRIPT
    write_bytes_atomic(path, checks_script(design_sha256, groups).encode("utf-8"))
    return path


def update_checks_script(out_dir: str | Path, design_sha256: str,
                         groups: Iterable[tuple[str, Iterable]]) -> Path | None:
    """:func:`write_checks_script` for ``tactcad check``: a file that cannot be written (an
    export folder without write access) is warned about, not an error, since the checks ran
    and their results are the command's answer (the command leaves the export's files as
    they are).

    Args:
        out_dir: the export checked. design_sha256: the design's hash.
        groups: (group, results) of the run.

    Returns:
        The file's path; None when there is no page to show it or it was not written.

    Warns:
        UserWarning: naming the file not updated and why.
    """
    import warnings

    try:
        return write_checks_script(Path(out_dir), design_sha256, groups)
    except OSError as exc:
        why = (exc.strerror or type(exc).__name__).lower()
        warnings.warn(UserWarning(
            f"{Path(out_dir) / CHECKS_SCRIPT}: not updated ({why}): the review page shows "
            "the checks it held before; this run's results are those printed"))
        return None
