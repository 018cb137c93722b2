"""The Circolare 2019 §C7.2.3 floor spectrum against values computed by hand, and NTC 2018's
procedure reading it on a floor."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from audit import G
from audit.physics.building.floor import Building, Floor
from audit.physics.ntc2018_floor_spectrum import NTC2018FloorSpectrum, floor_spectrum_parameters
from audit.physics.ntc2018_spectrum import NTC2018Spectrum
from procedures.ntc_2018 import NTC2018

# a_g = 0.25 g, F0 = 2.5, T_C* = 0.3 s, soil A, topography T1: S = S_S·S_T = 1·1, α·S = 0.25
GROUND = NTC2018Spectrum(0.25, 2.5, 0.3, "A", "T1")
ROOF_1S = NTC2018FloorSpectrum(GROUND, 1.0, 1.0)


def test_table_c7_2_i():
    assert floor_spectrum_parameters(0.4) == (0.8, 1.4, 5.0)
    assert floor_spectrum_parameters(0.5) == (0.8, 1.4, 5.0)
    assert floor_spectrum_parameters(1.0) == (0.3, 1.2, 4.0)
    assert floor_spectrum_parameters(1.5) == (0.3, 1.0, 2.5)


def test_roof_of_a_1s_building_by_hand():
    # T_1 = 1 s: a = 0.3, b = 1.2, a_p = 4; α·S·(1 + z/H) = 0.25·2 = 0.5 g
    periods = [0.0, 0.15, 0.6, 2.4, 6.0]
    expected = [
        0.5 * 4 / (1 + 3 * 1.0),   # T_a = 0: 0.5·4/(1 + 3·(1 − 0)²) = 0.5
        1.142857,                  # T_a = 0.15 < 0.3: 0.5·4/(1 + 3·0.5²) = 2/1.75
        2.0,                       # 0.3 ≤ T_a = 0.6 < 1.2: the plateau 0.5·4
        0.5,                       # T_a = 2.4 ≥ 1.2: 0.5·4/(1 + 3·(1 − 2)²) = 2/4
        0.25,                      # T_a = 6: 0.5·4/(1 + 3·16) = 0.0408 < α·S: α·S = 0.25
    ]
    np.testing.assert_allclose(ROOF_1S.acceleration(periods, 0.05), expected, atol=1e-6)
    assert ROOF_1S.peak_floor_acceleration_g == pytest.approx(0.5)
    # Sd = Sa·g·T²/(4π²) at T = 0.6 s: 2.0·9.81·0.36/39.478418 = 0.178913 m
    assert ROOF_1S.displacement(0.6, 0.05) == pytest.approx(0.178913, abs=1e-6)


def test_mid_height_of_a_stiff_building_by_hand():
    # T_1 = 0.4 s: a = 0.8, b = 1.4, a_p = 5; z/H = 0.5: α·S·1.5 = 0.375 g; T_a = 0.16 s <
    # a·T_1 = 0.32 s: 0.375·5/(1 + 4·(1 − 0.5)²) = 1.875/2 = 0.9375 g
    assert NTC2018FloorSpectrum(GROUND, 0.5, 0.4).acceleration(0.16, 0.05) \
        == pytest.approx(0.9375)


def test_damping():
    # ξ = 10 %: η = √(10/15) = 0.816497; the plateau 2.0·0.816497 = 1.632993 g; a rigid element
    # (T_a = 0) still feels the floor's 0.5 g
    assert ROOF_1S.acceleration(0.6, 0.10) == pytest.approx(1.632993, abs=1e-6)
    assert ROOF_1S.acceleration(0.0, 0.10) == pytest.approx(0.5)


def test_ntc2018_reads_the_floor_spectrum_on_a_floor():
    entry = SimpleNamespace(site=dict(zip(("ntc_ag_g", "ntc_f0", "ntc_tc_star_s", "ntc_soil",
                                           "ntc_topography"), (0.25, 2.5, 0.3, "A", "T1"))))
    roof = NTC2018(floor=Floor.parse(Floor(1.0, Building(1.0))))
    # the floor's peak α·S·(1 + z/H) = 0.5 g in place of a_g·S = 0.25 g
    assert roof.peak_ground_acceleration(entry, None) == pytest.approx(0.5 * G)
    assert NTC2018().peak_ground_acceleration(entry, None) == pytest.approx(0.25 * G)
    # the demand spectrum at ξ_SLV = 8 % is the floor's: plateau 2.0·√(10/13) = 1.754116 g at 0.6 s
    sd = roof.displacement_spectrum(entry, 0.08, None)(0.6)
    assert sd == pytest.approx(1.754116 * G * 0.36 / (4 * np.pi ** 2), rel=1e-6)
