"""Typical-section (2-DOF plunge/pitch) aeroelastic model built on the project's 2-D kernels.

Source: Hodges & Pierce, *Introduction to Structural Dynamics and Aeroelasticity*, 2nd ed. (2011) ch. 5
(equations of motion, Peters finite-state and Theodorsen flutter); ``docs/reference/aero-kinematics.md``
§3.2 (benchmark values). Aerodynamics from :mod:`flexsim.aero.theodorsen` (the rigid-section
loads) and :mod:`flexsim.aero.inflow` (Peters finite-state inflow).

Non-dimensionalisation: semichord ``b = 1``, density ``ρ = 1``, pitch frequency ``ω_θ = 1``, mass
``m = μπρb²``. Speeds are therefore ``U/(bω_θ)``, eigenvalues and frequencies are in units of ``ω_θ``,
plunge is ``h/b``. States (Peters): ``x = [h, θ, ḣ, θ̇, λ_1..λ_N]`` with ``h`` positive down at the
elastic axis and ``θ`` nose up. Equations of motion (Hodges & Pierce ch. 5):
``m(ḧ + b x_θ θ̈) + k_h h = -L``, ``I_P θ̈ + m b x_θ ḧ + k_θ θ = M_EA``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import eigvals
from scipy.optimize import brentq

from flexsim.aero.inflow import inflow_coefficients
from flexsim.aero.pk import pk_track
from flexsim.aero.theodorsen import theodorsen_function, theodorsen_operator

MODELS = ("peters", "quasi_steady", "theodorsen")
_FORCE_SIGNS = np.array([-1.0, 1.0])  # generalized forces [-L, M_EA] conjugate to [h, θ]


@dataclass(frozen=True)
class TypicalSection:
    """Dimensionless typical-section parameters (Hodges & Pierce 2011 ch. 5; defaults: reference §3.2).

    Attributes
    ----------
    a : float
        Elastic axis, semichords aft of mid-chord.
    e : float
        Centre of mass, semichords aft of mid-chord (``x_θ = e - a``).
    mu : float
        Mass ratio ``m/(πρb²)``.
    r2 : float
        Squared radius of gyration about the elastic axis ``I_P/(m b²)``.
    sigma : float
        Frequency ratio ``ω_h/ω_θ``.
    """

    a: float = -0.2
    e: float = -0.1
    mu: float = 20.0
    r2: float = 0.24
    sigma: float = 0.4

    def __post_init__(self) -> None:
        for name in ("mu", "r2", "sigma"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"{name} must be > 0; got {getattr(self, name)!r}")
        if not -1.0 < self.a < 1.0:
            raise ValueError(f"a must satisfy -1 < a < 1; got {self.a!r}")

    @property
    def x_theta(self) -> float:
        """Static unbalance ``x_θ = e - a`` [semichords]."""
        return self.e - self.a


@dataclass(frozen=True)
class FlutterResult:
    """Flutter and divergence of a typical section (speeds in ``bω_θ``, frequency in ``ω_θ``).

    ``flutter_speed`` and ``flutter_frequency`` are ``None`` if no crossing was found below the scan limit.
    """

    flutter_speed: float | None
    flutter_frequency: float | None
    divergence_speed: float
    model: str


def _check_model(model: str) -> str:
    if model not in MODELS:
        raise ValueError(f"model must be one of {MODELS}; got {model!r}")
    return model


def structural_matrices(section: TypicalSection) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Structural mass and stiffness for ``q = [h/b, θ]`` (Hodges & Pierce 2011 ch. 5; non-dimensional).

    Returns
    -------
    (ndarray, ndarray), each shape (2, 2)
        ``M_s = m[[1, x_θ], [x_θ, r²]]``, ``K_s = m diag(σ², r²)`` with ``m = μπ``.
    """
    m = section.mu * np.pi
    mass = m * np.array([[1.0, section.x_theta], [section.x_theta, section.r2]])
    stiffness = m * np.diag([section.sigma**2, section.r2])
    return mass, stiffness


