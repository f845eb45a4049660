#!/bin/sh
# System packages the test suite needs beyond the Python stack:
#   freecad-python3  FreeCAD's headless `freecadcmd`, which opens every
#                    exported STEP file for the design-review test.
# Installs only what is missing, and only when it can: as root with apt-get
# (CI). Otherwise it says what to install and exits 0, so that `make test`
# still runs; the FreeCAD test then skips with that reason.
set -eu

missing=""
command -v freecadcmd >/dev/null 2>&1 || missing="$missing freecad-python3"

if [ -z "$missing" ]; then
    exit 0
fi
if [ "$(id -u)" != "0" ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "install-system-deps: missing:$missing (install as root: apt-get install -y$missing)" >&2
    exit 0
fi
echo "install-system-deps: installing$missing (about a minute)" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get install -y $missing >/dev/null 2>&1 || {
    apt-get update >/dev/null
    apt-get install -y $missing >/dev/null
}
command -v freecadcmd >/dev/null 2>&1
