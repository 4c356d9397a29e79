"""The book's coefficient tables 2.2 and 6.1 to 6.7, reproduced to the printed digits.

Where the book misprints a value, the test pins the right one (ERRATA, docs/errata.md)
and checks that the printed one is really off, so an erratum cannot hide a bug.
"""

from __future__ import annotations

from decimal import ROUND_HALF_UP, Decimal

import pytest
from book_tables import (
    DOUBLE_S_ALPHAS,
    DOUBLE_S_BETAS,
    ERRATA,
    TABLE_2_2,
    TABLE_6_1,
    TABLE_6_2,
    TABLE_6_2_LAWS,
    TABLE_6_3,
    TABLE_6_4_C_V,
    TABLE_6_5_C_A,
    TABLE_6_6_C_V_RMS,
    TABLE_6_7_C_A_RMS,
)

from sizer.laws import make_law

PEAK_RMS = ("C_v", "C_a", "C_v_rms", "C_a_rms")


def matches_printed(value: float, printed: str) -> bool:
    """True if value rounds (half up, as printed tables do) to ``printed``."""
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    if decimals == 0:
        return abs(value - float(printed)) <= 1e-9 * max(1.0, abs(value))
    shown = Decimal(repr(value)).quantize(Decimal(1).scaleb(-decimals), rounding=ROUND_HALF_UP)
    return str(shown) == printed


def cases():
    for name, row in TABLE_6_1.items():
        for coef, printed in zip(("C_v", "C_a"), row, strict=True):
            yield "6.1", name, TABLE_6_2_LAWS[name], coef, printed
    for name, row in TABLE_6_2.items():
        for coef, printed in zip(PEAK_RMS, row, strict=True):
            yield "6.2", name, TABLE_6_2_LAWS[name], coef, printed
    for alpha, row in TABLE_6_3.items():
        for coef, printed in zip(PEAK_RMS, row, strict=True):
            yield "6.3", alpha, f"trapezoidal(alpha={alpha})", coef, printed
    grids = (("6.4", TABLE_6_4_C_V, "C_v"), ("6.5", TABLE_6_5_C_A, "C_a"),
             ("6.6", TABLE_6_6_C_V_RMS, "C_v_rms"), ("6.7", TABLE_6_7_C_A_RMS, "C_a_rms"))
    for table, grid, coef in grids:
        for alpha, row in zip(DOUBLE_S_ALPHAS, grid, strict=True):
            for beta, printed in zip(DOUBLE_S_BETAS, row, strict=True):
                spec = f"double_s(alpha={alpha}, beta={beta})"
                yield table, f"{alpha}, {beta}", spec, coef, printed
    for degree, row in TABLE_2_2.items():
        for coef, printed in zip(("C_v", "C_a", "C_j"), row, strict=True):
            yield "2.2", str(degree), f"polynomial({degree})", coef, printed


CASES = list(cases())


@pytest.mark.parametrize(("table", "row", "spec", "coef", "printed"), CASES,
                         ids=[f"T{c[0]}-{c[1]}-{c[3]}" for c in CASES])
def test_book_table_value(table, row, spec, coef, printed):
    value = getattr(make_law(spec).coefficients, coef)
    corrected = ERRATA.get((table, row, coef))
    if corrected is None:
        assert matches_printed(value, printed), f"{value!r} does not print as {printed}"
    else:
        assert not matches_printed(value, printed), "erratum listed but book value matches"
        assert matches_printed(value, corrected), f"{value!r} does not print as {corrected}"


def test_every_erratum_is_a_table_entry():
    keys = {(c[0], c[1], c[3]) for c in CASES}
    assert set(ERRATA) <= keys
