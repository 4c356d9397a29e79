"""Per-catalog columns read once (sizer.sizing.catalog_facts): the values a plain read of
each motor gives, kept per catalog tuple and rebuilt for another tuple."""

from __future__ import annotations

import numpy as np
import pytest

from sizer.envelope import continuous_region
from sizer.model import Motor
from sizer.sizing.candidates import KEPT, catalog_facts


def catalog(offset: float = 0.0) -> tuple[Motor, ...]:
    return (Motor("a", 1e-4, 1.0 + offset, 3.0, 300.0, thermal_time_constant=900.0,
                  max_winding_temperature_rise=100.0),
            Motor("b", 2e-4, 2.0 + offset, 6.0, 250.0),
            Motor("c", 3e-4, 3.0 + offset, 9.0, 200.0, continuous_curve=((0.0, 3.3),
                                                                          (200.0, 2.5))))


def test_columns_are_each_motors_value_or_nan():
    facts = catalog_facts(catalog())
    np.testing.assert_array_equal(facts.column("thermal_time_constant"),
                                  [900.0, np.nan, np.nan])
    np.testing.assert_array_equal(facts.column("continuous_torque"), [1.0, 2.0, 3.0])
    assert facts.heated
    assert not catalog_facts(catalog()[1:]).heated
    with pytest.raises(ValueError):
        facts.column("continuous_torque")[0] = 5.0  # shared: read only


def test_regions_are_the_motors_own():
    motors = catalog()
    table = catalog_facts(motors).continuous("linear")
    speed = np.array([[0.0, 100.0, 150.0]] * 3)
    for row, motor in enumerate(motors):
        region = continuous_region(motor, "linear")
        alone = catalog_facts((motor,)).continuous("linear")
        np.testing.assert_array_equal(table.limit(speed)[row], alone.limit(speed[:1])[0])
        assert len(region) >= 2


def test_kept_per_tuple_and_rebuilt_for_another():
    motors = catalog()
    assert catalog_facts(motors) is catalog_facts(motors)
    other = catalog(offset=0.5)
    np.testing.assert_array_equal(catalog_facts(other).column("continuous_torque"),
                                  [1.5, 2.5, 3.5])
    for k in range(KEPT + 2):  # more catalogs than are kept: each still reads its own
        mine = catalog(offset=float(k))
        assert catalog_facts(mine).column("continuous_torque")[0] == 1.0 + k
    np.testing.assert_array_equal(catalog_facts(motors).column("continuous_torque"),
                                  [1.0, 2.0, 3.0])
