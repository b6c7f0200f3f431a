"""Compiled kernels of the one right-hand side: structure, strips, inflow, drag, wind, ISA (numba).

This package holds the only implementation of the physics evaluated per right-hand-side call; the classes of
:mod:`flexsim.structure`, :mod:`flexsim.model`, :mod:`flexsim.sim.disturbances` and :mod:`flexsim.atmosphere`
build the frozen data once and call these kernels (their docstrings cite the equations again). Every
kernel takes flat float64 arrays or a NamedTuple of them, is compiled by numba with ``cache=True`` (machine code
kept in ``__pycache__``; a fresh process loads it in a fraction of a second) and is plain numpy/Python when
``NUMBA_DISABLE_JIT=1`` (debugging; tests/model/test_kernels.py runs a small case that way and compares).

Modules (every public name is importable from ``flexsim._kernels`` itself):

* :mod:`~flexsim._kernels.layout` -- the packed data (F, I) generated from the terms' data classes
  (:func:`~flexsim._kernels.layout.term_data`), field views, sparsity derived at pack time, and the compile
  decorator :func:`~flexsim._kernels.layout.kernel`;
* :mod:`~flexsim._kernels.isa` -- ISA 1976 constants and scalar state, the 3-2-1 rotation;
* :mod:`~flexsim._kernels.state` -- the model variant and its state vector (``unpack``) and the air state at a state
  (``air``, ``air_state``: density, Mach number, speed of sound), below every term;
* one module per term of eq. 33, each with its data class and kernel: :mod:`~flexsim._kernels.structure`
  (inertia: M(q), dT/dq, dM/dt V, eqs. 8-10, 33), :mod:`~flexsim._kernels.elasticity` (eqs. 14-16),
  :mod:`~flexsim._kernels.gravity` (eq. 32), :mod:`~flexsim._kernels.thrust` (eqs. 17-24),
  :mod:`~flexsim._kernels.gyroscopic` (the engines' rotors);
* :mod:`~flexsim._kernels.strips` -- strip kinematics and airloads, apparent mass (eqs. 17-31);
* :mod:`~flexsim._kernels.peters` -- Peters finite-state inflow;
* :mod:`~flexsim._kernels.downwash` -- the wing's downwash at the tail (DATCOM 4.4.1);
* :mod:`~flexsim._kernels.drag` -- parasite drag items; :mod:`~flexsim._kernels.bodies` -- slender-body moments;
* :mod:`~flexsim._kernels.wind` -- gusts and Dryden fields as arrays and their evaluation;
* :mod:`~flexsim._kernels.solve` -- Gaussian and block elimination of E V_dot = f;
* :mod:`~flexsim._kernels.equations` -- assembly of E V_dot = f and the right-hand side (eqs. 4, 33).

Numba's cache of a ``cache=True`` function is keyed on its own file only, and these kernels call each other
across the files: every kernel's cache is keyed on the source of the whole package
(:func:`flexsim._numba_cache.depends_on` of this package, applied by :func:`~flexsim._kernels.layout.kernel`), and
a compiled caller outside the package declares ``depends_on(flexsim._kernels)`` likewise.

Sources (symbols as in the modules that build the data):
* Tuzcu & Nguyen (2014) "Flutter of Maneuvering Aircraft" (the paper): eqs. (2)-(4) kinematics, (7)-(10)
  M(q), (12) and (33) equations of motion, (14)-(16) stiffness, (17)-(24) generalized forces, (25)-(31)
  strip airloads, (32) gravity.
* Peters, Karunamoorthy & Cao (1995), finite-state inflow, as written in
  ``docs/reference/aero-kinematics.md`` section 2.1; Peters-Johnson strip loads, sections 1.3-1.6.
* Raymer (2018) sec. 12.5, parasite drag of the file's drag items (:mod:`flexsim.model.drag`); Munk (1924),
  NACA Report 184, slender-body moments (:mod:`flexsim.model.bodies`); USAF DATCOM sec. 4.4.1, wing downwash
  at the tail (:func:`flexsim.model.coupling.tail_downwash`).
* U.S. Standard Atmosphere 1976, eqs. 18, 23, 33a/b, 42, 50 (:mod:`flexsim.atmosphere`).
* CS-25.341(a) / MIL-F-8785C 3.7.3 discrete gust; MIL-F-8785C 3.7.2 Dryden turbulence, frozen field
  (:mod:`flexsim.sim.disturbances`).

Units SI, angles in radians. Frames: body axes xyz (x forward, y right, z down), inertial NED, component
axes x_i y_i z_i (paper Table 1), strip axes d (chord, to the trailing edge), n (plunge, down), p = d x n.
"""

