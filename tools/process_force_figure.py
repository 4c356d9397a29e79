"""Draw docs/figures/process-forces.svg, the figure of docs/process-forces.md.

Top: the sign convention on a press (a positive force opposes a positive move). Bottom:
the motor torque of the press cycle of that page with the right sign (+2000 N) and the
intuitive wrong one (-2000 N), computed here by hand, independently of sizer: a cycloidal
move a(t) = 2 pi h / T^2 sin(2 pi t / T) per segment, the screw's load torque
(m a + F) / K (K = 2 pi / lead) divided by its efficiency where the motor drives it and
multiplied by it where the load drives the motor, plus the rotor's J_m K a.
(tests/test_force_sign_warning.py checks sizer's RMS torque against the same model.)

    python tools/process_force_figure.py [OUT.svg]
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

MASS, ROTOR, LEAD, EFFICIENCY = 30.0, 1e-4, 0.01, 0.9
SEGMENTS = (("approach", 0.08, 0.2, False), ("press", 0.02, 0.3, True),
            ("return", -0.10, 0.25, False))
DWELL = 0.25
"""The press cycle of docs/process-forces.md: h (m), T (s), pressing or not; then a dwell."""


def press_torque(force: float, points: int = 4001) -> tuple[np.ndarray, np.ndarray]:
    """Time (s) and motor torque (N*m) over one cycle."""
    k = 2.0 * math.pi / LEAD
    times, torques, start = [], [], 0.0
    for _, h, duration, pressing in SEGMENTS:
        t = np.linspace(0.0, duration, points)
        a = 2.0 * math.pi * h / duration**2 * np.sin(2.0 * math.pi * t / duration)
        v = h / duration * (1.0 - np.cos(2.0 * math.pi * t / duration))
        load = (MASS * a + (force if pressing else 0.0)) / k
        load = np.where(load * v > 0.0, load / EFFICIENCY, load * EFFICIENCY)
        times.append(start + t)
        torques.append(ROTOR * k * a + load)
        start += duration
    times.append(np.array([start, start + DWELL]))
    torques.append(np.zeros(2))
    return np.concatenate(times), np.concatenate(torques)


def rms(force: float) -> float:
    t, torque = press_torque(force, 200001)
    return math.sqrt(float(np.trapezoid(torque**2, t)) / t[-1])


def draw(out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams["svg.hashsalt"] = "sizer"
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.5, 6.4),
                                      gridspec_kw={"height_ratios": [1.0, 1.6]})
    top.set_xlim(0, 10)
    top.set_ylim(0, 4)
    top.axis("off")
    top.add_patch(plt.Rectangle((1.0, 1.4), 3.0, 1.2, color="#9db4d0"))
    top.text(2.5, 2.0, "ram", ha="center", va="center")
    top.add_patch(plt.Rectangle((5.2, 1.1), 1.2, 1.8, color="#d9c29b"))
    top.text(5.8, 2.0, "part", ha="center", va="center")
    top.annotate("", xy=(4.8, 3.3), xytext=(1.0, 3.3),
                 arrowprops={"arrowstyle": "->", "lw": 2, "color": "black"})
    top.text(2.9, 3.55, "positive move: displacement: +20 mm", ha="center")
    top.annotate("", xy=(4.1, 0.8), xytext=(5.9, 0.8),
                 arrowprops={"arrowstyle": "->", "lw": 2.5, "color": "#c0392b"})
    top.text(6.1, 0.7, "the part pushes back:\nforce: +2000 N (opposes the move)",
             color="#c0392b", va="center")
    top.set_title("A positive force (torque) opposes a positive move: "
                  "write a resisting force with the move's sign", fontsize=10)
    for force, color, label in ((2000.0, "#1f4e79", "force: +2000 N (right)"),
                                (-2000.0, "#c0392b", "force: -2000 N (wrong sign)")):
        t, torque = press_torque(force)
        bottom.plot(t * 1000.0, torque, color=color, lw=1.6 if force > 0 else 1.0,
                    label=f"{label}: RMS {rms(force):.3g} N*m")
    start = SEGMENTS[0][2]
    bottom.axvspan(start * 1000.0, (start + SEGMENTS[1][2]) * 1000.0, color="#eeeeee",
                   zorder=0)
    bottom.text((start + SEGMENTS[1][2] / 2.0) * 1000.0, 0.4, "press", ha="center")
    bottom.axhline(0.0, color="gray", lw=0.8)
    bottom.set_xlabel("time [ms]")
    bottom.set_ylabel("motor torque [N*m]")
    bottom.legend(loc="upper right", fontsize=9)
    bottom.set_title(f"30 kg ram, 10 mm-lead screw of efficiency {EFFICIENCY:g}: the wrong "
                     f"sign back-drives the screw", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, format="svg", metadata={"Date": None})
    plt.close(fig)


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else (
        Path(__file__).resolve().parent.parent / "docs" / "figures" / "process-forces.svg")
    draw(target)
    print(f"{target}: RMS {rms(2000.0):.4g} N*m (+2000 N), {rms(-2000.0):.4g} N*m (-2000 N)")
