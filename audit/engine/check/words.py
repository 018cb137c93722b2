"""The words of ``audit check``: the sentence per object for a calculation note, and the
summary printed on standard output (a paragraph, then per object its sentence and table)."""

from __future__ import annotations

from statistics import median

from audit.engine.check.spectrum_read import reading_words
from records.suite import counted_records

#: Share of an annual rate from outside the stripes above which the sentence warns of it.
EXTRAPOLATED_SHARE = 0.10


def metres(value: float) -> str:
    """A width in metres: to the centimetre from 10 cm, to two significant figures below, so
    that a small object's width is not printed "0.00 m".

    Parameters
    ----------
    value : float
        The width [m].
    """
    return f"{value:.2f} m" if value >= 0.1 else f"{value:.2g} m"


def im_words(im, site_im: float, return_period_years: float | None = None) -> str:
    """The site's intensity in words, e.g. ``S_a(1 s) = S_X1 = 0.9 g``, or ``S_a(1 s) =
    0.764 g of the hazard curve at 2,475 years`` where the hazard curve sets it.

    Parameters
    ----------
    im : IntensityMeasure
        The check's intensity measure.
    site_im : float
        The site's intensity [g].
    return_period_years : float, optional
        The hazard curve's return period [years], where it sets the intensity.
    """
    if return_period_years is not None:
        name = f"S_a({im.period_s:g} s)" if im.kind == "sa" else "PGA"
        return (f"{name} = {site_im:.3g} g of the hazard curve at {return_period_years:,.0f} "
                "years")
    if im.kind == "sa":
        design = " = S_X1" if im.period_s == 1.0 else " of the design spectrum"
        return f"S_a({im.period_s:g} s){design} = {site_im:.3g} g"
    return f"PGA = 0.4 S_XS = {site_im:.3g} g"


def exact_width_words(exact: dict, target: str) -> str:
    """The exact width for P(overturn) ≤ ``target`` % with its 90 % band over records, to the
    precision the band supports, or why there is none.

    Parameters
    ----------
    exact : dict
        The object's ``exact`` entry of ``check.json``.
    target : str
        The target P(overturn) in per cent, ``"10"`` or ``"50"``.
    """
    from audit.engine.check.width_family import quoted
    width = exact[f"required_width_m_{target}pct"]
    if width is None:
        return "none ≤ 0.95 h (restrain it)"
    band = exact.get(f"required_width_m_{target}pct_band")
    atlas = exact.get("atlas")
    error = atlas and atlas[f"required_width_m_{target}pct_error"]
    if atlas:  # the atlas's width has no band over records: its own error instead
        return f"{width:.2f} m" + (f" ±{100 * error:.1f} %" if error is not None else "")
    return quoted(width, band) if band else f"{width:.2f} m"


def _names(titles) -> str:
    return titles[0] if len(titles) == 1 else ", ".join(titles[:-1]) + " and " + titles[-1]


def _judged(entries) -> str:
    """Procedures with their limit states, e.g. ``NTC 2018 / Circolare 2019 (SLV, SLC)``."""
    states = {}
    for entry in entries:
        states.setdefault(entry["procedure"], []).append(entry["limit_state"])
    return _names([title if names == ["overturning"] else f"{title} ({', '.join(names)})"
                   for title, names in states.items()])


def p_words(exact: dict, records: int) -> str:
    """The exact P(overturn) at the site as its headline says it, and which estimate that is:
    the lognormal's with its band, the count at the site's stripe with its exact band (where it
    rejects the lognormal's P: it lies outside the count's band), or the one-sided 95 % bound
    where no record (or every
    record) overturns the object there (:mod:`audit.engine.design.site_probability`).

    Parameters
    ----------
    exact : dict
        The object's ``exact`` entry of ``check.json``.
    records : int
        Number of records.
    """
    at = exact["p_at_site"]
    count = at["count"]
    k, n = count["overturned"], count["records"]
    atlas = exact.get("atlas")
    source = f", {atlas['text']}" if atlas else ""
    if at["bound"] is not None:
        return (f"{at['headline']} (one-sided 95 % bound: {k} of {n} records overturn it at "
                f"the site's intensity{source})")
    if at["estimator"] == "count":
        return (f"{at['headline']} ({k} of {n} records at the site's intensity, exact band; "
                + (f"they reject the lognormal's {100 * at['model']['p']:.0f} %{source})"
                   if at["model"]["p"] is not None else f"no lognormal fits{source})"))
    return f"{at['headline']} (lognormal; {k} of {n} records at the site's intensity{source})"


