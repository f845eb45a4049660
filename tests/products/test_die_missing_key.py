"""A die design file without one of its keys is refused with the key's allowed range, as a
wrong value of it is (it said "allowed a value (missing)")."""

from __future__ import annotations

import json

import pytest

from conftest import DIE_EXAMPLE, run_cli


@pytest.mark.parametrize("key, allowed", [
    ("kr_over_km", "1 < value <= 1000"),
    ("full_scale_force_N", "1e-09 <= value <= 1000 N"),
    ("kobj_range_N_per_mm", "[LO, HI] with"),
    ("jaw", "a trocar class")])
def test_a_missing_die_key_states_its_allowed_range(tmp_path, key, allowed):
    text = DIE_EXAMPLE.read_text(encoding="utf-8")
    kept = [line for line in text.splitlines() if not line.startswith(f"{key} = ")]
    assert len(kept) == len(text.splitlines()) - 1
    design = tmp_path / "die.toml"
    design.write_text("\n".join(kept) + "\n", encoding="utf-8")
    r = run_cli("verify", "--design", str(design), "--json", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert (error["field"], error["value"]) == (f"die.{key}", None)
    assert error["allowed"].startswith(allowed)
