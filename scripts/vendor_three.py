"""Refresh the three.js files the review page inlines (``src/tactcad/data/three``).

The release is the one ``web/package.json`` pins; its tarball is fetched with
``npm pack`` and checked against the sha512 ``integrity`` of
``web/package-lock.json`` before anything is written. Only the modules the
page carries (:data:`tactcad.export.review_assets.MODULES`), three's MIT
``LICENSE`` and its ``package.json`` are kept, with a ``SHA256SUMS`` file
that tactcad checks when it builds a page. Run it when the pin changes:

    python scripts/vendor_three.py

npm is needed here, at packaging time only; an installed tactcad never runs it.
"""

from __future__ import annotations

import base64
import hashlib
import json
import shutil
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))
from tactcad.export.review_assets import KEPT_FILES, SUMS_FILE  # noqa: E402

WEB = REPO / "web"
TARGET = REPO / "src" / "tactcad" / "data" / "three"


def pinned() -> tuple[str, str]:
    """(version, sha512 integrity) of ``three`` in the lock file."""
    lock = json.loads((WEB / "package-lock.json").read_text(encoding="utf-8"))
    entry = lock["packages"]["node_modules/three"]
    return entry["version"], entry["integrity"]


def fetch(version: str, integrity: str, into: Path) -> Path:
    """The npm tarball of three@version in ``into``, its sha512 checked."""
    name = subprocess.run(["npm", "pack", f"three@{version}", "--silent"], cwd=into,
                          check=True, capture_output=True, text=True).stdout.strip().splitlines()[-1]
    tarball = into / name
    algo, _, expected = integrity.partition("-")
    digest = base64.b64encode(hashlib.new(algo, tarball.read_bytes()).digest()).decode()
    if digest != expected:
        raise SystemExit(f"{tarball.name}: {algo} {digest} is not the lock file's {expected}")
    return tarball


def main() -> int:
    version, integrity = pinned()
    with tempfile.TemporaryDirectory() as tmp:
        tarball = fetch(version, integrity, Path(tmp))
        with tarfile.open(tarball) as tar:
            tar.extractall(tmp, filter="data")
        package = Path(tmp) / "package"
        if TARGET.exists():
            shutil.rmtree(TARGET)
        sums = []
        for rel in KEPT_FILES:
            dest = TARGET / rel
            dest.parent.mkdir(parents=True, exist_ok=True)
            data = (package / rel).read_bytes()
            dest.write_bytes(data)
            sums.append(f"{hashlib.sha256(data).hexdigest()}  {rel}\n")
    (TARGET / SUMS_FILE).write_text(f"# three {version} ({integrity})\n" + "".join(sums),
                                    encoding="utf-8")
    print(f"three {version}: {len(KEPT_FILES)} files in {TARGET.relative_to(REPO)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
