"""FEMA P-58 (2nd edition, 2018) fragilities of unanchored contents, read at the ground floor.

P-58 gives, for unanchored bookcases and filing cabinets, a lognormal fragility in peak floor
velocity (PFV) whose damage state is overturning ("Book case falls over and contents are
scattered"), and for unanchored equipment and fragile contents one in peak floor acceleration
(PFA). P-58 intends *floor* motion; its comment on every PFV row reads "At the ground floor the
fragility will be based upon the ground motion only." An audit on ground-motion records tests
only that ground-floor clause: PFV = PGV and PFA = PGA here.

Source and version: the FEMA P-58 fragility database v3.1.2 (``FEMAP-58_FragilityDatabase_v3.1.2``,
P-58 Volume 3) as parsed by NHERI SimCenter (``fragility_DB_FEMA_P58_2nd`` of pelicun and its
Damage and Loss Model Library). The values below are tabulated from that parse, i.e. second-hand:
pelicun was not made a dependency (installing it would downgrade scipy and add pandas and
scikit-learn). The formula P-58 derived the PFV medians from (aspect ratio and a building period)
is not in the database; the medians are taken as published.

The block of a component: b = depth/2, h = height/2 from the dimensions in P-58's comments,
which assumes uniform contents (centre of mass at mid-height and mid-depth).
"""

from __future__ import annotations

from audit import G
from procedures.probabilistic import FragilityComponent, LognormalFragility, ProbabilisticProcedure

INCH_M = 0.0254

#: β of every P-58 PFV overturning fragility [-].
PFV_BETA = 0.5

def _pfv(id_, description, depth_in, height_in, median_m_s):
    return FragilityComponent(id_, description, "PGV", LognormalFragility(median_m_s, PFV_BETA),
                              depth_in * INCH_M, height_in * INCH_M)

def _pfa(id_, description, median_g, beta):
    return FragilityComponent(id_, description, "PGA", LognormalFragility(median_g * G, beta))

class FEMAP58(ProbabilisticProcedure):
    """Overturning of unanchored contents by the FEMA P-58 fragility database v3.1.2."""

    name = "femap58"
    title = "FEMA P-58 (2018), unanchored contents"
    components = (
        _pfv("E.20.22.102a", "Bookcase, 2 shelves, unanchored laterally", 12.625, 29.0, 0.724),
        _pfv("E.20.22.103a", "Bookcase, 3 shelves, unanchored laterally", 12.625, 41.0, 0.493),
        _pfv("E.20.22.104a", "Bookcase, 4 shelves, unanchored laterally", 12.625, 56.0, 0.361),
        _pfv("E.20.22.105a", "Bookcase, 5 shelves, unanchored laterally", 12.625, 71.0, 0.290),
        _pfv("E.20.22.106a", "Bookcase, 6 shelves, unanchored laterally", 12.625, 81.25, 0.251),
        _pfv("E.20.22.112a", "Vertical filing cabinet, 2 drawer, unanchored", 15.0, 24.0, 1.229),
        _pfv("E.20.22.114a", "Vertical filing cabinet, 4 drawer, unanchored", 15.0, 52.0, 0.498),
        # the P-58 comments of the two lateral cabinets give 4 and 5 drawers for these sizes
        _pfv("E.20.22.124a", "Lateral filing cabinet, 2 drawer, unanchored", 18.6, 52.5, 0.688),
        _pfv("E.20.22.125a", "Lateral filing cabinet, 4 drawer, unanchored", 18.6, 67.75, 0.526),
        _pfa("E.20.22.010", "Unsecured fragile objects on shelves, unknown restraint", 0.40, 0.6),
        _pfa("E.20.22.011", "Unsecured fragile objects on shelves, museum putty", 1.0, 0.5),
        _pfa("E.20.22.012", "Unsecured fragile objects on shelves, latched", 0.6, 0.6),
        _pfa("E.20.22.013", "Unsecured fragile objects on shelves, low friction", 0.25, 0.5),
        _pfa("D.50.11.011a", "Transformer < 100 kVA, unanchored, not vibration isolated",
             1.01, 0.6),
        _pfa("D.50.92.011a", "Battery rack, unanchored", 1.11, 0.6),
        _pfa("D.30.67.011a", "Control panel, unanchored", 0.69, 0.4),
        _pfa("D.50.12.031a", "Distribution panel 100-350 A, unanchored", 2.16, 0.45),
    )
