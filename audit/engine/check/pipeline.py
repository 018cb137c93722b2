"""``audit check``: does this object, at this site, pass each guideline; how likely is it really
to overturn; how wide must it be.

For every object (:mod:`audit.engine.check.objects`) and a FEMA 356 site (S_XS, S_X1 at the
hazard level the user assesses), the suite's records are each scaled to the site's intensity
(S_X1 for the default S_a(1 s); the design spectrum at the intensity measure otherwise; with a
hazard curve and a return period, the curve's, while the guidelines keep the design spectrum:
:mod:`audit.engine.check.site`) and to the fixed stripe lattice, every other level (√2 apart,
:func:`check_levels`, :mod:`audit.engine.shared.lattice`): the design-level audit's unit of work
(:func:`audit.engine.design.stripes.record_stripes`). From it, per object:

* the exact multiple-stripe fragility (:func:`~audit.engine.design.lognormal_fit.fit_lognormal`),
  fitted on the lattice's stripes only, so it is the object's (with the record set and the
  floor), not the site's; its P(overturn) at the site's intensity with a band from a bootstrap
  over records (:func:`~audit.engine.design.bootstrap.bootstrap_lognormal`), beside the count at
  the site's own stripe with its exact band, the headline the one the count does not contradict
  (:mod:`audit.engine.design.site_probability`);
* per procedure and limit state, its verdict at the site by its own acceptance criterion,
  demand against capacity (:mod:`audit.engine.check.limits`: NTC 2018's SLV and SLC on d/d₀,
  θ against α, Housner's energy check; the records' demands made one by the guideline's rule
  for a suite), the exact P at the site of exceeding that same limit, and where it draws its
  line on the stripes;
* the friction each record needs at the site and, on a base of friction μ, which mode governs
  (:mod:`audit.engine.check.sliding`);
* the width each guideline requires at the object's height, against the exact widths for
  P(overturn) at the site ≤ 10 % and ≤ 50 % (:mod:`audit.engine.check.widths`): each record's
  bracket found with its judgement, the brackets that matter halved after.

With an atlas of the records on the floor, the exact side of every object inside its grid (the
fragility, P at the site, the exact widths, the risk) is read from it instead
(:mod:`audit.engine.check.atlas_side`), with its error there; the rest is solved as above.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from audit.engine.shared.blocks import BlockList
from audit.engine.shared.lattice import on_lattice, with_site
from audit.engine.check.risk import hazard_document, object_risk, p50_of_blocks
from audit.engine.check.settings import CheckSettings
from audit.engine.check.atlas_side import AtlasSide, CheckAtlases
from audit.engine.check.site import site_intensity
from audit.engine.check.sliding import sliding_answer
from audit.engine.check.words import sentence
from audit.engine.check.judgement import at_site, judge
from audit.engine.check.record_part import CheckWork, check_record
from audit.engine.check.guideline_widths import GuidelineWidths
from audit.engine.check.spectrum_read import (FLOOR, GuidelineSpectra, floor_design_site,
                                              floor_site)
from audit.engine.check.widths import Family, exact_required_widths, probability_at_site
from audit.engine.check.other_im import other_im_answers
from audit.engine.check.component_checks import component_entries, component_provisions
from audit.engine.shared.design_site import Site
from audit.engine.shared.floors import floor_at_site
from audit.engine.design.guideline_lines import guideline_lines
from audit.engine.check.width_family import width_answer
from audit.engine.design.site_probability import lattice_fragility
from audit.engine.design.stripes import StripeSettings
from audit.engine.design.risk import LognormalFragility, StripeFragility
from audit.engine.shared.runtime import Runtime
from audit.engine.shared.scheduler import computed_parts, open_scheduler, side_thread
from audit.errors import InputError, InputWarning
from audit.physics.building.floor import Floor
from procedures.parameters import parameters_used
from records.sites import NTC2018_SITE_KEYS

#: Every how many levels of the lattice a check solves (2: √2 apart).
LATTICE_EVERY = 2
#: Exact P(overturn) at the site that the exact required widths target.
TARGETS = (0.10, 0.50)


def check_levels(site_im: float) -> np.ndarray:
    """The stripes of a check, ascending: the lattice's levels √2 apart
    (:func:`~audit.engine.shared.lattice.stripe_lattice`, every :data:`LATTICE_EVERY`) and one
    stripe at the site's intensity (added, unless it is a lattice level).

    Parameters
    ----------
    site_im : float
        The site's intensity (in the IM's unit, e.g. [g]).
    """
    return with_site(site_im, LATTICE_EVERY)


def fitted_stripes(levels) -> np.ndarray:
    """Which of a check's stripes the fragility is fitted on: the lattice's (not a site's).

    Parameters
    ----------
    levels : array_like of float
        The check's stripes (in the IM's unit).
    """
    return on_lattice(levels, LATTICE_EVERY)


@dataclass
class CheckRun:
    """What a check produced: per object, the exact answer and each procedure's (the fields of
    ``check.json``), and the run's description."""

    objects: list
    summary: dict


