"""Numerical building blocks shared by the laws and the sizing engine (pure numpy).

- :mod:`sizer.numerics.roots`: the project's one bracketing root finder (Chandrupatla's
  method).
- :mod:`sizer.numerics.golden`: the golden-section step of the bracketed extremum
  searches and Brent's method for a maximum (used where no derivative of the objective
  is available).
- :mod:`sizer.numerics.hermite`: the root of a cubic Hermite model on an interval (the
  start of the laws' stationary points and of the power-flow reversals).
- :mod:`sizer.numerics.arrays`: array helpers of the start-up path (``sorted_unique``).
"""
