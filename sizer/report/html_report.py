"""The design report as one self-contained HTML file (``sizer report DESIGN -o DIR --html``).

The content is the Markdown report's (:class:`sizer.report.design_report.DesignReport`),
rendered to HTML by a converter of the small Markdown subset that report writes
(headings, paragraphs, lists, tables, inline code, figures); each figure is drawn as SVG
and inlined, and two sections are added: the design file as written and the provenance
(sizer's version, the design file's name and SHA-256, the options, the library versions).

Self-contained: no script, no external style sheet, font, image or link; every text is
escaped (``html.escape``); the SVG figures lose their XML prologue, namespace URIs and
metadata, and their ids are prefixed per figure so that two figures never share one.
A print style sheet (A4, figures and table rows never split) makes it print to PDF.
The bytes are deterministic: the same design and results give the same file.
"""

from __future__ import annotations

import hashlib
import html
import platform
import re
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from sizer import __version__
from sizer.report.output import write_text_atomically

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.sizing import SizingResult

HTML_FILE = "report.html"
MAX_DESIGN_TEXT = 200_000
"""Characters of the design file shown in the report (a longer file is cut, and says so)."""

CSP = "default-src 'none'; style-src 'unsafe-inline'; img-src data:"
"""The page's Content-Security-Policy: a browser loads nothing from outside it (no script,
no remote style, font or image), whatever a text inside says."""

STYLE = """
:root { color-scheme: light; }
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue",
       Arial, sans-serif; color: #1b1f24; background: #fff; margin: 0; }
main { max-width: 64rem; margin: 0 auto; padding: 1.5rem 1.5rem 3rem; }
h1 { font-size: 1.7rem; border-bottom: 2px solid #1f4e79; padding-bottom: .3rem; }
h2 { font-size: 1.3rem; color: #1f4e79; margin-top: 2.2rem;
     border-bottom: 1px solid #c9d6e3; padding-bottom: .2rem; }
h3 { font-size: 1.1rem; margin-top: 1.6rem; }
code, pre { font-family: ui-monospace, "SFMono-Regular", Menlo, Consolas, monospace;
            font-size: .88em; }
code { background: #f1f3f5; padding: 0 .25em; border-radius: 3px; }
pre { background: #f6f8fa; border: 1px solid #d8dee4; padding: .8rem; overflow-x: auto;
      white-space: pre-wrap; word-break: break-word; }
.table { overflow-x: auto; margin: .8rem 0; }
table { border-collapse: collapse; font-size: .85rem; }
th, td { border: 1px solid #d0d7de; padding: .25rem .5rem; vertical-align: top; }
th { background: #eef3f8; text-align: left; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tbody tr:nth-child(even) { background: #fafbfc; }
figure { margin: 1rem 0; }
figure svg { display: block; max-width: 100%; height: auto; }
figcaption { font-size: .85rem; color: #57606a; margin-top: .3rem; }
footer, .provenance { font-size: .85rem; color: #57606a; }
@page { size: A4; margin: 14mm 12mm; }
@media print {
  body { font-size: 10pt; }
  main { max-width: none; padding: 0; }
  h2 { break-after: avoid; page-break-after: avoid; }
  h3 { break-after: avoid; page-break-after: avoid; }
  figure, tr, pre { break-inside: avoid; page-break-inside: avoid; }
  .table { overflow: visible; }
  table { font-size: 7.5pt; }
  thead { display: table-header-group; }
  tbody tr:nth-child(even) { background: none; }
}
"""


# ------------------------------------------------------------------ the Markdown
_ESCAPED = re.compile(r"\\([\\*|])")
_CODE = re.compile(r"`([^`]*)`")
_CELL = re.compile(r"((?:\\.|[^|\\])*)\|")
_IMAGE = re.compile(r"!\[((?:\\.|[^\]\\])*)\]\(([^)\s]+)\)")


def unescape_markdown(text: str) -> str:
    """The text of a Markdown escape (``\\*``, ``\\|``, ``\\\\``), as the report writes them."""
    return _ESCAPED.sub(r"\1", text)


def inline(text: str) -> str:
    """A line of Markdown as HTML: escaped, with `code` spans."""
    parts = []
    last = 0
    for match in _CODE.finditer(text):
        parts.append(html.escape(unescape_markdown(text[last:match.start()])))
        parts.append(f"<code>{html.escape(unescape_markdown(match.group(1)))}</code>")
        last = match.end()
    parts.append(html.escape(unescape_markdown(text[last:])))
    return "".join(parts)


def _cells(line: str) -> list[str]:
    body = line.strip()
    return [cell.strip() for cell in _CELL.findall(body[1:])] if body.startswith("|") else []


