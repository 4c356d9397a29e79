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
