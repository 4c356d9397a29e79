"""No broken link in the docs, no missing file in `--help`.

Every relative link of README.md and docs/*.md points to a file of the repository (and, with
an anchor into a Markdown file, to one of its headings, by GitHub's rule for anchors); every
repository path that a command's `--help` names (examples/..., docs/..., catalogs/...)
exists."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest
import typer

ROOT = Path(__file__).resolve().parent.parent
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")
# the top-level folders of the repository a help text may name a file in
REPOSITORY_FOLDERS = ("examples", "docs", "catalogs", "benchmarks", "tools", "tests", "sizer")


def prose(text: str) -> str:
    """The text outside fenced code blocks (links there are shown, not followed)."""
    out, inside = [], False
    for line in text.splitlines():
        if line.startswith("```"):
            inside = not inside
        elif not inside:
            out.append(line)
    return "\n".join(out)


def anchors(path: Path) -> set[str]:
    """GitHub's anchors of a Markdown file's headings: lower case, punctuation but '-' and
    '_' dropped, spaces to '-', a repeated one numbered -1, -2..."""
    seen: dict[str, int] = {}
    result = set()
    for line in prose(path.read_text(encoding="utf-8")).splitlines():
        heading = re.match(r"^#{1,6} (.*)", line)
        if not heading:
            continue
        slug = re.sub(r"[^\w\- ]", "", heading.group(1).strip().lower()).replace(" ", "-")
        count = seen.get(slug, 0)
        seen[slug] = count + 1
        result.add(slug if count == 0 else f"{slug}-{count}")
    return result


def links(document: Path) -> list[str]:
    return [a or b for a, b in LINK.findall(prose(document.read_text(encoding="utf-8")))]


def test_the_slug_rule() -> None:
    assert {"sizer-plot-the-speed-torque-diagram", "spectra"} <= anchors(
        ROOT / "docs" / "plots-and-reports.md") | anchors(ROOT / "docs" / "vibration.md")


@pytest.mark.parametrize("document", DOCUMENTS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_relative_link_resolves(document: Path) -> None:
    broken = []
    for target in links(document):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # https:, mailto:
            continue
        path, _, anchor = target.partition("#")
        file = (document.parent / path).resolve() if path else document
        if not file.exists():
            broken.append(f"{target}: no such file")
        elif not file.is_relative_to(ROOT):
            broken.append(f"{target}: outside the repository")
        elif anchor and file.suffix == ".md" and anchor not in anchors(file):
            broken.append(f"{target}: no heading with that anchor")
    assert not broken, f"{document.relative_to(ROOT)}: " + "; ".join(broken)


def help_texts(monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    """What `--help` prints for every command and subcommand, by its name (help text wraps
    at spaces, so a path stays whole)."""
    from sizer.cli.app import app, run

    monkeypatch.setenv("COLUMNS", "240")
    texts: dict[str, str] = {}

    def walk(command: object, words: list[str]) -> None:
        buffer = io.StringIO()
        with contextlib.redirect_stdout(buffer):
            code = run([*words, "--help"])
        assert code == 0, words
        texts[" ".join(["sizer", *words])] = buffer.getvalue()
        for name, sub in getattr(command, "commands", {}).items():
            walk(sub, [*words, name])

    walk(typer.main.get_command(app), [])
    return texts


def test_help_texts_cover_the_commands(monkeypatch: pytest.MonkeyPatch) -> None:
    texts = help_texts(monkeypatch)
    assert {"sizer size", "sizer vibration", "sizer catalog validate"} <= set(texts)


def test_every_file_named_in_help_exists(monkeypatch: pytest.MonkeyPatch) -> None:
    missing = []
    folders = "|".join(REPOSITORY_FOLDERS)
    for name, text in help_texts(monkeypatch).items():
        for path in re.findall(rf"(?<![\w/.-])((?:{folders})/[\w./-]*\w)", text):
            if any(c in path for c in "*?") or (ROOT / path).exists():
                continue
            missing.append(f"{name}: {path}")
    assert not missing, missing
