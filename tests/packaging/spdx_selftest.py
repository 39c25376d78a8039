# SPDX-License-Identifier: Apache-2.0
# packaging_spdx_script: scripts/spdx on a scratch git checkout with one file of each kind:
# `check` lists exactly the source files without the licence line, `apply` gives each of them the
# line in its comment syntax (after a "#!" line and a Python coding line) and changes nothing else,
# and `check` passes afterwards. Run with Debian's python3: spdx_selftest.py <path of scripts/spdx>
import pathlib
import subprocess
import sys
import tempfile

LINE = "SPDX-License-Identifier: Apache-2.0"
script = sys.argv[1]

# name -> (content before, content expected after apply; None: must not change)
cases = {
    "src/a.cpp": ("#include <x>\n", f"// {LINE}\n#include <x>\n"),
    "src/b.hpp": ("// doc\n#pragma once\n", f"// {LINE}\n// doc\n#pragma once\n"),
    "CMakeLists.txt": ("project(x)\n", f"# {LINE}\nproject(x)\n"),
    "cmake/c.cmake.in": ("@PACKAGE_INIT@\n", f"# {LINE}\n@PACKAGE_INIT@\n"),
    "gen/t.cpp.in": ("int x;\n", f"// {LINE}\nint x;\n"),
    "tool.py": ("#!/usr/bin/env python3\n# -*- coding: utf-8 -*-\nprint(1)\n",
                f"#!/usr/bin/env python3\n# -*- coding: utf-8 -*-\n# {LINE}\nprint(1)\n"),
    "page.js": ("'use strict';\n", f"// {LINE}\n'use strict';\n"),
    "scripts/run": ("#!/usr/bin/env bash\necho hi\n", f"#!/usr/bin/env bash\n# {LINE}\necho hi\n"),
    "done.cpp": (f"// {LINE}\nint y;\n", None),
    "README.md": ("# title\n", None),
    "data/run.csv": ("t_s\n0\n", None),
    "scripts/notes": ("plain text, no shebang\n", None),
    "firmware/board/stm32g474/svd/x.h": ("int z;\n", None),
}
expected_missing = sorted(n for n, (_, after) in cases.items() if after is not None)


def spdx(root, mode):
    return subprocess.run([sys.executable, script, mode, "--root", str(root)],
                          capture_output=True, text=True)


with tempfile.TemporaryDirectory() as tmp:
    root = pathlib.Path(tmp)
    for name, (before, _) in cases.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(before)
    (root / "untracked.cpp").write_text("int w;\n")  # not in git: not the project's
    subprocess.run(["git", "init", "-q", str(root)], check=True)
    subprocess.run(["git", "-C", str(root), "add", "--", *cases], check=True)

    r = spdx(root, "check")
    assert r.returncode == 1, f"check passed with files missing the line: {r}"
    assert sorted(r.stdout.split()) == expected_missing, f"check listed {r.stdout.split()}"

    r = spdx(root, "apply")
    assert r.returncode == 0, f"apply failed: {r}"
    for name, (before, after) in cases.items():
        got = (root / name).read_text()
        assert got == (before if after is None else after), f"{name} after apply: {got!r}"
    assert (root / "untracked.cpp").read_text() == "int w;\n"

    r = spdx(root, "check")
    assert r.returncode == 0 and r.stdout == "", f"check after apply: {r}"
    r = spdx(root, "apply")  # idempotent
    assert (root / "src/a.cpp").read_text() == f"// {LINE}\n#include <x>\n"
print(f"scripts/spdx: check listed the {len(expected_missing)} unlicensed sources, apply fixed them")
