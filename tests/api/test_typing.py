"""The public API as a user's type checker sees it: mypy finds no error in
tactcad's public modules, and a user's script gets real types, not Any."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow
ROOT = Path(__file__).resolve().parents[2]

USER_SCRIPT = '''
import tactcad
project = tactcad.load()
reveal_type(project)
reveal_type(project.element(1).stiffness().stiffness_N_per_mm)
reveal_type(project.plan.material.youngs_modulus_MPa)
try:
    tactcad.load("x.toml")
except tactcad.DesignErrors as exc:
    reveal_type(exc.errors)
'''


def _mypy(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "mypy", *args], cwd=cwd, capture_output=True,
                          text=True)


def test_the_public_modules_check_clean():
    out = _mypy()  # pyproject's [tool.mypy] names the files
    assert out.returncode == 0, out.stdout
    assert out.stdout.startswith("Success: no issues found in 3 source files")


def test_a_users_script_sees_real_types(tmp_path):
    script = tmp_path / "user.py"
    script.write_text(USER_SCRIPT, encoding="utf-8")
    out = _mypy("--follow-imports", "silent", "--config-file", str(ROOT / "pyproject.toml"),
                str(script), cwd=tmp_path)
    assert out.returncode == 0, out.stdout
    revealed = [line.split('Revealed type is "', 1)[1].rstrip('"')
                for line in out.stdout.splitlines() if "Revealed type" in line]
    assert [r.replace("builtins.", "") for r in revealed] == [
        "tactcad.api.Project", "float", "float", "tuple[tactcad.errors.DesignError, ...]"]
