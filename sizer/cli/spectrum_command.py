"""``sizer spectrum``: the amplitude spectrum of laws' acceleration (book sec. 7.3), or the
harmonics of a move repeated with a period (sec. 7.3.3), printed, exported and plotted."""

from __future__ import annotations

import math
from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from sizer.cli.options import FormatOption, OutputOption, as_option, blame_option, scaled_move
from sizer.errors import UserError
from sizer.input_limits import MAX_SPECTRUM_CURVE_POINTS, MAX_SPECTRUM_LINES
from sizer.report.formats import Format

MAX_FT = 1000.0
"""Largest normalized frequency f T."""

MAX_POINTS = MAX_SPECTRUM_LINES
"""Most frequencies (sizer.input_limits)."""

MAX_WORK = 2_000_000.0
"""Largest points x max f T (the numerical transform's cost grows with both)."""

ORDER_NAMES = {1: "velocity", 2: "acceleration", 3: "jerk"}


class Scale(StrEnum):
    """What the values are: the Fourier amplitude |A| or the book's V = |A| / pi."""

    FOURIER = "fourier"
    BOOK = "book"


def spectrum(
    specs: Annotated[list[str], typer.Argument(
        metavar="SPEC...", help="Laws, e.g. cycloidal poly5 'trapezoidal(alpha=1/3)'.",
        show_default=False)],
    max_ft: Annotated[float, typer.Option(
        "--max-ft", metavar="X", help="Largest normalized frequency f*T (the book's "
                                      "Omega); also with --duration.")] = 10.0,
    points: Annotated[int, typer.Option(
        "--points", "-n", metavar="N", help="Equally spaced frequencies from 0 to "
                                            "--max-ft, ends included.")] = 501,
    order: Annotated[int, typer.Option(
        "--order", metavar="K", help="Derivative: 2 acceleration (the book's), "
                                     "1 velocity, 3 jerk (with the impulses where the "
                                     "acceleration jumps).")] = 2,
    scale: Annotated[Scale, typer.Option(
        "--scale", case_sensitive=False,
        help="fourier: the Fourier amplitude |A|; book: V = |A|/pi as the book plots "
             "it (eq. 7.8).")] = Scale.FOURIER,
    displacement: Annotated[str | None, typer.Option(
        "--displacement", metavar="H",
        help="Scale to a move of h ('90 deg', '200 mm'; rad if bare), with --duration: "
             "frequencies in Hz, amplitudes in physical units (sec. 7.3.4). Default: "
             "normalized, h = T = 1.", show_default=False)] = None,
    duration: Annotated[str | None, typer.Option(
        "--duration", metavar="T", help="Duration T of the move ('0.2 s'), with "
                                        "--displacement.", show_default=False)] = None,
    period: Annotated[str | None, typer.Option(
        "--period", metavar="TC",
        help="The move repeated every TC >= T (rise then dwell; sec. 7.3.3): print its "
             "harmonics up to --max-ft instead. A time with --duration, else TC/T as a "
             "bare number (1: the book's case).", show_default=False)] = None,
    with_return: Annotated[bool, typer.Option(
        "--return", help="With --period: rise, dwell, return at TC/2, dwell (needs "
                         "TC >= 2T).")] = False,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
    plot: Annotated[Path | None, typer.Option(
        "--plot", dir_okay=False, metavar="FILE",
        help="Also draw the spectra to FILE.png or FILE.svg.", show_default=False)] = None,
    dpi: Annotated[int, typer.Option(
        "--dpi", metavar="N", min=10, max=1200, help="Resolution of the PNG.")] = 100,
    size: Annotated[str | None, typer.Option(
        "--size", metavar="WxH", help="Figure size in inches. Default: 8x5.",
        show_default=False)] = None,
) -> None:
    """Amplitude spectrum of motion laws' acceleration over the normalized frequency f*T.

    |A_N(fT)| = |int_0^1 q_N''(tau) exp(-i 2 pi fT tau) dtau|, the Fourier amplitude of
    the acceleration normalized by h/T (book sec. 7.3; --scale book divides by pi as the
    book's figures do): the family's closed form where it has one, else the exact
    numerical transform. With --displacement and --duration: |A(f)| = (h/T) |A_N(fT)| at
    f in Hz (sec. 7.3.4). With --period: the amplitudes v_k and phases of the Fourier
    series of the repeated move's acceleration at f = k/TC (sec. 7.3.3).

    Examples:

        sizer spectrum cycloidal poly5 'trapezoidal(alpha=1/3)' --plot spectra.png

        sizer spectrum poly5 --displacement 5 --duration 15 --max-ft 5 --format csv

        sizer spectrum cycloidal gutman_1_3 --period 1 --max-ft 8
    """
    from sizer.cli.output_guard import check_output
    from sizer.cli.plot_command import parse_size
    from sizer.laws import make_law  # lazy: keeps --help fast
    from sizer.report.document import publish
    from sizer.report.plots import figure_format

    check_output(output)
    figure_size = parse_size(size)
    if plot is not None:
        figure_format(plot, field="--plot")
        check_output(plot, field="--plot")
        if output is not None and plot.resolve() == output.resolve():
            raise UserError("is the same file as --output: name another file",
                            file=str(plot), field="--plot")
    if not (math.isfinite(max_ft) and 0.0 < max_ft <= MAX_FT):
        raise UserError(f"must be a number in (0, {MAX_FT:g}], got {max_ft:g}",
                        field="--max-ft")
    if not 2 <= points <= MAX_POINTS:
        raise UserError(f"must be between 2 and {MAX_POINTS:,} (MAX_SPECTRUM_LINES), got "
                        f"{points}", field="--points")
    if points * max(max_ft, 1.0) > MAX_WORK:
        raise UserError(f"--points x --max-ft must be at most {MAX_WORK:g}, got "
                        f"{points} x {max_ft:g}", field="--points")
    if order not in ORDER_NAMES:
        raise UserError(f"expected 1 (velocity), 2 (acceleration) or 3 (jerk), got {order}",
                        field="--order")
    move = scaled_move(displacement, duration, "the normalized spectrum")
    _check_scaled(move, max_ft)
    ratio = _period_ratio(period, move)
    if with_return and ratio is None:
        raise UserError("--return describes the repeated cycle: give --period too",
                        field="--return")
    if ratio is not None and order != 2:
        raise UserError("the harmonics of a repeated move are those of its acceleration; "
                        "leave --order out", field="--order")
    with blame_option("SPEC"):
        laws = [make_law(spec) for spec in dict.fromkeys(specs)]
    check_output(output)  # again: not over a file a law read (a cam table)
    check_output(plot, field="--plot")
    if ratio is None:
        document = _spectrum_document(laws, max_ft, points, order, scale, move)
        envelopes: list = []
    else:
        document, envelopes = _harmonics_document(laws, max_ft, ratio, with_return, move)
    publish(document, fmt, output)
    if plot is not None:
        from sizer.report.plots import save_figure
        from sizer.report.plots.spectrum_plot import spectrum_figure

        figure = spectrum_figure(document, envelopes=envelopes, size=figure_size, dpi=dpi)
        save_figure(figure, plot, dpi=dpi)


