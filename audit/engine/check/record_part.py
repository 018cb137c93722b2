"""One record's part of a check (the unit of work the scheduler hands out): the record's stripes
(:func:`audit.engine.design.stripes.record_stripes` on the check's stripes), each
record-reading procedure's judgement at the site, and the friction each object needs there.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from audit.engine.check.judgement import at_site, judge
from audit.engine.check.sliding import required_friction
from audit.engine.design.stripes import RecordStripes, StripeSettings, record_stripes
from procedures.context import RecordContext


@dataclass(frozen=True)
class CheckWork:
    """What every record's part of a check depends on.

    Attributes
    ----------
    stripes : audit.engine.design.stripes.StripeSettings
        The stripes (the site's intensity its ``design_im``) and the objects as blocks.
    objects : tuple of audit.engine.shared.blocks.Block
    per_record : tuple of str
        Procedures judged on every record (those reading the record); the others read only the
        site and are judged once.
    site_im : float
        The site's intensity (one of the stripes) [unit of the IM].
    """

    stripes: StripeSettings
    objects: tuple
    per_record: tuple
    site_im: float

    @property
    def jobs(self) -> int:
        return self.stripes.jobs

    def with_jobs(self, jobs: int) -> CheckWork:
        """This work with ``jobs`` solver threads (a Dask worker's one).

        Parameters
        ----------
        jobs : int
            Solver threads.
        """
        return replace(self, stripes=replace(self.stripes, jobs=jobs))

    def as_dict(self) -> dict:
        return {**self.stripes.as_dict(), "kind": "check", "per_record": list(self.per_record),
                "site_im": self.site_im}


@dataclass
class CheckRecord:
    """One record's part of a check: its stripes, the judgements of the procedures that read
    it (None where a procedure cannot evaluate the record), and its context, whose cached
    spectra the width searches read again, and the friction each object's pure-rocking response
    needs at the site's intensity (:mod:`audit.engine.check.sliding`)."""

    stripes: RecordStripes
    judged: dict
    context: RecordContext
    required_friction: np.ndarray | None = None


def check_record(entry, procedures, settings: CheckWork) -> CheckRecord:
    """The unit of work of a check: one record's stripes, then each record-reading procedure's
    judgement at the site, on the same cached spectra. A check reads only verdicts, so its
    displacement spectra are computed only where the iterations read them (at each object's
    damping and, in the width search, at each width's).

    Parameters
    ----------
    entry : records.RecordEntry
        The record.
    procedures : sequence of procedures.base.Procedure
        The guidelines.
    settings : CheckWork
        The check's work: stripes, objects and the procedures judged record by record.
    """
    margins = settings.stripes
    context = RecordContext(entry, margins.free_motion_s, margins.jobs).on_demand()
    stripes = record_stripes(entry, procedures, margins, context)
    scaled, scaled_context = at_site(entry, context, stripes.intensity, margins.design_im)
    judged = {}
    for proc in procedures:
        if proc.name in settings.per_record and proc.unmet_requirements(scaled) is None:
            judged[proc.name] = judge(proc, scaled, scaled_context, settings.objects,
                                      margins.restitution, margins.g)
    friction = required_friction(entry.motion, settings.site_im / stripes.intensity,
                                 margins.blocks,
                                 margins.restitution, margins.g, margins.free_motion_s,
                                 margins.jobs)
    return CheckRecord(stripes, judged, context, friction)


__all__ = ["CheckWork", "CheckRecord", "check_record"]
