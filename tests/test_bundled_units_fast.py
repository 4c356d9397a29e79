"""Every unit the bundled catalogs write converts without pint (its import and registry
cost about 0.3 s of every run that loads the default catalogs)."""

from __future__ import annotations

import subprocess
import sys

CODE = """
import sys
from sizer.io import bundled_catalogs, load_catalog
from sizer.io.loader import bundled_drive_catalogs, read_drive_catalog
from sizer.io.transmission import bundled_gearbox_catalogs, load_gearbox_catalog
for path in bundled_catalogs().values():
    load_catalog(path)
for path in bundled_drive_catalogs().values():
    read_drive_catalog(path)
for path in bundled_gearbox_catalogs().values():
    load_gearbox_catalog(path)
print("pint" in sys.modules)
"""


def test_the_bundled_catalogs_load_without_pint() -> None:
    out = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False", out.stderr