def run_check(procedures, suite, objects, settings: CheckSettings,
              runtime: Runtime, floor: Floor = Floor(), provision_params: dict | None = None,
              atlases: CheckAtlases | None = None) -> CheckRun:
    """Check every object at the suite's design site (see the module).

    Parameters
    ----------
    procedures : list of procedures.Procedure
    suite : records.RecordSuite
        Its ``design_site`` (S_XS, S_X1 [g]) is the site.
    objects : sequence of audit.engine.shared.blocks.Block
    settings : audit.engine.check.settings.CheckSettings
        With a hazard curve, also the risk (:mod:`audit.engine.check.risk`).
    runtime : audit.engine.shared.runtime.Runtime
        ``jobs``, ``scheduler`` and ``progress`` (a check keeps no parts to resume).
    floor : audit.physics.building.floor.Floor
        Where the objects stand, for the component provisions' static checks
        (:mod:`audit.engine.check.component_checks`, ``component_provisions`` of each object).
    provision_params : dict, optional
        The component provisions' parameters, ``{name: {attribute: value}}`` (checked).
    atlases : audit.engine.check.atlas_side.CheckAtlases, optional
        Atlases of the suite on this floor (restitution, g and free motion the check's) and
        their keys: of the check's intensity measure, the exact side of every object inside
        its grid read from it (:mod:`audit.engine.check.atlas_side`), the others solved; of
        the other standard one, P there (:mod:`audit.engine.check.other_im`).
    """
    from audit.engine.check.summary import (CheckFrame, ObjectFindings, object_answer,
                                            run_summary)
    entries = [entry for entry in suite if entry.motion is not None]
    if not entries:
        raise InputError(f"records: no record of {suite.description} has a file", "records")
    im, restitution, g = settings.im, settings.restitution, settings.g
    site = site_intensity(im, suite.design_site, settings.hazard,
                          settings.site_return_period_years)
    site_im, design_im = site.site_im, site.design_im  # the exact answer's; the guidelines'
    spectra = GuidelineSpectra(settings.guideline_spectrum,
                               {key: suite.design_site[key] for key in ("sxs_g", "sx1_g")})
    if not floor.on_ground and settings.guideline_spectrum == FLOOR:
        # the design-site guidelines read the floor's spectrum from the start, stripes and all
        spectra.floor = floor_site(suite, entries, im, settings.free_motion_s, design_im)
        entries = [replace(entry, site={**entry.site, **spectra.floor}) for entry in entries]
    levels = check_levels(site_im)
    fitted = fitted_stripes(levels)  # the fragility's stripes: the lattice, not the site's
    objects = tuple(objects)
    atlases = atlases or CheckAtlases()
    side = (AtlasSide.of(*atlases.own, objects, levels, fitted, site_im, g)
            if atlases.own is not None else None)
    covered = side.covered if side is not None else np.zeros(len(objects), dtype=bool)
    jobs, progress = runtime.jobs, runtime.progress
    per_record = tuple(p.name for p in procedures if p.reads_record(entries[0]))
    # the atlas answers whether each record overturns each object; the records' exact peak θ
    # is read only by a limit short of overturning: with none chosen, nothing is solved
    rotations = not covered.all() or any(p.rotation_limits for p in procedures)
    work = CheckWork(StripeSettings(im, tuple(levels.tolist()), design_im,
                                    BlockList.of(named=objects), restitution, g,
                                    settings.free_motion_s, jobs, exact=rotations),
                     objects, per_record, site_im)
    curve = settings.hazard
    targets = TARGETS + ((settings.risk_target,) if curve is not None else ())

    def measure(overturned, levels):  # P at the site for TARGETS, P in 50 years for the risk
        p_site = probability_at_site(overturned, levels, site_im)
        if curve is None:
            return p_site
        return np.column_stack([p_site] * len(TARGETS) + [p50_of_blocks(overturned, levels,
                                                                         curve)])

    with open_scheduler(runtime.scheduler, jobs) as executor:
        parts, _, where = computed_parts(check_record, entries, procedures, work, executor,
                                         progress=progress)
        _stage(progress, "the exact width for P(overturn) ≤ 10 % and ≤ 50 % at each height"
               + (" and for the risk target" if curve is not None else ""))
        intensity = {e.id: part.stripes.intensity for e, part in zip(entries, parts)}
        # the width searches read the fragility alone: the lattice's stripes, not the site's
        family = Family(entries, levels[fitted], intensity, settings, jobs, executor, progress)
        contexts = {}  # records scaled to the site, on the spectra their parts computed

        def site_context(i: int):
            if i not in contexts:
                contexts[i] = at_site(entries[i], parts[i].context, intensity[entries[i].id],
                                      design_im)
            return contexts[i]

        def beside_the_exact_search():
            # a procedure reading only the site: one answer for every record, judged on the first
            site_judged = {p.name: judge(p, *site_context(0), objects, restitution, g)
                           for p in procedures if p.name not in per_record
                           and p.unmet_requirements(site_context(0)[0]) is None}
            lines = guideline_lines(
                procedures, entries, work.stripes,
                {p.name: np.stack([part.stripes.predicted[p.name] for part in parts])
                 for p in procedures},
                {p.name: np.array([part.stripes.evaluated[p.name] for part in parts])
                 for p in procedures})
            search = GuidelineWidths(parts, lines, site_judged, site_context, settings)
            document = floor_at_site(suite, entries, intensity, site_im)
            on_other = {}
            if not floor.on_ground:  # the design-site guidelines on the other spectrum too
                if spectra.floor is None:
                    spectra.floor = floor_design_site(
                        (document if site_im == design_im else
                         floor_at_site(suite, entries, intensity, design_im))["spectra"])
                on_other = spectra.judged_on_other(
                    [p for p in procedures if p.name in site_judged], *site_context(0),
                    objects, restitution, g)
            return ([[search.of(proc, b, obj) for proc in procedures]
                     for b, obj in enumerate(objects)], document, on_other)

        # the guidelines' searches and, on a floor, the spectra of the floor and ground motions
        # run on a side thread beside the exact search (one solver call per record)
        with side_thread() as beside:
            guidelines = beside.submit(beside_the_exact_search)
            solved = []
            widths, width_errors = _exact_widths(family, objects, covered, side, targets,
                                                 measure, solved)
            _stage(progress, "the exact P(overturn) at the other standard intensity measure")
            others = other_im_answers(family, objects, suite.design_site, check_levels,
                                      fitted_stripes, settings.seed, atlases.other)
            _stage(progress, "the width each guideline requires at each object's height")
            judged, floor_document, on_other = guidelines.result()
        exact_over = np.stack([part.stripes.exact_overturned for part in parts])
        exact_theta = np.stack([part.stripes.exact_theta_rad for part in parts])
        guideline_p50 = (_guideline_risk(family, objects, judged, curve) if curve is not None
                         else {})
    frame = CheckFrame(levels, site_im, im, [e.id for e in entries], entries[0],
                       settings.limit_state, fitted)
    answers = []
    read = np.flatnonzero(covered)  # the objects whose exact side is the atlas's
    from_atlas = (side.outcomes([objects[b].alpha_deg for b in read],
                                [objects[b].size_s for b in read]) if read.size else None)
    p_errors = (side.p_error([objects[b].alpha_deg for b in read],
                             [objects[b].size_s for b in read]) if read.size else None)
    for b, obj in enumerate(objects):
        solved_over = exact_over[:, :, b]  # (record, stripe)
        source = None
        if covered[b]:
            k = int(np.searchsorted(read, b))
            over = from_atlas[:, :, k]
            source = side.source(float(p_errors[k]), width_errors[b], rotations,
                                 others[b]["source"])
            family_widths = None  # the width family is fitted on solved widths: none here
        else:
            over = solved_over
            family_widths = _family_widths(obj, over[:, fitted], solved, levels[fitted],
                                           site_im)
        fit, boot = lattice_fragility(levels[fitted], over[:, fitted], settings.seed)
        risk = None
        if curve is not None:
            model = LognormalFragility(fit.median, fit.beta) if fit else None
            counted = StripeFragility(levels[fitted], over[:, fitted].mean(axis=0))
            width = widths[b][len(TARGETS)]
            risk = object_risk(model, counted, curve, settings.risk_target,
                               float(width) if math.isfinite(width) else None)
        answers.append(object_answer(
            ObjectFindings(obj, b, fit, boot, over, widths[b], judged[b], risk,
                           guideline_p50.get(b, {}), exact_theta[:, :, b] if rotations else None,
                           family_widths, others[b], solved_over if rotations else None, source),
            frame))
        sliding = sliding_answer([part.required_friction[b] for part in parts], frame.record_ids,
                                 obj.alpha_deg, settings.friction)
        answer = answers[-1]
        answer["exact"]["site_return_period_years"] = site.return_period_years
        answer.update(sliding=sliding, sentence=sentence(answer, im, sliding))
    design_site = suite.design_site or {}
    ntc = entries[0].site
    ntc_site = (tuple(ntc[key] for key in NTC2018_SITE_KEYS)
                if all(ntc.get(key) is not None for key in NTC2018_SITE_KEYS) else None)
    provisions = component_provisions(provision_params)
    for obj, answer in zip(objects, answers):
        answer["component_provisions"] = [
            {**entry, "exact_p_exceed": answer["exact"]["p_overturn_at_site"]}
            for entry in component_entries(obj.width_m, obj.height_m,
                                           site=Site(design_site["sxs_g"], design_site["sx1_g"],
                                                     ntc=ntc_site), floor=floor,
                                           provisions=provisions, mass_kg=settings.mass_kg)]
    spectra.annotate(answers, procedures, entries[0], on_other)
    if curve is not None:
        _warn_truncated(answers, curve)
    summary = run_summary(suite, entries, im, levels, site_im, procedures, restitution, where)
    summary.update(design_im=design_im, site_hazard=site.as_dict(curve),
                   friction=settings.friction)
    summary["floor"] = floor_document
    # every parameter the guidelines and provisions used, with the clause of its default
    summary["parameters"] = {plug_in.name: parameters_used(plug_in)
                             for plug_in in (*procedures, *provisions)
                             if type(plug_in).parameters}
    summary["mass_kg"] = settings.mass_kg
    summary["guideline_spectrum"] = spectra.as_dict()
    if curve is not None:
        summary["hazard"] = hazard_document(curve, settings.risk_target)
    return CheckRun(answers, summary)


