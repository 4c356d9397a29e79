"""What shape a machine cycle has, for the engine: the task shorthand or not, the scale
of its free durations, and the laws that are ranked over it (issue 12)."""

from __future__ import annotations

import math
from dataclasses import replace

from sizer.errors import UserError
from sizer.model.cycle import Cycle, Dwell, Move
from sizer.model.domain import Design, Task


def shorthand_task(cycle: Cycle) -> Task | None:
    """The task whose expansion is ``cycle`` (sizer.model.cycle.from_task: move, dwell,
    move back, dwell, equal durations, no load changes), else None."""
    if cycle.shorthand is not None:
        return cycle.shorthand
    if cycle.minimize_segment is not None or cycle.cycle_time is not None:
        return None
    segments = cycle.segments
    moves = [s for s in segments if isinstance(s, Move)]
    dwells = [s for s in segments if isinstance(s, Dwell)]
    if len(moves) + len(dwells) != len(segments) or not 1 <= len(moves) <= 2:
        return None
    if any(m.law is not None or not m.rest_to_rest or not m.load.is_zero for m in moves):
        return None
    if any(d.duration is None or not d.load.is_zero for d in dwells):
        return None
    first = moves[0]
    if len(moves) == 2:
        back = moves[1]
        if back.displacement != -first.displacement or back.duration != first.duration:
            return None
        if first.duration is None and len(set(cycle.weights())) > 2:  # unequal free shares
            return None
        expected: list[type] = [Move, Dwell, Move, Dwell] if dwells else [Move, Move]
    else:
        expected = [Move, Dwell] if dwells else [Move]
    if [type(s) for s in segments] != expected:
        return None
    dwell = dwells[0].duration if dwells else 0.0
    if any(d.duration != dwell for d in dwells) or (dwells and not dwell):
        return None
    return Task(first.displacement, first.duration, dwell=dwell or 0.0,
                return_move=len(moves) == 2, linear=cycle.linear)


def plain_design(design: Design) -> Design:
    """The design with a cycle that is the task shorthand (move, dwell, move back, dwell)
    written as a task, so that it is sized by the single-law engine with identical
    results (:func:`shorthand_task`); other designs unchanged."""
    if design.cycle is None:
        return design
    task = shorthand_task(design.cycle)
    return design if task is None else replace(design, task=task, cycle=None)


def given_scale(cycle: Cycle) -> float:
    """The scale s of the free durations when it is not minimized: from the cycle time
    target (T_i = w_i s fill what the fixed durations leave), or 1 when nothing is free."""
    weights = math.fsum(cycle.weights())
    if cycle.cycle_time is None or weights == 0.0:
        return 1.0
    return (cycle.cycle_time - cycle.fixed_time) / weights


def ranked_laws(design: Design) -> tuple[str, ...]:
    """The law specs the ranking runs over: the design's laws (those that can meet the
    boundary speeds of every move that names no law of its own); with a cycle whose every
    move names its law, that cycle once, labelled by its first move's law."""
    cycle = design.cycle
    if cycle is None:
        if not design.laws:
            raise UserError("no motion laws to consider", field="laws")
        return design.laws
    open_moves = [m for m in cycle.moves if m.law is None]
    if not open_moves:
        return (cycle.moves[0].law,) if cycle.moves and cycle.moves[0].law else ("cycloidal",)
    if not design.laws:
        raise UserError("no motion laws to consider for the moves that name none",
                        field="laws")
    if all(m.rest_to_rest for m in open_moves):
        return design.laws
    from sizer.laws.boundary_speeds import boundary_form

    accelerated = any(m.start_acceleration != 0.0 or m.end_acceleration != 0.0
                      for m in open_moves)

    def usable(spec: str) -> bool:
        basis = boundary_form(spec) if not _has_auto(spec) else None
        return basis is not None and (not accelerated or basis.meets_accelerations)

    kept = tuple(spec for spec in design.laws if usable(spec))
    if not kept:
        raise UserError("none of the laws can start or end a move at a non-zero speed"
                        + (" or acceleration (polynomials of degree 5 and 7 can)" if accelerated
                           else " (those that can: trapezoidal, double_s, polynomial of "
                                "degree 3, 5 or 7, constant_acceleration)")
                        + "; name one in `laws:` or give the move its own `law:`",
                        field="laws")
    return kept


def _has_auto(spec: str) -> bool:
    from sizer.laws import AUTO, resolve

    return any(v == AUTO for v in resolve(spec)[1].values())


def left_out_laws(design: Design) -> tuple[str, ...]:
    """The design's laws the ranking leaves out (no form with the moves' boundary speeds
    or accelerations)."""
    if design.cycle is None or not any(m.law is None for m in design.cycle.moves):
        return ()
    kept = set(ranked_laws(design))
    return tuple(spec for spec in design.laws if spec not in kept)
