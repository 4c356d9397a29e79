"""What a notebook shows of a sizing: HTML tables for Jupyter and a pandas DataFrame.

:class:`sizer.sizing.SizingResult` and :class:`sizer.sizing.CandidateResult` call these
from ``_repr_html_`` and ``to_pandas`` (imported when called): the results are plain data
(sizer.sizing.results), this module only lays them out. The HTML is one ``<table>`` with
inline styles, every text escaped, no script and no external resource; figures are shown
for people (duration in ms, speed in rpm, margins in %), records and DataFrames stay SI.

pandas is an optional extra (``pip install 'sizer-motion[pandas]'``), imported here only.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from html import escape
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # types only: the sizing layer calls this module, not the reverse
    from sizer.sizing.results import CandidateResult, SizingResult

PANDAS_EXTRA = "pandas"
"""The optional extra of pyproject.toml that installs pandas."""
INSTALL_HINT = f"pip install 'sizer-motion[{PANDAS_EXTRA}]'"
MAX_HTML_ROWS = 25
"""Rows a result's HTML table shows (the rest counted below it)."""
RPM_PER_RAD_S = 30.0 / math.pi
SUMMARY_MARGINS = ("peak", "rms", "speed")
"""The margins every row of the HTML table shows (the limiting one besides)."""

_STYLE_TABLE = "border-collapse:collapse;font-size:90%"
_STYLE_CELL = "padding:1px 6px;border-bottom:1px solid #ddd"
_STYLE_FAIL = "color:#b00020"


def to_pandas(records: Sequence[Mapping[str, object]], units: Mapping[str, str],
              design: str = "", mode: str = "") -> Any:
    """A DataFrame of flat records, indexed by ``rank`` where they have one; ``attrs``
    holds ``units`` (by column), the design's name and the mode."""
    try:
        import pandas as pd  # type: ignore[import-not-found,import-untyped,unused-ignore]
    except ImportError as error:
        raise ImportError(f"to_pandas() needs pandas, an optional extra of sizer: "
                          f"{INSTALL_HINT} (or pip install pandas)") from error
    frame = pd.DataFrame.from_records(list(records))
    if "rank" in frame.columns:
        frame = frame.set_index("rank")
    frame.attrs["units"] = {k: v for k, v in units.items() if k in frame.columns}
    frame.attrs["design"] = design
    frame.attrs["mode"] = mode
    return frame


def _number(value: float | None, scale: float = 1.0, digits: int = 4) -> str:
    if value is None or not math.isfinite(value):
        return "n/a"
    return f"{value * scale:.{digits}g}"


def _percent(value: float | None) -> str:
    if value is None or not math.isfinite(value):
        return "n/a"
    return f"{100.0 * value:.1f}"


def _row(cells: Sequence[str], tag: str = "td", style: str = "") -> str:
    extra = f";{style}" if style else ""
    inner = "".join(f'<{tag} style="{_STYLE_CELL}{extra}">{escape(c)}</{tag}>'
                    for c in cells)
    return f"<tr>{inner}</tr>"


def _table(caption: str, header: Sequence[str], rows: Sequence[tuple[Sequence[str], bool]],
           footer: str = "") -> str:
    body = "".join(_row(cells, style="" if ok else _STYLE_FAIL) for cells, ok in rows)
    foot = f'<p style="font-size:85%;margin:2px 0">{escape(footer)}</p>' if footer else ""
    return (f'<div class="sizer-result"><table style="{_STYLE_TABLE}">'
            f'<caption style="text-align:left;font-weight:bold">{escape(caption)}</caption>'
            f"<thead>{_row(header, 'th')}</thead><tbody>{body}</tbody></table>{foot}</div>")


def sizing_html(result: SizingResult, max_rows: int = MAX_HTML_ROWS) -> str:
    """The ranked candidates: motor, law, verdict, duration, peak and RMS torque, speed,
    the peak, RMS and speed margins and the limiting check with its margin."""
    rows = []
    for rank, r in enumerate(result.results[:max_rows], 1):
        known = r.duration is not None
        margins = [_percent(r.margin(n) if known else None) for n in SUMMARY_MARGINS]
        limiting = r.margin(r.limiting) if r.limiting and known else None
        rows.append(([str(rank), r.motor, r.law, "yes" if r.feasible else "no",
                      _number(r.duration, 1e3), _number(r.peak_torque),
                      _number(r.rms_torque), _number(r.max_speed, RPM_PER_RAD_S),
                      *margins, r.limiting or "", _percent(limiting)], r.feasible))
    total, feasible = len(result.results), len(result.feasible)
    title = result.design_name or "sizing"
    caption = (f"{title}: {feasible} of {total} candidates feasible "
               f"({result.mode} mode)")
    more = total - len(rows)
    footer = f"... {more} more (records() or to_pandas() for all)" if more > 0 else ""
    header = ("#", "motor", "law", "ok", "T [ms]", "peak [N*m]", "rms [N*m]",
              "speed [rpm]", "peak margin [%]", "rms margin [%]", "speed margin [%]",
              "limiting", "limiting margin [%]")
    notes = "".join(f"<li>{escape(n)}</li>" for n in result.notes)
    details = (f'<details><summary style="font-size:85%">notes</summary><ul '
               f'style="font-size:85%">{notes}</ul></details>' if notes else "")
    return _table(caption, header, rows, footer) + details


def candidate_html(result: CandidateResult) -> str:
    """One candidate: its verdict and figures in the caption, a row per check."""
    verdict = "feasible" if result.feasible else "not feasible"
    figures = ", ".join(f"{name} {text}" for name, text in (
        ("T", f"{_number(result.duration, 1e3)} ms"),
        ("peak", f"{_number(result.peak_torque)} N*m"),
        ("rms", f"{_number(result.rms_torque)} N*m"),
        ("speed", f"{_number(result.max_speed, RPM_PER_RAD_S)} rpm")))
    caption = f"{result.motor} with {result.law}: {verdict} ({figures})"
    rows = [([c.name, _number(c.value, digits=6), _number(c.limit, digits=6), c.unit,
              _percent(c.margin), _percent(c.required) if c.required else "",
              "ok" if c.passed else "FAILS"], c.passed) for c in result.checks]
    header = ("check", "value", "limit", "unit", "margin [%]", "required [%]", "verdict")
    footer = f"limiting: {result.limiting}" + (f"; {result.reason}" if result.reason else "")
    return _table(caption, header, rows, footer)