def _table(lines: list[str]) -> str:
    header, rule, *rows = lines
    aligns = ["num" if cell.endswith(":") and not cell.startswith(":") else ""
              for cell in _cells(rule)]

    def cell(tag: str, index: int, text: str) -> str:
        align = aligns[index] if index < len(aligns) else ""
        attr = f' class="{align}"' if align else ""
        return f"<{tag}{attr}>{inline(text)}</{tag}>"

    out = ['<div class="table"><table>', "<thead><tr>"]
    out += [cell("th", i, text) for i, text in enumerate(_cells(header))]
    out.append("</tr></thead><tbody>")
    for row in rows:
        out.append("<tr>" + "".join(cell("td", i, text)
                                    for i, text in enumerate(_cells(row))) + "</tr>")
    out.append("</tbody></table></div>")
    return "\n".join(out)


def _figure(alt: str, name: str, figures: Mapping[str, str]) -> str:
    caption = inline(alt)
    svg = figures.get(name)
    if svg is None:  # a figure that was not drawn: its caption, no broken reference
        return f'<p class="missing-figure">[figure not drawn: {caption}]</p>'
    label = html.escape(unescape_markdown(alt), quote=True)
    svg = svg.replace("<svg ", f'<svg role="img" aria-label="{label}" ', 1)
    return f"<figure>\n{svg}\n<figcaption>{caption}</figcaption>\n</figure>"


def markdown_to_html(text: str, figures: Mapping[str, str] | None = None) -> str:
    """The report's Markdown as HTML: headings, paragraphs, '- ' lists, tables, inline
    code and figures (``![alt](name)`` replaced by the SVG text ``figures[name]``)."""
    figures = figures or {}
    out: list[str] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        if not stripped:
            i += 1
            continue
        heading = re.match(r"(#{1,6}) (.*)", stripped)
        if heading:
            level = len(heading.group(1))
            out.append(f"<h{level}>{inline(heading.group(2))}</h{level}>")
            i += 1
            continue
        image = _IMAGE.fullmatch(stripped)
        if image:
            out.append(_figure(image.group(1), image.group(2), figures))
            i += 1
            continue
        if stripped.startswith("|"):
            block = []
            while i < len(lines) and lines[i].strip().startswith("|"):
                block.append(lines[i])
                i += 1
            out.append(_table(block) if len(block) >= 2 else
                       f"<p>{inline(block[0])}</p>")
            continue
        if stripped.startswith("- "):
            items = []
            while i < len(lines) and lines[i].strip().startswith("- "):
                items.append(f"<li>{inline(lines[i].strip()[2:])}</li>")
                i += 1
            out.append("<ul>\n" + "\n".join(items) + "\n</ul>")
            continue
        paragraph = []
        while i < len(lines) and lines[i].strip() and not _starts_block(lines[i].strip()):
            paragraph.append(lines[i].strip())
            i += 1
        out.append(f"<p>{inline(' '.join(paragraph))}</p>")
    return "\n".join(out)


def _starts_block(line: str) -> bool:
    return (line.startswith(("|", "- ")) or re.match(r"#{1,6} ", line) is not None
            or _IMAGE.fullmatch(line) is not None)


# ------------------------------------------------------------------------ SVG
_SVG_START = re.compile(r"<svg\b")
_METADATA = re.compile(r"<metadata>.*?</metadata>\s*", re.S)
_COMMENT = re.compile(r"<!--.*?-->\s*", re.S)
_NAMESPACE = re.compile(r'\s+xmlns(?::\w+)?="[^"]*"')
_ID = re.compile(r'\bid="([^"]+)"')
_HREF = re.compile(r'((?:xlink:)?href)="#([^"]+)"')
_URL = re.compile(r"url\(#([^)]+)\)")


def inline_svg(svg: str | bytes, prefix: str) -> str:
    """matplotlib's SVG text for inlining in HTML: from its <svg> element on, without
    metadata, comments or namespace URIs (HTML puts <svg> in its namespace), ids
    prefixed."""
    text = svg.decode("utf-8") if isinstance(svg, bytes) else svg
    match = _SVG_START.search(text)
    if match is None:
        raise ValueError("not an SVG document")
    text = text[match.start():].strip()
    text = _METADATA.sub("", text)
    text = _COMMENT.sub("", text)  # matplotlib's copies of the texts it draws as paths
    text = _NAMESPACE.sub("", text)
    text = _ID.sub(lambda m: f'id="{prefix}{m.group(1)}"', text)
    text = _HREF.sub(lambda m: f'{m.group(1)}="#{prefix}{m.group(2)}"', text)
    return _URL.sub(lambda m: f"url(#{prefix}{m.group(1)})", text)


