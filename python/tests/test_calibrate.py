# SPDX-License-Identifier: Apache-2.0
"""palp.calibrate_kf against palp-sim in free air: the table the plant was built with, the keys of
`palpctl calibrate kf --json`, and a real SIGINT that leaves the coil at 0 A and the device's
table as it was."""

import os
import signal
import subprocess
import sys
import textwrap

import pytest

import palp

# the SDK's kf_calibration_json: the keys palpctl calibrate kf --json prints
KEYS = {"anchor", "balance", "c_N", "c_N_se", "calibrate", "committed", "kv_N_per_mm", "levels",
        "nodes", "residual_rms_N", "warning", "written"}


def plant_kf(stroke_mm):
    """The plant's K_f table (hil/plant config.hpp), N/A."""
    if stroke_mm >= 23.5:
        return 2.918
    if stroke_mm >= 17:
        return 2.918 + (23.5 - stroke_mm) * (3.84 - 2.918) / 6.5
    return 3.84 + (17 - stroke_mm) * (3.30 - 3.84) / 17


def test_calibrate_kf_finds_the_plants_table_and_writes_it_to_the_device(sim):
    phases = []
    with sim.probe() as probe:
        run = palp.calibrate_kf(probe, progress=lambda phase, f: phases.append(phase))
        table = probe.calibration()
    assert "staircase" in phases and phases[-1] == "analysing"
    assert run.written and not run.committed and not run.interrupted
    d = run.to_dict()
    assert set(d) == KEYS
    assert d["calibrate"] == "kf" and d["written"] is True and d["committed"] is False
    assert d["anchor"] == {"stroke_mm": 24.0, "kf_N_per_A": 2.918}
    assert len(d["nodes"]) == 16 == len(run.node_stroke_m)  # the block's 16
    for node in d["nodes"]:
        assert set(node) == {"stroke_mm", "kf_N_per_A", "kf_N_per_A_se"}
        truth = plant_kf(node["stroke_mm"])
        assert node["kf_N_per_A"] == pytest.approx(truth, rel=0.02), node
    # the device holds the table now (RAM): 1 count = 1 um, K_f as float32
    assert list(table.kf_position_counts) == [round(s * 1e6) for s in run.node_stroke_m]
    assert list(table.kf_N_per_A) == pytest.approx(run.kf_N_per_A, rel=1e-6)


def test_bad_settings_are_a_config_error_before_the_device_moves(sim):
    s = palp.KfCalibrationSettings()
    s.stop_A = s.start_A
    with sim.probe() as probe:
        with pytest.raises(palp.ConfigError, match="stop_A must lie above start_A"):
            palp.calibrate_kf(probe, s)
        assert probe.status().program_state == "idle"
    s = palp.KfCalibrationSettings()
    s.anchor = None
    assert s.anchor is None
    s.anchor = (0.02, 3.0)
    assert s.anchor == (0.02, 3.0)


CHILD = textwrap.dedent("""
    import socket
    import sys
    import palp
    def coil_A():  # palp-sim's true coil current, from its control channel
        with socket.create_connection(("127.0.0.1", int(sys.argv[2])), timeout=5) as s:
            s.sendall(b"status\\n")
            reply = s.makefile().readline()
        return dict(w.split("=", 1) for w in reply.split() if "=" in w)["coil_A"]
    announced = []
    def progress(phase, fraction):
        if phase == "staircase" and fraction > 0.05 and not announced:
            announced.append(True)
            print("staircase", flush=True)
    probe = palp.Probe(sys.argv[1], timeout_s=10)
    before = list(probe.calibration().kf_N_per_A)
    try:
        palp.calibrate_kf(probe, progress=progress)
        print("finished", flush=True)
    except KeyboardInterrupt:
        status = probe.status()
        same = list(probe.calibration().kf_N_per_A) == before
        print(f"interrupted i_cmd_A={status.i_cmd_A} program_state={status.program_state} "
              f"coil_A={coil_A()} table_unchanged={same}", flush=True)
        raise
""")


def test_sigint_mid_staircase_leaves_the_coil_at_zero_and_the_table_unwritten(sim):
    # paced at 20x real time the default staircase (141 s of device time) takes ~7 s
    assert sim.control("pace 20").startswith("ok")
    child = subprocess.Popen([sys.executable, "-c", CHILD, sim.uri, str(sim.control_port)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "staircase\n"
    os.kill(child.pid, signal.SIGINT)
    out, err = child.communicate(timeout=30)
    assert child.returncode == -signal.SIGINT, (out, err)
    assert "KeyboardInterrupt" in err
    assert out.startswith("interrupted"), out
    words = dict(w.split("=") for w in out.split()[1:])
    assert float(words["i_cmd_A"]) == 0.0
    assert words["program_state"] != "running"
    assert abs(float(words["coil_A"])) < 0.02
    assert words["table_unchanged"] == "True"
