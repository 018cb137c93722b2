"""Facts of the seven near-fault records of the reference report (SPEC §6–7).

Table 5.1 gives PGA, PGV and the period of the main pulse; Table 3.1 gives the FEMA 356
site parameters for the five US records. The keys are the ids of
``../shared/records/seed-suite.toml``.
"""

from __future__ import annotations

from dataclasses import dataclass

from audit.errors import InputError


@dataclass(frozen=True)
class RecordFacts:
    """Published facts of one record.

    Attributes
    ----------
    pga_g : float
        Table 5.1 peak ground acceleration [g].
    pgv_ms : float
        Table 5.1 peak ground velocity [m/s].
    pulse_period_s : float or None
        Table 5.1 period of the main pulse T_p [s]; None where the table gives none.
    site_class, sxs_g, sx1_g :
        Table 3.1 FEMA 356 site class and design parameters S_XS, S_X1 [g]; None for the
        non-US records.
    """

    id: str
    event: str
    year: int
    station: str
    component: str
    pga_g: float
    pgv_ms: float
    pulse_period_s: float | None
    site_class: str | None = None
    sxs_g: float | None = None
    sx1_g: float | None = None

    @property
    def name(self) -> str:
        """Display name, e.g. "San Fernando 1971, Pacoima Dam"."""
        return f"{self.event} {self.year}, {self.station}"


SEED_CATALOGUE: dict[str, RecordFacts] = {
    facts.id: facts
    for facts in (
        RecordFacts("pacoima_dam_1971", "San Fernando", 1971, "Pacoima Dam", "fault-normal",
                    1.226, 1.20, 1.3, "B", 1.59, 0.50),
        RecordFacts("el_centro_5_1979", "Imperial Valley", 1979, "El Centro Array #5", "fault-normal",
                    0.379, 0.90, 3.2, "D", 1.34, 0.81),
        RecordFacts("los_gatos_1989", "Loma Prieta", 1989, "Los Gatos", "fault-normal",
                    0.563, 0.95, 3.0, "D", 1.94, 1.83),
        RecordFacts("rinaldi_1994", "Northridge", 1994, "Rinaldi", "fault-normal",
                    0.838, 1.75, 1.0, "C", 1.56, 0.69),
        RecordFacts("sylmar_1994", "Northridge", 1994, "Sylmar", "fault-normal",
                    0.732, 1.20, 2.3, "D", 1.56, 0.80),
        RecordFacts("erzincan_1992", "Erzincan, Turkey", 1992, "Erzincan", "fault-normal",
                    0.515, 0.70, 1.8),
        RecordFacts("takatori_1995", "Kobe", 1995, "Takatori", "fault-normal",
                    0.611, 1.25, None),
    )
}

#: Takatori has no main-pulse period in Table 5.1; the built-in pulse suite uses this one.
DEFAULT_PULSE_PERIOD_S = 1.0


def record_facts(record_id: str) -> RecordFacts:
    """Catalogue entry of a seed record; :class:`InputError` for an unknown id."""
    try:
        return SEED_CATALOGUE[record_id]
    except KeyError:
        known = ", ".join(SEED_CATALOGUE)
        raise InputError(f"record id: unknown '{record_id}', the catalogue has {known}") from None
