# SPDX-License-Identifier: Apache-2.0
"""palp.set_log_handler: the SDK's log lines from real events on palp-sim (a connect, stream gaps
from lost frames, a dropped robot link reconnected), a handler that raises, and a bad handler."""

import re
import threading

import pytest

import palp
from conftest import Sim


class Lines:
    """A thread-safe handler: the SDK calls it from its I/O threads."""

    def __init__(self):
        self.lock = threading.Lock()
        self.lines = []

    def __call__(self, level, message):
        with self.lock:
            self.lines.append(f"{level}: {message}")

    def text(self):
        with self.lock:
            return "\n".join(self.lines) + "\n"


@pytest.fixture
def lines():
    handler = Lines()
    palp.set_log_handler(handler)
    yield handler
    palp.set_log_handler(None)


def test_connect_and_stream_gaps_from_lost_frames_reach_the_handler(sim, lines):
    assert sim.control("drop-frames 25").startswith("ok")  # every 25th device frame lost
    with sim.probe() as probe:
        probe.configure_stream(rate_Hz=1000)
        probe.start_stream()
        samples, gaps = probe.read(1000)
        probe.stop_stream()
    assert len(gaps) > 0
    text = lines.text()
    assert f"info: connected to {sim.uri}: device SIM-0001" in text, text
    logged = re.findall(r"warning: stream gap: (\d+) samples missing from index (\d+) \(transport\)", text)
    # every gap the read returned was logged, with its count and first index
    assert {(int(g["count"]), int(g["first_index"])) for g in gaps} <= {(int(c), int(i)) for c, i in logged}


def test_a_dropped_robot_link_is_logged_as_lost_and_reconnected(lines):
    s = Sim(["--robot-port", "0"])
    try:
        robot = palp.Robot(s.robot_uri)
        start = robot.pose()
        assert s.control("robot-drop").startswith("ok")
        assert robot.pose().x_m == pytest.approx(start.x_m, abs=1e-6)  # reconnected underneath
        text = lines.text()
        assert re.search(r"warning: robot bridge \S+: the link failed \(.*\): reconnecting\n", text), text
        assert re.search(r"info: robot bridge \S+ reconnected after \S+ s\n", text), text
    finally:
        s.stop()


def test_a_handler_that_raises_is_reported_as_unraisable_and_the_sdk_goes_on(sim, monkeypatch):
    seen = []
    monkeypatch.setattr("sys.unraisablehook", lambda u: seen.append(u))

    def broken(level, message):
        raise RuntimeError("handler bug")

    palp.set_log_handler(broken)
    try:
        with sim.probe() as probe:
            assert probe.status().state  # connected and talking despite the handler
    finally:
        palp.set_log_handler(None)
    assert any(isinstance(u.exc_value, RuntimeError) for u in seen)


def test_a_handler_that_is_not_callable_is_a_config_error():
    with pytest.raises(palp.ConfigError, match="a callable handler\\(level, message\\) or None, not int"):
        palp.set_log_handler(5)
