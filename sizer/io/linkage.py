"""A linkage stage of a design's transmission (seed 003): read, its geometry checked.

The linkage must be the transmission's last stage: the stages before it turn its crank
(their ratio is motor speed over crank speed), its output is the load. Its geometry is
checked by building it (sizer.mechanics.linkages): a rod not longer than the crank plus
the offset, a four-bar that cannot close or whose crank cannot turn fully, are errors at
the stage's line.
"""

from __future__ import annotations

from typing import Any

from sizer.bounded_yaml import format_path
from sizer.errors import UserError
from sizer.io.schema.transmission_inputs import DiscCamInput, FourBarInput, SliderCrankInput
from sizer.io.yaml_source import YamlSource
from sizer.mechanics.linkages.of_stage import linkage_of, linkages_of
from sizer.model.cycle import Cycle
from sizer.model.domain import LinkageStage


def linkage_stage(item: SliderCrankInput | FourBarInput | DiscCamInput, source: YamlSource,
                  at: tuple[Any, ...]) -> LinkageStage:
    """The LinkageStage of a ``slider_crank``, ``four_bar`` or ``disc_cam`` item, its
    geometry built (a cam's is made per law, from the cycle: sizer.mechanics.disc_cam)."""
    if isinstance(item, DiscCamInput):
        return cam_stage(item, source, at)
    common: dict[str, Any] = {
        "law_on": item.law_on, "start_angle": item.start_angle,
        "direction": 1 if item.direction == "positive" else -1,
        "crank_inertia": item.crank_inertia, "name": item.name or "", "output": item.output or ""}
    if isinstance(item, SliderCrankInput):
        stage = LinkageStage("slider_crank", (item.crank_radius, item.rod_length, item.offset),
                             link_mass_at_crank=item.rod_mass_at_crank,
                             link_mass_at_output=item.rod_mass_at_slider, **common)
    else:
        stage = LinkageStage("four_bar", (item.crank, item.coupler, item.rocker, item.ground),
                             branch=item.branch, link_mass_at_crank=item.coupler_mass_at_crank,
                             link_mass_at_output=item.coupler_mass_at_rocker,
                             driven_link=item.driven_link, **common)
    try:
        linkage_of(stage)
    except UserError as error:
        raise source.relocate(error, (*at, error.field) if error.field else at) from None
    return stage


def cam_stage(item: DiscCamInput, source: YamlSource, at: tuple[Any, ...]) -> LinkageStage:
    """The CamStage of a ``disc_cam`` item (sizer.mechanics.disc_cam): the law is on the
    follower (its lift over the cam angle); its speed and lift are made per law from the
    cycle (sizer.sizing.linkage_move.cam_design; the cycle checked by :func:`cam_cycle`).
    A spring (force-closed) is its preload and its force (or, oscillating, torque) at the
    top; an oscillating follower is its pivot distance and arm length."""
    import math

    from sizer.mechanics.disc_cam import CamStage, fits

    oscillating = item.follower == "oscillating_roller"
    fields = ("pivot_distance", "arm_length")
    spring = ("spring_torque_preload", "spring_torque_at_top") if oscillating else \
        ("spring_preload", "spring_force_at_top")
    wrong = ("spring_preload", "spring_force_at_top") if oscillating else \
        ("spring_torque_preload", "spring_torque_at_top", *fields)
    for name in wrong:
        if getattr(item, name) is not None:
            what = "an oscillating follower's spring acts on its arm: give spring_torque_" \
                "preload and spring_torque_at_top" if oscillating and "spring" in name else \
                f"{name} is a field of an oscillating follower (follower: oscillating_roller)"
            raise source.error(what, (*at, name))
    arm: tuple[float, float] | None = None
    if oscillating:
        for name in fields:
            if getattr(item, name) is None:
                raise source.error(f"an oscillating follower needs its {name}", (*at, "follower"))
        if item.offset:
            raise source.error("an oscillating follower has no offset: its pivot_distance and "
                               "arm_length place it", (*at, "offset"))
        assert item.pivot_distance is not None and item.arm_length is not None
        arm = (item.pivot_distance, item.arm_length)
    if item.base_radius is not None and \
            not fits(item.base_radius + item.roller_radius, item.offset, arm):
        reach = f"larger than the offset ({abs(item.offset):g} m)" if arm is None else \
            f"between |pivot_distance - arm_length| and their sum ({abs(arm[0] - arm[1]):g} " \
            f"and {arm[0] + arm[1]:g} m: the arm reaches it)"
        raise source.error(f"the prime circle (base radius + roller radius, "
                           f"{item.base_radius + item.roller_radius:g} m) must be {reach}",
                           (*at, "base_radius"))
    preload, top = (getattr(item, name) for name in spring)
    unit = "N*m" if oscillating else "N"
    if top is not None and preload is None:
        raise source.error(f"a spring's {spring[1].split('_')[1]} at the top needs its "
                           f"preload ({spring[0]})", (*at, spring[1]))
    if top is not None and preload is not None and top < preload:
        raise source.error(f"a spring pushes harder when compressed: its value at the top "
                           f"({top:g} {unit}) must be at least its preload ({preload:g} "
                           f"{unit})", (*at, spring[1]))
    limit = item.pressure_angle if item.pressure_angle is not None else \
        math.radians(45.0 if oscillating else 30.0)
    return CamStage("disc_cam", (item.base_radius or 0.0, item.offset, item.roller_radius),
                    law_on="output", crank_inertia=item.cam_inertia,
                    link_mass_at_output=item.follower_mass, name=item.name or "",
                    base_radius=item.base_radius, offset=item.offset,
                    roller_radius=item.roller_radius, pressure_angle=limit,
                    force_closed=preload is not None, spring_preload=preload or 0.0,
                    spring_force_at_top=top, arm=arm)


