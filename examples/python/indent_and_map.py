# SPDX-License-Identifier: Apache-2.0
# %% [markdown]
# # Indent and map with palp from Python
#
# A notebook-style script (cells marked `# %%`, as VS Code and Jupytext read them) against
# palp-sim with its soft-lined pad and its robot bridge:
#
#     palp-sim --phantom pad_2d --robot-port 7072     # prints the three ports it listens on
#     PALP_URI=sim://127.0.0.1:7070 PALP_ROBOT_URI=modbus://127.0.0.1:7072 \
#         python3 examples/python/indent_and_map.py
#
# With the hardware: PALP_URI=usb://<serial>, PALP_ROBOT_URI=modbus://<bridge>, and a rig file of
# the real rig instead of the one written below (docs/rig-and-plan.md). Results go to PALP_OUT
# (default: a new temporary directory). python/tests/test_example.py runs this file.

# %%
import json
import os
import tempfile

import numpy as np

import palp
import palp.analyze

probe_uri = os.environ.get("PALP_URI", "sim://127.0.0.1:7070")
robot_uri = os.environ.get("PALP_ROBOT_URI", "modbus://127.0.0.1:7072")
out = os.environ.get("PALP_OUT") or tempfile.mkdtemp(prefix="palp-example-")
print("palp", palp.sdk_version, "results in", out)

# %% [markdown]
# ## The probe: who it is, and one second of samples as a numpy structured array (SI units)

# %%
probe = palp.Probe(probe_uri)
print(probe.info.serial, "firmware", probe.info.firmware_version)
probe.configure_stream(rate_Hz=1000)
probe.start_stream()
samples, gaps = probe.read(1000, timeout_s=10)
probe.stop_stream()
print(f"{len(samples)} samples, {len(gaps)} gaps; z = {1e3 * samples['z_m'].mean():.3f} mm")
assert np.all(np.diff(samples["index"]) == 1)

# %% [markdown]
# ## The rig and the plan: a 1 x 3 row across the pad (its work object is palp-sim's phantom frame)

# %%
rig_file, plan_file = os.path.join(out, "rig.json"), os.path.join(out, "plan.json")
with open(rig_file, "w") as f:
    json.dump({"format_version": 1, "robot_uri": robot_uri, "probe_uri": probe_uri,
               "tool_tcp_mm_deg": [0, 0, 200, 0, 0, 0], "safe_height_mm": 8,
               "work_object": {"name": "pad", "pose_mm_deg": [600, 0, 300, 0, 0, 180]}}, f)
with open(plan_file, "w") as f:
    json.dump({"format_version": 1, "name": "pad 1 x 3", "work_object": "pad",
               "grid": {"rows": 1, "columns": 3, "origin_mm": [10, 45], "pitch_mm": [40, 40]},
               "contact_E_star_Pa": 3.3e6}, f)
rig, plan = palp.load_rig(rig_file), palp.load_plan(plan_file)
print(plan.name, plan.point_count(), "points")

# %% [markdown]
# ## The map: touch, indent (the 2D protocol, one repetition), retract, at every point.
# Ctrl-C stops the arm, leaves the coil at 0 A and raises the arm to the safe height.

# %%
settings = palp.IndentationSettings.preset("2d")
settings.repetitions = 1
robot = palp.Robot(robot_uri)
stiffness_map = palp.map_plan(probe, robot, rig, plan, os.path.join(out, "map"), settings,
                              progress=lambda done, total, phase: print(f"  {done}/{total} {phase}"))
analysis = palp.analyze_map(stiffness_map)
print("complete:", stiffness_map.complete)
print("k (N/m) per point:", [None if k is None else round(k, 1) for k in analysis.k_N_per_m])
print("soft columns:", analysis.soft_columns)

# %% [markdown]
# ## One point again, without the device: its recording re-analysed (the keys of
# `palpctl analyze indentation --json`), and its columns in pandas when pandas is installed

# %%
point = stiffness_map.to_dict()["points"][0]
csv = os.path.join(out, "map", point["result_dir"], "indentation.csv")
summary = palp.analyze.indentation(csv)
print("model", summary["model_by_aic"], "k_fd", summary["k_fd_N_per_mm"], "N/mm")
try:
    print(palp.analyze.to_pandas(csv).describe())
except ImportError:
    print("(pandas not installed)")
probe.close()
