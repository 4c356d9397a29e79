"""The mechanism of a design's linkage stage (sizer.model.domain.LinkageStage).

Every coordinate of a stage is read as a function of its crank angle theta (q1: in a
Grashof crank-rocker and a slider-crank it turns fully, so it is a coordinate the whole
mechanism is a function of). The motor turns the ``driven_link`` (the crank, or a
four-bar's rocker); the load is on the ``output`` coordinate. Read in the other direction
(a four-bar driven from its rocker) the motor's coordinate q3(theta) has the dead points
where the crank and the coupler are in line, and the paper's results (seed 003 sec. 4)
apply to it with input and output swapped: the law on the rocker gives the crank's
motion by the same limits (:mod:`inverse_motion`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from sizer.mechanics.linkages import Linkage
from sizer.model.domain import LinkageStage

DEFAULT_OUTPUT = {("slider_crank", "crank"): "slider_position",
                  ("four_bar", "crank"): "rocker_angle",
                  ("four_bar", "rocker"): "crank_angle",
                  ("disc_cam", "crank"): "follower_lift"}
"""The output coordinate of a stage that names none, by its kind and driven link."""

OUTPUTS = {("slider_crank", "crank"): ("slider_position", "rod_angle"),
           ("four_bar", "crank"): ("rocker_angle", "coupler_angle"),
           ("four_bar", "rocker"): ("crank_angle", "coupler_angle")}
"""The output coordinates a stage may have, by its kind and driven link."""


@dataclass(frozen=True)
class StageLinkages:
    """A stage's coordinates as functions of its crank angle: ``motor`` the driven link's
    (the crank angle itself when the motor turns the crank), ``output`` the load's,
    ``joint`` the coordinate the connecting link's mass at its output end moves with
    (the slider, or the rocker's angle)."""

    motor: Linkage
    output: Linkage
    joint: Linkage
    crank_driven: bool


def output_name(stage: LinkageStage) -> str:
    """The stage's output coordinate (its default when it names none)."""
    return stage.output or DEFAULT_OUTPUT[(stage.kind, stage.driven_link)]


def linkages_of(stage: LinkageStage) -> StageLinkages:
    """The coordinates of a LinkageStage; UserError for bad geometry (field: the link) or
    an output its driven link does not give (field "output")."""
    from sizer.errors import UserError

    if stage.kind == "disc_cam":  # the follower's lift over the cam angle, set per law
        lift = getattr(stage, "lift", None)
        assert lift is not None, "a cam's lift is set per law (sizer.mechanics.disc_cam)"
        return StageLinkages(CrankAngle(), lift, lift, True)
    key = (stage.kind, stage.driven_link)
    if key not in OUTPUTS:
        raise UserError(f"a {stage.kind} is driven from its crank, not its "
                        f"{stage.driven_link}", field="driven_link")
    output = output_name(stage)
    if output not in OUTPUTS[key]:
        raise UserError(f"with the motor on the {stage.driven_link} the output is one of "
                        f"{', '.join(OUTPUTS[key])}, got {output!r}", field="output")
    if stage.kind == "slider_crank":
        from sizer.mechanics.linkages.slider_crank import SliderCrank

        r, rod, e = stage.lengths
        slider = SliderCrank(r, rod, e)
        return StageLinkages(CrankAngle(), replace(slider, coordinate=output), slider, True)
    from sizer.mechanics.linkages.four_bar import FourBar

    crank_, coupler, rocker, ground = stage.lengths
    bar = FourBar(crank=crank_, coupler=coupler, rocker=rocker, ground=ground,
                  branch=stage.branch)
    motor = bar if stage.driven_link == "rocker" else replace(bar, coordinate="crank_angle")
    return StageLinkages(motor, replace(bar, coordinate=output), bar,
                         stage.driven_link == "crank")


def linkage_of(stage: LinkageStage) -> Linkage:
    """The load's coordinate of a LinkageStage (its ``output``) as a function of the crank
    angle; UserError for bad geometry."""
    return linkages_of(stage).output


@dataclass(frozen=True)
class CrankAngle:
    """The crank angle as a coordinate of itself (the motor's, when it turns the crank)."""

    output_linear: bool = False

    def output(self, theta: np.ndarray, order: int = 0) -> np.ndarray:
        theta = np.asarray(theta, dtype=float)
        return theta.copy() if order == 0 else np.full(theta.shape, float(order == 1))

    def input_of(self, s: np.ndarray, half: int) -> np.ndarray:
        return np.asarray(s, dtype=float).copy()

    def dead_points(self) -> np.ndarray:
        return np.empty(0)

    def output_range(self) -> tuple[float, float]:
        return -math.inf, math.inf
