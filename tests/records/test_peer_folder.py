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
    assert "in a folder, then read the records from it" in missing.missing_reason


def test_list_says_which_files_to_download(capsys, monkeypatch):
    monkeypatch.delenv("ROCKING_AUDIT_RECORDS", raising=False)
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for record in ("el_centro_5_1979", "los_gatos_1989", "pacoima_dam_1971", "takatori_1995"):
        facts = SEED_CATALOGUE[record]
        assert f"RSN {facts.rsn}" in out and facts.peer_file in out
    assert "shared" not in out and "SPEC" not in out


# --- a PEER download folder: the .AT2 files and the _SearchResults.csv beside them -------------

LANDERS = ("RSN879_LANDERS_LCN260.AT2", "RSN879_LANDERS_LCN345.AT2")
HEADER = ("Result ID, Spectral Ordinate, Record Sequence Number, Mean Squared Error, Scale Factor,"
          " Tp-Pulse Period (sec), Earthquake Name, Year, Station Name, Magnitude, Mechanism,"
          " Rjb (km), Rrup (km), Vs30 (m/sec), Lowest Useable Frequency (Hz),"
          " Horizontal-1 Acc. Filename, Horizontal-2 Acc. Filename, Vertical Acc. Filename,,,")


def _search_results(folder, rows, header=HEADER):
    """A _SearchResults.csv in PEER's layout: the search criteria, the records table (leading
    spaces, names in doubled quotes, trailing empty columns), a blank row, then notes."""
    lines = [" PEER Ground Motion Database, Time Series Search Report -- NGA-West2,,,,",
             ",,,,", " -- Summary of PEER Ground Motion Database Search Criteria --,,,,",
             "Magnitude Min:,6.5,,,", ",,,,", " -- Summary of Metadata of Selected Records --,,,,",
             header, *rows, ",,,,,,,,,,,,,,,,,,,,",
             " These records were obtained from the NGA-West2 On-Line Ground-Motion Database,,,",
             " These records are UNSCALED, AS RECORDED,,,"]
    (folder / "_SearchResults.csv").write_text("\n".join(lines) + "\n")


def _row(number, rsn, scale, event, station, files):
    return (f"{number}, SRSS,{rsn},0.1,{scale}, -,\" \"\"{event}\"\"\",1992,\" \"\"{station}\"\"\","
            f"7.28, strike slip,2.19,2.19,1369,0.1, {files[0]}, {files[1]} , {files[2]}  ,,,")


def _at2_g(path):
    """Accelerations of an AT2 file in g, read apart from the project's reader: the values
    after the four header lines."""
    return np.array(" ".join(path.read_text().splitlines()[4:]).split(), dtype=float)


@pytest.fixture
def peer_download(records_dir, tmp_path, monkeypatch):
    """Two real Landers components, a vertical file, a Kobe record whose first component was
    not downloaded, and the search results listing them (Landers × 1.5, Kobe × 2)."""
    monkeypatch.delenv("ROCKING_AUDIT_RECORDS", raising=False)
    raw = records_dir / "raw"
    for name in LANDERS:
        (tmp_path / name).symlink_to(raw / name)
    (tmp_path / "RSN879_LANDERS_LCN-UP.AT2").symlink_to(raw / LANDERS[0])
    (tmp_path / "RSN1120_KOBE_TAK090.AT2").symlink_to(raw / "RSN1120_KOBE_TAK090.AT2")
    _search_results(tmp_path, [
        _row(1, 879, 1.5, "Landers", "Lucerne", (*LANDERS, "RSN879_LANDERS_LCN-UP.AT2")),
        _row(2, 1120, 2, "Kobe_ Japan", "Takatori ",
             ("RSN1120_KOBE_TAK000.AT2", "RSN1120_KOBE_TAK090.AT2", "---"))])
    return tmp_path


