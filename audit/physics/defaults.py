"""Defaults of the exact solver (light: no imports, so the command line can show them)."""

#: Free motion simulated after the excitation ends [s].
DEFAULT_FREE_MOTION_S = 10.0
#: Runge–Kutta steps per radian of p·t: h ≤ 1/(steps_per_radian·p).
DEFAULT_STEPS_PER_RADIAN = 40.0
#: Largest rebound, as a fraction of α, of a chatter that may end in rest (the chatter must also
#: converge before the ground could lift the block: audit.physics.rocking.chatter_time_bound).
DEFAULT_REST_TOLERANCE = 1e-6
