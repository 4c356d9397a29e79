"""The limits on what sizer reads from users, written once (documented in docs/input-files.md).

Every user file is read through :func:`sizer.io.files.read_user_text`; YAML is composed under
the node, depth, alias and scalar limits; law specs and unit texts are bounded before they
are parsed. Exceeding one gives a UserError naming the file (or field) and the limit.
"""

from __future__ import annotations

MIB = 1024 * 1024

MAX_DESIGN_BYTES = 1 * MIB
"""A design file (sizer size/check/plot/report)."""
MAX_CATALOG_BYTES = 32 * MIB
"""A motor catalog, a gearbox catalog or a CSV to import (10,000 motors with curves: 13 MB)."""
MAX_CAM_TABLE_BYTES = 8 * MIB
"""A cam table's CSV file (MAX_CAM_TABLE_ROWS rows of the five columns ``sizer law`` writes:
about 2 MB), refused by its size before it is read."""

MAX_DESIGN_NODES = 200_000
"""Nodes (keys, values, items) of a design file once aliases are expanded."""
MAX_CATALOG_NODES = 5_000_000
"""Nodes of a catalog file once aliases are expanded (10,000 motors with curves: 1.4 M)."""
MAX_YAML_DEPTH = 100
"""Nesting of mappings and lists in a YAML file."""
MAX_SCALAR_CHARS = 65_536
"""Characters of one YAML value or key (a note, a source citation...)."""
MAX_INT_DIGITS = 400
"""Digits of an integer in a file: 400 digits is already beyond the float range."""

MAX_LAW_SPEC_CHARS = 500
"""Characters of a law spec like ``double_s(alpha=1/3, beta=1/4)``."""
MAX_DATA_LAW_CHARS = 200_000
"""Characters of a law defined by data (a spline's points and conditions) in its canonical
one-line text; longer tables belong in a cam_table file."""
MAX_NUMBER_CHARS = 100
"""Characters of one number in a law spec or a quantity (``1e-3``, ``1/3``)."""
MAX_EXPONENT = 400
"""Largest decimal exponent written in a number (``1e400`` is beyond the float range anyway)."""
MAX_QUANTITY_CHARS = 100
"""Characters of a quantity with its unit, like ``0.04 kgf*m^2 GD^2``."""
MAX_UNIT_POWER = 12
"""Largest power in a unit text (``m^3``, ``s^-2``; ``m^99999999`` is refused)."""

MAX_CYCLE_SEGMENTS = 400
"""Segments of a design's ``cycle:``. Memory grows with the segments of a chunk of
candidates (sizer.sizing.move.candidates_per_chunk: fewer candidates a chunk as the moves
grow, down to one): 400 segments and the 64 bundled motors peak at 1.3 GB, within 2 GiB
(benchmarks/README.md)."""
MAX_MACHINE_AXES = 8
"""Axes of a machine file (``axes:``); each axis is sized several times to find the master
speed, so a machine's time grows with its axes."""

MAX_SPECTRUM_LINES = 100_000
"""Rows of ``sizer spectrum``: the frequencies of --points, or the harmonics of a repeated
move up to --max-ft (--max-ft x T_c/T of them); each row costs a fixed time (the end series
of sizer.vibration.far_field for high f T), so 100,000 take about a second a law."""
MAX_SPECTRUM_CURVE_POINTS = 20_001
"""Points of the spectrum's envelope drawn with the harmonics (a curve, not a table)."""
MAX_VIBRATION_POINTS = 10_000
"""Durations of one ``sizer vibration`` sweep (--points); each costs a fixed time however
long the move or fast the mode (f_n T of 1e8 costs what 1 does): 10,000 take about 5 s a
law (residual and tracking error)."""

MAX_VIA_POINTS = 250
"""Points, positions, times, control points, weights or knots of one law defined by data
(splines, B-splines, NURBS, via_trapezoid): their systems are solved dense (the cost grows
as the cube: 1,000 points took 20 s to 90 s); longer tables belong in a cam_table file."""
MAX_AUTO_TIMES_POINTS = 32
"""Positions of a spline with ``times: auto`` (an optimization over every interior time,
with exact derivatives since issue 34: 0.02-0.4 s for 24-32 random positions on one
thread; it was about 10 s for 24)."""
MAX_CAM_TABLE_ROWS = 20_000
"""Rows of a cam table (each row is a piece of the fitted spline: every command's work and
memory grow with them)."""
MAX_DATA_LAW_EXCURSION = 1.0e6
"""Largest |q_N| of a law defined by data that moves (its excursion over its
displacement): data that swing a million times further than they move make no law."""
