"""The nonlinear aircraft's time-domain run (flexsim.sim.flexible_run) against invariants.

* The nonlinear trim is a steady state: over 1 s the velocity drifts below 1e-8 m/s and the strains below 1e-8
  (the trim's residual is ~1e-10 scaled; the BDF tolerances are rtol 1e-6, atol 1e-8, so drift above atol would be
  a real unsteadiness, not round-off).
* In vacuum (density 0, thrust 0; the structure has no damping) the run conserves the free structure's energy
  (flexsim.structure.free_flexible.conserved_quantities) to 1e-4 of the strain energy released, the accuracy of
  rtol 1e-8 over 0.3 s of the elastic oscillation.
* The HALE's 1-cos gust encounter (fixed ROS2 steps of 10 ms, within 3.9 cm of BDF: tests/sim/test_flexible_step.py):
  tips beyond 25 % of the semispan, logged with the deformed nodes, read back and viewed (Rerun's own ``rrd verify``).
Four elements per beam keep these runs short (the 8-element structure's highest root, ~6000 rad/s, makes BDF's
finite-difference Jacobian costlier).
"""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

import flexsim as fs
from flexsim.io.flight_log import read_flight_log
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim.sim.flexible_run import simulate_flexible, write_flexible_log
from flexsim.structure.free_flexible import conserved_quantities, quaternion_matrix
from flexsim.trimming.flexible_trim import trim_flexible

SEMISPAN_M = 16.0  # PHC 2001's wing half (flexsim/aircraft/data/phc_hale.md)


@pytest.fixture(scope="module")
def hale():
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    return model, trim_flexible(model, fs.SteadyManoeuvre.level(altitude_m=20000.0, speed_m_s=25.0), elements_per_beam=4)


def test_trim_is_a_steady_state(hale):
    model, point = hale
    run = simulate_flexible(model, point, 1.0, sample_dt_s=0.25)
    assert np.abs(run.velocity_m_s - point.velocity_m_s).max() < 1e-8
    assert np.abs(run.strains - point.strains).max() < 1e-8
    assert any("quasi-steady" in w for w in run.warnings)


def test_vacuum_run_conserves_energy(hale):
    model, point = hale
    vacuum = dataclasses.replace(point, density_kg_m3=0.0)
    run = simulate_flexible(model, vacuum, 0.3, controls=np.zeros(4), sample_dt_s=0.05, rtol=1e-8, atol=1e-10)
    structure = point.aircraft.free_structure(model.terms.gravity_m_s2)
    e = np.array([conserved_quantities(structure, y).energy_j for y in run.states])
    released = conserved_quantities(structure, run.states[0]).strain_j
    assert np.abs(run.strains - point.strains).max() > 1e-3  # the wings do swing
    assert np.abs(e - e[0]).max() < 1e-4 * released


@pytest.mark.parametrize("field, value", [("t_end_s", -1.0), ("sample_dt_s", 0.0), ("rtol", 1.0)])
def test_bad_input_names_the_field(hale, field, value):
    model, point = hale
    kwargs = {"t_end_s": 1.0, "sample_dt_s": 0.1, "rtol": 1e-6, field: value}
    t_end = kwargs.pop("t_end_s")
    with pytest.raises(ValueError, match=field):
        simulate_flexible(model, point, t_end, **kwargs)


def test_hale_gust_encounter_nonlinear_logs_and_views(hale, tmp_path):
    model, point = hale
    y0 = point.state()
    gust = OneMinusCosineGust.encounter(10.0, 60.0, position_ned_m=y0[:3],
                                        velocity_ned_m_s=quaternion_matrix(y0[3:7]) @ point.velocity_m_s,
                                        start_time_s=0.2)
    run = simulate_flexible(model, point, 1.5, wind=gust, sample_dt_s=0.05, step_s=0.01)
    peak = run.tip_deflection_fraction.max()
    print(f"peak tip deflection {peak * SEMISPAN_M:.2f} m ({100 * peak:.1f} % of the semispan), "
          f"trim {100 * point.tip_deflection_fraction.max():.1f} %, wall {run.wall_s:.0f} s, {run.n_rhs} rhs")
    assert peak > 0.25
    assert peak > point.tip_deflection_fraction.max() + 0.01  # the gust bends the wings up beyond the trim
    log = tmp_path / "hale-nl-gust.mcap"
    write_flexible_log(run, log)
    flight = read_flight_log(log)
    assert flight.complete and abs(flight.t[-1] - 1.5) < 1e-9
    right = flight.structure["right_wing"]
    up = -(right[:, -1, 2] - point.aircraft.undeformed_tips[point.aircraft.beam_index("right_wing"), 2])
    assert up.max() > 0.25 * SEMISPAN_M  # the logged nodes are the deformed wing's
    rrd = tmp_path / "hale-nl-gust.rrd"
    from flexsim.cli.main import main
    assert main(["view", str(log), "--save", str(rrd)]) == 0
    verify = subprocess.run([sys.executable, "-m", "rerun", "rrd", "verify", str(rrd)], capture_output=True, text=True,
                            timeout=120)
    assert verify.returncode == 0, verify.stderr
