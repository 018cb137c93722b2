"""One block and one ground motion: :class:`Block`, :func:`rock` and its
:class:`RockingResponse`."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from audit import G
from audit.engine import fields as check
from audit.engine.defaults import DEFAULT_FREE_MOTION_S
from audit.errors import InputError, InputWarning
from audit.physics.block import Restitution, RigidBlock
from audit.physics.building.floor import DEFAULT_BUILDING_DAMPING
from audit.physics.rocking import RockingHistory
from audit.physics.rocking import simulate

#: Above this full height or width [m] a "block" is refused: no free-standing object is that
#: large, and the likeliest cause is a dimension typed in millimetres.
REFUSED_DIMENSION_M = 100.0
#: Above this full height [m] a block is accepted with a warning (a tall tank, a monument).
WARNED_DIMENSION_M = 10.0


@dataclass(frozen=True, kw_only=True)
class Block:
    """A free-standing rectangular block, by its slenderness and size (keyword arguments only:
    ``Block(alpha_deg=15, size_s=2.0)``; by its dimensions, :meth:`from_dimensions`).

    Parameters
    ----------
    alpha_deg : float
        Slenderness α = atan(b/h) [degrees], 0 < α < 45.
    size_s : float
        Size 2π/p [s], p = √(3g/(4R)) the frequency parameter (Eq. 4.2), R the half-diagonal.
    r : float, optional
        Coefficient of restitution (ratio of kinetic energies after/before an impact) [-];
        Eq. 4.8 of Makris & Konstantinidis (2001), r = (1 − 1.5 sin²α)², when not given.
    g : float
        Acceleration of gravity [m/s²].
    """

    alpha_deg: float
    size_s: float
    r: float | None = None
    g: float = G

    def __post_init__(self):
        check.number("alpha_deg", self.alpha_deg, "a slenderness between 0 and 45 degrees", 0,
                     45, low_open=True, high_open=True)
        check.number("size_s", self.size_s, "a positive size 2π/p in s", 0, low_open=True)
        _check_r_g(self.r, self.g)

    @classmethod
    def from_dimensions(cls, width_m: float, height_m: float, r: float | None = None,
                        g: float = G) -> Block:
        """The block of full width 2b and full height 2h [m]: α = atan(b/h), R = √(b² + h²).

        A dimension above :data:`REFUSED_DIMENSION_M` (100 m) is refused (millimetres typed
        as metres), a height above :data:`WARNED_DIMENSION_M` (10 m) warned about.
        """
        _check_r_g(r, g)
        for name, value in (("width_m", width_m), ("height_m", height_m)):
            check.number(name, value, "a positive number of metres", 0, low_open=True)
            if value > REFUSED_DIMENSION_M:
                raise InputError(f"{name}: {value:g} m is beyond any free-standing block "
                                 f"(the limit is {REFUSED_DIMENSION_M:g} m); dimensions are in "
                                 "metres, not millimetres", name)
        if width_m >= height_m:
            raise InputError(f"width_m, height_m: a rocking block is taller than it is wide "
                             f"(α < 45°), got width {width_m:g} m ≥ height {height_m:g} m",
                             "width_m", "height_m")
        if height_m > WARNED_DIMENSION_M:
            warnings.warn(f"height_m: {height_m:g} m is taller than most free-standing blocks "
                          f"(above {WARNED_DIMENSION_M:g} m); dimensions are in metres",
                          InputWarning, stacklevel=2)
        rigid = RigidBlock.from_dimensions(width_m / 2.0, height_m / 2.0, r, g)
        return cls(alpha_deg=math.degrees(rigid.alpha), size_s=rigid.size_s, r=r, g=g)

    @classmethod
    def parse(cls, text: str, r: float | None = None, g: float = G) -> Block:
        """The block typed as ``WIDTHxHEIGHT`` [m] (full width × full height), e.g. ``0.8x2.0``."""
        from audit.engine.blocks import parse_blocks
        blocks = parse_blocks([text], "block", g)
        if len(blocks) != 1:
            raise InputError(f"block: expected one block WIDTHxHEIGHT, got {text!r}", "block")
        return cls.from_dimensions(blocks[0].width_m, blocks[0].height_m, r, g)

    @property
    def rigid(self) -> RigidBlock:
        """The solver's block (p [rad/s], α [rad], r, g)."""
        return RigidBlock.from_size(self.size_s, math.radians(self.alpha_deg), self.r, self.g)

    @property
    def p_rad_s(self) -> float:
        """Frequency parameter p = 2π/size [rad/s]."""
        return 2.0 * math.pi / self.size_s

    @property
    def radius_m(self) -> float:
        """Half-diagonal R = 3g/(4p²) [m]."""
        return self.rigid.radius

    @property
    def width_m(self) -> float:
        """Full width 2b = 2R sin α [m]."""
        return 2.0 * self.rigid.half_width

    @property
    def height_m(self) -> float:
        """Full height 2h = 2R cos α [m]."""
        return 2.0 * self.rigid.half_height

    @property
    def restitution(self) -> float:
        """The coefficient of restitution r the solver uses [-]."""
        return self.rigid.r


