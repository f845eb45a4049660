"""`tactcad scenes comb/comb10.toml`: a design file given as the command's word is read as
the design (it was read as a scene's name), a scene's name still as a scene's."""

from __future__ import annotations

import shutil

from tactcad.cli import main
from tactcad.commands.scenes import design_or_scene
from tactcad.project_folder import examples


def test_a_design_file_as_the_word_is_the_design(tmp_path, monkeypatch, capsys):
    shutil.copytree(examples()["macro_array"].parent, tmp_path / "comb")
    (tmp_path / "comb" / "macro_array.toml").rename(tmp_path / "comb" / "comb10.toml")
    for other in ("a.toml", "b.toml"):  # a folder of several designs: no default one
        (tmp_path / other).write_bytes(examples()["macro_array"].read_bytes())
    monkeypatch.chdir(tmp_path)
    assert main(["scenes", "comb/comb10.toml"]) == 0
    out = capsys.readouterr().out
    assert "wirecut  [wirecut]" in out and "--design" not in out


def test_the_word_is_a_scene_otherwise():
    assert design_or_scene(None, "array") == (None, "array")
    assert design_or_scene("d.toml", "x.toml") == ("d.toml", "x.toml")  # --design given
    assert design_or_scene(None, "comb/comb10.TOML") == ("comb/comb10.TOML", None)
    assert design_or_scene(None, None) == (None, None)
