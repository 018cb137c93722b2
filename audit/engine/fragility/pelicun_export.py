"""Exact fragilities out to pelicun: the FEMA P-58 damage-and-loss library layout.

pelicun (NHERI SimCenter) reads a component's fragility from a CSV of one row per component,
the layout of its Damage and Loss Model Library (``fragility.csv`` of "FEMA P-58 2nd Edition"),
checked against pelicun's own loader (``DamageModel.load_model_parameters``: a table is a
damage-state model where its columns carry ``LS1``; ``Incomplete`` = 1 rows are dropped; the
``Demand-Unit`` converts the thetas to SI):

    ID, Incomplete, Demand-Type, Demand-Unit, Demand-Offset, Demand-Directional,
    LS1-Family, LS1-Theta_0, LS1-Theta_1

One limit state, overturning, lognormal with median Theta_0 and β Theta_1. The demand is peak
floor velocity (``mps``) or peak floor acceleration (``mps2``, SI, so that no value of g is
assumed) at the object's floor (Demand-Offset 0, so pelicun's own ``DemandOffset`` option
applies as to P-58's rows), and it is *directional* (``Demand-Directional`` 1): the exact
fragility was computed for one horizontal component of each record, so it is a fragility of
the peak of one direction. pelicun gives a non-directional component the larger of the two
directions × its ``NonDirectionalMultipliers`` (1.2 by default, FEMA P-58's factor;
``_assemble_required_demand_data`` in ``pelicun/model/demand_model.py``), which would apply
the exact fragility to a demand it was not computed for; a directional one reads the demand
of the component's own direction unchanged. pelicun's damage loader reads no JSON beside the
CSV, so none is written. A row keeps the
component's id: listed before the P-58 library in pelicun's ``data_paths``, it replaces P-58's
fragility of the same component (earlier paths take precedence).
"""

from __future__ import annotations

import math

import pandas as pd

from audit.errors import InputError

#: The columns of the layout, in order.
PELICUN_COLUMNS = ("ID", "Incomplete", "Demand-Type", "Demand-Unit", "Demand-Offset",
                   "Demand-Directional", "LS1-Family", "LS1-Theta_0", "LS1-Theta_1")
#: The tool's intensity measure → pelicun's demand type and the unit of the SI value.
DEMAND_TYPES = {"PGV": ("Peak Floor Velocity", "mps"), "PGA": ("Peak Floor Acceleration", "mps2")}


def pelicun_fragility_table(components) -> pd.DataFrame:
    """The pelicun fragility table of ``components``.

    Parameters
    ----------
    components : iterable of procedures.probabilistic.FragilityComponent
        Each with its id, intensity measure (``PGV`` [m/s] or ``PGA`` [m/s²], read at the
        object's floor) and lognormal fragility (median in SI, β).

    Returns
    -------
    pandas.DataFrame
        One row per component, columns :data:`PELICUN_COLUMNS`; a component without a finite
        positive median and β (no fit exists) is marked ``Incomplete`` = 1 so pelicun drops it.
    """
    rows = []
    for component in components:
        if component.intensity_measure not in DEMAND_TYPES:
            raise InputError(f"components: {component.id} has intensity measure "
                             f"{component.intensity_measure!r}; pelicun takes "
                             f"{', '.join(DEMAND_TYPES)}", "components")
        demand, unit = DEMAND_TYPES[component.intensity_measure]
        median, beta = component.fragility.median, component.fragility.beta
        complete = all(math.isfinite(value) and value > 0 for value in (median, beta))
        rows.append((component.id, 0 if complete else 1, demand, unit, 0, 1, "lognormal",
                     median if complete else None, beta if complete else None))
    return pd.DataFrame(rows, columns=list(PELICUN_COLUMNS))


def pelicun_fragility_csv(components) -> bytes:
    """:func:`pelicun_fragility_table` as the CSV file pelicun reads (full float precision).

    Parameters
    ----------
    components : iterable of procedures.probabilistic.FragilityComponent
        As for :func:`pelicun_fragility_table`.
    """
    return pelicun_fragility_table(components).to_csv(index=False, float_format="%.17g").encode()


__all__ = ["PELICUN_COLUMNS", "DEMAND_TYPES", "pelicun_fragility_table", "pelicun_fragility_csv"]