from __future__ import annotations

from flexsim._kernels.bodies import SlenderBodyData, body_force, body_moments, munk_moments
from flexsim._kernels.downwash import DownwashData, downwash_velocity
from flexsim._kernels.drag import ParasiteDragData, parasite_drag, point_velocity
from flexsim._kernels.equations import (_rhs, _rhs_wind, aerodynamic_force, assemble, rhs, rhs_batch, rhs_strip_wind,
                                        strip_wind_at)
from flexsim._kernels.isa import (_EXPONENT, _SCALE, EARTH_RADIUS, G0, GAMMA, GAS_CONSTANT, H_TROPOPAUSE, LAPSE_RATE,
                                  P0, P_TROPOPAUSE, T0, T_TROPOPAUSE, _geopotential, _sound_speed, dcm_321, isa_scalar)
from flexsim._kernels.layout import (SOLVE_PERM, SOLVE_PTR, TERMS, KernelData, _f1, _f2, _f3, _f4, _flag, _i1,
                                     fields_of, flag_names, float_fields, int_fields, pack, pack_fields, solve_structure,
                                     strip_columns)
from flexsim._kernels.peters import PetersData, inflow_derivative, inflow_lambda0
from flexsim._kernels.solve import _gauss, block_solve, blocks_decoupled, solve
from flexsim._kernels.state import air, air_state, unpack
from flexsim._kernels.strips import (StripData, aero_evaluate, circulatory, compressibility_factor, downwash_shift, inflow_rate,
                                     strip_kinematics, tail_downwash)
from flexsim._kernels.elasticity import elastic_force
from flexsim._kernels.gravity import gravity_force
from flexsim._kernels.gyroscopic import gyroscopic_force
from flexsim._kernels.structure import inertia, inertia_term
from flexsim._kernels.thrust import thrust_force
from flexsim._kernels.wind import (NO_WIND, BatchWind, WindData, air_velocity_rows, dryden_along_track, dryden_track,
                                   gust_profile, gust_profiles, join_winds, pack_winds, strip_positions, strip_wind,
                                   wind_ned)

__all__ = ["TERMS", "float_fields", "int_fields", "flag_names", "KernelData", "pack", "fields_of", "pack_fields",
           "StripData", "PetersData", "DownwashData", "ParasiteDragData", "SlenderBodyData", "WindData", "NO_WIND", "BatchWind", "pack_winds",
           "join_winds", "rhs", "rhs_batch", "air_velocity_rows", "rhs_strip_wind", "assemble", "aerodynamic_force", "unpack", "air", "air_state", "inertia",
           "strip_kinematics", "circulatory", "tail_downwash", "downwash_shift", "aero_evaluate", "inflow_rate",
           "point_velocity", "parasite_drag", "munk_moments", "body_moments", "body_force", "strip_positions", "strip_wind",
           "strip_wind_at", "wind_ned", "gust_profile", "gust_profiles", "dryden_along_track", "dryden_track", "isa_scalar",
           "dcm_321", "inertia_term", "elastic_force", "gravity_force", "thrust_force", "gyroscopic_force", "solve", "block_solve", "blocks_decoupled", "strip_columns", "solve_structure", "compressibility_factor"]
