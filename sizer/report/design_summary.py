"""What a design asked for, as plain JSON data in SI with the units stated.

Reports of ``sizer size`` and ``sizer check`` start with it, so a result file says which
task, load, transmission and limits its numbers belong to.
"""

from __future__ import annotations

from typing import Any

from sizer.model.domain import Design
from sizer.report.numbers import finite_or_none


def _units(linear: bool) -> dict[str, str]:
    """SI units of the axis-dependent quantities (load side)."""
    if linear:
        return {"displacement": "m", "inertia": "kg", "damping": "N*s/m", "force": "N",
                "acceleration": "m/s^2", "jerk": "m/s^3"}
    return {"displacement": "rad", "inertia": "kg*m^2", "damping": "N*m*s/rad",
            "force": "N*m", "acceleration": "rad/s^2", "jerk": "rad/s^3"}


def _choice(design: Design) -> dict[str, Any] | None:
    """The free ratio of a stage: the options tried (each result gives its own choice)."""
    choice = design.ratio_choice
    if choice is None:
        return None
    return {"stage": choice.stage,
            "ratios": [float(r) for r in choice.ratios] or None,
            "bounds": [float(b) for b in choice.bounds] if choice.bounds else None,
            "gearboxes": [o.gearbox for o in choice.gearboxes] or None}


def design_summary(design: Design, notes: tuple[str, ...] = ()) -> dict[str, Any]:
    """The design as a JSON object (fixed key order), each section with its ``units``."""
    task, load, limits = design.task, design.load, design.limits
    units = _units(task.linear)
    transmission = design.transmission
    choice = design.ratio_choice
    chosen = choice.stage if choice is not None else None
    catalog = choice is not None and bool(choice.gearboxes)
    summary = {
        "name": design.name,
        "mode": "minimize" if task.minimize else "duration",
        "task": {
            "axis": "linear" if task.linear else "rotary",
            "displacement": float(task.displacement),
            "duration": finite_or_none(task.duration),
            "dwell": float(task.dwell),
            "return": bool(task.return_move),
            "units": {"displacement": units["displacement"], "duration": "s", "dwell": "s"},
        },
        "load": {
            "mass" if task.linear else "inertia": float(load.inertia),
            "damping": float(load.damping),
            "friction": float(load.friction),
            "force" if task.linear else "torque": float(load.torque),
            "units": {"mass" if task.linear else "inertia": units["inertia"],
                      "damping": units["damping"], "friction": units["force"],
                      "force" if task.linear else "torque": units["force"]},
        },
        "transmission": {
            "ratio": None if chosen is not None else float(transmission.ratio),
            "efficiency": None if catalog else float(transmission.efficiency),
            "inertia": None if catalog else float(transmission.inertia),
            "stages": [
                {"type": stage.kind, "name": None if i == chosen and catalog else stage.name,
                 "ratio": None if i == chosen else float(stage.ratio),
                 "efficiency": None if i == chosen and catalog else float(stage.efficiency),
                 "inertia": None if i == chosen and catalog else float(stage.inertia),
                 "chosen_per_pair": i == chosen}
                for i, stage in enumerate(transmission.stages)
            ],
            "choice": _choice(design),
            "units": {"ratio": "input speed / output speed (rad/rad; rad/m into a linear "
                               "axis); null where chosen per pair (see choice and each "
                               "result's ratio and gearbox)", "efficiency": "1",
                      "inertia": "kg*m^2 (total: at the motor shaft; a stage: at its input)"},
        },
        "limits": {
            "torque_margin": float(limits.torque_margin),
            "speed_margin": float(limits.speed_margin),
            "inertia_ratio": finite_or_none(limits.inertia_ratio),
            "max_acceleration": finite_or_none(limits.max_acceleration),
            "max_jerk": finite_or_none(limits.max_jerk),
            "thermal_speed": limits.thermal_speed,
            "envelope": limits.envelope,
            "units": {"torque_margin": "1", "speed_margin": "1", "inertia_ratio": "1",
                      "max_acceleration": units["acceleration"], "max_jerk": units["jerk"]},
        },
        "laws": [law.text for law in design.laws],
        "motors": len(design.motors),
        "check": ({"motor": design.chosen_motor,
                   "law": design.chosen_law.text if design.chosen_law else None}
                  if design.chosen_motor or design.chosen_law else None),
        "notes": list(notes),
    }
    if design.cycle is None:  # the task shorthand: the summary as it always was
        return summary
    from sizer.report.cycle_summary import cycle_json

    items = list(summary.items())
    at = [key for key, _ in items].index("task") + 1
    return dict([*items[:at], ("cycle", cycle_json(design.cycle)), *items[at:]])
