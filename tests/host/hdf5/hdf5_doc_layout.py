# SPDX-License-Identifier: Apache-2.0
"""The layout table of docs/hdf5-format.md, for the independent checks (check_h5py.py,
check_h5dump_layout.py): rows (object, kind, type, unit), and per fixture file the rows that apply
to it with their names in angle brackets (<result>, <recording>, <point>, rep<k>, ...) expanded
to the file's objects: as concrete paths (each must be in the file) and as a pattern (every object
of the file must match a row)."""
import re

_POINTS = ["/map/points/r1_c1", "/map/points/r2_c1"]  # the known map's indented points
# what each name in angle brackets stands for in each fixture file (hdf5_fixture.hpp)
PLACES = {
    "recording.h5": {"<recording>": ["/recording"]},
    "result.h5": {"<result>": ["/result"], "<indentation>": ["/result"],
                  "<recording>": ["/result/recordings/indentation.csv"]},
    "identification.h5": {"<result>": ["/result"], "<identification>": ["/result"],
                          "<recording>": ["/result/recordings/sweep.csv"]},
    "map.h5": {"<result>": _POINTS, "<indentation>": _POINTS, "<point>": _POINTS + ["/map/points/r1_c2"],
               "<recording>": [p + "/recordings/indentation.csv" for p in _POINTS]},
}
ROOTS = {"recording.h5": "/recording", "result.h5": "/result", "identification.h5": "/result", "map.h5": "/map"}
FILES = tuple(PLACES)


def _cell(text):
    text = text.strip()
    return text[1:-1] if text.startswith("`") and text.endswith("`") else text


def rows(doc_path):
    out = []
    for line in open(doc_path, encoding="utf-8"):
        m = re.match(r"^\| `([^`]+)` \| (group|dataset|attribute) \|([^|]*)\|([^|]*)\|", line)
        if m:
            out.append((m.group(1), m.group(2), _cell(m.group(3)), _cell(m.group(4))))
    if len(out) < 40:
        raise SystemExit(f"{doc_path}: found only {len(out)} layout rows; the table's format changed?")
    return out


def rows_for(doc_path, file_name):
    """The rows that apply to one fixture file: (paths, pattern, kind, type, unit), `paths` the
    concrete objects (rep<k> as rep0), `pattern` a regex every object the row stands for matches."""
    places, root = PLACES[file_name], ROOTS[file_name]
    result = []
    for obj, kind, typ, unit in rows(doc_path):
        m = re.match(r"^(<[a-z]+>)(.*)$", obj)
        if m:
            if m.group(1) not in places:
                continue  # a kind of object this file has not
            bases, rest = places[m.group(1)], m.group(2)
        else:
            base = obj.split("@")[0]
            if base not in ("", "/") and not (base == root or base.startswith(root + "/")):
                continue  # the other kinds of file's objects
            bases, rest = [""], obj
        # <recording> inside a map's point stands for several; rep<k> for rep0, rep1, ...
        paths = [b + rest.replace("rep<k>", "rep0") for b in bases]
        pattern = "(" + "|".join(re.escape(b) for b in bases) + ")" + re.escape(rest).replace(
            re.escape("rep<k>"), r"rep\d+")
        result.append((paths, pattern, kind, typ, unit))
    return result


def row_of(documented, path, kind):
    """The documented row an object of the file is, or None."""
    for row in documented:
        if row[2] == kind and re.fullmatch(row[1], path):
            return row
    return None
