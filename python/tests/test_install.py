# SPDX-License-Identifier: Apache-2.0
"""`cmake --install --component python` puts the package into Debian's dist-packages layout, and
Debian's interpreter imports it from there."""

import os
import subprocess
import sys


def test_the_installed_package_imports_from_dist_packages(tmp_path):
    prefix = tmp_path / "usr"
    subprocess.run(["cmake", "--install", os.environ["PALP_BUILD_DIR"], "--component", "python",
                    "--prefix", str(prefix)], check=True, capture_output=True)
    site = prefix / "lib" / "python3" / "dist-packages"
    files = sorted(p.name for p in (site / "palp").iterdir())
    assert "__init__.py" in files and "_palp.pyi" in files and "py.typed" in files
    assert any(f.startswith("_palp.") and f.endswith(".so") for f in files), files
    r = subprocess.run([sys.executable, "-c", "import palp; print(palp.__file__); print(palp.sdk_version)"],
                       env={"PYTHONPATH": str(site), "PATH": os.environ.get("PATH", "")},
                       capture_output=True, text=True, check=True)
    assert r.stdout.splitlines()[0] == str(site / "palp" / "__init__.py")
