"""The review page as ``tactcad watch`` serves it, and its data on their own.

An update under watch should not make the browser download and parse the
whole page again (6 MB, half of it three.js, which never changes). From each
page the watch publishes, :func:`live_view` takes:

* ``data``: the text of the page's ``review-data`` element (the drawings, BOM,
  elements, manifest facts), sent as ``GET /data`` with the scenes' digests;
* ``glbs``: every scene's GLB bytes by their sha256 (``GET /scene/<sha256>``),
  so the page fetches a scene only when its bytes changed, and does not
  parse a scene again into three.js when they did not;
* ``page``: the page to serve at ``/``: the export's page with the tail of
  its script (the export's own live reload, which re-reads the whole page)
  replaced by ``data/review_live.js``. The exported file is not changed.

Pure functions of the page's bytes; the server holds the results.
"""

from __future__ import annotations

import base64
import hashlib
import json
import re
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources

from tactcad.export.review_page import _json_in_html

#: where the export's script hands over to its live reload (review_page.js)
LIVE_TAIL_MARK = b"// --- live reload under `tactcad watch`"
CHECKS_PREFIX = "window.TACTCAD_CHECKS = "


@dataclass(frozen=True)
class LiveView:
    """One published page, split for the server (see the module doc)."""

    page: bytes
    data: str | None  # JSON text of review-data; None for a page without it
    scenes: dict[str, str] = field(default_factory=dict)  # scene name -> sha256 of its GLB
    glbs: dict[str, bytes] = field(default_factory=dict)  # sha256 -> GLB bytes


@lru_cache(maxsize=1)
def _live_script() -> bytes:
    return (resources.files("tactcad") / "data" / "review_live.js").read_bytes()


def _element_text(page: bytes, element_id: str) -> bytes | None:
    """The text of ``<script ... id="element_id">`` (its JSON has no ``<``)."""
    found = re.search(rb'<script type="application/json" id="' + element_id.encode() + rb'">',
                      page)
    if found is None:
        return None
    end = page.find(b"</script>", found.end())
    return page[found.end():end] if end >= 0 else None


def live_view(page: bytes, seq: int) -> LiveView:
    """Split a review page (``review/index.html`` bytes) for ``tactcad watch``;
    ``seq`` is the sequence number the served page starts polling from.

    A page without the review elements (not a review page) is served as it is.
    """
    data, scenes_text = _element_text(page, "review-data"), _element_text(page, "review-scenes")
    if data is None or scenes_text is None:
        return LiveView(page=page, data=None)
    glbs, scenes = {}, {}
    for name, text in json.loads(scenes_text).items():
        glb = base64.b64decode(text)
        digest = hashlib.sha256(glb).hexdigest()
        scenes[name], glbs[digest] = digest, glb
    return LiveView(page=_with_live_script(page, seq, scenes), data=data.decode("utf-8"),
                    scenes=scenes, glbs=glbs)


def _with_live_script(page: bytes, seq: int, scenes: dict[str, str]) -> bytes:
    """The page with its script's live-reload tail replaced by the watch's."""
    start = page.rfind(LIVE_TAIL_MARK)
    end = page.find(b"</script>", start)
    if start < 0 or end < 0:
        return page
    live = _live_script().replace(
        b"@@LIVE@@", _json_in_html({"seq": seq, "scenes": scenes}).encode("utf-8"))
    return page[:start] + live + page[end:]


def checks_json(script: str | None) -> str | None:
    """The JSON text of a ``review/checks.js`` (``window.TACTCAD_CHECKS = {...};``), or None."""
    if not script or not script.startswith(CHECKS_PREFIX):
        return None
    text = script[len(CHECKS_PREFIX):].rstrip().rstrip(";")
    try:
        json.loads(text)
    except ValueError:  # not one tactcad wrote: the page shows no results
        return None
    return text


def data_body(view: LiveView, seq: int, sha256: str, checks: str | None) -> bytes:
    """``GET /data``: ``{"seq", "sha256", "scenes": {name: sha256}, "checks", "data"}``,
    the page's data and check results as the JSON texts they are (not parsed again)."""
    head = json.dumps({"seq": seq, "sha256": sha256, "scenes": view.scenes}, sort_keys=True)
    return (head[:-1] + f', "checks": {checks or "null"}, "data": {view.data or "null"}}}'
            ).encode("utf-8")
