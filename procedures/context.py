"""What a procedure may ask of one record: its response spectra, computed once and cached (in
the process, and between runs in the user cache: :mod:`audit.physics.spectra_store`).

Record spectra are tabulated on :data:`procedures.base.SPECTRUM_PERIODS_S`, linear in T in
between, which is what the root scan of :func:`procedures.rotation_map.fixed_points` relies on.
"""

from __future__ import annotations

from concurrent.futures import Future

from audit.physics.defaults import DEFAULT_FREE_MOTION_S
from audit.physics.response_spectra import DisplacementOnDemand, response_spectra
from audit.physics.spectra_store import stored_spectra
from procedures.base import SPECTRUM_PERIODS_S
from procedures.tabulated import TabulatedDisplacement, TabulatedOnDemand


class RecordContext:
    """The spectra of one record that procedures read, computed once and cached.

    Parameters
    ----------
    entry : records.RecordEntry
        The record; ``entry.motion`` is None for a record without a file (a procedure that
        needs no motion, such as one reading a design spectrum, still estimates).
    free_motion_s : float
        Free motion after the record [s], the same window as the exact solver's.
    jobs : int
        Threads computing the record's spectra.
    """

    def __init__(self, entry, free_motion_s: float = DEFAULT_FREE_MOTION_S, jobs: int = 1):
        self.entry = entry
        self.free_motion_s = free_motion_s
        self.jobs = jobs
        # the spectra are those of ``_motion`` × ``_factor``: scaled contexts share them, and
        # the displacement spectra computed where read (``_on_demand``, by damping) too
        self._motion, self._factor, self._spectra = entry.motion, 1.0, {}
        self._on_demand, self._partial = False, {}
        # the cached spectra × _factor, by damping: a procedure reads them several times per
        # evaluation, and a check evaluates every object at each stripe
        self._scaled = {}

    def scaled(self, entry, factor: float) -> RecordContext:
        """The context of ``entry``, this context's record scaled by ``factor``: it reads the
        same cached spectra × factor (a linear oscillator's response is linear in the ground
        motion), so scaling a record to many levels computes its spectra once."""
        other = RecordContext(entry, self.free_motion_s, self.jobs)
        other._motion, other._factor = self._motion, self._factor * factor
        other._spectra, other._partial = self._spectra, self._partial
        other._on_demand = self._on_demand
        if factor == 1.0:
            other._scaled = self._scaled
        return other

    def on_demand(self) -> RecordContext:
        """This context, its displacement spectra not yet cached computed only at the periods
        read (:class:`~procedures.tabulated.TabulatedOnDemand`), with the same values: for a
        verdict alone, whose iteration reads a few dozen of the 801 periods at a damping read
        nowhere else (not for fixed points or a stored spectrum, which read them all)."""
        other = self.scaled(self.entry, 1.0)
        other._on_demand = True
        return other

    def prefetch(self, damping: float, pool) -> None:
        """Start computing the full spectra at damping β [-] on ``pool`` (an executor), unless
        cached: :meth:`true_spectra` waits for them when first asked, so the kernel runs
        beside whatever the caller does meanwhile."""
        key = round(float(damping), 12)
        if key not in self._spectra:
            self._spectra[key] = (pool.submit(response_spectra, self._motion, SPECTRUM_PERIODS_S,
                                              [key], self.free_motion_s, jobs=self.jobs), False)

    def true_spectra(self, damping: float, displacement_only: bool = False):
        """True response spectra of the record at damping β [-] on :data:`SPECTRUM_PERIODS_S`;
        Sd alone (Sv, Sa NaN) when ``displacement_only`` and no full spectra are cached."""
        key = round(float(damping), 12)
        cached = self._spectra.get(key)
        if cached is not None and isinstance(cached[0], Future):  # prefetched
            cached = self._spectra[key] = (cached[0].result(), cached[1])
        if cached is None or (cached[1] and not displacement_only):
            # a record's property at a damping its guideline fixes: kept between runs
            self._spectra[key] = (stored_spectra(
                self._motion, SPECTRUM_PERIODS_S, key, self.free_motion_s, jobs=self.jobs,
                displacement_only=displacement_only), displacement_only)
        spectra = self._spectra[key][0]
        if self._factor == 1.0:
            return spectra
        base, scaled = self._scaled.get(key, (None, None))
        if base is not spectra:  # not yet scaled, or the full spectra replaced Sd alone since
            scaled = spectra.scaled(self._factor)
            self._scaled[key] = (spectra, scaled)
        return scaled

    def true_displacement(self, damping: float):
        """Sd(T) [m] at damping β [-], linear in T between the tabulated periods."""
        key = round(float(damping), 12)
        if self._on_demand and key not in self._spectra:
            if key not in self._partial:
                self._partial[key] = DisplacementOnDemand(self._motion, SPECTRUM_PERIODS_S, key,
                                                          self.free_motion_s)
            return TabulatedOnDemand(self._partial[key], self._factor)
        spectra = self.true_spectra(damping, displacement_only=True)
        return TabulatedDisplacement(spectra.period_s, spectra.sd[0])


__all__ = ["RecordContext"]
