"""A campaign's validation: the exact grid once, then per specimen the fit, the cross-validation
by ground motion, the scores of model, baselines and peer columns, and the predictions of the
tests without an outcome. Its files are the tables the page is drawn from."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from audit.errors import InputError
from audit.engine.validation.baselines import scores
from audit.engine.validation.cross_validation import MODEL, folds_by_record, out_of_fold
from audit.engine.validation.fit import fit_block
from audit.engine.validation.grid import Intensities, band_passed, intensities, overturning_grid
from audit.engine.validation.refine import REFINEMENTS, refined_blocks
from audit.engine.validation.settings import ValidationSettings

PREDICTIONS_CSV = "predictions.csv"
FITS_CSV = "validation-fits.csv"
SCORES_CSV = "validation-scores.csv"
TESTS_CSV = "validation-tests.csv"
RIDGE_CSV = "validation-ridge.csv"


def _step_pct(nodes) -> float:
    """The largest step between log-spaced nodes [%]."""
    return float(np.expm1(np.diff(np.log(np.asarray(nodes, dtype=float))).max()) * 100) \
        if len(nodes) > 1 else math.nan


@dataclass(frozen=True)
class CampaignValidation:
    """What ``validate`` found.

    Attributes
    ----------
    fits : dict
        Specimen → :class:`~audit.engine.validation.fit.BlockFit` on every test with an outcome.
    fold_fits : dict
        Specimen → the BlockFit of each cross-validation fold.
    geometry : pandas.DataFrame
        The geometric estimates given (``specimen, alpha_deg, p_rad_s, note``); may be empty.
    scores : pandas.DataFrame
        One row per specimen and method: ``n, accuracy, brier, log_loss``, the confusion matrix,
        and the paired difference of Brier score from the model's with its standard error.
    tests : pandas.DataFrame
        One row per test and specimen: intensities, fold, observed outcome, the model's
        probability (full fit) and every method's out-of-fold probability.
    predictions : pandas.DataFrame
        ``test, specimen, p_overturn, predicted_overturned`` for tests without an outcome.
    solves : int
        Exact simulations run.
    settings : ValidationSettings
    """

    fits: dict
    fold_fits: dict
    geometry: pd.DataFrame
    scores: pd.DataFrame
    tests: pd.DataFrame
    predictions: pd.DataFrame
    solves: int
    settings: ValidationSettings

    def fits_table(self) -> pd.DataFrame:
        """One row per specimen: fitted parameters with their 95 % profile-likelihood
        intervals, whether α̂ and p are identified (their interval inside the searched range),
        the fine grid's steps, the range over the cross-validation folds' fits, and the
        geometric estimates (NaN where none was given)."""
        rows = []
        for name, fit in self.fits.items():
            given = self.geometry[self.geometry["specimen"] == name]
            grid = fit.blocks
            rows.append({
                "specimen": name, "n_tests": fit.n_tests,
                "alpha_deg": fit.alpha_deg, "alpha_deg_low": fit.alpha.low,
                "alpha_deg_high": fit.alpha.high, "alpha_identified": fit.alpha.identified,
                "sigma_ln_alpha": fit.sigma, "sigma_low": fit.sigma_95.low,
                "sigma_high": fit.sigma_95.high,
                "p_rad_s": fit.p_rad_s, "p_rad_s_low": fit.p.low, "p_rad_s_high": fit.p.high,
                "p_identified": fit.p.identified,
                "restitution_factor": fit.restitution_factor,
                "restitution_factor_low": fit.restitution.low,
                "restitution_factor_high": fit.restitution.high,
                "log_likelihood": fit.log_likelihood,
                "alpha_step_pct": float(np.expm1(np.diff(fit.surface.log_medians).max()) * 100),
                "p_step_pct": _step_pct(grid.p_rad_s),
                "restitution_step": float(np.diff(grid.restitution_factors).max())
                if len(grid.restitution_factors) > 1 else math.nan,
                **self._fold_spread(name),
                "geometry_alpha_deg": given["alpha_deg"].iloc[0] if len(given) else math.nan,
                "geometry_p_rad_s": given["p_rad_s"].iloc[0] if len(given) else math.nan,
                "geometry_note": given["note"].iloc[0] if len(given) else ""})
        return pd.DataFrame(rows)

    def ridge_table(self) -> pd.DataFrame:
        """Per specimen and p of its fine grid: the best α̂, the 95 % region's α̂ range at that
        p (empty outside it) and the profile log-likelihood: the ridge α(p) along which the
        outcomes trade p for α."""
        return pd.concat([pd.DataFrame({"specimen": name, **fit.ridge})
                          for name, fit in self.fits.items()], ignore_index=True)

    def _fold_spread(self, name) -> dict:
        """Smallest and largest α̂, p and f over the cross-validation folds' fits."""
        out = {}
        for column, attribute in (("alpha_deg", "alpha_deg"), ("p_rad_s", "p_rad_s"),
                                  ("restitution_factor", "restitution_factor")):
            values = [getattr(fit, attribute) for fit in self.fold_fits[name]]
            out[f"{column}_folds_min"], out[f"{column}_folds_max"] = min(values), max(values)
        return out

    def files(self) -> dict:
        """The output files (name → bytes)."""
        def csv(frame):
            return frame.to_csv(index=False, float_format="%.6g").encode()
        return {PREDICTIONS_CSV: csv(self.predictions), FITS_CSV: csv(self.fits_table()),
                SCORES_CSV: csv(self.scores), TESTS_CSV: csv(self.tests),
                RIDGE_CSV: csv(self.ridge_table())}


