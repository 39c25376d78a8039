# SPDX-License-Identifier: Apache-2.0
"""Streaming into numpy against palp-sim: lossless, contiguous, SI fields."""

import numpy as np

import palp


def test_streams_100000_samples_lossless_into_a_structured_array(sim):
    with sim.probe() as probe:
        info = probe.configure_stream(rate_Hz=10000)
        assert info.rate_Hz == 10000
        probe.start_stream()
        samples, gaps = probe.read(100_000, timeout_s=120)
        probe.stop_stream()
        assert len(gaps) == 0, gaps
        assert len(samples) == 100_000
        assert samples.dtype == palp.sample_dtype
        # contiguous indices from the stream's start: nothing lost, nothing repeated
        assert np.array_equal(samples["index"], np.arange(100_000, dtype=np.uint64))
        # device time advances by exactly the period (10 kHz: 100 µs)
        assert np.allclose(np.diff(samples["t_s"]), 1e-4, rtol=0, atol=1e-9)
        assert probe.health().host_samples_missing == 0


def test_sample_fields_carry_si_units_in_their_names(sim):
    names = palp.sample_dtype.names
    assert names == ("index", "t_s", "t_host_s", "i_cmd_A", "i_A", "z_m", "encoder_counts",
                     "p1_Pa", "p2_Pa", "p3_Pa", "p4_Pa", "p5_Pa", "p6_Pa", "status", "v_cmd_V")
    assert palp.gap_dtype.names == ("first_index", "count", "source", "t_s", "count_known")
    with sim.probe() as probe:
        probe.configure_stream(rate_Hz=1000)
        probe.start_stream()
        probe.run(palp.HoldProgram(current_A=0.8, duration_s=0.2), timeout_s=10)
        probe.stop_stream()
        samples, _ = probe.read(10**7, timeout_s=0.5)  # everything queued, the hold included
    # the encoder's counts are µm: z_m is the same position in metres
    assert np.allclose(samples["z_m"], samples["encoder_counts"] * 1e-6)
    assert np.max(samples["i_cmd_A"]) == 0.8  # the held current, as the stream carries it


def test_a_gap_is_a_record_with_its_first_index_and_count(sim):
    # every 3rd device-to-host frame dropped: the SDK sees the missing indices as transport gaps
    assert sim.control("drop-frames 3").startswith("ok")
    with sim.probe(reconnect=False) as probe:
        probe.configure_stream(rate_Hz=1000, batch_samples=10)
        probe.start_stream()
        samples, gaps = probe.read(2000, timeout_s=30)
        probe.stop_stream()
    assert len(gaps) > 0
    assert set(gaps["source"]) == {palp.GAP_SOURCES.index("transport")}
    # samples and gaps together account for every index, without overlap
    covered = np.concatenate([samples["index"]] + [np.arange(g["first_index"], g["first_index"] + g["count"],
                                                              dtype=np.uint64) for g in gaps])
    covered.sort()
    assert np.array_equal(covered, np.arange(covered[0], covered[0] + len(covered), dtype=np.uint64))
