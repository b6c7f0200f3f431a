"""Atmospheric disturbances as wind fields passed to :meth:`~flexsim.model.aircraft_model.AircraftModel.rhs`.

Every disturbance here is a callable ``wind(t, positions_ned_m) -> (k, 3)``: the air velocity [m/s] in
inertial north-east-down (NED) axes at k inertial positions [m] (the aerodynamic strips) at time t [s],
passed per call: ``model.rhs(t, x, u, wind)``, ``simulate(..., wind=...)``. The model evaluates the strip loads with the air velocity
relative to each strip, so a disturbance reaches different strips at different times (the nose before
the tail, one wing before the other in a yawed encounter).

* :class:`OneMinusCosineGust`: the discrete "1-cos" gust of CS-25.341(a) / FAR 25.341(a),
  ``U(s) = (U_ds / 2) (1 - cos(pi s / H))`` for ``0 <= s <= 2 H`` (s the penetration distance, H the
  gust gradient distance), or the MIL-F-8785C 3.7.3 / MIL-HDBK-1797 discrete gust, which rises over H and
  then stays (``persistent=True``). A plane front, frozen in the air.
* :class:`DrydenTurbulence`: continuous turbulence with the Dryden spectra of MIL-F-8785C 3.7.2.2
  (equivalently MIL-HDBK-1797 4.9.2 with its scale-length convention), frozen in the air along a straight
  flight direction (Taylor's hypothesis) and generated once, from a seed, by filtering Gaussian white noise
  in the frequency domain on a periodic distance grid; interpolated linearly between grid points.
* :func:`combine`: the sum of several wind fields.

Each field carries its parameters as arrays (``wind_data``, :class:`flexsim._kernels.WindData`), so that the
model's compiled right-hand side evaluates it at the strips without calling back into Python; ``__call__``
runs the same kernel (:func:`flexsim._kernels.wind_ned`). Any other callable with the same signature works
too (called from Python once per right-hand side).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from flexsim import _kernels as _k
from flexsim._arrays import frozen_array, kernel_arg

__all__ = [
    "WindField",
    "OneMinusCosineGust",
    "DrydenTurbulence",
    "dryden_spectrum",
    "mil_f_8785c_turbulence",
    "combine",
    "SEVERITIES",
]

#: Type of a wind field: ``wind(t [s], positions_ned_m (k, 3)) -> air velocity NED (k, 3) [m/s]``.
WindField = Callable[[float, np.ndarray], np.ndarray]

_FT = 0.3048  # [m / ft]
_KT = 0.514444  # [m/s / kt]

#: Severity -> (row of the MIL-F-8785C Figure 7 table (probability of exceedance), wind speed at 20 ft [kt]
#: for the low-altitude model, MIL-F-8785C 3.7.2.1): light 1e-2 and 15 kt, moderate 1e-3 and 30 kt,
#: severe 1e-5 and 45 kt.
SEVERITIES = {"light": (2, 15.0), "moderate": (3, 30.0), "severe": (5, 45.0)}
#: MIL-F-8785C Figure 7: rms turbulence intensity [ft/s] at medium/high altitude against altitude [ft],
#: one row per probability of exceedance 2e-1, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6 (digitised values as
#: used by common flight simulators, e.g. JSBSim's FGWinds).
_POE_ALTITUDE_FT = np.array([500.0, 1750.0, 3750.0, 7500.0, 15000.0, 25000.0, 35000.0, 45000.0, 55000.0, 65000.0, 75000.0, 80000.0])
_POE_SIGMA_FT_S = np.array([
    [3.2, 2.2, 1.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [4.2, 3.6, 3.3, 1.6, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [6.6, 6.9, 7.4, 6.7, 4.6, 2.7, 0.4, 0.0, 0.0, 0.0, 0.0, 0.0],
    [8.6, 9.6, 10.6, 10.1, 8.0, 6.6, 5.0, 4.2, 2.7, 0.0, 0.0, 0.0],
    [11.8, 13.0, 16.0, 15.1, 11.6, 9.7, 8.1, 8.2, 7.9, 4.9, 3.2, 2.1],
    [15.6, 17.6, 23.0, 23.6, 22.1, 20.0, 16.0, 15.1, 12.1, 7.9, 6.2, 5.1],
    [18.7, 21.5, 28.4, 30.2, 30.7, 31.0, 25.2, 23.1, 17.5, 10.7, 8.4, 7.2],
])


def _wind_data(gusts=None, turb=None, turb_grid=None) -> _k.WindData:
    """Frozen :class:`flexsim._kernels.WindData` (missing parts empty)."""
    return _k.WindData(frozen_array(np.zeros((0, 12)) if gusts is None else gusts),
                       frozen_array(np.zeros((0, 15)) if turb is None else turb),
                       frozen_array(np.zeros((3, 1)) if turb_grid is None else turb_grid))


def _finite(name: str, value: object, *, positive: bool = False, nonnegative: bool = False) -> float:
    """A finite float, optionally > 0 or >= 0; ValueError naming the field otherwise."""
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be a finite number") from None
    if not math.isfinite(v) or (positive and v <= 0.0) or (nonnegative and v < 0.0):
        allowed = "> 0" if positive else ">= 0" if nonnegative else "finite"
        raise ValueError(f"{name} = {value!r}: must be a finite number {allowed}".rstrip())
    return v


def _vector3(name: str, value: object, *, unit: bool = False) -> np.ndarray:
    """A finite 3-vector (normalised if ``unit``); ValueError naming the field otherwise."""
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be 3 finite numbers") from None
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"{name} = {value!r}: must be 3 finite numbers (NED)")
    if unit:
        norm = float(np.linalg.norm(v))
        if norm < 1e-12:
            raise ValueError(f"{name} = {value!r}: must be a non-zero direction")
        v = v / norm
    v.setflags(write=False)
    return v


def _positions(positions_ned_m: np.ndarray) -> np.ndarray:
    p = np.asarray(positions_ned_m, dtype=float)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"positions_ned_m: expected shape (k, 3), got {p.shape}")
    return kernel_arg(p)


@dataclass(frozen=True, eq=False)
class OneMinusCosineGust:
    """Discrete "1-cos" gust: a plane front frozen in the air (CS-25.341(a); MIL-F-8785C 3.7.3).

    With s = n . (r - r_front) the distance of a point r behind the front plane (n the unit normal,
    pointing the way the aircraft penetrates the gust)::

        U(s) = (U_ds / 2) (1 - cos(pi s / H))    for 0 <= s <= 2 H,   0 elsewhere       (CS-25.341(a))
        U(s) = (U_ds / 2) (1 - cos(pi s / H))    for 0 <= s <= H,     U_ds for s > H    (persistent, MIL-F-8785C)

    and the air velocity is ``U(s) * direction``.

    Attributes
    ----------
    amplitude_m_s : float
        Peak gust velocity U_ds [m/s] (finite; negative reverses ``direction``).
    gradient_length_m : float
        Gust gradient distance H [m], > 0 (the distance to the peak; CS-25: 9 to 107 m).
    direction_ned : array_like, shape (3,)
        Direction of the air velocity in NED axes (normalised); default (0, 0, -1), an up-gust.
    normal_ned : array_like, shape (3,)
        Normal of the front plane, pointing into the gust (normalised); default (1, 0, 0): an aircraft
        flying north penetrates it.
    front_position_ned_m : array_like, shape (3,)
        A point of the front plane [m], NED.
    persistent : bool
        False: the full 1-cos shape of length 2H (CS-25); True: the MIL-F-8785C shape, which stays at
        U_ds after s = H.
    """

    amplitude_m_s: float
    gradient_length_m: float
    direction_ned: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, -1.0]))
    normal_ned: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))
    front_position_ned_m: np.ndarray = field(default_factory=lambda: np.zeros(3))
    persistent: bool = False
    wind_data: _k.WindData = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "amplitude_m_s", _finite("amplitude_m_s", self.amplitude_m_s))
        object.__setattr__(self, "gradient_length_m", _finite("gradient_length_m", self.gradient_length_m, positive=True))
        object.__setattr__(self, "direction_ned", _vector3("direction_ned", self.direction_ned, unit=True))
        object.__setattr__(self, "normal_ned", _vector3("normal_ned", self.normal_ned, unit=True))
        object.__setattr__(self, "front_position_ned_m", _vector3("front_position_ned_m", self.front_position_ned_m))
        if not isinstance(self.persistent, bool):
            raise ValueError(f"persistent = {self.persistent!r}: must be True or False")
        params = np.concatenate([[self.amplitude_m_s, self.gradient_length_m], self.direction_ned, self.normal_ned,
                                 self.front_position_ned_m, [float(self.persistent)]])
        object.__setattr__(self, "wind_data", _wind_data(gusts=params[None, :]))

    @classmethod
    def encounter(
        cls,
        amplitude_m_s: float,
        gradient_length_m: float,
        *,
        position_ned_m: Sequence[float],
        velocity_ned_m_s: Sequence[float],
        start_time_s: float,
        direction_ned: Sequence[float] = (0.0, 0.0, -1.0),
        persistent: bool = False,
    ) -> "OneMinusCosineGust":
        """A gust whose front reaches a point moving in a straight line at a given time.

        The front is normal to ``velocity_ned_m_s`` and passes through ``position_ned_m +
        velocity_ned_m_s * start_time_s``: a point starting at ``position_ned_m`` (e.g. the body origin
        of a trimmed aircraft) and flying straight at that velocity enters the gust at ``start_time_s``
        and sees ``U(V (t - start_time_s))``. Points ahead of it (the nose) enter earlier.

        Parameters
        ----------
        amplitude_m_s, gradient_length_m : float
            U_ds [m/s] and H [m] (see the class).
        position_ned_m : array_like, shape (3,)
            Starting position [m], NED.
        velocity_ned_m_s : array_like, shape (3,)
            Inertial velocity [m/s], NED, non-zero.
        start_time_s : float
            Time [s] >= 0 at which the point reaches the front.
        direction_ned : array_like, shape (3,)
            Direction of the gust velocity (default up).
        persistent : bool
            See the class.
        """
        pos = _vector3("position_ned_m", position_ned_m)
        vel = _vector3("velocity_ned_m_s", velocity_ned_m_s)
        if float(np.linalg.norm(vel)) < 1e-9:
            raise ValueError(f"velocity_ned_m_s = {velocity_ned_m_s!r}: must be non-zero (it sets the gust front's normal)")
        t0 = _finite("start_time_s", start_time_s, nonnegative=True)
        return cls(amplitude_m_s, gradient_length_m, direction_ned=np.asarray(direction_ned, float), normal_ned=vel,
                   front_position_ned_m=pos + vel * t0, persistent=persistent)

    def profile(self, s_m: np.ndarray) -> np.ndarray:
        """Gust velocity U(s) [m/s] at penetration distances ``s_m`` [m] (any shape)."""
        s = np.asarray(s_m, dtype=float)
        return _k.gust_profiles(kernel_arg(s.ravel()), self.amplitude_m_s, self.gradient_length_m, self.persistent).reshape(s.shape)

    def __call__(self, t: float, positions_ned_m: np.ndarray) -> np.ndarray:
        """Air velocity [m/s], NED, shape (k, 3), at ``positions_ned_m`` (k, 3) [m]; independent of t."""
        return _k.wind_ned(*self.wind_data, _positions(positions_ned_m))


def dryden_spectrum(component: str, omega_rad_m: np.ndarray, sigma_m_s: float, length_m: float) -> np.ndarray:
    """One-sided Dryden power spectral density [(m/s)^2 / (rad/m)] (MIL-F-8785C 3.7.2.2, Table III).

    ``Phi_u = sigma^2 (2 L / pi) / (1 + (L W)^2)``,
    ``Phi_v = Phi_w = sigma^2 (L / pi) (1 + 3 (L W)^2) / (1 + (L W)^2)^2``, W the spatial frequency
    [rad/m] >= 0; each integrates to sigma^2 over 0 <= W < inf.

    Parameters
    ----------
    component : {"u", "v", "w"}
        Longitudinal, lateral or vertical.
    omega_rad_m : array_like
        Spatial frequency W [rad/m].
    sigma_m_s : float
        rms intensity [m/s].
    length_m : float
        Scale length L [m].
    """
    if component not in ("u", "v", "w"):
        raise ValueError(f"component = {component!r}: must be 'u', 'v' or 'w'")
    lw2 = (length_m * np.asarray(omega_rad_m, dtype=float)) ** 2
    if component == "u":
        return sigma_m_s**2 * (2.0 * length_m / np.pi) / (1.0 + lw2)
    return sigma_m_s**2 * (length_m / np.pi) * (1.0 + 3.0 * lw2) / (1.0 + lw2) ** 2


def mil_f_8785c_turbulence(altitude_m: float, severity: str = "moderate") -> tuple[np.ndarray, np.ndarray]:
    """Dryden intensities and scale lengths of MIL-F-8785C 3.7.2 at an altitude.

    Low altitude (h <= 1000 ft, 3.7.2.3): ``L_w = h``, ``L_u = L_v = h / (0.177 + 0.000823 h)^1.2``,
    ``sigma_w = 0.1 W20``, ``sigma_u = sigma_v = sigma_w / (0.177 + 0.000823 h)^0.4`` (h in ft, h >= 10 ft);
    medium/high altitude (h >= 2000 ft, 3.7.2.2): ``L_u = L_v = L_w = 1750 ft`` and
    ``sigma_u = sigma_v = sigma_w`` from Figure 7 at the severity's probability of exceedance; linear
    interpolation in between.

    Parameters
    ----------
    altitude_m : float
        Altitude [m], 3.048 m (10 ft) to 24384 m (80000 ft).
    severity : {"light", "moderate", "severe"}
        Probability of exceedance 1e-2, 1e-3, 1e-5 and wind at 20 ft of 15, 30, 45 kt.

    Returns
    -------
    sigma_m_s : ndarray, shape (3,)
        rms intensities (u, v, w) [m/s].
    length_m : ndarray, shape (3,)
        Scale lengths (L_u, L_v, L_w) [m].
    """
    if severity not in SEVERITIES:
        raise ValueError(f"severity = {severity!r}: must be one of {', '.join(SEVERITIES)}")
    h_m = _finite("altitude_m", altitude_m)
    h = h_m / _FT
    if not 10.0 <= h <= _POE_ALTITUDE_FT[-1]:
        raise ValueError(f"altitude_m = {altitude_m!r}: must be in [{10 * _FT:.3f}, {_POE_ALTITUDE_FT[-1] * _FT:.0f}] m "
                         "(MIL-F-8785C turbulence model range)")
    row, w20_kt = SEVERITIES[severity]

    def low(hf: float) -> tuple[np.ndarray, np.ndarray]:
        k = 0.177 + 0.000823 * hf
        sw = 0.1 * w20_kt * _KT / _FT  # [ft/s]
        lu = hf / k**1.2
        return np.array([sw / k**0.4, sw / k**0.4, sw]), np.array([lu, lu, hf])

    def high(hf: float) -> tuple[np.ndarray, np.ndarray]:
        s = float(np.interp(hf, _POE_ALTITUDE_FT, _POE_SIGMA_FT_S[row]))
        return np.full(3, s), np.full(3, 1750.0)

    if h <= 1000.0:
        sig, lengths = low(h)
    elif h >= 2000.0:
        sig, lengths = high(h)
    else:
        f = (h - 1000.0) / 1000.0
        (s0, l0), (s1, l1) = low(1000.0), high(2000.0)
        sig, lengths = (1 - f) * s0 + f * s1, (1 - f) * l0 + f * l1
    return sig * _FT, lengths * _FT


@dataclass(frozen=True, eq=False)
class DrydenTurbulence:
    """Continuous Dryden turbulence, frozen in the air along a straight flight direction (seeded).

    The field is a function of the distance xi = d . (r - origin) along the horizontal flight direction
    d = (cos psi, sin psi, 0) (Taylor's frozen-turbulence hypothesis): a point moving along d at speed V
    sees the Dryden spectra of MIL-F-8785C 3.7.2.2 in time. Components: u along d, v horizontal to the
    right of d, w down. Each component is Gaussian white noise filtered in the frequency domain by
    sqrt(Phi) (:func:`dryden_spectrum`) on a periodic grid of ``n_points`` points ``spacing_m`` apart
    (period P = n_points * spacing_m), so that the realisation repeats after P and its variance is
    sum_k Phi(W_k) dW ~ sigma^2 (W_k = 2 pi k / P; the mean is removed). The field is independent of
    time; it is meant for straight or nearly straight flight along d (in a turn the distance along d no
    longer follows the flight path).

    Attributes
    ----------
    sigma_m_s : array_like, shape (3,)
        rms intensities (sigma_u, sigma_v, sigma_w) [m/s], >= 0.
    length_m : array_like, shape (3,)
        Scale lengths (L_u, L_v, L_w) [m], > 0.
    seed : int
        Seed of the generator (numpy PCG64); the same seed gives the same field.
    heading_rad : float
        Heading psi of the flight direction d [rad] (0: north).
    origin_ned_m : array_like, shape (3,)
        Where xi = 0 [m].
    spacing_m : float
        Grid spacing [m], > 0 and <= min(L) / 4 (default 1 m).
    n_points : int
        Grid points, a power of 2 >= 1024; the period must be >= 20 max(L) (default 2**17).
    """

    sigma_m_s: np.ndarray
    length_m: np.ndarray
    seed: int = 0
    heading_rad: float = 0.0
    origin_ned_m: np.ndarray = field(default_factory=lambda: np.zeros(3))
    spacing_m: float = 1.0
    n_points: int = 2**17
    _grid: np.ndarray = field(init=False, repr=False, compare=False)
    _axes: np.ndarray = field(init=False, repr=False, compare=False)
    wind_data: _k.WindData = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        sig = np.asarray(self.sigma_m_s, dtype=float)
        lengths = np.asarray(self.length_m, dtype=float)
        if sig.shape != (3,) or not np.all(np.isfinite(sig)) or np.any(sig < 0):
            raise ValueError(f"sigma_m_s = {self.sigma_m_s!r}: must be 3 finite numbers >= 0 [m/s] (u, v, w)")
        if lengths.shape != (3,) or not np.all(np.isfinite(lengths)) or np.any(lengths <= 0):
            raise ValueError(f"length_m = {self.length_m!r}: must be 3 finite numbers > 0 [m] (L_u, L_v, L_w)")
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)) or self.seed < 0:
            raise ValueError(f"seed = {self.seed!r}: must be an integer >= 0")
        spacing = _finite("spacing_m", self.spacing_m, positive=True)
        if spacing > lengths.min() / 4:
            raise ValueError(f"spacing_m = {self.spacing_m!r}: must be <= min(length_m) / 4 = {lengths.min() / 4:.4g} m "
                             "to resolve the spectra")
        n = self.n_points
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1024 or n & (n - 1):
            raise ValueError(f"n_points = {n!r}: must be a power of 2 >= 1024")
        if n * spacing < 20 * lengths.max():
            raise ValueError(f"n_points * spacing_m = {n * spacing:.4g} m: the period must be >= 20 max(length_m) = "
                             f"{20 * lengths.max():.4g} m (increase n_points)")
        heading = _finite("heading_rad", self.heading_rad)
        for name, value in (("sigma_m_s", sig), ("length_m", lengths)):
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        object.__setattr__(self, "origin_ned_m", _vector3("origin_ned_m", self.origin_ned_m))
        object.__setattr__(self, "spacing_m", spacing)
        object.__setattr__(self, "heading_rad", heading)
        ch, sh = math.cos(heading), math.sin(heading)
        axes = np.array([[ch, sh, 0.0], [-sh, ch, 0.0], [0.0, 0.0, 1.0]])  # rows: d (u), right (v), down (w)
        axes.setflags(write=False)
        object.__setattr__(self, "_axes", axes)
        grid = frozen_array(self._generate(int(n), spacing, sig, lengths, int(self.seed)))
        object.__setattr__(self, "_grid", grid)
        turb = np.concatenate([axes.ravel(), self.origin_ned_m, [spacing, 0.0, float(n)]])[None, :]
        object.__setattr__(self, "wind_data", _wind_data(turb=turb, turb_grid=grid))

    @classmethod
    def mil_f_8785c(cls, altitude_m: float, severity: str = "moderate", **kwargs) -> "DrydenTurbulence":
        """Turbulence with the MIL-F-8785C intensities and scale lengths at ``altitude_m``
        (:func:`mil_f_8785c_turbulence`); other attributes as keywords."""
        sigma, length = mil_f_8785c_turbulence(altitude_m, severity)
        return cls(sigma, length, **kwargs)

    @staticmethod
    def _generate(n: int, spacing: float, sigma: np.ndarray, lengths: np.ndarray, seed: int) -> np.ndarray:
        """Field values (3, n) on the grid: irfft of complex Gaussian amplitudes with variance Phi dW."""
        rng = np.random.default_rng(seed)
        d_omega = 2.0 * np.pi / (n * spacing)
        omega = d_omega * np.arange(n // 2 + 1)
        out = np.empty((3, n))
        for i, comp in enumerate("uvw"):
            var = dryden_spectrum(comp, omega, sigma[i], lengths[i]) * d_omega
            var[0] = 0.0  # zero mean
            var[-1] = 0.0  # Nyquist bin: no sine part, left out
            a = rng.standard_normal(omega.size) * np.sqrt(var)
            b = rng.standard_normal(omega.size) * np.sqrt(var)
            out[i] = np.fft.irfft(0.5 * n * (a - 1j * b), n)
        return out

    @property
    def period_m(self) -> float:
        """Length after which the field repeats [m]."""
        return self.n_points * self.spacing_m

    def variance_on_grid(self) -> np.ndarray:
        """Expected variance of each component of this discretised field, sum_k Phi(W_k) dW, shape (3,)
        [(m/s)^2] (slightly below sigma^2: the band below 2 pi / P and above the Nyquist frequency is cut)."""
        d_omega = 2.0 * np.pi / self.period_m
        omega = d_omega * np.arange(1, self.n_points // 2)
        return np.array([dryden_spectrum(c, omega, self.sigma_m_s[i], self.length_m[i]).sum() * d_omega for i, c in enumerate("uvw")])

    def along_track(self, xi_m: np.ndarray) -> np.ndarray:
        """Turbulence components (u, v, w) [m/s] at distances ``xi_m`` [m] along d, shape (k, 3)."""
        return _k.dryden_track(self._grid, self.spacing_m, kernel_arg(np.ravel(xi_m)))

    def __call__(self, t: float, positions_ned_m: np.ndarray) -> np.ndarray:
        """Air velocity [m/s], NED, shape (k, 3), at ``positions_ned_m`` (k, 3) [m]; independent of t."""
        return _k.wind_ned(*self.wind_data, _positions(positions_ned_m))


@dataclass(frozen=True)
class _Sum:
    winds: tuple[WindField, ...]
    #: The parts' arrays joined (None when a part is a plain callable).
    wind_data: _k.WindData | None = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "wind_data", self._joined())

    def _joined(self) -> _k.WindData | None:
        parts = [getattr(w, "wind_data", None) for w in self.winds]
        if not all(isinstance(p, _k.WindData) for p in parts):
            return None
        return _k.join_winds(parts)

    def __call__(self, t: float, positions_ned_m: np.ndarray) -> np.ndarray:
        p = _positions(positions_ned_m)
        total = np.zeros(p.shape)
        for w in self.winds:
            total = total + np.asarray(w(t, p), dtype=float)
        return total


def combine(*winds: WindField) -> WindField:
    """The sum of several wind fields (e.g. a gust on top of turbulence), itself a wind field."""
    if not winds:
        raise ValueError("combine: give at least one wind field")
    for i, w in enumerate(winds):
        if not callable(w):
            raise ValueError(f"combine: argument {i} = {w!r} is not a callable wind(t, positions_ned_m)")
    return _Sum(tuple(winds))
