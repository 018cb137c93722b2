"""Hazard-curve readers: the real files of OpenQuake's demo run and of the USGS service, and
bad files (one line naming the file and the field)."""

import json
import math

import numpy as np
import pytest

from audit.errors import InputError
from records.hazard import read_hazard, read_openquake_curve, read_plain_curve, read_usgs_curve

SA1 = "openquake-demo/hazard_curve-mean-SA(1.0)_2.csv"


def _oq_text(levels, rows, imt="SA(1.0)", years=50.0):
    """An export in the engine's layout, written here line by line."""
    header = "lon,lat,depth," + ",".join(f"poe-{x:.7f}" for x in levels)
    meta = (f"generated_by='OpenQuake engine 3.26.2', kind='mean', "
            f"investigation_time={years}, imt='{imt}'")
    lines = ["#" + "," * (len(levels) + 2) + f'"{meta}"', header]
    lines += [f"{lon:.5f},{lat:.5f},0.00000," + ",".join(f"{p:.6E}" for p in poes)
              for lon, lat, poes in rows]
    return "\n".join(lines) + "\n"


def test_openquake_poe_to_annual_rate_at_the_readme_levels(hazard_dir):
    # the file's README: SA(1.0) at site (0.0, -0.3): level 0.1034991 g poe 0.6628807 in 50
    # years, and the tabulated rates; λ = −ln(1 − poe)/50
    curve = read_hazard(hazard_dir / SA1, site=(0.0, -0.3))
    assert curve.im_name == "SA(1.0)" and curve.site == (0.0, -0.3)
    level = np.argmin(np.abs(curve.im_g - 0.1034991))
    assert curve.annual_rate[level] == pytest.approx(-math.log(1 - 0.6628807) / 50, rel=1e-6)
    for im_g, rate in ((0.103, 2.17e-2), (0.398, 2.03e-3), (1.093, 1.41e-4), (3.0, 3.45e-6)):
        j = np.argmin(np.abs(curve.im_g - im_g))
        assert curve.annual_rate[j] == pytest.approx(rate, rel=6e-3)
    # the engine's hazard map: 0.390 g at 1/475 per year (log-log interpolation)
    at_475 = np.exp(np.interp(math.log(1 / 475), np.log(curve.annual_rate[::-1]),
                              np.log(curve.im_g[::-1])))
    assert at_475 == pytest.approx(0.390, abs=0.0015)


def test_openquake_sites_matched_by_location_not_row(hazard_dir):
    # the engine writes site (-1, 1) first; its curve is the lowest of the three
    rows = (hazard_dir / SA1).read_text().splitlines()[2:]
    first = [float(v) for v in rows[0].split(",")]
    assert first[:2] == [-1.0, 1.0]
    curve = read_openquake_curve(hazard_dir / SA1, site=(-1.0, 1.0))
    assert curve.annual_rate[0] == pytest.approx(-math.log(1 - first[3]) / 50, rel=1e-6)
    other = read_openquake_curve(hazard_dir / SA1, site=(1.3, 0.0))
    assert other.annual_rate[5] != curve.annual_rate[5]
    # the same site written to within the tolerance
    assert read_openquake_curve(hazard_dir / SA1, site=(1.3004, -0.0004)).site == (1.3, 0.0)


def test_openquake_exact_zeros_kept_at_the_top(hazard_dir):
    curve = read_openquake_curve(hazard_dir / SA1, site=(-1.0, 1.0))
    zeros = np.flatnonzero(curve.annual_rate == 0)
    assert zeros.size == 7 and zeros[-1] == curve.im_g.size - 1
    assert np.all(np.diff(zeros) == 1)  # all at the top
    assert curve.im_g[-1] == pytest.approx(3.0)


def test_openquake_repeated_values_near_one_are_a_flat_stretch(hazard_dir):
    curve = read_openquake_curve(hazard_dir / "openquake-demo/hazard_curve-mean-PGA_2.csv",
                                 site=(0.0, -0.3))
    assert curve.annual_rate[0] == curve.annual_rate[1]  # poe 0.9999999 twice (float32)
    assert np.all(np.diff(curve.annual_rate) <= 0)


@pytest.mark.parametrize("imt", ["PGA", "SA(0.3)", "SA(1.0)", "SA(2.0)"])
def test_every_demo_file_and_site_reads(hazard_dir, imt):
    for site in ((0.0, -0.3), (1.3, 0.0), (-1.0, 1.0)):
        curve = read_hazard(hazard_dir / f"openquake-demo/hazard_curve-mean-{imt}_2.csv", site)
        assert curve.im_name == imt and curve.im_g.size == 20


def test_usgs_static_response(hazard_dir):
    path = hazard_dir / "usgs-example.json"
    document = json.loads(path.read_text())
    for k, imt in enumerate(("PGA", "SA(0.2)", "SA(1.0)")):
        curve = read_usgs_curve(path, imt=imt, site=(-118.0, 34.0))
        assert curve.im_name == imt
        # already annual rates: the file's numbers as they are
        assert curve.annual_rate.tolist() == document["response"][k]["data"][0]["yvals"]
        assert curve.im_g.tolist() == document["response"][k]["metadata"]["xvals"]
    assert read_usgs_curve(path, imt="SA1P0").period_s == 1.0


