"""How a region without a curve is completed from the ratings, up to ``max_speed``.

Most catalogs print corner figures only: the rated (continuous) torque tau_c from standstill
up to the rated speed v_n, the peak torque tau_p and the maximum speed v_max. Their
speed-torque diagrams (Yaskawa's continuous and intermittent duty zones, Mitsubishi's
continuous and short-duration running ranges) reach v_max, but the torque there is drawn,
not printed, and depends on the supply voltage. A rule, chosen by the design's
``limits.envelope`` (or ``--envelope``), says what a region without a curve is taken to be:

- ``book``: the book's rectangles (sec. 6.1.1): tau_c and tau_p up to v_n; v_max unused.
- ``linear``: the rectangles up to v_n, then straight lines to v_max: the
  intermittent torque from tau_p down to tau_c, the continuous torque from tau_c down to
  tau_c v_n / v_max (the rated power's torque at v_max).
- ``linear_intermittent``: only the intermittent region is extended as in ``linear``; the
  continuous region stays the book's up to v_n (Yaskawa's derating figures hold for an
  average speed up to the rated speed only).
- ``electrical`` (the default): a motor whose datasheet gives its winding (k_t or k_e,
  the resistance, the bus or supply voltage of its ratings; the inductance and poles where
  printed) has the intermittent region its supply allows (sizer.envelope.electrical: the
  peak torque up to the voltage limit's corner, then k_t times the voltage-limited
  current) and the ``linear`` continuous region clipped by it; any other motor is
  completed as by ``linear``.

Why ``electrical`` is the default: where a datasheet prints the winding, the region its
supply allows follows from physics and from printed figures alone; it is what the maker's
diagram draws for that supply (agreement with printed curves: docs/envelopes.md). Where it
does not, ``linear``: an engineer reading a servo catalog expects intermittent operation up
to the maximum speed, as every datasheet diagram shows, and the book's rectangles refuse
any move above v_n. The straight lines use printed figures only and assume little: the
peak torque is not assumed beyond v_n, and at v_max the motor keeps only its rated torque
briefly and its rated power continuously. It is an assumption, not the datasheet's curve;
it is stated in every output, and a catalog's own curves always win. A motor without
``max_speed`` (or with v_max = v_n) keeps the rectangles under ``linear``.
"""

from __future__ import annotations

from sizer.envelope.electrical import Winding, clipped, electrical_intermittent
from sizer.model.domain import DEFAULT_ENVELOPE, Curve, EnvelopeRule, Motor

ENVELOPE_RULES: dict[str, str] = {
    "book": "the book's rectangular regions up to the rated speed (sec. 6.1.1)",
    "linear": "the book's rectangular regions up to the rated speed, then lines to "
              "max_speed (tau_p down to tau_c, tau_c down to the rated power); assumed, "
              "not datasheet curves",
    "linear_intermittent": "the book's rectangular regions up to the rated speed, the "
                           "intermittent one then a line to max_speed (tau_p down to "
                           "tau_c); assumed, not datasheet curves",
    "electrical": "the intermittent region their supply allows where they give k_t, R "
                  "and its voltage (the linear continuous region under it), else the "
                  "linear rule's regions; computed from datasheet figures, not their curves",
}
"""Rule -> what a motor without curves is given, as stated in the outputs."""

__all__ = ["DEFAULT_ENVELOPE", "ENVELOPE_RULES", "completed_continuous",
           "completed_intermittent", "envelope_note", "from_zero"]


def _extends(motor: Motor, rule: EnvelopeRule) -> bool:
    if rule not in ENVELOPE_RULES:
        raise ValueError(f"unknown envelope rule {rule!r}; rules: {', '.join(ENVELOPE_RULES)}")
    return (rule != "book" and motor.max_speed is not None
            and motor.max_speed > motor.rated_speed)


def completed_continuous(motor: Motor, rule: EnvelopeRule) -> Curve:
    """The continuous region of a motor without a continuous curve, under ``rule``; but
    for the book's rectangles (the motor's corner figures as printed, which the catalog
    rules check), never above the intermittent region where that is the motor's printed
    curve or, under ``electrical``, its winding's (a motor cannot keep up what it cannot
    reach)."""
    tau_c, v_n = motor.continuous_torque, motor.rated_speed
    corner = ((0.0, tau_c), (v_n, tau_c))
    if rule == "linear_intermittent" or not _extends(motor, rule):
        region: Curve = corner
    else:
        v_max = float(motor.max_speed)  # type: ignore[arg-type]
        region = (*corner, (v_max, tau_c * v_n / v_max))
    if rule == "book":
        return region
    if motor.intermittent_curve:
        return clipped(region, from_zero(motor.intermittent_curve))
    limit = _electrical(motor) if rule == "electrical" else None
    return region if limit is None else clipped(region, limit)


def completed_intermittent(motor: Motor, rule: EnvelopeRule) -> Curve:
    """The intermittent region of a motor without an intermittent curve, under ``rule``."""
    if rule == "electrical":
        limit = _electrical(motor)
        return completed_intermittent(motor, "linear") if limit is None else limit
    tau_p, v_n = motor.peak_torque, motor.rated_speed
    corner = ((0.0, tau_p), (v_n, tau_p))
    if not _extends(motor, rule):
        return corner
    return (*corner, (float(motor.max_speed), motor.continuous_torque))  # type: ignore[arg-type]


def _electrical(motor: Motor) -> Curve | None:
    """The intermittent region from the motor's winding, or None without its data."""
    winding = Winding.of(motor)
    return None if winding is None else electrical_intermittent(motor, winding)


def from_zero(curve: Curve) -> Curve:
    """A curve starting above zero speed holds its first torque down to standstill."""
    return ((0.0, curve[0][1]), *curve) if curve[0][0] > 0.0 else tuple(curve)


def envelope_note(rule: EnvelopeRule) -> str:
    """The sentence the outputs carry when some motor has no curve."""
    return f"envelope {rule}: motors without curves have {ENVELOPE_RULES[rule]}"
