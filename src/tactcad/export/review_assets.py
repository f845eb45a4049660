"""The JavaScript the review page carries: three.js, its OrbitControls and
GLTFLoader, shipped inside the package (``tactcad/data/three``: the modules
below, three's MIT ``LICENSE``, its ``package.json`` and ``SHA256SUMS``).

The files are the npm release ``web/package.json`` pins, checked against the
lock file's sha512 when ``scripts/vendor_three.py`` copies them in; tactcad
checks each file's sha256 against ``SHA256SUMS`` before a page carries it. An
installed tactcad therefore writes the page with no npm and no network.

A page opened from ``file://`` may not load module files beside it (the
browser refuses them as cross-origin), so every module is inlined into the
page's import map as a ``data:`` URL. three's modules import one another by
relative paths, which a ``data:`` URL cannot resolve; each such path is
rewritten to the bare name the import map gives that module. Nothing else
in the package's text is changed.
"""

from __future__ import annotations

import base64
import hashlib
import json
import os
import re
from functools import lru_cache
from importlib import resources
from importlib.resources.abc import Traversable
from pathlib import PurePosixPath

from tactcad.errors import TactcadError

#: import-map name -> file inside the ``three`` package
MODULES = {
    "three": "build/three.module.js",
    "three/core": "build/three.core.js",
    "three/addons/controls/OrbitControls.js": "examples/jsm/controls/OrbitControls.js",
    "three/addons/loaders/GLTFLoader.js": "examples/jsm/loaders/GLTFLoader.js",
    "three/addons/utils/BufferGeometryUtils.js": "examples/jsm/utils/BufferGeometryUtils.js",
    "three/addons/utils/SkeletonUtils.js": "examples/jsm/utils/SkeletonUtils.js",
}
#: every file kept of the npm package: the modules, the licence, the version
KEPT_FILES = (*MODULES.values(), "LICENSE", "package.json")
#: "<sha256>  <file>" per kept file, first line a comment naming the release
SUMS_FILE = "SHA256SUMS"

_RELATIVE = re.compile(r"""(\bfrom\s*|\bimport\s*)(['"])(\.{1,2}/[^'"]+)\2""")


class ReviewAssetsError(TactcadError):
    """The three.js files shipped with tactcad are missing or changed."""


def three_dir() -> Traversable:
    """The three.js files shipped in the package (``tactcad/data/three``)."""
    return resources.files("tactcad") / "data" / "three"


def _sums() -> str:
    try:
        return (three_dir() / SUMS_FILE).read_text(encoding="utf-8")
    except OSError as exc:
        raise ReviewAssetsError(f"the review page's three.js is missing from this tactcad "
                                f"installation ({exc.strerror}: data/three/{SUMS_FILE}): "
                                "reinstall tactcad") from None


def _checked(rel: str) -> str:
    """The text of ``rel`` of the shipped three.js, its sha256 checked against SHA256SUMS."""
    expected = {name: digest for digest, _, name in
                (line.partition("  ") for line in _sums().splitlines() if not line.startswith("#"))}
    try:
        data = (three_dir() / rel).read_bytes()
    except OSError:
        data = None
    if data is None or hashlib.sha256(data).hexdigest() != expected.get(rel):
        raise ReviewAssetsError(f"data/three/{rel} of this tactcad installation is missing or "
                                f"not the file {SUMS_FILE} names: reinstall tactcad")
    return data.decode("utf-8")


def _rewrite(text: str, own: str) -> str:
    """``text`` with every relative import made the bare import-map name of its file."""
    by_file = {f: name for name, f in MODULES.items()}
    base = PurePosixPath(own).parent

    def bare(m: re.Match) -> str:
        target = os.path.normpath(base / m.group(3)).replace(os.sep, "/")
        if target not in by_file:
            raise ReviewAssetsError(f"{own} imports {m.group(3)}, which the review page does not "
                                    "carry (three's layout changed: update MODULES)")
        return f"{m.group(1)}{m.group(2)}{by_file[target]}{m.group(2)}"
    return _RELATIVE.sub(bare, text)


@lru_cache(maxsize=1)
def _import_map() -> str:
    imports = {}
    for name, rel in MODULES.items():
        text = _rewrite(_checked(rel), rel)
        imports[name] = "data:text/javascript;base64," + base64.b64encode(text.encode()).decode()
    return json.dumps({"imports": imports}, sort_keys=True)


def import_map() -> str:
    """The page's ``<script type="importmap">`` body (JSON), every module inlined.

    Raises:
        ReviewAssetsError: a shipped file is missing or changed, or three's
            layout changed (a module imports a file the page does not carry).
    """
    return _import_map()


def three_version() -> str:
    """The shipped three.js version (its package.json)."""
    return json.loads(_checked("package.json"))["version"]


def assets_identity() -> str:
    """What of the JavaScript shapes the page's bytes (for the job's content key):
    the sha256 of ``SHA256SUMS``, so no module is read until a page is written."""
    return hashlib.sha256(_sums().encode()).hexdigest()
