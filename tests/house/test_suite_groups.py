"""The suite's own scheduling lists name tests that exist: a renamed browser
test left out of ``BROWSER_TESTS`` would run beside another browser, a renamed long
test left out of ``LONGEST_FIRST`` would start wherever it is collected."""

from __future__ import annotations

import re
from pathlib import Path

from conftest import BROWSER_TESTS, LONGEST_FIRST, _start_rank, _test_key

TESTS = Path(__file__).resolve().parents[1]


def test_every_listed_browser_test_is_a_test_function_of_its_file():
    for key in sorted(BROWSER_TESTS):
        path, name = key.split("::")
        text = (TESTS / path).read_text(encoding="utf-8")
        assert re.search(rf"^def {re.escape(name)}\(", text, re.M), key


def test_a_node_id_is_keyed_without_parameters_or_group():
    assert _test_key("tests/export/test_x.py::test_y[a-b]@browser") == "export/test_x.py::test_y"
    assert _test_key("tests/export/test_x.py::test_y") == "export/test_x.py::test_y"


def test_every_longest_first_test_is_a_test_function_of_its_file():
    for key in LONGEST_FIRST:
        path, name = key.split("::")
        text = (TESTS / path).read_text(encoding="utf-8")
        assert re.search(rf"^def {re.escape(name.split('[')[0])}\(", text, re.M), key


class _Item:
    def __init__(self, nodeid: str):
        self.nodeid = nodeid


def test_the_longest_tests_rank_first_with_or_without_their_parameters():
    first = _Item("tests/" + LONGEST_FIRST[0])
    parametrised = _Item("tests/" + LONGEST_FIRST[3] + "[draws1-2]")
    other = _Item("tests/export/test_x.py::test_y[a]@browser")
    docs = _Item("tests/docs/test_code_blocks.py::test_page_code_runs[how-to/other.md]")
    assert _start_rank(first) == 0 and _start_rank(parametrised) == 3
    assert _start_rank(other) == _start_rank(docs) == len(LONGEST_FIRST)


#: (test file, module fixture) -> the xdist group its readers run in: each fixture costs
#: seconds (a design search, a solve), and pytest-xdist makes a module fixture once on every
#: worker that runs a test reading it, so readers spread over two workers made it twice.
ONE_WORKER_FIXTURES = {
    ("studies/test_design_reasons.py", "designed"): "design-reasons",
    ("mechanics/test_fem2d.py", "extremes"): "fem2d-extremes",
    ("mechanics/test_comb_crosstalk.py", "fem"): "comb-crosstalk-fe",
    ("mechanics/test_die_dynamics.py", "calculix"): "die-calculix",
    ("products/test_die_review_in_use.py", "die_page"): "die-review-page",
    ("export/test_stl.py", "stl_export"): "stl-export",
    ("docs/test_site.py", "site"): "docs-site",
}


def _test_functions(path: Path) -> dict:
    """{name: function} of the ``test_`` functions of the test file at ``path``, imported."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(f"_groups_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return {n: f for n, f in vars(module).items() if n.startswith("test_") and callable(f)}


def test_every_reader_of_a_costly_module_fixture_runs_in_its_group():
    import inspect

    for (path, fixture), group in ONE_WORKER_FIXTURES.items():
        readers = {n: f for n, f in _test_functions(TESTS / path).items()
                   if fixture in inspect.signature(f).parameters}
        assert readers, (path, fixture)
        for name, f in readers.items():
            groups = [m.args[0] for m in getattr(f, "pytestmark", []) if m.name == "xdist_group"]
            assert groups == [group], f"{path}::{name} reads {fixture}: mark it {group!r}"