def _score_rows(name, outcomes, probabilities: dict, lapse) -> list:
    rows = []
    model_brier = (np.clip(probabilities[MODEL], lapse, 1.0 - lapse) - outcomes) ** 2
    for method, probability in probabilities.items():
        probability = np.clip(probability, lapse, 1.0 - lapse)
        s = scores(probability, outcomes)
        difference = (probability - outcomes) ** 2 - model_brier
        rows.append({"specimen": name, "method": method, **vars(s),
                     "brier_minus_model": float(difference.mean()),
                     "brier_minus_model_se": float(difference.std(ddof=1)
                                                   / math.sqrt(difference.size))})
    return rows


def _fine_grid(motions, settings, coarse, known, y, progress):
    """The grid the specimen is fitted on and the solves it took: the coarse one, or fine
    grids solved in turn along the region the previous grid's fit allows
    (:mod:`~audit.engine.validation.refine`). The folds' fits read the same grid: a region
    covering theirs too was measured to triple the grid for the same solves and miss the truth
    more often; a fold's optimum outside it lowers its scores, it does not flatter them."""
    grid, solves = coarse, 0
    for _ in range(REFINEMENTS if settings.refined_solves else 0):
        fine = refined_blocks(grid.blocks, [fit_block(grid.overturned[known], y, grid.blocks,
                                                      settings.lapse)], settings.refined_solves)
        if hasattr(progress, "stage"):
            progress.stage(f"fine grid: α {fine.alpha_deg.min():.3g}–"
                           f"{fine.alpha_deg.max():.3g}° ({fine.alpha_deg.shape[-1]} per (f, p)), "
                           f"p {fine.p_rad_s[0]:.3g}–"
                           f"{fine.p_rad_s[-1]:.3g} rad/s ({fine.p_rad_s.size}), f "
                           f"{fine.restitution_factors[0]:g}–{fine.restitution_factors[-1]:g} "
                           f"({fine.restitution_factors.size}): {fine.solves_per_test} blocks "
                           "under each motion")
        grid = overturning_grid(motions, settings, progress, fine)
        solves += grid.solves
    return grid, solves


