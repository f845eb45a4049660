"""One row of a check report."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class CheckResult:
    """Outcome of one check on one subject (a part, a file, an instance pair)."""

    check: str
    subject: str
    passed: bool
    detail: str = ""

    def line(self) -> str:
        return f"{'PASS' if self.passed else 'FAIL'}  {self.check:<24} {self.subject:<28} {self.detail}"


def failures(results) -> list[CheckResult]:
    return [r for r in results if not r.passed]
