"""``audit check --hazard``: each object's annual rate of overturning against the Cornell et al.
(2002) closed form of its own fitted fragility, the P in 50 years of the object as a guideline
sizes it against a separate check of that object, the exact width for the risk target against
checks either side of it, and the hazard curve's intensity measure held to the check's."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.stats import norm

import audit
from audit.cli import main
from audit.errors import InputError
from tests.engine.check.pulses import eight_pulses
from records.hazard import HazardCurve

SITE = (1.5, 0.9)  # PGA of the design spectrum 0.4 S_XS = 0.6 g
K0, K = 2e-6, 2.5  # λ(s) = K0 s^−K, s in g
TARGET = 0.02



def _power_law(levels=np.geomspace(1e-4, 60.0, 90)):
    return HazardCurve.checked("PGA", levels, K0 * levels ** -K, "power law")


def _check(objects, **options):
    return audit.check(objects, SITE, procedures=["fema356", "priestley1978"],
                       records=eight_pulses(), im="pga",
                       hazard=audit.Hazard(_power_law(), risk_target=TARGET),
                       solver=audit.Solver(free_motion_s=5.0), **options)


@pytest.fixture(scope="module")
def result():
    return _check(["0.4x1.8"])


def test_annual_rate_is_the_cornell_closed_form_of_the_objects_fit(result):
    obj = result.document["objects"][0]
    theta, beta = obj["exact"]["median_g"], obj["exact"]["beta"]
    cornell = K0 * theta ** -K * math.exp(0.5 * K * K * beta * beta)
    risk = obj["risk"]
    assert risk["annual_rate"] == pytest.approx(cornell, rel=0.01)
    assert risk["p50"] == pytest.approx(-math.expm1(-50 * cornell), rel=0.01)
    assert risk["im"] == "PGA" and risk["hazard_source"] == "power law"
    assert risk["meets_target"] == (risk["p50"] <= TARGET) and not risk["truncated"]
    # below the lowest stripe s0: ∫ Φ((x − ln θ)/β) |dλ| for x = ln s < ln s0, by parts
    # = λ_ov Φ((ln s0 − ln θ + Kβ²)/β) − λ(s0) Φ((ln s0 − ln θ)/β)
    s0 = min(obj["exact"]["stripes"]["im"])
    below = (norm.cdf((math.log(s0 / theta) + K * beta ** 2) / beta)
             - K0 * s0 ** -K * norm.cdf(math.log(s0 / theta) / beta) / cornell)
    assert risk["share_below_stripes"] == pytest.approx(below, abs=0.005)
    assert result.document["hazard"]["target_p50"] == TARGET


def test_a_guidelines_risk_is_that_of_the_object_at_the_width_it_requires(result):
    obj = result.document["objects"][0]
    proc = next(p for p in obj["procedures"] if p["risk_p50"] is not None)
    width = proc["required_width_m"]
    sized = _check([("sized", width, obj["height_m"])]).document["objects"][0]
    # the same block solved through the object's own stripes, fitted by the slow single fit
    assert proc["risk_p50"] == pytest.approx(sized["risk"]["p50"], rel=0.02)


def test_the_exact_width_for_the_target_is_where_p50_crosses_it(result):
    obj = result.document["objects"][0]
    width = obj["risk"]["required_width_m"]
    assert width is not None and 0.0 < width < obj["height_m"]
    either_side = _check([("at", width, obj["height_m"]),
                          ("narrower", width / 1.03, obj["height_m"])]).document["objects"]
    assert either_side[0]["risk"]["p50"] <= TARGET * 1.02  # the fit's, on the safe side
    assert either_side[1]["risk"]["p50"] > TARGET


def test_files_and_page_carry_the_risk(result, tmp_path):
    result.write(tmp_path)
    document = json.loads((tmp_path / "check.json").read_text())
    assert document["hazard"]["curve"]["im_g"][0] == pytest.approx(1e-4)
    csv = (tmp_path / "check.csv").read_text().splitlines()
    header = csv[0].split(",")
    row = dict(zip(header, csv[1].split(",")))
    assert float(row["p50"]) == pytest.approx(document["objects"][0]["risk"]["p50"], rel=1e-5)
    page = (tmp_path / "check.html").read_text()
    assert "Risk at the site" in page and "risk1" in page
    assert "P in 50 years" in result.summary_text() and "/yr" in result.sentences[0]


def test_the_hazard_curve_sets_the_intensity_measure():
    sa = HazardCurve.checked("SA(1.0)", np.geomspace(0.01, 5, 20),
                             1e-4 * np.geomspace(0.01, 5, 20) ** -2.0, "sa curve")
    with pytest.raises(InputError, match="im.*SA\\(1.0\\).*pga"):
        audit.check(["0.4x1.8"], SITE, records=eight_pulses(), im="pga", hazard=sa)
    with pytest.raises(InputError, match="^hazard.location"):
        audit.check(["0.4x1.8"], SITE, records=eight_pulses(),
                    hazard=audit.Hazard(None, location=(0.0, -0.3)))
    with pytest.raises(InputError, match="^hazard.risk_target"):
        audit.check(["0.4x1.8"], SITE, records=eight_pulses(),
                    hazard=audit.Hazard(sa, risk_target=1.5))


def test_cli_refuses_a_hazard_of_another_im_in_one_line(tmp_path, capsys):
    curve = tmp_path / "curve.csv"
    curve.write_text("# imt=SA(1.0)\nim_g,annual_rate\n0.1,1e-2\n0.5,1e-3\n1.0,1e-4\n")
    out = tmp_path / "out"
    assert main(["check", "--block", "0.6x1.8", "--site", "1.5,0.9", "--im", "pga",
                 "--hazard", str(curve), "--out", str(out)]) == 2
    error = capsys.readouterr().err.strip()
    assert "\n" not in error and "--im" in error and "SA(1.0)" in error
    assert not out.exists()
