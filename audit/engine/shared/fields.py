"""Checks of one settings field each, for the settings objects' ``parse``: the value as a user
of the Python API may give it (a scalar where a list is expected, a list or an array), checked
once and returned in one type, or an InputError naming the field.

Light on purpose (no numpy import), so that the command line's start-up stays light.
"""

from __future__ import annotations

import math
from numbers import Real

from audit.errors import InputError


def _real(field: str, value, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, Real):
        raise InputError(f"{field}: expected {what}, got {value!r}", field)
    return float(value)


def number(field: str, value, what: str = "a number", low: float | None = None,
           high: float | None = None, *, low_open: bool = False,
           high_open: bool = False) -> float:
    """``value`` as a finite float in [low, high] (open ends where asked).

    Parameters
    ----------
    field : str
        The argument's name, which the message starts with and the error names.
    value :
        A real number (not a bool, not text such as ``'0.01 s'``).
    what : str
        What is expected, with its unit (``"a duration ≥ 0 s"``), for the message.
    low, high : float, optional
        Bounds, in the field's unit.
    low_open, high_open : bool
        Whether ``low`` and ``high`` themselves are refused.
    """
    number_ = _real(field, value, what)
    below = low is not None and (number_ <= low if low_open else number_ < low)
    above = high is not None and (number_ >= high if high_open else number_ > high)
    if not math.isfinite(number_) or below or above:
        raise InputError(f"{field}: expected {what}, got {value!r}", field)
    return number_


def numbers(field: str, value, what: str = "numbers", low: float | None = None,
            high: float | None = None, *, low_open: bool = False,
            high_open: bool = False) -> tuple[float, ...]:
    """``value`` (a number, or a sequence or array of them) as a non-empty tuple of finite
    floats, each in [low, high].

    Parameters
    ----------
    field, what, low, high, low_open, high_open :
        As for :func:`number`; text and None are refused whole.
    value :
        A number, a list or tuple of numbers, or an array.
    """
    if isinstance(value, (str, bytes)) or value is None:
        raise InputError(f"{field}: expected {what}, got {value!r}", field)
    items = value.tolist() if hasattr(value, "tolist") else value
    if not hasattr(items, "__iter__"):
        items = [items]
    items = list(items)
    if not items:
        raise InputError(f"{field}: expected {what}, got none", field)
    return tuple(number(field, item, what, low, high, low_open=low_open, high_open=high_open)
                 for item in items)


def whole(field: str, value, low: int) -> int:
    """``value`` as an int ≥ ``low`` (an integral float too, not a bool).

    Parameters
    ----------
    field : str
        The argument's name, for the message.
    value : object
        What was given.
    low : int
        The least value allowed.
    """
    if isinstance(value, bool) or not isinstance(value, Real) or value != int(value) \
            or value < low:
        raise InputError(f"{field}: expected a whole number ≥ {low}, got {value!r}", field)
    return int(value)


def flag(field: str, value) -> bool:
    """``value`` as a bool (True or False, numpy's too; not 'yes' or 1.5).

    Parameters
    ----------
    field : str
        The argument's name, for the message.
    value : object
        What was given.
    """
    if value in (True, False) and not isinstance(value, (str, float)):
        return bool(value)
    raise InputError(f"{field}: expected True or False, got {value!r}", field)


def words(field: str, value) -> tuple[str, ...]:
    """``value`` (a string, or a sequence of them) as a tuple of strings.

    Parameters
    ----------
    field : str
        The argument's name, for the message.
    value : str or sequence of str
        What was given.
    """
    items = (value,) if isinstance(value, str) else value
    if not isinstance(items, (list, tuple)) or not all(isinstance(item, str) for item in items):
        raise InputError(f"{field}: expected text or a list of text, got {value!r}", field)
    return tuple(items)


