"""Shared fixtures: the default plan, and one export of it per test session."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from tactcad.design.array_plan import default_design_data, load_design


#: Fixtures that cost a full export or a FreeCAD run: their tests are slow.
SLOW_FIXTURES = {"exported", "freecad"}


def pytest_collection_modifyitems(config, items):
    """Mark every test that uses a costly fixture as slow, so that
    ``make test-fast`` (``-m "not slow"``) fits the inner loop; put the
    browser tests in one pytest-xdist group (:data:`BROWSER_FILES`)."""
    tests = Path(__file__).resolve().parent
    for item in items:
        if SLOW_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)
        if item.path.relative_to(tests).as_posix() in BROWSER_FILES:
            item.add_marker(pytest.mark.xdist_group("browser"))


@pytest.fixture(scope="session")
def project():
    """The default design validated with its rigs and scenes files."""
    from tactcad.design.project import load_project

    return load_project()


@pytest.fixture(scope="session")
def plan(project):
    return project.plan


@pytest.fixture
def design_data():
    """A fresh, mutable copy of the default design's raw tables."""
    return default_design_data()


@pytest.fixture(scope="session")
def exported(project, tmp_path_factory):
    """The default design exported once: (out_dir, ExportResult)."""
    from tactcad.export.run import export

    out = tmp_path_factory.mktemp("exports")
    return out, export(project, out, log=lambda s: None)


INSTALLER = Path(__file__).resolve().parents[1] / "scripts" / "install-system-deps.sh"


@pytest.fixture(scope="session")
def freecad():
    """``freecadcmd``: ``make test`` installs it first (scripts/install-system-deps.sh);
    when it is missing, installed here if the user is root, else the test is skipped."""
    from tactcad.checks.freecad_step import freecadcmd

    exe = freecadcmd()
    if exe is None:
        if os.geteuid() != 0:
            if os.environ.get("CI"):  # CI must review in FreeCAD, never skip it
                pytest.fail("freecadcmd is missing in CI and this user cannot install it")
            pytest.skip("freecadcmd is not installed and this user cannot install it "
                        "(run as root: apt-get install -y freecad-python3)")
        if shutil.which("apt-get") is None:
            pytest.fail("freecadcmd is missing and there is no apt-get to install "
                        "freecad-python3 with")
        subprocess.run(["sh", str(INSTALLER)], check=True, timeout=900)
        exe = freecadcmd()
        assert exe is not None, "scripts/install-system-deps.sh did not install freecadcmd"
    return exe


def with_default_companions(design: Path) -> Path:
    """``design`` (a file written in a test) with the default design's rigs
    and scenes files copied beside it, as its ``[files]`` table names them."""
    from tactcad.design.rig_plan import DEFAULT_RIGS
    from tactcad.design.scene_specs import DEFAULT_SCENES

    for f in (DEFAULT_RIGS, DEFAULT_SCENES):
        shutil.copy(f, design.parent / f.name)
    return design


def run_cli(*argv: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    """``tactcad ARGV`` run in this process (:func:`tactcad.cli.main`): its exit
    code, stdout and stderr as :func:`subprocess.run` gives them, without a new
    interpreter importing the CAD kernel again. For what a process boundary
    changes nothing of: refusals, exit codes, output; tests of signals, pipes,
    a fresh interpreter's imports or the installed program start a process."""
    import contextlib
    import io

    from tactcad.cli import main

    out, err = io.StringIO(), io.StringIO()
    here = Path.cwd()
    try:
        if cwd is not None:
            os.chdir(cwd)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main([str(a) for a in argv])
    finally:
        os.chdir(here)
    return subprocess.CompletedProcess(["tactcad", *argv], code, out.getvalue(), err.getvalue())


#: Test files that drive a browser (Chromium, headless) or the FreeCAD GUI: under
#: pytest-xdist they share one process (``--dist loadgroup``), so two never run at once.
BROWSER_FILES = {"commands/test_watch.py", "export/test_review_page.py",
                 "end_to_end/test_freecad_gui.py", "export/test_instructions_browser.py"}


@pytest.fixture(scope="module")
def browser():
    """:func:`tactcad.checks.review_browser.browser_page` (headless Chromium through
    Playwright), or the test skipped saying what is missing."""
    from tactcad.checks.review_browser import BrowserMissing, browser_page, chromium_path

    try:
        chromium_path()
        import playwright  # noqa: F401
    except (BrowserMissing, ImportError) as exc:
        pytest.skip(str(exc))
    return browser_page
