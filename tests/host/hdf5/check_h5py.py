# SPDX-License-Identifier: Apache-2.0
"""An independent reader of palp's HDF5 files: Debian's h5py opens the files palp-hdf5-fixture
wrote from the known synthetic recording, result, map and identification
(tests/host/hdf5/hdf5_fixture.hpp) and reads the known values, and every dataset's unit is the
one docs/hdf5-format.md states.

usage: /usr/bin/python3 check_h5py.py docs/hdf5-format.md FIXTURE_DIR"""
import json
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hdf5_doc_layout  # noqa: E402

doc, fixture = sys.argv[1], sys.argv[2]
failures = []


def text(value):
    """A palp string attribute: fixed-length UTF-8, which h5py gives as bytes."""
    return value.decode("utf-8") if isinstance(value, bytes) else value


def check(cond, what):
    if not cond:
        failures.append(what)


def check_recording(g, where):
    check(list(g["t_s"][:]) == [1.2, 1.201, 1.202, 1.203, 1.204], f"{where}/t_s values")
    check(g["t_s"].dtype == np.float64, f"{where}/t_s dtype {g['t_s'].dtype}")
    check(list(g["i_A"][:]) == [0.5012, 0.4987, 0.5093, 0.5104, 0.5211], f"{where}/i_A values")
    z = g["z_mm"][:]
    check(z[1] == 0.0 and np.signbit(z[1]), f"{where}/z_mm[1] is -0.0")
    check(z[4] == 1.2009999999999998, f"{where}/z_mm[4] exact")
    check(list(g["sample_index"][:]) == [1200, 1201, 1202, 1203, 1204], f"{where}/sample_index")
    check(g["sample_index"].dtype == np.uint64, f"{where}/sample_index dtype")
    check(list(g["status"][:]) == [33, 33, 33, 161, 33], f"{where}/status values")
    check(g["status"].dtype == np.uint16, f"{where}/status dtype")
    check(list(g["rep"][:]) == [0, 0, 0, 1, 1], f"{where}/rep values")
    check(g["rep"].dtype == np.int32, f"{where}/rep dtype")
    check(list(g["p6_Pa"][:]) == [1.4, 2.4, 3.4, 4.4, 5.4], f"{where}/p6_Pa values")
    check(g["t_s"].compression == "gzip" and g["t_s"].chunks is not None, f"{where}/t_s chunked+deflate")
    check(int(g.attrs["rows"]) == 5, f"{where}@rows")
    check(text(g.attrs["device.firmware_version"]) == "1.2.0", f"{where}@device.firmware_version")
    check(text(g.attrs["device.protocol"]) == "1.0", f"{where}@device.protocol")
    check(g.attrs["calibration.kf_N_per_A"] == 2.918, f"{where}@calibration.kf_N_per_A")
    check(list(g.attrs["calibration.pressure_offsets_Pa"]) == [12.5, 11.0, 13.25, 12.0, 10.5, 11.75],
          f"{where}@calibration.pressure_offsets_Pa")
    check(text(g.attrs["stroke_origin_z_mm_reason"]) == "the probe was not homed before this run",
          f"{where}@stroke_origin_z_mm_reason")
    side = json.loads(text(g.attrs["sidecar"]))
    check(side["schema"] == "palp.recording/1" and side["specimen"] == "insert, position 3",
          f"{where}@sidecar JSON")
    check(side["zeroing"][0]["what"] == "current_offset", f"{where}@sidecar zeroing")


with h5py.File(os.path.join(fixture, "recording.h5"), "r") as f:
    check(text(f.attrs["palp_format"]) == "palp.hdf5/1", "recording.h5 palp_format")
    check(text(f.attrs["content"]) == "recording", "recording.h5 content")
    check_recording(f["recording"], "recording.h5:/recording")

with h5py.File(os.path.join(fixture, "result.h5"), "r") as f:
    check(text(f.attrs["content"]) == "result", "result.h5 content")
    r = f["result"]
    summary = json.loads(text(r.attrs["result_json"]))
    check(summary["analysis"]["k_fd_N_per_mm"] == 0.125, "result_json analysis")
    check(text(r.attrs["firmware_version"]) == "1.2.0", "/result@firmware_version")
    a = r["analysis"].attrs
    check(a["k_fd_N_per_mm"] == 0.125 and a["delta0_mm"] == 1.5, "/result/analysis numbers")
    check(text(a["model_by_aic"]) == "hertz" and a["k_at_depth_N_per_mm.1_mm"] == 0.25, "/result/analysis others")
    check("E_star_hertz_Pa" not in a and text(a["E_star_hertz_Pa_reason"]) == "too few points", "null analysis value")
    check(r["pressure"].attrs["contact_point_mm"] == 25.0, "/result/pressure@contact_point_mm")
    check(list(r["recordings"].keys()) == ["indentation.csv"], "/result/recordings members")
    check_recording(r["recordings"]["indentation.csv"], "result.h5:/result/recordings/indentation.csv")

