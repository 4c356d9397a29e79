"""The paper's Table 1 cases on its four-bar (seed 003, Table 2 lengths, eq. 63 with
c1 = 0, t0 = 0 at the rocker's largest angle): feasible or not as its sec. 5 says.

c0 is the dead point's exact rocker angle (2.24593 rad): the printed 2.25 lies beyond the
rocker's swing (docs/errata.md)."""

from __future__ import annotations

import numpy as np
import pytest
from test_inverse_motion import eq63

from sizer.mechanics.linkages.four_bar import paper_four_bar
from sizer.mechanics.linkages.inverse_motion import dead_point_crossings, input_motion

FOUR_BAR = paper_four_bar()
TOP = FOUR_BAR.output_range()[1]
T = np.round(np.arange(-400, 401) * 5e-4, 12)


@pytest.mark.parametrize(("c2", "c3", "c4", "feasible"), [
    (0.0, 0.563, 0.0, False),  # sec. 5.1, Fig. 5: s_ddot = 0 with a jerk
    (0.0, 0.0, 0.563, True),   # Fig. 6: s_ddot = s_dddot = 0 (C3)
    (0.5, 0.563, 0.0, True),   # sec. 5.2, Fig. 7: s_ddot = -1, of the needed sign
])
def test_table1_four_bar(c2: float, c3: float, c4: float, feasible: bool) -> None:
    s, s1, s2, s3, left, right = eq63(c2, c3, c4, t=T, c0=TOP)
    issues = dead_point_crossings(FOUR_BAR, T, s, s1, s2, s3, left=left, right=right,
                                  units="rad")
    assert (issues == []) == feasible
    if not feasible:
        assert issues[0].kind == "jerk" and issues[0].time == 0.0
        return
    start = float(FOUR_BAR.input_of(np.array([s[0]]), 1)[0])
    _, theta1, theta2, _ = input_motion(FOUR_BAR, s, s1, s2, s3, start_theta=start)
    assert np.all(np.isfinite(theta1)) and np.all(np.isfinite(theta2))
    # the crank speed through the dead point: theta_dot^2 = s_ddot / s''(theta_dp)
    dead = float(FOUR_BAR.dead_points()[0])
    curvature = float(FOUR_BAR.output(np.array([dead]), 2)[0])
    assert theta1[400] ** 2 == pytest.approx(s2[400] / curvature, abs=1e-9)
    assert abs(theta1[399] - theta1[401]) < 0.05 * max(1.0, abs(theta1[400]))
