"""Bad input, as a hostile file and a tired user would give it: one line, exit 2, nothing written.

Every case of the corpus runs ``audit.cli.main`` in-process on inputs written into an empty
folder, and asserts that standard error holds exactly one line, that the line names the
option, field or file at fault, that the exit status is 2, and that no file appeared. A few
cases run ``python -m audit`` in a real process (signals, the entry point's own exit codes).
"""

import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from audit.cli import EXIT_INTERRUPTED, main
from audit.engine.shared import guards
from audit.engine.shared.schemas import GUIDE
from audit.files import write_files_atomically
from audit.errors import InputError
from records import ENV_VARIABLE, load_records

ROOT = Path(__file__).resolve().parents[2]

# --- small, valid inputs that the cases below break one field at a time ---------------------

VALUES = 0.3 * np.sin(np.linspace(0.0, 6.0 * np.pi, 200))  # 200 samples, PGA 0.3 g


def at2_text(npts="200", dt=".0100", units="ACCELERATION TIME SERIES IN UNITS OF G",
             values=None, header4=None):
    body = "\n".join(f"{v: .7E}" for v in (VALUES if values is None else values))
    line4 = header4 or f"NPTS=   {npts}, DT=   {dt} SEC"
    return (f"PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 90\n{units}\n"
            f"{line4}\n{body}\n")


def txt_text(comment="% test record. Acc. in g and dt=0.01 sec.", values=None):
    return comment + "\n" + "\n".join(f"{v:.7e} {2 * v:.7e}"
                                      for v in (VALUES if values is None else values)) + "\n"


class SymLink(str):
    """A file of a case that is a symbolic link to this target."""


GOOD_AT2 = at2_text()
GOOD_TXT = txt_text()


def manifest(**fields):
    """One [[record]] of a columns file ``rec.txt``; a field given as None is left out."""
    base = {"id": '"rec"', "file": '"rec.txt"', "format": '"columns"', "column": "1",
            "dt": "0.01", "units": '"g"'}
    base.update(fields)
    lines = [f"{key} = {value}" for key, value in base.items() if value is not None]
    return "[[record]]\n" + "\n".join(lines) + "\n"


def with_manifest(text, **files):
    return {"suite.toml": text, "rec.txt": GOOD_TXT, **files}


# Each case: (id, files to create, argv, words the error line must contain).
LIST = ["list", "--records", "suite.toml"]
ROCK = ["rock", "--size", "1", "--alpha", "10"]
PULSE = ["--pulse", "cosine", "--amplitude", "0.5", "--pulse-period", "1"]
SPEC = ["spectrum", *PULSE]
RESP = ["spectrum", "--kind", "response", *PULSE]
FEMA = ["design-spectrum", "fema356", "--sxs", "1", "--sx1", "0.5"]
UBC = ["design-spectrum", "ubc97"]
RUN = ["run", "all"]

