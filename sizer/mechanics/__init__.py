"""Transmissions and loads seen from the motor shaft (sec. 6.1.1)."""

from sizer.mechanics.drive import Drive

__all__ = ["Drive"]
