"""The one block of the audit, from the API down to the solver, the one ``WIDTHxHEIGHT`` parser
with the one set of limits every command applies, and the blocks an audit covers.

A block is a rectangular rigid block, by its full base width 2b and full height 2h [m] (the box
of its centre of mass) or by its slenderness α and size 2π/p; either gives the other through
α = atan(b/h), R = √(b² + h²) and p = √(3g/(4R)) (Eq. 4.2). :attr:`Block.rigid` is the one
conversion to the solver's :class:`~audit.physics.block.RigidBlock` (p [rad/s], α [rad]).

``--block WIDTHxHEIGHT`` means the same to ``check``, ``rock`` and ``margins``, and
:func:`within_limits` refuses the same blocks for all of them (see :data:`MAX_SIZE_S` for why).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from audit import G
from audit.engine.shared import fields as check
from audit.errors import InputError
from audit.physics.block import RigidBlock

if TYPE_CHECKING:  # numpy where a list of blocks is built: the API's front door imports Block
    import numpy as np

#: The largest block a user may name, by its size 2π/p [s] (10 s: R = 3g/(4p²) = 18.6 m, a
#: 0.6 m wide object 37 m tall). A limit chosen here from the physics, not a code's.
#:
#: Slenderness alone sets no limit: the solver integrates Eq. 4.3 exactly between impacts for
#: any 0 < α < 45° (Eq. 4.8's r > 0 holds there; at α ≥ 45° the "block" is wider than tall and
#: does not rock about its corners), so α < 45° is the only bound on it. Size does: the
#: rocking spectra scale with ω_p/p (Makris & Konstantinidis 2001), so a block of size 2π/p
#: is governed by ground motion of comparable periods, and processed strong-motion records are
#: high-pass filtered, their usable band rarely reaching beyond about 10 s (the response
#: spectra this project computes stop at 10 s too). A larger block's answer would rest on
#: ground motion the records do not hold: ``1x80`` (2π/p = 14.6 s) and ``1x500`` (36.6 s) are
#: refused. The usual cause of such a block is a dimension typed in millimetres, so the
#: message then gives the block in metres. Grid sweeps (``--size``) are research inputs and
#: are not limited.
MAX_SIZE_S = 10.0
#: From this base width [m] up, a block too large is taken as typed in millimetres and the
#: message gives it in metres; below it (``1x80``) no unit is guessed.
MILLIMETRES_HINT_WIDTH_M = 10.0


def _check_r_g(r, g) -> None:
    if r is not None:
        check.number("r", r, "a coefficient of restitution in (0, 1]", 0, 1, low_open=True)
    check.number("g", g, "a positive acceleration in m/s²", 0, low_open=True)


@dataclass(frozen=True, kw_only=True)
class Block:
    """A free-standing rectangular block, by its slenderness and size (keyword arguments only:
    ``Block(alpha_deg=15, size_s=2.0)``; by its dimensions, :meth:`from_dimensions`; as typed,
    :meth:`parse`).

    Parameters
    ----------
    alpha_deg : float
        Slenderness α = atan(b/h) [degrees], 0 < α < 45.
    size_s : float
        Size 2π/p [s], p = √(3g/(4R)) the frequency parameter (Eq. 4.2), R the half-diagonal.
    r : float, optional
        Coefficient of restitution (ratio of kinetic energies after/before an impact) [-];
        Eq. 4.8 of Makris & Konstantinidis (2001), r = (1 − 1.5 sin²α)², when not given.
    g : float
        Acceleration of gravity [m/s²].
    width_m, height_m : float, optional
        Full width 2b = 2R sin α and full height 2h = 2R cos α [m]; worked out from α and the
        size when not given (:meth:`from_dimensions` gives them as typed).
    name : str
        What outputs call the block; its dimensions (:attr:`label`) when empty.
    """

    alpha_deg: float
    size_s: float
    r: float | None = None
    g: float = G
    width_m: float | None = None
    height_m: float | None = None
    name: str = ""

    def __post_init__(self):
        check.number("alpha_deg", self.alpha_deg, "a slenderness between 0 and 45 degrees", 0,
                     45, low_open=True, high_open=True)
        check.number("size_s", self.size_s, "a positive size 2π/p in s", 0, low_open=True)
        _check_r_g(self.r, self.g)
        rigid = self.rigid
        for field, worked in (("width_m", 2.0 * rigid.half_width),
                              ("height_m", 2.0 * rigid.half_height)):
            given = getattr(self, field)
            if given is None:
                object.__setattr__(self, field, worked)
            elif not math.isclose(given, worked, rel_tol=1e-9):
                raise InputError(f"{field}: {given:g} m is not the {worked:g} m of α = "
                                 f"{self.alpha_deg:g}° and 2π/p = {self.size_s:g} s", field)

    @classmethod
    def from_dimensions(cls, width_m: float, height_m: float, r: float | None = None,
                        g: float = G, name: str = "") -> Block:
        """The block of full width 2b and full height 2h [m]: α = atan(b/h), R = √(b² + h²),
        within the limits every command applies (:func:`within_limits`).

        Parameters
        ----------
        width_m, height_m : float
            Full width 2b and full height 2h [m], positive, width < height.
        r : float, optional
            Coefficient of restitution [-]; Eq. 4.8 (from α) when not given.
        g : float
            Acceleration of gravity [m/s²].
        name : str
            What outputs call the block; its dimensions when empty.
        """
        for field, value in (("width_m", width_m), ("height_m", height_m)):
            check.number(field, value, "a positive number of metres", 0, low_open=True)
        _check_r_g(r, g)  # named as the arguments, before the solver's block checks them
        if width_m >= height_m:
            raise InputError(f"width_m, height_m: a rocking block is taller than it is wide "
                             f"(α < 45°), got width {width_m:g} m ≥ height {height_m:g} m",
                             "width_m", "height_m")
        return within_limits(cls.of_dimensions(width_m, height_m, r, g, name), "", "height_m")

    @classmethod
    def of_dimensions(cls, width_m: float, height_m: float, r: float | None = None,
                      g: float = G, name: str = "") -> Block:
        """:meth:`from_dimensions` without the limits, for the blocks the audit makes itself
        (a family of widths, the widths a guideline requires).

        Parameters
        ----------
        width_m, height_m : float
            Full width 2b and full height 2h [m].
        r : float, optional
            Coefficient of restitution [-]; Eq. 4.8 (from α) when not given.
        g : float
            Acceleration of gravity [m/s²].
        name : str
            What outputs call the block; its dimensions when empty.
        """
        rigid = RigidBlock.from_dimensions(width_m / 2.0, height_m / 2.0, r, g)
        return cls(alpha_deg=math.degrees(rigid.alpha), size_s=rigid.size_s, r=r, g=g,
                   width_m=float(width_m), height_m=float(height_m), name=name)

    @classmethod
    def parse(cls, text: str, r: float | None = None, g: float = G, *,
              option: str = "block") -> Block:
        """The one block typed as ``WIDTHxHEIGHT`` [m] (full width × full height), e.g.
        ``0.8x2.0``; InputError naming ``option``, the text and the field otherwise.

        Parameters
        ----------
        text : str
            ``WIDTHxHEIGHT`` [m].
        r : float, optional
            Coefficient of restitution [-]; Eq. 4.8 (from α) when not given.
        g : float
            Acceleration of gravity [m/s²].
        option : str
            The option or argument the text was given as, for the message.
        """
        blocks = parse_blocks([text], option, g, r)
        if len(blocks) != 1:
            raise InputError(f"{option}: expected one WIDTHxHEIGHT, got {text!r}", option)
        return blocks[0]

    def with_width(self, width_m: float) -> Block:
        """The block of the same height and another width (its family at this height).

        Parameters
        ----------
        width_m : float
            Full base width 2b of the new block [m].
        """
        return Block.of_dimensions(width_m, self.height_m, self.r, self.g, self.name)

    @property
    def label(self) -> str:
        """The name outputs give the block: its name, else ``WIDTHxHEIGHT`` in metres."""
        return self.name or f"{self.width_m:g}x{self.height_m:g}"

    @property
    def rigid(self) -> RigidBlock:
        """The solver's block (p [rad/s], α [rad], r, g): the one conversion."""
        return RigidBlock.from_size(self.size_s, math.radians(self.alpha_deg), self.r, self.g)

    @property
    def p_rad_s(self) -> float:
        """Frequency parameter p = 2π/size [rad/s]."""
        return 2.0 * math.pi / self.size_s

    @property
    def radius_m(self) -> float:
        """Half-diagonal R = 3g/(4p²) [m]."""
        return self.rigid.radius

    @property
    def restitution(self) -> float:
        """The coefficient of restitution r the solver uses [-]."""
        return self.rigid.r


