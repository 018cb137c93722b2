"""A site's seismic hazard curve, as every reader of :mod:`records.hazard` returns it.

A hazard curve gives, for ascending levels of one intensity measure, the mean annual rate at
which the level is exceeded at one site. The readers check a curve once, here, and name the
file and the field of anything wrong.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from audit.errors import InputError

#: Sites are matched by longitude and latitude within this distance in each [degrees].
SITE_TOLERANCE_DEG = 1e-3
#: Highest level a curve may give at :data:`PLAUSIBLE_RATE` [g]: the largest mapped MCE_R
#: accelerations are about 3 g (S_S near faults), as the bound on ``site`` says
#: (audit.engine.shared.design_site.MAX_SITE_G); a curve above it there is in cm/s² or m/s².
MAX_PLAUSIBLE_LEVEL_G = 5.0
#: The annual rate of the MCE_R, 2 % in 50 years [1/yr].
PLAUSIBLE_RATE = 1.0 / 2475.0

# PGA; SA(1.0) as OpenQuake writes it; SA1P0 / SA0P2 as the USGS services write it
_SA_OPENQUAKE = re.compile(r"^SA\(\s*([0-9.]+(?:[eE][-+]?\d+)?)\s*\)$")
_SA_USGS = re.compile(r"^SA(\d+)P(\d+)$")


def parse_imt(text: str, where: str) -> tuple[str, float | None]:
    """``("PGA", None)`` or ``("SA", T)`` [s] of an IMT written ``PGA``, ``SA(1.0)`` or
    ``SA1P0``; InputError naming ``where`` otherwise (PGV and other measures are not read)."""
    name = str(text).strip().upper()
    if name == "PGA":
        return "PGA", None
    period = math.nan
    if match := _SA_OPENQUAKE.match(name):
        period = float(match.group(1))
    elif match := _SA_USGS.match(name):
        period = float(f"{match.group(1)}.{match.group(2)}")
    if math.isfinite(period) and period > 0:
        return "SA", period
    raise InputError(f"{where}: imt: '{text}' is not read; expected PGA or SA(T) with T in s "
                     "(the curve must be of an acceleration in g)")


@dataclass(frozen=True)
class HazardCurve:
    """Mean annual rate of exceedance of each level of one intensity measure at one site.

    Attributes
    ----------
    imt : str
        ``PGA`` or ``SA``.
    period_s : float or None
        The period of ``SA`` [s]; None for PGA.
    im_g : numpy.ndarray
        Intensity levels, ascending [g].
    annual_rate : numpy.ndarray
        λ(im): mean annual rate of exceeding each level [1/yr], non-increasing; exactly 0 at
        levels the source says are never exceeded (only at the top).
    source : str
        Where the curve comes from: file, tool, and what the file says of it.
    site : (float, float) or None
        Longitude, latitude of the site [degrees]; None when the file does not say.
    """

    imt: str
    period_s: float | None
    im_g: np.ndarray
    annual_rate: np.ndarray
    source: str
    site: tuple | None = None

    @property
    def im_name(self) -> str:
        """``PGA`` or ``SA(T)``, T in s."""
        return "PGA" if self.imt == "PGA" else f"SA({float(self.period_s)})"

    def im_at_rate(self, annual_rate: float, field: str = "return_period") -> float:
        """The level [g] exceeded at ``annual_rate`` [1/yr]: the curve interpolated log–log
        (a power law between its levels, as the risk integral reads it),

        .. math:: \\ln im = \\ln im_i + \\frac{\\ln \\lambda - \\ln \\lambda_i}
                  {\\ln \\lambda_{i+1} - \\ln \\lambda_i} \\ln\\frac{im_{i+1}}{im_i}

        between the levels whose rates bracket λ. InputError naming ``field`` (the argument
        that gave λ: ``return_period`` or ``poe``) when λ lies outside the curve's positive
        rates (the curve says nothing there); on a flat stretch of the curve, its highest
        level of that rate."""
        positive = self.annual_rate > 0
        levels, rates = self.im_g[positive], self.annual_rate[positive]
        if not rates[-1] <= annual_rate <= rates[0]:
            raise InputError(
                f"{field}: the hazard curve ({self.source}) covers annual rates "
                f"{rates[-1]:.3g} to {rates[0]:.3g} /yr (return periods {1 / rates[0]:.3g} to "
                f"{1 / rates[-1]:.3g} years), not {annual_rate:.3g} /yr", field)
        # rates fall with the level: search the reversed (ascending) rates, whose first one
        # ≥ λ is, on a flat stretch at λ, the stretch's highest level
        x, y = np.log(rates[::-1]), np.log(levels[::-1])
        j = int(np.searchsorted(x, math.log(annual_rate), side="left"))
        if j == 0:  # λ is the lowest rate: the highest level exceeded at all
            return float(levels[-1])
        t = (math.log(annual_rate) - x[j - 1]) / (x[j] - x[j - 1])
        return float(np.exp(y[j - 1] + t * (y[j] - y[j - 1])))

    @classmethod
    def checked(cls, imt: str, levels, rates, source: str, site=None,
                where: str | None = None) -> HazardCurve:
        """A curve from a file's levels [g] and annual rates [1/yr], checked: InputError naming
        ``where`` (the file) and the field when levels are not positive and ascending, a rate
        is negative or not a number, the rates grow with the level, or fewer than two levels
        have a positive rate."""
        where = where or source
        kind, period = parse_imt(imt, where)
        levels = np.asarray(levels, dtype=float)
        rates = np.asarray(rates, dtype=float)
        if levels.ndim != 1 or levels.size < 2 or levels.size != rates.size:
            raise InputError(f"{where}: levels: expected as many levels as rates, at least 2; "
                             f"got {levels.size} levels and {rates.size} rates")
        if not (np.all(np.isfinite(levels)) and np.all(levels > 0)
                and np.all(np.diff(levels) > 0)):
            raise InputError(f"{where}: levels: intensity levels must be positive and ascending "
                             f"[g], got {_few(levels)}")
        bad = np.flatnonzero(~(rates >= 0) | ~np.isfinite(rates))
        if bad.size:
            raise InputError(f"{where}: rate at {levels[bad[0]]:g} g: expected a finite rate ≥ 0, "
                             f"got {rates[bad[0]]:g}")
        rising = np.flatnonzero(np.diff(rates) > 0)
        if rising.size:
            j = rising[0]
            raise InputError(f"{where}: rate at {levels[j + 1]:g} g: the curve rises "
                             f"({rates[j]:.4g} at {levels[j]:g} g, {rates[j + 1]:.4g} at "
                             f"{levels[j + 1]:g} g); a hazard curve never does")
        if np.count_nonzero(rates > 0) < 2:
            raise InputError(f"{where}: rates: fewer than two levels are ever exceeded; there is "
                             "no curve to integrate")
        implausible = np.flatnonzero((levels > MAX_PLAUSIBLE_LEVEL_G) & (rates >= PLAUSIBLE_RATE))
        if implausible.size:
            j = implausible[-1]
            raise InputError(f"{where}: levels: {levels[j]:.3g} g exceeded every "
                             f"{1 / rates[j]:,.0f} years is beyond any site's hazard (limit "
                             f"{MAX_PLAUSIBLE_LEVEL_G:g} g at 2,475 years): the levels must be "
                             "in g, not cm/s² or m/s²")
        return cls(kind, period, levels, rates, source, site)


def match_site(sites, site, where: str) -> int:
    """Index of the row of ``sites`` (pairs lon, lat) at ``site`` (lon, lat) within
    :data:`SITE_TOLERANCE_DEG`, the nearest if several; with ``site`` None, the only row.
    InputError naming ``where`` and the site field otherwise."""
    sites = np.asarray(sites, dtype=float).reshape(-1, 2)
    listed = ", ".join(f"({lon:g}, {lat:g})" for lon, lat in sites[:8]) \
        + (", ..." if len(sites) > 8 else "")
    if site is None:
        if len(sites) == 1:
            return 0
        raise InputError(f"{where}: site: the file holds {len(sites)} sites ({listed}); say "
                         "which one (lon, lat)")
    lon, lat = (float(v) for v in site)
    distance = np.maximum(np.abs(sites[:, 0] - lon), np.abs(sites[:, 1] - lat))
    if not np.any(distance <= SITE_TOLERANCE_DEG):
        raise InputError(f"{where}: site: no curve at ({lon:g}, {lat:g}) within "
                         f"{SITE_TOLERANCE_DEG:g}°; the file has {listed}")
    return int(np.argmin(distance))


def read_text(path) -> str:
    """A hazard file's text; InputError naming the file when it cannot be read as UTF-8."""
    try:
        return Path(path).read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise InputError(f"{path}: file not found") from None
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: encoding: not UTF-8 text (byte {exc.start + 1})") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror}") from None


def number(text, where, field: str) -> float:
    """``text`` as a float; InputError naming ``where`` and ``field`` otherwise."""
    try:
        return float(text)
    except (TypeError, ValueError):
        raise InputError(f"{where}: {field}: expected a number, got '{text}'") from None


def _few(values) -> str:
    shown = ", ".join(f"{v:g}" for v in values[:6])
    return shown + (", ..." if len(values) > 6 else "")


__all__ = ["HazardCurve", "parse_imt", "match_site", "read_text", "number", "SITE_TOLERANCE_DEG"]
