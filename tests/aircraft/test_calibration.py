"""Stiffness calibration factors (flexsim.aircraft.calibration) and the calibrated bundled GTM."""

import tomllib
from pathlib import Path

import numpy as np
import pytest

from flexsim.aircraft.calibration import BOUNDS, StructuralScaling
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel
from flexsim.structure.model import StructuralModel

CALIBRATION_FILE = Path(__file__).resolve().parents[2] / "tools" / "gtm_calibration.toml"


@pytest.fixture(scope="module")
def base():
    return load_aircraft("gtm_uncalibrated")


@pytest.mark.parametrize("name", sorted(BOUNDS))
def test_out_of_bounds_factor_names_field_value_and_range(name):
    lo, hi = BOUNDS[name]
    with pytest.raises(ValueError, match=rf"StructuralScaling\.{name} = {hi * 1.5}: must be in \[{lo}, {hi}\]"):
        StructuralScaling(**{name: hi * 1.5})
    with pytest.raises(ValueError, match=name):
        StructuralScaling(**{name: float("nan")})
    with pytest.raises(ValueError, match=name):
        StructuralScaling(**{name: "stiff"})


def test_apply_scales_only_the_named_tables(base):
    scaled = StructuralScaling(wing_gj=0.4, fuselage_ei=1.3, vtail_stiffness=2.0).apply(base)
    expect = {"right_wing": (1.0, 0.4), "left_wing": (1.0, 0.4), "fuselage": (1.3, 1.0), "vtail": (2.0, 2.0),
              "right_htail": (1.0, 1.0), "left_htail": (1.0, 1.0)}
    for c0, c1 in zip(base.components, scaled.components):
        k_ei, k_gj = expect[c0.name]
        np.testing.assert_array_equal(c1.sections.ei_nm2, c0.sections.ei_nm2 * k_ei)
        np.testing.assert_array_equal(c1.sections.gj_nm2, c0.sections.gj_nm2 * k_gj)
        np.testing.assert_array_equal(c1.sections.mass_kg_per_m, c0.sections.mass_kg_per_m)
    assert scaled.lumped_masses == base.lumped_masses and scaled.engines == base.engines


def test_uniform_stiffness_scale_scales_frequencies_by_its_square_root(base):
    """K -> k K with M unchanged: omega -> sqrt(k) omega for every elastic mode (closed form, 1e-9)."""
    k = 1.5
    scaled = StructuralScaling(wing_ei=k, wing_gj=k, fuselage_ei=k, fuselage_gj=k, htail_stiffness=k, vtail_stiffness=k).apply(base)
    f0 = in_vacuo_modes(AircraftModel(base, aero=None)).frequencies_rad_s[6:]
    f1 = in_vacuo_modes(AircraftModel(scaled, aero=None)).frequencies_rad_s[6:]
    np.testing.assert_allclose(f1, np.sqrt(k) * f0, rtol=1e-9)


def test_mass_factor_scales_mass_and_inertia_and_keeps_frequencies(base):
    """Option B scaling: M -> k M and K -> k K, so m and J scale by k and every omega is unchanged (1e-9)."""
    k = 1.5
    heavy = StructuralScaling(mass=k).apply(base)
    mp0, mp1 = StructuralModel(base).mass_properties, StructuralModel(heavy).mass_properties
    assert mp1.mass_kg == pytest.approx(k * mp0.mass_kg, rel=1e-12)
    np.testing.assert_allclose(mp1.cg_m, mp0.cg_m, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(mp1.inertia_cg_kg_m2, k * mp0.inertia_cg_kg_m2, rtol=1e-12, atol=1e-6)
    f0 = in_vacuo_modes(AircraftModel(base, aero=None)).frequencies_rad_s[6:]
    f1 = in_vacuo_modes(AircraftModel(heavy, aero=None)).frequencies_rad_s[6:]
    np.testing.assert_allclose(f1, f0, rtol=1e-9)


def test_bundled_gtm_is_the_uncalibrated_one_with_the_fitted_factors(base):
    """gtm.toml = gtm_uncalibrated.toml x tools/gtm_calibration.toml (6 significant digits in the files: 1e-5)."""
    with open(CALIBRATION_FILE, "rb") as fh:
        calibration = tomllib.load(fh)
    expected = StructuralScaling(**calibration["scaling"]).apply(base)
    gtm = load_aircraft("gtm")
    assert base.structural_damping_ratio == 0.0
    assert gtm.structural_damping_ratio == calibration["fixed"]["structural_damping_ratio"]
    for c0, c1 in zip(expected.components, gtm.components):
        for name in ("ei_nm2", "gj_nm2", "mass_kg_per_m", "torsional_inertia_kg_m", "cg_offset_m", "chord_m", "ea_fraction"):
            np.testing.assert_allclose(getattr(c1.sections, name), getattr(c0.sections, name), rtol=1e-5, err_msg=f"{c0.name}.{name}")
        np.testing.assert_allclose(c1.root_m, c0.root_m, rtol=1e-12)
