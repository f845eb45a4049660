"""Every accepted design exports and passes its own ``check``: random designs
drawn over the whole domain (:func:`tactcad.design.domain.draw_design`), each
written as a design file alone in a folder (its rigs and scenes made for it,
as a new lab's first design file gets them), exported and checked through the
command line, as a lab's CI runs it."""

from __future__ import annotations

import random

import pytest
import tomli_w

from tactcad import cli
from depth import draws
from tactcad.design.domain import draw_design

#: How many random designs the slow set exports and checks (seeds from 2000): a share in
#: ``make test``, 30 in ``make test-deep``.
DESIGNS = draws(6, 30)


def export_and_check(seed: int, folder, capsys) -> tuple[int, int, str]:
    """(export's exit code, check's exit code, check's failure lines) of the
    design drawn with ``seed``, written into ``folder``."""
    rng = random.Random(seed)
    data = draw_design(rng.uniform, rng.choice, name=f"domain{seed}")
    # its rigs, scenes and requirements made for its geometry, not those of the
    # file the draw starts from (which another geometry need not meet)
    for section in ("files", "requirements"):
        data.pop(section, None)
    folder.mkdir()
    design = folder / f"domain{seed}.toml"
    design.write_text(tomli_w.dumps(data), encoding="utf-8")
    out, cache = folder / "exports", folder / "cache"
    exported = cli.main(["export", "--design", str(design), "--out", str(out),
                         "--cache", str(cache), "--quiet"])
    capsys.readouterr()
    checked = cli.main(["check", "--design", str(design), "--out", str(out),
                        "--cache", str(cache), "--failures-only"])
    return exported, checked, capsys.readouterr().out


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(2000, 2000 + DESIGNS),
                         ids=lambda s: f"design{s - 1999}of{DESIGNS}")
def test_a_random_design_of_the_domain_exports_and_passes_its_check(seed, tmp_path, capsys):
    exported, checked, failures = export_and_check(seed, tmp_path / "project", capsys)
    assert exported == 0, f"design seed {seed} was not exported"
    assert checked == 0, f"design seed {seed} failed its check:\n{failures}"
