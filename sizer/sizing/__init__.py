"""Sizing: requirements, margins, minimum duration and ranking (book ch. 6)."""

from sizer.sizing.engine import assumptions, check_design, evaluate_law, size_design
from sizer.sizing.ranking import RANK_KEYS
from sizer.sizing.results import CandidateResult, Check, SizingResult

__all__ = [
    "RANK_KEYS",
    "CandidateResult",
    "Check",
    "SizingResult",
    "assumptions",
    "check_design",
    "evaluate_law",
    "size_design",
]
