"""Figures of docs/options.md and docs/design.md, for ``regenerate_docs_figures.py``."""

from __future__ import annotations


import numpy as np
from docs_figures_static import _cruise_trim, _turn_trim
from figure_text import exponent, figure, num

from flexsim.aero.lift_slopes import exposed_lift_slope, vlm_surfaces  # noqa: E402
from flexsim.aero.vlm import solve_vlm  # noqa: E402
from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.atmosphere import isa_density, speed_of_sound  # noqa: E402
from flexsim.model.aircraft_model import AircraftModel  # noqa: E402
from flexsim.model.coupling import AeroOptions  # noqa: E402


# --- docs/options.md ---------------------------------------------------------------------------------------------

def _small(x: float, unit: str, floor: float = 1e-9) -> str:
    """A drift: ``0``, ``below 1e-9`` (round-off, whose digits vary with the platform) or ``2.5e-6`` with ``unit``."""
    sep = "" if unit == "°" else " "
    if x == 0.0:
        return f"0{sep}{unit}"
    if abs(x) < floor:
        return f"below {exponent(floor)}{sep}{unit}"
    return f"{exponent(x, '.1e')}{sep}{unit}"


@figure(fast=False)
def options_turn_hold() -> str:
    """``python studies/coordinated_turn.py``'s 30 s hold of the coordinated turn's trim controls (unsteady)."""
    import coordinated_turn

    from flexsim.trimming import SteadyManoeuvre

    point, _ = _turn_trim(True)
    man = SteadyManoeuvre.turn(9144.0, 5000.0, mach=0.78, coordinated=True)
    duration = 30.0
    h = coordinated_turn.hold_trim(load_aircraft("gtm"), point, man, duration, "unsteady")
    if h.status != "completed":
        raise RuntimeError(f"options-turn-hold: the hold ended {h.status}")
    return (f"holds the trim's controls for {duration:g} s with the nonlinear model and unsteady aerodynamics "
            f"({h.method}, `simulate`'s default): altitude drift {_small(h.altitude_drift_m, 'm')}, bank drift "
            f"{_small(h.bank_drift_deg, '°')}, heading rate {h.heading_rate_rad_s:.6f} rad/s against V/R = "
            f"{h.v_over_r_rad_s:.6f} rad/s")


def options_t2() -> str:
    """The T2's pitch derivatives, neutral point and margin against the default GTM's CG and neutral point (cruise
    trim at 9144 m, M 0.78), in T2 c-bar fractions."""
    from flexsim.aircraft.t2_data import CBAR_M, T2_CG_CBAR, cbar_fraction, t2_pitch

    gtm, t2 = load_aircraft("gtm"), t2_pitch()
    _, margin = _cruise_trim(9144.0, 0.78)
    (fuselage,) = [c for c in gtm.components if c.name == "fuselage"]
    x_cg = fuselage.length_m - AircraftModel(gtm, aero="quasi-steady").structure.mass_properties.cg_m[0]  # aft of the nose
    cg, neutral = cbar_fraction(x_cg), cbar_fraction(x_cg + margin.neutral_point_aft_of_cg_m)
    return (f"has Cm_α = {num(t2.cm_alpha_per_rad, '.3f')} and CN_α = {t2.cn_alpha_per_rad:.3f} per radian (α = 0-6°) "
            f"about 25 % of its reference chord c̄ ({CBAR_M:.3f} m at full scale), a neutral point at "
            f"{100 * t2.neutral_point_cbar:.1f} % c̄ and a margin of {100 * (t2.neutral_point_cbar - T2_CG_CBAR):.0f} % at its "
            f"own CG ({100 * T2_CG_CBAR:.2f} % c̄). The model's CG is at {100 * cg:.1f} % c̄ and its neutral point at "
            f"{100 * neutral:.1f} % c̄: {100 * (t2.neutral_point_cbar - neutral):.1f} % c̄ ahead of the T2's")


def options_mean_chord() -> str:
    """Mean aerodynamic chord of the exposed right wing's strips (``flexsim/trimming/margin.py``), cruise trim."""
    return f"{_cruise_trim(9144.0, 0.78)[1].mean_chord_m:.2f} m"


def options_cg_shift() -> str:
    """How far aft the CG would move for a 25 % margin at the cruise trim (same neutral point and mean chord)."""
    margin = _cruise_trim(9144.0, 0.78)[1]
    return f"{margin.neutral_point_aft_of_cg_m - 0.25 * margin.mean_chord_m:.2f} m"


#: Wing reference area of the GTM [m^2] (the paper's; ``tools/make_gtm_toml.py``), for C_D0 and C_L.
GTM_WING_AREA_M2 = 181.25
#: OpenAP's drag polar of the 757-200, C_D = C_D0 + k C_L^2 (Sun, Hoekstra & Ellerbroek 2020;
#: openap/data/dragpolar/b752.yml), quoted in docs/options.md for comparison.
OPENAP_B752_CD0, OPENAP_B752_K = 0.021, 0.049


def options_gtm_polar() -> str:
    """The bundled gtm's total drag area and C_D0 (the sum of its ``[[aero.drag]]`` items)."""
    f = sum(item.drag_area_m2 for item in load_aircraft("gtm").aero_settings.drag)
    return f"f = {f:.3f} m², C_D0 = {f / GTM_WING_AREA_M2:.4f} on {GTM_WING_AREA_M2:g} m²"


