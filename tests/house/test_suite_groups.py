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
