# SPDX-License-Identifier: Apache-2.0
"""palp.map_plan's issue-24 options against palp-sim's pad and robot bridge: an adaptive 1 x 3 map
with a force limit and the dynamic identification at every point (map.json says so and every
point has its omega_n and zeta), and the refusals before anything moves."""

import json

import pytest

import palp
from conftest import Sim
from test_trace import rig_and_plan


@pytest.fixture
def pad_sim():
    s = Sim(["--phantom", "pad_2d", "--robot-port", "0"])
    yield s
    s.stop()


def test_an_adaptive_force_limited_dynamic_map_records_its_options_and_each_points_dynamics(
        pad_sim, tmp_path):
    rig, plan = rig_and_plan(pad_sim, tmp_path)
    settings = palp.IndentationSettings.preset("2d")
    settings.repetitions = 1
    with pad_sim.probe() as probe:
        m = palp.map_plan(probe, palp.Robot(pad_sim.robot_uri), rig, plan, tmp_path / "map",
                          settings, adaptive=True, max_points=3, max_force_N=3.0, dynamic=True)
    assert m.complete
    doc = m.to_dict()
    on_disk = json.loads((tmp_path / "map" / "map.json").read_text())
    assert doc["max_force_N"] == on_disk["max_force_N"] == 3.0
    assert doc["adaptive"]["max_points"] == 3
    assert len(doc["points"]) == 3
    for p in doc["points"]:
        assert p["indented"], p
        # the pad's contact resonance at the 1.0 A bias (excite's figures: 112-155 rad/s)
        assert 90 < p["omega_n_rad_per_s"] < 180, p
        assert 0.05 < p["zeta"] < 0.4, p
        assert (tmp_path / "map" / p["dynamic_dir"] / "result.json").is_file()


def test_an_unknown_alignment_and_a_budget_below_the_coarse_design_are_refused(pad_sim, tmp_path):
    rig, plan = rig_and_plan(pad_sim, tmp_path)
    with pad_sim.probe() as probe:
        robot = palp.Robot(pad_sim.robot_uri)
        with pytest.raises(palp.ConfigError) as e:
            palp.map_plan(probe, robot, rig, plan, tmp_path / "a", align="sideways")
        assert str(e.value) == 'map_plan: align must be "none" or "normal" (got "sideways")'
        with pytest.raises(palp.ConfigError) as e:
            palp.map_plan(probe, robot, rig, plan, tmp_path / "b", adaptive=True, max_points=2)
        assert str(e.value).startswith("adaptive grid: ")
    assert not (tmp_path / "a" / "map.json").exists()
    assert not (tmp_path / "b" / "map.json").exists()
