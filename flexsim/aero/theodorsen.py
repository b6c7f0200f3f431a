"""Theodorsen's function and Theodorsen's exact harmonic loads for plunge, pitch and flap.

Sources: Theodorsen, *General Theory of Aerodynamic Instability and the Mechanism of Flutter*, NACA Rep.
496 (1935) — loads and the constants T1–T14; Hodges & Pierce, *Introduction to Structural Dynamics and
Aeroelasticity*, 2nd ed. (2011) ch. 5 — typical-section form; ``docs/reference/aero-kinematics.md`` §3.1
and §1.7 (test values). Used as the reference model for the Peters airloads and as the paper's "US"
frequency-domain flutter model (paper eq. 27).

Conventions (the same as :mod:`flexsim.aero.peters`): plunge ``h`` at the elastic axis positive down [m],
pitch ``α`` nose up [rad], flap ``β`` trailing edge down [rad]; elastic axis at ``x = a b`` and hinge at
``x = d b`` (semichords from mid-chord, aft positive); outputs lift per span positive up [N/m], moment
about the elastic axis nose up [N] and hinge moment trailing edge down [N]. Harmonic motion
``q(t) = Re(q̂ e^{iωt})``, reduced frequency ``k = ω b / U``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import config, njit, types
from numpy.typing import ArrayLike, NDArray
from scipy.special import j0, j1, y0, y1


def _bessel(name: str, ufunc):
    """Cephes' ``name`` (one of j0, j1, y0, y1) callable from compiled code as ``f(x, 0)``: the C function scipy's
    ufunc of that name evaluates (``scipy.special.cython_special``), registered with LLVM under a symbol name, so
    that compiled callers are cached on disk by name rather than by address. Under ``NUMBA_DISABLE_JIT=1``: the
    ufunc itself (the same values)."""
    if config.DISABLE_JIT:
        return lambda x, _skip: float(ufunc(x))
    import llvmlite.binding as llvm
    from numba.extending import get_cython_function_address

    symbol = f"flexsim_cephes_{name}"
    llvm.add_symbol(symbol, get_cython_function_address("scipy.special.cython_special", name))
    return types.ExternalFunction(symbol, types.float64(types.float64, types.intc))


_J0, _J1, _Y0, _Y1 = (_bessel(n, f) for n, f in (("j0", j0), ("j1", j1), ("y0", y0), ("y1", y1)))


def theodorsen_function(k: ArrayLike) -> NDArray[np.complex128] | complex:
    """Theodorsen's function ``C(k) = H1⁽²⁾(k) / (H1⁽²⁾(k) + i H0⁽²⁾(k))``.

    Source: Theodorsen, NACA Rep. 496 (1935); reference §3.1. ``C(0) = 1`` exactly (the Hankel
    functions diverge there). ``e^{iωt}`` convention, so ``Im C <= 0``. For real ``k > 0``,
    ``Hn⁽²⁾(k) = Jn(k) - i Yn(k)`` (Abramowitz & Stegun 9.1.4), so
    ``C = (J1 - i Y1) / ((J1 + Y0) + i (J0 - Y1))`` from the four real Bessel functions (scipy's Cephes
    ``j0, j1, y0, y1``: equal to the complex Hankel functions of AMOS to 3e-14 relative for
    1e-8 <= k <= 1e3, and 4x cheaper; it is evaluated once per p-k iteration).

    Parameters
    ----------
    k : array_like, shape (...)
        Reduced frequency ``ω b / U`` >= 0, dimensionless.

    Returns
    -------
    complex or ndarray of complex, shape (...)
        A Python complex for scalar input.

    Raises
    ------
    ValueError
        If any ``k`` is negative or not finite.
    """
    k_arr = np.asarray(k, dtype=float)
    if not np.all(np.isfinite(k_arr) & (k_arr >= 0.0)):
        bad = k_arr[~(np.isfinite(k_arr) & (k_arr >= 0.0))].ravel()[0]
        raise ValueError(f"reduced frequency k must be finite and >= 0; got {bad!r}")
    positive = k_arr > 0.0
    value = np.where(positive, theodorsen_positive(np.where(positive, k_arr, 1.0)), 1.0 + 0.0j)
    return complex(value) if value.ndim == 0 else value


def theodorsen_positive(k: NDArray[np.float64]) -> NDArray[np.complex128]:
    """:func:`theodorsen_function` for an array of finite ``k > 0``, unchecked (compiled, :func:`theodorsen_scalar`
    per entry), for the p-k iteration's hundred calls per eigen-analysis (the checks cost a third of the call)."""
    k = np.asarray(k, dtype=float)
    return _theodorsen_array(np.ascontiguousarray(k).ravel()).reshape(k.shape)


