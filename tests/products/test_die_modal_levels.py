"""`tactcad modal` on a silicon die's design answers at each of the die's levels, the
closed form and fem3d, in one record of the same keys with each level's error estimate and
cost; at fem3d it reads the solve `tactcad die --fem3d` makes (the same function, kept in
the result store), so a second run solves nothing, and the Python API's `modes(model=...)`
gives the command's numbers."""

from __future__ import annotations

import json

import pytest

from conftest import DIE_EXAMPLE, run_cli

ROLES = ["reference", "measuring"]
#: The coarsest meshes of the die's fem3d (one element across and through each beam, two
#: along it; the finer of the pair doubles each): the claims below are which solve each
#: command reads and keeps, not its accuracy.
COARSEST = (2, 1, 1)


def _modal(folder, cache, *options: str) -> tuple[int, dict | str]:
    r = run_cli("modal", "--design", DIE_EXAMPLE.name, "--cache", cache, *options,
                cwd=folder)
    assert "Traceback" not in r.stderr, r.stderr
    return r.returncode, json.loads(r.stdout) if "--json" in options else r.stdout


def _keys(record: dict) -> tuple:
    return set(record), [set(row) for row in record["rows"]]


@pytest.fixture
def solved(monkeypatch) -> list[str]:
    """The die's fem3d solve on its coarsest meshes; the roles it solved, in order."""
    from tactcad.products.silicon_die.mechanics import die_fem3d

    full, roles = die_fem3d.die_beam_fem3d, []

    def coarsest(plan, beam, divisions=COARSEST, frame=True, progress=None):
        roles.append(beam.role)
        return full(plan, beam, divisions, frame, progress)

    monkeypatch.setattr(die_fem3d, "die_beam_fem3d", coarsest)
    return roles


@pytest.fixture
def stand_in(monkeypatch) -> list[str]:
    """fem3d replaced by a stand-in with figures of its own (f1 a tenth below the closed
    form's, its error and cost by role); the roles it was asked for, in order."""
    from tactcad.products.silicon_die.mechanics import die_dynamics, die_fem3d

    roles = []

    def fake(plan, beam, divisions=die_fem3d.DIVISIONS, frame=True, progress=None):
        roles.append(beam.role)
        f1 = 0.9 * die_dynamics.first_resonance_Hz(plan, beam)
        at = ROLES.index(beam.role)
        return die_fem3d.DieBeamFem(beam.role, 1.0, f1, 0.01, 0.003 + 0.001 * at, 1000 + at,
                                    40.0 + at, frame)

    monkeypatch.setattr(die_fem3d, "die_beam_fem3d", fake)
    return roles


def test_modal_at_fem3d_on_a_die_has_the_closed_forms_keys_its_error_and_cost(
        die_folder, tmp_path, stand_in):
    cache = tmp_path / "store"
    code, closed = _modal(die_folder, cache, "--json")
    assert code == 0 and closed["model"] == "closed-form" and stand_in == []
    code, fem = _modal(die_folder, cache, "--model", "fem3d", "--json")
    assert code == 0 and stand_in == ROLES, fem
    assert _keys(fem) == _keys(closed)
    assert fem["model"] == "fem3d" and not fem["reused"]
    for at, (row, was) in enumerate(zip(fem["rows"], closed["rows"])):
        assert row["role"] == was["role"] == ROLES[at] and row["model"] == "fem3d"
        assert row["first_Hz"] == pytest.approx(0.9 * was["first_Hz"], rel=1e-12)
        assert (row["first_Hz_error_rel"], row["wall_time_s"], row["dofs"]) == \
            (0.003 + 0.001 * at, 40.0 + at, 1000 + at)
        assert row["first_Hz_closed_form_error_rel"] == pytest.approx(1 / 0.9 - 1, rel=1e-9)
    assert fem["lowest_first_Hz"] == min(r["first_Hz"] for r in fem["rows"])
    assert fem["resonance_Hz"] == closed["resonance_Hz"]  # the closed form's, at both
    # the second run reads both rows from the store: no solve, the first run's cost
    code, again = _modal(die_folder, cache, "--model", "fem3d", "--json")
    assert code == 0 and stand_in == ROLES and again["reused"]
    assert [{**r, "reused": False} for r in again["rows"]] == fem["rows"]
    # printed: one line per row at both levels, each with its error and cost
    _, closed_text = _modal(die_folder, cache)
    _, fem_text = _modal(die_folder, cache, "--model", "fem3d")
    assert len(fem_text.splitlines()) == len(closed_text.splitlines()) == 4
    assert "model fem3d" in fem_text and "+/- 0.3 %" in fem_text and "+/- 5 %" in closed_text
    assert "solved in 40 s by an earlier run, reused" in fem_text


