"""An independent reader of palp's HDF5 files: Debian's h5py opens the files palp-hdf5-fixture
wrote from the known synthetic recording and result (tests/host/hdf5/hdf5_fixture.hpp) and reads
the known values, and every dataset's unit is the one docs/hdf5-format.md states.

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

# every dataset's unit is the documented one, and every dataset is documented
for name in ("recording.h5", "result.h5"):
    documented = {p: u for p, k, t, u in hdf5_doc_layout.rows_for(doc, name) if k == "dataset"}
    with h5py.File(os.path.join(fixture, name), "r") as f:
        found = {}
        f.visititems(lambda n, o: found.__setitem__("/" + n, text(o.attrs.get("unit")))
                     if isinstance(o, h5py.Dataset) else None)
    check(set(found) == set(documented), f"{name}: datasets {sorted(set(found) ^ set(documented))} "
                                         "are in the file or the doc, not both")
    for path, unit in found.items():
        check(unit == documented.get(path), f"{name}:{path} unit {unit!r}, the doc says {documented.get(path)!r}")

if failures:
    print("h5py check failed:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("h5py: recording.h5 and result.h5 read with the known values and the documented units")
