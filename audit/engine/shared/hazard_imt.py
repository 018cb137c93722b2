"""The hazard files' names of intensity measures (``PGA``, ``SA(1.0)``, ``SA1P0``) and
``--im``'s (``pga``, ``sa:1``), each to the other: a file of several IMTs is read at the one
the user names either way."""

from __future__ import annotations

from audit.errors import InputError


def imt_of(im: str) -> str | None:
    """The hazard files' IMT (``PGA``, ``SA(1.0)``) of an intensity measure as ``--im`` names
    it (``pga``, ``sa:1``); None for one no hazard file gives (PGV) or not an IM at all (the
    settings refuse those with their own message).

    Parameters
    ----------
    im : str
        Intensity measure as ``--im`` names it.
    """
    from audit.engine.shared.intensity import IntensityMeasure
    try:
        mine = IntensityMeasure.parse(im)
    except InputError:
        return None
    return {"pga": "PGA", "sa": f"SA({mine.period_s})"}.get(mine.kind)


def im_of_imt(imt: str) -> str:
    """``--im``'s name (``pga``, ``sa:1``) of a hazard file's IMT (``PGA``, ``SA(1.0)``,
    ``SA1P0``); InputError naming ``hazard.imt`` otherwise.

    Parameters
    ----------
    imt : str
        A hazard file's IMT.
    """
    from records.hazard import parse_imt
    try:
        kind, period = parse_imt(imt, "hazard.imt")
    except InputError as exc:
        raise InputError(str(exc), "hazard.imt") from None
    return "pga" if kind == "PGA" else f"sa:{period:g}"


__all__ = ["imt_of", "im_of_imt"]
