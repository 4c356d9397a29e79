"""The design in SI: plain, validated data the core computes on (built by sizer.io)."""

from sizer.model.domain import (
    Design,
    GearboxOption,
    Limits,
    Load,
    Motor,
    RatioChoice,
    Stage,
    Task,
    ThermalSpeedRule,
    Transmission,
)

__all__ = [
    "Design",
    "GearboxOption",
    "Limits",
    "Load",
    "Motor",
    "RatioChoice",
    "Stage",
    "Task",
    "ThermalSpeedRule",
    "Transmission",
]
