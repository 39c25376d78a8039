# SPDX-License-Identifier: Apache-2.0
"""Fixtures for the palp module's tests: palp-sim as a process on ephemeral loopback ports.

ctest passes the build's binaries in PALP_SIM and PALPCTL and the importable package root in
PYTHONPATH (python/tests/CMakeLists.txt)."""

import os
import re
import signal
import socket
import subprocess
import time

import pytest

import palp

# replies wait this long: the tests run beside whole builds on two cores (load 10+)
TIMEOUT_S = 10.0

BANNER = re.compile(r"palp-sim listening on tcp://127\.0\.0\.1:(\d+) \(device protocol\), "
                    r"control on tcp://127\.0\.0\.1:(\d+)")

# solid_1d, position 3, the floating tip just touching (as tests/cli/test_palpctl_indent.cpp)
SOLID = ["--phantom", "solid_1d", "--mount-mm", "27", "0", "-25"]


class Sim:
    """palp-sim paced as fast as possible; uri for palp.Probe, control() for its own knobs."""

    def __init__(self, extra=()):
        self.process = subprocess.Popen(
            [os.environ["PALP_SIM"], "--port", "0", "--control-port", "0", "--pace", "fast", *extra],
            stdout=subprocess.PIPE, text=True)
        line = self.process.stdout.readline()
        match = BANNER.search(line)
        if not match:
            self.process.kill()
            raise RuntimeError(f"palp-sim did not start: {line!r}")
        self.port, self.control_port = int(match.group(1)), int(match.group(2))
        robot = re.search(r"robot bridge on tcp://127\.0\.0\.1:(\d+)", line)
        self.robot_uri = f"modbus://127.0.0.1:{robot.group(1)}" if robot else None
        self.uri = f"sim://127.0.0.1:{self.port}"

    def probe(self, **options) -> palp.Probe:
        """A palp.Probe connected to this simulator, patient with a loaded machine."""
        return palp.Probe(self.uri, timeout_s=TIMEOUT_S, **options)

    def control(self, line: str) -> str:
        """One line on palp-sim's control channel; its one-line reply."""
        with socket.create_connection(("127.0.0.1", self.control_port), timeout=5) as s:
            s.sendall((line + "\n").encode())
            reply = b""
            while not reply.endswith(b"\n"):
                chunk = s.recv(4096)
                if not chunk:
                    break
                reply += chunk
        return reply.decode()

    def status(self) -> dict:
        """The control channel's status as a dict of its key=value words."""
        return dict(w.split("=", 1) for w in self.control("status").split() if "=" in w)

    def wait_no_client(self, timeout_s: float = 5.0) -> bool:
        end = time.monotonic() + timeout_s
        while time.monotonic() < end:
            if self.status().get("client") == "0":
                return True
            time.sleep(0.01)
        return False

    def stop(self):
        self.process.send_signal(signal.SIGTERM)
        self.process.wait(timeout=10)


@pytest.fixture
def sim():
    s = Sim()
    yield s
    s.stop()


@pytest.fixture
def solid_sim():
    s = Sim(SOLID)
    yield s
    s.stop()
