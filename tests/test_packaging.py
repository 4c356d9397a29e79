"""Packaging: the distribution's own name (not someone else's), the command, the licence."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def test_distribution_name_command_and_license() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert project["name"] == "sizer-motion"  # "sizer" on the registry is another project
    assert project["scripts"] == {"sizer": "sizer.cli.process:main"}
    assert project["license"] == {"text": "MIT"}
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License\n")
    assert "Copyright (c) 2026 sizer developers" in text
    assert "THE SOFTWARE IS PROVIDED \"AS IS\"" in text


def test_docs_install_the_distribution_by_its_name() -> None:
    readme = (ROOT / "README.md").read_text()
    assert "`sizer-motion`" in readme and "[LICENSE](LICENSE)" in readme
    workflow = (ROOT / "examples" / "ci" / "sizer-check.yml").read_text()
    assert '"sizer-motion @ git+' in workflow and '"sizer @ ' not in workflow
