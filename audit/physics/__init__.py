"""The mechanics: rigid block, exact rocking solver, linear oscillator, damping laws, design spectra.

Pure functions and small data classes over numpy arrays, SI units throughout; no file I/O and no
knowledge of procedures or reports.
"""
