"""The suite's own scheduling lists name tests that exist: a renamed browser
test left out of ``BROWSER_TESTS`` would run beside another browser."""

from __future__ import annotations

import re
from pathlib import Path

from conftest import BROWSER_TESTS, _test_key

TESTS = Path(__file__).resolve().parents[1]


def test_every_listed_browser_test_is_a_test_function_of_its_file():
    for key in sorted(BROWSER_TESTS):
        path, name = key.split("::")
        text = (TESTS / path).read_text(encoding="utf-8")
        assert re.search(rf"^def {re.escape(name)}\(", text, re.M), key


def test_a_node_id_is_keyed_without_parameters_or_group():
    assert _test_key("tests/export/test_x.py::test_y[a-b]@browser") == "export/test_x.py::test_y"
    assert _test_key("tests/export/test_x.py::test_y") == "export/test_x.py::test_y"
