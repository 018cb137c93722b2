"""The pelicun export of exact fragilities, loaded by pelicun itself (the ``pelicun`` extra)."""

from __future__ import annotations

import importlib.util
import math
from io import BytesIO

import numpy as np
import pandas as pd
import pytest
from scipy.stats import lognorm

from conftest import REQUIRE_PELICUN, unavailable

from audit.api.probabilistic import FragilityResult
from audit.engine.fragility.pipeline import COMPONENTS_CSV
from audit.engine.fragility.pelicun_export import PELICUN_COLUMNS, pelicun_fragility_csv
from procedures.fema_p58 import FEMAP58
from procedures.probabilistic import FragilityComponent, LognormalFragility

BOOKCASE = FragilityComponent("E.20.22.106a", "Bookcase, 6 shelves", "PGV",
                              LognormalFragility(0.3172843, 0.4137))
RACK = FragilityComponent("RA.rack", "Server rack 0.6 x 2.0 m", "PGA",
                          LognormalFragility(6.4871, 0.5523))

NO_FIT = FragilityComponent("RA.squat", "never overturned", "PGV",
                            LognormalFragility(math.nan, math.nan))


def _needs_pelicun():
    if importlib.util.find_spec("pelicun") is None:
        unavailable(REQUIRE_PELICUN, "pelicun is not installed (the pelicun extra)")


def test_layout_is_the_p58_librarys():
    table = pd.read_csv(BytesIO(pelicun_fragility_csv([BOOKCASE, RACK, NO_FIT])),
                        float_precision="round_trip")
    assert tuple(table.columns) == PELICUN_COLUMNS
    assert list(table["Demand-Type"]) == ["Peak Floor Velocity", "Peak Floor Acceleration",
                                          "Peak Floor Velocity"]
    assert list(table["Demand-Unit"]) == ["mps", "mps2", "mps"]
    assert list(table["Incomplete"]) == [0, 0, 1]
    # one horizontal component of each record: the demand of one direction
    assert list(table["Demand-Directional"]) == [1, 1, 1]
    # full precision: the median written is the median
    assert table["LS1-Theta_0"][0] == 0.3172843 and table["LS1-Theta_1"][1] == 0.5523


def test_fragility_result_exports_the_exact_fit():
    table = pd.DataFrame([{"component": "E.20.22.106a", "description": "Bookcase",
                           "width_m": 0.32, "height_m": 2.06,
                           "exact_median_m_s": 0.3172843, "exact_beta": 0.4137}])
    result = FragilityResult(FEMAP58(), {COMPONENTS_CSV: table}, "test")
    (component,) = result.exact_components()
    assert (component.fragility.median, component.fragility.beta) == (0.3172843, 0.4137)
    assert component.depth_m == pytest.approx(0.32) and component.intensity_measure == "PGV"
    assert result.pelicun_csv() == pelicun_fragility_csv([component])


def test_pelicun_loads_the_export_and_reproduces_p(tmp_path):
    _needs_pelicun()
    from pelicun import uq
    from pelicun.assessment import Assessment
    path = tmp_path / "fragility.csv"
    path.write_bytes(pelicun_fragility_csv([BOOKCASE, RACK, NO_FIT]))
    assessment = Assessment({"PrintLog": False, "Seed": 1, "Verbose": False})
    assessment.damage.load_model_parameters([str(path)], cmp_set={BOOKCASE.id, RACK.id, NO_FIT.id},
                                            warn_missing=False)
    params = assessment.damage.ds_model.damage_params
    assert NO_FIT.id not in params.index  # Incomplete rows are dropped by pelicun
    for component, demands in ((BOOKCASE, [0.1, 0.3172843, 0.9]), (RACK, [2.0, 6.5, 15.0])):
        theta = params.loc[component.id, ("LS1", "Theta_0")], \
            params.loc[component.id, ("LS1", "Theta_1")]
        assert params.loc[component.id, ("LS1", "Family")] == "lognormal"
        p_pelicun = uq.LogNormalRandomVariable("ls1", theta=np.array(theta)).cdf(
            np.array(demands))
        p_scipy = lognorm(s=component.fragility.beta, scale=component.fragility.median).cdf(demands)
        np.testing.assert_allclose(p_pelicun, p_scipy, rtol=0, atol=1e-6)
        assert not np.allclose(p_scipy, p_scipy[0])  # three distinct probabilities


def _assessment_at(path, component, demands, sample_size):
    """A pelicun assessment of one ``component`` (location 1, direction 1) loaded from the
    export at ``path``, under demands fixed at ``demands`` (direction → value, SI) on the
    floor pelicun reads for location 1 (its default DemandOffset −1 for PFA and PFV: floor 0)."""
    from pelicun.assessment import Assessment
    demand_type = "PFV" if component.intensity_measure == "PGV" else "PFA"
    unit = "mps" if demand_type == "PFV" else "mps2"
    assessment = Assessment({"PrintLog": False, "Seed": 7, "Verbose": False})
    marginals = pd.DataFrame({"Theta_0": list(demands.values()), "Units": unit},
                             index=pd.MultiIndex.from_tuples(
                                 [(demand_type, "0", direction) for direction in demands]))
    assessment.demand.load_model({"marginals": marginals})  # no Family: deterministic
    assessment.demand.generate_sample({"SampleSize": sample_size})
    assessment.stories = 1
    assessment.asset.load_cmp_model({"marginals": pd.DataFrame(
        {"Units": ["ea"], "Location": ["1"], "Direction": ["1"], "Theta_0": [1.0],
         "Blocks": [1]}, index=[component.id])})
    assessment.asset.generate_cmp_sample(sample_size)
    assessment.damage.load_model_parameters([str(path)], cmp_set={component.id},
                                            warn_missing=False)
    return assessment


