"""``audit check`` on the hazard/site/sliding path: the site's intensity read on the hazard curve
at a return period against an interpolation written out here from the file's own numbers,
probabilities typed as percentages, western coordinates, the USGS service's layout (the total is
the ``Total`` entry), and sliding against the closed form of a block that never lifts off
(its pure-rocking response needs |üg|/g of friction)."""

from __future__ import annotations

import csv
import json
import math

import pytest

import audit
from audit.api import Hazard
from audit.cli import build_parser, main
from audit.engine.check.settings import CheckSettings
from audit.engine.shared.fields import probability
from audit.errors import InputError
from tests.engine.check.pulses import PERIODS_S, eight_pulses

SITE = (1.5, 0.9)  # PGA of the design spectrum 0.4 S_XS = 0.6 g; S_X1 = 0.9 g
OQ_SA1 = "openquake-demo/hazard_curve-mean-SA(1.0)_2.csv"



def _interpolated_by_hand(path, lon, lat, years):
    """The level exceeded once in ``years`` at (lon, lat): the export's row read with the csv
    module, λ = −ln(1 − poe)/50 at each level (the README's conversion), and ln im linear in
    ln λ between the two levels whose rates bracket 1/years."""
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    header = rows[1]
    levels = [float(name[len("poe-"):]) for name in header[3:]]
    row = next(r for r in rows[2:] if abs(float(r[0]) - lon) < 1e-6
               and abs(float(r[1]) - lat) < 1e-6)
    rates = [-math.log(1.0 - float(p)) / 50.0 for p in row[3:]]
    target = 1.0 / years
    for k in range(len(levels) - 1):
        if rates[k] >= target >= rates[k + 1] > 0:
            t = (math.log(target) - math.log(rates[k])) / (math.log(rates[k + 1])
                                                          - math.log(rates[k]))
            return math.exp(math.log(levels[k]) + t * math.log(levels[k + 1] / levels[k]))
    raise AssertionError("no bracket")


def test_return_period_sets_the_exact_answers_intensity_from_the_curve(hazard_dir):
    path = hazard_dir / OQ_SA1
    expected = _interpolated_by_hand(path, 0.0, -0.3, 2475.0)
    assert expected == pytest.approx(0.764, rel=0.01)  # the engine's own hazard map (README)
    with pytest.warns(UserWarning, match="hazard curve gives sa:1 = 0.7"):
        result = audit.check(["0.4x1.8"], SITE, procedures=["fema356"], records=eight_pulses(),
                             hazard=audit.Hazard(path, location=(0.0, -0.3), return_period=2475),
                             solver=audit.Solver(free_motion_s=5.0))
    document = result.document
    assert document["site_im"] == pytest.approx(expected, rel=0.01)
    assert document["objects"][0]["exact"]["site_im_g"] == document["site_im"]
    # a stripe at the curve's intensity, beside the fixed lattice; the guidelines keep S_X1 = 0.9 g
    assert document["site_im"] in document["levels"]
    assert document["design_im"] == pytest.approx(0.9)
    site_hazard = document["site_hazard"]
    assert site_hazard["return_period_years"] == 2475
    assert "+" not in site_hazard["warning"] and "-15 %" in site_hazard["warning"]
    assert "hazard curve at 2,475 years" in result.summary_text()
    # 2 % in 50 years is a return period of −50/ln(0.98) = 2474.9 years
    by_poe = CheckSettings.parse(hazard=Hazard(path, location=(0.0, -0.3), poe="2%"))
    assert by_poe.site_return_period_years == pytest.approx(-50.0 / math.log(0.98))


def test_poe_and_return_period_need_a_hazard_and_one_of_them(hazard_dir):
    with pytest.raises(InputError, match="^hazard.return_period:.*no curve") as excinfo:
        CheckSettings.parse(hazard=Hazard(None, return_period=475))
    assert excinfo.value.fields == ("hazard.return_period",)
    with pytest.raises(InputError, match="return_period and hazard.poe"):
        CheckSettings.parse(hazard=Hazard(hazard_dir / OQ_SA1, location=(0.0, -0.3),
                                          return_period=475, poe=0.1))
    with pytest.raises(InputError, match="^hazard.return_period: the hazard curve .* covers"):
        audit.check(["0.4x1.8"], SITE, records=eight_pulses(),
                    hazard=Hazard(hazard_dir / OQ_SA1, location=(0.0, -0.3), return_period=1e9))


@pytest.mark.parametrize("given, expected", [("2%", 0.02), ("2 %", 0.02), (0.02, 0.02),
                                             ("0.1", 0.1), ("10%", 0.1)])
def test_a_probability_may_be_a_percentage(given, expected):
    assert probability("risk_target", given) == pytest.approx(expected)
    assert CheckSettings.parse(hazard=Hazard(None, risk_target=given)).risk_target == \
        pytest.approx(expected)


