#!/bin/sh
# The lower bounds of pyproject.toml's ranges, tried: a throwaway venv gets the
# lowest version each range allows (the CAD stack's exact pins as they are),
# then tactcad from this checkout, then the fast tests of the estimators, the
# design files and an export of the STEP files. $1: the Python to use.
set -eu
python="${1:-python3}"
here=$(CDPATH= cd -- "$(dirname -- "$0")/.." && pwd)
venv=$(mktemp -d)/venv
trap 'rm -rf "$(dirname "$venv")"' EXIT
"$python" -m venv "$venv"
"$venv/bin/pip" install --quiet --upgrade pip
lows=$("$venv/bin/python" - "$here/pyproject.toml" <<'PY'
import re, sys, tomllib
deps = tomllib.load(open(sys.argv[1], "rb"))["project"]["dependencies"]
for d in deps:
    m = re.match(r"^([A-Za-z0-9_.-]+)\s*(==|>=)\s*([^,;\s]+)", d)
    print(f"{m[1]}=={m[3]}" if m else d)
PY
)
echo "lowest versions: $(echo $lows)"
"$venv/bin/pip" install --quiet --prefer-binary $lows
"$venv/bin/pip" install --quiet --no-deps -e "$here"
"$venv/bin/pip" install --quiet pytest hypothesis
cd "$here"
"$venv/bin/python" -m pytest -q -p no:cacheprovider tests/mechanics/test_closed_form.py tests/design/test_array.py \
    tests/design/test_validation.py tests/design/test_project_folder.py
"$venv/bin/python" -m tactcad.cli export --only step --no-cache --quiet --out "$(dirname "$venv")/exports"
echo "lower bounds: passed"
