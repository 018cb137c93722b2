"""What ``audit rock`` prints: one block's exact response to one motion, in a few lines."""

from __future__ import annotations

import math


def rocking_text(solution, motion, alpha_deg: float, block_m: str | None,
                 friction_mu: float | None, slides: bool | None) -> str:
    """The lines ``audit rock`` prints, each ending in a newline.

    Parameters
    ----------
    solution : audit.physics.rocking.RockingHistory
        The exact response (its block: p [rad/s], α [rad], r, R [m]).
    motion : records.GroundMotion
        The excitation (its id, component and source).
    alpha_deg : float
        The block's slenderness as given [degrees].
    block_m : str or None
        ``WIDTHxHEIGHT`` [m] when the block was given by its dimensions.
    friction_mu, slides : float or None, bool or None
        The base's friction coefficient μ [-] checked and whether the block slides (None
        without μ).
    """
    rigid = solution.block
    state = (f"OVERTURNS at t = {solution.overturn_time:.3f} s" if solution.overturned
             else "survives" if solution.uplifted else "does not uplift (PGA ≤ g tan α)")
    source = "" if motion.source in ("", "analytic pulse") else f" — {motion.source}"
    # after overturning there is no "after the excitation"
    after = ("n/a" if solution.overturned
             else f"{solution.peak_rotation_after_excitation / rigid.alpha:.4f} α")
    free = ("n/a" if math.isnan(solution.peak_rotation_free_vibration)
            else f"{solution.peak_rotation_free_vibration / rigid.alpha:.4f} α (largest turning point)")
    cycles = ", ".join(f"{d:.3f}" for d in solution.cycle_durations[:8]) or "—"
    more = " …" if solution.cycle_durations.size > 8 else ""
    friction = solution.required_friction
    text = ((f"Block {block_m} m (width × height): " if block_m else "Block ")
            + f"p = {rigid.p:.4g} rad/s (2π/p = {rigid.size_s:.4g} s, R = {rigid.radius:.3g} m), "
            f"α = {alpha_deg:g}°, r = {rigid.r:.4f}\n"
            f"Excitation: {motion.id}: {motion.component}{source}\n"
            f"Result: {state}\n"
            f"  peak |θ|                   {solution.peak_rotation:.6g} rad = "
            f"{solution.peak_rotation_ratio:.4f} α\n"
            f"  peak |θ| after excitation  {after}\n"
            f"  free-vibration peak |θ|    {free}\n"
            f"  peak |θ'|                  {solution.peak_angular_velocity:.6g} rad/s\n"
            f"  impacts                    {solution.n_impacts}\n"
            f"  full rocking cycles [s]    {cycles}{more}\n"
            f"  required friction |H|/V    "
            f"{'n/a (jumps: V < 0)' if solution.jumps else f'{friction:.4f}'} "
            f"(tan α = {math.tan(rigid.alpha):.4f})"
            + ("" if slides is None else
               f"\n  {'with μ = ' + format(friction_mu, 'g'):<27}"
               f"{'SLIDES: pure rocking does not apply' if slides else 'rocks without sliding'}"))
    return text + "\n"


__all__ = ["rocking_text"]