def sentence(answer: dict, im, sliding: dict | None = None) -> str:
    """One sentence for a calculation note: the guidelines' verdicts by their own limit states,
    the exact P(overturn) at the site with its band, the exact widths; with ``sliding``, what
    the base's friction does: first, the rest following as "if it could not slide", where
    sliding governs (``sliding["governs"]``: most records slide it), else after.

    Parameters
    ----------
    answer : dict
        The object's entry of ``check.json``.
    im : IntensityMeasure
        The check's intensity measure.
    sliding : dict, optional
        The object's ``sliding`` entry (:func:`~audit.engine.check.sliding.sliding_answer`).
    """
    head = f"{answer['name']} ({answer['width_m']:.3g} m wide × {answer['height_m']:.3g} m tall): "
    rocking = _rocking_words(answer, im)
    if sliding is None:
        return head + rocking
    if sliding.get("governs"):
        return f"{head}{sliding['text']} If it could not slide: {rocking}"
    return f"{head}{rocking} {sliding['text']}"


def _rocking_words(answer: dict, im) -> str:
    """:func:`sentence` after the object's name: the answers of rocking."""
    by = {v: [p for p in answer["procedures"] if p["verdict"] == v]
          for v in ("passes", "fails", "cannot judge")}
    parts = []
    if by["passes"]:
        parts.append(f"{_judged(by['passes'])} accept{'s' if len(by['passes']) == 1 else ''} it")
    if by["fails"]:
        parts.append(f"{_judged(by['fails'])} reject{'s' if len(by['fails']) == 1 else ''} it")
    if by["cannot judge"]:
        parts.append(f"{_judged(by['cannot judge'])} cannot judge it")
    exact = answer["exact"]
    text = ("; ".join(parts) + f"; the exact P(overturn) at "
            f"{im_words(im, exact['site_im_g'], exact.get('site_return_period_years'))} is "
            f"{p_words(exact, exact['stripes']['records'])}")
    w10, w50 = exact["required_width_m_10pct"], exact["required_width_m_50pct"]
    if w10 is None:
        text += "; no width up to 0.95 × its height brings it to 10 % (restrain it)"
    else:
        text += (f"; it needs {exact_width_words(exact, '10')} of base width for 10 %"
                 + (f" ({exact_width_words(exact, '50')} for 50 %)" if w50 is not None else ""))
    risk = answer["risk"]
    if risk is None:
        return text + "."
    width = risk["required_width_m"]
    rate = risk["annual_rate"]
    outside = risk["share_below_stripes"] + risk["share_above_stripes"]
    return (text + f". From the site's hazard curve it overturns at {rate:.2e}/yr"
            + (f" (once in {1 / rate:,.0f} years)" if rate > 0 else "")
            + f", P = {100 * risk['p50']:.2g} % in 50 years "
            f"({'within' if risk['meets_target'] else 'above'} the "
            f"{100 * risk['target_p50']:g} % target"
            + (f"; {metres(width)} of base width meets it)" if width is not None else
               "; no width up to 0.95 × its height meets it)")
            + (f"; {100 * outside:.0f} % of that rate comes from intensities outside the stripes, "
               "where the fitted fragility is extrapolated." if outside > EXTRAPOLATED_SHARE
               else "."))


