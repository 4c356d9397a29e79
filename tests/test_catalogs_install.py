"""A real (non-editable) ``pip install`` finds the bundled catalogs: they are package data.

This test builds and installs sizer into a fresh virtual environment (about 5-10 s), once.
Set SIZER_SKIP_INSTALL_TEST=1 to skip it (e.g. offline, where pip cannot fetch setuptools
for the isolated build). The quick checks of the package data are in
test_catalogs_bundled.py.
"""

from __future__ import annotations

import json
import os
import shutil
import site
import subprocess
import sys
from pathlib import Path

import pytest

from sizer.io import bundled_catalogs, load_catalog

ROOT = Path(__file__).resolve().parent.parent

SCRIPT = """
import json, sys
import sizer
from sizer.io import bundled_catalogs, default_catalogs, load_catalog, load_design
from sizer.catalog_tools import validate_catalogs
design = load_design(sys.argv[1], default_motors=True)
report = validate_catalogs(list(bundled_catalogs().values()))
print(json.dumps({
    "module": sizer.__file__,
    "catalogs": {name: len(load_catalog(name)) for name in bundled_catalogs()},
    "default": sorted(default_catalogs()),
    "design_motors": len(design.motors),
    "findings": [str(f) for f in report.findings],
}))
"""

DESIGN = """\
task: {displacement: 90 deg, duration: 0.3 s}
load: {inertia: 0.05 kg*m^2}
transmission: {type: gearbox, ratio: 10}
"""


@pytest.mark.skipif(os.environ.get("SIZER_SKIP_INSTALL_TEST") == "1",
                    reason="SIZER_SKIP_INSTALL_TEST=1")
def test_pip_install_finds_the_bundled_catalogs(tmp_path):
    source = tmp_path / "src"
    source.mkdir()
    shutil.copytree(ROOT / "sizer", source / "sizer",
                    ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, source / name)
    venv = tmp_path / "venv"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    # without pip: seeding pip into the venv (ensurepip) took 7 of the test's 18 s; the
    # running pip installs into the venv instead (`pip --python`, pip >= 22.3)
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", "--system-site-packages",
                    str(venv)], check=True, env=env, timeout=120)
    python = venv / ("Scripts" if os.name == "nt" else "bin") / "python"
    # the dependencies come from the environment running the tests, a virtual one too
    # (--system-site-packages reaches only the base interpreter's)
    purelib = subprocess.run([str(python), "-c",
                              "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                             capture_output=True, text=True, check=True, env=env,
                             timeout=60).stdout.strip()
    outer = [p for p in site.getsitepackages() if Path(p).is_dir()]
    (Path(purelib) / "outer-environment.pth").write_text("\n".join(outer) + "\n")
    install = subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install",
                              "--no-deps", "--no-input",
                              "--disable-pip-version-check", "-q", str(source)],
                             capture_output=True, text=True, env=env, timeout=600)
    assert install.returncode == 0, install.stdout + install.stderr
    shutil.rmtree(source)  # the installed copy must not lean on the sources
    design = tmp_path / "design.yaml"
    design.write_text(DESIGN)
    result = subprocess.run([str(python), "-c", SCRIPT, str(design)], capture_output=True,
                            text=True, env=env, cwd=tmp_path, timeout=120)
    assert result.returncode == 0, result.stderr
    found = json.loads(result.stdout)
    assert Path(found["module"]).is_relative_to(venv)
    assert found["catalogs"] == {name: len(load_catalog(name)) for name in bundled_catalogs()}
    assert "book-examples" not in found["default"] and len(found["default"]) >= 4
    assert found["design_motors"] == sum(n for name, n in found["catalogs"].items()
                                         if name in found["default"])
    assert found["findings"] == []