def test_a_die_projects_modes_refuse_another_level_by_its_keyword():
    import tactcad
    from tactcad.errors import DesignError

    die = tactcad.load(DIE_EXAMPLE)
    with pytest.raises(DesignError) as err:
        die.modes(model="fem2d")
    assert err.value.field == "model" and "fem3d" in str(err.value), str(err.value)
    assert die.modes()["model"] == "closed-form"


@pytest.mark.slow  # four fem3d solves of a beam on its frame at the coarsest mesh, and a die
@pytest.mark.xdist_group("die-fem3d")
def test_modal_fem3d_reads_the_die_commands_fem3d_and_keeps_it(die_folder, tmp_path, solved):
    """`tactcad die --fem3d` and `modal --model fem3d` on the same design give the same f1,
    error and mesh for each row; a second `modal` and the API's `modes(model="fem3d")` on
    the same store solve nothing and give the first run's numbers."""
    import tactcad
    from tactcad.store import Store, keeping_results

    die = run_cli("die", "--design", DIE_EXAMPLE.name, "--fem3d", "--json", "--quiet",
                  "--out", tmp_path / "die", cwd=die_folder)
    assert die.returncode == 0, die.stdout[-2000:] + die.stderr
    assert solved == ROLES  # the die command keeps no store: it solves
    by_role = {r["role"]: r for r in json.loads(die.stdout)["fem3d"]}
    cache = tmp_path / "store"
    code, fem = _modal(die_folder, cache, "--model", "fem3d", "--json", "--quiet")
    assert code == 0 and solved == ROLES * 2 and not fem["reused"]
    assert [r["role"] for r in fem["rows"]] == ROLES
    for row in fem["rows"]:
        kept = by_role[row["role"]]
        assert row["first_Hz"] == pytest.approx(kept["first_Hz"], rel=1e-9)
        assert row["first_Hz_error_rel"] == pytest.approx(kept["first_Hz_error_rel"], rel=1e-6)
        assert row["dofs"] == kept["dofs"]
        assert row["first_Hz_closed_form_error_rel"] == pytest.approx(
            kept["first_Hz_closed_form_error_rel"], rel=1e-6)
    code, again = _modal(die_folder, cache, "--model", "fem3d", "--json", "--quiet")
    assert code == 0 and solved == ROLES * 2 and again["reused"]
    assert [r["first_Hz"] for r in again["rows"]] == [r["first_Hz"] for r in fem["rows"]]
    with keeping_results(Store(cache)):
        mine = tactcad.load(die_folder / DIE_EXAMPLE.name).modes(model="fem3d")
    assert solved == ROLES * 2 and mine["reused"]
    assert [r["first_Hz"] for r in mine["rows"]] == [r["first_Hz"] for r in fem["rows"]]


def test_die_fem3d_keeps_its_solves_where_modal_and_a_second_die_read_them(
        die_folder, tmp_path, stand_in):
    # `die --fem3d` had no store: it solved every time, and `modal --model fem3d` after it
    # solved again
    cache = tmp_path / "store"
    first = run_cli("die", "--design", DIE_EXAMPLE.name, "--fem3d", "--cache", cache,
                    "--out", "die1", "--json", cwd=die_folder)
    assert first.returncode == 0, first.stdout + first.stderr
    assert stand_in == ROLES
    fem3d = {r["role"]: r for r in json.loads(first.stdout)["fem3d"]}
    code, modal = _modal(die_folder, cache, "--model", "fem3d", "--json")
    assert code == 0 and modal["reused"] and stand_in == ROLES, modal  # nothing solved
    for row in modal["rows"]:
        assert row["first_Hz"] == fem3d[row["role"]]["first_Hz"]
    again = run_cli("die", "--design", DIE_EXAMPLE.name, "--fem3d", "--cache", cache,
                    "--out", "die2", "--json", cwd=die_folder)
    assert again.returncode == 0 and stand_in == ROLES, again.stderr


