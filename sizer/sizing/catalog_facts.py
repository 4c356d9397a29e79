"""What the motors of a catalog give, read once per catalog rather than on every call.

The engine's candidate arrays (sizer.sizing.motors.MotorArrays) share one tuple of the
distinct motors, their ``catalog``, across every subset, chunk and transmission option.
The energy and heat checks read per-motor ratings from it (thermal time constant, allowed
rise, k_t, R) and the motors' own continuous regions: a Python pass over the catalog,
once per evaluation, where a 10,000-motor catalog is evaluated hundreds of times. Here
each such column is built on first use and kept with the catalog (keyed by the tuple's
identity, the tuple held so that the identity stays its own; the last few catalogs).
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np

from sizer.envelope import RegionTable, continuous_region
from sizer.model.domain import EnvelopeRule, Motor

KEPT = 8
"""Catalogs whose facts are kept (a design has one; tests and loops make more)."""


class CatalogFacts:
    """Columns of one catalog's motors, each built on first use."""

    def __init__(self, catalog: tuple[Motor, ...]) -> None:
        self.catalog = catalog
        self._columns: dict[str, np.ndarray] = {}
        self._regions: dict[str, RegionTable] = {}
        self.heated = any(m.thermal_time_constant is not None
                          and m.max_winding_temperature_rise is not None for m in catalog)
        """Some motor gives its thermal time constant and allowed rise (a heat check)."""

    def column(self, name: str) -> np.ndarray:
        """The motors' rating ``name`` as floats, NaN where a motor leaves it out (read
        only: shared by every caller)."""
        found = self._columns.get(name)
        if found is None:
            found = np.array([np.nan if getattr(m, name) is None else float(getattr(m, name))
                              for m in self.catalog], dtype=float)
            found.setflags(write=False)
            self._columns[name] = found
        return found

    def continuous(self, envelope: EnvelopeRule) -> RegionTable:
        """The motors' own continuous regions (not clipped by a drive), by ``envelope``."""
        found = self._regions.get(envelope)
        if found is None:
            found = self._regions[envelope] = RegionTable(
                [continuous_region(m, envelope) for m in self.catalog])
        return found


_KEPT: OrderedDict[int, CatalogFacts] = OrderedDict()


def catalog_facts(catalog: tuple[Motor, ...]) -> CatalogFacts:
    """The facts of ``catalog`` (a tuple: a list could change; it gets fresh facts)."""
    if not isinstance(catalog, tuple):
        return CatalogFacts(tuple(catalog))
    key = id(catalog)
    found = _KEPT.get(key)
    if found is None or found.catalog is not catalog:
        found = _KEPT[key] = CatalogFacts(catalog)
        while len(_KEPT) > KEPT:
            _KEPT.popitem(last=False)
    else:
        _KEPT.move_to_end(key)
    return found
