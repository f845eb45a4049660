"""A die's Python object offers what its docstring promises, through the commands' own
functions: its design hash as its export's manifest gives it, its check as `tactcad check`
runs it, and the die views the command line runs on it."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import DIE_EXAMPLE as EXAMPLE, run_cli

@pytest.mark.slow  # exports a die and checks it, about a minute
def test_a_die_projects_hash_and_check_are_the_commands(die_folder, monkeypatch):
    import tactcad
    from tactcad.api import CheckReport, DieProject

    monkeypatch.chdir(die_folder)
    die = tactcad.load(die_folder / EXAMPLE.name)
    assert isinstance(die, DieProject)
    out = Path("exports")  # as the command line below names it
    assert die.export(out) == 0
    manifest = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    assert die.design_hash == manifest["design"]["sha256"]
    report = die.check(out)
    assert isinstance(report, CheckReport) and report.reused_export and report.passed
    cli = json.loads(run_cli("check", "--out", "exports", "--json", cwd=die_folder).stdout)
    assert [(r.check, r.subject, r.status) for r in report.results] == \
        [(c["check"], c["subject"], c["status"]) for c in cli["checks"]]


@pytest.mark.slow  # the die's crosstalk solve, about 20 s
def test_a_die_project_runs_the_die_views_the_cli_runs(die_folder):
    import tactcad

    die = tactcad.load(die_folder / EXAMPLE.name)
    grasp = json.loads(run_cli("grasp", "--force-N", "1", "--json", cwd=die_folder).stdout)
    mine = die.grasp(force_N=1)
    assert mine["grasp"]["tips"] == grasp["grasp"]["tips"]
    crosstalk = die.crosstalk()
    assert crosstalk["beams"] == [b.number for b in die.plan.beams]
    # plain Python throughout: the same JSON the command prints
    printed = json.loads(run_cli("crosstalk", "--json", cwd=die_folder).stdout)
    mine = json.loads(json.dumps(crosstalk))
    # a run's own facts aside: its time, the path as given, whether the solve was read back
    # from the result store (the API keeps its solves there as the command does)
    same = set(mine) & set(printed) - {"cost_s", "design", "reused"}
    assert "beams" in same and {k: mine[k] for k in same} == {k: printed[k] for k in same}
    assert json.loads(json.dumps(die.grasp(force_N=1)))["grasp"]["tips"] == grasp["grasp"]["tips"]
    thermal = json.loads(run_cli("thermal", "--json", cwd=die_folder).stdout)
    assert die.thermal()["self_heating_K"] == thermal["self_heating_K"]


def test_a_die_projects_refusals_name_its_keyword_arguments(die_folder):
    import tactcad
    from tactcad.errors import DesignError

    die = tactcad.load(die_folder / EXAMPLE.name)
    for kwargs, field in ((dict(kobj=-1), "kobj"), (dict(force_N=1e3), "force_N"),
                          (dict(force_N=1.0, angle_deg=3.0), "force_N / angle_deg"),
                          # the command's own ranges and types: no grasp of nothing, no text
                          (dict(force_N=0), "force_N"), (dict(force_N="1"), "force_N"),
                          (dict(opening_deg=95.0), "opening_deg")):
        with pytest.raises(DesignError) as err:
            die.grasp(**kwargs)
        assert err.value.field == field and "--" not in str(err.value), str(err.value)


def test_a_die_projects_tolerance_is_the_commands_json():
    import tactcad
    from tactcad.errors import DesignError

    die = tactcad.load(EXAMPLE)
    printed = json.loads(run_cli("tolerance", "--design", str(EXAMPLE), "--samples", "2000",
                                 "--json").stdout)
    assert json.loads(json.dumps(die.tolerance(samples=2000))) == printed
    with pytest.raises(DesignError) as err:
        die.tolerance(samples=1)
    assert err.value.field == "samples" and "--" not in str(err.value), str(err.value)


def test_a_die_project_refuses_the_arrays_keywords_by_name():
    import inspect

    import tactcad
    from tactcad.api import DieProject, Project
    from tactcad.errors import DesignError

    die = tactcad.load(EXAMPLE)
    # the array's default is an option not given, as on the command line
    assert die.tolerance(samples=200, arm_tol=None, reference=None)["samples"] == 200
    shared = [n for n in dir(DieProject) if not n.startswith("_") and callable(
        getattr(DieProject, n)) and callable(getattr(Project, n, None))]
    assert "tolerance" in shared
    checked = 0
    for name in shared:
        own = set(inspect.signature(getattr(DieProject, name)).parameters)
        for keyword in inspect.signature(getattr(Project, name)).parameters:
            if keyword in own:
                continue
            with pytest.raises(DesignError) as err:  # not Python's TypeError
                getattr(die, name)(**{keyword: 0.01})
            assert err.value.field == keyword and f"a die's {name}()" in str(err.value), \
                str(err.value)
            checked += 1
    assert checked >= 4  # tolerance's what-if tolerances and reference at least


def test_a_die_projects_budget_is_the_json_the_command_prints_unreadable_terms_included():
    """An unreadable term (the posts as made, at the range's stiff end) is infinite in the
    computation: the command writes it as null, and so does the API, so its result is
    valid JSON with the command's values."""
    import tactcad

    mine = tactcad.load(EXAMPLE).budget()
    text = json.dumps(mine, allow_nan=False)  # raises on an inf or NaN left in it
    printed = json.loads(run_cli("budget", "--design", str(EXAMPLE), "--json").stdout)
    terms = printed["kobj_budget"]["terms_rel"]
    assert any(v is None for values in terms.values() for v in values)  # the case at hand
    assert json.loads(text)["kobj_budget"]["terms_rel"] == terms


def test_a_die_projects_solves_are_kept_in_the_working_folders_store(tmp_path, monkeypatch):
    """As the command's: a die report's solves (here the tissue coupling's punch solves of
    its budget) go to the working folder's store, for the next call and the next command;
    a caller's own store block is the one used."""
    import tactcad
    from tactcad.store import STORE_FOLDER, Store, keeping_results

    import tactcad.store
    from tactcad.in_use.tissue_coupling import _normalised_compliance

    monkeypatch.chdir(tmp_path)
    # the working folder's store, as a command's default (the suite points it elsewhere)
    monkeypatch.setattr(tactcad.store, "DEFAULT_STORE", tmp_path / STORE_FOLDER)
    _normalised_compliance.cache_clear()  # this process's memory of the solves
    with keeping_results(Store(None)):  # the caller's choice: keep nothing
        tactcad.load(EXAMPLE).budget()
    assert not (tmp_path / STORE_FOLDER).exists()
    _normalised_compliance.cache_clear()
    first = tactcad.load(EXAMPLE).budget()
    kept = [p for p in (tmp_path / STORE_FOLDER).rglob("*") if p.is_file()]
    assert kept and tactcad.load(EXAMPLE).budget() == first


def test_a_die_projects_export_refuses_an_unusable_cache_before_any_work(tmp_path,
                                                                        monkeypatch):
    import tactcad
    from tactcad.errors import DesignError

    monkeypatch.chdir(tmp_path)
    (tmp_path / "a_file").write_text("x", encoding="utf-8")
    with pytest.raises(DesignError) as err:
        tactcad.load(EXAMPLE).export("out", cache="a_file")
    assert err.value.field == "cache" and "it is an existing file" in str(err.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file"]
