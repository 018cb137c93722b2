"""``--guideline-spectrum``: on a roof, FEMA 356 (which reads only a design spectrum) says which
spectrum it read, and is judged on the other too; the floor's S_XS, S_X1 read off its spectrum
by ASCE 7-16 §21.4's rule, worked by hand; FEMA 356's line on the floor's spectrum is its uplift
step there, by hand."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

import audit
from audit.cli import main
from audit.engine.check.spectrum_read import floor_design_site
from audit.engine.check.words import summary_text
from audit.errors import InputError
from tests.engine.check.pulses import eight_pulses

SITE = (1.0, 0.6)
BLOCK = "0.7x1.7"
ROOF = {"floor": audit.Floor(1.0, audit.Building(1.0))}


def test_the_floor_site_is_read_off_the_spectrum_by_asce_7_section_21_4():
    period = [0.1, 0.2, 0.5, 1.0, 1.5, 2.0, 4.0, 5.0, 6.0]
    sa_g = [5.0, 1.0, 2.0, 3.0, 2.5, 1.6, 0.5, 0.3, 9.0]  # 0.1 s and 6 s: outside the ranges
    site = floor_design_site({"period_s": period, "floor_median_sa_g": sa_g})
    assert site["sxs_g"] == pytest.approx(0.9 * 3.0)  # the largest Sa over 0.2–5 s
    assert site["sx1_g"] == pytest.approx(1.5 * 2.5)  # the largest T·Sa over 1–5 s: 3.75 at 1.5 s


@pytest.fixture(scope="module")
def roof():
    pulses = eight_pulses()
    four = replace(pulses, entries=pulses.entries[::2], description="four one-cosine pulses")
    return {choice: audit.check(BLOCK, SITE, procedures=["fema356", "priestley1978"], records=four,
                                guideline_spectrum=choice, solver=audit.Solver(free_motion_s=2.0),
                                **ROOF).document
            for choice in ("ground", "floor")}


def _entry(document, key):
    return next(p for p in document["objects"][0]["procedures"] if p["key"] == key)


def test_fema356_on_a_roof_says_which_spectrum_it_read(roof):
    ground, floor = (_entry(roof[c], "fema356") for c in ("ground", "floor"))
    assert ground["spectrum_read"] == "the ground's design spectrum (S_XS = 1 g, S_X1 = 0.6 g)"
    assert floor["spectrum_read"].startswith("the floor's response spectrum")
    assert "the floor's here" in floor["basis"] and "site's" in ground["basis"]
    assert _entry(roof["ground"], "priestley1978")["spectrum_read"] == (
        "true displacement spectrum of the record at damping β (Eq. 3.2) "
        "(each record's floor motion)")
    spectra = roof["floor"]["guideline_spectrum"]
    assert spectra["read"] == "floor" and roof["ground"]["guideline_spectrum"]["read"] == "ground"
    # the floor's spectrum is the same whichever is read, and far above the ground's on a roof
    assert spectra["floor"] == pytest.approx(roof["ground"]["guideline_spectrum"]["floor"],
                                             rel=1e-12)
    assert spectra["floor_over_ground"]["sx1_g"] > 2.0
    # each run's verdict on the other spectrum is the other run's verdict
    assert ground["other_spectrum"]["verdict"] == floor["verdict"]
    assert floor["other_spectrum"]["verdict"] == ground["verdict"]
    assert (ground["verdict"], floor["verdict"]) == ("passes", "fails")
    # the printed summary says it, with the other verdict
    printed = summary_text(roof["ground"])
    assert ("FEMA 356 (2000) overturning read the ground's design spectrum (S_XS = 1 g, S_X1 = "
            "0.6 g); on the floor's response spectrum") in printed
    assert "it would fail (θ ≥ α)" in printed


def test_fema356_line_on_the_floors_spectrum_is_its_uplift_step_there(roof):
    # uplift where 0.4·S_XS·λ = tan α, λ = level / S_X1(ground), S_XS the spectrum read
    tan_alpha = 0.7 / 1.7
    for choice, document in roof.items():
        sxs = document["guideline_spectrum"][choice]["sxs_g"]
        step = SITE[1] * tan_alpha / (0.4 * sxs)
        levels = np.array(document["levels"])
        if levels[0] < step < levels[-1]:
            assert _entry(document, "fema356")["guideline_im"] == pytest.approx(step, rel=1e-6)
        else:
            assert _entry(document, "fema356")["guideline_im"] is None
    # the exact answer does not depend on the guidelines' spectrum
    assert roof["ground"]["objects"][0]["exact"] == roof["floor"]["objects"][0]["exact"]


def test_floor_on_the_ground_and_a_bad_choice_are_refused_by_name():
    for options in ({"guideline_spectrum": "floor"}, {"guideline_spectrum": "roof", **ROOF}):
        with pytest.raises(InputError, match="guideline_spectrum"):
            audit.check(BLOCK, SITE, records=eight_pulses(), **options)


def test_the_command_line_refuses_floor_on_the_ground_in_one_line(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["check", "--block", BLOCK, "--site", "1.0,0.6", "--guideline-spectrum", "floor",
                 "--out", str(out)]) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and "--guideline-spectrum floor" in error[0] and "--floor" in error[0]
    assert not out.exists()