def figure_prefix(name: str) -> str:
    """An id prefix from a figure's file name: 'speed-torque-1.png' -> 'speed-torque-1-'."""
    stem = Path(name).stem
    return re.sub(r"[^A-Za-z0-9_-]", "-", stem) + "-"


# ------------------------------------------------------------------- document
def provenance_rows(source: str | None, design_bytes: bytes | None,
                    options: Mapping[str, str]) -> list[tuple[str, str]]:
    """What made the report: versions, the design file (name, no path) and its digest, the
    options. No date or host: the same inputs give the same file."""
    import matplotlib
    import numpy

    rows = [("sizer", __version__)]
    if source:
        rows.append(("design file", Path(source).name))
    if design_bytes is not None:
        rows.append(("design file SHA-256", hashlib.sha256(design_bytes).hexdigest()))
    rows += [(name, value) for name, value in options.items()]
    rows += [("Python", platform.python_version()), ("numpy", numpy.__version__),
             ("matplotlib", matplotlib.__version__),
             ("method", "Biagiotti & Melchiorri, Trajectory Planning for Automatic "
                        "Machines and Robots, ch. 6")]
    return rows


def _key_value(rows: Iterable[tuple[str, str]]) -> str:
    body = "\n".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(v)}</td></tr>"
                     for k, v in rows)
    return f'<div class="table"><table class="provenance">\n{body}\n</table></div>'


def design_section(source: str | None, design_bytes: bytes | None) -> str:
    """The design file as written (cut at MAX_DESIGN_TEXT characters)."""
    if design_bytes is None:
        return ""
    text = design_bytes.decode("utf-8", errors="replace")
    note = ""
    if len(text) > MAX_DESIGN_TEXT:
        note = (f"<p>The first {MAX_DESIGN_TEXT:,} of {len(text):,} characters.</p>\n")
        text = text[:MAX_DESIGN_TEXT]
    name = html.escape(Path(source).name) if source else "the design"
    return (f'<section id="design-file">\n<h2>Design file</h2>\n<p><code>{name}</code>, as '
            f"written (files it names, such as catalogs or cam tables, are not included)."
            f"</p>\n{note}<pre>{html.escape(text)}</pre>\n</section>")


def html_document(title: str, body: str) -> str:
    """A complete HTML5 page: the inline style sheet, the body in <main>."""
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            f"<meta http-equiv=\"Content-Security-Policy\" content=\"{CSP}\">\n"
            "<meta name=\"generator\" content=\"sizer " + html.escape(__version__) + "\">\n"
            f"<title>{html.escape(title)}</title>\n<style>{STYLE}</style>\n</head>\n"
            f"<body>\n<main>\n{body}\n</main>\n</body>\n</html>\n")


def report_html(design: Design, sizing: SizingResult, *, top: int, best: int,
                rank_by: str | None = None, source: str | None = None,
                design_bytes: bytes | None = None, dpi: float = 100.0,
                samples: int = 401) -> str:
    """The whole HTML text of the report (figures drawn here, as SVG)."""
    from sizer.report.design_report import DesignReport, draw_figures
    from sizer.report.plots.figure_files import figure_bytes

    report = DesignReport(design, sizing, top=top, best=best, rank_by=rank_by, source=source)
    figures = {}
    for name, figure in draw_figures(design, report, dpi=dpi, samples=samples):
        figures[name] = inline_svg(figure_bytes(figure, "svg"), figure_prefix(name))
    body = markdown_to_html(report.markdown(), figures)
    options = {"ranked by": report.rank_key, "ranking rows (--top)": str(top),
               "candidates detailed (--best)": str(best)}
    body += "\n" + design_section(source, design_bytes)
    body += ('\n<section id="provenance" class="provenance">\n<h2>Provenance</h2>\n'
             + _key_value(provenance_rows(source, design_bytes, options)) + "\n</section>")
    title = f"Sizing report: {design.name or 'design'}"
    return html_document(title, body)


def write_html_report(design: Design, sizing: SizingResult, directory: Path | str, *,
                      top: int, best: int, rank_by: str | None = None,
                      source: str | None = None, design_bytes: bytes | None = None,
                      dpi: float = 100.0, samples: int = 401) -> Path:
    """Write ``directory``/report.html atomically (the directory created if needed)."""
    from sizer.report.design_report import report_directory

    directory = report_directory(directory)
    text = report_html(design, sizing, top=top, best=best, rank_by=rank_by, source=source,
                       design_bytes=design_bytes, dpi=dpi, samples=samples)
    path = directory / HTML_FILE
    write_text_atomically(path, text)  # failures: a UserError naming the file
    return path
