"""The ``tactcad`` program (the console script and ``python -m tactcad``).

Its first act holds the stop signals while the command-line modules load
(:func:`tactcad.stopping.hold_stops_while_loading`): Ctrl-C a moment after
the start is the command's interrupt (for ``watch``, its normal end), never
a traceback from the middle of an import.
"""

from tactcad.stopping import hold_stops_while_loading

hold_stops_while_loading()

from tactcad.cli import console  # noqa: E402  (after the hold, by design)

__all__ = ["console"]

if __name__ == "__main__":
    console()
