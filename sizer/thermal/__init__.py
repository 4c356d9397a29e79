"""Winding heat (issue 16): first-order and two-node models driven by the losses, exact
for piecewise-linear losses, over one-off sequences or the periodic steady state, and the
verdict saying whether the RMS check or the thermal model applies."""

from sizer.thermal.check import WindingCheck, winding_check
from sizer.thermal.network import (
    Response,
    ThermalModel,
    first_order,
    thermal_resistance,
    two_node,
)
from sizer.thermal.verdict import RMS_SHARE, ThermalVerdict, applied_check, thermal_verdict

__all__ = ["RMS_SHARE", "Response", "ThermalModel", "ThermalVerdict", "WindingCheck",
           "applied_check", "first_order", "thermal_resistance", "thermal_verdict", "two_node",
           "winding_check"]