CASES = [
    # ---------------------------------------------------------------- usage errors (argparse)
    ("no-command", {}, [], ["COMMAND"]),
    ("unknown-command", {}, ["audit-everything"], ["audit-everything"]),
    ("unknown-global-flag", {}, ["--verbose", "list"], ["--verbose"]),
    ("run-no-procedure", {}, ["run"], ["procedure"]),
    ("run-unknown-flag", {}, [*RUN, "--sizez", "1"], ["--sizez"]),
    ("run-agree-band-above-1", {}, [*RUN, "--agree-band", "2"], ["--agree-band"]),
    ("run-robustness-negative", {}, [*RUN, "--robustness", "-0.1"], ["--robustness"]),
    ("run-ntc-site-two-fields", {}, [*RUN, "--ntc-site", "0.25,2.4"], ["--ntc-site"]),
    ("run-ntc-site-topography", {}, [*RUN, "--ntc-site", "0.25,2.4,0.3,B,T9"],
     ["--ntc-site", "topography"]),
    ("run-ntc-site-soil", {}, [*RUN, "--ntc-site", "0.25,2.4,0.3,Z,T1"], ["--ntc-site", "soil"]),
    ("run-ntc-site-negative-f0", {}, [*RUN, "--ntc-site", "0.25,-2.4,0.3,B,T1"],
     ["--ntc-site", "F0"]),
    ("run-site-one-value", {}, [*RUN, "--site", "1.5"], ["--site"]),
    ("run-scale-without-site", {}, [*RUN, "--scale-to-site"], ["--scale-to-site"]),
    ("run-scheduler-unknown", {}, [*RUN, "--scheduler", "yarn"], ["--scheduler"]),
    ("rock-no-alpha", {}, ["rock", "--size", "1", *PULSE], ["--alpha"]),
    ("spectrum-bad-kind", {}, ["spectrum", "--kind", "fourier"], ["--kind"]),
    ("pulse-bad-shape", {}, [*ROCK, "--pulse", "square"], ["--pulse"]),
    ("design-bad-code", {}, ["design-spectrum", "ec8"], ["code"]),
    ("option-missing-value", {}, [*RUN, "--size"], ["--size"]),
    ("report-no-dir", {}, ["report"], ["RESULTS_DIR"]),
    # ---------------------------------------------------------------- --jobs
    ("jobs-zero", {}, [*RUN, "--jobs", "0"], ["--jobs"]),
    ("jobs-negative", {}, [*SPEC, "--jobs", "-3"], ["--jobs"]),
    ("jobs-text", {}, [*RUN, "--jobs", "many"], ["--jobs"]),
    ("jobs-fraction", {}, [*SPEC, "--jobs", "1.5"], ["--jobs"]),
    # ---------------------------------------------------------------- --size / --periods grids
    ("sizes-inf-stop", {}, [*RUN, "--size", "0.5:inf:0.1"], ["--size"]),
    ("sizes-nan-step", {}, [*RUN, "--size", "0.5:8:nan"], ["--size"]),
    ("sizes-huge-grid", {}, [*RUN, "--size", "0.5:1e12:1"], ["--size"]),
    ("sizes-zero-start", {}, [*RUN, "--size", "0:8:0.1"], ["--size"]),
    ("sizes-negative-start", {}, [*RUN, "--size", "-1:8:0.1"], ["--size"]),
    ("sizes-reversed", {}, [*RUN, "--size", "8:0.5:0.1"], ["--size"]),
    ("sizes-zero-step", {}, [*RUN, "--size", "0.5:8:0"], ["--size"]),
    ("sizes-negative-step", {}, [*RUN, "--size", "0.5:8:-0.1"], ["--size"]),
    ("sizes-words", {}, [*RUN, "--size", "small:large:some"], ["--size"]),
    ("sizes-two-parts", {}, [*RUN, "--size", "0.5:8"], ["--size"]),
    ("sizes-four-parts", {}, [*RUN, "--size", "0.5:8:0.1:2"], ["--size"]),
    ("sizes-empty", {}, [*RUN, "--size", ""], ["--size"]),
    ("sizes-commas-only", {}, [*SPEC, "--size", ",,"], ["--size"]),
    ("sizes-list-negative", {}, [*SPEC, "--size", "1,-2"], ["--size"]),
    ("sizes-list-zero", {}, [*SPEC, "--size", "0,1"], ["--size"]),
    ("sizes-list-nan", {}, [*SPEC, "--size", "1,nan"], ["--size"]),
    ("sizes-runaway-cost", {}, [*RUN, "--size", "0.5:8:0.00001"],
     ["work", "--size, 750,001 values (151 by default)", "--force"]),
    ("periods-zero-step", {}, [*RESP, "--periods", "0:10:0"], ["--periods"]),
    ("periods-negative", {}, [*RESP, "--periods", "-1:10:1"], ["--periods"]),
    ("periods-inf", {}, [*RESP, "--periods", "0:inf:1"], ["--periods"]),
    ("periods-huge-grid", {}, [*UBC, "--periods", "0:1e9:1"], ["--periods"]),
    ("periods-list-negative", {}, [*UBC, "--periods", "0.1,-0.2"], ["--periods"]),
    ("periods-text", {}, [*FEMA, "--periods", "short"], ["--periods"]),
    ("response-runaway-cost", {}, [*RESP, "--periods", "0.001:100:0.0001", "--damping",
                                   "1,2,3,4,5,6,7,8,9,10"], ["work", "--periods", "--force"]),
    # ---------------------------------------------------------------- cost named by its cause
    ("rock-duration-runaway-cost", {}, [*ROCK, *PULSE, "--free-motion", "1e9"],
     ["--free-motion 1e+09 s", "--force"]),
    ("spectrum-free-motion-runaway-cost", {}, [*SPEC, "--free-motion", "1e9"],
     ["--free-motion 1e+09 s", "--force"]),
    ("response-free-motion-runaway-cost", {}, [*RESP, "--free-motion", "1e9"],
     ["--free-motion 1e+09 s", "--force"]),
    ("margins-stripes-runaway-cost", {}, ["margins", "all", "--records", "pulses", "--stripes",
                                          ",".join(f"{0.01 * i:g}" for i in range(1, 5000))],
     ["--stripes, 4,999 values (27 by default)", "--force"]),
    # ---------------------------------------------------------------- --alpha
    ("alpha-zero", {}, [*RUN, "--alpha", "0"], ["--alpha"]),
    ("alpha-45", {}, [*SPEC, "--alpha", "45"], ["--alpha"]),
    ("alpha-negative", {}, [*RUN, "--alpha", "10,-5"], ["--alpha"]),
    ("alpha-radians-typed", {}, [*SPEC, "--alpha", "0.2,90"], ["--alpha"]),
    ("alpha-nan", {}, [*RUN, "--alpha", "nan"], ["--alpha"]),
    ("alpha-text", {}, [*RUN, "--alpha", "ten"], ["--alpha"]),
    ("alpha-empty", {}, [*RUN, "--alpha", ""], ["--alpha"]),
    ("rock-alpha-zero", {}, ["rock", "--size", "1", "--alpha", "0", *PULSE], ["--alpha"]),
    ("rock-alpha-90", {}, ["rock", "--size", "1", "--alpha", "90", *PULSE], ["--alpha"]),
    ("rock-alpha-inf", {}, ["rock", "--size", "1", "--alpha", "inf", *PULSE], ["--alpha"]),
    # ---------------------------------------------------------------- --damping
    ("damping-negative-design", {}, [*UBC, "--damping", "-5"], ["--damping"]),
    ("damping-negative-response", {}, [*RESP, "--damping", "-5"], ["--damping"]),
    ("damping-100", {}, [*RESP, "--damping", "100"], ["--damping"]),
    ("damping-nan", {}, [*FEMA, "--damping", "nan"], ["--damping"]),
    ("damping-text", {}, [*FEMA, "--damping", "five"], ["--damping"]),
    ("damping-one-bad-of-three", {}, [*RESP, "--damping", "5,10,-15"], ["--damping"]),
    # ---------------------------------------------------------------- design-spectrum values
    ("sxs-negative", {}, ["design-spectrum", "fema356", "--sxs", "-1", "--sx1", "0.5"], ["--sxs"]),
    ("sxs-zero", {}, ["design-spectrum", "fema356", "--sxs", "0", "--sx1", "0.5"], ["--sxs"]),
    ("sxs-nan", {}, ["design-spectrum", "fema356", "--sxs", "nan", "--sx1", "0.5"], ["--sxs"]),
    ("sxs-inf", {}, ["design-spectrum", "fema356", "--sxs", "inf", "--sx1", "0.5"], ["--sxs"]),
    ("sxs-text", {}, ["design-spectrum", "fema356", "--sxs", "high", "--sx1", "0.5"], ["--sxs"]),
    ("sx1-negative", {}, ["design-spectrum", "fema356", "--sxs", "1", "--sx1", "-0.5"], ["--sx1"]),
    ("fema-missing-sx1", {}, ["design-spectrum", "fema356", "--sxs", "1"], ["--sx1"]),
    ("na-negative", {}, [*UBC, "--na", "-1"], ["--na"]),
    ("nv-zero", {}, [*UBC, "--nv", "0"], ["--nv"]),
    ("na-nan", {}, [*UBC, "--na", "nan"], ["--na"]),
    # ---------------------------------------------------------------- rock values
    ("rock-no-size", {}, ["rock", "--alpha", "10", *PULSE], ["--size"]),
    ("rock-p-and-size", {}, ["rock", "--p", "2", "--size", "1", "--alpha", "10", *PULSE], ["--p"]),
    ("rock-p-zero", {}, ["rock", "--p", "0", "--alpha", "10", *PULSE], ["--p"]),
    ("rock-p-negative", {}, ["rock", "--p", "-2", "--alpha", "10", *PULSE], ["--p"]),
    ("rock-p-nan", {}, ["rock", "--p", "nan", "--alpha", "10", *PULSE], ["--p"]),
    ("rock-size-inf", {}, ["rock", "--size", "inf", "--alpha", "10", *PULSE], ["--size"]),
    ("rock-size-text", {}, ["rock", "--size", "big", "--alpha", "10", *PULSE], ["--size"]),
    ("rock-r-negative", {}, [*ROCK, "--r", "-0.1", *PULSE], ["--r"]),
    ("rock-r-above-one", {}, [*ROCK, "--r", "1.5", *PULSE], ["--r"]),
    ("rock-r-nan", {}, [*ROCK, "--r", "nan", *PULSE], ["--r"]),
    ("rock-duration-negative", {}, [*ROCK, "--free-motion", "-1", *PULSE], ["--free-motion"]),
    ("rock-duration-inf", {}, [*ROCK, "--free-motion", "inf", *PULSE], ["--free-motion"]),
    ("rock-duration-nan", {}, [*ROCK, "--free-motion", "nan", *PULSE], ["--free-motion"]),
    ("free-motion-negative", {}, [*RUN, "--free-motion", "-10"], ["--free-motion"]),
    ("free-motion-text", {}, [*SPEC, "--free-motion", "long"], ["--free-motion"]),
    # ---------------------------------------------------------------- excitation
    ("no-excitation", {}, ROCK, ["--record"]),
    ("record-and-pulse", {}, [*ROCK, "--record", "x", *PULSE], ["--record"]),
    ("pulse-no-amplitude", {}, [*ROCK, "--pulse", "sine", "--pulse-period", "1"], ["--amplitude"]),
    ("pulse-no-period", {}, [*ROCK, "--pulse", "sine", "--amplitude", "1"], ["--pulse-period"]),
    ("amplitude-negative", {}, [*ROCK, "--pulse", "sine", "--amplitude", "-1",
                                "--pulse-period", "1"], ["--amplitude"]),
    ("amplitude-zero", {}, [*ROCK, "--pulse", "sine", "--amplitude", "0",
                            "--pulse-period", "1"], ["--amplitude"]),
    ("amplitude-nan", {}, [*SPEC[:3], "--amplitude", "nan", "--pulse-period", "1"],
     ["--amplitude"]),
    ("pulse-period-zero", {}, [*ROCK, "--pulse", "sine", "--amplitude", "1",
                               "--pulse-period", "0"], ["--pulse-period"]),
    ("pulse-period-inf", {}, [*ROCK, "--pulse", "sine", "--amplitude", "1",
                              "--pulse-period", "inf"], ["--pulse-period"]),
    ("record-unknown-id", {}, [*ROCK, "--record", "kobe_2099"], ["kobe_2099"]),
    ("record-file-absent", {}, [*ROCK, "--record", "gone.AT2"], ["--record", "gone.AT2"]),
    ("record-file-is-folder", {"rec.AT2/x": ""}, [*ROCK, "--records", "rec.AT2",
                                                   "--record", "x"], ["rec.AT2"]),
    # ---------------------------------------------------------------- outputs
    ("out-is-a-file", {"taken": "x"}, [*RUN, "--out", "taken"], ["--out", "taken"]),
    ("out-under-a-file", {"taken": "x"}, [*RUN, "--out", "taken/run1"], ["--out", "taken"]),
    ("csv-is-a-folder", {"dir/keep": ""}, [*SPEC, "--csv", "dir"], ["--csv", "dir"]),
    ("csv-trailing-slash", {}, [*SPEC, "--csv", "newdir/"], ["--csv", "newdir/"]),
    ("csv-under-a-file", {"taken": "x"}, [*UBC, "--csv", "taken/out.csv"], ["--csv", "taken"]),
    ("plot-is-a-folder", {"dir/keep": ""}, [*ROCK, *PULSE, "--plot", "dir"], ["--plot", "dir"]),
    ("plot-ok-csv-folder", {}, [*SPEC, "--plot", "out.png", "--csv", "csvdir/"], ["--csv"]),
    ("plot-under-a-file", {"taken": "x"}, [*RESP, "--plot", "taken/p.png"], ["--plot", "taken"]),
    ("design-csv-folder", {"dir/keep": ""}, [*FEMA, "--csv", "dir"], ["--csv", "dir"]),
    ("out-unwritable-fs", {}, [*RUN, "--out", "/proc/audit-out"], ["--out", "/proc"]),
    ("csv-unwritable-fs", {}, [*UBC, "--csv", "/proc/ubc.csv"], ["--csv", "/proc"]),
    ("plot-unwritable-fs", {}, [*ROCK, *PULSE, "--plot", "/sys/rock.png"], ["--plot", "/sys"]),
    # ---------------------------------------------------------------- procedures and report
    ("unknown-procedure", {}, ["run", "fema999"], ["fema999"]),
    ("report-absent", {}, ["report", "nowhere"], ["nowhere"]),
    ("report-a-file", {"results": "x"}, ["report", "results"], ["results"]),
    ("report-empty-folder", {"results/.keep": ""}, ["report", "results"], ["results"]),
    ("report-broken-json", {"results/results.csv": "record\n", "results/summary.json": "{",
                            **{f"results/{name}": "a\n" for name in (
                                "spectra.csv", "histories.csv", "rocking.csv",
                                "estimates-only.csv", "checks.csv", "suite.csv", "claims.csv",
                                "design-spectra.csv", "mechanics.csv")}},
     ["report", "results"], ["summary.json"]),
    # a results.csv of another program (or edited): its file named, not a KeyError
    ("report-results-wrong-columns", {
        "results/summary.json": "{}",
        "results/results.csv": "rec,proc,alpha\nx,fema356,10\n",
        **{f"results/{name}": ",".join(GUIDE[name]) + "\n" for name in (
            "spectra.csv", "histories.csv", "rocking.csv", "estimates-only.csv", "checks.csv",
            "suite.csv", "claims.csv", "design-spectra.csv", "mechanics.csv")}},
     ["report", "results"], ["results/results.csv", "columns missing: record, procedure"]),
    # ---------------------------------------------------------------- --records paths
    ("records-absent", {}, ["list", "--records", "nothing.toml"], ["nothing.toml"]),
    ("records-empty-folder", {"empty/.keep": ""}, ["list", "--records", "empty"], ["empty"]),
    ("records-folder-no-at2", {"recs/a.txt": GOOD_TXT}, ["list", "--records", "recs"], ["recs"]),
    ("records-folder-one-bad", {"recs/a.AT2": GOOD_AT2, "recs/b.AT2": "garbage\n",
                                "recs/c.AT2": ""}, ["list", "--records", "recs"],
     ["b.AT2", "1 other"]),
    ("run-suite-first-bad", {"recs/a.AT2": "", "recs/b.AT2": GOOD_AT2},
     [*RUN, "--records", "recs"], ["a.AT2"]),
    # ---------------------------------------------------------------- text records: time, dt, units
    ("records-time-column-uneven",
     {"t.txt": "".join(f"{0.01 * i + (0.003 if i == 7 else 0):.3f} {v:.5f}\n"
                       for i, v in enumerate(VALUES))},
     ["list", "--records", "t.txt", "--units", "g"], ["t.txt", "line 8", "time"]),
    ("records-time-column-backwards",
     {"t.txt": "".join(f"{0.01 * (i - 2 * (i == 7)):.2f} {v:.5f}\n"
                       for i, v in enumerate(VALUES))},
     ["list", "--records", "t.txt", "--units", "g"], ["t.txt", "line 8", "time"]),
    ("records-time-column-and-other-dt",
     {"t.txt": "".join(f"{0.01 * i:.2f} {v:.5f}\n" for i, v in enumerate(VALUES))},
     ["list", "--records", "t.txt", "--units", "g", "--dt", "0.02"], ["t.txt", "dt"]),
    ("records-one-column-no-dt", {"one.txt": "0.1\n0.2\n"}, ["list", "--records", "one.txt"],
     ["one.txt", "dt"]),
    ("records-one-column-no-units", {"one.txt": "0.1\n0.2\n"},
     ["list", "--records", "one.txt", "--dt", "0.01"], ["one.txt", "units"]),
    ("records-dt-negative", {"one.txt": "0.1\n0.2\n"},
     ["list", "--records", "one.txt", "--dt", "-0.01"], ["--dt"]),
    ("records-units-unknown", {"one.txt": "0.1\n0.2\n"},
     ["list", "--records", "one.txt", "--units", "gal"], ["--units"]),
    ("records-dt-for-a-suite", {}, ["list", "--records", "pulses", "--dt", "0.01"],
     ["dt", "pulses"]),
    ("records-dt-for-an-at2", {"a.AT2": GOOD_AT2}, ["list", "--records", "a.AT2", "--dt", "0.01"],
     ["dt", "a.AT2"]),
    ("records-suite-misspelt", {}, ["list", "--records", "p695-farfield"],
     ["p695-farfield", "did you mean 'p695-far-field'"]),
    # ---------------------------------------------------------------- manifests: file level
    ("manifest-empty", {"suite.toml": ""}, LIST, ["suite.toml", "[[record]]"]),
    ("manifest-not-toml", {"suite.toml": "[[record]\nid = 1"}, LIST, ["suite.toml", "TOML"]),
    ("manifest-utf16", {"suite.toml": manifest().encode("utf-16")}, LIST, ["suite.toml", "UTF-16"]),
    ("manifest-binary", {"suite.toml": bytes(range(256)) * 4}, LIST, ["suite.toml", "encoding"]),
    ("manifest-record-table", {"suite.toml": manifest().replace("[[record]]", "[record]")},
     LIST, ["suite.toml", "[[record]]"]),
    ("manifest-record-integer", {"suite.toml": "record = 5\n"}, LIST, ["suite.toml", "record"]),
    ("manifest-record-numbers", {"suite.toml": "record = [1, 2]\n"}, LIST, ["record 1"]),
    ("manifest-wrong-table-name", {"suite.toml": manifest().replace("record", "records")},
     LIST, ["suite.toml", "[[record]]"]),
    ("manifest-is-folder-named-toml", {"suite.toml/x": ""}, LIST, ["suite.toml"]),
    # ---------------------------------------------------------------- manifests: fields
    ("manifest-dt-string", with_manifest(manifest(dt='"0.01"')), LIST, ["'rec'", "dt"]),
    ("manifest-dt-array", with_manifest(manifest(dt="[0.01, 0.02]")), LIST, ["dt"]),
    ("manifest-dt-true", with_manifest(manifest(dt="true")), LIST, ["dt"]),
    ("manifest-dt-tiny", with_manifest(manifest(dt="1e-12")), LIST, ["dt"]),
    ("manifest-dt-zero", with_manifest(manifest(dt="0")), LIST, ["dt"]),
    ("manifest-dt-negative", with_manifest(manifest(dt="-0.01")), LIST, ["dt"]),
    ("manifest-dt-nan", with_manifest(manifest(dt="nan")), LIST, ["dt"]),
    ("manifest-dt-inf", with_manifest(manifest(dt="inf")), LIST, ["dt"]),
    ("manifest-dt-huge", with_manifest(manifest(dt="100")), LIST, ["dt"]),
    ("manifest-units-array", with_manifest(manifest(units='["g"]')), LIST, ["units"]),
    ("manifest-units-unknown", with_manifest(manifest(units='"ft/s2"')), LIST, ["units", "ft/s2"]),
    ("manifest-units-number", with_manifest(manifest(units="9.81")), LIST, ["units"]),
    ("manifest-file-integer", with_manifest(manifest(file="5")), LIST, ["file"]),
    ("manifest-file-empty", with_manifest(manifest(file='""')), LIST, ["file"]),
    ("manifest-file-absent", with_manifest(manifest(file='"gone.txt"')), LIST,
     ["file", "gone.txt"]),
    ("manifest-file-missing-key", with_manifest(manifest(file=None)), LIST, ["file"]),
    ("manifest-file-folder", with_manifest(manifest(file='"sub"'), **{"sub/x": ""}), LIST,
     ["file", "sub"]),
    ("manifest-format-unknown", with_manifest(manifest(format='"sac"')), LIST, ["format", "sac"]),
    ("manifest-format-missing", with_manifest(manifest(format=None)), LIST, ["format"]),
    ("manifest-format-number", with_manifest(manifest(format="2")), LIST, ["format"]),
    ("manifest-column-zero", with_manifest(manifest(column="0")), LIST, ["column"]),
    ("manifest-column-string", with_manifest(manifest(column='"1"')), LIST, ["column"]),
    ("manifest-column-float", with_manifest(manifest(column="1.5")), LIST, ["column"]),
    ("manifest-column-bool", with_manifest(manifest(column="true")), LIST, ["column"]),
    ("manifest-column-beyond", with_manifest(manifest(column="7")), LIST, ["column 7"]),
    ("manifest-sxs-text", with_manifest(manifest(sxs_g='"x"')), LIST, ["sxs_g"]),
    ("manifest-sxs-negative", with_manifest(manifest(sxs_g="-1.0")), LIST, ["sxs_g"]),
    ("manifest-sxs-nan", with_manifest(manifest(sxs_g="nan")), LIST, ["sxs_g"]),
    ("manifest-sxs-zero", with_manifest(manifest(sxs_g="0")), LIST, ["sxs_g"]),
    ("manifest-sx1-bool", with_manifest(manifest(sx1_g="false")), LIST, ["sx1_g"]),
    ("manifest-missing-yes", with_manifest(manifest(missing='"yes"')), LIST, ["missing"]),
    ("manifest-missing-one", with_manifest(manifest(missing="1")), LIST, ["missing"]),
    ("manifest-id-absent", with_manifest(manifest(id=None)), LIST, ["record 1", "id"]),
    ("manifest-id-number", with_manifest(manifest(id="5")), LIST, ["id"]),
    ("manifest-id-empty", with_manifest(manifest(id='""')), LIST, ["id"]),
    ("manifest-id-twice", with_manifest(manifest() + manifest()), LIST, ["'rec'", "twice"]),
    ("manifest-unknown-field", with_manifest(manifest(scale="2")), LIST, ["scale"]),
    ("manifest-component-number", with_manifest(manifest(component="90")), LIST, ["component"]),
    ("manifest-site-class-number", with_manifest(manifest(site_class="4")), LIST, ["site_class"]),
    ("manifest-at2-with-dt", with_manifest(manifest(file='"a.AT2"', format='"peer-at2"',
                                                    column=None, units=None),
                                           **{"a.AT2": GOOD_AT2}), LIST, ["dt"]),
    ("manifest-units-g-for-cm", with_manifest(manifest(units='"g"'),
                                              **{"rec.txt": txt_text(values=VALUES * 300)}),
     LIST, ["units", "rec.txt"]),
    ("manifest-two-bad-records", with_manifest(manifest(dt='"x"') + manifest(id='"r2"', dt="-1")),
     LIST, ["'rec'", "1 other"]),
    # ---------------------------------------------------------------- AT2 files
    ("at2-empty", {"a.AT2": ""}, [*ROCK, "--record", "a.AT2"], ["a.AT2", "empty"]),
    ("at2-blank", {"a.AT2": "  \n\n \t\n"}, [*ROCK, "--record", "a.AT2"], ["a.AT2", "empty"]),
    ("at2-three-lines", {"a.AT2": "\n".join(GOOD_AT2.splitlines()[:3])},
     [*ROCK, "--record", "a.AT2"], ["a.AT2", "header"]),
    ("at2-no-units", {"a.AT2": at2_text(units="ACCELERATION TIME SERIES")},
     [*ROCK, "--record", "a.AT2"], ["a.AT2", "line 3"]),
    ("at2-no-npts-line", {"a.AT2": at2_text(header4="200 values follow")},
     [*ROCK, "--record", "a.AT2"], ["a.AT2", "line 4"]),
    ("at2-npts-too-many", {"a.AT2": at2_text(npts="201")}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2", "NPTS"]),
    ("at2-npts-too-few", {"a.AT2": at2_text(npts="20")}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2", "NPTS"]),
    ("at2-npts-absurd", {"a.AT2": at2_text(npts="9" * 30)}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2", "NPTS"]),
    ("at2-truncated", {"a.AT2": GOOD_AT2[: len(GOOD_AT2) // 2]}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2"]),
    ("at2-dt-zero", {"a.AT2": at2_text(dt="0.0")}, [*ROCK, "--record", "a.AT2"], ["a.AT2", "dt"]),
    ("at2-dt-tiny", {"a.AT2": at2_text(dt="1E-12")}, [*ROCK, "--record", "a.AT2"], ["a.AT2", "dt"]),
    ("at2-dt-negative", {"a.AT2": at2_text(dt="-.01")}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2", "dt"]),
    ("at2-dt-dot", {"a.AT2": at2_text(dt=".")}, [*ROCK, "--record", "a.AT2"], ["a.AT2", "DT"]),
    ("at2-dt-huge", {"a.AT2": at2_text(dt="1E+30")}, [*ROCK, "--record", "a.AT2"], ["a.AT2", "dt"]),
    ("at2-nan-value", {"a.AT2": at2_text(values=[*VALUES[:199], math.nan])},
     [*ROCK, "--record", "a.AT2"], ["a.AT2", "line"]),
    ("at2-inf-value", {"a.AT2": at2_text(values=[math.inf, *VALUES[1:]])},
     [*ROCK, "--record", "a.AT2"], ["a.AT2", "line 5"]),
    ("at2-overflow-value", {"a.AT2": GOOD_AT2.replace(GOOD_AT2.splitlines()[6], "1E400", 1)},
     [*ROCK, "--record", "a.AT2"], ["a.AT2", "line 7"]),
    ("at2-garbage-token", {"a.AT2": GOOD_AT2 + "oops\n"}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2", "oops"]),
    ("at2-huge-values", {"a.AT2": at2_text(values=VALUES * 1e6)}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2", "units"]),
    ("at2-one-sample", {"a.AT2": at2_text(npts="1", values=[0.1])}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2", "sample"]),
    ("at2-binary", {"a.AT2": bytes(range(256)) * 8}, [*ROCK, "--record", "a.AT2"], ["a.AT2"]),
    ("at2-utf16", {"a.AT2": GOOD_AT2.encode("utf-16")}, [*ROCK, "--record", "a.AT2"],
     ["a.AT2", "UTF-16"]),
    ("at2-in-folder-suite", {"recs/a.AT2": at2_text(npts="7")}, ["list", "--records", "recs"],
     ["a.AT2", "NPTS"]),
    # ---------------------------------------------------------------- text files
    ("txt-no-dt", {"r.txt": txt_text("% units: g")}, [*ROCK, "--record", "r.txt"], ["r.txt", "dt"]),
    ("txt-no-units", {"r.txt": txt_text("% dt = 0.01")}, [*ROCK, "--record", "r.txt"],
     ["r.txt", "units"]),
    ("txt-dt-zero", {"r.txt": txt_text("% in g, dt = 0")}, [*ROCK, "--record", "r.txt"],
     ["r.txt", "dt"]),
    ("txt-dt-tiny", {"r.txt": txt_text("% in g, dt = 1e-12")}, [*ROCK, "--record", "r.txt"],
     ["r.txt", "dt"]),
    ("txt-dt-dots", {"r.txt": txt_text("% in g, dt = ..")}, [*ROCK, "--record", "r.txt"],
     ["r.txt", "dt"]),
    ("txt-only-comments", {"r.txt": "% dt = 0.01 in g\n# nothing else\n"},
     [*ROCK, "--record", "r.txt"], ["r.txt", "data"]),
    ("txt-nan", {"r.txt": txt_text(values=[*VALUES[:50], math.nan, *VALUES[51:]])},
     [*ROCK, "--record", "r.txt"], ["r.txt", "line 52"]),
    ("txt-text-value", {"r.txt": GOOD_TXT + "end of record\n"}, [*ROCK, "--record", "r.txt"],
     ["r.txt", "end"]),
    ("txt-npts-mismatch", {"r.txt": txt_text("% in g, dt = 0.01, npts = 500")},
     [*ROCK, "--record", "r.txt"], ["r.txt", "npts"]),
    ("txt-one-sample", {"r.txt": "% in g, dt = 0.01\n0.1\n"}, [*ROCK, "--record", "r.txt"],
     ["r.txt", "sample"]),
    ("txt-ragged-column", with_manifest(manifest(column="2"),
                                        **{"rec.txt": GOOD_TXT + "0.1\n"}), LIST,
     ["rec.txt", "column 2"]),
    ("txt-empty", {"r.txt": ""}, [*ROCK, "--record", "r.txt"], ["r.txt", "empty"]),
    ("txt-binary-nul", {"r.txt": b"% in g, dt = 0.01\n0.1\x00\x00 0.2\n"},
     [*ROCK, "--record", "r.txt"], ["r.txt"]),
    # ---------------------------------------------------------------- symbolic links
    ("symlink-dangling-record", {"r.AT2": SymLink("gone.AT2")}, [*ROCK, "--record", "r.AT2"],
     ["r.AT2"]),
    ("symlink-loop-records", {"loop.toml": SymLink("loop.toml")}, ["list", "--records",
                                                                   "loop.toml"], ["loop.toml"]),
    ("symlink-out-to-file", {"taken": "x", "out": SymLink("taken")}, [*RUN, "--out", "out"],
     ["--out", "out"]),
    ("symlink-csv-to-folder", {"dir/keep": "", "out.csv": SymLink("dir")},
     [*UBC, "--csv", "out.csv"], ["--csv", "out.csv"]),
    ("symlink-manifest-file-dangling", with_manifest(manifest(file='"link.txt"'),
                                                     **{"link.txt": SymLink("nowhere.txt")}),
     LIST, ["file", "link.txt"]),
]


def _tree(folder: Path) -> set:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    """An empty working folder, with no record suite from the environment."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv(ENV_VARIABLE, raising=False)
    return tmp_path


def _write(folder: Path, files: dict):
    for name, content in files.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, SymLink):
            path.symlink_to(str(content))
        elif isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content)


def test_corpus_is_large_and_ids_unique():
    ids = [case[0] for case in CASES]
    assert len(ids) >= 120 and len(set(ids)) == len(ids)


@pytest.mark.parametrize("files, argv, words", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_input_gets_one_line_and_exit_2(workdir, capsys, files, argv, words):
    _write(workdir, files)
    before = _tree(workdir)
    status = main(argv)
    err = capsys.readouterr().err
    lines = err.splitlines()
    assert status == 2, err
    assert len(lines) == 1, err
    assert lines[0].startswith("error: ")
    assert "Traceback" not in err and "staging" not in err
    for word in words:
        assert word in lines[0], (word, lines[0])
    assert _tree(workdir) == before, "files were written"


# --- what is accepted, with a note or a warning -------------------------------------------------

def test_jobs_capped_at_cores_with_a_note(workdir, capsys):
    assert main([*SPEC, "--size", "1", "--alpha", "10", "--jobs", "1000"]) == 0
    err = capsys.readouterr().err.splitlines()
    cores = len(os.sched_getaffinity(0))
    assert err[0] == f"note: --jobs 1000: only {cores} core(s) available; using {cores}"


def test_small_pga_for_declared_units_warns_on_one_line(workdir, capsys):
    # a file in g declared as cm/s2: PGA 0.3 g read as 0.3 cm/s² ≈ 0.0003 g
    _write(workdir, with_manifest(manifest(units='"cm/s2"')))
    assert main(LIST) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("warning: ") and "units" in err[0]
    assert "rec.txt" in err[0] and "0.00031 g" in err[0]


def test_strict_suite_names_first_bad_and_counts_others(workdir):
    _write(workdir, {"recs/a.AT2": GOOD_AT2, "recs/b.AT2": "", "recs/c.AT2": at2_text(npts="3"),
                     "recs/d.AT2": at2_text(dt="0")})
    with pytest.raises(InputError, match=r"b\.AT2: file is empty \(2 other record\(s\) also bad"):
        load_records("recs")


def test_skip_bad_records_keeps_the_rest_and_lists_each(workdir):
    _write(workdir, {"recs/a.AT2": GOOD_AT2, "recs/b.AT2": "", "recs/c.AT2": at2_text(npts="3")})
    suite = load_records("recs", skip_bad=True)
    assert [e.id for e in suite] == ["a"]
    assert [r["record"] for r in suite.rejected] == ["b", "c"]
    assert suite.rejected[0]["file"].endswith("b.AT2")
    assert suite.rejected[0]["reason"] == "file is empty"
    assert "NPTS" in suite.rejected[1]["reason"]
    with pytest.raises(InputError, match="b.AT2"):  # nothing readable: still an error
        load_records("recs/b.AT2", skip_bad=True)


def test_the_api_skips_bad_records_for_every_command_warning_each(workdir, capsys):
    from audit.api import Records
    from audit.api.inputs import record_suite
    from audit.errors import InputWarning
    _write(workdir, {"recs/a.AT2": GOOD_AT2, "recs/b.AT2": "", "recs/c.AT2": at2_text(npts="3")})
    with pytest.warns(InputWarning) as caught:
        suite = record_suite(Records("recs", skip_bad_records=True))
    assert [e.id for e in suite] == ["a"]
    assert [str(w.message).split(" (")[0] for w in caught] == ["not audited: b", "not audited: c"]
    with pytest.raises(InputError, match="b.AT2"):  # without it, the first bad record stops
        record_suite("recs")
    # every command that reads records offers it
    for command in ("check", "run", "margins", "list", "rock", "spectrum", "floor-motion",
                    "fragility"):
        main([command, "--help"])
        assert "--skip-bad-records" in capsys.readouterr().out, command


def test_skip_bad_manifest_records(workdir):
    _write(workdir, with_manifest(manifest() + manifest(id='"r2"', file='"gone.txt"')))
    suite = load_records("suite.toml", skip_bad=True)
    assert [e.id for e in suite] == ["rec"]
    # paths are absolute, so summary.json names the file wherever the report is read
    assert suite.rejected == ({"record": "r2", "file": str(Path("gone.txt").absolute()),
                               "reason": suite.rejected[0]["reason"]},)
    assert "gone.txt" in suite.rejected[0]["reason"]


def test_cost_guard_warns_between_the_limits(capsys):
    from records import one_pulse
    motion = one_pulse("cosine", 1.0, 1.0)  # 2001 samples
    # blocks chosen so that the estimate lies between the warning and the refusal
    blocks = int(3 * guards.WARN_SECONDS * guards.ROCKING_SAMPLES_PER_S / 2001)
    cost = guards.estimate([motion], 0.0, blocks=blocks)
    assert guards.WARN_SECONDS < cost.seconds < guards.REFUSE_SECONDS
    guards.check(cost, force=False)
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("warning: ") and "3 min" in err[0]
    big = guards.estimate([motion], 0.0, blocks=blocks * 100)
    with pytest.raises(InputError, match="force=True"):
        guards.check(big, force=False)
    guards.check(big, force=True)  # force lifts the refusal, the warning stays
    assert "warning" in capsys.readouterr().err


def test_long_history_is_decimated_with_exact_peaks(monkeypatch):
    from audit.physics.block import RigidBlock
    from audit.physics.rocking import history
    from records import one_pulse
    block = RigidBlock.from_size(1.0, math.radians(10))
    motion = one_pulse("cosine", 0.5, 0.5)
    full = history.simulate(block, motion, free_motion_s=5.0)
    monkeypatch.setattr(history, "HISTORY_CAPACITY", 1000)
    small = history.simulate(block, motion, free_motion_s=5.0)
    stride = -(-full.theta.size // 1000)
    assert small.theta.size <= 1000 and stride > 1
    np.testing.assert_array_equal(small.theta, full.theta[::stride])
    np.testing.assert_allclose(small.time, full.time[::stride], rtol=1e-12)
    np.testing.assert_array_equal(small.impact_times, full.impact_times)
    assert small.peak_rotation == full.peak_rotation
    assert small.peak_angular_velocity == full.peak_angular_velocity


@pytest.mark.slow  # ~20 s: writes and reads a five-million-sample record
def test_five_million_sample_record_refused_before_work(workdir, capsys):
    # 5,000,000 samples at 0.01 s: the record of issue 14 that took 347 s
    (workdir / "long.txt").write_text("% in g, dt = 0.01\n" + "0.01\n-0.02\n0.03\n-0.01\n"
                                      * 1_250_000)
    assert main([*RUN, "--records", "long.txt", "--out", "out"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and "5,001,000 samples" in err[0] and "--force" in err[0]
    assert not (workdir / "out").exists()


# --- outputs: checked first, written together, staging cleaned ----------------------------------

def test_plot_not_left_when_the_csv_cannot_be_written(workdir, capsys):
    _write(workdir, {"taken": "x"})
    assert main([*SPEC, "--size", "1", "--alpha", "10", "--plot", "out.png",
                 "--csv", "taken/out.csv"]) == 2
    assert not (workdir / "out.png").exists()
    assert main([*SPEC, "--size", "1", "--alpha", "10", "--plot", "out.png",
                 "--csv", "new/out.csv"]) == 0
    assert (workdir / "out.png").read_bytes()[:4] == b"\x89PNG"
    assert (workdir / "new" / "out.csv").is_file()
    assert [p.name for p in workdir.rglob(".*")] == []


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_read_only_out_refused_before_work(workdir, capsys):
    (workdir / "locked").mkdir(mode=0o555)
    assert main([*RUN, "--out", "locked/run"]) == 2
    assert "--out: locked/run: folder locked is not writable" in capsys.readouterr().err


def test_non_empty_out_previous_files_replaced_others_kept(workdir):
    out = workdir / "out"
    _write(workdir, {"out/results.csv": "old", "out/notes.txt": "mine"})
    write_files_atomically(out, {"results.csv": b"new", "summary.json": b"{}"})
    assert (out / "results.csv").read_text() == "new"
    assert (out / "notes.txt").read_text() == "mine"
    assert (out / "summary.json").read_text() == "{}"


def test_atomic_files_get_the_permissions_of_any_new_file(workdir):
    # mkstemp makes its files 0600: a report written through it could not be shared
    from audit.files import write_file_atomically
    write_file_atomically(workdir / "atomic.html", b"x")
    with open(workdir / "plain.html", "wb") as file:
        file.write(b"x")
    assert (workdir / "atomic.html").stat().st_mode == (workdir / "plain.html").stat().st_mode


def test_stale_staging_folders_of_killed_runs_are_cleaned(workdir):
    dead_pid = 2 ** 22 + 12345  # above the kernel's pid_max: never alive
    stale = workdir / f".out-staging-{dead_pid}-abc123"
    alive = workdir / f".out-staging-{os.getpid()}-def456"
    other = workdir / ".other-staging-1-x"
    for folder in (stale, alive, other):
        folder.mkdir()
        (folder / "results.csv").write_text("partial")
        os.utime(folder, (time.time() - 3600, time.time() - 3600))
    write_files_atomically(workdir / "out", {"results.csv": b"new"})
    assert not stale.exists() and alive.exists() and other.exists()
    assert sorted(p.name for p in workdir.iterdir()) == sorted(
        ["out", alive.name, other.name])


# --- real processes: the entry point's exit codes and Ctrl-C ------------------------------------

def _cli(*args, cwd, env=None):
    environment = {k: v for k, v in os.environ.items() if k != ENV_VARIABLE}
    environment["PYTHONPATH"] = str(ROOT)
    environment.update(env or {})
    return subprocess.Popen([sys.executable, "-m", "audit", *args], cwd=cwd, env=environment,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


@pytest.mark.parametrize("argv, word", [
    (["run", "all", "--jobs", "-1"], "--jobs"),
    (["design-spectrum", "ubc97", "--damping", "-5"], "--damping"),
    (["frobnicate"], "frobnicate"),
])
def test_entry_point_one_line_exit_2(tmp_path, argv, word):
    process = _cli(*argv, cwd=tmp_path)
    out, err = process.communicate(timeout=60)
    assert process.returncode == 2 and len(err.splitlines()) == 1 and word in err
    assert list(tmp_path.iterdir()) == []


#: Runs the CLI with a Ctrl-C sent from inside numba's object-cache hook, a ctypes callback
#: that llvmlite calls while numba compiles the solver or loads it from its cache: the window
#: in which a Ctrl-C was once lost ("Exception ignored …", then exit 0).
CTRL_C_IN_NUMBA_CALLBACK = """
import os, signal, sys
from numba.core import codegen
hook = codegen.CPUCodeLibrary._object_getbuffer_hook.__func__
def interrupting(cls, ll_module):
    if not os.environ.get("INTERRUPTED"):
        os.environ["INTERRUPTED"] = "1"
        print("sending SIGINT inside the callback", file=sys.stderr)
        os.kill(os.getpid(), signal.SIGINT)
    return hook(cls, ll_module)
codegen.CPUCodeLibrary._object_getbuffer_hook = classmethod(interrupting)
from audit.cli import main
code = main(sys.argv[1:])
sys.stderr.flush()
os._exit(code)
"""


def test_ctrl_c_inside_a_numba_callback_stops_the_command(tmp_path):
    environment = {k: v for k, v in os.environ.items() if k not in (ENV_VARIABLE, "INTERRUPTED")}
    environment["PYTHONPATH"] = str(ROOT)
    process = subprocess.run(
        [sys.executable, "-c", CTRL_C_IN_NUMBA_CALLBACK, "margins", "fema356", "--records",
         "pulses", "--size", "1:2:0.5", "--alpha", "10", "--out", "out"],
        cwd=tmp_path, env=environment, capture_output=True, text=True, timeout=600)
    lines = [line for line in process.stderr.splitlines() if not line.startswith("[")]
    assert lines == ["sending SIGINT inside the callback", "interrupted; nothing written"], \
        process.stderr
    assert process.returncode == EXIT_INTERRUPTED
    assert list(tmp_path.iterdir()) == []


def test_ctrl_c_stops_with_one_line_exit_130_and_nothing_written(tmp_path):
    # the pulse suite over a fine grid: long enough to be interrupted while computing
    process = _cli("run", "all", "--size", "0.2:8:0.002", "--alpha", "5,10,15,20,25",
                   "--free-motion", "60", "--out", "out", "--force", cwd=tmp_path)
    time.sleep(4.0)
    assert process.poll() is None, process.communicate()
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=60)
    # the one line of the interruption; warnings and progress lines ("[  1.0 s] ...") aside
    lines = [line for line in err.splitlines() if not line.startswith(("warning:", "["))]
    assert process.returncode == EXIT_INTERRUPTED, err
    assert len(lines) == 1, err
    # no output file; only records finished before the interruption, kept for --resume
    kept = sorted((tmp_path / "out" / ".partial").glob("*"))
    if kept:
        assert sorted(p.name for p in tmp_path.rglob("*") if p.is_file()) == [p.name for p in kept]
        assert lines[0] == (f"interrupted; {len(kept)} record(s) kept in out/.partial: the same "
                            "command with --resume completes the run"), err
    else:
        assert lines == ["interrupted; nothing written"], err
        assert list(tmp_path.iterdir()) == []
