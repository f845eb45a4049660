"""One row of a check report."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class CheckResult:
    """Outcome of one check on one subject (a part, a file, an instance pair).

    ``undecided``: the check passes but could not decide (a requirement whose
    margin lies inside its error estimate); ``info``: a figure reported, not judged (a
    verification row of verdict ``info``: no requirement to pass or fail), never failed
    nor counted as passed; :attr:`status` says so.
    """

    check: str
    subject: str
    passed: bool
    detail: str = ""
    undecided: bool = False
    info: bool = False

    def __post_init__(self):
        # a verdict computed with NumPy (np.True_) is a bool here: JSON and `is True` take it
        object.__setattr__(self, "passed", bool(self.passed))
        object.__setattr__(self, "undecided", bool(self.undecided))
        object.__setattr__(self, "info", bool(self.info))

    @property
    def status(self) -> str:
        """``pass``, ``fail``, ``undecided`` or ``info``."""
        return status_of(self)

    def line(self) -> str:
        """``PASS``, ``FAIL``, ``UNDECIDED`` or ``INFO``, the check, its subject and the detail."""
        return f"{STATUS_LABELS[self.status]}  {self.check:<24} {self.subject:<28} {self.detail}"


#: How each status is printed at the head of a check's line.
STATUS_LABELS = {"pass": "PASS", "fail": "FAIL", "undecided": "UNDECIDED", "info": "INFO"}


def failures(results) -> list[CheckResult]:
    return [r for r in results if not r.passed]


def status_counts(results) -> dict[str, int]:
    """How many of ``results`` passed, are undecided, failed and are reported, not judged:
    each result counted once (``{"passed": n, "undecided": n, "failed": n, "info": n}``; an
    ``info`` one is not counted as passed)."""
    found = [status_of(r) for r in results]
    return {"passed": found.count("pass"), "undecided": found.count("undecided"),
            "failed": found.count("fail"), "info": found.count("info")}


def counts_text(counts: dict[str, int]) -> str:
    """``3 passed, 1 undecided, 0 failed, 2 info`` (the undecided and info counts only where
    there are any)."""
    open_ = f"{counts['undecided']} undecided, " if counts["undecided"] else ""
    info = f", {counts['info']} info" if counts.get("info") else ""
    return f"{counts['passed']} passed, {open_}{counts['failed']} failed{info}"


def reported_passed(result) -> bool | None:
    """``passed`` as a report writes it: ``None`` for an ``info`` result (reported, not
    judged: neither passed nor failed, as a verification row of verdict ``info`` says
    ``"pass": null``), the result's own ``passed`` otherwise.

    Args:
        result: anything with ``passed`` and, optionally, ``undecided`` and ``info``.

    Returns:
        ``True``, ``False`` or ``None``.
    """
    return None if status_of(result) == "info" else bool(result.passed)


def status_of(result) -> str:
    """``pass``, ``fail``, ``undecided`` or ``info`` of a check result (anything with
    ``passed`` and, optionally, ``undecided`` and ``info``)."""
    if not result.passed:
        return "fail"
    if getattr(result, "info", False):
        return "info"
    return "undecided" if getattr(result, "undecided", False) else "pass"