def _check_r_g(r, g) -> None:
    if r is not None:
        check.number("r", r, "a coefficient of restitution in (0, 1]", 0, 1, low_open=True)
    check.number("g", g, "a positive acceleration in m/s²", 0, low_open=True)


class RockingResponse:
    """The exact response of one block to one ground motion (:func:`rock`).

    Attributes
    ----------
    block : Block
    motion : records.GroundMotion
    overturned : bool
    peak : float
        max |θ| [rad] (α when the block overturns).
    peak_ratio : float
        max |θ| / α [-].
    overturn_time_s : float or None
    impacts : int
    r : float
        The coefficient of restitution the solver used [-].
    friction : float or None
        The base's friction coefficient μ [-] checked, if any.
    slides : bool or None
        Whether the pure-rocking response needs more friction than μ (None without μ).
    solution : audit.physics.rocking.RockingHistory
        Everything the solver returned (cycles, turning points, reactions).
    """

    def __init__(self, block: Block, motion, response: RockingHistory, friction=None,
                 restitution: str = "", floor: dict | None = None):
        from audit.engine.floors import floor_document
        from audit.engine.ground_truth import slides
        from audit.physics.building.floor import Floor
        self.block, self.motion, self.solution = block, motion, response
        #: Where the block stands (:func:`audit.engine.floors.floor_document`).
        self.floor = floor or floor_document(Floor())
        self.overturned = bool(response.overturned)
        self.peak = float(response.peak_rotation)
        self.peak_ratio = float(response.peak_rotation_ratio)
        self.overturn_time_s = float(response.overturn_time) if response.overturned else None
        self.impacts = int(response.n_impacts)
        self.r = float(response.block.r)
        self.restitution = restitution or f"{self.r:g}"
        self.friction = friction
        self.slides = None if friction is None else bool(slides(response.required_friction,
                                                                friction))

    @property
    def history(self):
        """The response at every solver output point, a pandas DataFrame: ``time_s,
        theta_rad, theta_dot_rad_s, ground_acc_g``; an impact appears twice at its time (θ'
        before, then after); nothing after overturning."""
        import pandas as pd
        time, theta, omega = self.solution.history()
        return pd.DataFrame({"time_s": time, "theta_rad": theta, "theta_dot_rad_s": omega,
                             "ground_acc_g": self.motion.acceleration_at(time) / G})

    def history_csv(self) -> bytes:
        """:attr:`history` as CSV bytes (numbers ``%.10g``), written without pandas."""
        import io

        import numpy as np
        time, theta, omega = self.solution.history()
        table = np.column_stack((time, theta, omega, self.motion.acceleration_at(time) / G))
        text = io.StringIO()
        np.savetxt(text, table, fmt="%.10g", delimiter=",", comments="",
                   header="time_s,theta_rad,theta_dot_rad_s,ground_acc_g")
        return text.getvalue().encode()

    def as_dict(self) -> dict:
        """The response's numbers, JSON-ready (None where a value does not exist)."""
        response, rigid = self.solution, self.solution.block
        required = response.required_friction
        free = response.peak_rotation_free_vibration
        return {
            "record": self.motion.id, "p": rigid.p, "size_s": rigid.size_s,
            "alpha_deg": self.block.alpha_deg, "r": rigid.r, "restitution": self.restitution,
            "R_m": rigid.radius,
            "overturned": response.overturned,
            "overturn_time": None if math.isnan(response.overturn_time)
            else response.overturn_time,
            "peak_rotation": response.peak_rotation,
            "peak_rotation_ratio": response.peak_rotation_ratio,
            "peak_rotation_after_excitation": response.peak_rotation_after_excitation,
            "peak_rotation_free_vibration": None if math.isnan(free) else free,
            "peak_angular_velocity": response.peak_angular_velocity,
            "impacts": response.n_impacts,
            "cycle_durations": response.cycle_durations.tolist(),
            "uplifted": response.uplifted,
            "required_friction": None if math.isinf(required) else required,
            "jumps": response.jumps, "friction": self.friction, "slides": self.slides,
            "floor": self.floor}

    def plot(self, height_in: float = 5.0):
        """θ/α and θ' against time, rocking cycles shaded: a matplotlib Figure."""
        from reports.figures import draw_time_histories, new_figure
        response = self.solution
        fig = new_figure(10.0, height_in)
        draw_time_histories(fig, [{
            "time": response.time, "theta_ratio": response.theta / response.block.alpha,
            "omega": response.omega,
            "title": (f"{getattr(self.motion, 'id', 'motion')}: 2π/p = {self.block.size_s:.3g} s, "
                      f"α = {self.block.alpha_deg:g}°"),
            "rocking_span": ((response.impact_times[0], response.impact_times[-1])
                             if response.n_impacts else None),
            "cycle_starts": response.cycle_starts, "cycle_durations": response.cycle_durations,
            "excitation_end": response.excitation_end}])
        return fig

    def __repr__(self) -> str:
        what = (f"overturns at t = {self.overturn_time_s:.3f} s" if self.overturned
                else f"peak θ/α = {self.peak_ratio:.4f}")
        return (f"RockingResponse(α = {self.block.alpha_deg:g}°, 2π/p = {self.block.size_s:g} s: "
                f"{what}, {self.impacts} impact{'' if self.impacts == 1 else 's'})")


