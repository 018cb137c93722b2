"""Defaults of the exact solver (light: no imports, so the command line can show them)."""

#: Free motion simulated after the excitation ends [s].
DEFAULT_FREE_MOTION_S = 10.0
#: Runge–Kutta steps per radian of p·t: h ≤ 1/(steps_per_radian·p).
DEFAULT_STEPS_PER_RADIAN = 40.0
#: A rebound that would lift the block by less than this fraction of α counts as rest.
DEFAULT_REST_TOLERANCE = 1e-6
