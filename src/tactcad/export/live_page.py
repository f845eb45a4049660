"""The review page's parts as ``tactcad watch`` serves them.

An update under watch should not make the browser download and parse the
whole page again (6 MB, half of it three.js, which never changes), nor every
drawing sheet when one changed. The server holds, per published state:

* ``data``: the page's data (``GET /data``), in which each scene's GLB and
  each sheet's SVG is named by its sha256, not carried;
* ``glbs`` and ``sheets``: those bytes by their sha256 (``GET /scene/<sha256>``,
  ``GET /sheet/<sha256>``), so the page fetches a scene or a sheet only when
  its bytes changed, and does not parse a scene into three.js again when they
  did not.

``GET /`` serves the exported page as it is: the page itself reads ``/data``
when it finds itself served (``review_page.js``).

Pure functions; the server holds the results.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

from tactcad.export.review_page import ReviewContents

CHECKS_PREFIX = "window.TACTCAD_CHECKS = "


@dataclass(frozen=True)
class LiveView:
    """One published state of the page, split for the server (see the module doc)."""

    data: bytes = b"null"  # GET /data
    glbs: dict[str, bytes] = field(default_factory=dict)  # sha256 -> GLB bytes
    sheets: dict[str, bytes] = field(default_factory=dict)  # sha256 -> SVG bytes


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


def live_view(contents: ReviewContents | None, seq: int, sha256: str,
              checks: str | None) -> LiveView:
    """The server's view of ``contents`` as state ``seq`` of design ``sha256``:
    ``GET /data`` is ``{"seq", "sha256", "checks", "data"}`` (``data`` None
    when there is no review page to show), with the check results' JSON text
    as it is (not parsed again)."""
    head = json.dumps({"seq": seq, "sha256": sha256})
    if contents is None:
        return LiveView(data=(head[:-1] + ', "checks": null, "data": null}').encode("utf-8"))
    data = json.dumps(contents.data, sort_keys=True, ensure_ascii=False, allow_nan=False)
    body = head[:-1] + f', "checks": {checks or "null"}, "data": {data}}}'
    glbs = {contents.data["scene_sha256"][n]: glb for n, glb in contents.scenes.items()}
    return LiveView(body.encode("utf-8"), glbs, dict(contents.sheets))