def _exact_widths(family: Family, objects, covered, side, targets, measure, solved):
    """Each object's exact widths for ``targets`` (object, target) [m] and, where they are the
    atlas's, their relative errors for the first two (object, 2) [-] (NaN where solved).
    Objects of one height share their search: the width it finds is the height's; the heights
    of objects inside the atlas searched on it, the others' solved (appended to ``solved``)."""
    heights = np.array([o.height_m for o in objects])
    widths = np.full((len(objects), len(targets)), np.nan)
    errors = np.full((len(objects), 2), np.nan)
    for on_atlas in (False, True):
        mine = np.flatnonzero(covered == on_atlas)
        if not mine.size:
            continue
        unique, height_of = np.unique(heights[mine], return_inverse=True)
        if on_atlas:
            found = side.required_widths(unique, targets, measure)
            errors[mine] = side.width_errors(unique, found[:, :len(TARGETS)],
                                             TARGETS)[height_of]
        else:
            found = exact_required_widths(family, unique, targets, measure, solved)
        widths[mine] = found[height_of]
    return widths, errors


def _family_widths(obj, over, solved, levels, site_im):
    """The object's height as one fragility family (:mod:`audit.engine.check.width_family`), fitted on
    the object's own outcomes and every width solved at its height, on the lattice's stripes
    ``levels``."""
    widths, outcomes = [obj.width_m], [over[:, :, None]]
    for heights, solved_widths, overturned in solved:
        mine = heights == obj.height_m
        widths += solved_widths[mine].tolist()
        outcomes.append(overturned[:, :, mine])
    return width_answer(widths, levels, np.concatenate(outcomes, axis=2), site_im, TARGETS,
                        obj.height_m)