def test_usgs_dynamic_response_takes_the_total(tmp_path):
    path = tmp_path / "dynamic.json"
    path.write_text(json.dumps({"status": "success", "response": [{
        "metadata": {"imt": {"value": "SA1P0"}, "xvalues": [0.1, 0.2, 0.4],
                     "longitude": -122.3, "latitude": 37.8},
        "data": [{"component": "Fault", "yvalues": [0.01, 0.004, 0.001]},
                 {"component": "Total", "yvalues": [0.03, 0.01, 0.002]}]}]}))
    curve = read_hazard(path)
    assert curve.annual_rate.tolist() == [0.03, 0.01, 0.002] and curve.im_name == "SA(1.0)"


def test_plain_csv(tmp_path):
    path = tmp_path / "curve.csv"
    path.write_text("# imt=PGA\nim_g,annual_rate\n0.1,0.02\n0.2,0.005\n0.4,0.0008\n")
    curve = read_hazard(path)
    assert curve.imt == "PGA" and curve.annual_rate.tolist() == [0.02, 0.005, 0.0008]
    assert curve.site is None


def _one_line(excinfo, *words):
    message = str(excinfo.value)
    assert "\n" not in message
    for word in words:
        assert word in message, message


def test_missing_site(hazard_dir):
    with pytest.raises(InputError) as excinfo:
        read_openquake_curve(hazard_dir / SA1, site=(0.5, -0.5))
    _one_line(excinfo, "hazard_curve-mean-SA(1.0)_2.csv", "site", "(0.5, -0.5)", "(0, -0.3)")
    with pytest.raises(InputError) as excinfo:
        read_openquake_curve(hazard_dir / SA1)
    _one_line(excinfo, "site", "3 sites")


def test_usgs_site_that_is_not_the_response(hazard_dir):
    with pytest.raises(InputError) as excinfo:
        read_usgs_curve(hazard_dir / "usgs-example.json", imt="PGA", site=(-117.0, 34.0))
    _one_line(excinfo, "usgs-example.json", "site")
    with pytest.raises(InputError) as excinfo:
        read_usgs_curve(hazard_dir / "usgs-example.json")
    _one_line(excinfo, "imt", "PGA, SA(0.2), SA(1.0)")


def test_non_monotone_curve(tmp_path):
    path = tmp_path / "oq.csv"
    path.write_text(_oq_text([0.1, 0.2, 0.4], [(0.0, 0.0, [0.5, 0.6, 0.1])]))
    with pytest.raises(InputError) as excinfo:
        read_openquake_curve(path)
    _one_line(excinfo, "oq.csv", "rate at 0.2 g", "rises")


@pytest.mark.parametrize("value, field", [("-1.0E-02", "poe-0.4000000"),
                                          ("nan", "poe-0.4000000"),
                                          ("x", "poe-0.4000000")])
def test_bad_probability(tmp_path, value, field):
    path = tmp_path / "oq.csv"
    text = _oq_text([0.1, 0.2, 0.4], [(0.0, 0.0, [0.5, 0.2, 0.1])])
    path.write_text(text.replace("1.000000E-01\n", value + "\n"))
    with pytest.raises(InputError) as excinfo:
        read_openquake_curve(path)
    _one_line(excinfo, "oq.csv", field)


@pytest.mark.parametrize("rate", ["-0.001", "nan"])
def test_negative_or_nan_rate(tmp_path, rate):
    path = tmp_path / "curve.csv"
    path.write_text(f"# imt=PGA\nim_g,annual_rate\n0.1,0.02\n0.2,0.005\n0.4,{rate}\n")
    with pytest.raises(InputError) as excinfo:
        read_plain_curve(path)
    _one_line(excinfo, "curve.csv", "rate at 0.4 g")


def test_missing_columns_and_metadata(tmp_path):
    path = tmp_path / "curve.csv"
    path.write_text("# imt=PGA\nim_g,rate\n0.1,0.02\n0.2,0.005\n")
    with pytest.raises(InputError) as excinfo:
        read_plain_curve(path)
    _one_line(excinfo, "curve.csv", "annual_rate")
    path.write_text("im_g,annual_rate\n0.1,0.02\n0.2,0.005\n")
    with pytest.raises(InputError) as excinfo:
        read_plain_curve(path)
    _one_line(excinfo, "curve.csv", "imt")
    oq = tmp_path / "oq.csv"
    oq.write_text(_oq_text([0.1, 0.2], [(0.0, 0.0, [0.5, 0.2])]).replace("lat,", "latitude,"))
    with pytest.raises(InputError) as excinfo:
        read_openquake_curve(oq)
    _one_line(excinfo, "oq.csv", "lat")
    oq.write_text(_oq_text([0.1, 0.2], [(0.0, 0.0, [0.5, 0.2])]).replace(
        "investigation_time", "time"))
    with pytest.raises(InputError) as excinfo:
        read_hazard(oq)  # no longer looks like an export: read as plain CSV, which it is not
    _one_line(excinfo, "oq.csv", "imt")


def test_imt_not_read(tmp_path):
    oq = tmp_path / "oq.csv"
    oq.write_text(_oq_text([0.1, 0.2], [(0.0, 0.0, [0.5, 0.2])], imt="PGV"))
    with pytest.raises(InputError) as excinfo:
        read_openquake_curve(oq)
    _one_line(excinfo, "oq.csv", "imt", "PGV")
