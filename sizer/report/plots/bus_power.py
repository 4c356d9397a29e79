"""The summed bus power of a machine's axes over one machine cycle (issue 16).

One panel: the DC bus power P(t) of the axes' chosen pairs added with their phases
(sizer.sizing.machine_bus), drawn as its piecewise-linear samples, the part the motors
return (P < 0) shaded; the capacitors' absorbable energy per stop and the braking
resistor's continuous power in the legend. Only units are converted here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from sizer.report.numbers import short
from sizer.report.plots.figure_files import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sizer.sizing.machine import BusResult

DEFAULT_SIZE = (10.0, 4.5)
GID_POWER = "bus-power"
GID_RETURNED = "bus-returned"


def bus_figure(bus: BusResult, *, size: tuple[float, float] | None = None,
               dpi: float = 100.0, title: str = "") -> Figure:
    """The bus power of ``bus`` over the machine cycle (time in ms, power in W)."""
    figure = new_figure(size or DEFAULT_SIZE, dpi)
    ax = figure.subplots()
    t, p = bus.time * 1000.0, bus.power
    ax.plot(t, p, color="#1f77b4", lw=1.5, gid=GID_POWER,
            label=f"bus power of {', '.join(bus.axes)} (peak {short(bus.peak_power)} W)")
    ax.fill_between(t, p, 0.0, where=p < 0.0, color="#ff7f0e", alpha=0.35, lw=0.0,
                    gid=GID_RETURNED, interpolate=True,
                    label=f"returned: {short(bus.regenerated_energy)} J per cycle, resistor "
                          f"{short(bus.resistor_power)} W")
    ax.axhline(0.0, color="0.4", lw=0.8)
    ax.set_xlim(0.0, float(np.max(t)))
    ax.set_xlabel("machine time [ms]")
    ax.set_ylabel("DC bus power [W]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    heading = f"{title}: " if title else ""
    figure.suptitle(f"{heading}the axes' power on the shared DC bus over one machine cycle",
                    fontsize="medium")
    return figure