def test_peer_download_folder_scales_the_listed_horizontal_components(peer_download,
                                                                      records_dir):
    from audit import G
    suite = load_records(peer_download)
    assert [entry.id for entry in suite] == ["RSN879_LANDERS_LCN260", "RSN879_LANDERS_LCN345",
                                             "RSN1120_KOBE_TAK000", "RSN1120_KOBE_TAK090"]
    for name in LANDERS:  # the vertical file is not a record
        entry = suite.get(name.removesuffix(".AT2"))
        np.testing.assert_allclose(entry.motion.acceleration,
                                   1.5 * G * _at2_g(records_dir / "raw" / name), rtol=1e-12)
        assert "× 1.5" in entry.component and "scale factor" in entry.component
        assert entry.metadata == {
            "rsn": 879, "event": "Landers", "station": "Lucerne", "mechanism": "strike slip",
            "year": 1992, "magnitude": 7.28, "rjb_km": 2.19, "rrup_km": 2.19, "vs30_m_s": 1369.0,
            "scale_factor": 1.5, "peer_file": name,
            "search_results": str(peer_download / "_SearchResults.csv"),
            "vertical_file": "RSN879_LANDERS_LCN-UP.AT2"}
        # the station's vertical file (here a copy of LCN260) rides along, scaled the same
        np.testing.assert_allclose(entry.motion.vertical,
                                   1.5 * G * _at2_g(records_dir / "raw" / LANDERS[0]),
                                   rtol=1e-12)
    kobe = suite.get("RSN1120_KOBE_TAK090")
    assert kobe.metadata["station"] == "Takatori" and "vertical_file" not in kobe.metadata
    assert kobe.motion.vertical is None
    np.testing.assert_allclose(kobe.motion.acceleration,
                               2 * G * _at2_g(records_dir / "raw" / "RSN1120_KOBE_TAK090.AT2"))
    missing = suite.get("RSN1120_KOBE_TAK000")
    assert missing.missing and missing.metadata["rsn"] == 1120
    assert missing.missing_reason == ("RSN1120_KOBE_TAK000.AT2 is listed in _SearchResults.csv "
                                      "but not in the folder")


def test_list_shows_the_search_metadata_and_the_missing_file(peer_download, capsys):
    assert main(["list", "--records", str(peer_download)]) == 0
    out = capsys.readouterr().out
    assert "PEER NGA-West2 search results" in out and "1 listed file(s) not in the folder" in out
    assert ("Landers 1992, Lucerne: RSN 879, M 7.28, strike slip, Rjb 2.2 km, Rrup 2.2 km, "
            "Vs30 1369 m/s, scaled × 1.5") in out
    assert "RSN1120_KOBE_TAK000: MISSING: RSN1120_KOBE_TAK000.AT2 is listed" in out
    assert "LCN-UP" not in out.split("Records (")[1].split("\n", 1)[1]


def test_folder_without_search_results_reads_its_files_unscaled(peer_download, records_dir):
    from audit import G
    (peer_download / "_SearchResults.csv").unlink()
    suite = load_records(peer_download)
    assert "RSN879_LANDERS_LCN-UP" in [entry.id for entry in suite]  # every file, as before
    entry = suite.get("RSN879_LANDERS_LCN260")
    np.testing.assert_allclose(entry.motion.acceleration,
                               G * _at2_g(records_dir / "raw" / LANDERS[0]), rtol=1e-12)
    assert entry.metadata == {}


