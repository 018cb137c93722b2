"""FEMA P695's acceptance fits each sized block once, without the bootstrap, against the slow
path it replaced: the whole design-level audit of every sized block, one block per guideline,
under each impact model."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pandas as pd

from audit.engine.design.margins import margins_tables
from audit.engine.design.settings import MarginsSettings
from audit.engine.design.tables import exact_fit
from audit.engine.design.p695_acceptance import counted_fit, p695_acceptance, sized_blocks
from audit.engine.shared.blocks import Block
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.solver import Solver
from audit.physics.block import Restitution
from audit.engine.shared.sites import with_design_site
from records import RecordEntry, RecordSuite, one_pulse

LEVELS_G = np.geomspace(0.15, 1.2, 9)


def _suite():
    entries = tuple(RecordEntry(f"cosine_{t:g}s", one_pulse("cosine", 0.5, t, record_id=f"c{t:g}"))
                    for t in (1.0, 2.0, 3.0))
    return with_design_site(RecordSuite(entries, "three one-cosine pulses"), 1.5, 0.9,
                            override=True)


def _settings(restitution="housner", **values):
    return MarginsSettings.parse(**{"im": "pga", "stripes": LEVELS_G, "alpha_deg": (15.0,),
                                    "size_s": [3.0],
                                    "solver": Solver(restitution, free_motion_s=8.0), **values})


def test_blocks_sized_alike_share_their_fit_and_every_value_is_the_full_audits():
    suite = _suite()
    # two guidelines size the same block at 3 s (12°), a third another (16°), one more a
    # 2.5 s block; the exact curve is no guideline
    required = pd.DataFrame({
        "procedure": ["priestley1978", "fema356", "housner1963", "fema356", "exact@0.50"],
        "size_s": [3.0, 3.0, 3.0, 2.5, 3.0], "required_alpha_deg": [12.0, 12.0, 16.0, 12.0, 9.0],
        "exact_overturning_share": [0.0] * 5})
    table, _ = p695_acceptance(suite, _settings(), Runtime(), required)
    assert list(table["procedure"]) == ["priestley1978", "fema356", "housner1963", "fema356"]
    sized = sized_blocks(required, 9.81)
    blocks = tuple(Block.of_dimensions(float(w), float(h), g=9.81)
                   for w, h in zip(sized["width_m"], sized["height_m"]))
    # the slow path: margins_tables of the sized blocks (duplicates and all, bootstrap and all)
    full = {v: margins_tables([], suite,
                              replace(_settings(), alpha_deg=(), size_s=(), blocks=blocks,
                                      restitution=Restitution.parse(v), required=False),
                              Runtime()).fragility for v in ("housner", "x0.9", "x0.8")}
    base = full["housner"]
    assert base["median"].notna().all()  # every sized block has a fit to compare
    for column in ("median", "cmr", "cmr_bound"):
        assert list(table[column]) == list(base[column])  # equal, not close
    assert list(table["beta_rtr"]) == list(base["beta"])
    log_ratios = np.log([full[v]["median"].to_numpy() / base["median"].to_numpy()
                         for v in ("x0.9", "x0.8")])
    assert list(table["beta_mdl"]) == list(np.sqrt(np.mean(log_ratios ** 2, axis=0)))
    assert table.loc[0, "median"] == table.loc[1, "median"] != table.loc[2, "median"]


def test_a_blocks_counts_are_fitted_once_and_the_fit_is_the_slow_paths():
    """counted_fit against exact_fit with its bands, block by block: equal numbers, a fit
    reused only for the same counts (the same per stripe, however the records fall), and
    no fit where the counts fix no median."""
    levels = np.geomspace(0.2, 2.0, 6)
    rng = np.random.default_rng(7)
    # 12 records × 6 stripes × 5 blocks; block 1 shuffles block 0's records within each
    # stripe (same counts), block 3 one more overturning at one stripe, block 4 none at all
    over = rng.random((12, 6, 5)) < np.linspace(0.05, 0.95, 6)[None, :, None]
    over[:, :, 1] = rng.permuted(over[:, :, 0], axis=0)
    over[:, :, 3] = over[:, :, 0]
    over[np.flatnonzero(~over[:, 2, 0])[0], 2, 3] = True
    over[:, :, 4] = False
    known = {}
    fits = [counted_fit(levels, over[:, :, b], known) for b in range(5)]
    for b in range(4):
        slow = exact_fit(levels, over[:, :, b])
        assert (fits[b].median, fits[b].beta) == (slow.median, slow.beta)
    assert fits[1] is fits[0] and fits[3] is not fits[0]
    assert fits[3].median != fits[0].median
    assert fits[4] is None and exact_fit(levels, over[:, :, 4]) is None
    assert len(known) == 4  # blocks 0 (and 1), 2, 3 and 4
