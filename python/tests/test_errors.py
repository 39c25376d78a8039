# SPDX-License-Identifier: Apache-2.0
"""The SDK's exceptions as Python classes, with the C++ message and fields."""

import builtins
import socket

import pytest

import palp


def test_the_classes_mirror_the_sdk_hierarchy():
    for name in ("ConfigError", "ConnectionError", "TimeoutError", "VersionError", "DeviceError",
                 "FaultError", "ProtocolError", "RecordingError", "DataError", "RobotRejectedError",
                 "RobotFaultError", "FlashError", "RobotLinkError"):
        assert issubclass(getattr(palp, name), palp.Error), name
    assert issubclass(palp.RobotLinkError, palp.ConnectionError)
    assert issubclass(palp.ConnectionError, builtins.ConnectionError)
    assert issubclass(palp.TimeoutError, builtins.TimeoutError)
    assert issubclass(palp.ConfigError, ValueError)


def test_a_bad_uri_is_a_config_error_with_the_sdks_message():
    with pytest.raises(palp.ConfigError) as e:
        palp.Probe("nonsense://x")
    assert "nonsense" in str(e.value)


def test_an_absent_device_is_a_connection_error():
    with socket.socket() as s:  # a loopback port nothing listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with pytest.raises(palp.ConnectionError) as e:
        palp.Probe(f"sim://127.0.0.1:{port}", reconnect=False)
    assert str(port) in str(e.value)


def test_a_malformed_recording_is_a_recording_error_naming_file_and_line(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("t_s,i_A,z_mm\n0,0.5,1\n0.1,abc,1\n")
    with pytest.raises(palp.RecordingError) as e:
        palp.read_recording(str(bad))
    assert e.value.file.endswith("bad.csv") and e.value.line == 3
    assert "abc" in str(e.value) and str(e.value).startswith(str(bad))


def test_a_refused_parameter_is_a_device_error_with_its_code(sim):
    with sim.probe() as probe:
        params = probe.params()
        params.control_rate_Hz = 12345  # in the catalogue's range, refused by the device
        with pytest.raises(palp.DeviceError) as e:
            probe.set_params(params)
        assert e.value.request == "SetParams" and e.value.code != 0
        assert "out_of_range" in str(e.value)


def test_a_message_field_refuses_an_unknown_enum_name():
    with pytest.raises(palp.ConfigError, match="unknown value \"sideways\""):
        palp.Params(contact_output="sideways")