@pytest.mark.parametrize("header, scale, field", [
    ("Record ID, Record Sequence Number, Scale Factor", "1.5", "Result ID"),
    (HEADER.replace(" Scale Factor,", " Factor,"), "1.5", "Scale Factor"),
    (HEADER, "one and a half", "Scale Factor"),
    (HEADER, "-1", "Scale Factor"),
])
def test_bad_search_results_stop_with_one_line_naming_the_file_and_field(
        peer_download, capsys, header, scale, field):
    _search_results(peer_download, [_row(1, 879, scale, "Landers", "Lucerne",
                                         (*LANDERS, "---"))], header)
    assert main(["list", "--records", str(peer_download)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "_SearchResults.csv" in err[0] and field in err[0]


def test_peer_vertical_files_say_which_way_is_positive():
    from records.peer_search import pointing_down
    assert pointing_down("RSN77_SFERN_PUL-DWN.AT2") and pointing_down("rsn1_x-dwn.at2")
    assert not pointing_down("RSN879_LANDERS_LCN-UP.AT2")
    assert not pointing_down("RSN1063_NORTHR_RRS-V.AT2")


# --- a damaged _SearchResults.csv is refused, not read in part ---------------------------------

@pytest.fixture
def synthetic_download(tmp_path, monkeypatch):
    """Two records of two components and a vertical each (RSN 879 × 1.5, RSN 77 × 2), the
    files synthetic; the table's second row starts on line 9 of the CSV."""
    monkeypatch.delenv("ROCKING_AUDIT_RECORDS", raising=False)
    names = {879: ("RSN879_LANDERS_LCN260.AT2", "RSN879_LANDERS_LCN345.AT2",
                   "RSN879_LANDERS_LCN-UP.AT2"),
             77: ("RSN77_SFERN_PUL164.AT2", "RSN77_SFERN_PUL254.AT2", "RSN77_SFERN_PUL-DWN.AT2")}
    for files in names.values():
        for name in files:
            _at2(tmp_path / name, "Synthetic", 0.01, _pulse(0.2))
    _search_results(tmp_path, [_row(1, 879, 1.5, "Landers", "Lucerne", names[879]),
                               _row(2, 77, 2, "San Fernando", "Pacoima Dam", names[77])])
    return tmp_path


def _refusal(folder, capsys, *args):
    """The one line `audit list` (or the command given) writes for a refused folder."""
    assert main([*(args or ["list"]), "--records", str(folder)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and f"{folder / '_SearchResults.csv'}" in err[0]
    return err[0]


def test_synthetic_download_reads_both_records_scaled(synthetic_download):
    suite = load_records(synthetic_download)
    assert [entry.id for entry in suite] == ["RSN879_LANDERS_LCN260", "RSN879_LANDERS_LCN345",
                                             "RSN77_SFERN_PUL164", "RSN77_SFERN_PUL254"]
    assert suite.get("RSN77_SFERN_PUL164").motion.pga_g == pytest.approx(0.4, rel=1e-6)


def test_search_results_cut_inside_a_row_are_refused(synthetic_download, capsys):
    csv_path = synthetic_download / "_SearchResults.csv"
    text = csv_path.read_bytes()
    csv_path.write_bytes(text[:text.index(b"Pacoima Dam") + 20])  # a download cut short
    message = _refusal(synthetic_download, capsys)
    assert "line 9" in message and "truncated" in message


def test_search_results_cut_between_rows_are_refused(synthetic_download, capsys):
    csv_path = synthetic_download / "_SearchResults.csv"
    lines = csv_path.read_text().splitlines()
    csv_path.write_text("\n".join(lines[:8]) + "\n")  # the header and the first row only
    message = _refusal(synthetic_download, capsys)
    assert "line 8" in message and "blank row" in message and "truncated" in message


def test_search_results_with_no_rows_are_refused(synthetic_download, capsys):
    csv_path = synthetic_download / "_SearchResults.csv"
    lines = csv_path.read_text().splitlines()
    csv_path.write_text("\n".join([*lines[:7], ",,,,"]) + "\n")
    message = _refusal(synthetic_download, capsys)
    assert "line 7" in message and "no records" in message


def test_a_short_row_is_refused_naming_its_line_and_the_first_column_it_lacks(
        synthetic_download, capsys, tmp_path):
    csv_path = synthetic_download / "_SearchResults.csv"
    lines = csv_path.read_text().splitlines()
    lines[8] = ",".join(lines[8].split(",")[:8])  # row 2 stops after Year
    csv_path.write_text("\n".join(lines) + "\n")
    out = tmp_path / "out"
    message = _refusal(synthetic_download, capsys, "run", "fema356", "--out", str(out))
    assert "line 9: Station Name:" in message and "8 cells" in message
    assert not out.exists()


def test_an_unlisted_vertical_file_is_not_read_as_a_horizontal_record(synthetic_download,
                                                                      capsys):
    _at2(synthetic_download / "RSN1120_KOBE_TAK-UP.AT2", "Takatori", 0.01, _pulse(0.1))
    message = _refusal(synthetic_download, capsys)
    assert "RSN1120_KOBE_TAK-UP.AT2: a vertical component" in message