def _compared(proc: dict, half_width_m: float) -> str:
    """Demand against capacity in words: θ against α (no uplift where θ = 0), d against the
    limit state's d_LS with d/d₀, or the check's numbers."""
    if proc["verdict"] == "cannot judge":
        return "cannot judge: " + (proc["reason"] or "")
    unit, demand, capacity = proc["unit"], proc["demand"], proc["capacity"]
    if unit == "deg":
        if demand is None:
            return f"θ ≥ α {capacity:.3g}° (overturns)"
        if demand == 0.0:
            return f"no uplift (θ = 0) vs α {capacity:.3g}°"
        return f"θ {demand:.3g}° vs α {capacity:.3g}°"
    if demand is None:
        return proc["reason"] or ""
    if unit == "m":
        words = (f"d {demand:.3g} m vs {capacity:.3g} m (d/d₀ {demand / half_width_m:.2f} vs "
                 f"{capacity / half_width_m:.2g})")
        return ("no uplift (d = 0) vs " + f"{capacity:.3g} m" if demand == 0.0 else words)
    return f"demand {demand:.3g} vs capacity {capacity:.3g} {unit}"


def anchorage_words(anchorage: dict) -> str:
    """The anchorage forces of a failing component provision: shear V and the far edge's
    tension T per unit weight (and in kN with the mass), and times Ω0p where the code asks.

    Parameters
    ----------
    anchorage : dict
        A provision entry's ``anchorage`` in check.json: ``shear``, ``tension`` [W], their
        ``_kN`` with the mass, ``omega_0p`` and the ``_omega`` forces where the code asks.
    """
    def forces(suffix: str) -> str:
        words = [f"{name} {anchorage[key + suffix]:.3g} W"
                 + (f" = {anchorage[key + suffix + '_kN']:.3g} kN"
                    if key + suffix + "_kN" in anchorage else "")
                 for name, key in (("V", "shear"), ("T", "tension"))]
        return ", ".join(words)
    text = forces("")
    if "omega_0p" in anchorage:
        text += f"; ×Ω0p {anchorage['omega_0p']:g} (non-ductile anchors): {forces('_omega')}"
    return text


def _percent(p: float | None) -> str:
    """Two significant figures, in fixed notation: "100 %", never "1e+02 %"."""
    return "—" if p is None else f"{float(f'{100 * p:.2g}'):g} %"


def _width_words(proc: dict) -> str:
    """The width a guideline requires, or why there is none."""
    width = proc["required_width_m"]
    if width is not None:
        return f"{width:.2f} m"
    if proc["verdict"] == "cannot judge":
        return "— (cannot judge)"
    return "none ≤ 0.99 h (restrain it)"


def _intensity(name: str):
    from audit.engine.shared.intensity import IntensityMeasure
    return IntensityMeasure.parse(name)


def _scaled_to(document: dict) -> str:
    """Where the records are scaled: the site's intensity, and the design spectrum's for the
    guidelines where the hazard curve sets the site's."""
    im = _intensity(document["im"])
    site_hazard = document.get("site_hazard")
    if not site_hazard:
        return im_words(im, document["site_im"])
    years = site_hazard["return_period_years"]
    return (f"{im_words(im, document['site_im'], years)} (P = "
            f"{100 * site_hazard['poe_50_years']:.2g} % in 50 years) for the exact answer, to "
            f"{im_words(im, document['design_im'])} for the guidelines,")