def within_limits(block: Block, where: str, *fields: str) -> Block:
    """``block`` if a user may name it (size 2π/p ≤ :data:`MAX_SIZE_S`); otherwise InputError
    naming ``where`` (the option and text, or nothing for an argument) and ``height_m``, with
    the block in metres when the dimensions look typed in millimetres.

    Parameters
    ----------
    block : Block
        The block to check.
    where : str
        The option and text it was given as (``"--block 1x80"``), or ``""`` for an argument.
    *fields : str
        The fields the InputError names (its ``fields``).

    Returns
    -------
    Block
        ``block`` itself.
    """
    if block.size_s <= MAX_SIZE_S:
        return block
    w, h = block.width_m, block.height_m
    # a base 10 m wide or more is no object's: the numbers were typed in millimetres (the
    # drawings' unit; centimetres would be a guess between two)
    hint = (f"; millimetres? {_metres(w / 1000.0)}x{_metres(h / 1000.0)} m"
            if w >= MILLIMETRES_HINT_WIDTH_M else "")
    radius = 3.0 * block.g / (4.0 * (2.0 * math.pi / MAX_SIZE_S) ** 2)
    # no "block" in the words: the command line puts its flag in place of the field "block"
    raise InputError(f"{where + ': ' if where else ''}height_m: {w:.4g} m × {h:.4g} m has "
                     f"2π/p = {block.size_s:.3g} s, beyond the {MAX_SIZE_S:g} s (R = "
                     f"{radius:.3g} m) of ground motion the records hold" + hint, *fields)