Move = tuple[float, float, bool] | None
"""(h, T, linear) of a scaled spectrum, or None for normalized."""


def _check_scaled(move: Move, max_ft: float) -> None:
    """The scaled frequencies (max f T / T) and amplitudes (|h| / T^k, k = 0, 1, 2:
    sizer.laws.motion.scale_fault) within the float range, else a UserError naming
    --duration."""
    from sizer.laws.motion import scale_fault

    if move is None:
        return
    h, T, _ = move
    try:
        values = [max_ft / T, 1.0 / T]
    except (OverflowError, ZeroDivisionError):
        values = [math.inf]
    fault = scale_fault(h, T, orders=2)
    if fault is not None or not all(math.isfinite(v) and v > 0.0 for v in values):
        raise UserError(f"h = {h:g} and T = {T:g} s put the scaled spectrum (f up to "
                        f"--max-ft / T, amplitudes h / T^k) outside the float range",
                        field="--duration")


def _period_ratio(period: str | None, move: Move) -> float | None:
    """T_c/T from --period: a time with --duration, a bare ratio without."""
    from sizer.units import to_si

    if period is None:
        return None
    if move is None:
        try:
            ratio = float(period)
        except ValueError:
            raise UserError(f"without --duration, give TC/T as a bare number, got "
                            f"{period!r}", field="--period") from None
    else:
        ratio = to_si(period, "time", field="--period") / move[1]
    if not math.isfinite(ratio):
        raise UserError(f"must be a finite number, got {period!r}", field="--period")
    return ratio


def _units(move: Move, order: int) -> str:
    """The unit of an amplitude of q^(order) scaled by h/T^(order-1): h's unit / s^(order-1)."""
    if move is None:
        return ""
    base = "m" if move[2] else "rad"
    return base if order == 1 else f"{base}/s" if order == 2 else f"{base}/s^2"


