"""``sizer size --robust``: the sizing table with each pair's worst case over the corners
of the design's tolerances (sizer.robust, docs/robust.md)."""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from sizer.report.candidate_row import percent
from sizer.report.json_text import render_json
from sizer.report.numbers import finite_or_none
from sizer.report.sizing_table import SizingDocument
from sizer.report.table import Column, Table, make_table

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.model.tolerance import Tolerance
    from sizer.robust import Corner, RobustResult, RobustSizing

RANKING = ("the pairs feasible at every corner first, then as usual (the nominal "
           "ranking within each group)")
RANKING_BUILDS = ("the pairs feasible at every build (corner and sample) first, then as "
                  "usual (the nominal ranking within each group)")
RANKING_DURATION = ("the pairs feasible at every build first, then the shortest worst-case "
                    "T_min first (ties: the nominal ranking)")
FIXED_RATIO = ("each pair's ratio (a free ratio, a catalog gearbox) is the one chosen at the "
               "nominal design, as the one bought, and fixed at every build")
RANKING_WORST = ("the pairs feasible at every build first, then the largest worst-case "
                 "margin first (ties: the nominal ranking by margin)")


def corner_text(corner: Corner, absolute: dict[str, str] | None = None) -> str:
    """'load.inertia +20 %, motor.peak_torque -10 %' (an input named in ``absolute``:
    its change in that unit, 'load.friction -0.1 N*m')."""
    absolute = absolute or {}
    return ", ".join(f"{name} {change:+.4g} {absolute[name]}".rstrip() if name in absolute
                     else f"{name} {change * 100.0:+.4g} %" for name, change in corner)


def _corner_json(corner: Corner) -> dict[str, float]:
    return {name: change for name, change in corner}


def _amount(width: float, absolute: bool, unit: str) -> str:
    return f"{width:.4g} {unit}".rstrip() if absolute else f"{width * 100.0:.4g} %"


def tolerance_text(t: Tolerance, unit: str = "") -> str:
    """'load.inertia +-20 %', 'load.friction +-0.1 N*m', 'motor.peak_torque normal, sigma
    5 %, truncated at +-2 sigma (+-10 %)'."""
    if t.distribution == "normal" and t.sigma is not None and t.sigmas is not None:
        return (f"{t.name} normal, sigma {_amount(t.sigma, t.absolute, unit)}, truncated "
                f"at +-{t.sigmas:g} sigma (+-{_amount(t.width, t.absolute, unit)})")
    return f"{t.name} +-{_amount(t.width, t.absolute, unit)}"


def share_text(result: RobustResult) -> str:
    """'99.2 [98.6, 99.6]': the share of the samples that pass and its 95 % interval, in
    per cent ('' without samples)."""
    if not result.samples:
        return ""
    low, high = result.interval
    return f"{result.share * 100.0:.1f} [{low * 100.0:.1f}, {high * 100.0:.1f}]"