@njit(cache=True, nogil=True)
def theodorsen_scalar(k: float) -> complex:
    """``C(k)`` for one finite ``k > 0`` (compiled; the expression of :func:`theodorsen_function`).

    ``C = (J1 - i Y1) / ((J1 + Y0) + i (J0 - Y1))`` with Cephes' Bessel functions (the C functions of scipy's
    ``j0, j1, y0, y1`` ufuncs), the complex quotient by Smith's algorithm (Smith, "Algorithm 116: Complex
    division", Commun. ACM 5(8), 435, 1962) in the form numpy's complex division evaluates it (ratio of the smaller
    to the larger part of the divisor, then one reciprocal), so that the values equal numpy's evaluation of the
    same expression bit for bit (``tests/aero/test_theodorsen.py``).
    """
    bj0, bj1, by0, by1 = _J0(k, 0), _J1(k, 0), _Y0(k, 0), _Y1(k, 0)
    ar, ai = bj1, -by1  # numerator J1 - i Y1
    br, bi = bj1 + by0, bj0 - by1  # denominator
    if abs(br) >= abs(bi):
        rat = bi / br
        scl = 1.0 / (br + bi * rat)
        return complex((ar + ai * rat) * scl, (ai - ar * rat) * scl)
    rat = br / bi
    scl = 1.0 / (bi + br * rat)
    return complex((ar * rat + ai) * scl, (ai * rat - ar) * scl)


@njit(cache=True, nogil=True)
def _theodorsen_array(k: np.ndarray) -> np.ndarray:
    out = np.empty(k.shape[0], np.complex128)
    for i in range(k.shape[0]):
        out[i] = theodorsen_scalar(k[i])
    return out


@dataclass(frozen=True)
class TheodorsenConstants:
    """Theodorsen's flap constants T1–T14 (NACA Rep. 496).

    For hinge ``d`` (Theodorsen's ``c``) and elastic axis ``a``, semichords from mid-chord.

    All dimensionless. ``T6 = T2`` is kept for completeness.
    """

    T1: float
    T2: float
    T3: float
    T4: float
    T5: float
    T6: float
    T7: float
    T8: float
    T9: float
    T10: float
    T11: float
    T12: float
    T13: float
    T14: float


def theodorsen_constants(a: float, d: float) -> TheodorsenConstants:
    """Compute T1–T14 (Theodorsen, NACA Rep. 496, 1935, list of T-functions; reference §1.6).

    Parameters
    ----------
    a : float
        Elastic axis [semichords from mid-chord].
    d : float
        Flap hinge [semichords from mid-chord], ``-1 < d < 1``.

    Returns
    -------
    TheodorsenConstants
    """
    if not -1.0 < d < 1.0:
        raise ValueError(f"flap hinge position d must satisfy -1 < d < 1; got {d!r}")
    s = np.sqrt(1.0 - d * d)
    ac = np.arccos(d)
    t1 = -s * (2.0 + d * d) / 3.0 + d * ac
    t2 = d * (1.0 - d * d) - s * (1.0 + d * d) * ac + d * ac * ac
    t3 = (
        -(0.125 + d * d) * ac * ac
        + 0.25 * d * s * ac * (7.0 + 2.0 * d * d)
        - 0.125 * (1.0 - d * d) * (5.0 * d * d + 4.0)
    )
    t4 = -ac + d * s
    t5 = -(1.0 - d * d) - ac * ac + 2.0 * d * s * ac
    t7 = -(0.125 + d * d) * ac + 0.125 * d * s * (7.0 + 2.0 * d * d)
    t8 = -s * (2.0 * d * d + 1.0) / 3.0 + d * ac
    t9 = 0.5 * (s**3 / 3.0 + a * t4)
    t10 = s + ac
    t11 = ac * (1.0 - 2.0 * d) + s * (2.0 - d)
    t12 = s * (2.0 + d) - ac * (2.0 * d + 1.0)
    t13 = 0.5 * (-t7 - (d - a) * t1)
    t14 = 1.0 / 16.0 + 0.5 * a * d
    values = (t1, t2, t3, t4, t5, t2, t7, t8, t9, t10, t11, t12, t13, t14)
    return TheodorsenConstants(*(float(v) for v in values))


@dataclass(frozen=True, eq=False)
class TheodorsenOperator:
    """Theodorsen's loads split into non-circulatory and circulatory parts.

    ``loads = mass q̈ + damping q̇ + stiffness q + C(k) circulation (downwash_displacement·q +
    downwash_rate·q̇)`` with ``q = [h, α]`` or ``[h, α, β]`` and ``loads = [L, M_EA]`` or
    ``[L, M_EA, H]``.
    The bracket is Theodorsen's ``Q`` (3/4-chord downwash [m/s]; paper eq. 27 for ``β = 0``).

    Attributes
    ----------
    mass, damping, stiffness : ndarray, shape (n, n)
    circulation, downwash_displacement, downwash_rate : ndarray, shape (n,)
    """

    mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    circulation: NDArray[np.float64]
    downwash_displacement: NDArray[np.float64]
    downwash_rate: NDArray[np.float64]


