"""A die's export, like an array's, removes what a killed run left beside its folder and
says each job it runs on stderr."""

from __future__ import annotations

import pytest

from conftest import DIE_EXAMPLE as EXAMPLE


@pytest.mark.slow  # a whole export of a die
def test_a_dies_export_removes_a_killed_runs_staging_folder(die_folder, capsys):
    from tactcad import cli

    left = die_folder / ".out.staging-killed1"  # as a run killed mid-export leaves it
    (left / "scenes").mkdir(parents=True)
    (left / f"{EXAMPLE.stem}.gds").write_bytes(b"half a mask")
    aside = die_folder / ".out.old-killed2"  # an old export renamed aside, not yet removed
    aside.mkdir()
    assert cli.main(["export", "--design", str(die_folder / EXAMPLE.name), "--out",
                     str(die_folder / "out"), "--no-cache"]) == 0
    # progress, one line per job run, on stderr as an array's export gives it
    wrote = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("  wrote ")]
    assert f"  wrote {EXAMPLE.stem}.gds" in wrote and len(wrote) >= 10
    assert not left.exists() and not aside.exists()
    assert (die_folder / "out" / "manifest.json").is_file()
    assert not [p for p in die_folder.iterdir() if p.name.startswith(".out.")]


def test_a_project_folders_gitignore_keeps_a_killed_exports_folders_out():
    from importlib import resources

    text = (resources.files("tactcad") / "data" / "project" / "gitignore").read_text()
    import fnmatch

    lines = [ln.rstrip("/") for ln in text.splitlines() if ln and not ln.startswith("#")]
    for leftover in (".exports.staging-8a07nxbz", ".exports.old-1x2y3z", ".e.staging-q"):
        assert any(fnmatch.fnmatch(leftover, pattern) for pattern in lines), leftover