def summary_text(document: dict) -> str:
    """The summary on standard output: one paragraph, then per object its sentence and table.

    Parameters
    ----------
    document : dict
        ``check.json``.
    """
    site = document["site"]
    source = document["records_source"].split(":")[0]
    lines = [f"Site S_XS = {site['sxs_g']:g} g, S_X1 = {site['sx1_g']:g} g, at the hazard level "
             f"these values are for (as given); "
             f"{counted_records(len(document['records']), source)}, each scaled "
             f"to {_scaled_to(document)} and to "
             f"{len(document['levels'])} stripes {min(document['levels']):.3g}–"
             f"{max(document['levels']):.3g} {document['im_unit']} for the exact fragility "
             "(a fixed lattice, √2 apart, which the fragility is fitted on, and the site's own "
             "stripe; P at the site is the lognormal's unless the count at the site's stripe "
             "rejects it (the lognormal's P outside the count's exact band), then the count's: "
             "see docs/check.md).", ""]
    site_hazard = document.get("site_hazard")
    if site_hazard and site_hazard.get("warning"):
        lines[-1:-1] = [f"Warning: {site_hazard['warning']}."]
    floor = document.get("floor") or {}
    if floor.get("building_model"):
        peaks = list(floor["records"].values())
        lines[-1:-1] = [f"The objects stand {floor['description']}: the site scales the ground "
                        f"motion, the objects rock on the floor's (median over the records at the "
                        f"site: PFA {median([p['pfa_g'] for p in peaks]):.3g} g, PFV "
                        f"{median([p['pfv_m_s'] for p in peaks]):.3g} m/s)."]
    hazard = document.get("hazard")
    if hazard:
        lines[-1:-1] = [f"Risk from the hazard curve {hazard['source']}: target P ≤ "
                        f"{100 * hazard['target_p50']:g} % of overturning in 50 years; "
                        "'P in 50 yr' is of the object at the width each row requires."]
    for obj in document["objects"]:
        lines += [obj["sentence"], ""]
        rows = [("procedure", "limit state", "verdict", "demand vs capacity", "width needed",
                 "exact P(exceed)") + (("P in 50 yr",) if hazard else ())]
        for proc in obj["procedures"]:
            rows.append((proc["procedure"], proc["limit_state"], proc["verdict"],
                         _compared(proc, obj["width_m"] / 2.0), _width_words(proc),
                         _percent(proc["exact_p_exceed"]))
                        + ((_percent(proc["risk_p50"]),) if hazard else ()))
        for entry in obj.get("component_provisions", ()):  # static checks: no risk at a width
            width = entry["required_width_m"]
            rows.append((f"{entry['procedure']} (static)", entry["limit_state"],
                         entry["verdict"],
                         f"F/W {entry['demand']:.3g} vs {entry['capacity']:.3g} g"
                         if entry["demand"] is not None else entry["basis"],
                         metres(width) if width is not None else "—",
                         _percent(entry["exact_p_exceed"]))
                        + (("",) if hazard else ()))
            if entry.get("anchorage"):
                rows.append(("  its anchorage (if anchored)", "", "",
                             anchorage_words(entry["anchorage"]), "", "")
                            + (("",) if hazard else ()))
        exact = obj["exact"]
        for target in ("10", "50"):
            rows.append((f"exact, P(overturn) ≤ {target} %", "overturning", "", "",
                         exact_width_words(exact, target), "")
                        + (("",) if hazard else ()))
        if hazard:
            width = obj["risk"]["required_width_m"]
            rows.append((f"exact, P in 50 years ≤ {100 * hazard['target_p50']:g} %",
                         "overturning", "", "",
                         metres(width) if width is not None else "none ≤ 0.95 h", "",
                         f"≤ {_percent(hazard['target_p50'])}" if width is not None else ""))
        sizes = [max(len(row[k]) for row in rows) for k in range(len(rows[0]))]
        lines += ["  " + "  ".join(cell.ljust(size) for cell, size in zip(row, sizes)).rstrip()
                  for row in rows]
        lines += [f"  (object width {obj['width_m']:.3g} m; exact P(overturn) at the site "
                  f"{p_words(exact, exact['stripes']['records'])}; "
                  + (f"exact fragility: median {exact['median_g']:.3g} {exact['im_unit']}, "
                     f"β = {exact['beta']:.2f})" if exact["median_g"] else
                     "no lognormal fits the stripes: no record overturns it at any stripe, or "
                     "every record at every one)")]
        other = exact.get("other_im")
        if other:
            lines += [f"  (at the other standard intensity measure, the records scaled to "
                      f"{im_words(_intensity(other['im']), other['site_im'])} instead: exact "
                      f"P(overturn) {other['p_at_site']['headline']}"
                      + (f" from its atlas, ±{100 * other['p_error']:.1f} %"
                         if other.get("source") == "atlas" else "") + "; use the IM of "
                      "your hazard, see docs/check.md)"]
        lines += [""]
        lines += [f"  {proc['procedure']} {proc['limit_state']}: {proc['basis']}."
                  for proc in obj["procedures"] if proc["basis"]
                  and proc["basis"].startswith("applied record by record")]
        lines += [f"  {reading_words(proc)}." for proc in obj["procedures"]
                  if proc.get("other_spectrum")] + [""]
    return "\n".join(lines).rstrip() + "\n"


__all__ = ["sentence", "summary_text", "im_words", "anchorage_words", "EXTRAPOLATED_SHARE"]
