# SPDX-License-Identifier: Apache-2.0
"""examples/python/indent_and_map.py runs against palp-sim with the pad and the robot bridge."""

import os
import subprocess
import sys

import pytest

from conftest import Sim


@pytest.fixture
def pad_sim():
    s = Sim(["--phantom", "pad_2d", "--robot-port", "0"])
    yield s
    s.stop()


def test_the_notebook_example_maps_the_pad_and_reanalyses_a_point(pad_sim, tmp_path):
    example = os.path.join(os.environ["PALP_SOURCE_DIR"], "examples", "python", "indent_and_map.py")
    env = dict(os.environ, PALP_URI=pad_sim.uri, PALP_ROBOT_URI=pad_sim.robot_uri, PALP_OUT=str(tmp_path))
    r = subprocess.run([sys.executable, example], env=env, capture_output=True, text=True, timeout=280)
    assert r.returncode == 0, r.stderr
    assert "complete: True" in r.stdout
    assert "soft columns: [2]" in r.stdout  # the pad's soft line under the middle point
    assert (tmp_path / "map" / "map.json").exists()
    assert "model " in r.stdout
