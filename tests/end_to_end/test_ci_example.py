"""The CI workflow a new sensor project gets (``tactcad new``) and ``make
ci-example`` run the same tactcad steps, and the workflow names a real option
of each."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import yaml

from tactcad import cli

ROOT = Path(__file__).resolve().parents[2]


def project_workflow(tmp_path: Path) -> str:
    """The workflow file of a project made by ``tactcad new``."""
    assert cli.main(["new", str(tmp_path / "p"), "--quiet"]) == 0
    return (tmp_path / "p" / ".github" / "workflows" / "hardware.yml").read_text(encoding="utf-8")


def tactcad_steps(text: str) -> list[tuple[str, list[str]]]:
    """(command, its options) of every ``tactcad`` line, in order."""
    steps = []
    for line in text.splitlines():
        m = re.search(r"(?:^|\s|/)tactcad (\w+)(.*)", line)
        if m and not line.lstrip().startswith("#"):
            words = shlex.split(m.group(2).split("||")[0], posix=True)
            steps.append((m.group(1), sorted(w for w in words if w.startswith("--"))))
    return steps


def test_workflow_and_make_ci_example_run_the_same_steps(tmp_path):
    workflow = project_workflow(tmp_path)
    doc = yaml.safe_load(workflow)
    runs = "\n".join(s.get("run", "") for s in doc["jobs"]["export-check-diff"]["steps"])
    make = (ROOT / "Makefile").read_text(encoding="utf-8")
    recipe = make[make.index("\nci-example:"):].split("\n\n")[0]
    assert tactcad_steps(runs) == tactcad_steps(recipe)
    assert [c for c, _ in tactcad_steps(runs)] == ["export", "check", "diff"]
    assert "check-report.xml" in str(doc["jobs"]["export-check-diff"]["steps"][-1])


def test_every_option_the_workflow_uses_exists(tmp_path):
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    workflow = project_workflow(tmp_path)
    for command, opts in tactcad_steps(workflow):
        known = {s for a in sub.choices[command]._actions for s in a.option_strings}
        assert set(opts) <= known, (command, set(opts) - known)