@dataclass(frozen=True, eq=False)
class _LinearAero:
    """``[L, M_EA] = mass q̈ + damping q̇ + stiffness q + lambda0 λ0``;
    ``ẇ0 + ẇ1/2 = inflow_acceleration·q̈ + inflow_velocity·q̇`` (``q = [h, θ]``, constant ``u0``)."""

    mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    lambda0: NDArray[np.float64]
    inflow_acceleration: NDArray[np.float64]
    inflow_velocity: NDArray[np.float64]


def _peters_linear_aero(section: TypicalSection, speed: float) -> _LinearAero:
    """Rigid-section Peters airloads, exactly linear at constant ``u0`` (``b = ρ = 1``).

    Peters' rigid-section loads are Theodorsen's non-circulatory terms plus the circulatory lift of the
    3/4-chord downwash ``Q`` less the inflow ``λ0`` (reference §1.5; with ``λ0 = (1 - C)Q`` they are
    Theodorsen's loads, paper eq. 27), so they are assembled from :func:`theodorsen_operator`:
    ``[L, M_EA] = mass q̈ + damping q̇ + circulation (Q - λ0)``, ``Q = downwash_displacement·q +
    downwash_rate·q̇``; the inflow forcing is ``ẇ0 + ẇ1/2 = Q̇``.
    """
    op = theodorsen_operator(section.a, 1.0, 1.0, speed)
    return _LinearAero(
        mass=op.mass,
        damping=op.damping + np.outer(op.circulation, op.downwash_rate),
        stiffness=op.stiffness + np.outer(op.circulation, op.downwash_displacement),
        lambda0=-op.circulation,
        inflow_acceleration=op.downwash_rate,
        inflow_velocity=op.downwash_displacement,
    )


