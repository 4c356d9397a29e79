"""Where a law defined by data may go: moving ends, periodic cams, master speeds.

A spline or cam table may start and end moving (book sec. 4.4.2: a periodic motion,
the electronic cam of a machine that never stops). Such a law is one period of a repeated
motion: in the task shorthand it needs no dwell and no return and must be periodic
(speed and acceleration equal at both ends); in a cycle of segments it cannot be one
move among others (its end speeds are fixed by its shape, not by the move). A cam on a
master axis (``units: {time: deg}``) lasts its master angle at the task's
``master_speed``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

from sizer.errors import UserError
from sizer.io.plausibility import warning_text
from sizer.io.yaml_source import YamlSource
from sizer.laws.choice import LawChoice, law_choice


def _data_law(spec: str) -> Any:
    from sizer.laws.data_law import DataLaw

    choice = law_choice(spec)  # an open shaped law is shaped at each duration: rest to rest
    return choice.law if choice.is_fixed and issubclass(choice.family, DataLaw) else None


@dataclass(frozen=True)
class LocatedLaw:
    """A law of the design, where it is written, and its law defined by data (None for a
    family's law or an open shaped one), built once for every rule of this module."""

    spec: str
    at: tuple[Any, ...]
    data: Any = None

    @property
    def choice(self) -> LawChoice:
        """The law choice of ``spec`` (read once per text: sizer.laws.choice)."""
        return law_choice(self.spec)


def locate_laws(laws: Iterable[tuple[str, tuple[Any, ...]]]) -> list[LocatedLaw]:
    """Each ``(spec, where)`` with its law defined by data."""
    return [LocatedLaw(spec, at, _data_law(spec)) for spec, at in laws]


def _moving(law: Any) -> str | None:
    """Why a law defined by data is not rest-to-rest ("starts moving (v_N(0) = 1.2)")."""
    if law is None or law.rest_to_rest:
        return None
    start, end = law.end_speeds
    parts = [f"starts moving (v_N(0) = {start:.6g})" if start else "",
             f"ends moving (v_N(1) = {end:.6g})" if end else ""]
    return " and ".join(p for p in parts if p)


def moving_ends(spec: str) -> str | None:
    """Why law ``spec`` is not rest-to-rest ("starts moving (v_N(0) = 1.2)"), or None."""
    return _moving(_data_law(spec))


def check_task_laws(laws: Sequence[LocatedLaw], task: Any, source: YamlSource) -> None:
    """A law whose ends move, in the task shorthand: one period, no dwell, no return."""
    for law in laws:
        reason = _moving(law.data)
        if reason is None:
            continue
        name = law.data.law_id
        if task.dwell != 0.0 or task.return_move:
            raise source.error(f"the {name} {reason}: it is one period of a repeated motion "
                               f"(an electronic cam), so the task needs dwell 0 and no "
                               f"return; or make the law start and end at rest", law.at)
        if not law.data.periodic:
            raise source.error(f"the {name} {reason} and its ends do not join (speed "
                               f"{law.data.end_speeds[0]:.6g} and "
                               f"{law.data.end_speeds[1]:.6g}, normalized): a repeated "
                               f"motion must be periodic, e.g. a cubic_spline with "
                               f"periodic: true", law.at)


def check_cycle_laws(laws: Sequence[LocatedLaw], source: YamlSource) -> None:
    """A law whose ends move cannot be one move of a cycle of segments."""
    for law in laws:
        reason = _moving(law.data)
        if reason is not None:
            raise source.error(f"the {law.data.law_id} {reason}: in a cycle of "
                               f"segments a move's law must start and end at rest (its end "
                               f"speeds are the move's); size a periodic cam as a task with "
                               f"dwell 0", law.at)


def master_duration(laws: Sequence[LocatedLaw], master_speed: float, source: YamlSource,
                    at: tuple[Any, ...]) -> float:
    """The duration of a move whose laws are cams on a master axis, at ``master_speed``:
    their master angle over the speed (every law must have the same master angle)."""
    spans: list[tuple[float, tuple[Any, ...]]] = []
    for law in laws:
        scale = getattr(law.data, "scale", None)
        if scale is None or not scale.master:
            raise source.error("master_speed needs laws on a master axis (a law defined by "
                               "data with units: {time: deg, ...}, or a cam table whose first "
                               f"column is an angle); law {_short(law.spec)} is not one",
                               law.at)
        spans.append((scale.span, law.at))
    first = spans[0][0]
    for span, where in spans[1:]:
        if abs(span - first) > 1e-9 * first:
            raise source.error(f"the laws span different master angles ({first:.6g} rad and "
                               f"{span:.6g} rad): with a master_speed every law must span "
                               f"the same angle", where)
    if master_speed <= 0.0:
        raise UserError("must be positive", field="task.master_speed")
    return first / master_speed


def _short(spec: str) -> str:
    return repr(spec if len(spec) <= 40 else spec[:37] + "...")


def _scaled(laws: Sequence[LocatedLaw]) -> list[tuple[Any, tuple[Any, ...]]]:
    """(scale, where) of every law defined by data with units of its own."""
    return [(law.data.scale, law.at) for law in laws
            if law.data is not None and law.data.scale is not None]


def law_displacement(laws: Sequence[LocatedLaw], source: YamlSource,
                     at: tuple[Any, ...]) -> tuple[float, bool]:
    """The task's displacement when it is not written: that of its laws defined by data
    with units (all of them, and all the same), in SI, and whether it is a length."""
    scaled = _scaled(laws)
    if not scaled or len(scaled) != len(laws):
        raise source.error("is required: an angle like '90 deg' or a length like '200 mm' "
                           "(it may be left out only when every law is defined by data "
                           "with units: {time: ..., position: ...})", at)
    first = scaled[0][0]
    for scale, where in scaled[1:]:
        if scale.linear != first.linear or \
                abs(scale.displacement - first.displacement) > 1e-9 * abs(first.displacement):
            raise source.error(f"the laws move by different displacements "
                               f"({first.displacement:.6g} and {scale.displacement:.6g}, "
                               f"SI): write the task's displacement", where)
    return first.displacement, first.linear


def scale_warnings(laws: Sequence[LocatedLaw], h: float, linear: bool,
                   source: YamlSource) -> list[str]:
    """A warning for each law with units whose own displacement is not the task's: the
    task's displacement scales the law's shape."""
    out = []
    for scale, where in _scaled(laws):
        if scale.linear != linear:
            raise source.error(f"this law's positions are {'lengths' if scale.linear else 'angles'}"
                               f" but the task's displacement is "
                               f"{'a length' if linear else 'an angle'}", where)
        if abs(scale.displacement - h) > 1e-6 * abs(h):
            unit = "m" if linear else "rad"
            out.append(warning_text(source, where,
                                    f"its data move {scale.displacement:.6g} {unit}, the "
                                    f"task's displacement is {h:.6g} {unit}: the task "
                                    f"scales the law's shape"))
    return out


def oscillation_warnings(laws: Sequence[LocatedLaw], source: YamlSource) -> list[str]:
    """A warning at each data law whose report measures an oscillating curve (the
    polynomials through points of book sec. 4.1-4.2: Runge's phenomenon, Fig. 4.5)."""
    out = []
    for law in laws:
        report = getattr(law.data, "report", None)
        if not report or not {"overshoot", "lebesgue_constant"} & set(report):  # no measure
            continue
        from sizer.laws.multipoint.interpolating_polynomial import oscillation_warning

        message = oscillation_warning(report)
        if message is not None:
            out.append(warning_text(source, law.at, message))
    return out
