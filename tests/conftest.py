"""Shared fixtures: the default plan, and one export of it per test session."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from tactcad.design.array_plan import DEFAULT_DESIGN, default_design_data


#: Fixtures that cost a full export or a FreeCAD run: their tests are slow.
SLOW_FIXTURES = {"exported", "freecad", "default_store", "example_exported", "arm_changed_cold"}


def _test_key(nodeid: str) -> str:
    """``dir/test_file.py::test_name`` of a node id (no ``tests/``, parameters or xdist group)."""
    path, _, name = nodeid.partition("::")
    return path.removeprefix("tests/") + "::" + name.split("[")[0].split("@")[0]


#: The longest tests of ``make test`` (ten seconds or more each, from its ``--durations``),
#: longest first; the ones collected late (``studies/``) matter most. pytest-xdist hands
#: out tests in collection order (after its groups), so these start first, one per
#: worker, instead of one of them starting last and running alone while the other idles.
LONGEST_FIRST = (
    "end_to_end/test_designed_invariant.py::test_the_palpation_strip_designs_and_passes_its_check",
    "end_to_end/test_random_designs.py::test_a_random_design_of_the_domain_exports_and_passes_its_check",
    "end_to_end/test_designed_invariant.py::test_every_written_design_passes_its_own_check",
    "mechanics/test_die_dynamics.py::test_on_its_frame_the_dies_fem3d_agrees_with_calculix_to_one_percent",
    "studies/test_verify_ladder_accuracy.py::test_k_r_over_k_m_climbing_alone_gives_the_records_the_full_matrix_gives",
    "export/test_live_server.py::test_a_short_load_during_edits_has_no_error_and_prints_its_latencies",
    "assembly/test_scenes.py::test_collision_fails_check_with_names_and_volume",
    "commands/test_watch.py::test_watch_keeps_one_drawing_worker_that_degrades_and_ends_cleanly",
    "api/test_die_project.py::test_a_die_project_runs_the_die_views_the_cli_runs",
    "docs/test_code_blocks.py::test_page_code_runs[tutorials/mems-die.md]",
    "design/test_die_fillets.py::test_the_closed_forms_root_peak_is_within_5_percent_of_fem3d_on_and_off_the_example",
    "design/test_example_design.py::test_example_meets_every_requirement_and_its_binding_limit_holds_at_fem3d",
    "end_to_end/test_designed_invariant.py::test_a_refusals_frontier_is_the_searchs_whatever_force_was_asked",
    "in_use/test_contact_convergence.py::test_an_undecided_tissue_row_is_judged_on_a_finer_check_where_the_cells_allow",
    "in_use/test_tissue_coupling_fem.py::test_two_punches_agree_with_an_elastic_block_within_5_percent",
    "mechanics/test_gauge_strain_calculix.py::test_fem3d_grid_strain_agrees_with_calculix",
    "products/test_die_modal_levels.py::test_modal_fem3d_reads_the_die_commands_fem3d_and_keeps_it",
    "drawings/test_no_overlap.py::test_thirty_random_designs_of_the_domain_draw_clear",
    "commands/test_design_refused_store.py::test_the_stacked_searchs_refusal_run_again_solves_nothing",
    "mechanics/test_bonded_layer.py::test_the_stated_layer_errors_hold_against_fem3d_with_the_layer_meshed",
    "mechanics/test_modal_calculix.py::test_fem3d_first_frequency_agrees_with_calculix",
    "studies/test_layout_search.py::test_a_soft_range_refusal_offers_a_force_that_designs_far_below_the_best_layouts",
    "docs/test_code_blocks.py::test_page_code_runs[how-to/design-array.md]",
    "studies/test_resonance.py::test_a_thin_sheet_is_verified_at_fem3d_whatever_the_level",
)


def _start_rank(item) -> int:
    """An item's place in :data:`LONGEST_FIRST`, by its id with or without its parameters
    (every other test after them)."""
    with_parameters = item.nodeid.removeprefix("tests/").split("@")[0]
    for key in (with_parameters, _test_key(item.nodeid)):
        if key in LONGEST_FIRST:
            return LONGEST_FIRST.index(key)
    return len(LONGEST_FIRST)


def pytest_configure(config):
    """Refuse a ``TACTCAD_TEST_DEPTH`` that is neither depth (:mod:`depth`)."""
    from depth import DEPTH, DEPTHS

    if DEPTH not in DEPTHS:
        raise pytest.UsageError(f"TACTCAD_TEST_DEPTH = {DEPTH!r}: allowed {' or '.join(DEPTHS)}")


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist's own hook reads the group marks
def pytest_collection_modifyitems(config, items):
    """Mark every test that uses a costly fixture as slow, so that
    ``make test-fast`` (``-m "not slow"``) fits the inner loop; put the tests
    of :data:`BROWSER_TESTS` in one pytest-xdist group, and only those (the
    rest of their files is scheduled like any test). A test that uses the
    :func:`browser` fixture and is not listed there stops the run."""
    items.sort(key=_start_rank)  # stable: the rest keep their collection order
    for item in items:
        if SLOW_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)
        listed = _test_key(item.nodeid) in BROWSER_TESTS
        if "browser" in getattr(item, "fixturenames", ()) and not listed:
            raise pytest.UsageError(f"{item.nodeid} drives a browser: list it in "
                                    "tests/conftest.py BROWSER_TESTS")
        if listed:
            item.add_marker(pytest.mark.xdist_group("browser"))


def pytest_xdist_node_collection_finished(node, ids):
    """Under ``--dist loadgroup`` the browser tests must carry their group in
    their ids (pytest-xdist schedules by it); a pytest that drops it would
    silently run them on any worker, two browsers at once."""
    if node.config.getoption("dist", None) != "loadgroup":
        return
    lost = [i for i in ids if _test_key(i) in BROWSER_TESTS and "@browser" not in i]
    if lost:
        pytest.exit(f"--dist loadgroup: {len(lost)} browser tests lost their xdist group "
                    f"(first: {lost[0]}); install the pytest of constraints.txt", returncode=4)


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


def _run_folder(tmp_path_factory) -> Path:
    """The folder every pytest-xdist worker of this run shares (the run's own
    base folder without xdist)."""
    base = tmp_path_factory.getbasetemp()
    return base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base


#: The shipped example that is not the paper's design (tests of a new design's files).
EXAMPLE_DESIGN = Path(__file__).resolve().parents[1] / "hardware" / "ti_array_2x3" / "ti_array_2x3.toml"
#: The shipped silicon die's design file (the 5 mm jaw's).
DIE_EXAMPLE = (Path(__file__).resolve().parents[1] / "hardware" / "grasper_jaw_5mm_mems"
               / "grasper_jaw_5mm_mems.toml")


@pytest.fixture
def die_folder(tmp_path):
    """A working folder holding a copy of the shipped die's design file alone."""
    (tmp_path / DIE_EXAMPLE.name).write_bytes(DIE_EXAMPLE.read_bytes())
    return tmp_path