@pytest.mark.parametrize("given", ["2", "0%", "100%", "two", None, True, float("nan")])
def test_a_probability_outside_0_1_is_refused_naming_the_argument(given):
    with pytest.raises(InputError) as excinfo:
        CheckSettings.parse(hazard=Hazard(None, risk_target=given))
    assert excinfo.value.fields == ("hazard.risk_target",)


def test_the_command_line_takes_percentages_and_western_coordinates():
    args = build_parser().parse_args(["check", "--block", "0.6x1.8", "--site", "1,0.6",
                                      "--hazard", "x.json", "--site-location", "-118,34",
                                      "--risk-target", "2%", "--poe", "10%"])
    assert args.site_location == "-118,34"
    # the percentages reach the settings as typed, which read them
    assert probability("risk_target", args.risk_target) == pytest.approx(0.02)
    assert probability("poe", args.poe) == pytest.approx(0.1)
    args = build_parser().parse_args(["margins", "all", "--site", "1,0.6", "--hazard", "x.json",
                                      "--site-location", "-118.25,-34.5"])
    assert args.site_location == "-118.25,-34.5"


def test_usgs_file_from_the_command_line_with_its_imt(hazard_dir, seed_manifest, tmp_path,
                                                      capsys):
    out = tmp_path / "out"
    assert main(["check", "fema356", "--block", "0.4x1.8", "--site", "1.0,0.6",
                 "--hazard", str(hazard_dir / "usgs-example.json"), "--hazard-imt", "SA(1.0)",
                 "--site-location", "-118,34", "--records", str(seed_manifest),
                 "--out", str(out)]) == 0
    document = json.loads((out / "check.json").read_text())
    assert document["im"] == "sa:1" and document["hazard"]["im"] == "SA(1.0)"
    assert "site (-118, 34)" in document["hazard"]["source"]


def test_the_usgs_file_is_read_at_the_ims_imt(hazard_dir):
    path = hazard_dir / "usgs-example.json"
    by_im = CheckSettings.parse(hazard=path, im="sa:1.0")
    assert by_im.hazard.im_name == "SA(1.0)" and by_im.im.name == "sa:1"
    by_imt = CheckSettings.parse(hazard=Hazard(path, imt="PGA"))
    assert by_imt.im.name == "pga"
    assert by_imt.hazard.annual_rate.tolist() == \
        json.loads(path.read_text())["response"][0]["data"][0]["yvals"]
    with pytest.raises(InputError, match="hazard.imt") as excinfo:
        CheckSettings.parse(hazard=path)
    assert "hazard.imt" in excinfo.value.fields


def test_the_imt_mismatch_keeps_the_services_name(hazard_dir, capsys):
    assert main(["check", "--block", "0.4x1.8", "--site", "1.0,0.6", "--im", "sa:1.0",
                 "--hazard", str(hazard_dir / "usgs-example.json"), "--hazard-imt", "PGA"]) == 2
    error = capsys.readouterr().err.strip()
    assert "\n" not in error and error.startswith("error: --hazard: imt:")
    assert "USGS hazard service" in error and "--hazard service" not in error
    assert "--im" in error


def _dynamic(tmp_path, data, name="dynamic.json"):
    path = tmp_path / name
    path.write_text(json.dumps({"status": "success", "response": [{
        "metadata": {"imt": {"value": "SA1P0"}, "xvalues": [0.1, 0.2, 0.4],
                     "longitude": -122.3, "latitude": 37.8}, "data": data}]}))
    return path


def test_a_dynamic_response_without_its_total_is_refused(tmp_path, capsys):
    path = _dynamic(tmp_path, [{"component": "Fault", "yvalues": [0.01, 0.004, 0.001]},
                               {"component": "Grid", "yvalues": [0.02, 0.006, 0.001]}])
    with pytest.raises(InputError, match="dynamic.json: response\\[0\\]: data: no entry with "
                                         "component 'Total'"):
        audit.check(["0.4x1.8"], SITE, records=eight_pulses(), hazard=path)
    assert main(["check", "--block", "0.4x1.8", "--site", "1.0,0.6",
                 "--hazard", str(path)]) == 2
    error = capsys.readouterr().err.strip()
    assert "\n" not in error and "dynamic.json" in error and "Total" in error


@pytest.mark.parametrize("data, kind", [([0.01, 0.004, 0.001], "float"),
                                        (["0.01", "0.004"], "str"), ([[0.1]], "list")])
def test_data_of_numbers_or_strings_is_refused_in_one_line(tmp_path, capsys, data, kind):
    path = _dynamic(tmp_path, data)
    assert main(["check", "--block", "0.4x1.8", "--site", "1.0,0.6",
                 "--hazard", str(path)]) == 2
    error = capsys.readouterr().err.strip()
    assert "\n" not in error and "Traceback" not in error
    assert "dynamic.json: response[0]: data[0]: expected an object" in error and kind in error


