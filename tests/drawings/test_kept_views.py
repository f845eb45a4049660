"""Each part view's projected edges are kept in the result store by the part's spec and
the view: an edit that changes one part re-projects that part's views only, and an edit
that changes every sheet but no solid (the design's date) re-projects none."""

from __future__ import annotations

import json

import pytest

from tactcad import cli
from tactcad.drawings.views import PROJECTION_KIND
from tactcad.store import counting_results

VIEWS_PER_PART = 3  # front, top, left


def _drawn_parts(out) -> set[str]:
    man = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    return {f["part"] for f in man["files"] if f["kind"] == "drawing-svg"}


def _export_drawings(store, out, *extra: str) -> tuple[int, int, set[str]]:
    """(views projected, views read back, parts drawn) of one drawings-only export."""
    with counting_results() as counts:
        code = cli.main(["export", "--quiet", "--cache", str(store), "--out", str(out),
                         "--only", "drawings", *extra])
    assert code == 0
    return (counts.computed.get(PROJECTION_KIND, 0), counts.reused.get(PROJECTION_KIND, 0),
            _drawn_parts(out))


@pytest.mark.slow
def test_one_changed_arm_reprojects_only_that_parts_views(tmp_path, monkeypatch, plan):
    monkeypatch.setenv("TACTCAD_WORKERS", "0")  # the drawings run in this process, counted here
    store, out = tmp_path / "store", tmp_path / "out"
    computed, reused, parts = _export_drawings(store, out)
    assert (computed, reused) == (VIEWS_PER_PART * len(parts), 0)

    arms = [s.geometry.arm_length_mm for s in plan.slots]
    arms[-1] = arms[-1] + 0.5 if arms[-1] + 0.5 <= 8.0 else arms[-1] - 0.5
    changed = "arms.lengths_mm=[" + ", ".join(repr(a) for a in arms) + "]"
    computed, reused, after = _export_drawings(store, out, "--set", changed)
    new_parts = after - parts
    assert len(new_parts) >= 1  # the changed arm's element is a part of its own
    assert computed == VIEWS_PER_PART * len(new_parts)
    # sheets drawn again for an unchanged part (their drawing's inputs moved) read its views back
    assert reused % VIEWS_PER_PART == 0 and reused < VIEWS_PER_PART * len(after)

    # a new date changes every sheet's title block and no solid: every view is read back
    computed, reused, again = _export_drawings(store, out, "--set", changed,
                                               "--set", 'design.date="2031-01-02"')
    assert again == after
    assert (computed, reused) == (0, VIEWS_PER_PART * len(after))
