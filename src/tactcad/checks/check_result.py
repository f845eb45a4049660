"""One row of a check report."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class CheckResult:
    """Outcome of one check on one subject (a part, a file, an instance pair).

    ``undecided``: the check passes but could not decide (a requirement whose
    margin lies inside its error estimate); :attr:`status` says so.
    """

    check: str
    subject: str
    passed: bool
    detail: str = ""
    undecided: bool = False

    @property
    def status(self) -> str:
        """``pass``, ``fail`` or ``undecided``."""
        return status_of(self)

    def line(self) -> str:
        return f"{'PASS' if self.passed else 'FAIL'}  {self.check:<24} {self.subject:<28} {self.detail}"


def failures(results) -> list[CheckResult]:
    return [r for r in results if not r.passed]


def status_of(result) -> str:
    """``pass``, ``fail`` or ``undecided`` of a check result (anything with ``passed`` and,
    optionally, ``undecided``)."""
    if not result.passed:
        return "fail"
    return "undecided" if getattr(result, "undecided", False) else "pass"