def _once_per_run(tmp_path_factory, name: str, make) -> Path:
    """``shared/<name>``, made by ``make(path)`` once per test run: the first
    worker to ask makes it under a lock, the others wait and find it made.
    What it holds is read, never changed, by the tests."""
    import fcntl

    shared = _run_folder(tmp_path_factory)
    target, made = shared / name, shared / f"{name}.made"
    with open(shared / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not made.exists():
            make(target)
            made.write_text("")
    return target


def _filled_store(tmp_path_factory, name: str, design: Path | None) -> Path:
    """A store holding every job of ``design``'s export (``None``: the default
    design), filled by one cold export per test run (:func:`_once_per_run`)."""
    from tactcad.design.project import load_project
    from tactcad.export.run import export
    from tactcad.store import Store

    def fill(store: Path) -> None:
        export(load_project(design), store.with_name(f"{name}-export"), log=lambda s: None,
               store=Store(store))
    return _once_per_run(tmp_path_factory, f"{name}-store", fill)


#: The default design's arm lengths with element 5's arm 6 -> 6.5 mm.
ARM_CHANGED_LENGTHS = [4.0, 7.0, 6.0, 8.0, 6.5, 8.0, 5.0, 4.0, 5.0, 7.0]


@pytest.fixture(scope="session")
def arm_changed_cold(tmp_path_factory) -> tuple[Path, Path]:
    """(design file, export folder): the default design with element 5's arm
    6 -> 6.5 mm (:data:`ARM_CHANGED_LENGTHS`), exported cold, with no store,
    once per test run; read only."""
    from tactcad.design.project import load_project
    from tactcad.export.run import export

    def make(folder: Path) -> None:
        folder.mkdir()
        text = DEFAULT_DESIGN.read_text(encoding="utf-8")
        old = "lengths_mm = [4.0, 7.0, 6.0, 8.0, 6.0, 8.0, 5.0, 4.0, 5.0, 7.0]"
        assert old in text
        design = folder / "changed.toml"
        design.write_text(text.replace(old, f"lengths_mm = {ARM_CHANGED_LENGTHS}"),
                          encoding="utf-8")
        export(load_project(with_default_companions(design)), folder / "cold",
               log=lambda s: None)
    folder = _once_per_run(tmp_path_factory, "arm-changed", make)
    return folder / "changed.toml", folder / "cold"


@pytest.fixture(scope="session", autouse=True)
def run_default_store(tmp_path_factory):
    """An export without ``--cache`` stores its jobs in ``./.tactcad-cache``; in the
    tests that is a folder of this test run, shared by its workers, never the
    checkout's (a run starts as cold as on a fresh clone, and writes nothing into
    the source tree). Processes a test starts choose their store themselves."""
    import tactcad.store

    kept = tactcad.store.DEFAULT_STORE
    tactcad.store.DEFAULT_STORE = _run_folder(tmp_path_factory) / "cwd-default-store"
    yield
    tactcad.store.DEFAULT_STORE = kept


@pytest.fixture(scope="session")
def default_store(tmp_path_factory) -> Path:
    """The default design's export jobs (:func:`_filled_store`). Tests whose
    subject is not a cold export (watch sessions, served pages, the session
    export below) start from it, or from a copy (:func:`warm_store_copy`) when
    they add jobs of their own."""
    return _filled_store(tmp_path_factory, "default-design", None)


@pytest.fixture(scope="session")
def verified_store(tmp_path_factory, default_store) -> Path:
    """:func:`default_store` with the solves ``verify`` and ``check`` decide the default
    design's requirements with (each undecided one up the ladder: its full-scale force at
    fem3d), made once per test run, so the tests that check the default design read them
    back instead of each solving them again. Read only: copy it (:func:`warm_store_copy`)
    to add to it."""
    import tactcad

    def fill(store: Path) -> None:
        shutil.copytree(default_store, store)
        tactcad.load().verify(cache=store)
    return _once_per_run(tmp_path_factory, "default-design-verified-store", fill)


@pytest.fixture(scope="session")
def example_exported(tmp_path_factory) -> Path:
    """The non-paper example (:data:`EXAMPLE_DESIGN`) exported once per worker,
    its jobs from a store filled once per run; tests that add files (``check``)
    work on a copy."""
    from tactcad.design.project import load_project
    from tactcad.export.run import export
    from tactcad.store import Store

    store = _filled_store(tmp_path_factory, "example-design", EXAMPLE_DESIGN)
    out = tmp_path_factory.mktemp("example-exports")
    export(load_project(EXAMPLE_DESIGN), out, log=lambda s: None, store=Store(store))
    return out


def warm_store_copy(default_store: Path, target: Path) -> Path:
    """A private copy of :func:`default_store` at ``target`` (a session that adds
    jobs, e.g. edits, writes into its own copy only)."""
    shutil.copytree(default_store, target)
    return target


@pytest.fixture(scope="session")
def exported(project, tmp_path_factory, default_store):
    """The default design exported once per worker: (out_dir, ExportResult), its
    jobs fetched from :func:`default_store` (the same bytes as a cold export:
    tests/export/test_export_set.py)."""
    from tactcad.export.run import export
    from tactcad.store import Store

    out = tmp_path_factory.mktemp("exports")
    return out, export(project, out, log=lambda s: None, store=Store(default_store))


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


@pytest.fixture(scope="session")
def ccx():
    """CalculiX's ``ccx`` (Debian's ``calculix-ccx``): installed here if missing and the
    user is root (scripts/install-system-deps.sh), else the test is skipped saying so."""
    exe = shutil.which("ccx")
    if exe is None:
        if os.geteuid() != 0 or shutil.which("apt-get") is None:
            if os.environ.get("CI"):
                pytest.fail("ccx is missing in CI and cannot be installed here")
            pytest.skip("ccx is not installed (as root: apt-get install -y calculix-ccx)")
        subprocess.run(["sh", str(INSTALLER)], check=True, timeout=900)
        exe = shutil.which("ccx")
        assert exe is not None, "scripts/install-system-deps.sh did not install ccx"
    return exe


def with_default_companions(design: Path) -> Path:
    """``design`` (a file written in a test) with the default design's rigs
    and scenes files copied beside it, as its ``[files]`` table names them."""
    from tactcad.design.rig_plan import DEFAULT_RIGS
    from tactcad.design.scene_specs import DEFAULT_SCENES

    for f in (DEFAULT_RIGS, DEFAULT_SCENES):
        shutil.copy(f, design.parent / f.name)
    return design


def file_digests(folder: Path) -> dict[str, str]:
    """sha256 of every file under ``folder``, by its path relative to it (``/``)."""
    import hashlib

    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


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


def designed_once(tmp_path_factory, name: str, argv: tuple[str, ...]) -> tuple[Path, str]:
    """(working folder, what it printed): ``tactcad ARGV`` (a ``design``) run in the folder
    ``shared/<name>`` once per test run (:func:`_once_per_run`), for the tests that read
    what one whole design search wrote and said; read only, copy it before running a
    command in it.

    Raises:
        AssertionError: the command did not exit 0.
    """
    def make(folder: Path) -> None:
        folder.mkdir()
        r = run_cli(*argv, cwd=folder)
        assert r.returncode == 0, r.stdout + r.stderr
        (folder / "said.txt").write_text(r.stdout, encoding="utf-8")
    folder = _once_per_run(tmp_path_factory, name, make)
    return folder, (folder / "said.txt").read_text(encoding="utf-8")


#: ``tactcad design`` of a 17-4PH array whose 0.105 mm web in a 5 mm sheet moves K by
#: +/-51 % over its web tolerance and puts the closed form's out-of-plane error above 100 %.
THIN_WEB_DESIGN = ("design", "--kr-over-km", "6", "--kobj-range", "0.5", "4",
                   "--full-scale-force", "0.114", "--material", "17-4PH-H900", "--columns", "4",
                   "--out", "ph4")


@pytest.fixture
def thin_web_designed(tmp_path_factory) -> tuple[Path, str]:
    """(project folder, what ``design`` printed) of :data:`THIN_WEB_DESIGN`, searched once
    a test run (:func:`designed_once`)."""
    folder, said = designed_once(tmp_path_factory, "thin-web-design", THIN_WEB_DESIGN)
    return folder / "ph4", said


#: ``tactcad design --json`` of a stiff 7075-T6 stacked array into ``next.toml``, with the
#: tissue coupling (its default) named.
STACKED_7075_DESIGN = ("design", "--kr-over-km", "3", "--kobj-range", "5", "20",
                       "--full-scale-force", "0.3", "--material", "7075-T6", "--verify", "none",
                       "--out", "next.toml", "--json", "--tissue-coupling", "on")


@pytest.fixture
def stacked_7075_designed(tmp_path_factory) -> tuple[Path, str]:
    """(working folder holding ``next.toml``, the JSON ``design`` printed) of
    :data:`STACKED_7075_DESIGN`, searched once a test run (:func:`designed_once`)."""
    return designed_once(tmp_path_factory, "stacked-7075-design", STACKED_7075_DESIGN)


#: ``tactcad design --json`` of a quick stacked array (the shipped base design, a stiff
#: range) held to ``--kobj-accuracy 0.5``, written outside its working folder: to
#: ``../stacked-kobj-accuracy.toml``, beside that folder.
STACKED_KOBJ_ACCURACY_DESIGN = ("design", "--kr-over-km", "3", "--kobj-range", "5", "20",
                                "--full-scale-force", "0.3", "--kobj-accuracy", "0.5",
                                "--out", "../stacked-kobj-accuracy.toml", "--json")


@pytest.fixture
def stacked_kobj_accuracy_designed(tmp_path_factory) -> tuple[Path, Path, str]:
    """(working folder, the design file written outside it, the JSON ``design`` printed) of
    :data:`STACKED_KOBJ_ACCURACY_DESIGN`, searched once a test run (:func:`designed_once`)."""
    folder, said = designed_once(tmp_path_factory, "stacked-kobj-accuracy-design",
                                 STACKED_KOBJ_ACCURACY_DESIGN)
    return folder, folder.parent / "stacked-kobj-accuracy.toml", said


#: The tests that drive a browser (Chromium, headless) or the FreeCAD GUI: under
#: pytest-xdist they share one process (``--dist loadgroup``), so two never run at
#: once; the other tests of their files go to any worker.
BROWSER_TESTS = {
    "commands/test_watch.py::test_watch_session_in_chromium",
    "commands/test_watch.py::test_served_scenes_follow_the_last_choice_and_free_the_ones_left",
    "end_to_end/test_freecad_gui.py::test_review_file_opens_with_the_scene_in_view",
    "export/test_instructions_browser.py::test_book_opens_offline_in_chromium",
    "export/test_review_page.py::test_a_build_step_lights_its_parts_and_the_slider_explodes_them",
    "export/test_review_page.py::test_page_offline_in_chromium",
    "export/test_review_page.py::test_page_served_by_any_web_server_shows_what_it_carries",
    "export/test_review_page.py::test_a_page_whose_watch_stopped_asks_less_and_less_often",
    "export/test_review_page.py::test_check_results_join_the_page",
    "export/test_review_page.py::test_an_undecided_requirement_shows_as_undecided_not_pass",
    "export/test_review_page.py::test_a_requirement_reported_not_judged_shows_as_info_in_the_checks",
    "export/test_review_budget.py::test_the_exported_page_shows_the_budget_table",
    "export/test_atlas_view.py::test_the_page_draws_the_atlas_and_a_click_shows_the_point",
}


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


def ctrl_c_at_its_default() -> None:
    """``preexec_fn`` of a process whose Ctrl-C a test sends: SIGINT and SIGQUIT
    at their defaults in the child, whatever this process ignores at that
    moment (a C ``system()`` in another thread ignores both process-wide while
    it runs, and a child would inherit that: a watch started then ignores Ctrl-C)."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGQUIT, signal.SIG_DFL)
