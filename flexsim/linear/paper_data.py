"""Published results of Tuzcu & Nguyen (2014), Tables 2 and 3 (steady level flight at flutter).

Columns: altitude h [m], flutter Mach M_F, flutter frequency omega_F [rad/s], pitch theta [deg], thrust
T_e [kN], elevator delta_e [deg], wing-tip bending w_w(L_w) [m] and torsion psi_w(L_w) [deg]. Also the
glide point quoted in the text (9144 m: gamma = -3.12 deg, M_F = 0.7787, omega_F = 34.939 rad/s).
"""

from __future__ import annotations

__all__ = ["TABLE_QS", "TABLE_US", "COLUMNS", "GLIDE_9144", "PAPER_TREND_SIGNS", "paper_crossover_altitude_m"]

COLUMNS = ("altitude_m", "mach", "omega_rad_s", "theta_deg", "thrust_kN", "elevator_deg", "tip_deflection_m", "tip_twist_deg")

#: Table 2: flutter using the quasi-steady theory (QS).
TABLE_QS = (
    (0.0, 0.6851, 15.604, 1.1461, 17.791, -3.6194, -1.0794, 1.1745),
    (3048.0, 0.7451, 35.228, 1.3449, 20.876, -4.0749, -1.0370, 1.1497),
    (6096.0, 0.7227, 35.305, 2.4763, 38.430, -6.6427, -0.9138, 1.0809),
    (9144.0, 0.7329, 35.321, 3.8298, 59.408, -9.6013, -0.8549, 1.0518),
)

#: Table 3: flutter using the unsteady theory (US, Theodorsen wake at flutter).
TABLE_US = (
    (0.0, 0.6742, 17.773, 1.2209, 18.951, -3.7906, -1.0621, 1.1643),
    (3048.0, 0.7433, 34.923, 1.3589, 21.093, -4.1069, -1.0344, 1.1483),
    (6096.0, 0.7565, 34.930, 2.0867, 32.386, -5.7663, -0.9427, 1.0965),
    (9144.0, 0.7791, 34.936, 3.0625, 47.519, -7.9412, -0.8827, 1.0650),
)

#: Glide at 9144 m read from the climb study (paper text): gamma [deg], M_F, omega_F [rad/s].
GLIDE_9144 = (-3.12, 0.7787, 34.939)


def _trend_signs() -> dict:
    """The paper's trend signs, from its text to Figs. 7-10 and 12-15 (page 21-22 of the accepted manuscript).

    Turns: "M_F decreases while omega_F increases as R increases for all altitudes except the sea level
    altitude at which M_F increases while omega_F decreases with R for the US model, and both M_F and
    omega_F remain almost unchanged with R for the QS model." Climbs: "M_F increases while omega_F
    decreases as gamma increases for all of the altitudes" (both models). Key: (kind, "dM_F" or
    "domega_F", model, altitude [m]) -> -1, 0 or +1.
    """
    out = {}
    for h in (0.0, 3048.0, 6096.0, 9144.0):
        for model in ("QS", "US"):
            if h == 0.0:
                m, w = (1, -1) if model == "US" else (0, 0)
            else:
                m, w = -1, 1
            out[("turn", "dM_F", model, h)] = m
            out[("turn", "domega_F", model, h)] = w
            out[("climb", "dM_F", model, h)] = 1
            out[("climb", "domega_F", model, h)] = -1
    return out


#: The paper's trend signs (see :func:`_trend_signs`); for comparison beside computed trends only.
PAPER_TREND_SIGNS = _trend_signs()


def paper_crossover_altitude_m() -> float:
    """Altitude [m] where the paper's M_F(US) - M_F(QS) changes sign, interpolated in Tables 2-3 (display only)."""
    diff = [(us[0], us[1] - qs[1]) for qs, us in zip(TABLE_QS, TABLE_US)]
    for (h0, d0), (h1, d1) in zip(diff[:-1], diff[1:]):
        if d0 * d1 < 0:
            return h0 + (h1 - h0) * d0 / (d0 - d1)
    raise AssertionError("the paper's tables have a crossover between 3048 and 6096 m")
