"""Registry of procedures: the built-ins and every ``rocking_audit.procedures`` entry point.

A third-party distribution adds a procedure by declaring, in its ``pyproject.toml``::

    [project.entry-points."rocking_audit.procedures"]
    myname = "mypackage.mymodule:MyProcedure"

where ``MyProcedure`` subclasses :class:`procedures.base.Procedure`; a component provision (a
code's static force on an object on a floor, :class:`procedures.component.ComponentProvision`)
in the group ``rocking_audit.component_provisions``.
"""

from __future__ import annotations

from importlib.metadata import entry_points

from audit.errors import InputError
from procedures.asce_7_22 import ASCE722
from procedures.base import Procedure
from procedures.component import ComponentProvision
from procedures.en_1998_1 import EN19981
from procedures.probabilistic import ProbabilisticProcedure
from procedures.fema_356 import FEMA356
from procedures.fema_p58 import FEMAP58
from procedures.housner_1963 import Housner1963
from procedures.makris_roussos_2000 import MakrisRoussos2000
from procedures.ntc_2018 import NTC2018
from procedures.nzs_1170_5 import NZS11705
from procedures.priestley_1978 import PriestleyEvisonCarr1978

ENTRY_POINT_GROUP = "rocking_audit.procedures"
BUILT_IN = (PriestleyEvisonCarr1978, FEMA356, NTC2018, Housner1963, MakrisRoussos2000)
#: Probabilistic procedures (P(event | IM), audited by calibration, not by rotation) are kept
#: apart so "all" keeps meaning every rotation procedure; plug-ins declare them in their own group.
PROBABILISTIC_ENTRY_POINT_GROUP = "rocking_audit.probabilistic_procedures"
PROBABILISTIC_BUILT_IN = (FEMAP58,)
#: Component provisions (static forces on objects on floors) have a contract of their own too.
COMPONENT_ENTRY_POINT_GROUP = "rocking_audit.component_provisions"
COMPONENT_BUILT_IN = (ASCE722, EN19981, NZS11705)


def available_procedures(probabilistic: bool = False) -> dict[str, type]:
    """Procedure classes by name: built-ins first, then the installed plug-ins; the
    probabilistic ones (subclasses of :class:`ProbabilisticProcedure`) when ``probabilistic``."""
    if probabilistic:
        return _discover(PROBABILISTIC_BUILT_IN, PROBABILISTIC_ENTRY_POINT_GROUP,
                         ProbabilisticProcedure)
    return _discover(BUILT_IN, ENTRY_POINT_GROUP, Procedure)


def available_component_provisions() -> dict[str, type]:
    """Component provision classes by name: built-ins first, then the installed plug-ins of
    ``rocking_audit.component_provisions`` (subclasses of :class:`ComponentProvision`)."""
    return _discover(COMPONENT_BUILT_IN, COMPONENT_ENTRY_POINT_GROUP, ComponentProvision)


def _discover(built_in, group: str, base: type) -> dict[str, type]:
    found = {cls.name: cls for cls in built_in}
    for point in entry_points(group=group):
        if point.name in found:
            continue
        try:
            cls = point.load()
        except Exception as exc:  # a broken plug-in must not take the tool down
            raise InputError(f"procedure plug-in '{point.name}' ({point.value}): cannot be "
                             f"loaded: {exc}") from None
        if not (isinstance(cls, type) and issubclass(cls, base)):
            raise InputError(f"procedure plug-in '{point.name}' ({point.value}): is not a "
                             f"subclass of {base.__module__}.{base.__name__}")
        found[point.name] = cls
    return found


def get_procedures(name: str) -> list[Procedure]:
    """Instances of the procedure ``name``, or of every procedure for ``"all"``."""
    found = available_procedures()
    if name == "all":
        return [cls() for cls in found.values()]
    if name not in found:
        raise InputError(f"procedure: unknown '{name}', available: {', '.join(found)} or all")
    return [found[name]()]
