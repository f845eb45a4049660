"""tactcad as a lab installs it: the wheel (built from the sdist) in a clean
venv, run from a new git repository outside the checkout, with no checkout on
``sys.path``. The dependencies are the test environment's own, made visible
to the new venv by one ``.pth`` line and checked against the wheel's ranges
by ``pip check`` (installing them anew from the index took about a minute and
proves only pip's resolver; `make env` resolves the same ranges). The steps are a user's first hour: ``tactcad new``, export,
``check --junit``, ``diff`` against the previous commit (the CI template's
own steps), the documentation's Python example, ``export --only step`` and the
review page offline in Chromium; then a project made for a non-paper design
is searched for the paper's samples, loads and text."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import sysconfig
import tarfile
import time
import zipfile
from pathlib import Path

import pytest

import tactcad
from conftest import file_digests

# one worker builds the wheel once for every test of this module
pytestmark = [pytest.mark.slow, pytest.mark.xdist_group("installed_wheel")]

ROOT = Path(__file__).resolve().parents[2]
#: What only the paper's design may carry: its samples (N/mm), the evaluation
#: rig's load (N), its text.
PAPER_MARKS = ("10.01", "7.26", "6.28", "5.41", "4.51", "3.57", "2.34", "3.235",
               "Spring-based tactile", "paper", "macro_array", "Table 1", "Table 2")
#: Files whose numbers are geometry (coordinates can match a sample by chance).
GEOMETRY_SUFFIXES = (".step", ".glb", ".dxf", ".png", ".pdf", ".svg", ".FCStd")


def _run(args: list[str], cwd: Path, env: dict, ok=(0,), timings=None) -> subprocess.CompletedProcess:
    start = time.perf_counter()
    out = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True, timeout=1800)
    if timings is not None:
        timings.append((" ".join(Path(a).name if i == 0 else a for i, a in enumerate(args)),
                        time.perf_counter() - start))
    assert out.returncode in ok, f"{args}: exit {out.returncode}\n{out.stdout}\n{out.stderr}"
    return out


@pytest.fixture(scope="session")  # module scope was set up again when xdist interleaved
def installed(tmp_path_factory):
    """(venv bin folder, clean environment, timings, dist folder): the wheel built
    from the sdist, installed into a new venv whose dependencies are this
    environment's (see the module docstring)."""
    root = tmp_path_factory.mktemp("installed")
    dist, timings = root / "dist", []
    env = {"PATH": os.environ["PATH"], "HOME": os.environ.get("HOME", str(root)),
           "LANG": "C.UTF-8", "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    _run([sys.executable, "-m", "build", "--outdir", str(dist), str(ROOT)], root, env,
         timings=timings)
    venv = root / "venv"
    # no pip of its own (seeding one takes seconds): this pip installs into it (--python)
    _run([sys.executable, "-m", "venv", "--without-pip", str(venv)], root, env, timings=timings)
    wheel = next(dist.glob("tactcad-*.whl"))
    python = str(venv / "bin" / "python")
    pip = [sys.executable, "-m", "pip", "--python", python]
    site = _run([python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                root, env).stdout.strip()
    # the dependencies already installed here (a path line: the editable tactcad's own
    # .pth files there are not read, so only the wheel's tactcad can be imported)
    Path(site, "test-dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n",
                                                    encoding="utf-8")
    _run([*pip, "install", "--quiet", "--no-deps", str(wheel)], root, env, timings=timings)
    _run([*pip, "check"], root, env, timings=timings)
    user_env = {**env, "PATH": f"{venv / 'bin'}:{env['PATH']}"}
    return venv / "bin", user_env, timings, dist


def test_the_sdist_and_wheel_carry_the_package_data(installed):
    _, _, _, dist = installed
    sdist = next(dist.glob("tactcad-*.tar.gz"))
    with tarfile.open(sdist) as tar:
        names = [n.split("/", 1)[1] for n in tar.getnames() if "/" in n]
    for needed in ("hardware/macro_array/macro_array.toml", "hardware/ti_array_2x3/rigs.toml",
                   "src/tactcad/data/three/build/three.module.js", "tests/conftest.py",
                   "LICENSE", "CHANGELOG.md", "constraints.txt", "src/tactcad/py.typed",
                   "docs/conf.py", "docs/_ext/tactcad_reference.py", "docs/how-to/python.md"):
        assert needed in names, needed
    wheel = zipfile.ZipFile(next(dist.glob("tactcad-*.whl")))
    names = set(wheel.namelist())
    for needed in ("tactcad/examples/macro_array/rigs.toml", "tactcad/data/three/LICENSE",
                   "tactcad/data/three/SHA256SUMS", "tactcad/data/project/hardware.yml",
                   "tactcad/py.typed", f"tactcad-{tactcad.__version__}.dist-info/licenses/LICENSE"):
        assert needed in names, needed
    metadata = wheel.read(f"tactcad-{tactcad.__version__}.dist-info/METADATA").decode()
    assert "License-Expression: Apache-2.0" in metadata
    assert "Requires-Dist: numpy<3,>=2.2" in metadata  # a range, not a pin


def test_a_labs_first_hour_from_the_wheel(installed, tmp_path, example_exported):
    bin_, env, timings, _ = installed
    tactcad, python = str(bin_ / "tactcad"), str(bin_ / "python")
    where = _run([python, "-c", "import tactcad; print(tactcad.__file__)"], tmp_path, env)
    assert str(bin_.parent) in where.stdout and str(ROOT) not in where.stdout

    # named as the example: `new .` names the design for its folder, and the export below
    # must write the very bytes of the checkout's own export of the example
    repo = tmp_path / "ti_array_2x3"
    repo.mkdir()
    git = ["git", "-c", "user.name=lab", "-c", "user.email=lab@example.org"]
    _run(["git", "init", "-q"], repo, env)
    _run([tactcad, "new", ".", "--example", "ti_array_2x3"], repo, env, timings=timings)
    design = "ti_array_2x3.toml"  # named for its folder
    _run([*git, "add", "-A"], repo, env)
    _run([*git, "commit", "-qm", "sensor project"], repo, env)

    # the CI template's own steps, as it writes them
    workflow = (repo / ".github" / "workflows" / "hardware.yml").read_text(encoding="utf-8")
    assert f"DESIGN: {design}" in workflow
    _run([tactcad, "export", "--design", design, "--out", "exports"], repo, env, timings=timings)
    # a cold export in a new process, from the installed package data, writes the bytes
    # the test process's own export of the checkout's example wrote (another hash seed,
    # another folder, another copy of the package)
    # the manifest records the project's own input files, and a project made by `new` names
    # itself in its rigs file: every other byte of the manifest, and every other file, equal
    made, checkout = file_digests(repo / "exports"), file_digests(example_exported)
    assert {**made, "manifest.json": ""} == {**checkout, "manifest.json": ""}
    ours, theirs = (json.loads((folder / "manifest.json").read_text(encoding="utf-8"))
                    for folder in (repo / "exports", example_exported))
    roles = {f["role"]: f for f in ours.pop("inputs")["files"]}
    assert roles["design"] == {f["role"]: f for f in theirs.pop("inputs")["files"]}["design"]
    assert roles["rigs"]["file"] == "rigs.toml" and ours == theirs
    _run([tactcad, "check", "--design", design, "--out", "exports", "--junit",
          "check-report.xml", "--failures-only"], repo, env, timings=timings)
    report = (repo / "check-report.xml").read_text(encoding="utf-8")
    assert "<testsuites" in report and 'failures="0"' in report

    text = (repo / design).read_text(encoding="utf-8")
    (repo / design).write_text(text.replace("6.196", "6.5", 1), encoding="utf-8")
    _run([*git, "commit", "-qam", "longer reference arms"], repo, env)
    _run(["git", "worktree", "add", "-q", "base", "HEAD~1"], repo, env)
    _run([tactcad, "export", "--design", design, "--out", "exports"], repo, env, timings=timings)
    diff = _run([tactcad, "diff", f"base/{design}", "exports", "--out", "diff", "--json"],
                repo, env, ok=(0, 1), timings=timings)
    assert diff.returncode == 1 and "6.5" in diff.stdout

    # the documentation's Python example, in a folder of its own
    page = (ROOT / "docs" / "how-to" / "python.md").read_text(encoding="utf-8")
    code = re.findall(r"```python\n(.*?)```", page, re.S)[0]
    work = tmp_path / "py"
    work.mkdir()
    _run([tactcad, "new", "fingertip"], work, env)
    (work / "example.py").write_text(code, encoding="utf-8")
    out = _run([python, "example.py"], work, env, timings=timings)
    assert out.stderr == "" and out.stdout.splitlines()[-1].endswith("'manifest.json']")

    # --only step asks for no JavaScript; the page renders offline
    _run([tactcad, "export", "--design", design, "--only", "step", "--out", "steps"], repo, env,
         timings=timings)
    assert (repo / "steps" / "step" / "array.step").is_file()
    _review_renders(repo / "exports" / "review" / "index.html")

    figures: dict[str, float] = {}
    for cmd, seconds in timings:  # a command run twice (the export after the edit) keeps both
        key = cmd if cmd not in figures else f"{cmd} (again)"
        figures[key] = round(seconds, 1)
    print("\nfirst hour from the wheel (s):", json.dumps(figures, indent=1))


def _review_renders(page: Path) -> None:
    from tactcad.checks.review_browser import (BrowserMissing, browser_page, canvas_is_blank,
                                               chromium_path, wait_first_frame)

    try:
        chromium_path()
        import playwright  # noqa: F401
    except (BrowserMissing, ImportError):
        return  # the review page's own tests say so
    with browser_page() as tab:
        tab.goto(page.resolve().as_uri())
        wait_first_frame(tab)
        assert tab.errors == [] and not canvas_is_blank(tab)


def test_a_non_paper_project_carries_nothing_of_the_paper(installed, tmp_path):
    bin_, env, _, _ = installed
    tactcad = str(bin_ / "tactcad")
    _run([tactcad, "design", "--kr-over-km", "6", "--kobj-range", "5", "50",
          "--full-scale-force", "0.5", "--material", "17-4PH", "--columns", "4",
          "--verify", "none", "--out", "fingertip", "--quiet"], tmp_path, env)
    project = tmp_path / "fingertip"
    rigs = (project / "rigs.toml").read_text(encoding="utf-8")
    samples = json.loads(re.search(r"^stiffness_N_per_mm = (\[.*\])$", rigs, re.M)[1])
    assert samples and all(5.0 <= k <= 50.0 for k in samples)
    _run([tactcad, "export", "--out", "exports", "--quiet"], project, env)
    hits = []
    for path in sorted(project.rglob("*")):
        if not path.is_file() or path.suffix in GEOMETRY_SUFFIXES or ".tactcad-cache" in path.parts:
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        # the paper's samples are stiffnesses: a percentage that reads 2.34 % is not one
        hits += [f"{path.relative_to(project)}: {mark}" for mark in PAPER_MARKS
                 if re.search(rf"(?<![\w.]){re.escape(mark)}(?![\w])(?! ?%)", text)]
    assert hits == []


def test_a_die_for_the_5mm_jaw_from_the_wheel_exports_and_passes_its_check(installed, tmp_path):
    # issue: `design --jaw 5 ...` writes a die whose export (GDS, STEP, traveller, drawing)
    # passes `check`, KLayout's read-back included, from the wheel in a clean folder
    bin_, env, _, _ = installed
    tactcad = str(bin_ / "tactcad")
    _run([tactcad, "design", "--jaw", "5", "--kr-over-km", "10", "--kobj-range", "0.5", "5",
          "--full-scale-force", "0.009", "--out", "insert", "--quiet"], tmp_path, env)
    folder = tmp_path / "insert"
    _run([tactcad, "export", "--quiet"], folder, env)
    made = sorted(p.name for p in (folder / "exports").iterdir())
    for name in ("insert.gds", "insert.step", "insert_traveller.md", "insert_drawing.svg",
                 "insert_in_jaw.step", "insert_bom.csv"):
        assert name in made, made
    checked = _run([tactcad, "check", "--out", "exports", "--json"], folder, env)
    record = json.loads(checked.stdout)
    assert record["counts"]["failed"] == 0
    assert any(c["check"] == "gds_drc" for c in record["checks"])
