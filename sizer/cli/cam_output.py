"""What every ``sizer cam`` target does with its certificate: print it, and write its JSON
(--certificate) atomically."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import typer

from sizer.report.output import write_text_atomically
from sizer.report.printable import printable


def publish_certificate(record: dict[str, Any], lines: list[str],
                        certificate: Path | None) -> None:
    """Print the certificate's ``lines``; with ``certificate``, write ``record`` there as
    JSON."""
    typer.echo("\n".join(printable(line) for line in lines))
    if certificate is not None:
        write_text_atomically(certificate, json.dumps(record, indent=2) + "\n",
                              "--certificate")


def exit_on_failures(*messages: str | None) -> None:
    """Say each failure (the messages not None) on stderr and exit 1 when there is one: the
    file is written, but the tolerance or a check the law passed is not met."""
    from sizer.cli.exit_codes import ExitCode

    said = [m for m in messages if m is not None]
    for message in said:
        typer.echo(printable(message), err=True)
    if said:
        raise typer.Exit(ExitCode.CHECK_FAILED)
