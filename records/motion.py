"""The ground-motion type every reader, pulse and manifest produces."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from audit import G
from audit.errors import InputError


def pulse_acceleration(shape: str, amplitude: float, period_s: float, t: np.ndarray) -> np.ndarray:
    """One-cycle pulse üg(t), zero outside 0 ≤ t ≤ T_p.

    Parameters
    ----------
    shape : {"cosine", "sine"}
        Type-B one-cosine pulse üg = a_p cos(2πt/T_p) or type-A one-sine pulse
        üg = a_p sin(2πt/T_p).
    amplitude : float
        a_p [m/s²].
    period_s : float
        T_p [s].
    t : numpy.ndarray
        Times [s].

    Returns
    -------
    numpy.ndarray
        üg [m/s²].
    """
    phase = 2.0 * np.pi * np.asarray(t, dtype=float) / period_s
    wave = np.cos(phase) if shape == "cosine" else np.sin(phase)
    inside = (np.asarray(t) >= 0.0) & (np.asarray(t) <= period_s)
    return np.where(inside, amplitude * wave, 0.0)


@dataclass(frozen=True)
class Pulse:
    """Analytic pulse parameters, kept so the solver can evaluate the pulse exactly.

    Attributes
    ----------
    shape : str
        ``"cosine"`` (type-B, üg = a_p cos(2πt/T_p)) or ``"sine"`` (type-A, üg = a_p sin(2πt/T_p)).
    amplitude : float
        a_p [m/s²].
    period_s : float
        T_p [s]; the pulse lasts one period and is zero after.
    """

    shape: str
    amplitude: float
    period_s: float


@dataclass(frozen=True)
class GroundMotion:
    """A horizontal ground acceleration history in SI units.

    Attributes
    ----------
    id : str
        Catalogue or manifest key.
    acceleration : numpy.ndarray
        üg at t = k·dt [m/s²], linear between samples.
    dt : float
        Sampling step [s].
    component : str
        What the file holds, in words.
    source : str
        Where it came from: a file path, or ``"analytic pulse"``.
    sha256 : str
        SHA-256 of the data file ("" for analytic motions).
    pulse : Pulse or None
        Set for analytic pulses, so the solver can use the closed form between samples.
    metadata : dict
        What the source says about the record (event, station, ...).
    vertical : numpy.ndarray or None
        The vertical ground acceleration üv at the same samples [m/s², positive up], where the
        record has one; the exact solver reads it only when asked (``--vertical``).
    ground : GroundMotion or None
        Set on the motion of a floor (:func:`audit.physics.building.floor_motion.floor_motion`):
        the ground motion it was filtered from, which the hazard's intensity measures read.
    """

    id: str
    acceleration: np.ndarray
    dt: float
    component: str = ""
    source: str = ""
    sha256: str = ""
    pulse: Pulse | None = None
    metadata: dict = field(default_factory=dict)
    vertical: np.ndarray | None = None
    ground: GroundMotion | None = None

    def __post_init__(self):
        where = self.source or self.id
        acc = np.ascontiguousarray(self.acceleration, dtype=float)
        if acc.ndim != 1 or acc.size < 2:
            raise InputError(f"{where}: acceleration: needs at least 2 samples, got {acc.size}")
        if not np.all(np.isfinite(acc)):
            bad = int(np.flatnonzero(~np.isfinite(acc))[0])
            raise InputError(f"{where}: acceleration: sample {bad + 1} is not a finite number")
        if not (np.isfinite(self.dt) and self.dt > 0):
            raise InputError(f"{where}: dt: must be a positive number of seconds, got {self.dt}")
        object.__setattr__(self, "acceleration", acc)
        if self.vertical is not None:
            up = np.ascontiguousarray(self.vertical, dtype=float)
            if up.shape != acc.shape:
                raise InputError(f"{where}: vertical: needs one sample per horizontal sample "
                                 f"({acc.size}), got {up.size}")
            if not np.all(np.isfinite(up)):
                bad = int(np.flatnonzero(~np.isfinite(up))[0])
                raise InputError(f"{where}: vertical: sample {bad + 1} is not a finite number")
            object.__setattr__(self, "vertical", up)

    @property
    def duration(self) -> float:
        """Length of the record [s]."""
        return (self.acceleration.size - 1) * self.dt

    @property
    def time(self) -> np.ndarray:
        """Sample times [s]."""
        return np.arange(self.acceleration.size) * self.dt

    def acceleration_at(self, t) -> np.ndarray:
        """üg [m/s²] at times t [s] as the solver sees it: the closed form of an analytic pulse,
        else linear between samples; zero after the record."""
        if self.pulse is not None:
            return pulse_acceleration(self.pulse.shape, self.pulse.amplitude, self.pulse.period_s, t)
        return np.interp(t, self.time, self.acceleration, right=0.0)

    def scaled(self, factor: float, component: str | None = None) -> GroundMotion:
        """The same record with every acceleration (the vertical one too, and an analytic pulse's
        amplitude, and the ground motion of a floor's: the building is linear) × factor.

        Parameters
        ----------
        factor : float
            Scale factor [-].
        component : str, optional
            New description of the component (default: unchanged).
        """
        pulse = self.pulse and replace(self.pulse, amplitude=self.pulse.amplitude * factor)
        return replace(self, acceleration=self.acceleration * factor, pulse=pulse,
                       vertical=None if self.vertical is None else self.vertical * factor,
                       ground=None if self.ground is None else self.ground.scaled(factor),
                       component=self.component if component is None else component)

    def with_vertical(self, vertical: GroundMotion, down: bool = False) -> GroundMotion:
        """This record with the vertical component of ``vertical`` (another file of the same
        station), on this record's samples (linear between its own, zero past its end).

        Parameters
        ----------
        vertical : GroundMotion
            The vertical record, positive up unless ``down``.
        down : bool
            Its positive values point down (PEER's DWN files): the sign is flipped.
        """
        up = np.interp(self.time, vertical.time, vertical.acceleration, right=0.0)
        return replace(self, vertical=-up if down else up)

    @property
    def pga(self) -> float:
        """Peak ground acceleration max|üg| [m/s²]."""
        return float(np.max(np.abs(self.acceleration)))

    @property
    def pga_g(self) -> float:
        """Peak ground acceleration [g]."""
        return self.pga / G

    @property
    def pgv(self) -> float:
        """Peak ground velocity [m/s].

        Trapezoid-rule integral of (üg − mean üg) from v(0) = 0, with no filtering and no other
        baseline correction (so PGV depends on this processing; PGA does not).
        Analytic pulses are integrated without removing the mean.
        """
        acc = self.acceleration if self.pulse else self.acceleration - self.acceleration.mean()
        velocity = np.concatenate(([0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * self.dt)))
        return float(np.max(np.abs(velocity)))