def theodorsen_operator(
    a: float, rho: float, b: float, u: float, d: float | None = None
) -> TheodorsenOperator:
    """Theodorsen's loads on a typical section with an optional flap, as a linear operator.

    Source: Theodorsen, NACA Rep. 496 (1935), eqs. for ``P``, ``M_α``, ``M_β`` (with ``L = -P``);
    Hodges & Pierce (2011) ch. 5 for the plunge/pitch part:
    ``L = πρb²(ḧ + Uα̇ - baα̈) + 2πρUbC Q``,
    ``M_EA = -πρb³[½ḧ + Uα̇ + b(1/8 - a/2)α̈] + b(½ + a)L`` (no flap).

    Parameters
    ----------
    a : float
        Elastic axis [semichords from mid-chord].
    rho, b, u : float
        Density [kg/m³], semichord [m], free-stream speed [m/s].
    d : float, optional
        Flap hinge [semichords from mid-chord]; ``None`` (default) gives the 2-DOF (h, α) operator.

    Returns
    -------
    TheodorsenOperator
        Loads ``[L (up), M_EA (nose up), H (TE down)]`` per unit span.
    """
    pi = np.pi
    rb2 = rho * b * b
    mass = -rb2 * np.array([[-pi, pi * b * a], [-a * pi * b, pi * b * b * (0.125 + a * a)]])
    damping = -rb2 * np.array([[0.0, -u * pi], [0.0, pi * (0.5 - a) * u * b]])
    stiffness = np.zeros((2, 2))
    circulation = np.array([2.0 * pi * rho * u * b, 2.0 * pi * rho * u * b * b * (a + 0.5)])
    displacement = np.array([0.0, u])
    rate = np.array([1.0, b * (0.5 - a)])
    if d is not None:
        t = theodorsen_constants(a, d)
        flap_mass = -rb2 * np.array([t.T1 * b, -(t.T7 + (d - a) * t.T1) * b * b])
        flap_damping = -rb2 * np.array([u * t.T4, (t.T1 - t.T8 - (d - a) * t.T4 + 0.5 * t.T11) * u * b])
        flap_stiffness = -rb2 * np.array([0.0, (t.T4 + t.T10) * u * u])
        hinge_mass = -rb2 * np.array([-t.T1 * b, 2.0 * t.T13 * b * b, -t.T3 * b * b / pi])
        hinge_damping = -rb2 * np.array(
            [0.0, (-2.0 * t.T9 - t.T1 + t.T4 * (a - 0.5)) * u * b, -u * b * t.T4 * t.T11 / (2.0 * pi)]
        )
        hinge_stiffness = -rb2 * np.array([0.0, 0.0, u * u * (t.T5 - t.T4 * t.T10) / pi])
        mass = np.vstack([np.column_stack([mass, flap_mass]), hinge_mass])
        damping = np.vstack([np.column_stack([damping, flap_damping]), hinge_damping])
        stiffness = np.vstack([np.column_stack([stiffness, flap_stiffness]), hinge_stiffness])
        circulation = np.append(circulation, -rho * u * b * b * t.T12)
        displacement = np.append(displacement, t.T10 * u / pi)
        rate = np.append(rate, b * t.T11 / (2.0 * pi))
    return TheodorsenOperator(mass, damping, stiffness, circulation, displacement, rate)


def theodorsen_load_matrix(
    k: ArrayLike,
    a: float,
    rho: float,
    b: float,
    u: float,
    d: float | None = None,
    *,
    quasi_steady: bool = False,
) -> NDArray[np.complex128]:
    """Harmonic load matrix ``[L, M_EA(, H)]ᵀ = Λ(k) q̂`` of Theodorsen's exact theory.

    Source: Theodorsen, NACA Rep. 496 (1935); Hodges & Pierce (2011) ch. 5; test values reference §1.7.
    With ``quasi_steady=True`` the wake is dropped, ``C ≡ 1`` (apparent-mass terms kept), which is the
    paper's quasi-steady model (``λ0 = 0`` in eq. 25).

    Parameters
    ----------
    k : array_like, shape (...)
        Reduced frequency ``ω b / U`` >= 0.
    a, rho, b, u, d
        As in :func:`theodorsen_operator`.
    quasi_steady : bool, keyword-only
        Use ``C = 1``.

    Returns
    -------
    ndarray of complex, shape (..., n, n)
        ``n = 2`` (``q̂ = [ĥ, α̂]``) or ``3`` (``[ĥ, α̂, β̂]``); rows in N/m, N, N per unit ``q``.
    """
    op = theodorsen_operator(a, rho, b, u, d)
    k_arr = np.asarray(k, dtype=float)
    c_k = np.asarray(theodorsen_function(k_arr))  # also validates k
    if quasi_steady:
        c_k = np.ones_like(c_k)
    p = (1j * k_arr * u / b)[..., None, None]
    downwash = op.downwash_displacement + p * op.downwash_rate
    circulatory = c_k[..., None, None] * op.circulation[:, None] * downwash
    return p * p * op.mass + p * op.damping + op.stiffness + circulatory
