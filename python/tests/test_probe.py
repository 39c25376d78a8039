# SPDX-License-Identifier: Apache-2.0
"""palp.Probe against palp-sim: info, status, params, calibration, health, programs."""

import pytest

import palp


def test_info_and_status_describe_the_simulator(sim):
    with sim.probe() as probe:
        assert probe.info.serial == "SIM-0001"
        assert probe.info.control_rate_Hz == 20000
        assert probe.uri == sim.uri
        status = probe.status()
        assert status.state == "idle" and status.program_state == "idle"
        assert status.i_cmd_A == 0.0


def test_params_are_read_set_and_read_back(sim):
    with sim.probe() as probe:
        params = probe.params()
        assert params.current_clamp_A == pytest.approx(3.2)
        assert "current_clamp_A" in palp.Params.fields
        params.current_clamp_A = 2.5
        probe.set_params(params)
        assert probe.params().current_clamp_A == pytest.approx(2.5)
        assert probe.params().to_dict()["contact_output"] == params.contact_output


def test_calibration_lists_its_tables(sim):
    with sim.probe() as probe:
        cal = probe.calibration()
        assert len(cal.pressure_gain) == 6
        assert len(cal.kf_N_per_A) == len(cal.kf_position_counts)


def test_a_hold_program_runs_to_its_end(sim):
    with sim.probe() as probe:
        result = probe.run(palp.HoldProgram(current_A=0.3, duration_s=0.5), timeout_s=10)
        assert result.kind == "hold" and result.end == "completed"
        assert result.t_device_s >= 0.5
        assert probe.health().device_valid


def test_program_fields_are_keyword_arguments_with_catalogue_defaults():
    ramp = palp.RampProgram(stop_A=2.0)
    assert ramp.start_A == pytest.approx(0.5) and ramp.stop_A == 2.0
    assert ramp == palp.RampProgram(stop_A=2.0)
    with pytest.raises(palp.ConfigError, match="no field \"stop_mA\""):
        palp.RampProgram(stop_mA=2.0)


def test_list_devices_answers_a_list_without_usb():
    assert isinstance(palp.list_devices(), list)
