"""The engine's root finder: a re-export of :mod:`sizer.numerics.roots` (the one root
finder of the project, shared with the laws)."""

from sizer.numerics.roots import MAX_STEPS, illinois

__all__ = ["MAX_STEPS", "illinois"]
