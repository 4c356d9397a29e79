"""Rewrite the outputs under each ``$ sizer ...`` line of README.md and of the docs that
hold transcripts (TRANSCRIPTS) with the real output.

    python tools/update_readme_transcripts.py

tests/test_examples_e2e.py checks that these files show what the commands print; run this
after a change that moves the numbers, and read the diff before committing.
"""

from __future__ import annotations

import contextlib
import io
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # run from a checkout without installing

from sizer.cli.app import main  # noqa: E402


def output_of(args: list[str]) -> str:
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer), contextlib.suppress(SystemExit):
        main(args)
    return buffer.getvalue()


def rewrite(text: str) -> str:
    out: list[str] = []
    inside = skipping = False
    for line in text.splitlines():
        if line.startswith("```"):
            inside, skipping = not inside, False
            out.append(line)
        elif inside and line.startswith("$ sizer "):
            out.append(line)
            args = line[len("$ sizer "):].split()
            if "--output" not in args:
                out.extend(output_of(args).splitlines())
                skipping = True
        elif not skipping:
            out.append(line)
    return "\n".join(out) + "\n"


TRANSCRIPTS = ("README.md", "docs/commands.md", "docs/machine-cycles.md", "docs/vibration.md")
"""The files whose transcripts tests/test_examples_e2e.py reads (readme_transcripts)."""


if __name__ == "__main__":
    for name in TRANSCRIPTS:
        path = ROOT / name
        path.write_text(rewrite(path.read_text()))