with h5py.File(os.path.join(fixture, "map.h5"), "r") as f:
    check(text(f.attrs["content"]) == "map", "map.h5 content")
    m = f["map"]
    doc_json = json.loads(text(m.attrs["map_json"]))
    check(doc_json["format"] == "palp.map/1" and doc_json["complete"] is False, "map.h5 map_json")
    check(int(m.attrs["rows"]) == 2 and int(m.attrs["columns"]) == 2 and text(m.attrs["plan"]) == "pad",
          "/map@rows, columns, plan")
    a = m["analysis"]
    k = a["k_fd_N_per_mm"][:]
    check(k.shape == (2, 2) and k[0, 0] == 0.5 and k[1, 0] == 0.25 and np.isnan(k[0, 1]) and np.isnan(k[1, 1]),
          f"/map/analysis/k_fd_N_per_mm {k}")
    check(list(a["row_mean_N_per_mm"][:]) == [0.5, 0.25], "/map/analysis/row_mean_N_per_mm")
    check(list(a["soft_rows"][:]) == [2] and list(a["stiff_rows"][:]) == [1], "soft/stiff rows")
    check(len(a["soft_columns"]) == 0 and len(a["stiff_columns"]) == 0, "no soft/stiff column")
    check(a.attrs["median_N_per_mm"] == 0.5 and a.attrs["contrast"] == 0.1, "/map/analysis attributes")
    sx, sy = m["surface/contact_x_mm"][:], m["surface/contact_y_mm"][:]  # the touches: 10 mm per column/row
    check(sx[0, 0] == 10.0 and sx[0, 1] == 20.0 and sx[1, 0] == 10.0 and np.isnan(sx[1, 1]), f"contact_x_mm {sx}")
    check(sy[0, 0] == 10.0 and sy[0, 1] == 10.0 and sy[1, 0] == 20.0 and np.isnan(sy[1, 1]), f"contact_y_mm {sy}")
    check(sorted(m["points"].keys()) == ["r1_c1", "r1_c2", "r2_c1"], f"/map/points {list(m['points'].keys())}")
    p = m["points/r1_c1"]
    check(p.attrs["k_fd_N_per_mm"] == 0.5 and int(p.attrs["indented"]) == 1, "r1_c1 point attributes")
    check(text(m["points/r1_c2"].attrs["reason"]) == "no contact" and int(m["points/r1_c2"].attrs["indented"]) == 0,
          "r1_c2 not indented")
    rec = p["recordings/indentation.csv"]
    reps = rec["rep"][:]
    r0, r1 = p["repetitions/rep0"].attrs, p["repetitions/rep1"].attrs
    check(int(r0["first_row"]) == 0 and int(r0["rows"]) + int(r1["rows"]) == len(reps)
          and int(r1["first_row"]) == int(r0["rows"]), "repetitions' rows")
    check(set(reps[:int(r0["rows"])]) == {int(r0["rep"])} and set(reps[int(r1["first_row"]):]) == {int(r1["rep"])},
          "each repetition's rows hold its rep")
    for rk in (r0, r1):  # each repetition alone finds the synthetic run's E* (125.8 kPa, hdf5_fixture.hpp)
        check(abs(rk.get("E_star_hertz_Pa", 0.0) - 125.8e3) < 0.01 * 125.8e3, f"a repetition's E* {dict(rk)}")

with h5py.File(os.path.join(fixture, "identification.h5"), "r") as f:
    check(text(f.attrs["content"]) == "identification", "identification.h5 content")
    r = f["result"]
    check(text(r.attrs["experiment"]) == "identification", "/result@experiment")
    check(r["analysis"].attrs["f_n_Hz"] == 42.5, "/result/analysis@f_n_Hz")
    frf = r["frf"]
    check(list(frf["f_Hz"][:]) == [10.0, 20.0, 40.0], "/result/frf/f_Hz")
    check(list(frf["re_m_per_N"][:]) == [1e-3, 8e-4, 2e-4], "/result/frf/re_m_per_N")
    check(list(frf["im_m_per_N"][:]) == [-2e-4, -5e-4, -6e-4], "/result/frf/im_m_per_N")
    check(list(frf["sigma_m_per_N"][:]) == [1e-6, 2e-6, 3e-6], "/result/frf/sigma_m_per_N")
    check(int(frf.attrs["lines"]) == 3, "/result/frf@lines")
    check_recording(r["recordings/sweep.csv"], "identification.h5:/result/recordings/sweep.csv")

# every dataset's unit is the documented one, and every dataset is documented
for name in hdf5_doc_layout.FILES:
    documented = hdf5_doc_layout.rows_for(doc, name)
    with h5py.File(os.path.join(fixture, name), "r") as f:
        found = {}
        f.visititems(lambda n, o: found.__setitem__("/" + n, text(o.attrs.get("unit")))
                     if isinstance(o, h5py.Dataset) else None)
    for path, unit in found.items():
        row = hdf5_doc_layout.row_of(documented, path, "dataset")
        check(row is not None, f"{name}:{path} is not in the doc")
        check(row is None or unit == row[4], f"{name}:{path} unit {unit!r}, the doc says {row and row[4]!r}")
    for paths, _, kind, _, _ in documented:
        for path in paths:
            check(kind != "dataset" or path in found, f"{name}:{path} is in the doc, not in the file")

if failures:
    print("h5py check failed:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("h5py: " + ", ".join(hdf5_doc_layout.FILES) + " read with the known values and the documented units")
