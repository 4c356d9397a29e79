"""sizer: actuator sizing and motion-law selection for automatic machines.

The method is chapter 6 of Biagiotti & Melchiorri, *Trajectory Planning for Automatic
Machines and Robots*: shape coefficients of normalized motion laws, torque at the motor
shaft, peak points against the intermittent region and the RMS torque against the
continuous region.
"""

__version__ = "0.1.0"

__all__ = ["__version__", "check", "load", "load_machine", "plan", "size", "size_machine"]


def __getattr__(name: str):
    """``sizer.size``, ``sizer.check``, ``sizer.plan``, ``sizer.load``,
    ``sizer.size_machine``, ``sizer.load_machine`` (sizer.api), imported on first use so
    that ``import sizer`` stays light."""
    if name in ("size", "check", "plan", "load", "size_machine", "load_machine"):
        from sizer import api

        return getattr(api, name)
    raise AttributeError(f"module 'sizer' has no attribute {name!r}")
