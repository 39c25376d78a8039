# SPDX-License-Identifier: Apache-2.0
"""palp.identify against palp-sim's solid phantom (the multisine in contact), and its result
against palpctl's analysis of the recording it wrote."""

import json
import os
import subprocess

import pytest

import palp


def test_multisine_identification_finds_the_phantoms_resonance_and_reanalyses_the_same(solid_sim, tmp_path):
    settings = palp.IdentificationSettings.preset("contact_multisine")
    assert settings.method == "multisine"
    with solid_sim.probe() as probe:
        run = palp.identify(probe, settings)
    assert run.has_analysis and not run.interrupted, run.analysis_reason
    summary = run.summary()
    assert summary["omega_n_rad_per_s"] == pytest.approx(66.31, rel=0.05)  # the phantom's tuning
    assert "\nf_Hz,re_m_per_N,im_m_per_N,sigma_m_per_N\n" in run.frf_table()  # after its comment line
    written = run.write_result(tmp_path / "sweep")
    csv = os.path.join(written, "sweep.csv")
    # the offline analysis of the recording gives the run's numbers, key for key
    assert palp.analyze.sweep(csv) == summary
    r = subprocess.run([os.environ["PALPCTL"], "--json", "analyze", "sweep", "--input", csv],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    expected = json.loads(r.stdout)
    for key, value in summary.items():
        assert expected.get(key, "absent") == value, key


def test_settings_round_trip_through_their_dict():
    s = palp.IdentificationSettings.preset("free_air")
    assert not s.in_contact
    back = palp.IdentificationSettings.from_dict(s.to_dict())
    assert back.to_dict() == s.to_dict()


def test_the_fast_multisine_preset_is_bound_and_an_unknown_name_lists_the_presets():
    fast = palp.IdentificationSettings.preset("contact_multisine_fast")
    assert fast.method == "multisine" and fast.in_contact
    with pytest.raises(palp.ConfigError, match="one of contact_stepped, contact_multisine, free_air, "
                                               "contact_multisine_fast"):
        palp.IdentificationSettings.preset("fast")
