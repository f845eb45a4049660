"""A refused ``design --out NEW_DIR`` makes no folder, yet keeps what it solved where the
same command run again finds it: the store of the folder ``NEW_DIR`` would be made in (as
``--out NEW.toml`` there keeps it). A written project gets those results in its own store,
so its commands solve nothing again."""

from __future__ import annotations

import pytest

from tactcad import cli
from tactcad.errors import DesignError
from tactcad.store import STORE_FOLDER, Store, counting_results, kept_result, keeping_results

REFUSED = ["--kr-over-km", "6", "--kobj-range", "1", "10", "--full-scale-force", "0.3"]


def _solving_then_refused(calls: list):
    """A search that solves one value (kept in the run's store) and is then refused."""
    def search(*args, **kwargs):
        kept_result("refused-design test solve", lambda: calls.append(1) or 42.0, "inputs")
        raise DesignError("--full-scale-force", 0.3, "at most 0.153 N", "the search's bound")
    return search


def test_a_refused_design_keeps_its_solves_for_its_rerun_and_makes_no_folder(
        tmp_path, monkeypatch):
    import tactcad.studies.layout_search as layout_search

    calls: list = []
    monkeypatch.setattr(layout_search, "searched_design", _solving_then_refused(calls))
    monkeypatch.chdir(tmp_path)
    (tmp_path / "work").mkdir()
    argv = ["design", *REFUSED, "--out", str(tmp_path / "work" / "d")]
    with counting_results() as first:
        assert cli.main(argv) == 2
    assert not (tmp_path / "work" / "d").exists()  # a refusal makes no project folder
    assert len(calls) == 1 and first.solved() == 1
    # kept beside the folder it would have made, not in the working folder's store
    assert any((tmp_path / "work" / STORE_FOLDER).rglob("*.pickle"))
    assert not (tmp_path / STORE_FOLDER).exists()
    with counting_results() as second:
        assert cli.main(argv) == 2
    assert len(calls) == 1, "the rerun solved again"
    assert second.solved() == 0 and sum(second.reused.values()) == 1
    assert not (tmp_path / "work" / "d").exists()


@pytest.mark.parametrize("extra, kept_in", [([], "parent"), (["--no-cache"], None),
                                            (["--cache", "mine"], "mine")])
def test_a_refused_design_keeps_its_solves_where_its_options_say(tmp_path, monkeypatch,
                                                                 extra, kept_in):
    import tactcad.studies.layout_search as layout_search

    calls: list = []
    monkeypatch.setattr(layout_search, "searched_design", _solving_then_refused(calls))
    monkeypatch.chdir(tmp_path)
    argv = ["design", *REFUSED, "--out", "d", *[str(tmp_path / x) if x == "mine" else x
                                                for x in extra]]
    assert cli.main(argv) == 2 and cli.main(argv) == 2
    assert not (tmp_path / "d").exists()
    if kept_in is None:  # --no-cache: nothing kept, solved each time
        assert len(calls) == 2 and not (tmp_path / STORE_FOLDER).exists()
    else:
        assert len(calls) == 1
        store = tmp_path / (STORE_FOLDER if kept_in == "parent" else kept_in)
        assert any(store.rglob("*.pickle"))


def test_a_written_design_gives_its_new_folder_the_solves_made_for_it(tmp_path,
                                                                       monkeypatch):
    from tactcad.commands import design as cmd

    def written(args):
        kept_result("written-design test solve", lambda: 7.0, "inputs")
        folder = tmp_path / "d"
        folder.mkdir(exist_ok=True)
        (folder / "d.toml").write_text("# the design\n", encoding="utf-8")
        return 0
    monkeypatch.setattr(cmd, "_run", written)
    monkeypatch.chdir(tmp_path)
    assert cli.main(["design", *REFUSED, "--out", "d"]) == 0
    # the folder's own store holds it: its commands (verify in d/) read it, solving nothing
    with keeping_results(Store(tmp_path / "d" / STORE_FOLDER)), counting_results() as again:
        assert kept_result("written-design test solve", lambda: 0.0, "inputs") == 7.0
    assert again.solved() == 0


def test_an_existing_folder_keeps_its_own_store(tmp_path, monkeypatch):
    import tactcad.studies.layout_search as layout_search

    calls: list = []
    monkeypatch.setattr(layout_search, "searched_design", _solving_then_refused(calls))
    monkeypatch.chdir(tmp_path)
    (tmp_path / "d").mkdir()
    assert cli.main(["design", *REFUSED, "--out", "d"]) == 2
    assert (tmp_path / "d").is_dir() and any((tmp_path / "d" / STORE_FOLDER).rglob("*.pickle"))
    assert not (tmp_path / STORE_FOLDER).exists()


#: One ``tactcad`` run in a fresh process (the search's per-process memory would answer a
#: second run in this one): its exit code and what kept_result solved and reused, as JSON.
COUNTED = """
import json, sys
from tactcad import cli
from tactcad.store import counting_results
with counting_results() as c:
    code = cli.main(sys.argv[1:])
print(json.dumps({"code": code, "solved": c.solved(), "reused": sum(c.reused.values())}))
"""


def _counted_run(argv: list[str], cwd) -> dict:
    import json
    import os
    import subprocess
    import sys
    from pathlib import Path

    src = Path(__file__).resolve().parents[2] / "src"
    done = subprocess.run([sys.executable, "-c", COUNTED, *argv], cwd=cwd, capture_output=True,
                          text=True, env={**os.environ, "PYTHONPATH": str(src)})
    return json.loads(done.stdout.strip().splitlines()[-1])


@pytest.mark.slow  # two whole design searches (one to three minutes each)
def test_the_stacked_searchs_refusal_run_again_solves_nothing(tmp_path):
    argv = ["design", *REFUSED, "--out", "d"]
    first = _counted_run(argv, tmp_path)
    assert first["code"] == 2 and first["solved"] > 0 and not (tmp_path / "d").exists()
    second = _counted_run(argv, tmp_path)
    assert second["code"] == 2 and not (tmp_path / "d").exists()
    assert second["solved"] == 0 and second["reused"] >= first["solved"], (first, second)


def test_a_refused_design_through_a_dangling_link_makes_nothing_at_its_target(tmp_path,
                                                                             monkeypatch):
    import tactcad.studies.layout_search as layout_search

    calls: list = []
    monkeypatch.setattr(layout_search, "searched_design", _solving_then_refused(calls))
    monkeypatch.chdir(tmp_path)
    (tmp_path / "d").symlink_to(tmp_path / "nowhere")
    assert cli.main(["design", *REFUSED, "--out", "d"]) == 2
    assert cli.main(["design", *REFUSED, "--out", "d"]) == 2
    assert len(calls) == 1 and not (tmp_path / "nowhere").exists()
    assert any((tmp_path / STORE_FOLDER).rglob("*.pickle"))
