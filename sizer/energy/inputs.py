"""Checks of the figures the energy and heat models read (issue 16): one UserError naming
the field, never a NaN or a numpy exception further on."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from sizer.errors import UserError


def finite(value: ArrayLike, field: str) -> np.ndarray:
    """``value`` as a float array, every entry finite."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise UserError("must be a number or an array of numbers", field=field) from None
    if not bool(np.all(np.isfinite(array))):
        raise UserError("must be finite (no inf or NaN)", field=field)
    return array


def positive(value: ArrayLike, field: str, what: str = "") -> np.ndarray:
    """``value`` as a float array, every entry finite and > 0."""
    array = finite(value, field)
    if bool(np.any(array <= 0.0)):
        worst = float(np.min(array))
        raise UserError(f"must be > 0{what}, got {worst:g}", field=field)
    return array


def nonnegative(value: ArrayLike, field: str) -> np.ndarray:
    """``value`` as a float array, every entry finite and >= 0."""
    array = finite(value, field)
    if bool(np.any(array < 0.0)):
        raise UserError(f"must be >= 0, got {float(np.min(array)):g}", field=field)
    return array


def fraction(value: ArrayLike, field: str) -> np.ndarray:
    """A share in [0, 1)."""
    array = finite(value, field)
    if bool(np.any((array < 0.0) | (array >= 1.0))):
        raise UserError("must be in [0, 1)", field=field)
    return array


def times(value: ArrayLike, field: str = "time") -> np.ndarray:
    """Sample times: (samples,) shared by all candidates or (candidates, samples), at least
    two finite, non-decreasing values per row spanning a positive time (a repeated time is
    a jump of the sampled quantity there). Returned 2-D: (1 or candidates, samples)."""
    array = finite(value, field)
    if array.ndim == 1:
        array = array[None, :]
    if array.ndim != 2 or array.shape[1] < 2:
        raise UserError("must be at least two sample times, as an array (samples,) or "
                        "(candidates, samples)", field=field)
    if bool(np.any(np.diff(array, axis=1) < 0.0)):
        raise UserError("sample times must not decrease", field=field)
    if not bool(np.all(array[:, -1] > array[:, 0])):
        raise UserError("sample times must span a positive time", field=field)
    return array


def span(time: np.ndarray) -> np.ndarray:
    """The time each row of samples spans, (rows,)."""
    return time[:, -1] - time[:, 0]


def samples(value: ArrayLike, time: np.ndarray, field: str) -> np.ndarray:
    """Values sampled at ``time`` (2-D, from :func:`times`): shape (samples,) or
    (candidates, samples), returned 2-D."""
    array = finite(value, field)
    if array.ndim == 1:
        array = array[None, :]
    if array.ndim != 2 or array.shape[1] != time.shape[1]:
        raise UserError(f"must have one value per sample time ({time.shape[1]}), as an "
                        "array (samples,) or (candidates, samples)", field=field)
    if time.shape[0] not in (1, array.shape[0]) and array.shape[0] != 1:
        raise UserError(f"has {array.shape[0]} candidates (rows), the sample times "
                        f"{time.shape[0]}", field=field)
    return array


def per_candidate(value: ArrayLike, n: int, field: str) -> np.ndarray:
    """A scalar or one value per candidate, returned as a column (n or 1, 1)."""
    array = np.asarray(value, dtype=float)
    if array.ndim == 0:
        return array.reshape(1, 1)
    if array.ndim != 1 or array.size not in (1, n):
        raise UserError(f"must be one number or one per candidate ({n})", field=field)
    return array.reshape(-1, 1)
