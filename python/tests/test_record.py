# SPDX-License-Identifier: Apache-2.0
"""palp.record, the SDK recorder, against palp-sim: the files it writes read back with every
sample and the sidecar's keys; bad settings are ConfigErrors before any device is used."""

import os
import signal
import subprocess
import sys

import numpy as np
import pytest

import palp
from conftest import TIMEOUT_S


def test_a_0_2_s_stream_at_2_kHz_records_400_samples_that_read_back_with_the_sidecar(sim, tmp_path):
    out = tmp_path / "run"
    seen = []
    with sim.probe() as probe:
        r = palp.record(probe, out, duration_s=0.2, rate_Hz=2000, reply_timeout_s=TIMEOUT_S,
                        progress=lambda p: seen.append((p.samples, p.finished)))
    assert r.written and not r.interrupted
    assert (r.samples, r.samples_missing, r.gaps) == (400, 0, 0)
    assert r.program is None
    assert os.fspath(r.csv) == os.fspath(tmp_path / "run.csv")
    assert os.fspath(r.sidecar) == os.fspath(tmp_path / "run.json")
    assert seen[-1] == (400, True)  # the last progress call: finished, every sample written

    rec = palp.read_recording(r.csv)
    assert len(rec) == 400
    # 2 kHz: device time advances by exactly 0.5 ms
    assert np.allclose(np.diff(rec.columns["t_s"]), 5e-4, rtol=0, atol=1e-9)
    side = rec.sidecar
    # sidecar_written is the file, key for key, with what the writer added: the time and the
    # CSV's rows and CRC
    assert r.sidecar_written == side
    assert r.sidecar_written["csv_rows"] == 400
    assert r.sidecar_written["csv_crc32"] == side["csv_crc32"] and side["created_utc"]
    assert side["schema"] == "palp.recording/1"
    assert side["program"] is None and side["program_reason"] == "no program ran"
    assert side["device"]["serial"] and side["csv_rows"] == 400
    assert side["zeroing"] == []
    # the recorder's extra keys, at the sidecar's top level
    assert side["gaps"] == [] and side["samples_missing"] == 0
    assert set(side["health"]) >= {"host", "device"}


def test_a_hold_program_is_recorded_with_its_result_in_the_sidecar(sim, tmp_path):
    with sim.probe() as probe:
        r = palp.record(probe, tmp_path / "hold.csv", rate_Hz=1000, reply_timeout_s=TIMEOUT_S,
                        program=palp.HoldProgram(current_A=0.5, duration_s=0.1))
    assert r.program is not None and r.program.end == "completed"
    side = palp.read_recording(r.csv).sidecar
    assert side["program"]["kind"] == "hold"
    assert side["program"]["result"]["end"] == "completed"
    assert np.max(palp.read_recording(r.csv).columns["i_cmd_A"]) == pytest.approx(0.5)


def test_an_existing_recording_is_refused_before_the_device_is_used(sim, tmp_path):
    (tmp_path / "run.csv").write_text("t_s,i_A,z_mm\n")
    with sim.probe() as probe:
        with pytest.raises(palp.ConfigError, match="exists"):
            palp.record(probe, tmp_path / "run", duration_s=0.1)
        with pytest.raises(palp.ConfigError, match="duration"):
            palp.record(probe, tmp_path / "other", duration_s=0)
        with pytest.raises(palp.ConfigError, match="MultisineProgram"):
            palp.record(probe, tmp_path / "other", program=palp.MultisineProgram())
        assert probe.status().streaming is False


RECORD_CHILD = """
import sys
import palp
announced = []
def progress(p):
    if p.samples > 0 and not announced:
        announced.append(True)
        print("recording", flush=True)
probe = palp.Probe(sys.argv[1], timeout_s=10)
try:
    palp.record(probe, sys.argv[2], duration_s=600, rate_Hz=1000, reply_timeout_s=10, progress=progress)
    print("finished", flush=True)
except KeyboardInterrupt:
    rec = palp.read_recording(sys.argv[2])  # written before the exception: what came is kept
    print(f"interrupted rows={len(rec)} flag={rec.sidecar['interrupted']} "
          f"streaming={probe.status().streaming}", flush=True)
    raise
"""


def test_sigint_ends_the_recording_keeps_it_on_disk_and_raises_keyboard_interrupt(sim, tmp_path):
    # paced in real time the 600 s recording is far from its end when the SIGINT lands
    assert sim.control("pace realtime").startswith("ok")
    child = subprocess.Popen([sys.executable, "-c", RECORD_CHILD, sim.uri, str(tmp_path / "run.csv")],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "recording\n"
    os.kill(child.pid, signal.SIGINT)
    out, err = child.communicate(timeout=60)
    assert child.returncode == -signal.SIGINT, (out, err)
    assert "KeyboardInterrupt" in err
    assert out.startswith("interrupted"), out
    words = dict(w.split("=") for w in out.split()[1:])
    assert 0 < int(words["rows"]) < 600_000
    assert words["flag"] == "True" and words["streaming"] == "False"
