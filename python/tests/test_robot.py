# SPDX-License-Identifier: Apache-2.0
"""The robot's motions one by one against palp-sim's robot bridge over solid_1d: linear moves to
the micrometre, guarded approaches (the force guard on the resin, max travel in free air), hold,
and a real SIGINT during a slow move that stops the arm."""

import math
import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

import palp
from conftest import Sim

PROBE_TCP = palp.Pose(z_m=0.2)  # the tip 200 mm along the flange's z (tests/host/sim)


@pytest.fixture
def robot_sim():
    s = Sim(["--robot-port", "0", "--phantom", "solid_1d"])
    yield s
    s.stop()


def connect(sim):
    robot = palp.Robot(sim.robot_uri)
    robot.set_tool(1, PROBE_TCP)
    return robot


def distance(a, b):
    return math.dist((a.x_m, a.y_m, a.z_m), (b.x_m, b.y_m, b.z_m))


def test_move_lin_and_move_lin_rel_end_at_their_targets(robot_sim):
    robot = connect(robot_sim)
    start = robot.pose()
    assert robot.status().state == "idle" and robot.status().tool == 1
    # the tool starts 50 mm above the phantom origin (600, 0, 300) mm, pointing down (C = 180 deg)
    assert (start.x_m, start.y_m, start.z_m) == pytest.approx((0.6, 0.0, 0.35), abs=1e-6)
    target = palp.Pose(start.x_m + 0.010, start.y_m - 0.005, start.z_m + 0.002,
                       start.a_rad, start.b_rad, start.c_rad)
    r = robot.move_lin(target, 0.1)
    assert r.result == "done" and r.guard_fired == [] and r.latched is None
    assert distance(r.final_pose, target) < 2e-6  # the registers' micrometre
    assert distance(robot.pose(), target) < 2e-6
    # an offset in the tool's frame: its z points down, so +z is down in the base frame
    r = robot.move_lin_rel(palp.Pose(z_m=0.004), 0.1)
    assert r.result == "done"
    assert r.final_pose.z_m == pytest.approx(target.z_m - 0.004, abs=2e-6)
    assert (r.final_pose.x_m, r.final_pose.y_m) == pytest.approx((target.x_m, target.y_m), abs=2e-6)
    robot.hold()
    assert robot.status().state == "idle"


def test_a_force_guarded_approach_onto_the_resin_stops_on_the_force_guard(robot_sim):
    robot = connect(robot_sim)
    robot.move_lin_rel(palp.Pose(x_m=0.027, z_m=0.047), 0.1)  # 3 mm above position 3
    g = palp.GuardedApproach()
    assert g.axis == "tool_z"
    g.speed_m_per_s = 0.005
    g.max_travel_m = 0.02
    g.force_threshold_N = 2.0
    r = robot.guarded_approach(g)
    assert r.result == "guard_fired" and r.guard_fired == ["force"]
    # the coil sits at its rear stop: 2 N of the resin's reaction is reached a few mm in
    assert r.latched is not None and 0.294 < r.latched.z_m < 0.300
    assert r.final_pose.z_m < r.latched.z_m  # braked on after the latch
    assert robot.status().force_N >= 1.8


def test_a_guarded_approach_in_free_air_ends_at_its_max_travel(robot_sim):
    robot = connect(robot_sim)
    before = robot.pose()
    g = palp.GuardedApproach()
    g.speed_m_per_s = 0.01
    g.max_travel_m = -0.003  # up, away from the phantom
    r = robot.guarded_approach(g)
    assert r.result == "max_travel" and r.guard_fired == []
    assert r.final_pose.z_m == pytest.approx(before.z_m + 0.003, abs=2e-6)


def test_a_bad_axis_is_a_config_error_naming_the_axes():
    g = palp.GuardedApproach()
    with pytest.raises(palp.ConfigError, match=r'axis: unknown value "down" \(one of none, tool_x'):
        g.axis = "down"
    g.axis = "base_z"
    assert g.axis == "base_z"


CHILD = textwrap.dedent("""
    import sys
    import palp
    robot = palp.Robot(sys.argv[1])
    robot.set_tool(1, palp.Pose(z_m=0.2))
    start = robot.pose()
    target = palp.Pose(start.x_m + 0.05, start.y_m, start.z_m, start.a_rad, start.b_rad, start.c_rad)
    print("moving", flush=True)
    try:
        robot.move_lin(target, 0.005)  # 10 s of robot time
        print("finished", flush=True)
    except KeyboardInterrupt:
        s = robot.status()
        print(f"interrupted state={s.state} moved_m={s.pose.x_m - start.x_m}", flush=True)
        raise
""")


def test_sigint_during_a_slow_move_stops_the_arm_and_raises_keyboard_interrupt(robot_sim):
    assert robot_sim.control("pace realtime").startswith("ok")
    child = subprocess.Popen([sys.executable, "-c", CHILD, robot_sim.robot_uri],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "moving\n"
    time.sleep(1.0)
    os.kill(child.pid, signal.SIGINT)
    out, err = child.communicate(timeout=30)
    assert child.returncode == -signal.SIGINT, (out, err)
    assert "KeyboardInterrupt" in err
    assert out.startswith("interrupted"), out
    words = dict(w.split("=") for w in out.split()[1:])
    assert words["state"] == "idle"  # stopped and stationary
    assert 0.0 < float(words["moved_m"]) < 0.04  # stopped on the way, far from the 50 mm