def run_validation(campaign, settings: ValidationSettings, geometry: pd.DataFrame,
                   progress=None) -> CampaignValidation:
    """Validate the equivalent rigid block of every specimen of ``campaign``.

    Parameters
    ----------
    campaign : records.campaign.Campaign
    settings : ValidationSettings
    geometry : pandas.DataFrame
        Geometric estimates (``specimen, alpha_deg, p_rad_s, note``), shown beside the fit.
    progress : callable, optional
        ``progress(done, total, what)`` while the grids are solved.
    """
    filtered = [band_passed(m, settings) for m in campaign.motions]
    motions = filtered if settings.band_pass else list(campaign.motions)
    if hasattr(progress, "stage"):  # said once every motion could be filtered
        progress.stage(f"exact outcomes of {settings.solves_per_test} blocks under each of "
                       f"{len(motions)} table motions")
    measures = intensities(filtered)
    coarse = overturning_grid(motions, settings, progress)
    solves = coarse.solves
    base = pd.DataFrame({"test": campaign.tests["test"],
                         "ground_motion": campaign.tests["ground_motion"],
                         "pga_g": measures.pga_g, "pgv_m_s": measures.pgv,
                         "pgv_pga_s": measures.pgv_pga_s})
    fits, fold_fits, score_rows, test_frames, predictions = {}, {}, [], [], []
    for name in campaign.specimens:
        observed = campaign.outcomes[name]
        known = ~np.isnan(observed)
        y = observed[known]
        motions_known = campaign.tests["ground_motion"][known]
        if motions_known.nunique() < settings.folds:
            raise InputError(f"{campaign.folder / 'tests.csv'}: {name}_overturned: outcomes of "
                             f"{motions_known.nunique()} ground motions, fewer than the "
                             f"{settings.folds} cross-validation folds")
        fold = folds_by_record(motions_known, settings.folds)
        grid, refined = _fine_grid(motions, settings, coarse, known, y, progress)
        solves += refined
        oof = out_of_fold(grid.overturned[known], y, fold,
                          Intensities(measures.pga[known], measures.pgv[known]), settings,
                          grid.blocks)
        fold_fits[name] = oof.fits
        fits[name] = fit = fit_block(grid.overturned[known], y, grid.blocks, settings.lapse)
        probabilities = dict(oof.probabilities)
        for column, values in campaign.peers[name].items():
            if not np.isnan(values[known]).any():
                probabilities[column] = values[known]
        score_rows += _score_rows(name, y, probabilities, settings.lapse)
        model = fit.predict(grid.overturned)
        frame = base.assign(specimen=name, observed=observed, fold=-1, p_model=model.p_overturn,
                            p_model_low=model.low, p_model_high=model.high)
        frame.loc[known, "fold"] = fold
        for method, values in oof.probabilities.items():
            column = np.full(observed.size, np.nan)
            column[known] = values
            frame["cv_" + method] = column
        test_frames.append(frame)
        predictions.append(pd.DataFrame({
            "test": campaign.tests["test"][~known], "specimen": name,
            "p_overturn": model.p_overturn[~known], "p_overturn_low": model.low[~known],
            "p_overturn_high": model.high[~known],
            "predicted_overturned": (model.p_overturn[~known] >= 0.5).astype(int)}))
    order = ["test", "specimen", "ground_motion", "fold", "pga_g", "pgv_m_s", "pgv_pga_s",
             "observed", "p_model", "p_model_low", "p_model_high"]
    tests = pd.concat(test_frames, ignore_index=True)
    tests = tests[order + [c for c in tests.columns if c not in order]]
    return CampaignValidation(fits, fold_fits, geometry, pd.DataFrame(score_rows), tests,
                              pd.concat(predictions, ignore_index=True), solves, settings)


def methods_statement(fits_table: pd.DataFrame, scores_table: pd.DataFrame) -> str:
    """The sentence a report's Methods gives about the validation of the exact model, from the
    saved ``validation-fits.csv`` and ``validation-scores.csv``.

    Parameters
    ----------
    fits_table : pandas.DataFrame
        ``validation-fits.csv``.
    scores_table : pandas.DataFrame
        ``validation-scores.csv``.
    """
    parts = []
    for row in fits_table.itertuples():
        model = scores_table[(scores_table["specimen"] == row.specimen)
                             & (scores_table["method"] == MODEL)].iloc[0]
        parts.append(f"{row.specimen}: α = {row.alpha_deg:.1f}° (95 % {row.alpha_deg_low:.1f}–"
                     f"{row.alpha_deg_high:.1f}°), p = {row.p_rad_s:.2f} rad/s, restitution "
                     f"{row.restitution_factor:g} × Eq. 4.8; cross-validated accuracy "
                     f"{model.accuracy:.0%}, Brier {model.brier:.3f} over {model.n} tests")
    return ("The exact rigid-block model was checked against shake-table outcomes of "
            "free-standing rocks by fitting an equivalent block per specimen (" +
            "; ".join(parts) + "). Limits: irregular 3-D specimens idealised as a 2-D block, "
            "one uniaxial table, one laboratory; the fitted restitution holds for these "
            "specimens only.")


def fitted_restitution(fits_table: pd.DataFrame, specimen: str | None = None) -> str:
    """The ``--restitution`` value (``xFACTOR``) of a saved fit: the named specimen's, or the
    factor every specimen shares; None when the specimens' factors differ.

    Parameters
    ----------
    fits_table : pandas.DataFrame
        ``validation-fits.csv``.
    specimen : str, optional
        The specimen.

    Returns
    -------
    str or None
    """
    rows = fits_table if specimen is None else fits_table[fits_table["specimen"] == specimen]
    factors = set(rows["restitution_factor"])
    return f"x{factors.pop():g}" if len(factors) == 1 else None


__all__ = ["CampaignValidation", "run_validation", "methods_statement", "fitted_restitution",
           "PREDICTIONS_CSV", "FITS_CSV", "SCORES_CSV", "TESTS_CSV", "RIDGE_CSV"]
