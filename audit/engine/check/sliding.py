"""Sliding in ``audit check``: which mode governs an object on a base of friction coefficient μ,
with the ground truth's sliding model (:func:`audit.engine.shared.ground_truth.slides`).

The exact answer is Housner's pure rocking: the base holds the pivot whatever the horizontal
force. Pure rocking needs, at every instant, a friction coefficient |H|/V of the pivot's
reactions (:func:`audit.physics.rocking.motion_equation.pivot_reactions`); for a block at rest
that is |üg|/(g + üv), and at uplift tan α. So:

* tan α > μ: the base cannot pass the force that would lift the block (uplift needs
  |H|/V = tan α), so the block slides before it can rock (Shenton 1996, J. Eng. Mech. 122(7),
  the slide mode): under every record that needs more than μ it slides and never rocks, and
  the rocking answer does not apply to it; records that need less leave it at rest.
* tan α ≤ μ: it rocks, and a record whose rocking response needs more than μ somewhere makes
  it slide while rocking; that record's rocking answer assumes a base that holds.

The friction each record needs is that of its pure-rocking response at the site's intensity,
max |H|/V over the response (infinite where V < 0: the block would jump). Without μ the check
assumes no sliding and says what friction the records need.
"""

from __future__ import annotations

import math

import numpy as np

from audit.engine.shared.ground_truth import slides
from audit.physics.rocking import RockingOptions, rocking_blocks

#: The modes ``check.json`` names.
ROCKING, SLIDING, SLIDE_ROCK, REST = "rocking", "sliding", "rocking, sliding in some records", \
    "at rest"


def required_friction(motion, factor: float, blocks, restitution, g: float,
                      free_motion_s: float, jobs: int) -> np.ndarray:
    """max |H|/V [-] of each block's pure-rocking response to ``motion`` × ``factor`` (the
    record at the site's intensity), inf where the block would jump.

    Parameters
    ----------
    motion : records.GroundMotion
        The record.
    factor : float
        Scale factor to the site's intensity [-].
    blocks : BlockList
        The blocks.
    restitution : Restitution
        The impact model.
    g : float
        Acceleration of gravity [m/s²].
    free_motion_s : float
        Free-motion time after the record [s].
    jobs : int
        Solver threads.
    """
    alpha_rad = np.empty(len(blocks))
    for alpha, index in blocks.groups():
        alpha_rad[index] = alpha
    peaks = rocking_blocks(motion.scaled(float(factor)), blocks.size_s, alpha_rad,
                           r=restitution, options=RockingOptions(g, free_motion_s), jobs=jobs,
                           reactions=True)
    return np.asarray(peaks.required_friction, dtype=float)


def _finite(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def sliding_answer(needed, record_ids, alpha_deg: float, friction: float | None) -> dict:
    """The ``sliding`` entry of ``check.json`` for one object.

    Parameters
    ----------
    needed : numpy.ndarray
        Friction each record's pure-rocking response needs at the site's intensity [-].
    record_ids : list of str
    alpha_deg : float
        The object's slenderness [degrees]; tan α is the friction uplift needs.
    friction : float or None
        μ of the base; None: no sliding assumed.
    """
    needed = np.asarray(needed, dtype=float)
    tan_alpha = math.tan(math.radians(alpha_deg))
    jumping = ~np.isfinite(needed)
    finite = needed[~jumping]
    median = float(np.median(needed)) if needed.size else math.nan  # inf sorts last
    out = {"friction": friction, "tan_alpha": tan_alpha,
           "required_friction_median": _finite(median),
           "required_friction_max": _finite(_largest(needed)),
           "required_friction_max_finite": _finite(float(finite.max())) if finite.size else None,
           "records_jumping": [r for r, j in zip(record_ids, jumping) if j]}
    if friction is None:
        out.update(mode=None, records_sliding=None, governs=False,
                   text=(f"It assumes no sliding: at the site's intensity its rocking under the "
                         f"records needs a friction coefficient μ of {_mu(median)} (median over "
                         f"records) up to {_mu(_largest(needed))}; below tan α = "
                         f"{tan_alpha:.2f} it would slide before it could rock."))
        return out
    slid = np.asarray(slides(needed, friction), dtype=bool)
    sliding = [r for r, s in zip(record_ids, slid) if s]
    n, k = len(record_ids), len(sliding)
    governs = 2 * k > n  # most records slide it: the sentence leads with sliding
    if tan_alpha > friction:
        mode = SLIDING if k else REST
        text = (f"On μ = {friction:g} it slides before it can rock (tan α = {tan_alpha:.2f} > μ: "
                f"the base cannot pass the force that would lift it): {k} of {n} records at the "
                "site's intensity slide it (its sliding displacement is not computed)."
                if governs else
                f"On μ = {friction:g} it slides before it can rock (tan α = {tan_alpha:.2f} > μ: "
                f"the base cannot pass the force that would lift it): {k} of {n} records at the "
                "site's intensity slide it, and the rocking answer above does not apply to it "
                "(its sliding displacement is not computed)." if k else
                f"On μ = {friction:g} it would slide before rocking (tan α = {tan_alpha:.2f} > "
                f"μ), but no record at the site's intensity needs more than μ: it stays at rest.")
    elif k:
        mode = SLIDING if governs else SLIDE_ROCK
        text = (f"On μ = {friction:g} sliding governs: it rocks (tan α = {tan_alpha:.2f} ≤ μ), "
                f"but {k} of {n} records at the site's intensity need more friction than μ (up "
                f"to {_mu(_largest(needed))}) and slide it while it rocks (its sliding "
                "displacement is not computed)." if governs else
                f"On μ = {friction:g} it rocks (tan α = {tan_alpha:.2f} ≤ μ), but {k} of {n} "
                f"records at the site's intensity need more friction than μ (up to "
                f"{_mu(_largest(needed))}): it slides while rocking under them, and their rocking "
                "answers assume a base that holds.")
    else:
        mode = ROCKING
        text = (f"On μ = {friction:g} rocking governs: no record at the site's intensity needs "
                f"more friction than μ (at most {_mu(_largest(needed))}).")
    out.update(mode=mode, records_sliding=sliding, governs=governs, text=text)
    return out


def _largest(needed) -> float:
    return float(np.max(needed)) if np.size(needed) else math.nan


def _mu(value: float) -> str:
    return "∞ (it would jump)" if math.isinf(value) else f"{value:.2f}"


__all__ = ["required_friction", "sliding_answer", "ROCKING", "SLIDING", "SLIDE_ROCK", "REST"]
