"""``SOURCE_DATE_EPOCH`` read as the date every sheet prints (the reproducible-builds
convention). Its own module, importing nothing heavy: the command line checks the
variable before any import reads it (numpy's f2py turns a bad value into a traceback),
so ``tactcad --version`` does not load the drawing code to do so."""

from __future__ import annotations

import datetime
from typing import Mapping

from tactcad.errors import DesignError

#: The last second of year 9999 (s since 1970-01-01 UTC): the largest epoch allowed.
MAX_EPOCH_S = 253402300799


def epoch_date(environ: Mapping[str, str]) -> str | None:
    """``SOURCE_DATE_EPOCH`` of ``environ`` as an ISO 8601 UTC date, or None when unset or empty.

    Args:
        environ: the environment to read (``os.environ``).

    Returns:
        the date ``YYYY-MM-DD`` (UTC), or None when the variable is unset or empty.

    Raises:
        DesignError: it is not a whole number of seconds (s) in 0 .. 253402300799.
    """
    epoch = environ.get("SOURCE_DATE_EPOCH", "").strip()
    if not epoch:
        return None
    if not epoch.isdigit() or int(epoch) > MAX_EPOCH_S:
        raise DesignError("SOURCE_DATE_EPOCH", epoch, "a whole number of seconds since "
                          "1970-01-01 UTC, 0 .. 253402300799")
    return datetime.datetime.fromtimestamp(int(epoch), datetime.timezone.utc).date().isoformat()
