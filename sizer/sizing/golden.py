"""The engine's golden-section step: a re-export of :mod:`sizer.numerics.golden`."""

from sizer.numerics.golden import INV_PHI, Bracket, golden_step, interior_points

__all__ = ["INV_PHI", "Bracket", "golden_step", "interior_points"]
