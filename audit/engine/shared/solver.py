"""The exact solver's model as a command is given it (:class:`Solver`), checked once. Light: the
impact model's class is imported where it is parsed."""

from __future__ import annotations

from dataclasses import dataclass

from audit import G
from audit.engine.shared import fields as check
from audit.engine.shared.defaults import DEFAULT_FREE_MOTION_S, DEFAULT_RESTITUTION
from audit.errors import InputError, field_name

#: The commands that put the records' vertical acceleration in the equation of motion.
VERTICAL_READERS = ("run",)


@dataclass(frozen=True)
class Solver:
    """The exact rocking solver's model.

    :meth:`parse` checks every field once.

    Attributes
    ----------
    restitution : str, float or audit.physics.block.Restitution
        Impact model: ``housner`` (Eq. 4.8), a fixed r in (0, 1] [-] or ``xFACTOR`` times
        Eq. 4.8; :meth:`parse` returns a Restitution.
    free_motion_s : float
        Free motion after each record [s], ≥ 0.
    g : float
        Acceleration of gravity [m/s²].
    vertical : bool
        ``run``: the records' vertical components in the equation of motion and at uplift,
        where they have one.
    """

    restitution: object = DEFAULT_RESTITUTION
    free_motion_s: float = DEFAULT_FREE_MOTION_S
    g: float = G
    vertical: bool = False

    @classmethod
    def parse(cls, value=None, command: str | None = None,
              argument: str | None = "solver") -> Solver:
        """``value`` with every field checked once (InputError naming ``argument.field``).

        Parameters
        ----------
        value : Solver or None
            None: the defaults.
        command : str, optional
            The command reading it: ``vertical`` is refused by a command not in
            :data:`VERTICAL_READERS`. None: every field read.
        argument : str or None
            The argument the solver was given as, for the messages (None: a function whose own
            keywords are the fields).
        """
        from audit.physics.block import Restitution
        if value is None:
            value = cls()
        if not isinstance(value, Solver):
            raise InputError(f"{argument}: expected a Solver(restitution, free_motion_s, g, "
                             f"vertical), got {value!r}", argument)
        vertical = check.flag(field_name(argument, "vertical"), value.vertical)
        if vertical and command is not None and command not in VERTICAL_READERS:
            raise InputError(f"{field_name(argument, 'vertical')}: "
                             f"{' and '.join(VERTICAL_READERS)} only",
                             field_name(argument, "vertical"))
        restitution = value.restitution
        if not isinstance(restitution, Restitution):
            restitution = Restitution.parse(restitution, field_name(argument, "restitution"))
        return cls(restitution,
                   check.number(field_name(argument, "free_motion_s"), value.free_motion_s,
                                "a duration ≥ 0 s", 0),
                   check.number(field_name(argument, "g"), value.g,
                                "a positive acceleration in m/s²", 0, low_open=True),
                   vertical)


__all__ = ["Solver", "VERTICAL_READERS"]
