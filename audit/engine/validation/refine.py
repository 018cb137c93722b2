"""The fine grid solved along the region a coarser grid's outcomes allow.

One per cent of α flips several of a hundred outcomes, while the coarse grid steps 13 % in α
and 18 % in p; a fit on it can only land on its nodes, and a true block between two nodes
costs likelihood it would not cost on finer ones. The region (every lattice point within
:data:`REGION_DROP` of the best) is widened by one step of the coarser grid in f and p and solved
at half its step in ln p (f keeps its values: the outcomes hardly tell them apart). α and p
trade off along a ridge, so each new (f, p) gets its own α nodes, spread
over the α̂ the region holds at the neighbouring (f, p) of the coarser grid (widened by one of
its α steps and by 2σ of the largest dispersion of the 95 % set, which reaches beyond α̂): the
nodes follow the ridge instead of filling a rectangle. ``settings.refined_solves`` bounds the
blocks per test; p and f are thinned evenly where the region is too wide for their steps.
"""

from __future__ import annotations

import math

import numpy as np

from audit.engine.validation.grid import BlockGrid
from audit.engine.validation.profile import PROFILE_DROP_95

#: The region refined: lattice points this far below the best log-likelihood (the 95 % set's
#: 1.92, plus room for the coarser grid's misplacement of the optimum).
REGION_DROP = PROFILE_DROP_95 + 3.0
#: Fine grids solved in turn, each along the region the previous one allows.
REFINEMENTS = 3
#: The fine grid's steps as a share of the coarser grid's: ln p, f.
_P_SHARE, _F_SHARE = 0.5, 1.0
#: Fewest α nodes per (f, p), and the finest α step [ln α] worth solving.
_MIN_NODES, _FINEST_ALPHA_STEP = 8, 0.002


def _values(nodes, chosen, share, log):
    """New values over the chosen nodes widened by one node, at ``share`` of the step."""
    idx = np.flatnonzero(chosen)
    lo, hi = max(idx[0] - 1, 0), min(idx[-1] + 1, len(nodes) - 1)
    if lo == hi:
        return np.array([nodes[lo]])
    scale = np.log(nodes) if log else np.asarray(nodes, dtype=float)
    count = int(math.ceil((scale[hi] - scale[lo]) / (share * np.diff(scale).max()) - 1e-9)) + 1
    values = np.linspace(scale[lo], scale[hi], count)
    return np.exp(values) if log else values


def _thin(values, count, log):
    if values.size <= count:
        return values
    scale = np.log(values) if log else values
    new = np.linspace(scale[0], scale[-1], max(count, 1 if values.size == 1 else 2))
    return np.exp(new) if log else new


def refined_blocks(blocks, fits, budget: int) -> BlockGrid:
    """The fine grid along the region of ``fits`` (BlockFits on ``blocks``).

    Parameters
    ----------
    blocks : BlockGrid
        The coarser grid.
    fits : iterable of BlockFit
        The fits whose regions are covered.
    budget : int
        The most blocks per test.

    Returns
    -------
    BlockGrid
    """
    f, p = blocks.restitution_factors, blocks.p_rad_s
    # below the lattice's own best (the continuous refinement may lie above every lattice point)
    region = [fit.surface.log_likelihood >= fit.surface.log_likelihood.max() - REGION_DROP
              for fit in fits]
    keep_f = np.any([r.any(axis=(1, 2, 3)) for r in region], axis=0)
    keep_p = np.any([r.any(axis=(0, 2, 3)) for r in region], axis=0)
    new_f = _values(f, keep_f, _F_SHARE, log=False)
    new_p = _values(p, keep_p, _P_SHARE, log=True)
    while new_f.size * new_p.size * _MIN_NODES > budget and new_f.size * new_p.size > 1:
        shrink = math.sqrt(budget / (new_f.size * new_p.size * _MIN_NODES))
        new_f = _thin(new_f, max(2, math.floor(new_f.size * shrink)) if f.size > 1 else 1, False)
        new_p = _thin(new_p, max(2, math.floor(new_p.size * shrink)), True)
        if new_f.size <= 2 and new_p.size <= 2:
            break
    reach = 2.0 * max(max(fit.sigma, fit.surface.sigma[(
        fit.surface.log_likelihood >= fit.log_likelihood - PROFILE_DROP_95).any(
            axis=(0, 1, 2))].max(initial=0.0)) for fit in fits)
    log_alpha = np.log(blocks.alpha_deg)
    step = float(np.diff(log_alpha, axis=-1).max())
    bounds = (log_alpha.min(), log_alpha.max())
    medians = [np.log(np.degrees(np.exp(fit.surface.log_medians))) for fit in fits]
    df = np.diff(f).max() if f.size > 1 else 1.0
    dp = np.diff(np.log(p)).max() if p.size > 1 else 1.0
    spans = np.empty((new_f.size, new_p.size, 2))
    for a, fa in enumerate(new_f):
        for b, pb in enumerate(new_p):
            near = (np.abs(f - fa) <= df + 1e-9)[:, None] & \
                   (np.abs(np.log(p / pb)) <= dp + 1e-9)[None, :]
            held = np.concatenate([m[r[near].any(axis=(0, 2))] for m, r in zip(medians, region)])
            if held.size == 0:  # nothing of the region nearby: the whole region's α̂
                held = np.concatenate([m[r.any(axis=(0, 1, 3))] for m, r in zip(medians, region)])
            spans[a, b] = (max(held.min() - reach - step, bounds[0]),
                           min(held.max() + reach + step, bounds[1]))
    widest = float((spans[..., 1] - spans[..., 0]).max())
    nodes = max(_MIN_NODES, min(budget // (new_f.size * new_p.size),
                                int(math.ceil(widest / _FINEST_ALPHA_STEP)) + 1))
    alpha = np.exp(np.linspace(spans[..., 0], spans[..., 1], nodes, axis=-1))
    return BlockGrid(np.round(new_f, 4), np.round(new_p, 5), alpha, blocks.search_alpha_deg,
                     blocks.search_p_rad_s)


__all__ = ["refined_blocks", "REGION_DROP", "REFINEMENTS"]
