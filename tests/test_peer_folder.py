"""A folder of PEER NGA-West2 files as --records: the seed records a user downloaded take their
catalogue ids, Table 5.1 facts and FEMA 356 sites; the rest come from the package or say where
to get them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from audit.cli import main
from records import SEED_CATALOGUE, load_records
from records.sources import is_peer_file_of


def _at2(path, station, dt, values):
    """An AT2 file in the NGA-West2 layout: three text lines, NPTS/DT, five values a line."""
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", f"Synthetic, 01/01/2000, {station}",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS=   {len(values)}, DT=   {dt:.4f} SEC,"]
    lines += ["  ".join(f"{v: .7E}" for v in values[i:i + 5]) for i in range(0, len(values), 5)]
    path.write_text("\n".join(lines) + "\n")


def _pulse(amplitude_g, n=400, dt=0.01):
    t = np.arange(n) * dt
    return amplitude_g * np.sin(2 * math.pi * t / 1.0) * (t < 1.0)


def test_catalogue_names_a_peer_file_for_every_seed_record():
    for facts in SEED_CATALOGUE.values():
        assert facts.rsn > 0 and facts.peer_file.startswith(f"RSN{facts.rsn}_")
        assert is_peer_file_of(facts, facts.peer_file)
        assert is_peer_file_of(facts, facts.peer_file.lower())
    pacoima = SEED_CATALOGUE["pacoima_dam_1971"]
    assert (pacoima.rsn, pacoima.peer_file) == (77, "RSN77_SFERN_PUL164.AT2")
    assert SEED_CATALOGUE["takatori_1995"].rsn == 1120
    # another component of the same record is not the catalogue's
    assert not is_peer_file_of(SEED_CATALOGUE["takatori_1995"], "RSN1120_KOBE_TAK090.AT2")


def test_folder_of_peer_files_maps_them_to_the_catalogue(tmp_path, monkeypatch):
    monkeypatch.delenv("ROCKING_AUDIT_RECORDS", raising=False)
    _at2(tmp_path / "RSN77_SFERN_PUL164.AT2", "Pacoima Dam", 0.01, _pulse(0.5))
    _at2(tmp_path / "RSN1120_KOBE_TAK000.AT2", "Takatori", 0.01, _pulse(0.3))
    _at2(tmp_path / "RSN1120_KOBE_TAK090.AT2", "Takatori", 0.01, _pulse(0.2))
    suite = load_records(tmp_path)
    ids = [entry.id for entry in suite]
    # the seven seed records in catalogue order, then the folder's other file
    assert ids == [*SEED_CATALOGUE, "RSN1120_KOBE_TAK090"]
    pacoima = suite.get("pacoima_dam_1971")
    assert pacoima.motion.pga_g == pytest.approx(0.5, rel=1e-6)
    assert pacoima.facts.pga_g == 1.226  # Table 5.1
    assert (pacoima.site["sxs_g"], pacoima.site["sx1_g"]) == (1.59, 0.50)  # Table 3.1
    assert suite.get("takatori_1995").motion.pga_g == pytest.approx(0.3, rel=1e-6)
    assert suite.get("rinaldi_1994").metadata["p695_id"] == "rsn1063_rrs_032"  # the package's
    missing = suite.get("el_centro_5_1979")
    assert missing.missing and "RSN 180" in missing.missing_reason
    assert "RSN180_IMPVALL.H_H-E05230.AT2" in missing.missing_reason
    assert "--records FOLDER" in missing.missing_reason


def test_list_says_which_files_to_download(capsys, monkeypatch):
    monkeypatch.delenv("ROCKING_AUDIT_RECORDS", raising=False)
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for record in ("el_centro_5_1979", "los_gatos_1989", "pacoima_dam_1971", "takatori_1995"):
        facts = SEED_CATALOGUE[record]
        assert f"RSN {facts.rsn}" in out and facts.peer_file in out
    assert "shared" not in out and "SPEC" not in out
