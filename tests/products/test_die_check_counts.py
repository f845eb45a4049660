"""A die's ``export`` and ``check`` print different counts (the check adds checks of the
written files themselves): each says how its count and the other's differ, so the two
outputs side by side are read without a puzzle."""

from __future__ import annotations

import json
import re

import pytest

from conftest import run_cli

COUNTS = re.compile(r"^(\d+) passed, (?:(\d+) undecided, )?(\d+) failed(?:, (\d+) info)?$", re.M)


def _total(stdout: str) -> int:
    found = COUNTS.findall(stdout)
    assert found, stdout
    return sum(int(n or 0) for n in found[-1])


@pytest.mark.slow
def test_a_dies_export_and_check_each_say_what_the_other_counts(die_folder):
    e = run_cli("export", "--out", "exports", cwd=die_folder)
    assert e.returncode == 0, e.stdout + e.stderr
    c = run_cli("check", "--out", "exports", cwd=die_folder)
    assert c.returncode == 0, c.stdout + c.stderr
    exported, checked = _total(e.stdout), _total(c.stdout)
    added = checked - exported
    assert added > 0, (exported, checked)
    # the export names the checks the check adds, by the names the check prints them under
    j = json.loads(run_cli("check", "--out", "exports", "--json", cwd=die_folder).stdout)
    record = json.loads(run_cli("export", "--out", "exports", "--json", cwd=die_folder).stdout)
    assert len(record["checks"]) == exported
    export_names = {x["check"] for x in record["checks"]}
    new = [x for x in j["checks"] if x["check"] not in export_names]
    assert len(new) == added, new
    assert f"`tactcad check` prints these {exported} checks" in e.stdout, e.stdout[-600:]
    assert f"and {added} of the files themselves" in e.stdout, e.stdout[-600:]
    assert all(f"{x['check']} (" in e.stdout.splitlines()[-1] for x in new), e.stdout[-600:]
    # the check says how many of its own are on the files and that the rest are the export's
    last = c.stdout.splitlines()[-1]
    assert last.startswith(f"{added} of them on the files themselves"), last
    assert f"the other {exported} are the checks `tactcad export` prints" in last, last
    assert all(x["check"] in last for x in new), last
    assert (j["checks_on_the_files"], j["checks_export_prints"]) == (added, exported), j


@pytest.mark.slow
def test_a_dies_check_counts_a_hand_edit_among_the_files_own_checks(die_folder):
    assert run_cli("export", "--out", "exports", "--quiet", cwd=die_folder).returncode == 0
    bom = next((die_folder / "exports").glob("*_bom.csv"))
    bom.write_text(bom.read_text() + "# edited\n")
    page = die_folder / "exports" / "review" / "index.html"
    page.write_text(page.read_text() + "<!-- edited -->\n")
    c = run_cli("check", "--out", "exports", "--json", cwd=die_folder)
    j = json.loads(c.stdout)
    edited = [x for x in j["checks"] if x["check"] == "export_file" and x["status"] == "fail"]
    assert len(edited) == 2, edited
    # one failing check per edited file, each counted among the files' own, with die_files
    # and die_record
    assert j["checks_on_the_files"] == len(edited) + 2, j["checks_on_the_files"]
    assert j["checks_on_the_files"] + j["checks_export_prints"] == len(j["checks"])