def _stage(progress, text: str) -> None:
    if progress is not None and hasattr(progress, "stage"):
        progress.stage(text)


def _guideline_risk(family: Family, objects, judged, curve) -> dict:
    """P in 50 years of each object at the width each guideline requires, {object: {procedure
    name: P}}: every such block solved together."""
    pairs = [(b, proc.name, width) for b, row in enumerate(judged)
             for proc, _, _, width, _, _ in row if math.isfinite(width) and width > 0]
    out = {b: {} for b in range(len(objects))}
    if pairs:
        overturned = family.overturned([objects[b].height_m for b, _, _ in pairs],
                                       [w for _, _, w in pairs])
        for (b, name, _), p50 in zip(pairs, p50_of_blocks(overturned, family.levels, curve)):
            out[b][name] = float(p50)
    return out


def _warn_truncated(answers, curve) -> None:
    truncated = [a["name"] for a in answers if a["risk"]["truncated"]]
    if truncated:
        warnings.warn(f"hazard: {curve.source}: the curve stops below the fragility's median "
                      f"of {', '.join(truncated)}: their annual rate is a lower bound "
                      "(check.json risk.annual_rate_upper bounds it)", InputWarning,
                      stacklevel=3)


__all__ = ["run_check", "CheckRun", "check_levels", "fitted_stripes",
           "LATTICE_EVERY", "TARGETS"]