BLOCK = "0.8x1.2"  # tan α = 0.667 > 0.6: at PGA 0.6 g it never lifts off


@pytest.fixture(scope="module")
def stocky():
    def run(**options):
        return audit.check([BLOCK, "0.3x1.8"], SITE, procedures=["fema356"],
                           records=eight_pulses(), im="pga",
                           solver=audit.Solver(free_motion_s=5.0), **options).document
    return {mu: run(**({} if mu is None else {"friction": mu})) for mu in (None, 10.0, 0.2)}


def _without_sliding(document):
    out = json.loads(json.dumps(document))
    out.pop("friction")
    for obj in out["objects"]:
        obj.pop("sliding")
        obj.pop("sentence")
    return out


def test_friction_10_reproduces_the_frictionless_answer(stocky):
    assert _without_sliding(stocky[10.0]) == _without_sliding(stocky[None])
    for obj in stocky[10.0]["objects"]:
        assert obj["sliding"]["mode"] == "rocking" and obj["sliding"]["records_sliding"] == []
    assert all("assumes no sliding" in obj["sentence"] for obj in stocky[None]["objects"])


def test_a_block_that_never_lifts_needs_the_records_peak_acceleration(stocky):
    # at rest, H/V = |üg|/g: each pulse scaled to PGA 0.6 g needs μ = 0.6 exactly
    sliding = stocky[None]["objects"][0]["sliding"]
    assert sliding["tan_alpha"] == pytest.approx(0.8 / 1.2)
    assert sliding["required_friction_median"] == pytest.approx(0.6, rel=1e-6)
    assert sliding["required_friction_max"] == pytest.approx(0.6, rel=1e-6)


def test_a_stocky_block_on_mu_02_slides_before_it_rocks(stocky):
    stocky_on_02 = stocky[0.2]["objects"][0]
    sliding = stocky_on_02["sliding"]
    assert sliding["mode"] == "sliding" and len(sliding["records_sliding"]) == len(PERIODS_S)
    # every record slides it: the sentence leads with that, the rocking answer follows
    text = stocky_on_02["sentence"]
    assert sliding["governs"] and text.startswith("0.8x1.2 (0.8 m wide × 1.2 m tall): On μ = 0.2 "
                                                  "it slides before it can rock")
    assert (text.index("slides before it can rock") < text.index("If it could not slide:")
            < text.index("exact P(overturn)"))
    assert "does not apply" not in text
    # without friction, or on a base that holds, the rocking answer comes first
    for mu in (None, 10.0):
        head = stocky[mu]["objects"][0]
        assert not head["sliding"]["governs"] and "If it could not slide" not in head["sentence"]
        assert head["sentence"].index("exact P(overturn)") < head["sentence"].index(" μ ")
    # the slender one (tan α = 1/6 < 0.2) rocks; its records' rocking needs more than 0.2
    slender = stocky[0.2]["objects"][1]["sliding"]
    assert slender["tan_alpha"] < 0.2 and slender["mode"] != "rocking"


@pytest.mark.parametrize("given", [(-118, 34), [-118.0, 34.0], "-118,34", "-118, 34"])
def test_a_site_location_is_a_pair_or_its_text(hazard_dir, given):
    settings = CheckSettings.parse(hazard=Hazard(hazard_dir / "usgs-example.json", imt="PGA",
                                                 location=given))
    assert settings.hazard.site == (-118.0, 34.0)


@pytest.mark.parametrize("given", ["-118", "west,34", (1, 2, 3), 5.0, (-118, 95)])
def test_a_bad_site_location_names_the_argument(hazard_dir, given):
    with pytest.raises(InputError) as excinfo:
        CheckSettings.parse(hazard=Hazard(hazard_dir / "usgs-example.json", imt="PGA",
                                          location=given))
    assert excinfo.value.fields == ("hazard.location",)


def test_sliding_governs_when_most_records_slide_the_object():
    from audit.engine.check.sliding import sliding_answer
    ids = ["a", "b", "c", "d"]
    # tan α = 1/3 > μ = 0.2: each record needing more than 0.2 slides it before it rocks
    for needed, governs in (([0.5, 0.6, 0.7, 0.1], True), ([0.5, 0.6, 0.1, 0.1], False),
                            ([0.1] * 4, False)):
        answer = sliding_answer(needed, ids, math.degrees(math.atan(1 / 3)), 0.2)
        assert answer["governs"] is governs
        assert ("does not apply" in answer["text"]) is (not governs and answer["mode"] == "sliding")
    # tan α = 0.1 ≤ μ: it rocks, and slides while rocking under the records needing more
    answer = sliding_answer([0.5, 0.6, 0.7, 0.1], ids, math.degrees(math.atan(0.1)), 0.2)
    assert answer["governs"] and answer["mode"] == "sliding"
    assert answer["text"].startswith("On μ = 0.2 sliding governs")