def rock(block: Block, motion, *, free_motion_s: float = DEFAULT_FREE_MOTION_S,
         restitution=None, vertical: bool = False, friction: float | None = None,
         records=None, force: bool = False, floor: float = 0.0, building: float | None = None, building_model: str | None = None,
         building_damping: float = DEFAULT_BUILDING_DAMPING) -> RockingResponse:
    """Exact rocking response of ``block`` to ``motion`` (Eq. 4.3, impacts by Eq. 4.8).

    Parameters
    ----------
    block : Block
    motion : str, path, records.GroundMotion, records.RecordEntry or (array, float)
        A record id (of ``records``), a record file, a motion, or ``(acceleration [m/s²],
        dt [s])``.
    free_motion_s : float
        Free motion simulated after the excitation ends [s].
    restitution : str or float, optional
        The impact model, instead of the block's r: ``housner`` (Eq. 4.8), a fixed r, or
        ``xFACTOR`` times Eq. 4.8.
    vertical : bool
        Include the motion's vertical component (gravity g + üv).
    friction : float, optional
        Friction coefficient μ of the base [-]: whether the block slides (``.slides``).
    records : str, path or records.RecordSuite, optional
        Where a record id is looked up (default: the default suite).
    force : bool
        Start even when the estimated work is beyond the limits (:mod:`audit.engine.guards`).
    floor, building, building_model, building_damping :
        Where the object stands: z/H (0, the default, is the ground), the building's T1 [s],
        ``shear:N`` or ``continuum:α0`` (default ``continuum:10``) and its damping ratio
        (default 0.05); the object rocks on the floor's motion
        (:mod:`audit.physics.building.floor_motion`).
    """
    from audit.api.inputs import on_floor_of
    from audit.engine import guards
    if not isinstance(block, Block):
        raise InputError(f"block: expected a Block (audit.Block(alpha_deg=…, size_s=…) or "
                         f"Block.from_dimensions), got {block!r}", "block")
    motion, floor_document = on_floor_of(motion, {
        "floor": floor, "building": building, "building_model": building_model,
        "building_damping": building_damping}, records)
    free_motion_s = check.number("free_motion_s", free_motion_s, "a duration ≥ 0 s", 0)
    if friction is not None:
        friction = check.number("friction", friction, "a positive friction coefficient μ", 0,
                                low_open=True)
    if check.flag("vertical", vertical) and motion.vertical is None:
        raise InputError(f"vertical: {motion.id} has no vertical component (give it in the "
                         "manifest as vertical_file, or a PEER UP/DWN file beside the record)",
                         "vertical")
    rigid = block.rigid
    label = str(Restitution()) if block.r is None else f"{block.r:g}"
    if restitution is not None:
        model = restitution if isinstance(restitution, Restitution) else Restitution.parse(
            restitution, "restitution")
        rigid, label = RigidBlock(rigid.p, rigid.alpha, model, rigid.g), str(model)
    guards.check(guards.estimate([motion], free_motion_s, blocks=1), check.flag("force", force))
    return RockingResponse(block, motion, simulate(rigid, motion, free_motion_s, vertical=vertical),
                           friction, label, floor_document)


__all__ = ["Block", "RockingResponse", "rock", "REFUSED_DIMENSION_M", "WARNED_DIMENSION_M"]
