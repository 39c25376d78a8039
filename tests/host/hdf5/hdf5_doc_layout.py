"""The layout table of docs/hdf5-format.md, for the independent checks (check_h5py.py,
check_h5dump_layout.py): rows (object, kind, type, unit), with <recording> expanded per file."""
import re

RECORDING_GROUPS = {"recording.h5": "/recording", "result.h5": "/result/recordings/indentation.csv"}
FILE_ROOTS = {"recording.h5": "/recording", "result.h5": "/result"}


def _cell(text):
    text = text.strip()
    return text[1:-1] if text.startswith("`") and text.endswith("`") else text


def rows(doc_path):
    out = []
    for line in open(doc_path, encoding="utf-8"):
        m = re.match(r"^\| `([^`]+)` \| (group|dataset|attribute) \|([^|]*)\|([^|]*)\|", line)
        if m:
            out.append((m.group(1), m.group(2), _cell(m.group(3)), _cell(m.group(4))))
    if len(out) < 20:
        raise SystemExit(f"{doc_path}: found only {len(out)} layout rows; the table's format changed?")
    return out


def rows_for(doc_path, file_name):
    """The rows that apply to one fixture file, <recording> replaced by its group's path."""
    rec, root = RECORDING_GROUPS[file_name], FILE_ROOTS[file_name]
    result = []
    for obj, kind, typ, unit in rows(doc_path):
        path = obj.replace("<recording>", rec)
        base = path.split("@")[0]
        if base not in ("", "/") and not (base == root or base.startswith(root + "/")):
            continue  # the other kind of file's objects
        result.append((path, kind, typ, unit))
    return result
