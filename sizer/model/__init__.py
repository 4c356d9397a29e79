"""The design in SI: plain, validated data the core computes on (built by sizer.io)."""

from sizer.model.domain import (
    Design,
    Limits,
    Load,
    Motor,
    Stage,
    Task,
    ThermalSpeedRule,
    Transmission,
)

__all__ = [
    "Design",
    "Limits",
    "Load",
    "Motor",
    "Stage",
    "Task",
    "ThermalSpeedRule",
    "Transmission",
]
