"""What the design-level audit computes (:mod:`audit.engine.design.margins`), checked once."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from audit.engine.shared import fields as check
from audit.engine.shared.blocks import Block, parse_blocks, within_limits
from audit.engine.shared.defaults import (DEFAULT_ALPHA_DEG, DEFAULT_IM, DEFAULT_MARGINS_SIZES,
                                          DEFAULT_RISK_TARGET, DEFAULT_SITE_LEVEL, SITE_LEVELS)
from audit.engine.shared.grid import size_grid
from audit.engine.shared.intensity import IntensityMeasure
from audit.errors import InputError
from audit.physics.block import Restitution


@dataclass(frozen=True)
class MarginsSettings:
    """What a design-level audit computes.

    Build it with :meth:`parse`, which checks every field once.

    Attributes
    ----------
    im : IntensityMeasure
    stripes : tuple of float or None
        Intensity levels, increasing [unit of ``im``]; None: the default levels around the
        design intensity (or the suite's median).
    alpha_deg, size_s : tuple of float
        Slendernesses [degrees] and sizes 2π/p [s] of the grid (either may be empty when
        ``blocks`` are given).
    blocks : tuple of audit.engine.shared.blocks.Block
        Blocks by their dimensions, beside the grid.
    restitution : Restitution
    free_motion_s, g : float
        Free motion after each record [s]; gravity [m/s²].
    required : bool
        Also search the required slenderness of each size.
    site_level : {"mce", "design"}
        The hazard level of the site's spectral values: the CMR is over the MCE intensity
        (:data:`SITE_LEVELS`).
    hazard : records.hazard.HazardCurve or None
        The site's hazard curve: the annual rate of overturning of every block and the
        slenderness each size needs for ``risk_target`` (:mod:`audit.engine.design.margins_risk`).
    risk_target : float
        Probability of overturning in 50 years the risk-targeted slenderness meets [-].
    """

    im: IntensityMeasure
    stripes: tuple | None
    alpha_deg: tuple
    size_s: tuple
    blocks: tuple
    restitution: Restitution
    free_motion_s: float
    required: bool
    g: float
    site_level: str = DEFAULT_SITE_LEVEL
    hazard: object = None
    risk_target: float = DEFAULT_RISK_TARGET

    @classmethod
    def parse(cls, *, im=None, stripes=None, alpha_deg=DEFAULT_ALPHA_DEG, size_s=None,
              blocks=(), solver=None, required: bool = True,
              site_level: str = DEFAULT_SITE_LEVEL, hazard=None) -> MarginsSettings:
        """The settings of the given fields, each checked once (InputError naming the
        argument, or the group's field: ``solver.g``, ``hazard.imt``).

        Parameters
        ----------
        im : str or IntensityMeasure, optional
            ``pga`` [g], ``pgv`` [m/s] or ``sa:T``; default the hazard curve's IMT, else
            ``DEFAULT_IM``.
        stripes : float or sequence of float, optional
            Positive, finite, increasing, each once; None: the fixed lattice.
        alpha_deg, size_s : float or sequence of float
            ``size_s`` None: the default grid.
        blocks : sequence of str or objects with ``width_m``, ``height_m``
            ``"WIDTHxHEIGHT"`` [m], or a block (e.g. :class:`audit.Block`).
        solver : audit.engine.shared.solver.Solver, optional
            The exact solver's impact model, free motion and g (``vertical`` refused).
        required : bool
        site_level : {"mce", "design"}
            The site's hazard level (``site.level``).
        hazard : audit.engine.shared.hazard.Hazard, records.hazard.HazardCurve, str or path
            The site's hazard (:meth:`Hazard.parse <audit.engine.shared.hazard.Hazard.parse>`):
            its curve's IMT sets ``im`` when ``im`` is not given, and must be ``im`` when it
            is; its risk target the risk-targeted slenderness's.
        """
        from audit.engine.shared.design_site import level_of
        from audit.engine.shared.hazard import Hazard
        from audit.engine.shared.solver import Solver
        solver = Solver.parse(solver, "margins")
        if stripes is not None:
            stripes = check.numbers("stripes", stripes, "positive finite intensity levels", 0,
                                    low_open=True)
            if any(b <= a for a, b in zip(stripes, stripes[1:])):
                raise InputError(f"stripes: expected increasing intensity levels, each once, "
                                 f"got {', '.join(f'{s:g}' for s in stripes)}", "stripes")
        site_level = level_of(site_level, "site.level")
        hazard = Hazard.parse(hazard, "margins")
        risk_target = DEFAULT_RISK_TARGET if hazard is None else hazard.risk_target
        if hazard is not None and hazard.curve is None:
            hazard = None  # a risk target alone: no curve to read it on
        if not isinstance(im, (str, IntensityMeasure, type(None))):
            IntensityMeasure.parse(im)  # refused, naming im
        curve = None
        if hazard is not None:  # read and checked before any work
            from audit.engine.design.risk import site_hazard
            curve, im = site_hazard(hazard, im)
        im = DEFAULT_IM if im is None else im
        return cls(
            im=im if isinstance(im, IntensityMeasure) else IntensityMeasure.parse(im),
            stripes=stripes,
            alpha_deg=_grid("alpha_deg", alpha_deg, "slendernesses between 0 and 45 degrees",
                            0, 45),
            size_s=(tuple(float(s) for s in size_grid(*DEFAULT_MARGINS_SIZES)) if size_s is None
                    else _grid("size_s", size_s, "positive block sizes 2π/p in s", 0,
                               math.inf)),
            blocks=_blocks(blocks, solver.g), restitution=solver.restitution,
            free_motion_s=solver.free_motion_s, required=check.flag("required", required),
            g=solver.g, site_level=site_level, hazard=curve,
            risk_target=risk_target)


def _grid(field, value, what, low, high) -> tuple:
    """A grid axis: may be empty (blocks are then given by their dimensions alone)."""
    if value is not None and not isinstance(value, (str, bytes)) and hasattr(value, "__len__") \
            and len(value) == 0:
        return ()
    return check.numbers(field, value, what, low, high, low_open=True, high_open=True)


def _blocks(items, g: float) -> tuple:
    """``blocks`` as Blocks named by their dimensions: ``"WIDTHxHEIGHT"`` texts or Blocks,
    within the limits every command applies."""
    if isinstance(items, (str, Block)) or not hasattr(items, "__iter__"):
        items = [items]
    blocks = []
    for item in items:
        if isinstance(item, str):
            blocks += parse_blocks([item], "blocks", g)
        elif isinstance(item, Block):
            # margins' tables give a block by its dimensions (width_m, height_m), not a name
            blocks.append(within_limits(replace(item, name=""), "blocks", "blocks"))
        else:
            raise InputError(f"blocks: expected 'WIDTHxHEIGHT' in metres (e.g. '0.8x2.0') or a "
                             f"Block, got {item!r}", "blocks")
    return tuple(blocks)


__all__ = ["MarginsSettings", "SITE_LEVELS"]