def _metres(value: float) -> str:
    """A length as a user types it: ``0.5``, ``2.0``."""
    text = f"{value:g}"
    return text if any(c in text for c in ".e") else text + ".0"


def _block_of_text(item: str, option: str, g: float, r: float | None) -> Block:
    where = f"{option} {item}"
    parts = item.lower().replace("×", "x").split("x")
    if len(parts) != 2:
        raise InputError(f"{where}: expected WIDTHxHEIGHT in metres (e.g. 0.6x1.8)", option)
    dimensions = []
    for field, part in zip(("width_m", "height_m"), parts):
        try:
            value = float(part)
        except ValueError:
            value = math.nan
        if not (math.isfinite(value) and value > 0):
            raise InputError(f"{where}: {field}: expected a positive number of metres, got "
                             f"'{part}'", option)
        dimensions.append(value)
    width, height = dimensions
    if width >= height:
        raise InputError(f"{where}: width_m: a rocking object is taller than it is wide "
                         f"(α < 45°), got width {width:g} m ≥ height {height:g} m", option)
    return within_limits(Block.of_dimensions(width, height, r, g), where, option)


def parse_blocks(texts, option: str = "blocks", g: float = G,
                 r: float | None = None) -> list[Block]:
    """The one ``WIDTHxHEIGHT`` parser: the blocks of ``option``'s texts (repeated, each
    possibly comma-separated), e.g. ``0.4x2.0`` [m], unnamed; InputError naming the option,
    the text and the field otherwise.

    The limits, the same for every command: positive dimensions, width < height (α < 45°,
    the rocking model's blocks), and size 2π/p ≤ :data:`MAX_SIZE_S` = 10 s (the records'
    long-period band; the reasons at :data:`MAX_SIZE_S`).

    Parameters
    ----------
    texts : iterable of str or None
        The option's values, each one ``WIDTHxHEIGHT`` or several comma-separated.
    option : str
        The option's name, for the message.
    g : float
        Acceleration of gravity [m/s²].
    r : float, optional
        Coefficient of restitution [-]; Eq. 4.8 (from α) when not given.
    """
    return [_block_of_text(item.strip(), option, g, r) for text in texts or ()
            for item in str(text).split(",") if item.strip()]


@dataclass(frozen=True)
class BlockList:
    """Every block of an audit in one order: the grid (α-major, then size), then the named
    blocks. Arrays are one entry per block.

    Attributes
    ----------
    alpha_deg, size_s : numpy.ndarray
        Slenderness [degrees] and size 2π/p [s].
    width_m, height_m : numpy.ndarray
        Full width and height [m] of a named block, NaN for a grid block (the tables tell
        the two apart by them).
    """

    alpha_deg: np.ndarray
    size_s: np.ndarray
    width_m: np.ndarray
    height_m: np.ndarray

    @classmethod
    def of(cls, alpha_deg=(), size_s=(), named=()) -> BlockList:
        """The grid ``alpha_deg`` × ``size_s`` (every slenderness at every size), then the blocks
        ``named``.

        Parameters
        ----------
        alpha_deg : array_like of float
            Slendernesses of the grid [degrees].
        size_s : array_like of float
            Sizes 2π/p of the grid [s].
        named : iterable of Block
            Named blocks appended after the grid, labelled by :attr:`Block.label`.
        """
        import numpy as np
        alpha_deg = np.asarray(alpha_deg, dtype=float)
        size_s = np.asarray(size_s, dtype=float)
        grid_alpha, grid_size = (a.ravel() for a in np.meshgrid(alpha_deg, size_s,
                                                                   indexing="ij"))
        grid = np.full(grid_alpha.size, np.nan)
        return cls(np.concatenate([grid_alpha, [b.alpha_deg for b in named]]),
                   np.concatenate([grid_size, [b.size_s for b in named]]),
                   np.concatenate([grid, [b.width_m for b in named]]),
                   np.concatenate([grid, [b.height_m for b in named]]))

    def __len__(self) -> int:
        return self.alpha_deg.size

    @property
    def alpha_rad(self) -> np.ndarray:
        import numpy as np
        return np.radians(self.alpha_deg)

    def groups(self) -> list[tuple[float, np.ndarray]]:
        """Blocks of one slenderness together: ``(alpha_rad, indices)`` in order of first
        appearance; a procedure evaluates and the solver solves each group in one call."""
        import numpy as np
        groups: dict[float, list[int]] = {}
        for index, alpha in enumerate(self.alpha_deg):
            groups.setdefault(float(alpha), []).append(index)
        return [(math.radians(alpha), np.array(indices)) for alpha, indices in groups.items()]


__all__ = ["Block", "MAX_SIZE_S", "within_limits", "parse_blocks", "BlockList"]
