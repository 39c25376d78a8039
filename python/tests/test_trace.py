# SPDX-License-Identifier: Apache-2.0
"""palp.trace against palp-sim's pad and robot bridge: a 1 x 3 row, every point touched, and the
trace file written and read back."""

import json
import math

import pytest

import palp
from conftest import Sim


@pytest.fixture
def pad_sim():
    s = Sim(["--phantom", "pad_2d", "--robot-port", "0"])
    yield s
    s.stop()


def rig_and_plan(sim, tmp_path):
    """The example's rig (the work object is palp-sim's phantom frame) and a 1 x 3 row on the pad."""
    rig_file, plan_file = tmp_path / "rig.json", tmp_path / "plan.json"
    rig_file.write_text(json.dumps({
        "format_version": 1, "robot_uri": sim.robot_uri, "probe_uri": sim.uri,
        "tool_tcp_mm_deg": [0, 0, 200, 0, 0, 0], "safe_height_mm": 8,
        "work_object": {"name": "pad", "pose_mm_deg": [600, 0, 300, 0, 0, 180]}}))
    plan_file.write_text(json.dumps({
        "format_version": 1, "name": "pad 1 x 3", "work_object": "pad",
        "grid": {"rows": 1, "columns": 3, "origin_mm": [10, 45], "pitch_mm": [40, 40]},
        "contact_E_star_Pa": 3.3e6}))
    return palp.load_rig(rig_file), palp.load_plan(plan_file)


def test_a_1_by_3_trace_of_the_pad_touches_every_point_and_round_trips_its_file(pad_sim, tmp_path):
    rig, plan = rig_and_plan(pad_sim, tmp_path)
    done = []
    with pad_sim.probe() as probe:
        surface = palp.trace(probe, palp.Robot(pad_sim.robot_uri), rig, plan,
                             progress=lambda d, total: done.append((d, total)))
    assert surface.complete and surface.stopped_because == ""
    assert (surface.rows, surface.columns, surface.resume_index) == (1, 3, 3)
    assert done[-1] == (3, 3)
    assert [(p.row, p.column) for p in surface.points] == [(1, 1), (1, 2), (1, 3)]
    for p in surface.points:
        assert p.ok, p.reason
        # the grid's points, 40 mm apart along x (mm in the plan, m here)
        assert p.x_m == pytest.approx([0.010, 0.050, 0.090][p.column - 1], abs=1e-3)
        assert p.y_m == pytest.approx(0.045, abs=1e-3)
        assert abs(p.z_m) < 0.5e-3  # the pad's top is its frame's z = 0 plane (traced: -0.05 mm)
        assert math.isclose(math.hypot(*p.normal), 1.0, abs_tol=1e-9)
        assert p.detection_force_N > 0

    palp.save_trace(tmp_path / "trace.json", surface)
    back = palp.load_trace(tmp_path / "trace.json")
    assert back.complete and len(back.points) == 3
    for a, b in zip(surface.points, back.points):
        # trace.json is in mm with finite digits: the points agree to well under a micrometre
        assert (b.x_m, b.y_m, b.z_m) == pytest.approx((a.x_m, a.y_m, a.z_m), abs=1e-7)


def test_a_malformed_trace_file_is_a_config_error_naming_the_file(tmp_path):
    bad = tmp_path / "trace.json"
    bad.write_text("{}")
    with pytest.raises(palp.ConfigError, match="trace.json"):
        palp.load_trace(bad)
