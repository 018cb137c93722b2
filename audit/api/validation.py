"""Shake-table validation of the exact solver: :func:`validate` and its
:class:`ValidationResult` (see :mod:`audit.engine.validation.pipeline`)."""

from __future__ import annotations

from audit.api.result_shape import Files, table_html, with_page
from audit.engine.shared.defaults import DEFAULT_FREE_MOTION_S, DEFAULT_JOBS


class ValidationResult(Files):
    """A campaign's validation: ``.fits`` (specimen → fitted block), ``.fits_table``,
    ``.scores`` (also ``.table``), ``.tests``, ``.predictions`` (DataFrames, the CSV files of
    the same names), ``.solves``, ``.methods_statement`` (also ``.summary_text()``),
    ``.summary``, ``.write(folder)`` (the files and ``validation.html``) and
    ``.report(path)``."""

    PAGE = "validation.html"

    def __init__(self, validation):
        self.validation = validation
        self.fits, self.scores = validation.fits, validation.scores
        self.tests, self.predictions = validation.tests, validation.predictions
        self.fits_table, self.solves = validation.fits_table(), validation.solves

    @property
    def table(self):
        """The cross-validated scores of the model and the baselines per specimen."""
        return self.scores

    @property
    def summary(self) -> dict:
        """The campaign's size and the exact solves it took."""
        return {"specimens": len(self.fits_table), "tests": len(self.tests),
                "solves": self.solves}

    @property
    def methods_statement(self) -> str:
        """What a report's Methods says of this validation and its limits."""
        from audit.engine.validation.pipeline import methods_statement
        return methods_statement(self.fits_table, self.scores)

    def summary_text(self) -> str:
        """:attr:`methods_statement`, one paragraph."""
        return f"{self.methods_statement}\n"

    def files(self) -> dict[str, bytes]:
        """Every file, ``validation.html`` drawn from the CSV files as saved."""
        from reports.validation_page import VALIDATION_HTML, render_validation_page
        title = "Shake-table validation of the exact rocking model"
        return with_page(self.validation.files(), VALIDATION_HTML,
                         lambda saved: render_validation_page(saved, title, self.solves))

    def _repr_html_(self) -> str:
        return table_html(self.scores, self.methods_statement)

    def __repr__(self) -> str:
        return (f"ValidationResult({len(self.fits_table)} specimens, {len(self.tests)} tests, "
                f"{self.solves:,} exact solves)")


def validate(folder, geometry=None, *, folds: int = 5, jobs: int = DEFAULT_JOBS,
             free_motion_s: float = DEFAULT_FREE_MOTION_S, band_pass: bool = False,
             progress=False, settings=None) -> ValidationResult:
    """Fit each specimen's equivalent rigid block to a shake-table campaign and score it by
    cross-validation by ground motion against intensity baselines (docs/validation.md).

    Every argument is checked before anything is read; a bad one raises
    :class:`~audit.errors.InputError` naming it.

    Parameters
    ----------
    folder : str or Path
        The campaign folder (``tests.csv`` and the motion files it names).
    geometry : str or Path, optional
        CSV of geometric estimates (``specimen, alpha_deg, p_rad_s, note``); default the
        folder's ``specimens.csv`` if there is one.
    folds : int
        Cross-validation folds, ≥ 2 (tests of one ground motion always share a fold).
    jobs : int
        Solver threads, ≥ 1.
    free_motion_s : float
        Free rocking simulated after each test motion [s], ≥ 0.
    band_pass : bool
        Solve the blocks under the band-passed motions (0.1–25 Hz) rather than as recorded.
    progress : bool or callable
        A progress bar on standard error, or ``progress(done, total, test_id)``.
    settings : audit.engine.validation.settings.ValidationSettings, optional
        Every setting (grid, band-pass, lapse); overrides ``folds``, ``jobs``,
        ``free_motion_s`` and ``band_pass``.

    Returns
    -------
    ValidationResult
    """
    from audit.engine.shared import fields as check
    from audit.engine.shared.progress import Progress
    from audit.engine.validation.settings import ValidationSettings
    from audit.engine.validation.pipeline import run_validation
    from audit.errors import InputError
    from records.campaign import campaign_geometry, read_campaign
    folder = check.path("folder", folder, "the campaign folder")
    if geometry is not None:
        geometry = check.path("geometry", geometry, "a CSV file of geometric estimates")
    progress = check.callback("progress", progress, "progress(done, total, test_id)")
    if settings is None:
        settings = ValidationSettings(folds=folds, jobs=jobs, free_motion_s=free_motion_s,
                                      band_pass=band_pass)
    elif not isinstance(settings, ValidationSettings):
        raise InputError(f"settings: expected a ValidationSettings, got {settings!r}",
                         "settings")
    campaign = read_campaign(folder)
    given = campaign_geometry(campaign, geometry)
    bar = Progress(len(campaign.motions), "test") if progress is True else None
    try:
        result = run_validation(campaign, settings, given, bar or progress or None)
    finally:
        if bar is not None:
            bar.done()
    return ValidationResult(result)


__all__ = ["validate", "ValidationResult"]
