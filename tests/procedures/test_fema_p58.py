"""FEMA P-58 unanchored-content fragilities and the probabilistic audit's metrics, by hand."""

import math

import numpy as np
import pytest

from audit.api import Block
from audit.engine.fragility.calibration import brier_score, calibration, log_likelihood
from procedures.fema_p58 import FEMAP58
from procedures.registry import available_procedures


def test_bookcase_4_shelves_at_half_a_metre_per_second():
    # Φ(ln(0.5/0.361)/0.5) = 0.743 for E.20.22.104a (θ = 0.361 m/s, β = 0.5 in P-58 v3.1.2)
    assert FEMAP58().probability("E.20.22.104a", 0.5) == pytest.approx(0.743, abs=5e-4)
    assert FEMAP58().probability("E.20.22.104a", 0.361) == pytest.approx(0.5)
    assert FEMAP58().probability("E.20.22.104a", 0.0) == 0.0


def test_pga_rows_are_in_si():
    # the control panel's median 0.69 g: half the panels at PGA = 0.69 × 9.81 m/s²
    assert FEMAP58().probability("D.30.67.011a", 0.69 * 9.81) == pytest.approx(0.5)
    assert not FEMAP58().component("D.30.67.011a").has_block


@pytest.mark.parametrize("component_id, alpha_rad, p_rad_s", [
    # 12-5/8 in deep × 56 in tall: b = 0.16034 m, h = 0.7112 m, α = atan(b/h), R = √(b² + h²)
    # = 0.72905 m, p = √(3 × 9.81 / (4 × 0.72905)) = 3.1768 rad/s
    ("E.20.22.104a", 0.22174, 3.1768),
    # 15 in × 24 in: b = 0.1905 m, h = 0.3048 m, α = atan(0.625), R = 0.35944 m
    ("E.20.22.112a", 0.55860, 4.5243),
])
def test_component_blocks(component_id, alpha_rad, p_rad_s):
    component = FEMAP58().component(component_id)
    block = Block.from_dimensions(component.depth_m, component.height_m)
    assert math.radians(block.alpha_deg) == pytest.approx(alpha_rad, abs=1e-5)
    assert block.p_rad_s == pytest.approx(p_rad_s, abs=1e-4)


def test_registered_apart_from_the_rotation_procedures():
    assert available_procedures(probabilistic=True)["femap58"] is FEMAP58


def test_scores_by_hand():
    predicted, observed = [0.1, 0.4, 0.8, 0.9], [False, True, True, False]
    # (0.1² + 0.6² + 0.2² + 0.9²) / 4 = 1.22 / 4
    assert brier_score(predicted, observed) == pytest.approx(0.305)
    # ln 0.9 + ln 0.4 + ln 0.8 + ln 0.1
    assert log_likelihood(predicted, observed) == pytest.approx(-3.547379, abs=1e-6)
    assert log_likelihood([0.0], [True]) == -np.inf
    table = calibration(predicted + [1.0], observed + [True], edges=[0.0, 0.5, 1.0])
    np.testing.assert_array_equal(table.count, [2, 3])
    np.testing.assert_allclose(table.mean_predicted, [0.25, 2.7 / 3])
    np.testing.assert_allclose(table.observed_frequency, [0.5, 2 / 3])


def test_fragility_command_files_agree(tmp_path, capsys):
    import pandas as pd

    from audit.cli import main
    assert main(["fragility", "--records", "pulses", "--out", str(tmp_path)]) == 0
    components = pd.read_csv(tmp_path / "fragility-components.csv")
    stripes = pd.read_csv(tmp_path / "fragility-stripes.csv")
    outcomes = pd.read_csv(tmp_path / "fragility-outcomes.csv")
    # the nine P-58 components with dimensions; the PGA rows have none
    assert len(components) == 9
    # each stripe's count is the number of its records that overturn, file to file
    counted = outcomes.groupby(["component", "pgv_m_s"])["exact_overturned"].sum()
    np.testing.assert_array_equal(stripes.set_index(["component", "pgv_m_s"])["overturned"],
                                  counted.loc[stripes.set_index(["component", "pgv_m_s"]).index])
    page = (tmp_path / "fragility.html").read_text()
    assert "ground-floor clause" in page and "E.20.22.104a" in page


def test_fragility_command_unknown_procedure(tmp_path, capsys):
    from audit.cli import main
    out = tmp_path / "out"
    assert main(["fragility", "--procedure", "nope", "--out", str(out)]) == 2
    assert capsys.readouterr().err.count("\n") == 1
    assert not out.exists()


def test_fragility_files_match_the_column_guide():
    from audit.engine.fragility.calibration import PGV_LEVELS_M_S
    from audit.engine.fragility.pipeline import run_fragility
    from audit.engine.fragility.settings import FragilitySettings
    from audit.engine.shared.schemas import GUIDE
    from procedures.fema_p58 import FEMAP58
    from records import pulse_suite
    entries = list(pulse_suite())[:2]
    tables = run_fragility(FEMAP58(), [e.id for e in entries], [e.motion for e in entries],
                           FragilitySettings(levels_m_s=PGV_LEVELS_M_S[::4]))
    for name, table in tables.items():
        assert list(table.columns) == list(GUIDE[name]), name
