"""``python -m audit list``: registered procedures, the built-in suites and the records of the
record source."""

from __future__ import annotations

from audit.cli import options


def add_parser(sub):
    p = sub.add_parser("list", help="registered procedures, built-in suites and the records of the "
                                    "record source")
    options.add_records_option(p)
    options.add_skip_bad_records_option(p)
    p.set_defaults(func=run)


def run(args) -> int:
    from audit.api import (available_procedures, built_in_suites, pulse_words,
                           record_suite)
    print("Procedures:")
    for name, cls in available_procedures().items():
        print(f"  {name:<16} {cls.title} — {cls.damping_law}; {cls.spectrum_source}")
    print("\nProbabilistic procedures (audit fragility --procedure NAME):")
    for name, cls in available_procedures(probabilistic=True).items():
        print(f"  {name:<16} {cls.title} — P({cls.event} | "
              f"{'/'.join(sorted({c.intensity_measure for c in cls.components}))}) of "
              f"{len(cls.components)} components")
    print("\nBuilt-in suites (--records NAME):")
    for name, holds in built_in_suites().items():
        print(f"  {name:<26} {holds}")
    suite = record_suite(options.records(args))
    print(f"\nRecords ({suite.description}):")
    unknown = 0
    for entry in suite:
        if entry.missing:
            state = f"MISSING: {entry.missing_reason}"
        else:
            m = entry.motion
            state = (f"PGA {m.pga_g:.3f} g, PGV {m.pgv:.2f} m/s, dt {m.dt:g} s, "
                     f"{m.duration:.1f} s — {m.source}")
        site = (f" [FEMA site {entry.site.get('site_class') or '?'}: S_XS {entry.site['sxs_g']:g} g, "
                f"S_X1 {entry.site['sx1_g']:g} g]" if entry.site.get("sxs_g") else "")
        print(f"  {entry.id:<20} {entry.name}: {state}{site}")
        facts = seismology(entry.metadata)
        if facts:
            print(f"  {'':<20} {facts}")
        pulse = "" if entry.missing or entry.motion.pulse else pulse_words(entry)
        if pulse:
            print(f"  {'':<20} {pulse}")
        unknown += bool(not entry.missing and not entry.motion.pulse and not pulse)
    if unknown:
        print(f"\n{unknown} records' velocity pulses not identified yet (list reads them from "
              f"the cache): python -m audit pulse --records ...")
    return 0


#: Metadata key → how ``list`` shows it (P695 records name the mechanism ``fault_type``).
FACT_FORMATS = (("rsn", "RSN {}"), ("magnitude", "M {:g}"), ("mechanism", "{}"),
                ("fault_type", "{}"), ("rjb_km", "Rjb {:.1f} km"), ("rrup_km", "Rrup {:.1f} km"),
                ("vs30_m_s", "Vs30 {:.0f} m/s"), ("scale_factor", "scaled × {:g}"))


def seismology(metadata: dict) -> str:
    """The event, station, magnitude, distances [km], Vs30 [m/s] and scale factor a record's
    metadata holds, on one line (empty where it holds none), e.g. "Landers 1992, Joshua Tree:
    RSN 864, M 7.28, strike slip, Rjb 11.0 km, Rrup 11.0 km, Vs30 379 m/s"."""
    event = " ".join(str(metadata[key]) for key in ("event", "year") if key in metadata)
    where = ", ".join(text for text in (event, metadata.get("station", "")) if text)
    facts = ", ".join(form.format(metadata[key]) for key, form in FACT_FORMATS if key in metadata)
    return ": ".join(text for text in (where, facts) if text)
