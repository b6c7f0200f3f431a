"""The horizontal tail's downwash lag (the alpha-dot term): its switch, its data and its entries of E, compiled (not in
the paper; off by default: on with ``Terms(aero_terms=(DownwashLag(),))``, :attr:`flexsim.model.terms.Terms.aero_terms`).

The wing's downwash reaches the horizontal tail after the wake's travel time tau = l_t / V, so the tail sees the
downwash of the wing's angle of attack a moment earlier: epsilon(t) = (d epsilon/d alpha) alpha(t - tau), and to first
order the tail's angle of attack is larger by (d epsilon/d alpha) tau alpha_dot than with the instantaneous downwash
of :mod:`~flexsim._kernels.downwash`. This is the tail's contribution to the alpha-dot derivatives

    C_L_alpha_dot = 2 a_t V_H (d epsilon/d alpha),   C_m_alpha_dot = -2 a_t V_H (l_t / c_bar) (d epsilon/d alpha)

(alpha_dot made nondimensional by c_bar / 2V; a_t the tail's lift slope on its area S_t, V_H = S_t l_t / (S c_bar)
the tail volume ratio): Etkin & Reid, *Dynamics of Flight: Stability and Control*, 3rd ed., 1996, ch. 5, the
alpha_dot derivatives; the tail term of the USAF DATCOM (Hoak et al. 1978) sec. 7.4.4. With alpha_dot = w_dot / V
(body axes, small angles) the dynamic pressure cancels and the term is an apparent mass of w_dot: each horizontal-tail
strip j (chord c_j = 2 b_j, width w_j, incompressible lift slope Cl_a0,j, n_j . z_body = nz_j) carries the lift

    dL_j = rho / beta^2 k_j w_dot,   k_j = 1/2 c_j w_j Cl_a0,j nz_j (d epsilon/d alpha)_0 l_t   [m^3]

along -n_j at its elastic-axis point, whose generalized force by virtual work (eqs. 17-24) is -dL_j (n^T A)_j^T with
(n^T A)_j the strip's plunge map at q = 0 (:class:`~flexsim._kernels.strips.StripData` ``proj_n0``). Moved to the
left-hand side: E[:, 2] += rho / beta^2 sum_j k_j (n^T A)_j^T (column 2 of V = [v, omega, s, eta] is w). One beta
is the tail's Prandtl-Glauert factor, the other the DATCOM scaling of the downwash gradient with the wing's lift
slope (as in :mod:`~flexsim._kernels.downwash`), at the Mach number of the air state. l_t [m] is the distance along
body x from the wing's to the tail's lift-weighted quarter chords (the wake's path). The gradient
(d epsilon/d alpha)_0 is the aircraft file's ``[aero] downwash_gradient``; the term exists only where the downwash
does (physical formulation, ``AeroOptions(downwash=True)``). Not modelled: the lag's dependence on the deformation
(the maps at q = 0) and on the pitch rate. Body axes, SI units, radians.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from flexsim._kernels.layout import _f1, _f2, _flag, kernel, packed, term_data
from flexsim._kernels.strips import PRANDTL_GLAUERT, PROJ_N0, compressibility_factor, strip_mach


@dataclasses.dataclass(frozen=True)
class DownwashLag:
    """The switch of the horizontal tail's downwash lag (module docstring): a model has the term when its
    ``Terms(aero_terms=...)`` holds a ``DownwashLag()``. No options: the gradient (d epsilon/d alpha)_0 is the aircraft
    file's ``[aero] downwash_gradient`` and the arm l_t the strips'."""


@term_data
@dataclasses.dataclass(frozen=True)
class DownwashLagData:
    """The horizontal tail's downwash lag (module docstring), switched by :class:`DownwashLag`."""

    #: The term's options class (the switch, :attr:`flexsim.model.terms.Terms.aero_terms`).
    options = DownwashLag

    downwash_lag_k: np.ndarray = packed(1, "k_j = 1/2 c_j w_j Cl_a0,j nz_j (d eps/d alpha)_0 l_t (n_s,) [m^3], 0 off the tail")
    has_downwash_lag: int = packed(0, "1 with the downwash lag", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): k_j of its horizontal-tail
        strips from its strip coupling (``model.aero``) when its terms hold a :class:`DownwashLag`.

        Raises ValueError when the switch is on and the model has no downwash at the tail to lag (no wing or no
        horizontal tail, a zero ``downwash_gradient``, ``AeroOptions(downwash=False)`` or the paper's formulation).
        """
        if model.terms.aero_term(DownwashLag) is None:
            return dict(has_downwash_lag=False)
        a = model.aero
        if a is None or a.downwash_gradient == 0.0:
            raise ValueError("aero_terms: DownwashLag(): this model has no wing downwash at the horizontal tail to lag (it needs "
                             "a wing and a horizontal tail, the aircraft file's [aero] downwash_gradient > 0, "
                             "AeroOptions(downwash=True) and the physical formulation)")
        s = a.strips
        chord_x = np.einsum("sji,sj->si", a.strip_dcm, s.d)[:, 0]  # body-x component of the chord direction (C_i^T d)
        x_qc = s.position_body_m[:, 0] - (s.a + 0.5) * s.semichord_m * chord_x  # quarter chord, body x [m]
        tail_weight = s.lift_slope0 * s.semichord_m * s.width_m * a.dw_tail_nz  # zero off the tail
        l_t = float(a.dw_wing_weight @ x_qc - tail_weight @ x_qc / tail_weight.sum())
        k = 0.5 * 2.0 * s.semichord_m * s.width_m * s.lift_slope0 * a.dw_tail_nz * a.downwash_gradient * l_t
        return dict(downwash_lag_k=k, has_downwash_lag=True)


DOWNWASH_LAG_K = DownwashLagData.index["downwash_lag_k"]
HAS_DOWNWASH_LAG = DownwashLagData.index["has_downwash_lag"]


@kernel
def downwash_lag_mass(F, I, air, m):
    """m[:, 2] += rho / beta^2 sum_j k_j (n^T A)_j^T (module docstring): air (rho [kg/m^3], Mach [-], a [m/s]), the air
    state of :func:`flexsim._kernels.state.air_state`; m (n_v, n_v) E, added to in place [kg, kg m]."""
    if not _flag(I, HAS_DOWNWASH_LAG):
        return
    beta = compressibility_factor(_flag(I, PRANDTL_GLAUERT) != 0, strip_mach(F, I, air[1]))
    scale = air[0] / (beta * beta)
    k = _f1(F, I, DOWNWASH_LAG_K)
    pn0 = _f2(F, I, PROJ_N0)
    for j in range(k.shape[0]):
        if k[j] != 0.0:
            c = scale * k[j]
            for i in range(m.shape[0]):
                m[i, 2] += c * pn0[j, i]
