# SPDX-License-Identifier: Apache-2.0
"""Ctrl-C (a real SIGINT) during palp.indent: the SDK stops the ramp, the coil is at 0 A, and then
Python sees KeyboardInterrupt."""

import os
import signal
import subprocess
import sys
import textwrap

CHILD = textwrap.dedent("""
    import socket
    import sys
    import palp
    def coil_A():  # palp-sim's true coil current, from its control channel
        with socket.create_connection(("127.0.0.1", int(sys.argv[2])), timeout=5) as s:
            s.sendall(b"status\\n")
            reply = s.makefile().readline()
        return dict(w.split("=", 1) for w in reply.split() if "=" in w)["coil_A"]
    settings = palp.IndentationSettings.preset("1d")
    settings.stream_rate_Hz = 200
    announced = []
    def progress(p):
        if p.phase == "ramp" and not announced:
            announced.append(True)
            print("ramp", flush=True)
    probe = palp.Probe(sys.argv[1], timeout_s=10)
    try:
        palp.indent(probe, settings, progress)
        print("finished", flush=True)
    except KeyboardInterrupt:
        status = probe.status()  # still connected: what the SDK left behind
        print(f"interrupted i_cmd_A={status.i_cmd_A} program_state={status.program_state} "
              f"coil_A={coil_A()}", flush=True)
        raise
""")


def test_sigint_mid_ramp_leaves_the_coil_at_zero_and_raises_keyboard_interrupt(solid_sim):
    # paced at 20x real time the 1d preset's ramp takes ~6 s: the SIGINT lands mid-ramp
    assert solid_sim.control("pace 20").startswith("ok")
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, solid_sim.uri, str(solid_sim.control_port)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "ramp\n"
    os.kill(child.pid, signal.SIGINT)
    out, err = child.communicate(timeout=30)
    assert child.returncode == -signal.SIGINT, (out, err)  # Python's exit by KeyboardInterrupt
    assert "KeyboardInterrupt" in err
    words = dict(w.split("=") for w in out.split()[1:])
    assert out.startswith("interrupted"), out
    assert float(words["i_cmd_A"]) == 0.0
    assert words["program_state"] != "running"
    # the simulated coil's true current: at 0 A commanded it rests within the current loop's
    # noise (about 1 mA), far below the ramp's 0.5 A .. 3 A
    assert abs(float(words["coil_A"])) < 0.02
    assert solid_sim.wait_no_client()
    assert abs(float(solid_sim.status()["coil_A"])) < 0.02
