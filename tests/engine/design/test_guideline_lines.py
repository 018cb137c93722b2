"""One line per guideline for ``check`` and ``margins``
(:func:`audit.engine.design.guideline_lines.guideline_lines`): FEMA 356's line for 0.5 × 1.7 m
at S_XS, S_X1 = 1.0, 0.6 g is its uplift step, computed here by hand, in both commands."""

from __future__ import annotations

import math

import numpy as np
import pytest

import audit
from audit.engine.design.stripes import half_crossing
from tests.engine.check.pulses import eight_pulses

SXS_G, SX1_G = 1.0, 0.6
WIDTH_M, HEIGHT_M = 0.5, 1.7


def test_fema356_line_is_its_uplift_step_in_check_and_in_margins():
    # FEMA 356 uplifts when its design spectrum's zero-period acceleration 0.4·S_XS·λ reaches
    # g·tan α, λ = level / S_X1 the design spectrum's scale at Sa(1 s); this block's iteration
    # overturns as soon as it uplifts, so the uplift is where FEMA 356 starts predicting
    # overturning: 0.6 · (0.5/1.7) / 0.4 = 0.441 g
    uplift_g = SX1_G * (WIDTH_M / HEIGHT_M) / (0.4 * SXS_G)
    assert uplift_g == pytest.approx(0.441, abs=5e-4)
    block = f"{WIDTH_M}x{HEIGHT_M}"
    checked = audit.check(block, (SXS_G, SX1_G), procedures="fema356", records=eight_pulses(),
                          im="sa:1.0", solver=audit.Solver(free_motion_s=2.0))
    (entry,) = checked.document["objects"][0]["procedures"]
    margins = audit.margins("fema356", eight_pulses(), im="sa:1.0", alpha_deg=(), blocks=[block],
                            site=(SXS_G, SX1_G), required=False,
                            solver=audit.Solver(free_motion_s=2.0))
    capacity = margins.capacity
    margins_line = float(capacity.loc[capacity["procedure"] == "fema356", "guideline_im"].iloc[0])
    assert entry["guideline_im"] == pytest.approx(uplift_g, rel=1e-6)
    assert margins_line == pytest.approx(uplift_g, rel=1e-6)
    # the check's stripes bracket the step: interpolating the step between them (what the check
    # did) puts the line at their geometric mean instead, off by more than the 1 % the two
    # commands must agree within (on the lattice's stripes √2 apart, ~4 %)
    levels = np.array(checked.document["objects"][0]["exact"]["stripes"]["im"])
    below = levels[levels < uplift_g].max()
    above = levels[levels > uplift_g].min()
    interpolated = half_crossing(np.array([below, above]), np.array([0.0, 1.0]))
    assert interpolated == pytest.approx(math.sqrt(below * above))
    assert abs(interpolated / uplift_g - 1.0) > 0.02
