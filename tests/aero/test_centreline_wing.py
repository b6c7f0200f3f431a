"""A wing continuous through the centreline: both halves rooted at y = 0 (as the PHC HALE aircraft's).

* Invariant: the lattice of the two halves rooted at y = 0 (:func:`flexsim.aero.lift_slopes.vlm_surfaces`) is
  the lattice of one mirrored rectangular wing of the same planform and panels, so their lift slopes agree to
  round-off (1e-10 relative asserted; the influence sums run in a different order).
* The aircraft loads, builds a model and gives left-right symmetric strip slopes and mode pairs.
* A half whose planform crosses the centreline is refused with an error naming the component's ``root_m``; a
  planform the lattice cannot take (a half at 60 deg dihedral) with one naming the component and the way out.
"""

from __future__ import annotations

import numpy as np
import pytest

from flexsim.aero.lift_slopes import vlm_surfaces
from flexsim.aero.vlm import LiftingSurface, solve_vlm
from flexsim.aircraft.toml_loader import parse_aircraft
from flexsim.errors import AircraftDefinitionError
from flexsim.model.aircraft_model import AircraftModel
from flexsim.linear.modes import in_vacuo_modes

_HALF = """
[components.{name}]
root_m = [0.0, {y0}, 0.0]
euler_deg = [0.0, 0.0, {yaw}]
length_m = 16.0
bending_modes = 2
torsion_modes = 1
[components.{name}.aero]
strips = 8
lift_slope = "vlm"
[components.{name}.sections]
station_m = [0.0, 16.0]
mass_kg_per_m = [0.75, 0.75]
torsional_inertia_kg_m = [0.1, 0.1]
ei_nm2 = [2.0e4, 2.0e4]
gj_nm2 = [1.0e4, 1.0e4]
chord_m = [1.0, 1.0]
ea_fraction = [0.5, 0.5]
"""


def wing_toml(y_right: float = 0.0, y_left: float = 0.0) -> str:
    """A 32 m flying wing of two 16 m halves, chord 1 m, rooted at y_right and y_left (body axes)."""
    return ("schema_version = 1\nname = \"continuous wing\"\n" + _HALF.format(name="right_wing", y0=y_right, yaw=90.0)
            + _HALF.format(name="left_wing", y0=y_left, yaw=-90.0))


@pytest.fixture(scope="module")
def continuous():
    return parse_aircraft(wing_toml(), source="continuous.toml")


def test_lattice_of_two_halves_at_the_centreline_is_the_mirrored_wing(continuous):
    halves = vlm_surfaces(continuous)
    assert [s.name for s in halves] == ["right_wing", "left_wing"]
    assert all(s.le_m[0, 1] == 0.0 or s.le_m[-1, 1] == 0.0 for s in halves)  # no inboard extension added
    per_half = halves[0].n_spanwise
    mirrored = LiftingSurface("wing", np.array([[-0.5, 0.0, 0.0], [-0.5, 16.0, 0.0]]), np.array([1.0, 1.0]),
                              n_chordwise=halves[0].n_chordwise, n_spanwise=per_half, mirror=True)
    a, b = solve_vlm(halves, mach=0.0), solve_vlm([mirrored], mach=0.0)
    assert a.lift_slope_per_rad == pytest.approx(b.lift_slope_per_rad, rel=1e-10)
    y = np.linspace(0.5, 15.5, 7)
    right = a.surface("right_wing").lift_slope_at(y)
    assert right == pytest.approx(b.surface("wing").lift_slope_at(y), rel=1e-10)
    assert a.surface("left_wing").lift_slope_at(-y) == pytest.approx(right, rel=1e-10)


def test_the_continuous_wing_builds_a_model_with_symmetric_strips_and_clamped_modes(continuous):
    strips = AircraftModel(continuous, aero="quasi-steady").aero.strips
    component = np.array(strips.component)
    right, left = np.flatnonzero(component == "right_wing"), np.flatnonzero(component == "left_wing")
    assert right.size == left.size == 8
    slopes = np.asarray(strips.lift_slope0)
    assert np.all(np.isfinite(slopes)) and np.all(slopes > 0.0)
    assert np.sort(slopes[left]) == pytest.approx(np.sort(slopes[right]), rel=1e-9)
    # clamped at the root: Euler-Bernoulli cantilever (1.87510 / L)^2 sqrt(EI / m) = 2.24282 rad/s and uniform
    # torsion (pi / 2L) sqrt(GJ / I) = 31.0456 rad/s, once per half (the shape functions are the exact modes)
    omega = in_vacuo_modes(AircraftModel(continuous, variant="restrained")).frequencies_rad_s
    assert omega[:2] == pytest.approx([2.24282, 2.24282], rel=1e-5)
    assert omega[4:6] == pytest.approx([31.0456, 31.0456], rel=1e-5)


def test_a_half_crossing_the_centreline_is_refused_naming_its_root():
    aircraft = parse_aircraft(wing_toml(y_left=0.5), source="crossing.toml")
    with pytest.raises(AircraftDefinitionError, match=r"components\.left_wing\.root_m .*one side of y = 0"):
        AircraftModel(aircraft, aero="quasi-steady")


def test_a_continuous_wing_with_dihedral_is_on_the_centreline_despite_rounding():
    # with 10 deg dihedral the left half's root leading edge is at y ~ 1e-17 m (the axes' cosines), not exactly 0
    dihedral = wing_toml().replace("euler_deg = [0.0, 0.0, 90.0]", "euler_deg = [0.0, -10.0, 90.0]").replace(
        "euler_deg = [0.0, 0.0, -90.0]", "euler_deg = [0.0, 10.0, -90.0]")
    halves = vlm_surfaces(parse_aircraft(dihedral, source="dihedral.toml"))
    assert [s.le_m.shape[0] for s in halves] == [2, 2]  # root and tip: no inboard extension
    assert halves[0].le_m[0, 1] == 0.0 and halves[1].le_m[-1, 1] == 0.0


def test_a_planform_the_lattice_cannot_take_is_refused_naming_the_component():
    steep = wing_toml().replace("euler_deg = [0.0, 0.0, -90.0]", "euler_deg = [0.0, 60.0, -90.0]")
    aircraft = parse_aircraft(steep, source="steep.toml")
    with pytest.raises(AircraftDefinitionError, match=r"components\.left_wing: the vortex lattice .* cannot model its "
                                                      r"planform: segment dihedral must be within .*\"2pi\" or a number"):
        AircraftModel(aircraft, aero="quasi-steady")