def cam_cycle(cycle: Cycle, stage: LinkageStage, source: YamlSource) -> Cycle:
    """The cycle of a design through a disc cam, checked: every segment a move from rest
    to rest or a dwell, each of a fixed duration (the cam's geometry is made from their
    ratios: it turns once per machine cycle at constant speed), the displacements lengths
    (the follower's lift) summing to 0 (the follower comes back: a task needs its
    ``return``). The cam's speed and lift are made per law (sizer.sizing.linkage_move.
    cam_design)."""
    from sizer.model.cycle import Dwell, Move, from_task

    task = cycle.shorthand
    if task is not None and not task.return_move:
        raise source.error("a cam's follower comes back every turn: give the task's return "
                           "(return: true) or a cycle whose moves sum to 0", ("task",))
    if task is not None and task.duration is None:
        raise source.error("a cam's geometry is made from the moves' durations: give the "
                           "task's duration (not minimize)", ("task", "duration"))
    full = from_task(task) if task is not None else cycle
    where: tuple[Any, ...] = ("task", "displacement") if task is not None else ("cycle",)
    if full.linear != stage.output_linear:
        what = "a length like '20 mm'" if stage.output_linear else \
            "an angle like '15 deg' (the arm's swing)"
        raise source.error(f"through a disc cam a displacement is the follower's lift, "
                           f"{what}", where)
    free = full.free
    lift, travel = 0.0, 0.0
    for i, segment in enumerate(full.segments):
        where = ("task",) if task is not None else ("cycle", "segments", i)
        if not isinstance(segment, Move | Dwell) or (
                isinstance(segment, Move) and not segment.rest_to_rest):
            raise source.error("through a disc cam every segment is a move from rest to rest "
                               "or a dwell (the cam turns at constant speed)", where)
        if segment.duration is None or i in free:
            raise source.error("through a disc cam every segment needs its own duration (the "
                               "cam's geometry is made from them)", where)
        lift += segment.displacement
        travel = max(travel, abs(segment.displacement))
    if abs(lift) > 1e-9 * travel:
        unit = "m" if stage.output_linear else "rad"
        raise source.error(f"a cam's follower comes back every turn: the displacements sum "
                           f"to {lift:g} {unit}, not 0", ("cycle",))
    return cycle


def linkage_cycle(cycle: Cycle, stage: LinkageStage, source: YamlSource,
                  start_at: tuple[Any, ...] = ()) -> Cycle:
    """The cycle of a design whose transmission ends in a linkage, on its
    axis: the linkage's output (a slider is linear, a rocker rotary).

    With ``law_on: crank`` the displacements are the crank's turns, angles; with
    ``law_on: output`` the output's travels, of the output's kind. A run, or a move with
    boundary speeds, needs the law on a crank turned by the motor and a fixed duration
    (:func:`_check_moving`); a task's return move goes back from where the way out
    stopped. ``start_at``: the path of the stage's ``start_angle`` (blamed when the first
    move would fit the stroke from another start).
    """
    from dataclasses import replace

    from sizer.model.cycle import Move, Run

    if stage.kind == "disc_cam":
        return cam_cycle(cycle, stage, source)
    task = cycle.shorthand
    if task is not None:
        moves: list[tuple[float, tuple[Any, ...]]] = [(task.displacement,
                                                        ("task", "displacement"))]
        if task.return_move:
            moves.append((-task.displacement, ("task", "return")))
    else:
        moves = []
        free = cycle.free
        for i, segment in enumerate(cycle.segments):
            at = ("cycle", "segments", i)
            if isinstance(segment, Run | Move):
                moving = not (isinstance(segment, Move) and segment.rest_to_rest)
                if moving:
                    _check_moving(stage, segment, i in free, source, at)
                where: tuple[Any, ...] = (*at, "run") if isinstance(segment, Run) else \
                    (*at, "move", "displacement")
                moves.append((segment.displacement, where))
    linear = cycle.linear
    output = "a length (the slider's travel)" if stage.output_linear else \
        "an angle (the output's swing)"
    where = moves[0][1]
    if stage.law_on == "crank" and linear:
        turn = "turn" if stage.driven_link == "crank" else "swing"
        raise source.error(f"with law_on: crank a displacement is the {stage.driven_link}'s "
                           f"{turn}, an angle like '180 deg'", where)
    if stage.law_on == "output" and linear != stage.output_linear:
        raise source.error(f"with law_on: output a displacement is {output}", where)
    _check_strokes(stage, moves, source, start_at)
    return replace(cycle, linear=stage.output_linear, shorthand=task and replace(
        task, linear=stage.output_linear))


