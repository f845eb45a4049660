"""The program's hold on stop signals while it loads (tactcad.stopping)."""

from __future__ import annotations

import os
import signal

import pytest

from tactcad import stopping


@pytest.fixture
def handlers_kept():
    numbers = stopping.stop_signal_numbers()
    before = {n: signal.getsignal(n) for n in numbers}
    yield
    for n, handler in before.items():
        signal.signal(n, handler)
    stopping._held_while_loading = None


def test_a_ctrl_c_while_loading_is_held_then_raised_once_the_hold_ends(handlers_kept):
    stopping.hold_stops_while_loading()
    os.kill(os.getpid(), signal.SIGINT)
    os.kill(os.getpid(), signal.SIGINT)  # a second one adds nothing
    with pytest.raises(KeyboardInterrupt):
        stopping.act_on_held_stop()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    stopping.act_on_held_stop()  # the hold is over: nothing is raised again


def test_a_held_sigterm_goes_to_the_handler_installed_since(handlers_kept):
    stopping.hold_stops_while_loading()
    os.kill(os.getpid(), signal.SIGTERM)
    got = []
    signal.signal(signal.SIGTERM, lambda n, _f: got.append(n))  # the command's own
    stopping.act_on_held_stop()
    assert got == [signal.SIGTERM]
    assert signal.getsignal(signal.SIGHUP) is signal.SIG_DFL  # still held: back to its default


def test_without_a_hold_nothing_changes(handlers_kept):
    before = signal.getsignal(signal.SIGINT)
    stopping.act_on_held_stop()
    assert signal.getsignal(signal.SIGINT) is before
