"""Quantities with units at the boundary, SI floats inside (pint).

``to_si("3000 rpm", "angular_speed") == 314.159...``. A bare number (or a string with no
unit) is already SI. Angles are dimensionless in pint, so an angle and a plain number
are told apart by the unit text, not the dimension.

Units are read the way datasheets write them. The rules, applied to every field of a kind
(design files, catalogs, ``sizer catalog validate`` and ``sizer catalog import`` alike):

- **Frequencies are revolutions.** Where an angular speed, acceleration or jerk is expected,
  a unit with no angle in it (a pure frequency: ``Hz``, ``1/min``, ``min^-1``, ``1/s``,
  ``s^-1``; ``Hz/s``, ``1/s^2``, ``min^-2`` for accelerations, ``1/s^3`` for jerks) means
  revolutions per unit time: ``3000 min^-1`` = ``3000 rpm`` = ``50 rev/s`` = ``50 Hz`` =
  314.159... rad/s, and ``1 Hz/s`` = 2*pi rad/s^2. A unit with an angle (``rad``, ``deg``,
  ``rev``, ``r``, ``turn``; ``rpm`` and ``rps`` are rev per minute and per second) means
  that angle: ``1 rad/s`` stays 1 rad/s. Also read: ``RPM``, ``r/min``, ``U/min``, ``r/s``.
  A bare number stays SI (rad/s). A rotary damping is not covered: write its angle
  (``N*m*s/rad``, ``N*m/rpm``); a damping without one is per radian (SI).
- **Torques as datasheets write them.** Where a torque (or a rotary damping) is expected,
  ``Nm``, ``mNm``, ``kNm``, ``Ncm``, ``Nmm`` are N*m, mN*m, ... (pint alone reads ``Nm`` as
  a "number meter"); ``N.m``, ``N·m``, ``N-m`` and ``N*m`` are the same. Inertias accept
  ``kgm^2``, ``kgcm^2``, ``gcm^2`` likewise. Superscripts (``min⁻¹``, ``kg·cm²``) are read
  as exponents.
- **Gravitational (imperial) units.** Where a torque is expected, a mass times a length
  (``oz*in``, ``lb*ft``, ``kg*cm``) is read with the mass as its weight (x g_n = 9.80665
  m/s^2): ``1 oz*in`` = ``1 ozf*in`` = 7.0615518e-3 N*m, ``1 lb*ft`` = ``1 lbf*ft``. Where an
  inertia is expected, a mass times a length times a time squared (``oz*in*s^2``) is read
  the same way: ``1 oz*in*s^2`` = ``1 ozf*in*s^2`` = 7.0615518e-3 kg*m^2; ``lb*in^2`` and
  ``oz*in^2`` are plain inertias (1 lb*in^2 = 2.9263965e-4 kg*m^2).
- **GD^2.** An inertia may be given as the flywheel effect GD^2 with the marker ``GD^2``
  after the unit: ``"0.04 kgf*m^2 GD^2"`` is J = GD^2/4 = 0.01 kg*m^2 (G, the weight in kgf,
  is numerically the mass in kg; D the diameter of gyration). A GD^2 in N*m^2 is divided by
  4 g_n; one written with a mass (``kg*m^2 GD^2``) by 4.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache
from typing import Any

from sizer.errors import UserError
from sizer.input_limits import MAX_EXPONENT, MAX_NUMBER_CHARS, MAX_QUANTITY_CHARS, MAX_UNIT_POWER


@dataclass(frozen=True)
class Kind:
    """A physical kind of quantity: its pint dimensionality and an example for messages."""

    name: str
    dimensionality: str
    example: str
    si_unit: str


KINDS: dict[str, Kind] = {
    k.name: k
    for k in (
        Kind("time", "[time]", "0.2 s", "s"),
        Kind("angle", "", "90 deg", "rad"),
        Kind("length", "[length]", "200 mm", "m"),
        Kind("angular_speed", "1/[time]", "3000 rpm", "rad/s"),
        Kind("linear_speed", "[length]/[time]", "1.5 m/s", "m/s"),
        Kind("angular_acceleration", "1/[time]**2", "500 rad/s^2", "rad/s^2"),
        Kind("linear_acceleration", "[length]/[time]**2", "9.81 m/s^2", "m/s^2"),
        Kind("angular_jerk", "1/[time]**3", "1e5 rad/s^3", "rad/s^3"),
        Kind("linear_jerk", "[length]/[time]**3", "100 m/s^3", "m/s^3"),
        Kind("torque", "[mass]*[length]**2/[time]**2", "0.5 N*m", "N*m"),
        Kind("force", "[mass]*[length]/[time]**2", "100 N", "N"),
        Kind("inertia", "[mass]*[length]**2", "1.2 kg*cm^2", "kg*m^2"),
        Kind("mass", "[mass]", "12 kg", "kg"),
        Kind("density", "[mass]/[length]**3", "7.87e3 kg/m^3", "kg/m^3"),
        Kind("rotary_damping", "[mass]*[length]**2/[time]", "0.01 N*m*s/rad", "N*m*s/rad"),
        Kind("linear_damping", "[mass]/[time]", "5 N*s/m", "N*s/m"),
        Kind("fraction", "", "10 %", "1"),
        Kind("ratio", "", "10", "1"),
        Kind("money", "", "450", "1"),
        Kind("rate", "1/[time]", "50 1/min", "1/s"),  # cycles per time (a machine cycle's)
        Kind("temperature_rise", "[temperature]", "100 K", "K"),
        Kind("current", "[current]", "9 A", "A"),
        Kind("torque_constant", "[mass]*[length]**2/[time]**2/[current]", "0.88 N*m/A",
             "N*m/A"),
        Kind("resistance", "[mass]*[length]**2/[time]**3/[current]**2", "1.2 ohm", "ohm"),
        Kind("inductance", "[mass]*[length]**2/[time]**2/[current]**2", "12.5 mH", "H"),
        Kind("back_emf_constant", "[mass]*[length]**2/[time]**2/[current]", "52 V/krpm",
             "V*s/rad"),
        Kind("voltage", "[mass]*[length]**2/[time]**3/[current]", "600 V", "V"),
        Kind("capacitance", "[current]**2*[time]**4/[mass]/[length]**2", "705 uF", "F"),
        Kind("power", "[mass]*[length]**2/[time]**3", "1.5 kW", "W"),
    )
}

_ANGLE_UNITS = re.compile(r"^(rad|radian|radians|deg|degree|degrees|rev|revolution|revolutions|"
                          r"turn|turns|arcmin|arcminute|arcsec|arcsecond)$")


@cache
def registry() -> Any:
    """The shared pint UnitRegistry, created on first use (pint is slow to import)."""
    import pint

    ureg: Any = pint.UnitRegistry()
    ureg.define("rev = revolution")
    return ureg


_NUMBER_AND_UNIT = re.compile(
    r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?(?![\d.])"
    r"|[+-]?\.?(?:nan|inf(?:inity)?)(?![A-Za-z]))\s*(.*?)\s*$",
    re.IGNORECASE | re.ASCII,
)
"""A number and the unit after it, with or without a space: '0.5 s', '0.5s', '1e-3s',
'2e3rpm' (an exponent binds to the number: '1e5' alone is a number), '10%'."""

_SPACE = r"[ \t\n\r\f\v]"
_NUMBER_FORM = r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
_UNIT_FORM = r"(?:{s}*[^ \t\n\r\f\v0-9.,+\-*/^][^\r\n]*|{s}+[0-9]+{s}*/[^\r\n]*)"


def quantity_pattern(*, slash: bool = False) -> str:
    """The form of a quantity written as text, for the JSON Schemas (``sizer schema``) and
    :func:`to_si` alike: a finite number, then optionally a unit, glued or after spaces,
    that starts with a letter, ``%``, ``(``... or is ``1/...`` after a space (``50 1/min``);
    ``slash``: also a unit that starts with ``/`` (``50 /min``, a cycle rate). The unit
    itself, its kind and the range are checked by the loader only."""
    unit = _UNIT_FORM.format(s=_SPACE)
    if slash:
        unit = f"(?:{unit}|{_SPACE}*/[^\r\n]*)"
    return f"^{_SPACE}*{_NUMBER_FORM}{unit}?{_SPACE}*$"


QUANTITY_PATTERN = quantity_pattern()
"""See :func:`quantity_pattern`."""
_QUANTITY_FORM = re.compile(QUANTITY_PATTERN)
_FLOAT_MAX = 1.7976931348623157e308
_POWER = re.compile(r"\*\*\s*(\(\s*)?([+-]?\s*\d+(?:\.\d+)?(?:\s*/\s*\d+)?)(?(1)\s*\))")
_FACTOR = re.compile(r"(?<![A-Za-z_\d.])\d[\d.]*(?:[eE][+-]?\d+)?", re.ASCII)


class _LimitError(UserError):
    """A number or unit text out of bounds: its message stands as it is (not 'expected ...')."""


def _not_finite(value: Any, field: str | None) -> UserError:
    if isinstance(value, int):  # too large for a float (repr fails beyond 4300 digits)
        shown = f"an integer of about {int(value.bit_length() * 0.30103) + 1} digits"
    else:
        shown = repr(value) if len(repr(value)) <= 60 else f"{repr(value)[:57]}..."
    return _LimitError(f"{shown} is not a finite number: numbers must be finite, "
                     f"below {_FLOAT_MAX:.4g} in size", field=field)


def _check_unit_text(unit: str, text: str, spec: Kind, field: str | None) -> None:
    """Refuse powers pint would spend unbounded work on (``10**10**10``, ``m**1e9``)."""
    wrong = _LimitError(f"unit {unit!r} in {text!r}: a power must be a plain number of at most "
                      f"{MAX_UNIT_POWER} ({spec.name.replace('_', ' ')} expected, e.g. "
                      f"{spec.example!r})", field=field)
    pos = 0
    while (start := unit.find("**", pos)) >= 0:
        match = _POWER.match(unit, start)
        if match is None:
            raise wrong
        power = match.group(2).replace(" ", "")
        num, _, den = power.partition("/")
        if abs(float(num)) > MAX_UNIT_POWER or (den and float(den) == 0):
            raise wrong
        pos = match.end()
        if unit[pos:].lstrip().startswith("**"):
            raise wrong
    for factor in _FACTOR.findall(unit):
        exponent = re.search(r"[eE]([+-]?\d+)$", factor)
        too_big = exponent is not None and abs(int(exponent.group(1))) > MAX_EXPONENT
        if len(factor) > MAX_NUMBER_CHARS or too_big:
            raise _LimitError(f"unit {unit!r} in {text!r}: the number {factor[:30]!r} is out of "
                            f"range (numbers must be finite)", field=field)


def _expected(spec: Kind, got: Any, field: str | None) -> UserError:
    name = spec.name.replace("_", " ")
    article = "an" if name[0] in "aeiou" else "a"
    return UserError(f"expected {article} {name} like {spec.example!r}, got {got!r}", field=field)


def _split(text: str) -> tuple[str, str]:
    """('90', 'deg') from '90 deg'; the unit part may be empty."""
    match = _NUMBER_AND_UNIT.match(text)
    if not match:
        return "", text.strip()
    return match.group(1), match.group(2)


def to_si(value: Any, kind: str, *, field: str | None = None) -> float:
    """Convert a number or a text like '3000 rpm' of the given kind to an SI float.

    Raises UserError (with ``field``) for a wrong unit, a non-number or a non-finite value.
    """
    spec = KINDS[kind]
    if isinstance(value, bool) or value is None:
        raise _expected(spec, value, field)
    if isinstance(value, int | float):
        try:
            result = float(value)
        except OverflowError:  # an int beyond the float range
            raise _not_finite(value, field) from None
    elif isinstance(value, str):
        if len(value) > MAX_QUANTITY_CHARS:
            raise UserError(f"expected {spec.name.replace('_', ' ')} like {spec.example!r}, got "
                            f"a text of {len(value):,} characters (the limit is "
                            f"{MAX_QUANTITY_CHARS})", field=field)
        result = _parse_text(value, spec, field)
    else:
        raise _expected(spec, value, field)
    if not math.isfinite(result):
        raise _not_finite(value, field)
    return result


_ANGULAR_MOTION = frozenset({"angular_speed", "angular_acceleration", "angular_jerk"})
_TEMPERATURE_DIFFERENCES = frozenset({"K", "kelvin", "delta_degC", "delta_degF"})
"""Units of a temperature rise: a difference, no offset (a rise of 100 K = 100 delta_degC)."""
_TORQUE_LIKE = frozenset({"torque", "rotary_damping", "torque_constant"})
_ELECTRIC = frozenset({"current", "torque_constant"})
_PER_ANGLE = frozenset({"back_emf_constant"})
"""Quantities per unit of angular speed (V/krpm, mV/min^-1): a unit without an angle in its
speed counts revolutions (min^-1 = rpm), so its value is per 2 pi rad."""
_RMS_VOLT = re.compile(r"^(V|mV)(?:_?rms|rms|eff|_eff)$|^(Vrms|Veff)$", re.IGNORECASE)
_RMS_AMPERE = re.compile(r"^(A|mA)(?:_?rms|rms|eff|_eff)$|^(Arms|Aeff)$", re.IGNORECASE)
"""Amperes as datasheets write RMS currents ('Arms', 'A_rms', 'Aeff'): plain amperes (a
current of a drive or a motor is an RMS value throughout)."""

_SUPERSCRIPT = re.compile(r"([⁺⁻]?)([⁰¹²³⁴⁵⁶⁷⁸⁹]+)")
_SUPERSCRIPT_DIGITS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻", "0123456789+-")
_WORD = re.compile(r"[A-Za-zµμ_]+")
_ANGLE_WORDS = {"r": "rev", "U": "rev", "RPM": "rpm", "Rpm": "rpm", "RPS": "rps",
                "revs": "rev"}
"""Words of angular speeds as datasheets write them ('r/min', 'U/min', 'RPM')."""
_NEWTON_METRE = re.compile(r"^([kmcµμ]?)N(m|cm|mm)$")
_KILOGRAM_METRE = re.compile(r"^(k?g)(m|cm|mm)$")
_GD2 = re.compile(r"\s*\bGD(?:\^?2|\*\*2)$")


def _normalize(unit: str, kind: str) -> str:
    """A datasheet's unit text in pint's syntax, for a quantity of ``kind``."""
    unit = unit.replace("·", "*").replace("⋅", "*").replace("×", "*").replace("−", "-")
    unit = re.sub(r"(?<=[A-Za-z])[-.](?=[A-Za-z])", "*", unit)  # N-m, oz-in, N.m

    def word(match: re.Match[str]) -> str:
        text = match.group(0)
        if kind in _ANGULAR_MOTION:
            return _ANGLE_WORDS.get(text, text)
        if kind in _ELECTRIC and _RMS_AMPERE.match(text):
            return "mA" if text[:2].lower() == "ma" else "A"
        if kind in _PER_ANGLE and _RMS_VOLT.match(text):
            return "mV" if text[:2].lower() == "mv" else "V"
        if kind in _TORQUE_LIKE:
            return _NEWTON_METRE.sub(r"\1N*\2", text)
        if kind == "inertia":
            return _KILOGRAM_METRE.sub(r"\1*\2", text)
        return text

    return _WORD.sub(word, unit).replace("^", "**")


@dataclass(frozen=True)
class _Recipe:
    """How a number written with one unit becomes SI: ``number * factor``, then (for an
    angular quantity whose unit has no angle) ``* 2.0 * pi``, or (a GD^2) ``/ 4.0``.

    The operations are pint's own, in pint's order (pint converts a magnitude by one
    multiplication by a factor of the units alone), so the result is bit-identical to
    converting each value with pint.
    """

    factor: float
    revolutions: bool = False
    gd2: bool = False
    per_revolution: bool = False

    def apply(self, number: float) -> float:
        value = number * self.factor
        if self.revolutions:
            return value * 2.0 * math.pi
        if self.per_revolution:
            return value / (2.0 * math.pi)
        if self.gd2:
            return value / 4.0
        return value


_SI_FACTORS: dict[str, dict[str, float]] = {
    "time": {"s": 1.0, "ms": 0.001, "min": 60.0, "h": 3600.0},
    "angle": {"rad": 1.0, "deg": 0.017453292519943295, "rev": 6.283185307179586,
              "arcmin": 0.00029088820866572163, "arcsec": 4.84813681109536e-06},
    "length": {"m": 1.0, "mm": 0.001, "cm": 0.01, "um": 1e-06},
    "angular_speed": {"rad/s": 1.0, "rpm": 0.10471975511965977,
                      "rev/min": 0.10471975511965977, "rev/s": 6.283185307179586,
                      "deg/s": 0.017453292519943295},
    "linear_speed": {"m/s": 1.0, "mm/s": 0.001, "m/min": 0.016666666666666666},
    "angular_acceleration": {"rad/s**2": 1.0},
    "linear_acceleration": {"m/s**2": 1.0, "mm/s**2": 0.001},
    "angular_jerk": {"rad/s**3": 1.0},
    "linear_jerk": {"m/s**3": 1.0},
    "torque": {"N*m": 1.0, "mN*m": 0.001, "N*cm": 0.01,
               # a rotary spring's stiffness, read as a torque (the radian is a ratio)
               "N*m/rad": 1.0, "N*m/deg": 57.29577951308232},
    "force": {"N": 1.0, "kN": 1000.0},
    "inertia": {"kg*m**2": 1.0, "kg*cm**2": 0.0001, "g*cm**2": 1.0000000000000001e-07},
    "mass": {"kg": 1.0, "g": 0.001},
    "density": {"kg/m**3": 1.0},
    "rotary_damping": {"N*m*s/rad": 1.0},
    "linear_damping": {"N*s/m": 1.0},
    "rate": {"Hz": 1.0, "kHz": 1000.0, "1/s": 1.0},
    "current": {"A": 1.0},
    "temperature_rise": {"K": 1.0, "kelvin": 1.0},  # a difference of temperatures
    "torque_constant": {"N*m/A": 1.0, "mN*m/A": 0.001},
    "resistance": {"ohm": 1.0},
    "inductance": {"H": 1.0, "mH": 0.001},
    "back_emf_constant": {"V/krpm": 0.00954929658551372, "mV/rpm": 0.00954929658551372,
                          "V*s/rad": 1.0},  # per radian (a speed in rpm counts radians)
    "voltage": {"V": 1.0},
    "capacitance": {"F": 1.0, "uF": 1e-06, "mF": 0.001},
    "power": {"W": 1.0, "kW": 1000.0},
}
"""SI factors of the units written most often, per kind, so that those never need pint:
each equals pint's factor for that unit bit for bit (tests/test_units_fast_path.py)."""

_FAST: dict[tuple[str, str], _Recipe] = {
    (kind, unit): _Recipe(factor)
    for kind, units in _SI_FACTORS.items() for unit, factor in units.items()
}
_CACHE: dict[tuple[str, str, bool], _Recipe] = {}
"""Recipes found with pint, by (kind, unit in pint's syntax, GD^2): pint once per unit."""
_BY_TEXT: dict[tuple[str, str], _Recipe] = {}
"""Recipes by (kind, unit as written): a column of one unit costs one dictionary look-up
per value."""
_CACHE_SIZE = 10_000
"""At most this many units are remembered (a file of junk units cannot grow them)."""


def _parse_text(text: str, spec: Kind, field: str | None, *, reference: bool = False) -> float:
    """The SI value of a text like '3000 rpm'.

    A unit is converted once per process (:data:`_FAST`, else pint once, then
    :data:`_CACHE`); ``reference=True`` converts the value with pint directly, the way
    every value was converted before (for the tests that compare the two).
    """
    number, unit = _split(text.replace("%", " percent"))
    if not number:
        raise _expected(spec, text, field)
    finite_form = not number[-1:].isalpha()
    number = number if finite_form else number.replace(".", "")  # .inf, .nan
    if not unit:
        return float(number)
    if not reference:
        known = _BY_TEXT.get((spec.name, unit))
        if known is not None:
            return known.apply(float(number))
    if finite_form and _QUANTITY_FORM.fullmatch(text) is None:  # the schema's pattern
        _check_unit_text(_normalize(unit, spec.name), text, spec, field)  # a limit first
        raise _expected(spec, text, field)
    if spec.name == "fraction":
        if unit not in ("percent", "pct"):
            raise _expected(spec, text, field)
        return float(number) / 100.0
    if spec.name in ("ratio", "money"):
        raise _expected(spec, text, field)
    if spec.name == "angle" and not _ANGLE_UNITS.match(unit):
        raise _expected(spec, text, field)
    written = unit
    unit = _SUPERSCRIPT.sub(lambda m: "^" + m.group(0).translate(_SUPERSCRIPT_DIGITS), unit)
    gd2 = spec.name == "inertia" and _GD2.search(unit) is not None
    if gd2:
        unit = _GD2.sub("", unit)
    pint_unit = _normalize(unit, spec.name)
    if reference:
        _check_unit_text(pint_unit, text, spec, field)
        return _with_pint(float(number), pint_unit, unit, text, spec, field, gd2)
    recipe = None if gd2 else _FAST.get((spec.name, pint_unit))
    if recipe is None:
        recipe = _CACHE.get((spec.name, pint_unit, gd2))
    if recipe is None:
        _check_unit_text(pint_unit, text, spec, field)
        recipe = _pint_recipe(pint_unit, unit, text, spec, field, gd2)
        if len(_CACHE) < _CACHE_SIZE:
            _CACHE[(spec.name, pint_unit, gd2)] = recipe
    if len(_BY_TEXT) < _CACHE_SIZE:
        _BY_TEXT[(spec.name, written)] = recipe
    return recipe.apply(float(number))


def _pint_quantity(number: float, pint_unit: str, unit: str, text: str, spec: Kind,
                   field: str | None, gd2: bool) -> Any:
    """``number`` in ``pint_unit`` as a pint quantity of the dimension of ``spec`` (a mass
    read as its weight where a torque or an inertia is expected)."""
    ureg = registry()
    try:
        quantity = ureg.Quantity(number, pint_unit)
    except Exception as error:  # pint raises several unrelated error types
        raise UserError(f"unknown unit {unit!r} in {text!r} ({spec.name.replace('_', ' ')} "
                        f"expected, e.g. {spec.example!r})", field=field) from error
    if gd2:
        return quantity
    wrong = _expected(spec, text, field)
    if "[temperature]" in quantity.dimensionality:
        if spec.name == "temperature_rise" and pint_unit in _TEMPERATURE_DIFFERENCES:
            return quantity
        raise wrong  # degC, degF, K: no kind of ours holds a temperature (and offset units crash)
    expected = ureg.get_dimensionality(spec.dimensionality) if spec.dimensionality else {}
    if quantity.dimensionality != expected and spec.name in ("torque", "inertia"):
        # a mass where a weight is meant: oz*in, lb*ft (torques), oz*in*s^2 (an inertia)
        weight = quantity * ureg.standard_gravity
        if weight.dimensionality == expected:
            quantity = weight
    if quantity.dimensionality != expected:
        raise wrong
    return quantity


def _pint_recipe(pint_unit: str, unit: str, text: str, spec: Kind, field: str | None,
                 gd2: bool) -> _Recipe:
    """The recipe of one unit: pint's factor (the value of 1.0 in that unit, in SI) and
    the steps after it; UserError for a unit that is unknown or of another kind."""
    quantity = _pint_quantity(1.0, pint_unit, unit, text, spec, field, gd2)
    if gd2:
        return _Recipe(_gd2_factor(quantity, text, field), gd2=True)
    if spec.name in _ANGULAR_MOTION:
        factor, angle = _root_and_angle(quantity)
        if angle not in (0, 1):
            raise _expected(spec, text, field)
        return _Recipe(factor, revolutions=angle == 0)
    if spec.name in _PER_ANGLE:
        factor, angle = _base_and_angle(quantity)
        if angle not in (0, -1):
            raise _expected(spec, text, field)
        return _Recipe(factor, per_revolution=angle == 0)
    return _Recipe(float(quantity.to_base_units().magnitude))


def _with_pint(number: float, pint_unit: str, unit: str, text: str, spec: Kind,
               field: str | None, gd2: bool) -> float:
    """``number`` converted by pint itself (the reference of :class:`_Recipe`)."""
    quantity = _pint_quantity(number, pint_unit, unit, text, spec, field, gd2)
    if gd2:
        return _gd2_factor(quantity, text, field) / 4.0
    if spec.name in _ANGULAR_MOTION:
        magnitude, angle = _root_and_angle(quantity)
        if angle == 1:
            return magnitude
        if angle == 0:
            return magnitude * 2.0 * math.pi
        raise _expected(spec, text, field)
    if spec.name in _PER_ANGLE:
        magnitude, angle = _base_and_angle(quantity)
        if angle == -1:
            return magnitude
        if angle == 0:
            return magnitude / (2.0 * math.pi)
        raise _expected(spec, text, field)
    return float(quantity.to_base_units().magnitude)


def _root_and_angle(quantity: Any) -> tuple[float, float]:
    """The magnitude in root units and the power of the radian in them: 1 for an angular
    quantity, 0 when the unit has no angle (then it counts revolutions)."""
    root = quantity.to_root_units()
    return float(root.magnitude), dict(root.unit_items()).get("radian", 0)


def _base_and_angle(quantity: Any) -> tuple[float, float]:
    """The magnitude in SI base units (kg, not the root units' g) and the power of the
    radian in them: -1 for a quantity per radian, 0 when its speed counts revolutions."""
    base = quantity.to_base_units()
    return float(base.magnitude), dict(base.unit_items()).get("radian", 0)


def _gd2_factor(quantity: Any, text: str, field: str | None) -> float:
    """GD^2 in kgf*m^2 (G in kgf, numerically the mass in kg) or in kg*m^2; J = GD^2/4."""
    ureg = registry()
    if quantity.dimensionality == ureg.get_dimensionality("[mass]*[length]**3/[time]**2"):
        return float(quantity.to("kgf*m**2").magnitude)
    if quantity.dimensionality == ureg.get_dimensionality("[mass]*[length]**2"):
        return float(quantity.to("kg*m**2").magnitude)
    raise UserError(f"expected a GD^2 like '0.04 kgf*m^2 GD^2', got {text!r}", field=field)


_ASCII_SPACE = " \t\n\r\f\v"
_NUMBER_CHARS = "0123456789.eE+-"


def column_to_si(values: Sequence[Any], kind: str) -> list[float | None]:
    """The SI floats of a column of values of one kind (a catalog's inertias, say).

    Each distinct unit of the column is converted once (see :func:`to_si`), each value is
    then its number times the unit's factor, bit for bit as :func:`to_si` gives it. None
    where :func:`to_si` refuses the value (it is left to word what is wrong).
    """
    spec = KINDS[kind]
    match = _NUMBER_AND_UNIT.match
    recipes = _BY_TEXT
    factors: dict[str, float] = {}
    result: list[float | None] = []
    append = result.append
    for value in values:
        kind_of = type(value)
        if kind_of is float or kind_of is int:
            try:
                number = float(value)
            except OverflowError:
                number = math.inf
            append(number if math.isfinite(number) else None)
            continue
        if kind_of is not str or len(value) > MAX_QUANTITY_CHARS:
            append(None)
            continue
        if "%" in value:
            try:
                append(to_si(value, kind))
            except UserError:
                append(None)
            continue
        number_text, _, unit = value.partition(" ")
        unit = unit.strip(_ASCII_SPACE)
        if not number_text or number_text.strip(_NUMBER_CHARS) or not unit:
            # not the common 'number unit' with digits only: the pattern decides
            parts = match(value)
            if parts is None or parts.group(1)[-1:].isalpha():  # not a number, inf, nan
                append(None)
                continue
            number_text, unit = parts.groups()
        if not unit:
            number = float(number_text)
        else:
            factor = factors.get(unit)  # this column's units: a plain factor, or None
            if factor is None:
                recipe = recipes.get((spec.name, unit))
                if recipe is None:
                    try:
                        number = to_si(value, kind)  # finds the unit, remembers it
                    except UserError:
                        append(None)
                        continue
                    append(number if math.isfinite(number) else None)
                    continue
                if not (recipe.revolutions or recipe.gd2):
                    factors[unit] = recipe.factor
                try:
                    number = recipe.apply(float(number_text))
                except ValueError:  # '1.2.3 rpm'
                    append(None)
                    continue
            else:
                try:
                    number = float(number_text) * factor  # _Recipe.apply of a plain factor
                except ValueError:
                    append(None)
                    continue
        append(number if math.isfinite(number) else None)
    return result


def to_si_with_pint(value: Any, kind: str, *, field: str | None = None) -> float:
    """:func:`to_si` with every text converted by pint itself, value by value (slow; the
    reference the tests compare the fast path with)."""
    if isinstance(value, str) and len(value) <= MAX_QUANTITY_CHARS:
        spec = KINDS[kind]
        result = _parse_text(value, spec, field, reference=True)
        if not math.isfinite(result):
            raise _not_finite(value, field)
        return result
    return to_si(value, kind, field=field)


def is_angle_unit(unit: str) -> bool:
    """Whether a unit text names an angle (``deg``, ``rad``, ``rev``...)."""
    return bool(_ANGLE_UNITS.match(unit.strip()))


def parse_displacement(value: Any, *, field: str | None = None) -> tuple[float, bool]:
    """A displacement h in SI and whether it is linear (a length) rather than an angle."""
    if isinstance(value, str):
        _, unit = _split(value)
        if unit and not _ANGLE_UNITS.match(unit):
            try:
                return to_si(value, "length", field=field), True
            except _LimitError:
                raise
            except UserError as error:
                raise UserError(f"expected an angle like '90 deg' or a length like '200 mm', "
                                f"got {value!r}", field=field) from error
    return to_si(value, "angle", field=field), False
