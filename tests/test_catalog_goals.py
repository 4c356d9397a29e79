"""tools/catalog_goals.py prints issue 35's data goals over the bundled catalogs, the same
output for the same files."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[1] / "tools" / "catalog_goals.py"


def test_the_goals_script_prints_every_goal() -> None:
    runs = [subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, text=True,
                           check=False) for _ in range(2)]
    assert runs[0].returncode == 0, runs[0].stderr
    assert runs[0].stdout == runs[1].stdout
    text = runs[0].stdout
    for start in ("motors: ", "makers: ", "with k_t, R and L: ",
                  "with electrical envelope (k_t or k_e, R, bus voltage): ",
                  "electrical model vs printed curve points: ",
                  "grades of all figures: A ", "motor families with a drive family: ",
                  "gearbox series: ", "motors with prices: "):
        assert any(line.startswith(start) for line in text.splitlines()), start
