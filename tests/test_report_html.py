"""``sizer report DESIGN -o DIR --html`` (issue 36): one self-contained report.html.

Always: the file parses, holds the report's tables, figures (inline SVG), the design file
and the provenance, escapes what it shows, and references nothing outside itself.
Where a Chromium is installed (``shutil.which``), it loads the page headless with no
console message (the page's Content-Security-Policy reports any blocked load there),
its DOM has the tables and SVGs, and it prints to a PDF.
"""

from __future__ import annotations

import hashlib
import re
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")

from cli_run import run_cli

from sizer.report.html_report import (
    HTML_FILE,
    inline_svg,
    markdown_to_html,
)

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
TASK = EXAMPLES / "indexing-table.yaml"
CYCLE = EXAMPLES / "indexing-duty-cycle.yaml"

CHROMIUM = next((shutil.which(name) for name in ("chromium", "chromium-browser",
                                                  "google-chrome", "google-chrome-stable")
                 if shutil.which(name)), None)


class Page(HTMLParser):
    """Tags, attributes, style text and visible text of an HTML page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.tags: list[str] = []
        self.attributes: list[tuple[str, str, str]] = []
        self.styles: list[str] = []
        self.text: list[str] = []
        self._in_style = False

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.attributes += [(tag, name, value or "") for name, value in attrs]
        self._in_style = tag == "style"

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        self._in_style = False

    def handle_endtag(self, tag):
        if tag == "style":
            self._in_style = False

    def handle_data(self, data):
        (self.styles if self._in_style else self.text).append(data)


def parse(text: str) -> Page:
    page = Page()
    page.feed(text)
    page.close()
    return page


def external_references(text: str) -> list[str]:
    """Every reference of the page to something outside it (empty for a self-contained
    page): a src/href/xlink:href/action/data/poster/srcset attribute that is not '#...'
    or 'data:', a style (element or attribute) with @import or url() of something not
    '#...' or 'data:', any attribute naming a scheme or '//', a <script>, <link>, <base>,
    <iframe>, <object> or <embed>."""
    page = parse(text)
    found = [f"<{tag}>" for tag in page.tags
             if tag in {"script", "link", "base", "iframe", "object", "embed", "frame"}]
    reference_names = {"src", "href", "xlink:href", "action", "data", "poster", "srcset",
                       "formaction", "background", "manifest", "ping"}
    styles = list(page.styles)
    for tag, name, value in page.attributes:
        if name == "style":
            styles.append(value)
        if name in reference_names and not value.startswith(("#", "data:")):
            found.append(f"<{tag} {name}={value!r}>")
        if name != "content" and re.search(r"(?i)\b[a-z][a-z0-9+.-]*://|^//", value):
            found.append(f"<{tag} {name}={value!r}>")
    for style in styles:
        if "@import" in style:
            found.append("@import")
        for target in re.findall(r"url\(\s*['\"]?([^'\")]*)", style):
            if not target.startswith(("#", "data:")):
                found.append(f"url({target})")
    return found


@pytest.fixture(scope="module")
def task_report(tmp_path_factory) -> tuple[Path, str]:
    folder = tmp_path_factory.mktemp("html")
    result = run_cli("report", str(TASK), "-o", str(folder), "--html")
    assert result.returncode == 0, result.stderr
    path = folder / HTML_FILE
    assert result.stdout.strip() == f"{path}: self-contained HTML report"
    return path, path.read_text(encoding="utf-8")


def test_one_self_contained_file(task_report):
    path, text = task_report
    assert sorted(p.name for p in path.parent.iterdir()) == [HTML_FILE]  # no figure files
    assert text.startswith("<!DOCTYPE html>\n")
    assert external_references(text) == []
    assert "Content-Security-Policy" in text and "default-src 'none'" in text
    # no path of the machine it ran on
    assert str(EXAMPLES) not in text and str(path.parent) not in text


def test_it_holds_the_report(task_report):
    _, text = task_report
    page = parse(text)
    headings = [t for t in page.tags if t in {"h1", "h2", "h3"}]
    assert headings.count("h1") == 1
    visible = " ".join(page.text)
    for section in ("Task", "Load", "Transmission", "Limits", "Motors", "Motion laws",
                    "Ranking", "Best candidates", "Design file", "Provenance"):
        assert section in visible
    assert page.tags.count("table") >= 6
    # the figures: the laws' profiles and a speed-torque diagram per best candidate, SVG
    assert page.tags.count("svg") == page.tags.count("figure") == 1 + 3
    assert "img" not in page.tags
    assert "figcaption" in page.tags
    # speeds in rpm, torques in N*m; no Markdown escape left
    assert " rpm against " in visible and "N*m" in visible
    assert "\\*" not in visible and "rad/s against" not in visible
    # the design file as written, and its digest in the provenance
    source = TASK.read_bytes()
    assert hashlib.sha256(source).hexdigest() in visible
    assert "name: Indexing table" in visible


def test_svg_ids_are_unique_across_figures(task_report):
    _, text = task_report
    ids = re.findall(r'\bid="([^"]+)"', text)
    svg_ids = [i for i in ids if i.startswith(("laws-", "speed-torque-"))]
    assert svg_ids
    # every internal reference points at an id of the page
    targets = set(ids)
    for ref in re.findall(r'href="#([^"]+)"', text) + re.findall(r"url\(#([^)]+)\)", text):
        assert ref in targets


def test_a_cycle_report_has_its_time_figure(tmp_path):
    result = run_cli("report", str(CYCLE), "-o", str(tmp_path), "--html", "--best", "1")
    assert result.returncode == 0, result.stderr
    text = (tmp_path / HTML_FILE).read_text(encoding="utf-8")
    assert external_references(text) == []
    page = parse(text)
    assert page.tags.count("svg") == 3  # laws, speed-torque #1, torque and speed over time
    assert "Cycle by segment" in " ".join(page.text)


def test_the_report_is_deterministic(task_report, tmp_path):
    _, text = task_report
    result = run_cli("report", str(TASK), "-o", str(tmp_path), "--html")
    assert result.returncode == 0
    assert (tmp_path / HTML_FILE).read_text(encoding="utf-8") == text


def test_every_text_is_escaped():
    markdown = ("# A <b>&name</b>\n\nText with `<code>` and N\\*m.\n\n"
                "| a \\| b | <x> |\n| :--- | ---: |\n| <script>alert(1)</script> | 1 |\n\n"
                "- item <i>\n\n![caption <svg>](fig.png)\n")
    out = markdown_to_html(markdown, {"fig.png": "<svg viewBox=\"0 0 1 1\"></svg>"})
    assert "<b>" not in out and "<script>" not in out and "<i>" not in out
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in out
    assert "<h1>A &lt;b&gt;&amp;name&lt;/b&gt;</h1>" in out
    assert "<code>&lt;code&gt;</code>" in out and "N*m." in out
    assert "<th>a | b</th>" in out and '<th class="num">&lt;x&gt;</th>' in out
    assert '<td class="num">1</td>' in out
    assert 'aria-label="caption &lt;svg&gt;"' in out
    assert "<figcaption>caption &lt;svg&gt;</figcaption>" in out


def test_a_missing_figure_is_no_reference():
    out = markdown_to_html("![a figure](gone.png)\n", {})
    assert "gone.png" not in out and external_references(out) == []


def test_inline_svg_drops_the_prologue_and_prefixes_ids():
    svg = ('<?xml version="1.0"?>\n<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN"\n'
           '  "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">\n'
           '<svg xmlns:xlink="http://www.w3.org/1999/xlink" width="1pt" '
           'xmlns="http://www.w3.org/2000/svg"><metadata><rdf:RDF '
           'xmlns:dc="http://purl.org/dc/elements/1.1/"/></metadata>'
           '<defs><path id="m1"/><clipPath id="c2"/></defs>'
           '<!-- a label --><use xlink:href="#m1" clip-path="url(#c2)"/></svg>')
    out = inline_svg(svg, "fig-")
    assert out.startswith("<svg ") and "http" not in out and "metadata" not in out
    assert "<!--" not in out
    assert 'id="fig-m1"' in out and 'xlink:href="#fig-m1"' in out and "url(#fig-c2)" in out


def test_the_detector_finds_external_references():
    bad = ('<html><head><link rel="stylesheet" href="x.css"><style>@import "a.css"; '
           'b { background: url(http://x/y.png) }</style></head><body>'
           '<img src="fig.png"><a href="https://example.com">x</a>'
           '<svg><image href="//cdn/x.png"/></svg><p style="background:url(z.png)"></p>'
           '</body></html>')
    found = external_references(bad)
    for fragment in ("<link>", "@import", "url(http://x/y.png)", "fig.png",
                     "https://example.com", "//cdn/x.png", "url(z.png)"):
        assert any(fragment in f for f in found), fragment
    assert external_references('<a href="#x">x</a><img src="data:image/png;base64,AA">') == []


def test_html_of_a_machine_file_is_a_user_error(tmp_path):
    machine = next((EXAMPLES / "machines").glob("*.yaml"))
    result = run_cli("report", str(machine), "-o", str(tmp_path), "--html")
    assert result.returncode == 2
    assert "--html" in result.stderr and "Traceback" not in result.stderr
    assert list(tmp_path.iterdir()) == []


# ------------------------------------------------------------- a real browser
def _chromium(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    assert CHROMIUM is not None
    return subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--enable-logging=stderr", "--v=0", f"--user-data-dir={cwd / 'profile'}", *args],
        capture_output=True, text=True, timeout=120, cwd=cwd, check=False)


def _console(stderr: str) -> list[str]:
    """The page's console messages (errors, blocked loads) in Chromium's log."""
    return [line for line in stderr.splitlines() if ":CONSOLE" in line]


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium installed (apt-get install "
                                             "chromium)")
def test_chromium_loads_it_without_errors(task_report, tmp_path):
    path, _ = task_report
    result = _chromium("--dump-dom", path.as_uri(), cwd=tmp_path)
    assert result.returncode == 0, result.stderr[-2000:]
    assert _console(result.stderr) == []
    dom = result.stdout
    assert dom.count("<table") >= 6
    assert dom.count("<svg") == 4
    assert "Provenance" in dom and "Best candidates" in dom
    # the check works: the same page with an external image logs a blocked load
    bad = tmp_path / "bad.html"
    bad.write_text(path.read_text(encoding="utf-8").replace(
        "</main>", '<img src="https://example.invalid/x.png"><img src="x.png"></main>'),
        encoding="utf-8")
    blocked = _console(_chromium("--dump-dom", bad.as_uri(), cwd=tmp_path).stderr)
    assert len(blocked) == 2 and all("Content Security Policy" in b for b in blocked)


@pytest.mark.skipif(CHROMIUM is None, reason="no Chromium installed (apt-get install "
                                             "chromium)")
def test_chromium_prints_it_to_pdf(task_report, tmp_path):
    path, _ = task_report
    pdf = tmp_path / "report.pdf"
    result = _chromium("--no-pdf-header-footer", f"--print-to-pdf={pdf}", path.as_uri(),
                       cwd=tmp_path)
    assert result.returncode == 0, result.stderr[-2000:]
    assert _console(result.stderr) == []
    data = pdf.read_bytes()
    assert data.startswith(b"%PDF-")
    pages = len(re.findall(rb"/Type\s*/Page\b", data))
    assert pages >= 2
