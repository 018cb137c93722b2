"""The objects ``audit check`` is asked about: named blocks
(:class:`~audit.engine.shared.blocks.Block`) in metres, checked once.

An object is a rectangular block by its full base width and full height [m] (the box of its
centre of mass: the rocking model's 2b × 2h), or by its slenderness and size (α, 2π/p) for
one described that way. Every object passes the limits every command applies
(:func:`~audit.engine.shared.blocks.within_limits`); bad objects are refused with one line naming
the object and the field, before any work.
"""

from __future__ import annotations

import csv
import math
from dataclasses import replace
from pathlib import Path

from audit import G
from audit.engine.shared.blocks import Block, parse_blocks, within_limits
from audit.errors import InputError

#: Columns of an inventory file (``--objects``): required, then optional.
REQUIRED_COLUMNS = ("name",)
DIMENSION_COLUMNS = ("width_m", "height_m")
SLENDERNESS_COLUMNS = ("alpha_deg", "size_s")


def _positive(value, where: str, field: str, unit: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not (math.isfinite(number) and number > 0):
        raise InputError(f"{where}: {field}: expected a positive number of {unit}, got "
                         f"'{value}'")
    return number


def checked_object(name: str, width_m, height_m, where: str, g: float = G) -> Block:
    """The object ``name`` after the checks every block passes; InputError naming ``where``
    (the option, argument or file row) and the field otherwise.

    Parameters
    ----------
    name : str
        What the object is called in the answer.
    width_m, height_m : float
        Full base width and full height of the box of its centre of mass [m], positive,
        taller than wide (the limits of :func:`~audit.engine.shared.blocks.parse_blocks`).
    where : str
        Where it was given (``--block``, ``objects[2]``, a file's row), for the message.
    g : float
        Acceleration of gravity [m/s²].
    """
    width = _positive(width_m, where, "width_m", "metres")
    height = _positive(height_m, where, "height_m", "metres")
    if width >= height:
        raise InputError(f"{where}: width_m: a rocking block is taller than it is wide "
                         f"(α < 45°), got width {width:g} m ≥ height {height:g} m")
    return within_limits(Block.of_dimensions(width, height, g=g, name=str(name)), where)


def object_by_slenderness(name: str, alpha_deg, size_s, where: str, g: float = G) -> Block:
    """The object of slenderness α [degrees] and size 2π/p [s], checked as
    :func:`checked_object` (and, like every object, known by its dimensions from then on).

    Parameters
    ----------
    name : str
    alpha_deg : float
        Slenderness α = atan(b/h) [degrees], in (0, 45).
    size_s : float
        Size 2π/p [s], positive (p = √(3g/(4R)), R the half-diagonal, Eq. 4.2).
    where : str
        Where it was given, for the message.
    g : float
        Acceleration of gravity [m/s²].
    """
    alpha = _positive(alpha_deg, where, "alpha_deg", "degrees")
    if alpha >= 45.0:
        raise InputError(f"{where}: alpha_deg: slenderness must lie between 0 and 45 degrees, "
                         f"got {alpha:g}")
    size = _positive(size_s, where, "size_s", "seconds")
    shaped = Block(alpha_deg=alpha, size_s=size, g=g)
    return checked_object(name, shaped.width_m, shaped.height_m, where, g)


def parse_block_text(text: str, option: str = "blocks", g: float = G) -> list[Block]:
    """Objects of one ``--block`` value, ``WIDTHxHEIGHT`` [m] (several comma-separated), named
    as typed (:func:`~audit.engine.shared.blocks.parse_blocks`).

    Parameters
    ----------
    text : str
        ``WIDTHxHEIGHT`` [m], full width × full height, or several separated by commas.
    option : str
        The option or argument it came from, for the message.
    g : float
        Acceleration of gravity [m/s²].
    """
    items = [item.strip() for item in str(text).split(",") if item.strip()]
    return [replace(block, name=item) for item, block in zip(items, parse_blocks(items, option, g))]


def read_objects(path, option: str = "objects", g: float = G) -> list[Block]:
    """An inventory: a CSV file with ``name`` and either ``width_m,height_m`` or
    ``alpha_deg,size_s`` on each row (a row may use either pair). InputError naming the file,
    the row and the field of the first bad row.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file (UTF-8, a byte-order mark allowed); dimensions in m, α in degrees,
        sizes in s.
    option : str
        The option or argument it came from, for the message.
    g : float
        Acceleration of gravity [m/s²].
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise InputError(f"{option}: {path}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise InputError(f"{option}: {path}: not a UTF-8 text file") from None
    reader = csv.DictReader(text.splitlines())
    columns = [c.strip() for c in reader.fieldnames or ()]
    if "name" not in columns or not (set(DIMENSION_COLUMNS) <= set(columns)
                                     or set(SLENDERNESS_COLUMNS) <= set(columns)):
        raise InputError(f"{option}: {path}: expected the columns name,width_m,height_m "
                         f"(or name,alpha_deg,size_s), got {','.join(columns) or 'none'}")
    objects, names = [], set()
    for row_number, raw in enumerate(reader, start=2):
        extra = raw.pop(None, None)  # csv puts the fields beyond the header's under None
        row = {(k or "").strip(): (v or "").strip() for k, v in raw.items()}
        name = row.get("name", "")
        where = f"{option}: {path}: row {row_number}" + (f" ({name})" if name else "")
        if extra and any(field.strip() for field in extra):
            raise InputError(f"{where}: {len(columns) + len(extra)} fields, the header has "
                             f"{len(columns)} ({','.join(columns)}); quote a name that holds "
                             "a comma")
        if not name:
            raise InputError(f"{where}: name: empty")
        if name in names:
            raise InputError(f"{where}: name: '{name}' is already used by an earlier row")
        names.add(name)
        if row.get("width_m") or row.get("height_m"):
            objects.append(checked_object(name, row.get("width_m"), row.get("height_m"),
                                          where, g))
        else:
            objects.append(object_by_slenderness(name, row.get("alpha_deg"), row.get("size_s"),
                                                 where, g))
    if not objects:
        raise InputError(f"{option}: {path}: no object in the file")
    return objects


__all__ = ["checked_object", "object_by_slenderness", "parse_block_text", "read_objects"]
