"""The JavaScript the review page carries: three.js, its OrbitControls and
GLTFLoader, from the npm package ``three`` that ``make env`` installs into
``web/node_modules`` (pinned in ``web/package.json`` and its lock file).

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
from pathlib import Path

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

_RELATIVE = re.compile(r"""(\bfrom\s*|\bimport\s*)(['"])(\.{1,2}/[^'"]+)\2""")


class ReviewAssetsError(TactcadError):
    """The three.js package the review page needs is not installed."""


def three_dir() -> Path:
    """The installed ``three`` package: ``$TACTCAD_THREE_DIR``, else
    ``web/node_modules/three`` of the checkout.

    Raises:
        ReviewAssetsError: not there (run ``make env``).
    """
    env = os.environ.get("TACTCAD_THREE_DIR")
    path = Path(env) if env else Path(__file__).resolve().parents[3] / "web/node_modules/three"
    if not (path / "package.json").is_file():
        raise ReviewAssetsError(
            f"the review page needs the three.js package, not found at {path}: run `make env` "
            "(it installs web/package.json with npm) or set TACTCAD_THREE_DIR")
    return path


def _rewrite(text: str, own: str) -> str:
    """``text`` with every relative import made the bare import-map name of its file."""
    by_file = {f: name for name, f in MODULES.items()}
    base = Path(own).parent

    def bare(m: re.Match) -> str:
        target = os.path.normpath(base / m.group(3)).replace(os.sep, "/")
        if target not in by_file:
            raise ReviewAssetsError(f"{own} imports {m.group(3)}, which the review page does not "
                                    "carry (three's layout changed: update MODULES)")
        return f"{m.group(1)}{m.group(2)}{by_file[target]}{m.group(2)}"
    return _RELATIVE.sub(bare, text)


@lru_cache(maxsize=2)
def _import_map(root: str) -> tuple[str, str]:
    imports = {}
    for name, rel in MODULES.items():
        text = _rewrite((Path(root) / rel).read_text(encoding="utf-8"), rel)
        imports[name] = "data:text/javascript;base64," + base64.b64encode(text.encode()).decode()
    doc = json.dumps({"imports": imports}, sort_keys=True)
    return doc, hashlib.sha256(doc.encode()).hexdigest()


def import_map() -> str:
    """The page's ``<script type="importmap">`` body (JSON), every module inlined.

    Raises:
        ReviewAssetsError: the package is missing or its layout changed.
    """
    return _import_map(str(three_dir()))[0]


def three_version() -> str:
    """The installed three.js version (its package.json)."""
    return json.loads((three_dir() / "package.json").read_text(encoding="utf-8"))["version"]


def assets_identity() -> str:
    """What of the JavaScript shapes the page's bytes (for the job's content key)."""
    return _import_map(str(three_dir()))[1]
