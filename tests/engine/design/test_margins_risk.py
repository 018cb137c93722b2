"""The design-level audit at a site (``margins --hazard``): each block's rate against the
Cornell et al. (2002) closed form, the slenderness for a risk target against interpolation of
the closed-form probabilities, bad input on the command line, and the page."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from audit.cli import main
from audit.engine.design.margins import MarginsRun
from audit.engine.design.margins_risk import EXACT_RISK, margins_risk
from audit.errors import InputError
from records.hazard import read_hazard

K0, K, BETA = 5e-6, 2.5, 0.4
ALPHAS = (10.0, 20.0, 30.0)
MEDIANS_G = (0.2, 0.4, 0.8)


def _power_law_csv(path, imt="PGA"):
    levels = np.geomspace(1e-3, 50.0, 60)
    lines = [f"# imt={imt}", "im_g,annual_rate"]
    lines += [f"{s:.10g},{K0 * s ** -K:.10g}" for s in levels]
    path.write_text("\n".join(lines) + "\n")
    return path


def _closed_form_p50(median_g):
    rate = K0 * median_g ** -K * math.exp(0.5 * K * K * BETA * BETA)  # Cornell et al. 2002
    return 1.0 - math.exp(-50.0 * rate)


def _run(im="pga"):
    fragility = pd.DataFrame({"alpha_deg": ALPHAS, "size_s": 1.0, "width_m": np.nan,
                              "height_m": np.nan, "im": im,
                              "median": MEDIANS_G, "beta": BETA})
    levels = np.geomspace(0.05, 3.0, 8)
    stripes = pd.DataFrame([{"record": f"r{r}", "alpha_deg": a, "size_s": 1.0, "width_m": np.nan,
                             "height_m": np.nan,
                             "im": im, "im_level": x, "exact_overturned": x * (1 + r / 10) > m}
                            for a, m in zip(ALPHAS, MEDIANS_G) for x in levels
                            for r in range(10)])
    required = pd.DataFrame({"procedure": ["exact@0.10", "someguide"], "size_s": [1.0, 1.0],
                             "required_alpha_deg": [12.0, 15.0],
                             "exact_overturning_share": [0.1, 0.2]})
    return MarginsRun(stripes, fragility, pd.DataFrame(), {"im": im}, required_alpha=required)


def test_block_rates_and_the_risk_targeted_slenderness(tmp_path):
    curve = read_hazard(_power_law_csv(tmp_path / "curve.csv"))
    risk, risk_alpha = margins_risk(_run(), curve, target_p50=0.01)
    expected = [_closed_form_p50(m) for m in MEDIANS_G]
    assert risk["p50_fit"].to_numpy() == pytest.approx(expected, rel=1e-3)
    # the α where ln P crosses ln 0.01, between the grid's 10° and 20° (linear in α)
    ln_p = np.log(expected)
    assert ln_p[0] > math.log(0.01) > ln_p[1]
    alpha = 10.0 + 10.0 * (ln_p[0] - math.log(0.01)) / (ln_p[0] - ln_p[1])
    rows = risk_alpha.set_index("procedure")
    assert rows.loc[EXACT_RISK, "required_alpha_deg"] == pytest.approx(alpha, rel=1e-3)
    assert rows.loc[EXACT_RISK, "p50"] == pytest.approx(0.01, rel=1e-3)
    # a guideline's 15°: P interpolated in ln P halfway between 10° and 20°
    assert rows.loc["someguide", "p50"] == pytest.approx(math.sqrt(expected[0] * expected[1]),
                                                         rel=1e-3)
    assert "exact@0.10" not in rows.index


def test_the_run_and_the_curve_must_share_the_intensity_measure(tmp_path):
    curve = read_hazard(_power_law_csv(tmp_path / "curve.csv", imt="SA(1.0)"))
    with pytest.raises(InputError, match=r"imt: the curve is of SA\(1.0\).*audit is of pga"):
        margins_risk(_run("pga"), curve)


def _two_sites(path):
    meta = "investigation_time=50.0, imt='SA(1.0)'"
    path.write_text(f'#,,,,"{meta}"\nlon,lat,depth,poe-0.1,poe-0.2\n'
                    "0.0,0.0,0.0,0.5,0.1\n1.0,0.0,0.0,0.4,0.05\n")
    return path


@pytest.mark.parametrize("extra, words", [
    (["--hazard", "{tmp}/none.csv"], ["none.csv", "not found"]),
    (["--hazard", "{tmp}/two.csv"], ["two.csv", "site", "2 sites"]),
    (["--hazard", "{tmp}/two.csv", "--site-location", "5,5"], ["two.csv", "site", "(5, 5)"]),
    (["--hazard", "{tmp}/two.csv", "--site-location", "0,0", "--im", "pga"],
     ["imt", "SA(1.0)", "pga"]),
    (["--site-location", "0,0"], ["--site-location", "--hazard"]),
    (["--hazard", "{tmp}/two.csv", "--site-location", "0"], ["--site-location", "LON,LAT"]),
    (["--hazard", "{tmp}/two.csv", "--risk-target", "1.5"], ["--risk-target"]),
])
def test_bad_hazard_options_stop_with_one_line(tmp_path, capsys, extra, words):
    _two_sites(tmp_path / "two.csv")
    args = ["margins", "all", "--out", str(tmp_path / "m")]
    args += [a.replace("{tmp}", str(tmp_path)) for a in extra]
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    for word in words:
        assert word in err[0], err[0]
    assert not (tmp_path / "m").exists()


def test_margins_at_a_site_from_python_and_its_page(tmp_path):
    import audit
    from tests.engine.design.test_margins import LEVELS_G, _suite
    curve = _power_law_csv(tmp_path / "curve.csv")
    result = audit.margins("priestley1978", _suite(), stripes=LEVELS_G, alpha_deg=[15, 25],
                           size_s=[3.0], blocks=["0.8x4"], hazard=curve,
                           solver=audit.Solver(free_motion_s=8.0))
    assert result.summary["im"] == "pga"  # from the curve
    named = result.fragility[result.fragility["width_m"] == 0.8].iloc[0]
    alone = audit.risk(named, curve)
    row = result.risk[result.risk["width_m"] == 0.8].iloc[0]
    assert row["height_m"] == 4.0
    assert row["annual_rate_fit"] == pytest.approx(alone.annual_rate, rel=1e-12)
    assert row["p50_fit"] == pytest.approx(1 - math.exp(-50 * alone.annual_rate), rel=1e-9)
    out = result.write(tmp_path / "m")
    assert {"risk.csv", "risk_alpha.csv", "hazard.csv"} <= {p.name for p in out.iterdir()}
    page = (out / "margins.html").read_text()
    assert "Risk at the site" in page and 'id="risk0"' in page and 'id="riskmap"' in page
    assert f"λ_ov = {row['annual_rate_fit']:.3g}/yr" in page