class RobustDocument(SizingDocument):
    """The robust sizing's ranked results (sizer.report.sizing_table.SizingDocument) with
    a worst-case margin column (and, with samples, the share that passes) and, in JSON, a
    ``robust`` object per result. ``rank_by`` is the nominal sizing's key."""

    def __init__(self, robust: RobustSizing, design: Design, **options: Any) -> None:
        from sizer.robust import tolerance_units

        super().__init__(robust.sizing, design, **options)
        self.robust = robust
        self._of = {id(r.nominal): r for r in robust.results}
        units = tolerance_units(design)
        self._units = {t.name: units.get(t.input, "") for t in robust.tolerances}
        self._absolute = {t.name: self._units[t.name] for t in robust.tolerances
                          if t.absolute}

    def table(self, compact: bool = False) -> Table:
        base = super().table(compact)
        sampled = self.robust.samples > 0
        minimize = self.robust.minimize
        columns = (*base.columns, Column("worst margin [%]"), Column("robust", "left"),
                   *((Column("pass [%] (95 % interval)", "left"),) if sampled else ()),
                   *((Column("worst T_min [ms]"),) if minimize else ()),
                   *((Column("T_min p95 [ms]"),) if minimize and sampled else ()))
        rows = [(*row, percent(finite_or_none(self._of[id(r)].margin)),
                 _verdict(self._of[id(r)]),
                 *((share_text(self._of[id(r)]),) if sampled else ()),
                 *(_durations(self._of[id(r)], sampled) if minimize else ()))
                for row, (_, r) in zip(base.rows, self.rows, strict=True)]
        return make_table(columns, rows, title=base.title)

    def _ranking(self) -> str:
        if self.robust.by_worst_duration:
            return RANKING_DURATION
        if self.robust.by_worst_margin:
            return RANKING_WORST
        return RANKING_BUILDS if self.robust.samples else RANKING

    def footer(self, dropped: Sequence[str] = ()) -> list[str]:
        robust = self.robust
        tolerances = ", ".join(tolerance_text(t, self._units[t.name])
                               for t in robust.tolerances)
        n = robust.samples
        drawn = (f"{n} builds drawn from the tolerances' distributions (seed "
                 f"{robust.seed}); 'pass' is the share of them that pass every check, with "
                 f"its 95 % Wilson interval")
        if robust.corners:
            count = 2 ** len(robust.tolerances)
            lines = [f"robust: every pair at the {count} corners of {tolerances}"
                     + (f", and at {drawn}" if n else "")
                     + "; 'worst margin' is the least margin over them (exact where the "
                       "margins are monotone in the inputs; --format json names each "
                       "check's corner)"]
        else:
            lines = [f"robust: {len(robust.tolerances)} tolerances are too many for corners "
                     f"(2^{len(robust.tolerances)}): sampled instead, every pair at {drawn}; "
                     f"'worst margin' is the least margin seen over the samples (an "
                     f"estimate, not a bound): {tolerances}"]
        if robust.fixed_ratio:
            lines.append(f"robust: {FIXED_RATIO}")
        if robust.minimize:
            lines.append("robust: each build sized for its shortest duration (its margins "
                         "are at its own T_min); 'worst T_min' is the largest over the "
                         "builds, 'none' where a build has none (--format json names its "
                         "build)" + ("; 'T_min p95' the samples' 95th percentile (nearest "
                                     "rank)" if robust.samples else ""))
        lines.append(f"ranked robustly: {self._ranking()}")
        for rank, r in self.rows:
            worst = self._of[id(r)]
            if robust.corners and worst.sampled_checks and not robust.minimize:
                where = ", ".join(f"{name} (at {_WHERE[(worst.by or {})[name]]})"
                                  for name in worst.sampled_checks)
                lines.append(f"  #{rank} {r.motor}: not monotone, worse inside the box than "
                             f"at every corner: {where}; its worst case is that build's")
            if worst.limiting is not None and not worst.feasible:
                lines.append(f"  #{rank} {r.motor}: worst {worst.limiting} at "
                             f"{corner_text(worst.corner[worst.limiting], self._absolute)}")
        return [*super().footer(dropped), *lines]

    def json(self) -> str:
        data = json.loads(super().json())
        robust = self.robust
        data["tolerances"] = {t.name: t.width for t in robust.tolerances}
        data["tolerance_details"] = [
            {"name": t.name, "width": t.width, "absolute": t.absolute,
             "unit": self._units[t.name] if t.absolute else "1 (fraction)",
             "distribution": t.distribution, "sigma": t.sigma, "truncate": t.sigmas}
            for t in robust.tolerances]
        data["robust_method"] = {"corners": robust.corners, "samples": robust.samples,
                                 "seed": robust.seed if robust.samples else None}
        if robust.fixed_ratio:
            data["robust_method"]["ratio"] = FIXED_RATIO
        data["robust_ranking"] = self._ranking()
        for item, (_, r) in zip(data["results"], self.rows, strict=True):
            item["robust"] = robust_json(self._of[id(r)])
        return render_json(data)


_WHERE = {"samples": "a sample", "nominal": "the nominal machine"}


def _verdict(result: RobustResult) -> str:
    if result.feasible:
        return "ok"
    if result.failing:
        return f"FAILS at {result.failing}/{result.corners}"
    if result.passing < result.samples:
        return f"FAILS in {result.samples - result.passing}/{result.samples} samples"
    return "FAILS at the nominal machine"  # passes at every corner: not monotone


def robust_json(result: RobustResult) -> dict[str, Any]:
    """A pair's ``robust`` object: the verdict, the least worst-case margin, its check and
    corner, and each check's worst-case margin and corner."""
    limiting = result.limiting
    out: dict[str, Any] = {
        "feasible": result.feasible,
        "failing_corners": result.failing,
        "corners": result.corners,
        "margin": finite_or_none(result.margin),
        "limiting": limiting,
        "corner": _corner_json(result.corner[limiting]) if limiting is not None else None,
        "checks": {name: {"margin": finite_or_none(margin),
                          "corner": _corner_json(result.corner[name]),
                          "by": (result.by or {}).get(name)}
                   for name, margin in result.worst.items()},
    }
    if result.samples:
        low, high = result.interval
        out.update(samples=result.samples, passing_samples=result.passing,
                   share=result.share, interval=[low, high])
    if result.duration is not None:
        d = result.duration
        out["duration"] = {"worst": finite_or_none(d.worst), "corner": _corner_json(d.corner),
                           "by": d.by}
        if result.samples:
            out["duration"].update(p95=finite_or_none(d.p95),
                                   sampled_max=finite_or_none(d.sampled_max))
    return out


def _ms(seconds: float) -> str:
    return f"{seconds * 1000.0:.4g}" if math.isfinite(seconds) else "none"


def _durations(result: RobustResult, sampled: bool) -> tuple[str, ...]:
    """The worst T_min (and the samples' 95th percentile) in ms; 'none' where a build
    has no T_min."""
    d = result.duration
    if d is None:
        return ("", "") if sampled else ("",)
    return (_ms(d.worst), _ms(d.p95)) if sampled else (_ms(d.worst),)
