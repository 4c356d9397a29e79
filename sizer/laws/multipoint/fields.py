"""Reading the YAML mapping of a data-defined law: one clear message per bad field.

Every builder takes the mapping as plain data (numbers, lists, mappings, strings, as
PyYAML gives them) and reads it through these functions, so that a mistake names the
field and, where it matters, the point: ``UserError(message, field="points")``. The
design loader adds the file and the line.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from sizer.errors import UserError
from sizer.input_limits import MAX_VIA_POINTS

ORDER_NAMES: dict[str, int] = {"position": 0, "velocity": 1, "acceleration": 2, "jerk": 3,
                               "snap": 4}
"""Kinematic conditions by name and derivative order."""


def refuse_unknown(fields: Mapping[str, Any], known: Iterable[str], kind: str) -> None:
    """UserError naming the first key of ``fields`` that the kind does not read."""
    known = tuple(known)
    for key in fields:
        if key not in known and key != "kind":
            raise UserError(f"{kind} has no field {key!r}; its fields: "
                            f"{', '.join(known)} (and kind, units, name, as every law "
                            f"defined by data)", field=str(key))


def number(fields: Mapping[str, Any], key: str, default: float | None = None, *,
           positive: bool = False, low: float | None = None, high: float | None = None
           ) -> float:
    """A finite number (bool refused); ``default`` when absent, required when None."""
    if key not in fields or fields[key] is None:
        if default is None:
            raise UserError("is required", field=key)
        return default
    value = as_number(fields[key], key)
    if positive and not value > 0.0:
        raise UserError(f"must be positive, got {value:g}", field=key)
    if (low is not None and value < low) or (high is not None and value > high):
        raise UserError(f"must be in [{_text(low)}, {_text(high)}], got {value:g}", field=key)
    return value


def _text(bound: float | None) -> str:
    return "..." if bound is None else f"{bound:g}"


def integer(fields: Mapping[str, Any], key: str, default: int | None = None, *,
            low: int = 1, high: int = 20) -> int:
    """An integer in [low, high]; ``default`` when absent, required when None."""
    if key not in fields or fields[key] is None:
        if default is None:
            raise UserError("is required", field=key)
        return default
    value = fields[key]
    if isinstance(value, bool) or not isinstance(value, int | float) or value != int(value):
        raise UserError(f"must be an integer, got {value!r}", field=key)
    if not low <= int(value) <= high:
        raise UserError(f"must be between {low} and {high}, got {int(value)}", field=key)
    return int(value)


def as_number(value: Any, field: str) -> float:
    """A finite float from a YAML scalar, or UserError naming the field."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise UserError(f"must be a number, got {value!r}", field=field)
    value = float(value)
    if not math.isfinite(value):
        raise UserError(f"must be a finite number, got {value!r}", field=field)
    return value


def numbers(fields: Mapping[str, Any], key: str, *, minimum: int = 1,
            length: int | None = None) -> np.ndarray:
    """A list of finite numbers (at least ``minimum``, exactly ``length`` if given)."""
    if key not in fields or fields[key] is None:
        raise UserError("is required", field=key)
    value = fields[key]
    if not isinstance(value, list | tuple):
        raise UserError(f"must be a list of numbers, got {value!r}", field=key)
    too_many(len(value), key)
    out = np.array([as_number(v, f"{key}[{i}]") for i, v in enumerate(value)], dtype=float)
    if length is not None and len(out) != length:
        raise UserError(f"must have {length} numbers, got {len(out)}", field=key)
    if len(out) < minimum:
        raise UserError(f"needs at least {minimum} numbers, got {len(out)}", field=key)
    return out


def too_many(count: int, field: str) -> None:
    """UserError when a list of a law's data is longer than MAX_VIA_POINTS (the splines'
    dense systems cost the cube of it); a longer table belongs in a cam_table file."""
    if count > MAX_VIA_POINTS:
        raise UserError(f"{count:,} values: the limit is {MAX_VIA_POINTS:,} "
                        f"(MAX_VIA_POINTS); for more samples use a cam_table file",
                        field=field)