def test_the_die_records_first_resonance_is_modals_first_Hz_the_old_keys_declared(
        die_folder, tmp_path, stand_in):
    """`tactcad die --fem3d --json` named each row's first resonance ``f1_Hz`` (its error
    ``f1_error_rel``, the closed form's ``f1_closed_form_error_rel``) where `modal --json`
    names it ``first_Hz``: the record writes modal's names, the same figures as modal's row,
    and keeps the old keys beside them, the same values, listed in each row's
    ``deprecated_keys``."""
    cache = tmp_path / "store"
    die = run_cli("die", "--design", DIE_EXAMPLE.name, "--fem3d", "--cache", cache, "--out",
                  "die1", "--json", cwd=die_folder)
    assert die.returncode == 0, die.stdout[-2000:] + die.stderr
    record = json.loads(die.stdout)
    renamed = {"f1_Hz": "first_Hz", "f1_error_rel": "first_Hz_error_rel",
               "f1_closed_form_error_rel": "first_Hz_closed_form_error_rel"}
    code, modal = _modal(die_folder, cache, "--model", "fem3d", "--json")
    assert code == 0 and modal["reused"]
    rows = {r["role"]: r for r in record["fem3d"]}
    for row in modal["rows"]:
        kept = rows[row["role"]]
        assert (kept["first_Hz"], kept["first_Hz_error_rel"]) == \
            (row["first_Hz"], row["first_Hz_error_rel"])
        assert kept["first_Hz_closed_form_error_rel"] == pytest.approx(
            row["first_Hz_closed_form_error_rel"], rel=1e-9)
        assert kept["deprecated_keys"] == renamed
        for old, new in renamed.items():
            assert kept[old] == kept[new]


def test_the_fe_checks_first_resonance_is_first_Hz_the_old_keys_declared_by_the_die():
    """The CalculiX check's row names the first resonance as modal does (``fe_first_Hz``,
    ``closed_form_first_Hz``; the closed form's error ``first_Hz_closed_form_error_rel``,
    as the fem3d row names it); its old ``f1_`` names are the declared deprecated ones."""
    from tactcad.in_use.kobj_budget import with_declared_deprecated_keys
    from tactcad.products.silicon_die.mechanics.die_dynamics import FE_CHECK_RENAMED, FeCheck

    row = FeCheck("reference", 10.0, 10.5, 2000.0, 2100.0).as_json()
    assert (row["fe_first_Hz"], row["closed_form_first_Hz"]) == (2000.0, 2100.0)
    assert row["first_Hz_closed_form_error_rel"] == pytest.approx(0.05, rel=1e-12)
    assert not [k for k in row if k.startswith("f1")]
    kept = with_declared_deprecated_keys(row, FE_CHECK_RENAMED)
    assert all(kept[old] == row[new] for old, new in FE_CHECK_RENAMED.items())
    assert kept["deprecated_keys"]["f1_error_rel"] == "first_Hz_closed_form_error_rel"


def test_the_fe_checks_k_against_the_closed_form_is_not_named_as_a_levels_error_estimate():
    """A fem3d row's ``K_error_rel`` is fem3d's own error estimate; the CalculiX check's was
    the closed form's K against CalculiX's (a measured difference): it is
    ``K_closed_form_error_rel``, as the fem3d row names that, the old key declared."""
    from tactcad.in_use.kobj_budget import with_declared_deprecated_keys
    from tactcad.products.silicon_die.mechanics.die_dynamics import FE_CHECK_RENAMED, FeCheck

    row = FeCheck("reference", 10.0, 10.5, 2000.0, 2100.0).as_json()
    assert row["K_closed_form_error_rel"] == pytest.approx(
        row["K_closed_form_N_per_mm"] / row["K_fe_N_per_mm"] - 1, rel=1e-12)
    assert "K_error_rel" not in row
    kept = with_declared_deprecated_keys(row, FE_CHECK_RENAMED)
    assert kept["K_error_rel"] == kept["K_closed_form_error_rel"]
    assert kept["deprecated_keys"]["K_error_rel"] == "K_closed_form_error_rel"


@pytest.fixture
def fe_stand_in(monkeypatch) -> list[str]:
    """The CalculiX check replaced by a stand-in (K 2 % and f1 4 % below the closed form's,
    which it reads as the real check does); the roles it was asked for, in order."""
    from tactcad.products.silicon_die.mechanics import die_dynamics

    roles = []

    def fake(plan, beam, divisions=die_dynamics.FE_DIVISIONS, frame=True):
        roles.append(beam.role)
        k = die_dynamics.closed_form_k_N_per_mm(plan, beam, frame)
        f1 = die_dynamics.first_resonance_Hz(plan, beam, frame)
        return die_dynamics.FeCheck(beam.role, k / 1.02, k, f1 / 1.04, f1)

    monkeypatch.setattr(die_dynamics, "calculix_beam_check", fake)
    return roles


