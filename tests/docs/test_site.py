"""``make docs``'s build: Sphinx with every warning an error, and a site that
opens from ``file://`` with nothing from the network."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys

import pytest

from doc_pages import DOCS, ROOT

#: What would make a page fetch something: a script, style sheet or picture from a host.
FETCH = re.compile(r"""<(?:script|link|img|iframe)\b[^>]*\b(?:src|href)=["'](?:https?:)?//""", re.I)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    # a copy of the sources: the build writes its generated pages beside them, and a test
    # run writes nothing into the checkout
    source = out / "docs"
    shutil.copytree(DOCS, source, ignore=shutil.ignore_patterns("_build", "_generated"))
    proc = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b",
                           "html", "-d", str(out / "doctrees"), str(source), str(out / "html")],
                          capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    assert proc.returncode == 0, proc.stderr[-4000:]
    assert "WARNING" not in proc.stderr and "ERROR" not in proc.stderr, proc.stderr[-4000:]
    return out / "html"


@pytest.mark.xdist_group("docs-site")  # site: made once, on one worker
@pytest.mark.slow
def test_site_builds_without_warnings_and_fetches_nothing(site):
    pages = sorted(site.rglob("*.html"))
    assert len(pages) > 30
    fetching = [f"{p.relative_to(site)}: {m.group(0)}" for p in pages
                for m in FETCH.finditer(p.read_text(encoding="utf-8"))]
    assert not fetching, "\n".join(fetching)
    lumped = (site / "explanation" / "lumped-model.html").read_text(encoding="utf-8")
    assert not re.search(r"<script[^>]*mathjax", lumped, re.I)  # no MathJax, even a local one


@pytest.mark.xdist_group("docs-site")  # site: made once, on one worker
@pytest.mark.slow
def test_equations_are_mathml_and_the_reference_is_generated(site):
    lumped = (site / "explanation" / "lumped-model.html").read_text(encoding="utf-8")
    assert lumped.count("<math") >= 6 and "<mfrac>" in lumped
    cli = (site / "reference" / "cli.html").read_text(encoding="utf-8")
    for command in ("tactcad export", "tactcad bench export", "tactcad sweep grid",
                    "tactcad calibrate"):
        assert f"<span class=\"pre\">{command.split()[0]}</span>" in cli or command in cli
    assert "--dxf-version" in cli and "&#8211;set" not in cli  # option names as typed
    keys = (site / "reference" / "design-file.html").read_text(encoding="utf-8")
    assert "element.web_thickness_mm" in keys and "scene.&lt;name&gt;.rig" in keys
    api = (site / "reference" / "api.html").read_text(encoding="utf-8")
    assert 'id="tactcad.api.load"' in api and 'id="tactcad.api.Project"' in api
