"""The steps of a procedure that reads only the site (FEMA 356), every block bisected together,
against the slow path they replace: each block bisected alone, one full evaluation of the
procedure per halving, on a real record at a real site."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from audit.engine.shared.blocks import BlockList
from audit.engine.shared.lattice import stripe_lattice
from audit.engine.shared.intensity import IntensityMeasure
from audit.engine.shared.sites import with_design_site
from audit.engine.design.stripes import STEP_TOLERANCE, StripeSettings, locate_steps, record_stripes
from audit.physics.block import Restitution
from audit.physics.design_spectra import FEMA356Spectrum
from procedures import get_procedures
from procedures.context import RecordContext
from procedures.overturning import predicts_overturning
from records.sites import scaled_site


def test_fema356_spectra_of_many_sites_are_each_site_alone_bit_for_bit():
    rng = np.random.default_rng(35)
    sxs, sx1 = 1.5 * rng.uniform(0.2, 5.0, 400), 0.9 * rng.uniform(0.2, 5.0, 400)
    # all three branches (T_S = S_X1·B_S/(S_XS·B_1) spans ~0.01–15 s here), and a NaN period
    period_s = np.append(np.geomspace(0.002, 20.0, 399), np.nan)
    for damping in (0.05, 0.137, 0.31):
        together = FEMA356Spectrum(sxs, sx1).displacement(period_s, damping)
        alone = [FEMA356Spectrum(a, b).displacement(np.array([t]), damping)[0]
                 for a, b, t in zip(sxs, sx1, period_s)]
        np.testing.assert_array_equal(together, alone)  # equal, not close


def _bisected_alone(procedure, entry, settings, block, low, high):
    """The slow path: one block, its record and site scaled afresh to every middle level and
    the procedure evaluated there in full (estimate, fixed points, checks)."""
    blocks = settings.blocks
    alpha = math.radians(float(blocks.alpha_deg[block]))
    r = float(settings.restitution.r(alpha))
    p = np.array([2.0 * math.pi / blocks.size_s[block]])
    intensity = settings.im.of_record(entry.motion, settings.free_motion_s)
    while high / low > 1.0 + STEP_TOLERANCE:
        middle = math.sqrt(low * high)
        scaled = replace(entry, motion=entry.motion.scaled(middle / intensity),
                         site=scaled_site(entry.site, middle / settings.design_im))
        context = RecordContext(scaled, settings.free_motion_s)
        if predicts_overturning(procedure.evaluate(scaled, p, alpha, r, context, settings.g))[0]:
            high = middle
        else:
            low = middle
    return math.sqrt(low * high)


def test_steps_located_together_are_those_of_each_block_bisected_alone(seed_suite):
    suite = with_design_site(seed_suite, 1.5, 0.9, override=True)
    entry = next(e for e in suite if e.motion is not None)
    im = IntensityMeasure.parse("sa:1.0")
    design = im.of_design_site(suite.design_site)
    blocks = BlockList.of((10.0, 20.0), (0.75, 2.0, 4.5, 7.5), ())
    settings = StripeSettings(im, tuple(stripe_lattice().tolist()), design, blocks,
                              Restitution.parse("housner"), 9.81, 2.0, 1)
    fema356 = get_procedures("fema356")[0]
    answer = record_stripes(entry, [fema356], settings).predicted["fema356"]
    levels = np.asarray(settings.levels)
    brackets = {}
    for b in range(len(blocks)):
        switch = np.flatnonzero(answer[1:, b] & ~answer[:-1, b])
        if switch.size:
            brackets[b] = levels[switch[0]], levels[switch[0] + 1]
    assert len(brackets) >= 6  # steps inside the stripes for most blocks of both α
    together = locate_steps(fema356, entry, settings, brackets)
    assert together.keys() == brackets.keys()
    for b, (low, high) in brackets.items():
        assert together[b] == _bisected_alone(fema356, entry, settings, b, low, high)
        assert low < together[b] < high
    # where FEMA 356 steps up: its uplift (0.4 S_XS · level/design = g tan α) or its
    # iteration's overturning, the latter above the former (a step is located to
    # STEP_TOLERANCE: its reported level is the middle of a bracket that narrow)
    for b, level in together.items():
        uplift = math.tan(math.radians(blocks.alpha_deg[b])) / (0.4 * 1.5) * design
        assert level >= uplift * (1.0 - STEP_TOLERANCE)


def test_a_step_is_found_to_its_tolerance(seed_suite):
    """A bracket that holds the step of the uplift check alone (a block whose iteration
    overturns as soon as it uplifts) closes on the closed form g tan α = 0.4 S_XS × factor."""
    suite = with_design_site(seed_suite, 1.5, 0.9, override=True)
    entry = next(e for e in suite if e.motion is not None)
    im = IntensityMeasure.parse("sa:1.0")
    design = im.of_design_site(suite.design_site)
    blocks = BlockList.of((10.0,), (0.5,), ())
    settings = StripeSettings(im, (design,), design, blocks, Restitution.parse("housner"),
                              9.81, 2.0, 1)
    uplift = math.tan(math.radians(10.0)) / (0.4 * 1.5) * design
    step = locate_steps(get_procedures("fema356")[0], entry, settings,
                        {0: (uplift * 0.9, uplift * 1.1)})[0]
    assert step == pytest.approx(uplift, rel=STEP_TOLERANCE)


def test_an_ntc_site_alone_has_no_fema_design_intensity(seed_suite):
    """An NTC 2018 site without a FEMA 356 one leaves the suite's design site without S_XS,
    S_X1: no design intensity (margins' CMR then has none), not a KeyError; with the FEMA site
    it is the spectrum's Sa(1 s) = S_X1 / 1 s."""
    from audit.engine.shared.sites import with_ntc_site
    im = IntensityMeasure.parse("sa:1.0")
    ntc_only = with_ntc_site(seed_suite, 0.25, 2.4, 0.3, "B", "T1")
    assert "ntc" in ntc_only.design_site and im.of_design_site(ntc_only.design_site) is None
    both = with_design_site(ntc_only, 1.5, 0.9, override=True)
    assert im.of_design_site(both.design_site) == pytest.approx(0.9)


def test_an_ntc_site_alone_is_scaled_to_every_stripe_from_its_own_intensity(seed_suite):
    """With an NTC 2018 site and no FEMA 356 one, margins scales the NTC site to each stripe
    from its own S_e at the IM (it stayed as given at every stripe, so NTC drew its line at
    the lowest stripe where it failed). S_e(1 s) by hand for a_g 0.35 g, F0 2.4, T_C* 0.35 s,
    soil B, T1 (§3.2.3): S_S = 1.40 − 0.40·2.4·0.35 = 1.064, C_C = 1.10·0.35^−0.20, T_C =
    C_C·0.35 s, T_D = 4·0.35 + 1.6 = 3.0 s; T_C < 1 s < T_D: S_e = a_g·S_S·F0·T_C/1 s."""
    from audit.engine.design.margins import margins_stripes
    from audit.engine.design.settings import MarginsSettings
    from audit.engine.shared.runtime import Runtime
    from audit.engine.shared.sites import with_ntc_site
    t_c = 1.10 * 0.35 ** -0.20 * 0.35
    by_hand = 0.35 * 1.064 * 2.4 * t_c / 1.0
    im = IntensityMeasure.parse("sa:1.0")
    ntc_only = with_ntc_site(seed_suite, 0.35, 2.4, 0.35, "B", "T1")
    entry = next(e for e in ntc_only if e.motion is not None)
    assert im.of_ntc_site(entry.site) == pytest.approx(by_hand, rel=1e-12)
    assert IntensityMeasure.parse("pga").of_ntc_site(entry.site) == pytest.approx(0.35 * 1.064)
    assert IntensityMeasure.parse("pgv").of_ntc_site(entry.site) is None
    settings = MarginsSettings.parse(im="sa:1.0", alpha_deg=(15.0,), size_s=(2.0,))
    run = margins_stripes(get_procedures("ntc2018"), ntc_only, settings, Runtime(jobs=2))
    assert run.settings.design_im == pytest.approx(by_hand, rel=1e-12)
    assert run.mce_im is None  # NTC's intensity scales its site; it is not FEMA P695's MCE
    # NTC's answer now changes along the stripes: not overturning low, overturning high
    predicted = run.predicted["ntc2018"][:, :, 0]  # (record, stripe)
    assert not predicted[:, 0].any() and predicted[:, -1].all()