def pair(field: str, value, what: str, low: float | None = None,
         high: float | None = None, *, low_open: bool = False) -> tuple[float, float]:
    """``value`` as two finite floats (a sequence of two numbers: not one string, not one
    number), each in [low, high].

    Parameters
    ----------
    field : str
        The argument's name, for the message.
    value : sequence of two numbers
        What was given.
    what : str
        What the two numbers are, with their unit, for the message (``"S_XS, S_X1 in g"``).
    low, high : float, optional
        Bounds of each number, in its unit; none when not given.
    low_open : bool
        Whether ``low`` itself is refused.
    """
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
        raise InputError(f"{field}: expected two numbers {what}, got {value!r}", field)
    first, second = numbers(field, value, f"two numbers {what}", low, high, low_open=low_open)
    return first, second


def path(field: str, value, what: str = "a path"):
    """``value`` as a :class:`pathlib.Path` (from text or a path; not a number or None).

    Parameters
    ----------
    field : str
        The argument's name, for the message.
    value : str or pathlib.Path
        What was given.
    what : str
        What the path is, for the message.
    """
    from pathlib import Path
    if isinstance(value, (str, Path)) and str(value).strip():
        return Path(value)
    raise InputError(f"{field}: expected {what}, got {value!r}", field)


def callback(field: str, value, how: str):
    """``value`` as True, False or a callable ``how`` (e.g. ``progress(done, total, …)``).

    Parameters
    ----------
    field : str
        The argument's name, for the message.
    value : bool or callable
        What was given.
    how : str
        The callable's signature, for the message.
    """
    if value is True or value is False or callable(value):
        return value
    raise InputError(f"{field}: expected True, False or {how}, got {value!r}", field)


def unknown(where: str, values: dict, known) -> None:
    """InputError naming the first of ``values`` that is not a field of ``where``.

    Parameters
    ----------
    where : str
        What takes the fields (``"the design site"``), for the message.
    values : dict
        The arguments given, by name.
    known : iterable of str
        The names of the fields.
    """
    extra = [name for name in values if name not in known]
    if extra:
        raise InputError(f"{extra[0]}: not an argument of {where} (its arguments: "
                         f"{', '.join(known)})", extra[0])


def probability(field: str, value, what: str = "a probability strictly between 0 and 1") -> float:
    """``value`` as a probability in (0, 1): a number (0.02) or text, a number or a
    percentage ('0.02', '2%', '2 %'), as engineers write "2 % in 50 years".

    Parameters
    ----------
    field : str
        The argument's name, for the message.
    value : float or str
        What was given: ``0.02``, ``"0.02"`` or ``"2%"``.
    what : str
        What the probability is, for the message.
    """
    given = value
    if isinstance(value, str):
        text = value.strip()
        percent = text.endswith("%")
        try:
            value = float(text[:-1] if percent else text) / (100.0 if percent else 1.0)
        except ValueError:
            raise InputError(f"{field}: expected {what} (0.02 or 2%), got {given!r}",
                             field) from None
    if isinstance(value, bool) or not isinstance(value, Real) \
            or not (math.isfinite(value) and 0.0 < value < 1.0):
        raise InputError(f"{field}: expected {what} (0.02 or 2%), got {given!r}", field)
    return float(value)


def lon_lat(field: str, value) -> tuple[float, float]:
    """``value`` as a site (longitude, latitude) [degrees]: a pair of numbers, or text
    ``"LON,LAT"`` (``"-118,34"``: west and south negative).

    Parameters
    ----------
    field : str
        The argument's name, for the message.
    value : sequence of two numbers or str
        What was given: ``(-118, 34)`` or ``"-118,34"`` [degrees].
    """
    given = value
    if isinstance(value, str):
        value = value.split(",")
        try:
            value = [float(v) for v in value]
        except ValueError:
            value = None
    what = "LON,LAT in degrees (west and south negative), e.g. '-118,34' or (-118, 34)"
    if value is None or isinstance(value, (bytes, dict)) or not hasattr(value, "__len__") \
            or len(value) != 2:
        raise InputError(f"{field}: expected {what}, got {given!r}", field)
    lon, lat = (number(field, v, what) for v in value)
    if not (-180 <= lon <= 360 and -90 <= lat <= 90):
        raise InputError(f"{field}: expected {what}, got {given!r}", field)
    return lon, lat


__all__ = ["number", "numbers", "whole", "flag", "words", "pair", "path", "callback", "unknown",
           "probability", "lon_lat"]
