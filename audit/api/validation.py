"""Shake-table validation of the exact solver: :func:`validate` and its
:class:`ValidationResult` (see :mod:`audit.engine.validation_run`)."""

from __future__ import annotations

from pathlib import Path

from audit.api.design_level import with_page
from audit.engine.defaults import DEFAULT_FREE_MOTION_S, DEFAULT_JOBS


class ValidationResult:
    """A campaign's validation: ``.fits`` (specimen → fitted block), ``.fits_table``,
    ``.scores``, ``.tests``, ``.predictions`` (DataFrames, the CSV files of the same names),
    ``.solves``, ``.methods_statement``, ``.write(folder)`` (the files and
    ``validation.html``)."""

    def __init__(self, validation):
        self.validation = validation
        self.fits, self.scores = validation.fits, validation.scores
        self.tests, self.predictions = validation.tests, validation.predictions
        self.fits_table, self.solves = validation.fits_table(), validation.solves

    @property
    def methods_statement(self) -> str:
        """What a report's Methods says of this validation and its limits."""
        from audit.engine.validation_run import methods_statement
        return methods_statement(self.fits_table, self.scores)

    def files(self) -> dict[str, bytes]:
        """Every file, ``validation.html`` drawn from the CSV files as saved."""
        from reports.validation_page import VALIDATION_HTML, render_validation_page
        title = "Shake-table validation of the exact rocking model"
        return with_page(self.validation.files(), VALIDATION_HTML,
                         lambda saved: render_validation_page(saved, title, self.solves))

    def write(self, out_dir) -> Path:
        """Write the files and ``validation.html`` into ``out_dir`` (atomically, together)."""
        from audit.files import write_files_atomically
        write_files_atomically(Path(out_dir), self.files())
        return Path(out_dir)


def validate(folder, geometry=None, folds: int = 5, jobs: int = DEFAULT_JOBS,
             free_motion_s: float = DEFAULT_FREE_MOTION_S, progress=False,
             settings=None) -> ValidationResult:
    """Fit each specimen's equivalent rigid block to a shake-table campaign and score it by
    cross-validation by ground motion against intensity baselines (docs/validation.md).

    Parameters
    ----------
    folder : str or Path
        The campaign folder (``tests.csv`` and the motion files it names).
    geometry : str or Path, optional
        CSV of geometric estimates (``specimen, alpha_deg, p_rad_s, note``); default the
        folder's ``specimens.csv`` if there is one.
    folds, jobs, free_motion_s :
        Cross-validation folds; solver threads; free motion after each test [s].
    progress : bool or callable
        A progress bar on standard error, or ``progress(done, total, test_id)``.
    settings : audit.engine.validation_grid.ValidationSettings, optional
        Every setting (grid, band-pass, lapse); overrides ``folds``, ``jobs``, ``free_motion_s``.
    """
    from audit.engine.progress import Progress
    from audit.engine.validation_grid import ValidationSettings
    from audit.engine.validation_run import run_validation
    from records.campaign import campaign_geometry, read_campaign
    campaign = read_campaign(folder)
    given = campaign_geometry(campaign, geometry)
    settings = settings or ValidationSettings(folds=folds, jobs=jobs, free_motion_s=free_motion_s)
    bar = Progress(len(campaign.motions), "test") if progress is True else None
    try:
        result = run_validation(campaign, settings, given, bar or progress or None)
    finally:
        if bar is not None:
            bar.done()
    return ValidationResult(result)


__all__ = ["validate", "ValidationResult"]
