"""The tests mirror the house: every test file sits in ``tests/<room>/`` where
``<room>`` is a package of ``src/tactcad/`` (the module under test's room), or
in one of the few folders for what spans the house: ``api/`` (the Python API),
``house/`` (the layer order, the repository's scripts), ``docs/`` (the documentation site) and ``end_to_end/``
(runs that need a whole process or install: the wheel, CI, the FreeCAD GUI).
No test file sits at ``tests/`` itself or in a folder that is not a room."""

from __future__ import annotations

from pathlib import Path

import tactcad

TESTS = Path(__file__).resolve().parents[1]
SRC = Path(tactcad.__file__).resolve().parent
#: Test folders that mirror no package: the API module, the house as a whole, whole runs,
#: the documentation site (docs/).
BESIDE_THE_ROOMS = {"api", "house", "end_to_end", "docs"}
#: Folders of tests/ that hold no test (the shared data files).
NOT_TESTS = {"data", "__pycache__"}


def rooms() -> set[str]:
    """The packages of src/tactcad (folders with an ``__init__.py``)."""
    return {p.parent.name for p in SRC.glob("*/__init__.py")}


def misplaced(tests: Path, allowed: set[str]) -> list[str]:
    """Test files (``test_*.py``) at the top of ``tests`` or under a folder not in ``allowed``."""
    out = []
    for f in sorted(tests.rglob("test_*.py")):
        parts = f.relative_to(tests).parts
        if "__pycache__" in parts:
            continue
        if len(parts) == 1 or parts[0] not in allowed:
            out.append("/".join(parts))
    return out


def test_the_rooms_are_read_from_the_source():
    assert {"kernel", "partlib", "design", "export", "checks", "mechanics",
            "studies", "commands"} <= rooms()


def test_every_test_file_sits_in_a_room_of_the_source():
    assert misplaced(TESTS, rooms() | BESIDE_THE_ROOMS) == []


def test_every_folder_of_tests_is_a_room():
    folders = {p.name for p in TESTS.iterdir() if p.is_dir()} - NOT_TESTS
    assert folders - rooms() - BESIDE_THE_ROOMS == set()


def test_a_test_file_out_of_place_is_found(tmp_path):
    for name in ("test_top.py", "mechanics/test_beam.py", "utils/test_misc.py",
                 "data/test_x.py"):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text("")
    allowed = {"mechanics", "house"}
    assert misplaced(tmp_path, allowed) == ["data/test_x.py", "test_top.py",
                                            "utils/test_misc.py"]
