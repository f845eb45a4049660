"""A jaw a die's design file states and the jaw refuses is named by the file's key
(``die.jaw``), not by a ``--jaw`` option the user never gave; ``--jaw`` given stays
``--jaw``."""

from __future__ import annotations

import json
import re

from conftest import DIE_EXAMPLE as EXAMPLE, run_cli


def test_a_files_jaw_without_a_grasper_jaw_table_is_named_by_its_key(tmp_path):
    text = EXAMPLE.read_text(encoding="utf-8")
    text, n = re.subn(r'(?m)^jaw = ".*"$', 'jaw = "dd.toml"', text)
    assert n == 1
    (tmp_path / "dd_die.toml").write_text(text, encoding="utf-8")
    (tmp_path / "dd.toml").write_text("[die]\nname = \"other\"\n", encoding="utf-8")
    r = run_cli("verify", "--design", "dd_die.toml", "--json", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "die.jaw"
    assert error["value"].endswith("dd.toml") and "[grasper_jaw]" in error["allowed"]
    assert "--jaw" not in error["message"] and "dd_die.toml" in error["message"]
    text_run = run_cli("verify", "--design", "dd_die.toml", cwd=tmp_path)
    assert "die.jaw = " in text_run.stderr and "--jaw" not in text_run.stderr


def test_a_jaw_option_without_a_grasper_jaw_table_is_named_as_the_option(tmp_path):
    (tmp_path / "dd.toml").write_text("[die]\nname = \"other\"\n", encoding="utf-8")
    r = run_cli("die", "--jaw", "dd.toml", "--kr-over-km", "6", "--kobj-range", "0.5", "4",
                "--full-scale-force", "0.008", "--json", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    assert json.loads(r.stdout)["error"]["field"] == "--jaw"