def options_openap() -> str:
    """OpenAP's 757-200 polar at the cruise trim's lift coefficient (9144 m, M 0.78)."""
    from flexsim.atmosphere import isa_density, mach_to_true_airspeed

    s, _ = _cruise_trim(9144.0, 0.78)
    v = float(mach_to_true_airspeed(0.78, 9144.0))
    cl = 1e3 * s["lift_kN"] / (0.5 * float(isa_density(9144.0)) * v * v * GTM_WING_AREA_M2)
    return (f"C_D0 = {OPENAP_B752_CD0}, k = {OPENAP_B752_K}) gives L/D = "
            f"{cl / (OPENAP_B752_CD0 + OPENAP_B752_K * cl * cl):.1f} at the GTM's cruise C_L = {cl:.2f} (9144 m, M 0.78)")


def options_munk_items() -> str:
    """Volumes and k2 - k1 of the bundled gtm's Munk bodies (``flexsim.model.bodies.spheroid_apparent_mass``)."""
    from flexsim.model.bodies import spheroid_apparent_mass

    bodies = {b.name: b for b in load_aircraft("gtm").aero_settings.bodies}
    fus, nac = bodies["fuselage"], bodies["right_nacelle"]

    def dk(b) -> float:
        k1, k2 = spheroid_apparent_mass(b.length_m / b.diameter_m)
        return float(k2 - k1)

    return (f"fuselage {fus.length_m:g} m × Ø {fus.diameter_m:g} m, Vol = 0.8 × π D² L / 4 = {fus.volume_m3:.1f} m³ "
            f"(prismatic coefficient 0.8, an estimate), k₂ − k₁ = {dk(fus):.3f}; nacelles {nac.length_m:g} m × "
            f"Ø {nac.diameter_m:g} m, {nac.volume_m3:.1f} m³ each (k₂ − k₁ = {dk(nac):.3f})")


# --- docs/design.md ------------------------------------------------------------------------------------------------

_SPEED = 70.0  # [m/s] sea level, M 0.21 (tests/model/test_gtm_aero.py)
_ALPHA, _DALPHA = 0.03, 0.02  # [rad] central difference of the lift about this incidence


def _strip_lift_slope(downwash: bool) -> float:
    """dCL/dalpha [1/rad] on S_ref of the quasi-rigid gtm's strips (quasi-steady), from the model's generalized forces."""
    model = AircraftModel(load_aircraft("gtm"), variant="quasi-rigid", aero=AeroOptions(model="quasi-steady", downwash=downwash),
                          gravity_m_s2=0.0)
    lift = []
    for alpha in (_ALPHA - _DALPHA, _ALPHA + _DALPHA):
        vel = np.zeros(model.structure.dofs.n_v)
        vel[0:3] = _SPEED * np.array([np.cos(alpha), 0.0, np.sin(alpha)])
        _, f = model.generalized_forces(model.pack(position_m=[0.0, 0.0, 0.0], velocity=vel), np.zeros(4))
        lift.append(-f[2] * np.cos(alpha) + f[0] * np.sin(alpha))
    q_dyn = 0.5 * isa_density(0.0) * _SPEED**2
    return (lift[1] - lift[0]) / (2 * _DALPHA) / (q_dyn * GTM_WING_AREA_M2)


def design_lift_slope() -> str:
    """The strips' lift slope (without and with the file's tail downwash) against the lattice's on the same exposed
    surfaces, dCL/dalpha [1/rad] on S_ref at 70 m/s, sea level; Prandtl-Glauert on the lattice as on the strips."""
    aircraft = load_aircraft("gtm")
    beta = np.sqrt(1.0 - (_SPEED / speed_of_sound(0.0)) ** 2)
    exposed = exposed_lift_slope(aircraft, solve_vlm(vlm_surfaces(aircraft), mach=0.0, s_ref_m2=GTM_WING_AREA_M2)) / beta
    strips, with_downwash = _strip_lift_slope(False), _strip_lift_slope(True)
    return (f"{abs(strips / exposed - 1.0) * 100:.2f} % ({strips:.3f} vs {exposed:.3f} /rad on S_ref at M "
            f"{_SPEED / speed_of_sound(0.0):.2f}, sea level, without the file's tail downwash, which the lattice "
            f"holds already; with it the strips' is {with_downwash:.3f} /rad)")


def design_cla_peak() -> str:
    """Where the right wing's sectional lift slope (incompressible lattice, ``flexsim aero gtm``) peaks."""
    vlm = solve_vlm(vlm_surfaces(load_aircraft("gtm")), mach=0.0, s_ref_m2=GTM_WING_AREA_M2)
    wing = vlm.surface("right_wing")
    outboard = wing.eta > 0.0
    eta = wing.eta[outboard][np.argmax(wing.cl_alpha_per_rad[outboard])]
    if not 0.5 < eta < 1.0:
        raise RuntimeError(f"design-cla-peak: the sectional lift slope peaks at {eta:.2f} of the semispan, not "
                           f"outboard; rewrite the sentence of docs/design.md")
    return f"near {100 * eta:.0f} % of the semispan"
