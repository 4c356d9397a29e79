"""Power and energy at the motor shaft and the DC bus, braking and several axes on one
bus (issue 16). Pure numpy on sampled torque and speed, vectorized over candidates."""

from sizer.energy.braking import Braking, braking, capacitor_energy
from sizer.energy.bus import BusAxis, shared_bus
from sizer.energy.power import (
    WINDING_FACTORS,
    AxisPower,
    PowerFigures,
    axis_power,
    copper_loss,
    integral,
    interval_parts,
)

__all__ = ["WINDING_FACTORS", "AxisPower", "Braking", "BusAxis", "PowerFigures",
           "axis_power", "braking", "capacitor_energy", "copper_loss", "integral",
           "interval_parts", "shared_bus"]
