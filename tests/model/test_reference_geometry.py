"""The model's reference geometry (:mod:`flexsim.model.reference`): the wing's area, span, mean chord and mean
aerodynamic chord, computed once from its strips, against the closed forms of a trapezoidal wing and the GTM's
published values."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.reference import ReferenceGeometry
from flexsim.model.strips import StripSet


def _strips(chord_m: np.ndarray, width_m: np.ndarray, components) -> StripSet:
    """A StripSet carrying only what the reference geometry reads (component, semichord, width)."""
    n = len(components)
    zeros = np.zeros(n)
    values = {f.name: zeros for f in dataclasses.fields(StripSet)}
    return dataclasses.replace(StripSet(**values), component=tuple(components), semichord_m=chord_m / 2.0, width_m=width_m)


def test_trapezoidal_wing_closed_form():
    """A straight-tapered wing, root chord c_r, taper lambda, span b: S = b c_r (1 + lambda)/2, MAC = (2/3) c_r
    (1 + lambda + lambda^2)/(1 + lambda) (Etkin & Reid 1996 sec. 2.3); the strip sums converge as the strips
    narrow (midpoint rule, error O(1/n^2): 1e-5 relative at 400 strips per half)."""
    c_r, taper, b, n = 8.0, 0.3, 36.0, 400
    eta = (np.arange(n) + 0.5) / n  # midpoints of the half span
    chord = c_r * (1.0 - (1.0 - taper) * eta)
    width = np.full(n, b / 2.0 / n)
    strips = _strips(np.concatenate([chord, chord, [2.0]]), np.concatenate([width, width, [1.0]]),
                     ["right_wing"] * n + ["left_wing"] * n + ["fin"])  # the fin's strip is not part of the wing
    ref = ReferenceGeometry.of_strips(strips)
    assert ref.span_m == pytest.approx(b, rel=1e-12)
    assert ref.area_m2 == pytest.approx(b * c_r * (1.0 + taper) / 2.0, rel=1e-5)
    assert ref.mean_chord_m == pytest.approx(c_r * (1.0 + taper) / 2.0, rel=1e-5)
    assert ref.mac_m == pytest.approx(2.0 / 3.0 * c_r * (1.0 + taper + taper**2) / (1.0 + taper), rel=1e-5)
    assert ref.components == ("right_wing", "left_wing")
    assert ReferenceGeometry.of_strips(_strips(np.array([1.0]), np.array([1.0]), ["fin"])) is None
    with pytest.raises(ValueError, match="area_m2 = -1.0"):
        ReferenceGeometry(area_m2=-1.0, span_m=1.0, mean_chord_m=1.0, mac_m=1.0, components=())


def test_the_gtm_model_carries_its_reference_geometry():
    """The GTM's wing strips: the span is the two halves' elastic axes projected normal to the flow, ~2 L cos(sweep)
    (the strips' widths, :class:`flexsim.model.strips.StripSet`; the exposed wing, without the fuselage's width:
    34.19 m of the published 37.955 m, docs/reference), and the MAC is the static margin's (5.09 m,
    tests/trimming/test_static_margin.py)."""
    gtm = load_aircraft("gtm")
    model = AircraftModel(gtm, aero="quasi-steady")
    ref, wing = model.reference_geometry, gtm.component("right_wing")
    # the file's sweep is the elastic axis's in the wing's (dihedral) plane, the widths are normal to the flow: they
    # differ in second order of the dihedral (7e-5 relative on the GTM)
    assert ref.span_m == pytest.approx(2.0 * wing.length_m * np.cos(wing.sweep), rel=2e-4)
    assert ref.mac_m == pytest.approx(5.09, abs=0.01)
    assert ref.mean_chord_m == pytest.approx(ref.area_m2 / ref.span_m, rel=1e-15)
    assert AircraftModel(gtm, aero=None).reference_geometry is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        ref.area_m2 = 1.0