def state_matrices(
    section: TypicalSection, speed: float, model: str = "peters", n_states: int = 6
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Implicit state space ``E ẋ = A x`` of the typical section (Hodges & Pierce 2011 ch. 5; ref. §2.3).

    The apparent-mass terms of the loads and the accelerations in the inflow forcing ``ẇ0 + ẇ1/2`` are
    kept in ``E`` (no lagging). ``model="peters"``: ``x = [h, θ, ḣ, θ̇, λ]`` with ``N = n_states``
    inflow states; ``model="quasi_steady"``: ``λ0 = 0``, ``x = [h, θ, ḣ, θ̇]``.

    Parameters
    ----------
    section : TypicalSection
    speed : float
        ``U/(bω_θ)`` >= 0.
    model : {"peters", "quasi_steady"}
    n_states : int
        Inflow states for ``"peters"`` (1–10).

    Returns
    -------
    (E, A) : (ndarray, ndarray), each shape (n, n)
    """
    if _check_model(model) == "theodorsen":
        raise ValueError("model 'theodorsen' is frequency-domain; use pk_roots() for it")
    mass_s, stiff_s = structural_matrices(section)
    aero = _peters_linear_aero(section, speed)
    n_lam = inflow_coefficients(n_states).n_states if model == "peters" else 0
    size = 4 + n_lam
    e_mat = np.eye(size)
    a_mat = np.zeros((size, size))
    a_mat[0:2, 2:4] = np.eye(2)
    e_mat[2:4, 2:4] = mass_s - _FORCE_SIGNS[:, None] * aero.mass
    a_mat[2:4, 0:2] = -stiff_s + _FORCE_SIGNS[:, None] * aero.stiffness
    a_mat[2:4, 2:4] = _FORCE_SIGNS[:, None] * aero.damping
    if n_lam:
        inflow = inflow_coefficients(n_states)
        e_mat[4:, 4:] = inflow.A
        e_mat[4:, 2:4] = -np.outer(inflow.c, aero.inflow_acceleration)
        a_mat[2:4, 4:] = np.outer(_FORCE_SIGNS * aero.lambda0, 0.5 * inflow.b)
        a_mat[4:, 2:4] = np.outer(inflow.c, aero.inflow_velocity)
        a_mat[4:, 4:] = -speed * np.eye(n_lam)
    return e_mat, a_mat


def state_eigenvalues(
    section: TypicalSection, speed: float, model: str = "peters", n_states: int = 6
) -> NDArray[np.complex128]:
    """Eigenvalues of ``E⁻¹A`` (units of ``ω_θ``), sorted by decreasing real part.

    Parameters
    ----------
    section, speed, model, n_states
        As in :func:`state_matrices`.

    Returns
    -------
    ndarray of complex, shape (n,)
    """
    e_mat, a_mat = state_matrices(section, speed, model, n_states)
    roots = np.linalg.eigvals(np.linalg.solve(e_mat, a_mat))
    return roots[np.argsort(-roots.real, kind="stable")]


def wind_off_frequencies(section: TypicalSection) -> NDArray[np.float64]:
    """Coupled natural frequencies in vacuum [``ω_θ``], ascending (eigenvalues of ``(K_s, M_s)``)."""
    mass_s, stiff_s = structural_matrices(section)
    return np.sqrt(np.sort(eigvals(stiff_s, mass_s).real))


def _pk_state_matrix(section: TypicalSection, speed: float, omega: float) -> NDArray[np.complex128]:
    """State matrix of Theodorsen's flutter equations with ``C`` frozen at ``k = ω/U`` (units of ``ω_θ``)."""
    mass_s, stiff_s = structural_matrices(section)
    op = theodorsen_operator(section.a, 1.0, 1.0, speed)
    c_k = theodorsen_function(abs(omega) / speed)
    signs = _FORCE_SIGNS[:, None]
    mass = mass_s - signs * op.mass
    damping = signs * (op.damping + c_k * np.outer(op.circulation, op.downwash_rate))
    stiffness = stiff_s - signs * (op.stiffness + c_k * np.outer(op.circulation, op.downwash_displacement))
    lower = np.linalg.solve(mass, np.hstack([-stiffness, damping]))
    return np.vstack([np.hstack([np.zeros((2, 2)), np.eye(2)]), lower])


def pk_root(
    section: TypicalSection, speed: float, frequency_guess: float, tol: float = 1e-12, max_iter: int = 500
) -> complex:
    """p-k iteration for one mode with Theodorsen's aerodynamics (Hodges & Pierce 2011, ch. 5).

    ``(M_s - P M_nc)p² - P(D_nc + C(k) r w_rᵀ)p + K_s - P(K_nc + C(k) r w_dᵀ) = 0`` with the
    :class:`~flexsim.aero.theodorsen.TheodorsenOperator` parts and ``P = diag(-1, 1)``, in first-order form.
    The start is the root with ``Im p >= 0`` nearest ``ω`` at ``k = ω/U``; the iteration is the project's
    one p-k (:func:`flexsim.aero.pk.pk_track`): evaluate ``C(k)`` at ``k = Im p / U``, continue the root,
    until ``|Δk| < tol``. At ``Re p = 0`` this is Theodorsen's exact flutter point.

    Parameters
    ----------
    section : TypicalSection
    speed : float
        ``U/(bω_θ)`` > 0.
    frequency_guess : float
        Starting ``ω/ω_θ`` (> 0) of the mode to follow.
    tol : float
        Convergence tolerance on ``k``.
    max_iter : int
        Iteration limit.

    Returns
    -------
    complex
        ``p/ω_θ``.

    Raises
    ------
    RuntimeError
        If the iteration does not converge.
    """
    if not speed > 0.0:
        raise ValueError(f"speed must be > 0 for the p-k method; got {speed!r}")

    def a_of(omega: float) -> NDArray[np.complex128]:
        return _pk_state_matrix(section, speed, omega)

    vals, vecs = np.linalg.eig(a_of(frequency_guess))
    upper = np.flatnonzero(vals.imag >= 0.0)
    start = upper[np.argmin(np.abs(vals[upper].imag - frequency_guess))]
    # |Δk| < tol  <=>  |Δ Im p| < tol U; the kernel's test is relative to max(1, |Im p|)
    root = pk_track(a_of, vals[start], vecs[:, start], rtol=tol * speed / max(1.0, 2.0 * frequency_guess),
                    max_iter=max_iter)
    if not root.converged:
        raise RuntimeError(
            f"p-k iteration did not converge at speed {speed!r} from frequency {frequency_guess!r}"
        )
    return root.eigenvalue


def pk_roots(
    section: TypicalSection, speed: float, frequency_guesses: ArrayLike | None = None
) -> NDArray[np.complex128]:
    """p-k roots (Theodorsen) of both structural modes; guesses default to :func:`wind_off_frequencies`.

    Returns
    -------
    ndarray of complex, shape (2,)
        ``p/ω_θ`` per mode, in the order of the guesses.
    """
    guesses = wind_off_frequencies(section) if frequency_guesses is None else np.asarray(frequency_guesses)
    return np.array([pk_root(section, speed, g) for g in guesses])


def divergence_speed(section: TypicalSection) -> float:
    """Static divergence speed ``U_D/(bω_θ)`` (Hodges & Pierce 2011, ch. 4, typical section).

    Solves ``(K_s - U² P K̂_a) q = 0`` with ``K̂_a`` the strip-kernel steady stiffness at unit speed
    (``λ0 = 0`` in steady flow, so every model shares it). Benchmark: ``U_D = sqrt(μr²/(2(½ + a)))``.

    Returns
    -------
    float
        ``inf`` if no positive root exists (elastic axis at or ahead of the quarter chord).
    """
    _, stiff_s = structural_matrices(section)
    aero = _FORCE_SIGNS[:, None] * _peters_linear_aero(section, 1.0).stiffness
    with np.errstate(divide="ignore", invalid="ignore"):
        squared = eigvals(stiff_s, aero)
    real = np.isfinite(squared) & (np.abs(squared.imag) <= 1e-9 * np.abs(squared)) & (squared.real > 0.0)
    return float(np.sqrt(squared[real].real.min())) if np.any(real) else float("inf")


class _Growth(NamedTuple):
    real: float  # largest real part [ω_θ]
    frequency: float  # |Im| of that root [ω_θ]
    modes: NDArray | None  # p-k mode frequencies (continuation guesses), None for state space


def _growth(
    section: TypicalSection, model: str, n_states: int, speed: float, guesses: NDArray | None
) -> _Growth:
    """Largest real part at ``speed`` (p-k roots followed from ``guesses`` for ``"theodorsen"``)."""
    if model == "theodorsen":
        roots = pk_roots(section, speed, guesses)
        worst = int(np.argmax(roots.real))
        return _Growth(float(roots[worst].real), float(abs(roots[worst].imag)), roots.imag)
    root = state_eigenvalues(section, speed, model, n_states)[0]
    return _Growth(float(root.real), float(abs(root.imag)), None)


def flutter_analysis(
    section: TypicalSection,
    model: str = "peters",
    n_states: int = 6,
    speed_max: float = 5.0,
    speed_step: float = 0.05,
    xtol: float = 1e-8,
) -> FlutterResult:
    """Flutter speed and frequency (first zero crossing of a root's real part) and divergence speed.

    Scans ``U = speed_step, 2 speed_step, ... <= speed_max`` for the first sign change (negative to
    non-negative) of the largest real part (state-space models) or of the largest p-k damping
    (``"theodorsen"``; modes followed by continuation in speed), then refines it with ``brentq`` to
    ``xtol`` (default 1e-8, finer than the 1e-6 required). The first crossing of any root is reported; a
    static (zero-frequency) crossing would show ``flutter_frequency ≈ 0``.

    Parameters
    ----------
    section : TypicalSection
    model : {"peters", "quasi_steady", "theodorsen"}
    n_states : int
        Inflow states for ``"peters"`` (1–10).
    speed_max, speed_step : float
        Scan range and step [``bω_θ``].
    xtol : float
        Absolute tolerance of the crossing speed.

    Returns
    -------
    FlutterResult
    """
    _check_model(model)
    speeds = np.arange(1, int(np.floor(speed_max / speed_step + 1e-9)) + 1) * speed_step
    initial = wind_off_frequencies(section) if model == "theodorsen" else None
    left_speed, left = float(speeds[0]), _growth(section, model, n_states, float(speeds[0]), initial)
    for speed in map(float, speeds[1:]):
        right = _growth(section, model, n_states, speed, left.modes)
        if left.real < 0.0 <= right.real:
            guesses = left.modes
            crossing = brentq(
                lambda u: _growth(section, model, n_states, u, guesses).real, left_speed, speed, xtol=xtol
            )
            frequency = _growth(section, model, n_states, crossing, guesses).frequency
            return FlutterResult(crossing, frequency, divergence_speed(section), model)
        left_speed, left = speed, right
    return FlutterResult(None, None, divergence_speed(section), model)
