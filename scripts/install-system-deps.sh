#!/bin/sh
# System packages the test suite needs beyond the Python stack:
#   freecad-python3  FreeCAD's headless `freecadcmd`, which opens every
#                    exported STEP file for the design-review test.
#   freecad, xvfb   the FreeCAD GUI under a virtual display, to open a review
#                    file as a reviewer would (its saved camera).
#   chromium         the browser the review page's tests drive headless
#                    (Playwright, pointed at this system Chromium).
#   calculix-ccx     CalculiX's solver `ccx`, the independent *FREQUENCY model
#                    that checks fem3d's natural frequencies.
# Installs only what is missing, and only when it can: as root with apt-get
# (CI). Otherwise it says what to install and exits 0, so that `make test`
# still runs; the FreeCAD test then skips with that reason.
set -eu

missing=""
command -v freecadcmd >/dev/null 2>&1 || missing="$missing freecad-python3"
command -v chromium >/dev/null 2>&1 || missing="$missing chromium"
command -v freecad >/dev/null 2>&1 || missing="$missing freecad"
command -v xvfb-run >/dev/null 2>&1 || missing="$missing xvfb"
command -v ccx >/dev/null 2>&1 || missing="$missing calculix-ccx"

if [ -z "$missing" ]; then
    exit 0
fi
if [ "$(id -u)" != "0" ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "install-system-deps: missing:$missing (install as root: apt-get install -y$missing)" >&2
    exit 0
fi
echo "install-system-deps: installing$missing (a few minutes)" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get install -y $missing >/dev/null 2>&1 || {
    apt-get update >/dev/null
    apt-get install -y $missing >/dev/null
}
command -v freecadcmd >/dev/null 2>&1
command -v chromium >/dev/null 2>&1
command -v freecad >/dev/null 2>&1
command -v xvfb-run >/dev/null 2>&1
command -v ccx >/dev/null 2>&1
