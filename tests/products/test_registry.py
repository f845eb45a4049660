"""The product registry: every design file's product found by its table, a command a
product has no answer to refused naming those it has, and a fourth product added as one new
package (through the ``tactcad.products`` entry points) that answers, exports and checks
with no edit of tactcad."""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import pytest

from conftest import run_cli
from tactcad import products as registry
from tactcad.errors import DesignError
from tactcad.project_folder import product_of

HARDWARE = Path(__file__).resolve().parents[2] / "hardware"


def test_the_shipped_products_and_their_files():
    names = [p.name for p in registry.products()]
    assert names[-1] == "metal-array" and "silicon-die" in names
    assert product_of(HARDWARE / "macro_array" / "macro_array.toml").is_default
    die = product_of(HARDWARE / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml")
    assert die.name == "silicon-die" and not die.is_default
    for command in ("strength", "stiffness", "verify", "budget", "readout", "modal",
                    "tolerance"):
        assert callable(die.view(command)), command
    assert die.view("evaluate") is None
    assert callable(die.hook("export")) and callable(die.hook("check"))


def test_a_product_without_a_hook_or_a_name_is_refused_by_name():
    with pytest.raises(DesignError, match="export"):
        registry.product_named("metal-array").hook("export")
    with pytest.raises(DesignError, match="silicon-die"):
        registry.product_named("no-such-sensor")
    with pytest.raises(ValueError, match="module:function"):
        registry.resolved("no_colon")


def test_a_command_a_product_has_no_answer_to_names_those_it_has(tmp_path):
    source = HARDWARE / "grasper_jaw_5mm_mems" / "grasper_jaw_5mm_mems.toml"
    (tmp_path / source.name).write_bytes(source.read_bytes())
    r = run_cli("evaluate", "--json", cwd=tmp_path)
    assert r.returncode == 2, r.stdout + r.stderr
    error = json.loads(r.stdout)["error"]
    assert error["field"] == "--design"
    for command in ("strength", "stiffness", "tolerance", "export", "check",
                    "tactcad die --design"):
        assert command in error["message"], command


TOY = '''
"""A toy sensor product, one package: a spring of stiffness k under a force."""
import json
from pathlib import Path

from tactcad.products import Product
from tactcad.vocabulary.schema import read_toml


def _spring(design):
    table = read_toml(Path(design), "design file")["toy"]
    return float(table["k_N_per_mm"]), float(table["force_N"])


def strength_view(design, args):
    k, f = _spring(design)
    return {"travel_mm": f / k, "passed": f / k <= 1.0}, [f"travel {f / k:g} mm"]


def export(design, args):
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    k, f = _spring(design)
    (out / "toy.json").write_text(json.dumps({"k_N_per_mm": k, "force_N": f}))
    return 0


def check(design, args):
    record = json.loads((Path(args.out) / "toy.json").read_text())
    return 0 if (record["k_N_per_mm"], record["force_N"]) == _spring(design) else 1


def load(design, overrides):
    return _spring(design)


PRODUCT = Product(name="toy-spring", summary="a toy spring", design_table="toy",
                  views={"strength": "toy_sensor:strength_view"}, export="toy_sensor:export",
                  check="toy_sensor:check", load="toy_sensor:load")
'''


@pytest.fixture
def toy_product(tmp_path, monkeypatch):
    """A fourth product in a package of its own, registered as an installed distribution's
    entry point (no file of tactcad touched)."""
    site = tmp_path / "site"
    (site / "toy_sensor").mkdir(parents=True)
    (site / "toy_sensor" / "__init__.py").write_text(textwrap.dedent(TOY), encoding="utf-8")
    info = site / "toy_sensor-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: toy-sensor\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(
        f"[{registry.ENTRY_POINT_GROUP}]\ntoy = toy_sensor:PRODUCT\n")
    monkeypatch.syspath_prepend(str(site))
    registry.products.cache_clear()
    yield tmp_path
    registry.products.cache_clear()


def test_a_fourth_product_is_one_new_package(toy_product):
    import tactcad

    folder = toy_product / "project"
    folder.mkdir()
    (folder / "spring.toml").write_text("[toy]\nk_N_per_mm = 2.0\nforce_N = 1.0\n")
    assert product_of(folder / "spring.toml").name == "toy-spring"
    r = run_cli("strength", "--json", cwd=folder)
    assert r.returncode == 0 and json.loads(r.stdout)["travel_mm"] == 0.5, r.stdout + r.stderr
    assert run_cli("export", "--out", "exports", cwd=folder).returncode == 0
    assert run_cli("check", "--out", "exports", cwd=folder).returncode == 0
    (folder / "spring.toml").write_text("[toy]\nk_N_per_mm = 0.5\nforce_N = 1.0\n")
    assert run_cli("check", "--out", "exports", cwd=folder).returncode == 1  # export stale
    assert run_cli("strength", "--json", cwd=folder).returncode == 1  # 2 mm of travel
    assert tactcad.load(folder / "spring.toml") == (0.5, 1.0)
    refused = run_cli("budget", "--json", cwd=folder)
    assert refused.returncode == 2
    assert "toy-spring" in json.loads(refused.stdout)["error"]["message"]


def test_two_products_claiming_one_table_are_refused(toy_product, monkeypatch):
    shipped = registry._package_products()
    twin = registry.Product(name="twin", summary="", design_table="toy")
    monkeypatch.setattr(registry, "_package_products", lambda: [*shipped, twin])
    registry.products.cache_clear()
    with pytest.raises(ValueError, match="share"):
        registry.products()
