"""What the design-level audit computes (:mod:`audit.engine.design.margins`), checked once."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from audit import G
from audit.engine.shared import fields as check
from audit.engine.shared.blocks import Block, parse_blocks, within_limits
from audit.engine.shared.defaults import (DEFAULT_ALPHA_DEG, DEFAULT_FREE_MOTION_S, DEFAULT_IM,
                                   DEFAULT_MARGINS_SIZES, DEFAULT_RESTITUTION,
                                   DEFAULT_RISK_TARGET, DEFAULT_SITE_LEVEL,
                                   SITE_LEVELS)
from audit.engine.shared.grid import size_grid
from audit.engine.shared.intensity import IntensityMeasure
from audit.errors import InputError
from audit.physics.block import Restitution

#: The fields :meth:`MarginsSettings.parse` takes, and their defaults (``im``: None, the hazard
#: curve's IMT, else ``DEFAULT_IM``; ``size_s``: None, the default grid; ``stripes``: None,
#: levels around the design intensity).
MARGINS_DEFAULTS = {"im": None, "stripes": None, "alpha_deg": DEFAULT_ALPHA_DEG,
                    "size_s": None, "blocks": (), "restitution": DEFAULT_RESTITUTION,
                    "free_motion_s": DEFAULT_FREE_MOTION_S, "required": True, "g": G,
                    "site_level": DEFAULT_SITE_LEVEL, "hazard": None, "site_location": None,
                    "risk_target": DEFAULT_RISK_TARGET, "hazard_imt": None}
MARGINS_FIELDS = tuple(MARGINS_DEFAULTS)


@dataclass(frozen=True)
class MarginsSettings:
    """What a design-level audit computes.

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

    Build it with :meth:`parse`, which checks every field once.
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
    def parse(cls, **values) -> MarginsSettings:
        """The settings of the given fields, each checked once (InputError naming the field).

        Parameters
        ----------
        im : str or IntensityMeasure
            ``pga`` [g], ``pgv`` [m/s] or ``sa:T``.
        stripes : float or sequence of float, optional
            Positive, finite, increasing, each once.
        alpha_deg, size_s : float or sequence of float
        blocks : sequence of str or objects with ``width_m``, ``height_m``
            ``"WIDTHxHEIGHT"`` [m], or a block (e.g. :class:`audit.Block`).
        restitution : str, float or Restitution
        free_motion_s : float
        required : bool
        g : float
        site_level : {"mce", "design"}
        hazard : records.hazard.HazardCurve, str or pathlib.Path, optional
            A hazard curve or its file (OpenQuake, USGS or plain CSV); its IMT sets ``im``
            when ``im`` is not given, and must be ``im`` when it is.
        site_location : (float, float), optional
            Longitude, latitude [degrees] of the site in a hazard file of several sites.
        risk_target : float or str
            In (0, 1): 0.02 or '2%'.
        hazard_imt : str, optional
            The IMT of a hazard file of several (``PGA``, ``SA(1.0)``); without it, ``im``'s.
        """
        check.unknown("the design-level audit", values, MARGINS_FIELDS)
        value = {**MARGINS_DEFAULTS, **values}
        im = value["im"]
        g = check.number("g", value["g"], "a positive acceleration in m/s²", 0, low_open=True)
        stripes = value["stripes"]
        if stripes is not None:
            stripes = check.numbers("stripes", stripes, "positive finite intensity levels", 0,
                                    low_open=True)
            if any(b <= a for a, b in zip(stripes, stripes[1:])):
                raise InputError(f"stripes: expected increasing intensity levels, each once, "
                                 f"got {', '.join(f'{s:g}' for s in stripes)}", "stripes")
        sizes = value["size_s"]
        if value["site_location"] is not None and value["hazard"] is None:
            raise InputError("site_location: a site of the hazard file; no hazard given",
                             "site_location")
        if not isinstance(value["site_level"], str) or value["site_level"] not in SITE_LEVELS:
            raise InputError(f"site_level: expected {' or '.join(SITE_LEVELS)}, got "
                             f"{value['site_level']!r}", "site_level")
        risk_target = check.probability("risk_target", value["risk_target"])
        hazard = value["hazard"]
        if not isinstance(im, (str, IntensityMeasure, type(None))):
            IntensityMeasure.parse(im)  # refused, naming im
        location = (None if value["site_location"] is None
                    else check.lon_lat("site_location", value["site_location"]))
        if hazard is not None:  # read and checked before any work
            from audit.engine.design.risk import site_hazard
            hazard, im = site_hazard(hazard, location, risk_target, im, value["hazard_imt"])
        elif value["hazard_imt"] is not None:
            raise InputError("hazard_imt: the IMT of a hazard file; no hazard given",
                             "hazard_imt")
        im = DEFAULT_IM if im is None else im
        return cls(
            im=im if isinstance(im, IntensityMeasure) else IntensityMeasure.parse(im),
            stripes=stripes,
            alpha_deg=_grid("alpha_deg", value["alpha_deg"], "slendernesses between 0 and 45 "
                            "degrees", 0, 45),
            size_s=(tuple(float(s) for s in size_grid(*DEFAULT_MARGINS_SIZES)) if sizes is None
                    else _grid("size_s", sizes, "positive block sizes 2π/p in s", 0,
                               math.inf)),
            blocks=_blocks(value["blocks"], g),
            restitution=(value["restitution"] if isinstance(value["restitution"], Restitution)
                         else Restitution.parse(value["restitution"], "restitution")),
            free_motion_s=check.number("free_motion_s", value["free_motion_s"],
                                       "a duration ≥ 0 s", 0),
            required=check.flag("required", value["required"]),
            g=g, site_level=value["site_level"], hazard=hazard,
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


__all__ = ["MarginsSettings", "MARGINS_DEFAULTS", "MARGINS_FIELDS", "SITE_LEVELS"]
