"""Facts of the seven near-fault records of the reference report (Makris & Konstantinidis,
PEER 2001/07): Table 5.1 gives PGA, PGV and the period of the main pulse, Table 3.1 the FEMA 356
site parameters of the five US records. Each also names the record in the PEER NGA-West2
database (record sequence number and the file of the component used), so a user can download
the ones no package ships and point the tool at them (:mod:`records.sources`).
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
    rsn : int
        PEER NGA-West2 record sequence number.
    peer_component : str
        Station and component code ending the name of the PEER file used (``PUL164`` of
        ``RSN77_SFERN_PUL164.AT2``): the recorded component closest to fault-normal, or the one
        Table 5.1's PGA belongs to.
    peer_file : str
        That file's name in a PEER NGA-West2 download.
    peer_note : str
        What is confirmed of the name, and how the component relates to Table 5.1.
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
    rsn: int = 0
    peer_component: str = ""
    peer_file: str = ""
    peer_note: str = ""

    @property
    def name(self) -> str:
        """Display name, e.g. "San Fernando 1971, Pacoima Dam"."""
        return f"{self.event} {self.year}, {self.station}"


SEED_CATALOGUE: dict[str, RecordFacts] = {
    facts.id: facts
    for facts in (
        RecordFacts("pacoima_dam_1971", "San Fernando", 1971, "Pacoima Dam", "fault-normal",
                    1.226, 1.20, 1.3, "B", 1.59, 0.50, 77, "PUL164",
                    "RSN77_SFERN_PUL164.AT2", "164°, close to fault-normal"),
        RecordFacts("el_centro_5_1979", "Imperial Valley", 1979, "El Centro Array #5", "fault-normal",
                    0.379, 0.90, 3.2, "D", 1.34, 0.81, 180, "E05230",
                    "RSN180_IMPVALL.H_H-E05230.AT2",
                    "230°, 3° off fault-normal; named like the 140° file of the same record"),
        RecordFacts("los_gatos_1989", "Loma Prieta", 1989, "Los Gatos", "fault-normal",
                    0.563, 0.95, 3.0, "D", 1.94, 1.83, 779, "LGP000",
                    "RSN779_LOMAP_LGP000.AT2",
                    "Los Gatos Presentation Center (LGPC), 000°; sequence number and file name "
                    "not confirmed here: check the station in the PEER search"),
        RecordFacts("rinaldi_1994", "Northridge", 1994, "Rinaldi", "fault-normal",
                    0.838, 1.75, 1.0, "C", 1.56, 0.69, 1063, "RRS228",
                    "RSN1063_NORTHR_RRS228.AT2", "228°, 16° off fault-normal"),
        RecordFacts("sylmar_1994", "Northridge", 1994, "Sylmar", "fault-normal",
                    0.732, 1.20, 2.3, "D", 1.56, 0.80, 1086, "SYL360",
                    "RSN1086_NORTHR_SYL360.AT2", "360°, as recorded"),
        RecordFacts("erzincan_1992", "Erzincan, Turkey", 1992, "Erzincan", "fault-normal",
                    0.515, 0.70, 1.8, rsn=821, peer_component="ERZ-NS",
                    peer_file="RSN821_ERZIKAN_ERZ-NS.AT2",
                    peer_note="N-S as recorded, the component of Table 5.1's PGA; file name not "
                              "confirmed here"),
        RecordFacts("takatori_1995", "Kobe", 1995, "Takatori", "fault-normal",
                    0.611, 1.25, None, rsn=1120, peer_component="TAK000",
                    peer_file="RSN1120_KOBE_TAK000.AT2",
                    peer_note="000°, the component of Table 5.1's PGA"),
    )
}

#: Takatori has no main-pulse period in Table 5.1; the built-in pulse suite uses this one.
DEFAULT_PULSE_PERIOD_S = 1.0


def download_hint(facts: RecordFacts) -> str:
    """Where a user gets this record: its PEER NGA-West2 sequence number and file, and the option
    that reads it."""
    return (f"download RSN {facts.rsn} from the PEER NGA-West2 database and save "
            f"{facts.peer_file} ({facts.peer_note}) in a folder, then read the records from it")


def record_facts(record_id: str) -> RecordFacts:
    """Catalogue entry of a seed record; :class:`InputError` for an unknown id."""
    try:
        return SEED_CATALOGUE[record_id]
    except KeyError:
        known = ", ".join(SEED_CATALOGUE)
        raise InputError(f"record id: unknown '{record_id}', the catalogue has {known}") from None