def _spectrum_document(laws, max_ft: float, points: int, order: int, scale: Scale,
                       move: Move):
    import numpy as np

    from sizer.laws.data_spec import law_label
    from sizer.report.numbers import short
    from sizer.report.spectrum_table import SpectrumDocument, SpectrumSeries
    from sizer.vibration.spectrum import spectrum as law_spectrum
    from sizer.vibration.spectrum_closed_forms import closed_form_of

    fT = np.linspace(0.0, max_ft, points)
    factor = 1.0 if move is None else abs(move[0]) / move[1] ** (order - 1)
    if scale is Scale.BOOK:
        factor /= math.pi
    series = tuple(SpectrumSeries(law_label(law.spec), law.spec,
                                  closed_form_of(law) is not None and order != 1,
                                  factor * law_spectrum(law, fT, order)) for law in laws)
    name = {1: "V", 2: "A", 3: "J"}[order]
    if scale is Scale.BOOK:
        value_name = "V'_N" if move is None else "V"
        what = f"{ORDER_NAMES[order]} spectrum V = |{name}|/pi (book eq. 7.8)"
    else:
        value_name = f"|{name}_N|" if move is None else f"|{name}|"
        what = f"{ORDER_NAMES[order]} amplitude spectrum |{name}|"
    if move is None:
        frequency, frequency_name = fT, "fT"
        scaling = "normalized: h = T = 1, values by " + ("h" if order == 1 else "h/T"
                                                          if order == 2 else "h/T^2")
    else:
        h, T, _ = move
        frequency, frequency_name = fT / T, "f [Hz]"
        scaling = f"h = {short(h)} {'m' if move[2] else 'rad'}, T = {short(T)} s"
    meta = {"kind": "spectrum", "order": order, "quantity": ORDER_NAMES[order],
            "scale": scale.value, "normalized": move is None,
            "displacement": None if move is None else move[0],
            "duration": None if move is None else move[1],
            "units": {"frequency": "" if move is None else "Hz",
                      "value": _units(move, order)}}
    return SpectrumDocument(frequency, series, frequency_name, value_name,
                            _units(move, order), f"{what} ({scaling})", meta=meta)


def _harmonics_document(laws, max_ft: float, ratio: float, with_return: bool, move: Move):
    import numpy as np

    from sizer.laws.data_spec import law_label
    from sizer.report.numbers import short
    from sizer.report.spectrum_table import SpectrumDocument, SpectrumSeries
    from sizer.vibration.harmonics import (
        check_period_ratio,
        harmonic_content,
        harmonic_numbers,
    )
    from sizer.vibration.spectrum import acceleration_spectrum

    with blame_option("--period"):
        ratio = check_period_ratio(ratio, with_return, field="--period")
    with as_option("max_ft", "--max-ft"):
        k = harmonic_numbers(max_ft, ratio)
    if k.size == 0:
        raise UserError(f"no harmonic up to f*T = {max_ft:g}: the first is at "
                        f"f*T = T/TC = {1.0 / ratio:g}", field="--max-ft")
    contents = [harmonic_content(law, k, ratio, with_return) for law in laws]
    factor = 1.0 if move is None else abs(move[0]) / move[1] ** 2
    series = tuple(SpectrumSeries(law_label(law.spec), law.spec, False,
                                  factor * content.amplitude, content.phase)
                   for law, content in zip(laws, contents, strict=True))
    fT = contents[0].fT
    envelopes = []
    if not with_return:  # v_k samples 2 (T/T_c) |A_N| at fT = k T/T_c
        grid = np.linspace(0.0, float(fT[-1]),
                           min(max(201, 40 * k.size), MAX_SPECTRUM_CURVE_POINTS))
        envelopes = [(grid if move is None else grid / move[1],
                      factor * 2.0 / ratio * acceleration_spectrum(law, grid))
                     for law in laws]
    cycle = ("rise, dwell, return, dwell" if with_return else
             "rise repeated" if ratio == 1.0 else "rise, dwell")
    if move is None:
        frequency, frequency_name = fT, "fT"
        scaling = f"T_c/T = {short(ratio)}, values by h/T^2"
    else:
        h, T, _ = move
        frequency, frequency_name = fT / T, "f [Hz]"
        scaling = (f"h = {short(h)} {'m' if move[2] else 'rad'}, T = {short(T)} s, "
                   f"T_c = {short(ratio * T)} s")
    unit = "" if move is None else ("m/s^2" if move[2] else "rad/s^2")
    meta = {"kind": "harmonics", "cycle": cycle, "period_ratio": ratio,
            "with_return": with_return, "normalized": move is None,
            "displacement": None if move is None else move[0],
            "duration": None if move is None else move[1],
            "units": {"frequency": "" if move is None else "Hz", "value": unit,
                      "phase": "rad"}}
    title = f"harmonics v_k of the repeated acceleration ({cycle}; {scaling})"
    document = SpectrumDocument(frequency, series, frequency_name,
                                "v_Nk" if move is None else "v_k", unit, title, k=k,
                                meta=meta)
    return document, envelopes


def register(app: typer.Typer) -> None:
    app.command("spectrum")(spectrum)
