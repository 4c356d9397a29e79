"""Motion-law library: normalized shapes, exact coefficients, spec parsing."""

from sizer.laws.base import INFINITELY_SMOOTH, MotionLaw, Parameter, law_of
from sizer.laws.boundary_speeds import BoundaryBasis, boundary_form, has_boundary_form
from sizer.laws.choice import LawChoice, law_choice
from sizer.laws.coefficients import AccelerationJump, LawCoefficients
from sizer.laws.motion import ScaledMotion
from sizer.laws.pieces import Piece
from sizer.laws.registry import (
    ALIASES,
    DEFAULT_LAW_SPECS,
    LAW_FAMILIES,
    known_law_ids,
    make_law,
    resolve,
)
from sizer.laws.spec import AUTO, LawSpec, parse_law_spec

__all__ = [
    "ALIASES",
    "AUTO",
    "DEFAULT_LAW_SPECS",
    "INFINITELY_SMOOTH",
    "LAW_FAMILIES",
    "AccelerationJump",
    "BoundaryBasis",
    "LawChoice",
    "LawCoefficients",
    "LawSpec",
    "MotionLaw",
    "Parameter",
    "Piece",
    "ScaledMotion",
    "boundary_form",
    "has_boundary_form",
    "known_law_ids",
    "law_choice",
    "law_of",
    "make_law",
    "parse_law_spec",
    "resolve",
]
