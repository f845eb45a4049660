"""``tactcad check``'s export files group notes the files an export left out because a
program failed (the manifest's ``not_written``: FreeCAD's review files), in one info line
naming how to get them, and fails nothing for it."""

from __future__ import annotations

import json

from tactcad.checks.check_result import status_counts
from tactcad.checks.export_files import (NOT_WRITTEN_CHECK, export_files_group,
                                         not_written_results)
from tactcad.checks.groups import CheckContext


def _group(folder, manifest: dict) -> list:
    (folder / "manifest.json").write_text(json.dumps(manifest))
    return [r for _, results in export_files_group(CheckContext(None, folder, None, edited={}))
            for r in results]


def test_review_files_a_failed_freecad_left_out_are_noted_not_failed(tmp_path):
    found = _group(tmp_path, {"files": [], "not_written": [
        {"what": "review/*.FCStd", "files": ["review/wirecut.FCStd"],
         "reason": "freecadcmd exited 3 without a result"}]})
    notes = [r for r in found if r.check == NOT_WRITTEN_CHECK]
    assert len(notes) == 1 and notes[0].status == "info" and notes[0].subject == "review/*.FCStd"
    line = notes[0].line()
    assert "\n" not in line and "freecadcmd exited 3" in line
    assert f"tactcad export --out {tmp_path}" in line and "once FreeCAD works" in line
    assert status_counts(found)["failed"] == 0


def test_an_export_that_left_nothing_out_has_no_note(tmp_path):
    assert not [r for r in _group(tmp_path, {"files": []}) if r.check == NOT_WRITTEN_CHECK]
    assert not not_written_results(tmp_path, [])


def test_the_manifest_names_only_the_files_still_absent():
    """``not_written``: this run's records and, for a partial export, the earlier export's
    of a kind not asked for again, each naming the files the manifest does not list."""
    from tactcad.export.export_owner import EarlierExport
    from tactcad.export.run import not_written_now

    rec = {"what": "review/*.FCStd", "files": ["review/a.FCStd", "review/b.FCStd"],
           "reason": "freecadcmd exited 3 without a result"}
    assert not_written_now([rec], EarlierExport(), set()) == [rec]
    # the earlier export's files kept and listed: no record names them
    assert not_written_now([rec], EarlierExport(), {"review/a.FCStd", "review/b.FCStd"}) == []
    assert not_written_now([rec], EarlierExport(), {"review/a.FCStd"}) == [
        {**rec, "files": ["review/b.FCStd"]}]
    # a partial export without the review job carries the earlier record
    earlier = EarlierExport(not_written=(rec,))
    assert not_written_now([], earlier, {"bom.csv"}) == [rec]
    assert not_written_now([], earlier, {"review/a.FCStd", "review/b.FCStd"}) == []
    # the review job ran again and failed: its own record, once
    again = {**rec, "reason": "freecadcmd exited 4 without a result"}
    assert not_written_now([again], earlier, set()) == [again]
