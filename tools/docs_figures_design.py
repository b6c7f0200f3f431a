"""Figures of docs/design.md that no other module computes, for ``regenerate_docs_figures.py``.

Each function returns the text of one ``<!-- figures:NAME -->`` region; the registry and the command are in
``tools/regenerate_docs_figures.py``. ``tests/model/test_gtm_aero.py`` checks the same comparison independently.
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from flexsim.aero.lift_slopes import exposed_lift_slope, vlm_surfaces  # noqa: E402
from flexsim.aero.vlm import solve_vlm  # noqa: E402
from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.atmosphere import isa_density, speed_of_sound  # noqa: E402
from flexsim.model.aircraft_model import AircraftModel  # noqa: E402
from flexsim.model.coupling import AeroOptions  # noqa: E402

_SPEED = 70.0  # [m/s] sea level, M 0.21 (tests/model/test_gtm_aero.py)
_S_REF = 181.25  # [m^2] GTM reference area (flexsim/aircraft/data/sources/gtm-notional.md 2a)
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
    return (lift[1] - lift[0]) / (2 * _DALPHA) / (q_dyn * _S_REF)


@functools.cache
def _lift_slopes() -> tuple[float, float, float, float]:
    """(strips without the tail downwash, strips with the file's, lattice on the exposed surfaces, whole lattice),
    dCL/dalpha [1/rad] on S_ref at 70 m/s, sea level; Prandtl-Glauert on the lattice as on the strips."""
    aircraft = load_aircraft("gtm")
    beta = np.sqrt(1.0 - (_SPEED / speed_of_sound(0.0)) ** 2)
    vlm = solve_vlm(vlm_surfaces(aircraft), mach=0.0, s_ref_m2=_S_REF)
    return (_strip_lift_slope(False), _strip_lift_slope(True), exposed_lift_slope(aircraft, vlm) / beta,
            vlm.lift_slope_per_rad / beta)


def design_lift_slope() -> str:
    """The strips' lift slope against the lattice's on the same exposed surfaces."""
    strips, with_downwash, exposed, _ = _lift_slopes()
    return (f"{abs(strips / exposed - 1.0) * 100:.2f} % ({strips:.3f} vs {exposed:.3f} /rad on S_ref at M "
            f"{_SPEED / speed_of_sound(0.0):.2f}, sea level, without the file's tail downwash, which the lattice "
            f"holds already; with it the strips' is {with_downwash:.3f} /rad)")


def design_lift_slope_total() -> str:
    """The whole lattice's lift slope, carry-over across the fuselage included."""
    return f"{_lift_slopes()[3]:.2f} /rad"


def design_cla_peak() -> str:
    """Where the right wing's sectional lift slope (incompressible lattice, ``flexsim aero gtm``) peaks."""
    vlm = solve_vlm(vlm_surfaces(load_aircraft("gtm")), mach=0.0, s_ref_m2=_S_REF)
    wing = vlm.surface("right_wing")
    outboard = wing.eta > 0.0
    eta = wing.eta[outboard][np.argmax(wing.cl_alpha_per_rad[outboard])]
    if not 0.5 < eta < 1.0:
        raise RuntimeError(f"design-cla-peak: the sectional lift slope peaks at {eta:.2f} of the semispan, not "
                           f"outboard; rewrite the sentence of docs/design.md")
    return f"near {100 * eta:.0f} % of the semispan"


#: name -> (function, fast)
DESIGN_FIGURES = {"design-lift-slope": (design_lift_slope, True),
                  "design-lift-slope-total": (design_lift_slope_total, True),
                  "design-cla-peak": (design_cla_peak, True)}
