"""Which spectrum a guideline reads when the objects stand on a floor (``--guideline-spectrum
ground|floor``), and how far apart the two readings are.

The guidelines that read only a spectrum, not the time history: Priestley, Evison & Carr
(1978) the record's own displacement spectrum, Housner (1963) its velocity spectrum, NTC 2018
the record's displacement spectrum or its code spectrum, and FEMA 356 the site's design
spectrum (S_XS, S_X1), one answer for every record. On a floor the records are the floor
motions (:mod:`audit.engine.shared.floors`), so a guideline that reads the record reads the
floor motion's own spectrum, and NTC's code spectrum is the Circolare's floor spectrum
(§C7.2.3). FEMA 356's text reads the ground's design spectrum whatever the object stands on:

* ``ground`` (the default, as the text is written): FEMA 356 reads S_XS, S_X1 of ``--site``;
* ``floor``: it reads the floor's response spectrum instead, as a designer would feed it to
  FEMA 356: the median 5 %-damped spectrum of the floor motions at the site (the one
  ``check.json`` shows, ``floor.spectra``), read as a design spectrum's two parameters by the
  rule ASCE 7-16 §21.4 gives for a site-specific spectrum — S_XS = 0.9 × the largest Sa over
  0.2–5 s, S_X1 = the largest T·Sa over 1–5 s (§21.4's range for softer sites, so a building
  period anywhere up to 5 s is caught). FEMA 356 then modifies it for its damping (Table 1-6)
  and converts it to displacement (Eq. 3.5) as it does its own. The §21.4 rule is ASCE 7's for
  S_DS, S_D1, applied here by the project; FEMA 356's own words for a site-specific spectrum
  were not checked.

The building is linear, so the floor's spectrum scales with the ground's intensity as the
design spectrum does, and a stripe scales either alike. Either way, FEMA 356 is also judged on
the other spectrum, and the entry shows both verdicts and the ratio of the two spectra.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from audit.engine.check.judgement import judge
from audit.engine.check.limits import verdict
from audit.engine.shared.floors import floor_at_site

GROUND, FLOOR = "ground", "floor"
GUIDELINE_SPECTRA = (GROUND, FLOOR)
#: ASCE 7-16 §21.4: S_XS is this share of the largest Sa over SHORT_RANGE_S.
SHORT_SHARE = 0.9
SHORT_RANGE_S = (0.2, 5.0)
#: ASCE 7-16 §21.4 (v_s30 ≤ 365 m/s): S_X1 is the largest T·Sa over LONG_RANGE_S.
LONG_RANGE_S = (1.0, 5.0)


def floor_design_site(spectra: dict) -> dict:
    """S_XS and S_X1 [g] of the floor's median response spectrum, by ASCE 7-16 §21.4 (see the
    module).

    Parameters
    ----------
    spectra : dict
        ``floor.spectra`` of ``check.json``: ``period_s`` [s] and ``floor_median_sa_g`` [g],
        5 %-damped.

    Returns
    -------
    dict
        ``sxs_g`` and ``sx1_g`` [g].
    """
    period = np.asarray(spectra["period_s"], dtype=float)
    sa = np.asarray(spectra["floor_median_sa_g"], dtype=float)
    short = (period >= SHORT_RANGE_S[0]) & (period <= SHORT_RANGE_S[1])
    long = (period >= LONG_RANGE_S[0]) & (period <= LONG_RANGE_S[1])
    return {"sxs_g": SHORT_SHARE * float(sa[short].max()),
            "sx1_g": float((period[long] * sa[long]).max())}


def floor_site(suite, entries, im, free_motion_s: float, design_im: float) -> dict:
    """S_XS, S_X1 [g] of the floor's median response spectrum (:func:`floor_design_site`), the
    records scaled to the guidelines' intensity.

    Parameters
    ----------
    suite : records.RecordSuite
        The records on the floor.
    entries : sequence of records.RecordEntry
        Those with a motion.
    im : IntensityMeasure
        The check's intensity measure.
    free_motion_s : float
        Free motion after each record [s] (of its intensity, as the stripes read it).
    design_im : float
        The guidelines' intensity [unit of ``im``].
    """
    intensity = {entry.id: im.of_record(entry.motion, free_motion_s) for entry in entries}
    return floor_design_site(floor_at_site(suite, entries, intensity, design_im)["spectra"])


def reads_design_site(proc, entry) -> bool:
    """Whether ``proc`` reads only the FEMA 356 design site of ``entry`` (S_XS, S_X1): the
    guidelines ``--guideline-spectrum`` switches.

    Parameters
    ----------
    proc : procedures.base.Procedure
    entry : records.RecordEntry
    """
    return not proc.reads_record(entry) and "sxs_g" in proc.requires_site


def _site_words(site: dict) -> str:
    return f"S_XS = {site['sxs_g']:.3g} g, S_X1 = {site['sx1_g']:.3g} g"


def spectrum_words(choice: str, site: dict, on_floor: bool) -> str:
    """The spectrum a design-site guideline read, in words.

    Parameters
    ----------
    choice : str
        ``ground`` or ``floor``.
    site : dict
        The S_XS, S_X1 [g] it read.
    on_floor : bool
        Whether the objects stand on a floor.
    """
    if choice == FLOOR:
        return (f"the floor's response spectrum (median of the floor motions at the site, 5 %) "
                f"as {_site_words(site)} (ASCE 7-16 §21.4's reading)")
    return (f"the ground's design spectrum ({_site_words(site)})" if on_floor
            else f"the site's design spectrum ({_site_words(site)})")


def record_words() -> str:
    """What a guideline that reads the records read on a floor, in words."""
    return "each record's floor motion"


def other_reading(judgement, b: int, limit_state: str, choice: str, site: dict,
                  ratio: dict) -> dict:
    """A design-site guideline's verdict on the other spectrum, beside its entry.

    Parameters
    ----------
    judgement : audit.engine.check.judgement.Judgement
        Its judgement of every object on the other spectrum.
    b : int
        The object's index.
    limit_state : str
        The entry's limit state.
    choice : str
        The other spectrum, ``ground`` or ``floor``.
    site : dict
        The other spectrum's S_XS, S_X1 [g].
    ratio : dict
        The floor's S_XS and S_X1 over the ground's [-].
    """
    reading = next(r for r in judgement.readings[b] if r.limit_state == limit_state)
    demand = reading.demand
    return {"spectrum": choice, "site": site, "floor_over_ground": ratio,
            "spectrum_read": spectrum_words(choice, site, True),
            "verdict": "fails" if math.isinf(demand) else verdict(demand, reading.capacity),
            "demand": float(demand) if math.isfinite(demand) else None,
            "capacity": float(reading.capacity), "unit": reading.unit}


@dataclass
class GuidelineSpectra:
    """The spectra a check's design-site guidelines read, and read beside (see the module).

    Attributes
    ----------
    choice : str
        ``ground`` or ``floor``: the one read.
    ground : dict
        S_XS, S_X1 [g] of ``--site``.
    floor : dict or None
        S_XS, S_X1 [g] of the floor's median response spectrum at the site's design
        intensity (:func:`floor_design_site`); None on the ground.
    """

    choice: str
    ground: dict
    floor: dict | None = None

    @property
    def read(self) -> dict:
        """S_XS, S_X1 [g] of the spectrum read."""
        return self.floor if self.choice == FLOOR else self.ground

    @property
    def other(self) -> tuple[str, dict] | None:
        """The other spectrum (its name and S_XS, S_X1 [g]); None on the ground."""
        if self.floor is None:
            return None
        return (GROUND, self.ground) if self.choice == FLOOR else (FLOOR, self.floor)

    @property
    def ratio(self) -> dict | None:
        """The floor's S_XS and S_X1 over the ground's [-]; None on the ground."""
        if self.floor is None:
            return None
        return {key: self.floor[key] / self.ground[key] for key in ("sxs_g", "sx1_g")}

    def as_dict(self) -> dict:
        """``guideline_spectrum`` of ``check.json``."""
        return {"read": self.choice, "ground": self.ground, "floor": self.floor,
                "floor_over_ground": self.ratio}

    def judged_on_other(self, procedures, entry, context, objects, restitution, g) -> dict:
        """Each design-site guideline's judgement of every object on the other spectrum.

        Parameters
        ----------
        procedures : sequence of procedures.base.Procedure
            The guidelines that read only the site.
        entry, context :
            The first record and its spectra, at the site
            (:func:`~audit.engine.check.judgement.at_site`).
        objects : sequence of Block
        restitution : Restitution
        g : float
            Acceleration of gravity [m/s²].

        Returns
        -------
        dict
            Procedure name → :class:`~audit.engine.check.judgement.Judgement`.
        """
        other = replace(entry, site={**entry.site, **self.other[1]})
        return {proc.name: judge(proc, other, context, objects, restitution, g)
                for proc in procedures if reads_design_site(proc, entry)}

    def annotate(self, answers, procedures, first_entry, others: dict) -> None:
        """Give each guideline entry of ``answers`` the spectrum it read (``spectrum_read``)
        and, for a design-site guideline on a floor, its verdict on the other spectrum
        (``other_spectrum``, from ``others``: procedure name → its judgement there).

        Parameters
        ----------
        answers : list of dict
            The objects' entries of ``check.json``.
        procedures : sequence of procedures.base.Procedure
        first_entry : records.RecordEntry
            The suite's first record (the site each guideline read).
        others : dict
            Procedure name → :class:`~audit.engine.check.judgement.Judgement` on the other
            spectrum.
        """
        on_floor = self.floor is not None
        by_name = {proc.name: proc for proc in procedures}
        for b, answer in enumerate(answers):
            for entry in answer["procedures"]:
                proc = by_name[entry["key"]]
                if reads_design_site(proc, first_entry):
                    entry["spectrum_read"] = spectrum_words(self.choice, self.read, on_floor)
                    if self.choice == FLOOR:  # the basis names the site's, which it did not read
                        entry["basis"] = entry["basis"].replace(
                            "the site's design spectrum", "a design spectrum (the floor's here)")
                    if proc.name in others and entry["verdict"] != "cannot judge":
                        name, site = self.other
                        entry["other_spectrum"] = other_reading(
                            others[proc.name], b, entry["limit_state"], name, site, self.ratio)
                elif on_floor and proc.reads_record(first_entry):  # the procedure's own words
                    entry["spectrum_read"] = f"{entry['spectrum_read']} ({record_words()})"


def reading_words(entry: dict) -> str:
    """What a design-site guideline's entry read on a floor, and its verdict on the other
    spectrum, in words (a line of the printed summary and of the page).

    Parameters
    ----------
    entry : dict
        A guideline entry of ``check.json`` with ``other_spectrum``.
    """
    other, ratio = entry["other_spectrum"], entry["other_spectrum"]["floor_over_ground"]
    outcome = ("it would fail too" if other["verdict"] == entry["verdict"] == "fails" else
               "it would pass too" if other["verdict"] == entry["verdict"] == "passes" else
               f"it would {'fail' if other['verdict'] == 'fails' else 'pass'}")
    demand = ("θ ≥ α" if other["demand"] is None else
              "no uplift" if other["demand"] == 0.0 else f"θ {other['demand']:.3g}°") \
        if other["unit"] == "deg" else f"{other['demand']:.3g} {other['unit']}"
    return (f"{entry['procedure']} {entry['limit_state']} read {entry['spectrum_read']}; on "
            f"{other['spectrum_read']} {outcome} ({demand}). The floor's spectrum is "
            f"{ratio['sxs_g']:.2g}× the ground's design spectrum at short periods (S_XS) and "
            f"{ratio['sx1_g']:.2g}× at 1 s (S_X1)")


__all__ = ["GROUND", "FLOOR", "GUIDELINE_SPECTRA", "GuidelineSpectra", "floor_design_site",
           "floor_site", "reads_design_site", "reading_words", "spectrum_words", "record_words", "other_reading"]
