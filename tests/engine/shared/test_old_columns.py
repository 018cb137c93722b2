"""Files written by the version before one name per quantity (issue 44, item 6) are still
read: ``block_m`` ("0.6x1.8", empty for a grid block) and ``half_width_m``/``half_height_m``
become ``width_m``/``height_m`` in one place, :func:`upgrade_columns`."""

import io
import math

import pandas as pd

from audit.engine.design.risk_schema import RISK_GUIDE
from audit.engine.shared.schemas import GUIDE, block_labels, upgrade_columns
from reports.margins_page import _keys, _read

#: fragility.csv as the previous version wrote it (a few rows, a few of its columns): two grid
#: blocks, then the named blocks 0.6x1.8 and 0.8x4.
OLD_FRAGILITY = """alpha_deg,size_s,block_m,im,records,median,cmr_bound
15.0,2.0,,pga,20,0.41,
15.0,2.5,,pga,20,0.52,at least
18.43494882,2.1172,0.6x1.8,pga,20,0.47,
11.30993247,2.6818,0.8x4,pga,20,0.63,
"""
#: The same table in this version's columns.
NEW_FRAGILITY = """alpha_deg,size_s,width_m,height_m,im,records,median,cmr_bound
15.0,2.0,,,pga,20,0.41,
15.0,2.5,,,pga,20,0.52,at least
18.43494882,2.1172,0.6,1.8,pga,20,0.47,
11.30993247,2.6818,0.8,4.0,pga,20,0.63,
"""
#: fragility-components.csv of the previous version: b = depth/2, h = height/2.
OLD_COMPONENTS = """component,description,half_width_m,half_height_m,alpha_deg
E.20.22.106a,Bookcase,0.16,1.03,8.83
"""


def test_block_m_becomes_width_and_height_in_its_place():
    frame = upgrade_columns(pd.read_csv(io.StringIO(OLD_FRAGILITY)))
    assert list(frame.columns) == ["alpha_deg", "size_s", "width_m", "height_m", "im", "records",
                                   "median", "cmr_bound"]
    assert frame["width_m"].tolist()[2:] == [0.6, 0.8]
    assert frame["height_m"].tolist()[2:] == [1.8, 4.0]
    assert frame[["width_m", "height_m"]].iloc[:2].isna().all().all()  # grid blocks
    assert block_labels(frame).tolist() == ["", "", "0.6x1.8", "0.8x4"]


def test_old_and_new_files_read_alike(tmp_path):
    """The page's reader gives the same table, and the same block keys, for either layout."""
    (tmp_path / "old.csv").write_text(OLD_FRAGILITY)
    (tmp_path / "new.csv").write_text(NEW_FRAGILITY)
    old, new = _read(tmp_path / "old.csv"), _read(tmp_path / "new.csv")
    pd.testing.assert_frame_equal(old, new)
    assert _keys(old).tolist() == ["15|2", "15|2.5", "0.6x1.8", "0.8x4"]


def test_half_dimensions_are_doubled():
    frame = upgrade_columns(pd.read_csv(io.StringIO(OLD_COMPONENTS)))
    assert list(frame.columns) == ["component", "description", "width_m", "height_m",
                                   "alpha_deg"]
    assert (frame.loc[0, "width_m"], frame.loc[0, "height_m"]) == (0.32, 2.06)
    # the block the slenderness was written for: α = atan(b/h) = atan(width/height)
    assert abs(math.degrees(math.atan(0.32 / 2.06)) - frame.loc[0, "alpha_deg"]) < 0.005


def test_a_table_of_this_version_is_left_as_it_is():
    frame = pd.read_csv(io.StringIO(NEW_FRAGILITY))
    pd.testing.assert_frame_equal(upgrade_columns(frame.copy()), frame)


def test_no_table_names_the_old_columns():
    old = {"block_m", "half_width_m", "half_height_m"}
    assert not [(name, c) for name, columns in {**GUIDE, **RISK_GUIDE}.items() for c in columns if c in old]
