"""The NASA GTM T2 wind-tunnel pitch data bundled with the notional GTM, in full-scale chord fractions.

Source: ``flexsim/aircraft/data/sources/t2_aero_basic_beta0.csv`` (NASA ``GTM_DesignSim``, the T2's polynomial
aerodynamic database at beta = 0; its header names the file and the reference geometry of
``AC_baseparams_T2.m``: S = 5.9018 ft^2, c-bar = 0.9153 ft, LEMAC 4.5462 ft, Cm about 25 % c-bar, CG at 21.99 %
c-bar), scaled to full size by 1/0.055 (``flexsim/aircraft/data/sources/gtm-notional.md`` sec. 2a). Used by the
static-margin test and docs/options.md to compare the model's neutral point with the aircraft's measured one, and
for the end of the linear lift range, the GTM's ``[aero] max_alpha_deg`` (:func:`t2_linear_alpha_limit_deg`).
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np

T2_CSV = Path(__file__).parent / "data" / "sources" / "t2_aero_basic_beta0.csv"
#: Scale of the T2 model (5.5 %).
T2_SCALE = 0.055
#: Full-scale reference chord c-bar [m] (T2: 0.9153 ft).
CBAR_M = 0.9153 * 0.3048 / T2_SCALE
#: Full-scale leading edge of the mean aerodynamic chord, aft of the nose [m] (T2: 4.5462 ft from the T2's
#: reference station, whose nose is 8.745 in ahead of it).
LEMAC_M = (4.5462 - 8.745 / 12) * 0.3048 / T2_SCALE
#: The T2's own CG [fraction of c-bar] (AC_baseparams_T2.m).
T2_CG_CBAR = 0.2199
#: Reference point of the T2's Cm [fraction of c-bar].
T2_CM_REFERENCE_CBAR = 0.25


class T2Pitch(NamedTuple):
    """Pitch derivatives of the T2 database, fitted over alpha = 0..6 deg."""

    cm_alpha_per_rad: float  # dCm/dalpha about 25 % c-bar [1/rad]
    cn_alpha_per_rad: float  # dCN/dalpha, CN = -CZ [1/rad]
    neutral_point_cbar: float  # 0.25 - Cm_alpha / CN_alpha [fraction of c-bar]


def _table() -> np.ndarray:
    """The CSV's columns alpha_deg [deg], CX, CZ, Cm [-], shape (4, n)."""
    lines = [ln for ln in T2_CSV.read_text(encoding="utf-8").splitlines() if ln and not ln.startswith("#")]
    if lines[0] != "alpha_deg,CX,CZ,Cm":
        raise ValueError(f"{T2_CSV}: unexpected columns {lines[0]!r} (expected alpha_deg,CX,CZ,Cm)")
    return np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]]).T


def t2_pitch(alpha_range_deg: tuple[float, float] = (0.0, 6.0)) -> T2Pitch:
    """Least-squares slopes of Cm and CN = -CZ in alpha [rad] over ``alpha_range_deg`` and the neutral point
    0.25 - Cm_alpha/CN_alpha (Etkin & Reid 1996, sec. 2.3) [fraction of c-bar]."""
    alpha_deg, _, cz, cm = _table()
    sel = (alpha_deg >= alpha_range_deg[0]) & (alpha_deg <= alpha_range_deg[1])
    cm_a = float(np.polyfit(np.radians(alpha_deg[sel]), cm[sel], 1)[0])
    cn_a = float(np.polyfit(np.radians(alpha_deg[sel]), -cz[sel], 1)[0])
    return T2Pitch(cm_a, cn_a, T2_CM_REFERENCE_CBAR - cm_a / cn_a)


def cbar_fraction(x_aft_of_nose_m: float) -> float:
    """A full-scale fuselage station [m aft of the nose] as a fraction of the T2's c-bar from its LEMAC."""
    return (x_aft_of_nose_m - LEMAC_M) / CBAR_M


def t2_linear_alpha_limit_deg(tolerance: float = 0.10, fit_range_deg: tuple[float, float] = (0.0, 6.0)) -> tuple[float, float]:
    """End of the T2's linear lift range: the largest tabulated alpha [deg] up to which the normal-force
    coefficient CN = -CZ stays within ``tolerance`` (relative) of its least-squares line over ``fit_range_deg``
    (the range of :func:`t2_pitch`), and CN's relative shortfall there [-].

    With the defaults: 11 deg (CN 8.2 % below the line; 12.6 % at 12 deg, where the slope between the tabulated
    points has fallen to 38 % of the linear one): beyond it a linear (no-stall) model's lift is more than 10 % too
    high. The database stops at alpha = -5 deg on the negative side (within 0.1 % of the line there).
    """
    alpha_deg, _, cz, _ = _table()
    cn = -cz
    sel = (alpha_deg >= fit_range_deg[0]) & (alpha_deg <= fit_range_deg[1])
    line = np.polyval(np.polyfit(alpha_deg[sel], cn[sel], 1), alpha_deg)
    shortfall = 1.0 - cn / line
    above = alpha_deg > fit_range_deg[1]
    beyond = np.flatnonzero(above & (np.abs(shortfall) > tolerance))
    if beyond.size == 0:
        raise ValueError(f"{T2_CSV}: CN within {tolerance:.0%} of its line up to the last alpha tabulated")
    last = int(np.flatnonzero(above & (alpha_deg < alpha_deg[beyond[0]]))[-1])
    return float(alpha_deg[last]), float(shortfall[last])
