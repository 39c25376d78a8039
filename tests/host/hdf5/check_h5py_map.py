# SPDX-License-Identifier: Apache-2.0
"""An independent reader of a real map: palp-hdf5-sim-map mapped a 2 x 2 grid on palp-sim into
DIR/map and exported DIR/map.h5; Debian's h5py reads the file and its values equal what the
directory says: map.json's k_fd per point in the grid and on each point, its touches in the
surface grids, every point's samples
equal to its CSV (Python's csv and float(), exact), each repetition's rows those of its rep.

usage: /usr/bin/python3 check_h5py_map.py DIR"""
import csv
import json
import math
import os
import sys

import h5py
import numpy as np

root = sys.argv[1]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def text(value):
    return value.decode("utf-8") if isinstance(value, bytes) else value


with open(os.path.join(root, "map", "map.json"), encoding="utf-8") as fh:
    mj = json.load(fh)
with h5py.File(os.path.join(root, "map.h5"), "r") as f:
    m = f["map"]
    check(json.loads(text(m.attrs["map_json"])) == mj, "map_json is map.json")
    k = m["analysis/k_fd_N_per_mm"][:]
    check(k.shape == (mj["rows"], mj["columns"]) == (2, 2), f"grid shape {k.shape}")
    check(text(m["analysis/k_fd_N_per_mm"].attrs["unit"]) == "N/mm", "grid unit")
    check(len(mj["points"]) == 4, f"{len(mj['points'])} points in map.json")
    for sp in mj["surface"]["points"]:  # the surface grids hold map.json's touches exactly
        r, c = sp["row"] - 1, sp["column"] - 1
        for axis, name in enumerate(("x", "y", "z")):
            check(m["surface/contact_" + name + "_mm"][r, c] == sp["contact_mm"][axis], f"surface {name} at {r + 1},{c + 1}")
            check(m["surface/normal_" + name][r, c] == sp["normal"][axis], f"normal {name} at {r + 1},{c + 1}")
        check(m["surface/tilt_deg"][r, c] == sp["tilt_deg"], f"tilt at {r + 1},{c + 1}")
    for pt in mj["points"]:
        name = f"r{pt['row']}_c{pt['column']}"
        g = m["points"][name]
        want = pt["k_fd_N_per_mm"]
        check(isinstance(want, float) and want > 0, f"{name}: map.json k_fd {want}")
        check(k[pt["row"] - 1, pt["column"] - 1] == want, f"{name}: grid {k[pt['row'] - 1, pt['column'] - 1]} != {want}")
        check(g.attrs["k_fd_N_per_mm"] == want, f"{name}@k_fd_N_per_mm")
        with open(os.path.join(root, "map", pt["result_dir"], "result.json"), encoding="utf-8") as fh:
            result = json.load(fh)
        check(json.loads(text(g.attrs["result_json"])) == result, f"{name}: result_json is result.json")
        check(g["analysis"].attrs["k_fd_N_per_mm"] == result["analysis"]["k_fd_N_per_mm"], f"{name}/analysis")
        rec = g["recordings/indentation.csv"]
        with open(os.path.join(root, "map", pt["result_dir"], "indentation.csv"), newline="", encoding="utf-8") as fh:
            rows = [r for r in csv.reader(line for line in fh if not line.startswith("#"))]
        header, data = rows[0], rows[1:]
        check(int(rec.attrs["rows"]) == len(data) > 100, f"{name}: {rec.attrs['rows']} rows, the CSV {len(data)}")
        for col in ("t_s", "i_A", "z_mm", "p1_Pa"):
            values = [float(r[header.index(col)]) for r in data]
            check(list(rec[col][:]) == values, f"{name}/{col} differs from the CSV")
        side = json.loads(text(rec.attrs["sidecar"]))
        check(text(rec.attrs["device.protocol"]) == side["device"]["protocol"], f"{name}: device.protocol")
        check(rec.attrs["calibration.spring_k_N_per_mm"] == side["calibration"]["spring_k_N_per_mm"], f"{name}: calibration")
        check(text(rec.attrs["device.firmware_version"]) == side["device"]["firmware_version"], f"{name}: firmware")
        reps = rec["rep"][:]
        groups = sorted(g["repetitions"].keys())
        check(groups == ["rep0", "rep1"], f"{name}: repetitions {groups}")
        for gname in groups:
            a = g["repetitions"][gname].attrs
            part = reps[int(a["first_row"]):int(a["first_row"]) + int(a["rows"])]
            check(len(part) > 0 and set(part) == {int(a["rep"])}, f"{name}/{gname}: its rows")
            check(math.isfinite(a.get("k_fd_N_per_mm", math.nan)), f"{name}/{gname}: no k_fd")
        kr = [g["repetitions"][n].attrs["k_fd_N_per_mm"] for n in groups]
        sd = result["analysis"]["k_fd_N_per_mm_sd"]
        check(abs(np.std(kr, ddof=1) - sd) <= 1e-6 * sd, f"{name}: repetitions' k_fd s.d. {np.std(kr, ddof=1)} != {sd}")

if failures:
    print("h5py check of the palp-sim map failed:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("h5py: the palp-sim map's file equals its map.json, result.json and CSVs")
