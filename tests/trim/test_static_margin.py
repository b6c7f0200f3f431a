"""Static margin (issue 11): the neutral point is the point about which the pitching moment does not change
with the angle of attack (Etkin & Reid 1996, sec. 2.3).

Bound and source. The bundled GTM (fuselage and nacelle Munk moments, DATCOM tail downwash; docs/options.md) at
9144 m, M 0.78 puts the neutral point 1.41 m = 27.7 % of the exposed wing's mean chord (5.09 m) behind the CG.
The issue's range for a transport is 5-25 %; the GTM's own public wind-tunnel database (NASA T2, bundled as
flexsim/aircraft/data/sources/t2_aero_basic_beta0.csv) puts the neutral point at 25 % - Cm_alpha/CN_alpha =
57.1 % of its reference chord, i.e. a margin of 34 % at the model's CG (22.7 % of that chord). The test asserts
a stable margin no larger than the T2's (0.05 <= h_n - h <= T2) and the neutral point within 10 % of the chord
of the T2's; the paper's aircraft (strips only) had 59 % and fails both.
"""

from pathlib import Path

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.trim import SteadyManoeuvre, trim
from flexsim.trim.margin import static_margin

import flexsim.aircraft

T2_CSV = Path(flexsim.aircraft.__file__).parent / "data" / "sources" / "t2_aero_basic_beta0.csv"
#: T2 reference chord and leading edge of the mean aerodynamic chord at full scale (T2 x 1/0.055;
#: flexsim/aircraft/data/sources/gtm-notional.md sec. 2a: c = 5.072 m, LEMAC 21.16 m aft of the nose).
CBAR_M, LEMAC_M, LENGTH_M = 0.9153 * 0.3048 / 0.055, (4.5462 - 8.745 / 12) * 0.3048 / 0.055, 44.35


def t2_neutral_point() -> float:
    """Neutral point of the T2 database [fraction of its reference chord]: 0.25 - dCm/dCN over alpha 0..6 deg."""
    lines = [ln for ln in T2_CSV.read_text(encoding="utf-8").splitlines() if ln and not ln.startswith("#")]
    assert lines[0] == "alpha_deg,CX,CZ,Cm"
    alpha_deg, _, cz, cm = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]]).T
    sel = (alpha_deg >= 0) & (alpha_deg <= 6)
    cm_a = np.polyfit(np.radians(alpha_deg[sel]), cm[sel], 1)[0]
    cn_a = np.polyfit(np.radians(alpha_deg[sel]), -cz[sel], 1)[0]
    return 0.25 - cm_a / cn_a


def _neutral_point_and_cg(options: AeroOptions) -> tuple[float, float, float]:
    model = AircraftModel(load_aircraft("gtm"), aero=options)
    margin = static_margin(model, trim(model, SteadyManoeuvre.level(9144.0, mach=0.78)))
    x_cg = LENGTH_M - model.structure.mass_properties.cg_m[0]  # aft of the nose [m]; o is the tail end
    np_ref = (x_cg + margin.neutral_point_aft_of_cg_m - LEMAC_M) / CBAR_M
    return margin.fraction_of_mac, np_ref, (x_cg - LEMAC_M) / CBAR_M


def test_gtm_static_margin_between_a_transport_and_its_wind_tunnel_data():
    t2 = t2_neutral_point()
    assert t2 == pytest.approx(0.571, abs=0.002) and CBAR_M == pytest.approx(5.072, abs=1e-3)
    margin, neutral, cg = _neutral_point_and_cg(AeroOptions("quasi-steady"))
    assert cg == pytest.approx(0.227, abs=0.002)  # the T2's own CG is at 21.99 % (AC_baseparams_T2.m)
    assert 0.05 <= margin <= t2 - cg and abs(neutral - t2) <= 0.10
    strips_only, neutral_strips, _ = _neutral_point_and_cg(AeroOptions("quasi-steady", body_moments=False, downwash=False))
    assert strips_only > t2 - cg and neutral_strips - t2 > 0.10  # the paper's aircraft: 59 %


def test_moment_about_the_neutral_point_is_independent_of_alpha():
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.78))
    margin = static_margin(model, point)
    assert 0.2 < margin.fraction_of_mac < 0.35 and margin.mean_chord_m == pytest.approx(5.09, abs=0.01)
    lay = model.layout
    cg = model.structure.mass_properties.cg_m
    neutral = cg - np.array([margin.neutral_point_aft_of_cg_m, 0.0, 0.0])  # aft = -x in body axes
    about_np, about_cg = [], []
    for dw in (-0.5, 0.5):
        x = point.x.copy()
        x[lay.v.start + 2] += dw
        f = model.aerodynamic_force(x, point.u)
        about_np.append((f[3:6] - np.cross(neutral, f[0:3]))[1])
        about_cg.append((f[3:6] - np.cross(cg, f[0:3]))[1])
    # the moment change about the neutral point vanishes up to the drag change's arm (the NP is located along
    # body x only; the CG is 0.58 m below o): below 1 % of the change about the CG
    assert abs(about_np[1] - about_np[0]) < 0.01 * abs(about_cg[1] - about_cg[0])
    assert static_margin(model, point, dw_m_s=0.05).neutral_point_aft_of_cg_m == pytest.approx(margin.neutral_point_aft_of_cg_m, rel=1e-3)
