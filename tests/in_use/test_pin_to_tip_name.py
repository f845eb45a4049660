"""`jaw_length_mm` is the jaw's own length (heel to tip, as its table states it) and
`pin_to_tip_mm` the jaw from its pin to its tip, in a die's grasp and a comb's alike."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
DIE = ROOT / "hardware" / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml"
COMB = ROOT / "hardware" / "grasper_jaw_10mm" / "grasper_jaw_10mm.toml"


def test_a_dies_grasp_names_the_jaws_length_and_the_pin_to_tip_apart(tmp_path):
    import tactcad
    from tactcad.products.silicon_die.design.die_mount import die_mount

    (tmp_path / DIE.name).write_bytes(DIE.read_bytes())
    project = tactcad.load(tmp_path / DIE.name)
    mount = die_mount(project.plan, project.planned.jaw_stated)
    r = run_cli("grasp", "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    jaw = json.loads(r.stdout)["jaw"]
    assert jaw["jaw_length_mm"] == mount.jaw_length_mm  # as the export's mount states it
    assert jaw["pin_to_tip_mm"] == pytest.approx(mount.jaw_length_mm - mount.pin_x_mm)
    text = run_cli("grasp", cwd=tmp_path).stdout.splitlines()[0]
    assert f"jaw {mount.jaw_length_mm:g} mm" in text
    assert f"pin to tip {mount.jaw_length_mm - mount.pin_x_mm:.4g} mm" in text


def test_a_combs_grasp_names_the_pin_to_tip_as_such():
    r = run_cli("grasp", "--design", str(COMB), "--json")
    assert r.returncode == 0, r.stdout + r.stderr
    d = json.loads(r.stdout)
    assert "jaw_length_mm" not in d["jaw"] and d["jaw"]["pin_to_tip_mm"] > 0
    head = run_cli("grasp", "--design", str(COMB)).stdout.splitlines()[0]
    assert f"pin to tip {d['jaw']['pin_to_tip_mm']:.4g} mm" in head
    assert ", jaw " not in head
    refused = run_cli("grasp", "--design", str(COMB), "--pin-to-tip-mm", "1", "--json")
    assert refused.returncode == 2
    assert json.loads(refused.stdout)["error"]["field"] == "--pin-to-tip-mm"