def test_pelicun_reads_the_demand_of_the_components_direction_with_no_factor(tmp_path):
    """pelicun's own demand assembly (what its damage calculation compares with the
    capacities) gives the exported component the demand of its direction unchanged, not
    max(dir 1, dir 2) × 1.2; P at that demand from pelicun's loaded parameters is the exact
    fragility's to 1e-6, and pelicun's damage calculation reproduces it to its sampling."""
    _needs_pelicun()
    from pelicun import uq
    from pelicun.model.demand_model import (_assemble_required_demand_data,
                                            _get_required_demand_type)
    path = tmp_path / "fragility.csv"
    path.write_bytes(pelicun_fragility_csv([BOOKCASE, RACK]))
    sample_size = 20000
    for component, demands in ((BOOKCASE, {"1": 0.30, "2": 0.55}),
                               (RACK, {"1": 5.0, "2": 9.0})):
        assessment = _assessment_at(path, component, demands, sample_size)
        damage = assessment.damage.ds_model
        params = damage.damage_params
        assert params.loc[component.id, ("Demand", "Directional")] == 1
        assert assessment.options.nondir_multi_dict == {"ALL": 1.2}  # pelicun's default
        blocks = pd.DataFrame({"Blocks": [1]}, index=pd.MultiIndex.from_tuples(
            [(component.id, "1", "1", "0")], names=["cmp", "loc", "dir", "uid"]))
        required = _get_required_demand_type(params, blocks, assessment.options.demand_offset,
                                             assessment.options.edp_to_demand_type)
        assembled = _assemble_required_demand_data(set(required), {"ALL": 1.2},
                                                   assessment.demand.sample)
        (demand,) = assembled.values()
        np.testing.assert_array_equal(demand, np.full(sample_size, demands["1"]))
        theta = np.array([params.loc[component.id, ("LS1", "Theta_0")],
                          params.loc[component.id, ("LS1", "Theta_1")]])
        p_pelicun = uq.LogNormalRandomVariable("ls1", theta=theta).cdf(np.array([demand[0]]))[0]
        p_exact = lognorm(s=component.fragility.beta,
                          scale=component.fragility.median).cdf(demands["1"])
        assert abs(p_pelicun - p_exact) < 1e-6
        # the whole damage calculation: capacities sampled by Latin hypercube, so the share
        # in DS1 is P to within a few strata (and far from P at 1.2 × the larger direction)
        assessment.damage.calculate()
        in_ds1 = float((damage.ds_sample.to_numpy().ravel() == 1).mean())
        assert abs(in_ds1 - p_exact) < 5.0 / sample_size
        p_nondirectional = lognorm(s=component.fragility.beta, scale=component.fragility.median
                                   ).cdf(1.2 * max(demands.values()))
        assert p_nondirectional - p_exact > 0.2


def test_export_takes_precedence_over_the_p58_library(tmp_path):
    _needs_pelicun()
    from pelicun.assessment import Assessment
    path = tmp_path / "fragility.csv"
    path.write_bytes(pelicun_fragility_csv([BOOKCASE]))
    assessment = Assessment({"PrintLog": False, "Seed": 1, "Verbose": False})
    assessment.damage.load_model_parameters(
        [str(path), "PelicunDefault/FEMA P-58/fragility.csv"],
        cmp_set={BOOKCASE.id, "E.20.22.114a"}, warn_missing=False)
    params = assessment.damage.ds_model.damage_params
    # ours replaces P-58's 0.251 m/s; the filing cabinet keeps P-58's 0.498 m/s
    assert params.loc[BOOKCASE.id, ("LS1", "Theta_0")] == 0.3172843
    assert params.loc["E.20.22.114a", ("LS1", "Theta_0")] == pytest.approx(0.498)


def test_fragility_audit_exports_its_exact_fits():
    import audit
    from records import RecordEntry, RecordSuite, one_pulse
    pulses = RecordSuite(tuple(RecordEntry(f"cosine_{t:g}s", one_pulse("cosine", 0.5, t,
                                                                       record_id=f"c{t:g}"))
                               for t in (0.3, 0.6, 1.0, 2.0)), "four one-cosine pulses")
    result = audit.fragility("femap58", pulses)
    exported = pd.read_csv(BytesIO(result.pelicun_csv()),
                           float_precision="round_trip").set_index("ID")
    components = result.tables[COMPONENTS_CSV].set_index("component")
    assert list(exported.index) == list(components.index)  # the audited PGV components
    for component_id, row in components.iterrows():
        fitted = math.isfinite(row["exact_median_m_s"])
        assert exported.loc[component_id, "Incomplete"] == (0 if fitted else 1)
        if fitted:
            assert exported.loc[component_id, "LS1-Theta_0"] == row["exact_median_m_s"]
            assert exported.loc[component_id, "LS1-Theta_1"] == row["exact_beta"]
