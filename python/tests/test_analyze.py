# SPDX-License-Identifier: Apache-2.0
"""The analysis without a device, on synthetic recordings with a known answer."""

import numpy as np
import pytest

import palp

K_F, I_C, K_V = 2.918, 0.5, 43.9  # the analysis' defaults: N/A, A, N/m


def staircase(reps=2, per_step=8):
    """The 1d ramp's commanded current, 0.5 -> 3 -> 0.5 A by 0.01 A, per_step samples a step."""
    up = np.round(np.arange(0.5, 3.0 + 1e-9, 0.01), 2)
    cycle = np.concatenate([up, up[-2::-1]])
    i = np.repeat(np.tile(cycle, reps), per_step)
    rep = np.repeat(np.repeat(np.arange(reps), len(cycle)), per_step)
    return i, rep


def linear_spring_recording(k_N_per_m, z_c_mm=1.0):
    """A linear specimen: K_f (i - I_c) = (k + k_v) (z - z_c) beyond the contact point."""
    i, rep = staircase()
    z_mm = z_c_mm + 1e3 * K_F * (i - I_C) / (k_N_per_m + K_V)
    t = np.arange(len(i)) * 5e-3
    return {"t_s": t, "i_cmd_A": i, "i_A": i, "z_mm": z_mm, "rep": rep}


def test_a_linear_spring_gives_its_stiffness():
    summary = palp.analyze.indentation(linear_spring_recording(2000.0))
    assert summary["k_linear_N_per_mm"] == pytest.approx(2.0, rel=1e-3)
    assert summary["r2_linear"] == pytest.approx(1.0, abs=1e-9)
    assert summary["repetitions"] == 2


def test_pressure_gives_each_recorded_channels_slope_against_the_object_force():
    columns = linear_spring_recording(2000.0)
    force_N = 2000.0 * np.maximum(columns["z_mm"] - 1.0, 0.0) * 1e-3  # F_o = k (z - z_c)
    columns["p2_Pa"] = 40.0 * force_N  # only channels 2 and 5 recorded
    columns["p5_Pa"] = 100.0 * force_N
    result = palp.analyze.pressure(columns)
    assert [c["channel"] for c in result["channels"]] == [2, 5]
    assert result["channels"][0]["slope_Pa_per_N"] == pytest.approx(40.0, rel=1e-3)
    assert result["channels"][1]["slope_Pa_per_N"] == pytest.approx(100.0, rel=1e-3)
    assert result["contact_point_mm"] == pytest.approx(1.0, abs=1e-3)
    assert result["params"]["kf_N_per_A"] == K_F


def test_pressure_without_pressure_columns_is_a_data_error_saying_so():
    with pytest.raises(palp.DataError, match=r"no pressure column \(p1_Pa \.\. p6_Pa\)"):
        palp.analyze.pressure(linear_spring_recording(2000.0))


def test_a_recording_written_and_read_back_analyses_the_same(tmp_path):
    columns = linear_spring_recording(1000.0)
    palp.write_recording(str(tmp_path / "spring"), palp.Recording(columns))
    loaded = palp.read_recording(str(tmp_path / "spring.csv"))
    assert len(loaded) == len(columns["t_s"])
    assert np.array_equal(loaded.columns["z_mm"], columns["z_mm"])  # bit-exact
    assert loaded.sidecar["schema"] == "palp.recording/1"
    assert palp.analyze.indentation(tmp_path / "spring.csv") == palp.analyze.indentation(columns)


def test_columns_are_checked_with_a_clear_error():
    columns = linear_spring_recording(1000.0)
    del columns["z_mm"]
    with pytest.raises(palp.ConfigError, match="z_mm is missing"):
        palp.analyze.indentation(columns)
    columns = linear_spring_recording(1000.0)
    columns["z_mm"] = columns["z_mm"][:-1]
    with pytest.raises(palp.ConfigError, match="column z_mm has"):
        palp.analyze.indentation(columns)


def test_to_pandas_gives_the_columns_when_pandas_is_installed():
    pandas = pytest.importorskip("pandas")
    frame = palp.analyze.to_pandas(linear_spring_recording(1000.0))
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == ["t_s", "i_cmd_A", "i_A", "z_mm", "rep"]