def increasing(values: np.ndarray, field: str, *, strict: bool = True) -> np.ndarray:
    """``values`` if (strictly) increasing, else UserError naming the first bad index."""
    steps = np.diff(values)
    bad = np.flatnonzero(steps <= 0.0 if strict else steps < 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        word = "increasing" if strict else "non-decreasing"
        raise UserError(f"must be {word}: {field}[{i}] = {values[i]:g} follows "
                        f"{values[i - 1]:g}", field=field)
    return values


def points(fields: Mapping[str, Any], *, minimum: int = 2,
           times_key: str = "times", positions_key: str = "positions"
           ) -> tuple[np.ndarray, np.ndarray]:
    """Via-points (t, q): ``points: [[t, q], ...]``, or ``times`` and ``positions`` lists.

    The times must increase strictly; at least ``minimum`` points.
    """
    if "points" in fields:
        if times_key in fields or positions_key in fields:
            raise UserError(f"give either points or {times_key} and {positions_key}, "
                            f"not both", field="points")
        raw = fields["points"]
        if not isinstance(raw, list | tuple) or not all(
                isinstance(p, list | tuple) and len(p) == 2 for p in raw):
            raise UserError("must be a list of [t, q] pairs, e.g. [[0, 0], [0.5, 0.3], "
                            "[1, 1]]", field="points")
        too_many(len(raw), "points")
        t = np.array([as_number(p[0], f"points[{i}]") for i, p in enumerate(raw)])
        q = np.array([as_number(p[1], f"points[{i}]") for i, p in enumerate(raw)])
        if len(t) < minimum:
            raise UserError(f"needs at least {minimum} points, got {len(t)}", field="points")
        return _increasing_points(t), q
    q = numbers(fields, positions_key, minimum=minimum)
    t = numbers(fields, times_key, length=len(q))
    return increasing(t, times_key), q


def _increasing_points(t: np.ndarray) -> np.ndarray:
    bad = np.flatnonzero(np.diff(t) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise UserError(f"times must increase: point {i} has t = {t[i]:g} after "
                        f"t = {t[i - 1]:g}", field=f"points[{i}]")
    return t


def conditions(fields: Mapping[str, Any], key: str, *, highest: int = 4
               ) -> dict[int, float]:
    """Kinematic conditions at one end, ``start: {velocity: 0, acceleration: 0}``, as
    {derivative order: value}; {} when absent. Names: position ... snap (ORDER_NAMES)."""
    if key not in fields or fields[key] is None:
        return {}
    raw = fields[key]
    if not isinstance(raw, Mapping):
        raise UserError(f"must be a mapping like {{velocity: 0, acceleration: 0}}, got "
                        f"{raw!r}", field=key)
    out: dict[int, float] = {}
    for name, value in raw.items():
        order = ORDER_NAMES.get(str(name))
        if order is None or order > highest:
            allowed = [n for n, k in ORDER_NAMES.items() if k <= highest]
            raise UserError(f"unknown condition {name!r}; conditions: {', '.join(allowed)}",
                            field=f"{key}.{name}")
        out[order] = as_number(value, f"{key}.{name}")
    return out


# --- poly_spline, bspline, nurbs (helper B): order, interior and periodic conditions ---

def order_of(fields: Mapping[str, Any], *, low: int = 2, high: int = 12) -> int:
    """The spline's order k (degree k - 1, the slides' word): ``order: 6``, or the book's
    ``degree: 5``; one of the two is required."""
    if "order" in fields and "degree" in fields:
        raise UserError("give either order (k, the slides) or degree (p = k - 1, the "
                        "book), not both", field="order")
    if "degree" in fields:
        return integer(fields, "degree", low=low - 1, high=high - 1) + 1
    if "order" not in fields:
        raise UserError("is required (the spline's order k: degree k - 1, continuity "
                        "up to derivative k - 2; or give degree)", field="order")
    return integer(fields, "order", low=low, high=high)


def timed_conditions(fields: Mapping[str, Any], key: str = "conditions", *,
                     highest: int = 4) -> list[tuple[float, int, float, str]]:
    """Conditions inside the interval, ``conditions: [{t: 0.4, velocity: 0}, ...]``, as
    (t, derivative order, value, field label); [] when absent."""
    if key not in fields or fields[key] is None:
        return []
    raw = fields[key]
    if not isinstance(raw, list | tuple):
        raise UserError(f"must be a list like [{{t: 0.5, velocity: 0}}], got {raw!r}",
                        field=key)
    out: list[tuple[float, int, float, str]] = []
    for i, item in enumerate(raw):
        where = f"{key}[{i}]"
        if not isinstance(item, Mapping) or "t" not in item or len(item) < 2:
            raise UserError(f"must be a mapping with t and at least one condition, e.g. "
                            f"{{t: 0.5, velocity: 0}}, got {item!r}", field=where)
        t = as_number(item["t"], f"{where}.t")
        rest = {name: value for name, value in item.items() if name != "t"}
        for order, value in conditions({where: rest}, where, highest=highest).items():
            name = next(n for n, k in ORDER_NAMES.items() if k == order)
            out.append((t, order, value, f"{where}.{name}"))
    return out


def periodic(fields: Mapping[str, Any], key: str = "periodic", *, highest: int = 4
             ) -> list[int]:
    """Cyclic conditions s^(i)(t_0) = s^(i)(t_n) (book eq. 4.45), ``periodic: [velocity,
    acceleration]``, as derivative orders; [] when absent."""
    if key not in fields or fields[key] is None:
        return []
    raw = fields[key]
    if not isinstance(raw, list | tuple):
        raise UserError(f"must be a list of derivative names like [velocity, "
                        f"acceleration], got {raw!r}", field=key)
    out: list[int] = []
    for i, name in enumerate(raw):
        order = ORDER_NAMES.get(str(name))
        if order is None or not 1 <= order <= highest:
            allowed = [n for n, k in ORDER_NAMES.items() if 1 <= k <= highest]
            raise UserError(f"unknown derivative {name!r}; periodic takes: "
                            f"{', '.join(allowed)}", field=f"{key}[{i}]")
        if order in out:
            raise UserError(f"{name} is listed twice", field=f"{key}[{i}]")
        out.append(order)
    return out


# --- cam_table (helper C): the fitting fields ------------------------------------------

def boolean(fields: Mapping[str, Any], key: str, default: bool) -> bool:
    """A YAML boolean (true/false); ``default`` when absent."""
    if key not in fields or fields[key] is None:
        return default
    value = fields[key]
    if not isinstance(value, bool):
        raise UserError(f"must be true or false, got {value!r}", field=key)
    return value