def _current(row: dict) -> dict:
    """A row's figures under their current names: no deprecated duplicate, no cost."""
    old = row.get("deprecated_keys", {})
    return {k: v for k, v in row.items()
            if k not in old and k not in ("deprecated_keys", "wall_time_s", "reused")}


def test_a_dies_modal_rows_and_its_records_rows_agree_by_name_and_value(
        die_folder, tmp_path, stand_in, fe_stand_in):
    """`tactcad modal` on a die named its closed form's first resonance ``closed_form_Hz``
    and its error ``closed_form_error_rel`` where the die's record (`die --fem3d
    --fe-check --json`) names them ``closed_form_first_Hz`` and
    ``first_Hz_closed_form_error_rel``: modal writes the record's names with the record's
    values, every name a modal row shares with the record's row at its level the same
    number, and the old keys beside them, the same values, declared in ``deprecated_keys``."""
    renamed = {"closed_form_Hz": "closed_form_first_Hz",
               "closed_form_error_rel": "first_Hz_closed_form_error_rel"}
    cache = tmp_path / "store"
    die = run_cli("die", "--design", DIE_EXAMPLE.name, "--fem3d", "--fe-check", "--cache",
                  cache, "--out", "die1", "--json", cwd=die_folder)
    assert die.returncode == 0, die.stdout[-2000:] + die.stderr
    assert stand_in == fe_stand_in == ROLES
    record = json.loads(die.stdout)
    fem3d = {r["role"]: r for r in record["fem3d"]}
    fe = {r["role"]: r for r in record["fe_check"]}
    code, modal = _modal(die_folder, cache, "--model", "fem3d", "--json")
    assert code == 0 and modal["reused"]
    code, closed = _modal(die_folder, cache, "--json")
    assert code == 0
    for row in modal["rows"]:
        mine, kept = _current(row), _current(fem3d[row["role"]])
        shared = set(mine) & set(kept)
        assert {"first_Hz", "first_Hz_error_rel", "first_Hz_closed_form_error_rel"} <= shared
        for name in shared:
            assert mine[name] == pytest.approx(kept[name], rel=1e-9), name
    for row in modal["rows"] + closed["rows"]:
        role = row["role"]
        # the closed form's first resonance: one name, one number, in every record
        assert row["closed_form_first_Hz"] == pytest.approx(
            fe[role]["closed_form_first_Hz"], rel=1e-12)
        assert row["closed_form_first_Hz"] == pytest.approx(
            record["resonance_Hz"][role]["rayleigh"], rel=1e-12)
        assert set(renamed.items()) <= set(row["deprecated_keys"].items())
        assert not set(renamed) & set(_current(row))
        for old, new in renamed.items():
            assert row[old] == row[new]
    assert all(r["first_Hz_closed_form_error_rel"] is None for r in closed["rows"])
    # the FE check's K against the closed form under the fem3d row's name for it
    for role, row in fe.items():
        assert row["K_closed_form_error_rel"] == pytest.approx(0.02, rel=1e-9)
        assert row["K_error_rel"] == row["K_closed_form_error_rel"]
        assert row["deprecated_keys"]["K_error_rel"] == "K_closed_form_error_rel"
        assert fem3d[role]["K_error_rel"] != row["K_closed_form_error_rel"]


def test_a_dies_stiffness_at_fem3d_names_the_closed_forms_k_as_its_records_do(
        die_folder, tmp_path, stand_in):
    # stiffness --model fem3d wrote closed_form_N_per_mm / closed_form_error_rel where the
    # die's FE check and fem3d record write K_closed_form_N_per_mm / K_closed_form_error_rel
    r = run_cli("stiffness", "--design", DIE_EXAMPLE.name, "--cache", tmp_path / "store",
                "--model", "fem3d", "--json", cwd=die_folder)
    assert r.returncode == 0 and stand_in == ROLES, r.stdout[-400:]
    closed = json.loads(run_cli("stiffness", "--design", DIE_EXAMPLE.name, "--json",
                                cwd=die_folder).stdout)
    for row, was in zip(json.loads(r.stdout)["rows"], closed["rows"]):
        assert row["K_closed_form_N_per_mm"] == was["stiffness_N_per_mm"]
        assert row["K_closed_form_error_rel"] == pytest.approx(was["stiffness_N_per_mm"] - 1.0)
        assert row["deprecated_keys"] == {"closed_form_N_per_mm": "K_closed_form_N_per_mm",
                                          "closed_form_error_rel": "K_closed_form_error_rel"}
        assert row["closed_form_N_per_mm"] == row["K_closed_form_N_per_mm"]
        assert row["closed_form_error_rel"] == row["K_closed_form_error_rel"]
