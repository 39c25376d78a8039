# SPDX-License-Identifier: Apache-2.0
"""h5dump -H (Debian's hdf5-tools) of the files palp-hdf5-fixture wrote shows exactly the groups
and datasets docs/hdf5-format.md's layout table states, with the stated types, and the stated
attributes with theirs (a file may hold more attributes: the sidecar's and the analysis' typed
copies), both ways: every row is in the files, every group and dataset is a row.

usage: /usr/bin/python3 check_h5dump_layout.py docs/hdf5-format.md FIXTURE_DIR"""
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hdf5_doc_layout  # noqa: E402


def h5dump_objects(path):
    """{object path: (kind, type)} from h5dump -H; attributes as path@name."""
    text = subprocess.run(["h5dump", "-H", path], check=True, capture_output=True, text=True).stdout
    objects, stack = {}, []  # stack of (kind, path) per open brace
    for line in text.splitlines():
        s = line.strip()
        m = re.match(r'^(GROUP|DATASET|ATTRIBUTE) "([^"]*)" \{$', s)
        if m:
            kind, name = m.group(1).lower(), m.group(2)
            parent = next((p for k, p in reversed(stack) if k in ("group", "dataset")), "")
            if kind == "attribute":
                p = (parent or "/") + "@" + name
            elif name == "/":
                p = "/"
            else:
                p = (parent if parent != "/" else "") + "/" + name
            objects[p] = (kind, "")
            stack.append((kind, p))
            continue
        m = re.match(r"^DATATYPE\s+(\S+)", s)
        if m and stack and stack[-1][0] in ("dataset", "attribute") and objects[stack[-1][1]][1] == "":
            objects[stack[-1][1]] = (stack[-1][0], m.group(1))
        if s.endswith("{") and not re.match(r'^(GROUP|DATASET|ATTRIBUTE) ', s):
            stack.append(("other", ""))
        elif s == "}":
            stack.pop()
    return objects


doc, fixture = sys.argv[1], sys.argv[2]
failures = []
for name in hdf5_doc_layout.FILES:
    found = h5dump_objects(os.path.join(fixture, name))
    documented = hdf5_doc_layout.rows_for(doc, name)
    for paths, _, kind, typ, _ in documented:
        for path in paths:
            if path not in found:
                failures.append(f"{name}: {kind} {path} is documented but h5dump does not show it")
            elif found[path][0] != kind or (typ and found[path][1] != typ):
                failures.append(f"{name}: {path} is a {found[path]} in h5dump, the doc says {kind} {typ}")
    for path, (kind, typ) in found.items():
        if kind in ("group", "dataset") and path != "/":
            row = hdf5_doc_layout.row_of(documented, path, kind)
            if row is None:
                failures.append(f"{name}: h5dump shows {kind} {path} ({typ}), the doc does not list it")
            elif row[3] and typ != row[3]:
                failures.append(f"{name}: {kind} {path} is {typ}, the doc says {row[3]}")
        if kind == "dataset" and path + "@unit" not in found:
            failures.append(f"{name}: dataset {path} has no unit attribute")
    if not any(k == "dataset" for k, _ in found.values()):
        failures.append(f"{name}: h5dump shows no dataset at all")

if failures:
    print("h5dump layout check failed:\n  " + "\n  ".join(failures))
    sys.exit(1)
print("h5dump -H of " + ", ".join(hdf5_doc_layout.FILES) +
      ": the groups, datasets, types and attributes of docs/hdf5-format.md, both ways")
