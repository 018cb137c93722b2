"""Cost of ``validate`` on a shake-table campaign: wall and CPU time, exact simulations, and
the share spent solving the grid (the fits and cross-validation read the grid only).

    python benchmarks/validation.py CAMPAIGN_FOLDER [JOBS]
"""

import sys
import time

from audit.api import validate
from audit.engine.validation.grid import band_passed, overturning_grid
from audit.engine.validation.settings import ValidationSettings
from records.campaign import read_campaign


def main(folder, jobs=2):
    settings = ValidationSettings(jobs=jobs)
    campaign = read_campaign(folder)
    overturning_grid([band_passed(campaign.motions[0], settings)], settings)  # compile first
    wall, cpu = time.perf_counter(), time.process_time()
    result = validate(folder, jobs=jobs)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    grid_wall = time.perf_counter()
    overturning_grid([band_passed(m, settings) for m in campaign.motions[:20]], settings)
    grid_wall = (time.perf_counter() - grid_wall) * len(campaign.motions) / 20
    print(f"{len(campaign.motions)} tests, {result.solves:,} exact simulations, jobs={jobs}: "
          f"{wall:.0f} s wall, {cpu:.0f} s CPU; grid ≈ {grid_wall:.0f} s wall "
          f"({result.solves / wall:,.0f} simulations/s overall)")


if __name__ == "__main__":
    main(sys.argv[1], *(int(a) for a in sys.argv[2:3]))
