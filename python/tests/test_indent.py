# SPDX-License-Identifier: Apache-2.0
"""palp.indent against palp-sim's solid phantom, and its result against palpctl's on the same
recording."""

import json
import os
import subprocess

import pytest

import palp


def indent_once(sim, out_dir):
    settings = palp.IndentationSettings.preset("1d")
    settings.repetitions = 2
    settings.stream_rate_Hz = 200
    phases = []
    with sim.probe() as probe:
        run = palp.indent(probe, settings, lambda p: phases.append(p.phase))
    written = run.write_result(out_dir)
    return run, phases, written


def palpctl_json(*args):
    r = subprocess.run([os.environ["PALPCTL"], "--json", *args], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def test_indentation_result_equals_palpctls_analysis_of_the_recording_it_wrote(solid_sim, tmp_path):
    run, phases, written = indent_once(solid_sim, tmp_path / "solid-p3")
    assert not run.interrupted and run.has_analysis, run.analysis_reason
    assert run.program.end == "completed" and run.program.repetitions_done == 2
    assert phases[0] != "ramp" and "ramp" in phases  # the progress callback saw the phases
    summary = run.summary()
    assert summary["delta0_mm"] == pytest.approx(2.935, rel=0.1)  # the paper's solid, within 10 %
    csv = os.path.join(written, "indentation.csv")
    expected = palpctl_json("analyze", "indentation", "--input", csv)
    for key, value in expected.items():
        if key != "params":
            assert summary.get(key, "absent") == value, key
    # and the offline analysis from Python gives palpctl's dict, key for key
    offline = palp.analyze.indentation(csv)
    params = dict(expected.pop("params"))
    del params["input"], params["kf_table"]
    assert offline.pop("params") == params
    assert offline == expected
    # the pressure-force test: one SDK definition (pressure_analysis_of) behind the run's summary,
    # palpctl analyze pressure and palp.analyze.pressure
    expected_pressure = palpctl_json("analyze", "pressure", "--input", csv)
    offline_pressure = palp.analyze.pressure(csv)
    assert [c["channel"] for c in offline_pressure["channels"]] == [1, 2, 3, 4, 5, 6]
    for key in ("contact_point_mm", "n_loading", "channels"):
        assert offline_pressure[key] == expected_pressure[key] == summary["pressure"][key], key
    assert offline_pressure["params"] == params


def test_settings_round_trip_through_the_result_json_parameters():
    s = palp.IndentationSettings.preset("2d")
    s.analysis.poisson = 0.45
    back = palp.IndentationSettings.from_dict(s.to_dict())
    assert back.dwell_s == 0.025 and back.repetitions == 3
    assert back.analysis.poisson == 0.45
    assert s.to_dict()["analysis"]["poisson"] == 0.45


def test_a_bad_setting_is_a_config_error_naming_it_before_the_device_moves(solid_sim):
    s = palp.IndentationSettings.preset("1d")
    s.stream_rate_Hz = 2000
    with solid_sim.probe() as probe:
        with pytest.raises(palp.ConfigError, match="stream_rate_Hz"):
            palp.indent(probe, s)
        assert probe.status().program_state == "idle"