def _check_moving(stage: LinkageStage, segment: Any, free: bool, source: YamlSource,
                  at: tuple[Any, ...]) -> None:
    """A run or a move with boundary speeds through a linkage: the crank keeps turning, so
    the law must be on the crank, turned by the motor (an output or a driven rocker
    cannot keep moving at a speed through its dead points, where the crank's speed is
    the paper's limit, not the one given), and a move's duration fixed (its shape, the
    law's boundary form, depends on it; the time scaling of free durations does not hold
    for it)."""
    kind = "a run" if segment.__class__.__name__ == "Run" else \
        "a move with boundary speeds or accelerations"
    if stage.law_on != "crank" or stage.driven_link != "crank":
        raise source.error(f"{kind} through a linkage needs the law on the crank, turned "
                           f"by the motor (law_on: crank, driven_link: crank): the output "
                           f"(or a driven rocker) cannot keep moving through its dead "
                           f"points", at)
    if free or segment.duration is None:
        raise source.error(f"{kind} through a linkage needs its own duration (its shape "
                           f"through the position-dependent ratio depends on it)", at)


def _check_strokes(stage: LinkageStage, moves: list[tuple[float, tuple[Any, ...]]],
                   source: YamlSource, start_at: tuple[Any, ...] = ()) -> None:
    """Each move of the law's coordinate (the output's, or a driven rocker's), from where
    the last one ended, stays within its range (a crank's turn has none). A first move no
    longer than the stroke that leaves it is blamed on the start (``start_at``)."""
    import numpy as np

    views = linkages_of(stage)
    given = views.output if stage.law_on == "output" else views.motor
    if not given.dead_points().size:
        return
    position = float(given.output(np.array([stage.start_angle]))[0])
    low, high = given.output_range()
    for k, (h, at) in enumerate(moves):
        if k == 0 and start_at and abs(h) <= (high - low) * (1 + 1e-9):
            _check_stroke(given, position, h, source, start_at,
                          f"{format_path(at)} from start_angle "
                          f"{float(np.degrees(stage.start_angle)):.6g} deg: ",
                          "; change start_angle (where the move starts) or the displacement")
        _check_stroke(given, position, h, source, at)
        position += h


def _check_stroke(given: Any, start: float, h: float, source: YamlSource,
                  at: tuple[Any, ...], head: str = "", tail: str = "") -> None:
    """The move from ``start`` by ``h`` stays within the coordinate's range (else an error
    at ``at``, its message between ``head`` and ``tail``)."""
    low, high = given.output_range()
    end = start + h
    tolerance = 1e-9 * (high - low)
    if not low - tolerance <= end <= high + tolerance:
        unit = "m" if given.output_linear else "rad"
        name = "output" if getattr(given, "coordinate", "") != "rocker_angle" else "rocker"
        raise source.error(f"{head}the {name} would move from {start:.6g} {unit} to "
                           f"{end:.6g} {unit}, beyond its range [{low:.6g}, {high:.6g}] "
                           f"{unit} (the stroke between the dead points){tail}", at)


def output_linear(items: Any, linear: bool) -> bool:
    """Whether the load is linear: the displacement's kind, or, when the transmission
    ends in a linkage, its output's (a slider is linear, a rocker is not)."""
    items = items if isinstance(items, list) else [items] if items is not None else []
    for item in reversed(items):
        kind = getattr(item, "type", None)
        if kind == "disc_cam":
            return getattr(item, "follower", None) != "oscillating_roller"
        if kind in ("slider_crank", "four_bar"):
            return kind == "slider_crank" and getattr(item, "output", None) in (
                None, "slider_position")
        if kind not in (None, "direct"):
            break
    return linear


def check_linkage_design(model: Any, source: YamlSource) -> None:
    """Refuse what a design through a linkage states and sizing would not check: the
    residual vibration of the load's mode (its output does not follow the law, the ratio
    varies: sizer.sizing.vibration_check.refusal), at the limit, else at the mode."""
    load, limits = model.load, model.limits
    why = ("the residual vibration is not computed through a linkage (its output does "
           "not follow the law: the ratio varies)")
    if limits is not None and limits.residual_vibration is not None:
        raise source.error(f"{why}; remove limits.residual_vibration and the load's mode",
                           ("limits", "residual_vibration"))
    if load is not None and load.natural_frequency is not None:
        raise source.error(f"{why}; remove load.natural_frequency", ("load",
                                                                     "natural_frequency"))
