"""One block and one ground motion: :func:`rock` and its :class:`RockingResponse`; the block
is the audit's one :class:`~audit.engine.shared.blocks.Block`."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

from audit import G
from audit.api.result_shape import Files
from audit.engine.shared import fields as check
from audit.engine.shared.blocks import Block, within_limits
from audit.errors import InputError
from audit.physics.block import Restitution

if TYPE_CHECKING:  # the solver (numba) is loaded by rock, not by the front door
    from audit.engine.shared.runtime import Runtime
    from audit.engine.shared.solver import Solver
    from audit.physics.building.floor import Floor
    from audit.physics.rocking import RockingHistory


class RockingResponse(Files):
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
        from audit.engine.shared.floors import floor_document
        from audit.engine.shared.ground_truth import slides
        from audit.physics.building.floor import Floor
        self.block, self.motion, self.solution = block, motion, response
        #: Where the block stands (:func:`audit.engine.shared.floors.floor_document`).
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

    PAGE = "rocking.html"

    @property
    def table(self):
        """:attr:`history`, the response at every solver output point (a DataFrame)."""
        return self.history

    @property
    def summary(self) -> dict:
        """:meth:`as_dict`: the response's numbers, JSON-ready."""
        return self.as_dict()

    def summary_text(self, show_dimensions: bool = False) -> str:
        """What ``audit rock`` prints: the block, the excitation, and the response's numbers
        (peaks, impacts, cycles, the friction it needs); with ``show_dimensions`` the block is
        named by its full width × height [m] too."""
        from audit.engine.shared.rock_words import rocking_text
        block_m = f"{self.block.width_m:g}x{self.block.height_m:g}" if show_dimensions else None
        return rocking_text(self.solution, self.motion, self.block.alpha_deg, block_m,
                            self.friction, self.slides)

    def files(self) -> dict[str, bytes]:
        """``rocking.json`` (:attr:`summary`), ``history.csv``, ``rocking.png`` (:meth:`plot`)
        and ``rocking.html``, the text and the figure on one page."""
        import base64
        import html
        import json

        from reports.figures import png_bytes
        png = png_bytes(self.plot(height_in=3.9))
        page = (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Rocking response"
                f"</title></head><body><pre>{html.escape(self.summary_text())}</pre><img "
                f"alt='θ/α and θ′ against time' src='data:image/png;base64,"
                f"{base64.b64encode(png).decode()}'></body></html>\n")
        return {"rocking.json": (json.dumps(self.summary) + "\n").encode(),
                "history.csv": self.history_csv(), "rocking.png": png,
                self.PAGE: page.encode()}

    def _repr_html_(self) -> str:
        import html
        return f"<pre>{html.escape(self.summary_text())}</pre>"

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


def rock(block: Block, motion, *, records=None, solver: Solver | None = None,
         friction: float | None = None, floor: Floor | None = None,
         runtime: Runtime | None = None) -> RockingResponse:
    """Exact rocking response of ``block`` to ``motion`` (Eq. 4.3, impacts by Eq. 4.8).

    Parameters
    ----------
    block : Block or str
        The block, or its full width and height typed ``WIDTHxHEIGHT`` [m] (``"0.8x2.0"``);
        within the limits every command applies (:func:`audit.engine.shared.blocks.within_limits`).
    motion : str, path, records.GroundMotion, records.RecordEntry or (array, float)
        A record id (of ``records``), a record file, a motion, or ``(acceleration [m/s²],
        dt [s])``.
    records : Records, str, path or records.RecordSuite, optional
        Where a record id is looked up (default: the default suite) and how a record is read
        (:class:`~audit.engine.shared.record_request.Records`: the time step [s] and units of
        a text record file that states none, the unreadable records left out).
    solver : Solver, optional
        The solver's model: ``free_motion_s`` simulated after the excitation ends [s];
        ``restitution``, the impact model instead of the block's r (``housner``, Eq. 4.8, the
        default, keeps the block's; a fixed r; ``xFACTOR`` times Eq. 4.8); ``vertical``, the
        motion's vertical component in the equation (gravity g + üv). The block's ``g`` is the
        one used (``solver.g`` is refused).
    friction : float, optional
        Friction coefficient μ of the base [-]: whether the block slides (``.slides``).
    floor : Floor, optional
        Where the object stands (default the ground): on a floor of a building
        (``Floor(z_over_h, Building(period_s, model, damping))``) it rocks on the floor's
        motion (:mod:`audit.physics.building.floor_motion`).
    runtime : Runtime, optional
        ``force``: start even when the estimated work is beyond the limits
        (:mod:`audit.engine.shared.guards`).
    """
    from audit.api.inputs import floor_group, on_floor_of, runtime_of, solver_of
    from audit.engine.shared import guards
    from audit.physics.rocking import simulate
    if isinstance(block, str):
        block = Block.parse(block)
    if not isinstance(block, Block):
        raise InputError(f"block: expected a Block (audit.Block(alpha_deg=…, size_s=…) or "
                         f"Block.from_dimensions) or 'WIDTHxHEIGHT', got {block!r}", "block")
    block = within_limits(block, "block", "block")
    solver = solver_of(solver, "rock", ("restitution", "free_motion_s", "vertical"))
    force = runtime_of(runtime, "rock", ("force",)).force
    motion, floor_document = on_floor_of(motion, floor_group(floor), records)
    if friction is not None:
        friction = check.number("friction", friction, "a positive friction coefficient μ", 0,
                                low_open=True)
    if solver.vertical and motion.vertical is None:
        raise InputError(f"solver.vertical: {motion.id} has no vertical component (give it in "
                         "the manifest as vertical_file, or a PEER UP/DWN file beside the "
                         "record)", "solver.vertical")
    solved, label = block, str(Restitution()) if block.r is None else f"{block.r:g}"
    if solver.restitution != Restitution():
        # the block with the model's r, at α = radians(alpha_deg) as its solver's block has it
        solved = replace(block, r=float(solver.restitution.r(math.radians(block.alpha_deg))))
        label = str(solver.restitution)
    guards.check(guards.estimate([motion], solver.free_motion_s, blocks=1), force)
    return RockingResponse(block, motion, simulate(solved.rigid, motion, solver.free_motion_s,
                                                   vertical=solver.vertical),
                           friction, label, floor_document)


__all__ = ["Block", "RockingResponse", "rock"]
