"""Compiled kernels of the one right-hand side: structure, strips, inflow, drag, wind, ISA (numba).

This module holds the only implementation of the physics evaluated per right-hand-side call; the classes of
:mod:`flexsim.structure`, :mod:`flexsim.model`, :mod:`flexsim.sim.disturbances` and :mod:`flexsim.atmosphere`
build the frozen data once and call these kernels (their docstrings cite the equations again). Every
kernel takes flat float64 arrays or a NamedTuple of them (:class:`ModelData`), is compiled by numba with
``cache=True`` (machine code kept in ``__pycache__``; a fresh process loads it in a fraction of a second)
and is plain numpy/Python when ``NUMBA_DISABLE_JIT=1`` (debugging; tests/model/test_kernels.py runs a small
case that way and compares).

Data layout: a model's frozen arrays are packed once into one float64 buffer ``F`` and one int64 buffer ``I``
(:func:`pack`; :class:`KernelData`); a kernel takes views of the fields it needs by name (``_f2(F, I, M0)``:
the field's offset and shape are in the header of ``I``). Two flat arrays compile and dispatch fast; a
NamedTuple of ~50 arrays cost about 1.4 s of compilation per kernel signature and ~10 us per call (measured).

Why one module: numba's cache is invalidated by a change of the file of the cached function only, not of the
files of the functions it calls, so the kernels that call each other live in one file.

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

import math
from typing import NamedTuple

import numpy as np
from numba import njit

from flexsim._arrays import frozen_array

__all__ = ["FLOAT_FIELDS", "INT_FIELDS", "INT_NAMES", "KernelData", "pack", "WindData", "NO_WIND", "BatchWind", "pack_winds",
           "join_winds", "rhs", "rhs_batch", "air_velocity_rows", "rhs_strip_wind", "assemble", "aerodynamic_force", "unpack", "air", "inertia",
           "strip_kinematics", "circulatory", "tail_downwash", "downwash_shift", "aero_evaluate", "inflow_rate",
           "point_velocity", "parasite_drag", "munk_moments", "body_moments", "body_force", "strip_positions", "strip_wind",
           "strip_wind_at", "wind_ned", "gust_profile", "gust_profiles", "dryden_along_track", "dryden_track", "isa_scalar",
           "dcm_321", "solve", "block_solve", "blocks_decoupled", "strip_columns", "solve_structure", "compressibility_factor"]

_jit = njit(cache=True, nogil=True)
_entry = _jit

# ISA 1976 constants (flexsim.atmosphere re-exports them)
EARTH_RADIUS = 6_356_766.0  # r0 [m]
G0 = 9.80665  # [m/s^2]
GAS_CONSTANT = 8.31432 / 28.9644e-3  # R* / M0 [J/(kg K)]
GAMMA = 1.4
T0 = 288.15  # [K]
P0 = 101_325.0  # [Pa]
LAPSE_RATE = -0.0065  # [K/m]
H_TROPOPAUSE = 11_000.0  # geopotential [m]
T_TROPOPAUSE = T0 + LAPSE_RATE * H_TROPOPAUSE
_EXPONENT = -G0 / (GAS_CONSTANT * LAPSE_RATE)
P_TROPOPAUSE = P0 * (T_TROPOPAUSE / T0) ** _EXPONENT
_SCALE = G0 / (GAS_CONSTANT * T_TROPOPAUSE)
_MACH_CAP = 0.95


#: Float fields of F, in order (name, rank); shapes in :func:`pack`'s docstring.
FLOAT_FIELDS = (
    # model: [g [m/s^2], altitude_m (restrained), tunnel density (nan: none), aerodynamics density (nan: ISA)]
    ("floats", 1), ("euler_fixed", 1), ("v_fixed", 1), ("q_frozen", 1), ("xi_frozen", 1),
    # structure (paper eqs. 8-10, 14-16, 17-24)
    ("m0", 2), ("h", 3), ("m2", 4), ("k_bending", 2), ("k_torsion", 2), ("c_el", 2), ("thrust_t0", 1), ("thrust_t1", 2),
    # strips (eqs. 25-31) and Peters inflow
    ("proj_n0", 2), ("proj_d0", 2), ("proj_n1", 3), ("proj_d1", 3), ("proj_p", 2), ("rel", 2), ("incidence", 1),
    ("semichord", 1), ("ab", 1), ("k0", 1), ("pr_w", 1), ("width", 1), ("cd0", 1), ("flap_sign", 1), ("paper_strips", 1),
    ("n_over_d_x", 1), ("flap_w", 2), ("d", 2), ("n", 2), ("strip_dcm", 3), ("strip_pos", 2), ("a_inv", 2), ("a_inv_c", 1),
    ("b_vec", 1),
    # wing downwash at the tail: [d epsilon/d alpha at M -> 0]; wing weights and n . z_body of the tail strips
    ("aero_floats", 1), ("dw_wing_weight", 1), ("dw_tail_nz", 1),
    # parasite drag items
    ("drag_area", 1), ("drag_g0", 3), ("drag_g1", 4), ("drag_offset", 2),
    # slender bodies (Munk moments): rho-free coefficient Vol (k2 - k1) [m^3], maps, offsets, unit axes
    ("body_vol_dk", 1), ("body_g0", 3), ("body_g1", 4), ("body_offset", 2), ("body_axis", 2),
    # the pitch part of the strips' apparent mass per unit density, sum_j pi b^4 w / 8 (p^T B)^T (p^T B) [m^4]
    ("apparent_pitch", 2),
)
#: Int fields of I: flags and sizes (``ints``, entries below), active entries of V, flap control index per
#: strip, unsteady strips; derived by :func:`pack` (:func:`strip_columns`, :func:`solve_structure`): the columns
#: of V each strip's rows touch (CSR: pointers, indices) and the elimination order of E V_dot = f (order, pointers).
INT_FIELDS = ("ints", "active", "flap_index", "inflow_idx", "strip_col_ptr", "strip_cols", "solve_perm", "solve_ptr")
#: Entries of the ``ints`` field.
INT_NAMES = ("n_v", "nq", "nxi", "rigid", "use_frozen", "all_active", "n_states", "vel_start", "inflow_start", "n_inflow",
             "has_aero", "has_drag", "has_damping", "q_start", "xi_start", "finite_state", "n_inflow_per_strip",
             "prandtl_glauert", "paper", "has_bodies")
_NF = len(FLOAT_FIELDS)
_HEAD = 5 * _NF + 2 * len(INT_FIELDS)
(FLOATS, EULER_FIXED, V_FIXED, Q_FROZEN, XI_FROZEN, M0, H, M2, K_BENDING, K_TORSION, C_EL, THRUST_T0, THRUST_T1,
 PROJ_N0, PROJ_D0, PROJ_N1, PROJ_D1, PROJ_P, REL, INCIDENCE, SEMICHORD, AB, K0, PR_W, WIDTH, CD0, FLAP_SIGN,
 PAPER_STRIPS, N_OVER_D_X, FLAP_W, D, N, STRIP_DCM, STRIP_POS, A_INV, A_INV_C, B_VEC, AERO_FLOATS, DW_WING_WEIGHT,
 DW_TAIL_NZ, DRAG_AREA, DRAG_G0, DRAG_G1, DRAG_OFFSET, BODY_VOL_DK, BODY_G0, BODY_G1, BODY_OFFSET, BODY_AXIS,
 APPARENT_PITCH) = range(_NF)
INTS, ACTIVE, FLAP_INDEX, INFLOW_IDX, STRIP_COL_PTR, STRIP_COLS, SOLVE_PERM, SOLVE_PTR = range(len(INT_FIELDS))
(N_V, NQ, NXI, RIGID, USE_FROZEN, ALL_ACTIVE, N_STATES, VEL_START, INFLOW_START, N_INFLOW, HAS_AERO, HAS_DRAG,
 HAS_DAMPING, Q_START, XI_START, FINITE_STATE, N_PER_STRIP, PRANDTL_GLAUERT, PAPER, HAS_BODIES) = range(len(INT_NAMES))


class KernelData(NamedTuple):
    """The packed frozen data of one model (or of its strips alone): F float64, I int64, both read-only."""

    F: np.ndarray
    I: np.ndarray


def pack(floats: dict, ints: dict) -> KernelData:
    """Pack named arrays into (F, I) (missing fields are empty arrays of their rank).

    Shapes (n_v velocities, nq / nxi elastic coordinates, n_s strips, N inflow states per unsteady strip,
    k drag items): floats (4,); euler_fixed, v_fixed (3,); q_frozen (nq,); xi_frozen (nxi,); m0 (n_v, n_v);
    h (n_v, 3, nq); m2 (3, 3, nq, nq); k_bending (nq, nq); k_torsion (nxi, nxi); c_el (n_el, n_el); thrust_t0
    (n_v,); thrust_t1 (n_v, nq); proj_n0, proj_d0, proj_p (n_s, n_v); proj_n1, proj_d1 (n_s, 3, nq); rel
    (n_s, n_el); per-strip vectors (n_s,); flap_w, d, n, strip_pos (n_s, 3); strip_dcm (n_s, 3, 3); a_inv
    (N, N); a_inv_c, b_vec (N,); aero_floats (1,); dw_wing_weight, dw_tail_nz (n_s,); drag_area (k,); drag_g0
    (k, 6, n_v); drag_g1 (k, 3, 3, nq); drag_offset (k, 3); body_vol_dk (k_b,); body_g0, body_g1, body_offset
    like the drag's; body_axis (k_b, 3).
    ``ints``: ``ints`` (len(INT_NAMES),) with the entries of :data:`INT_NAMES` (given as a dict by name),
    active, flap_index, inflow_idx. The sparsity fields are derived here from the float fields
    (:func:`strip_columns`, :func:`solve_structure`).
    """
    strip_ptr, strip_cols = strip_columns(floats)
    perm, ptr = solve_structure(floats, ints.get("active"), strip_ptr, strip_cols)
    ints = {**ints, "strip_col_ptr": strip_ptr, "strip_cols": strip_cols, "solve_perm": perm, "solve_ptr": ptr}
    head = np.zeros(_HEAD, np.int64)
    chunks, off = [], 0
    for k, (name, rank) in enumerate(FLOAT_FIELDS):
        a = np.ascontiguousarray(floats.get(name, np.zeros((0,) * rank)), dtype=float)
        if a.ndim != rank:
            raise ValueError(f"kernel field {name}: rank {a.ndim}, expected {rank}")
        shape = a.shape + (1,) * (4 - rank)
        head[5 * k:5 * k + 5] = (off, *shape)
        chunks.append(a.ravel())
        off += a.size
    flags = np.zeros(len(INT_NAMES), np.int64)
    for name, value in ints.get("ints", {}).items():
        flags[INT_NAMES.index(name)] = int(value)
    int_chunks, ioff = [], _HEAD
    for k, name in enumerate(INT_FIELDS):
        a = flags if name == "ints" else np.asarray(ints.get(name, np.zeros(0)), dtype=np.int64).ravel()
        head[5 * _NF + 2 * k:5 * _NF + 2 * k + 2] = (ioff, a.size)
        int_chunks.append(a)
        ioff += a.size
    f = frozen_array(np.concatenate(chunks) if off else np.zeros(0))
    i = frozen_array(np.concatenate([head] + int_chunks), np.int64)
    return KernelData(f, i)


def _field(floats: dict, name: str, rank: int) -> np.ndarray:
    return np.asarray(floats.get(name, np.zeros((0,) * rank)), dtype=float)


def strip_columns(floats: dict) -> tuple[np.ndarray, np.ndarray]:
    """The entries of V each strip's rows touch, as CSR (pointers (n_s + 1,), ascending column indices).

    A strip's rows of A(q) (n^T A, d^T A) and of B (p^T B) are proj_n0 + proj_n1 q, proj_d0 + proj_d1 q (the q
    part in the omega columns 3-5 only) and proj_p (:func:`strip_kinematics`): exact zeros of these constant
    fields are zero at every state, so the strip loops skip them (the GTM: 14 of 30 columns per strip; a
    strip moves with the rigid body, its own component's modes and the fuselage's).
    """
    pn0, pd0, pp = _field(floats, "proj_n0", 2), _field(floats, "proj_d0", 2), _field(floats, "proj_p", 2)
    pn1, pd1 = _field(floats, "proj_n1", 3), _field(floats, "proj_d1", 3)
    ptr, cols = [0], []
    for j in range(pn0.shape[0]):
        used = (pn0[j] != 0.0) | (pd0[j] != 0.0) | (pp[j] != 0.0)
        if pn1.shape[2]:
            used[3:6] |= np.any(pn1[j] != 0.0, axis=1) | np.any(pd1[j] != 0.0, axis=1)
        cols.extend(np.flatnonzero(used).tolist())
        ptr.append(len(cols))
    return np.asarray(ptr, np.int64), np.asarray(cols, np.int64)


def solve_structure(floats: dict, active, strip_ptr: np.ndarray, strip_cols: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Elimination order of E V_dot = f over the active entries of V: diagonal blocks first, the coupling core last.

    The pattern of E = M(q) + M_a (eqs. 8-10, 33; :func:`assemble`) at any state: the non-zeros of M0; H q in the
    omega rows and columns (3-5) of the rows where H is non-zero and M2 : q q in the omega block (eq. 10); each
    strip's apparent mass sum_j left_j^T right_j on its columns x columns (:func:`strip_columns`). The core is the
    active entries coupled with every other one (the GTM: the 6 rigid-body entries and the fuselage's 4 modes); the
    rest splits into blocks coupled only through the core (the GTM: one 4 x 4 block per lifting surface, its two
    bending and two torsion modes). :func:`block_solve` eliminates the blocks into a Schur complement of the core.

    Returns perm (n_a,) (indices of V: block after block, then the core, each ascending) and ptr (n_blocks + 2,):
    block b is perm[ptr[b]:ptr[b + 1]], the core perm[ptr[-2]:]. With fewer than two blocks: perm = active, ptr = [0, n_a]
    (one dense elimination, :func:`solve`).
    """
    m0 = _field(floats, "m0", 2)
    act = np.arange(m0.shape[0]) if active is None else np.asarray(active, np.int64).ravel()
    whole = (act.astype(np.int64), np.asarray([0, act.size], np.int64))
    if m0.shape[0] < 6 or act.size == 0:
        return whole
    pattern = m0 != 0.0
    h, m2 = _field(floats, "h", 3), _field(floats, "m2", 4)
    if h.size:
        for a in range(3):
            rows = np.any(h[:, a, :] != 0.0, axis=1)
            pattern[rows, 3 + a] = True
            pattern[3 + a, rows] = True
    if m2.size:
        pattern[3:6, 3:6] |= np.any(m2 != 0.0, axis=(2, 3))
    for j in range(strip_ptr.size - 1):
        c = strip_cols[strip_ptr[j]:strip_ptr[j + 1]]
        pattern[np.ix_(c, c)] = True
    pattern = (pattern | pattern.T)[np.ix_(act, act)]
    n_a = act.size
    core = [i for i in range(n_a) if pattern[i].all()]
    rest = [i for i in range(n_a) if not pattern[i].all()]
    blocks, seen = [], set()
    for start in rest:  # connected components of the pattern without the core
        if start in seen:
            continue
        block, stack = [], [start]
        seen.add(start)
        while stack:
            i = stack.pop()
            block.append(i)
            for k in rest:
                if k not in seen and pattern[i, k]:
                    seen.add(k)
                    stack.append(k)
        blocks.append(sorted(block))
    if len(blocks) < 2:  # nothing to split (one block beside the core costs as much as one elimination)
        return whole
    order = [i for b in blocks for i in b] + core
    ptr = np.cumsum([0] + [len(b) for b in blocks] + [len(core)])
    return act[np.asarray(order, np.int64)].astype(np.int64), ptr.astype(np.int64)


class WindData(NamedTuple):
    """A wind field as arrays (built by :mod:`flexsim.sim.disturbances`; the sum of its parts, NED [m/s]).

    gusts (n_g, 12): U_ds [m/s], H [m], direction (3), front normal (3), front point (3) [m], persistent (0/1);
    turb (n_t, 15): rows d (u), right (v), down (w) of the track axes (9), origin (3) [m], grid spacing [m],
    first and end column of the field's grid in ``turb_grid``; turb_grid (3, total points) [m/s].
    """

    gusts: np.ndarray
    turb: np.ndarray
    turb_grid: np.ndarray


#: Still air.
NO_WIND = WindData(frozen_array(np.zeros((0, 12))), frozen_array(np.zeros((0, 15))), frozen_array(np.zeros((3, 1))))


def join_winds(parts) -> WindData:
    """One WindData with the parts' gusts and Dryden fields (their sum); grid columns renumbered."""
    gusts = [p.gusts for p in parts]
    turbs, grids, col = [], [], 0
    for p in parts:
        for r in range(p.turb.shape[0]):
            row = np.array(p.turb[r])
            grid = p.turb_grid[:, int(row[13]):int(row[14])]
            row[13], row[14] = col, col + grid.shape[1]
            col += grid.shape[1]
            turbs.append(row[None, :])
            grids.append(grid)
    return WindData(frozen_array(np.concatenate(gusts) if gusts else np.zeros((0, 12))),
                    frozen_array(np.concatenate(turbs) if turbs else np.zeros((0, 15))),
                    frozen_array(np.concatenate(grids, axis=1) if grids else np.zeros((3, 1))))


class BatchWind(NamedTuple):
    """The winds of N aircraft packed once (:func:`pack_winds`): rows (N, 4) int64 = [first gust, end gust,
    first Dryden field, end Dryden field] of each aircraft in the joined :class:`WindData` arrays."""

    rows: np.ndarray
    gusts: np.ndarray
    turb: np.ndarray
    turb_grid: np.ndarray


def pack_winds(winds) -> BatchWind:
    """Pack one WindData (or None: still air) per aircraft for :func:`rhs_batch` (once, e.g. per reset:
    the Dryden grids are copied)."""
    parts = [NO_WIND if w is None else w for w in winds]
    rows = np.zeros((len(parts), 4), np.int64)
    ng = nt = 0
    for i, p in enumerate(parts):
        rows[i] = (ng, ng + p.gusts.shape[0], nt, nt + p.turb.shape[0])
        ng, nt = ng + p.gusts.shape[0], nt + p.turb.shape[0]
    joined = join_winds(parts)
    return BatchWind(frozen_array(rows, np.int64), *joined)


# ------------------------------------------------------------------ field views
@_jit
def _f1(F, I, k):
    o = I[5 * k]
    return F[o:o + I[5 * k + 1]]


@_jit
def _f2(F, I, k):
    o, a, b = I[5 * k], I[5 * k + 1], I[5 * k + 2]
    return F[o:o + a * b].reshape((a, b))


@_jit
def _f3(F, I, k):
    o, a, b, c = I[5 * k], I[5 * k + 1], I[5 * k + 2], I[5 * k + 3]
    return F[o:o + a * b * c].reshape((a, b, c))


@_jit
def _f4(F, I, k):
    o, a, b, c, d = I[5 * k], I[5 * k + 1], I[5 * k + 2], I[5 * k + 3], I[5 * k + 4]
    return F[o:o + a * b * c * d].reshape((a, b, c, d))


@_jit
def _i1(I, k):
    o = I[5 * _NF + 2 * k]
    return I[o:o + I[5 * _NF + 2 * k + 1]]


@_jit
def _flag(I, k):
    return I[I[5 * _NF] + k]


# ------------------------------------------------------------------ atmosphere, kinematics
@_jit
def isa_scalar(h_geopotential):
    """ISA 1976 (density [kg/m^3], pressure [Pa], temperature [K]) at geopotential altitude H [m]
    (1976 standard eqs. 23, 33a/33b, 42); H in [-5000, 20000] m is checked by the callers."""
    if h_geopotential <= H_TROPOPAUSE:
        temperature = T0 + LAPSE_RATE * h_geopotential
        pressure = P0 * (temperature / T0) ** _EXPONENT
    else:
        temperature = T_TROPOPAUSE
        pressure = P_TROPOPAUSE * math.exp(-_SCALE * (h_geopotential - H_TROPOPAUSE))
    return pressure / (GAS_CONSTANT * temperature), pressure, temperature


@_jit
def _geopotential(z):
    """H = r0 z / (r0 + z) [m] from geometric altitude z [m] (1976 standard eq. 18)."""
    return EARTH_RADIUS * z / (EARTH_RADIUS + z)


@_jit
def _sound_speed(h_geopotential):
    """sqrt(gamma R T) [m/s] (1976 standard eq. 50)."""
    return math.sqrt(GAMMA * GAS_CONSTANT * (T0 + LAPSE_RATE * min(h_geopotential, H_TROPOPAUSE)))


@_jit
def dcm_321(phi, theta, psi):
    """C = R_x(phi) R_y(theta) R_z(psi): inertial -> body components (paper eq. 4; kinematics.dcm_321)."""
    sf, cf = math.sin(phi), math.cos(phi)
    st, ct = math.sin(theta), math.cos(theta)
    sp, cp = math.sin(psi), math.cos(psi)
    c = np.empty((3, 3))
    c[0, 0], c[0, 1], c[0, 2] = ct * cp, ct * sp, -st
    c[1, 0], c[1, 1], c[1, 2] = sf * st * cp - cf * sp, sf * st * sp + cf * cp, sf * ct
    c[2, 0], c[2, 1], c[2, 2] = cf * st * cp + sf * sp, cf * st * sp - sf * cp, cf * ct
    return c


# ------------------------------------------------------------------ structure
@_jit
def inertia(m0, h, m2, v, q, s):
    """M(q), dT/dq and dM/dt V in one pass (paper eqs. 8-10, 33; :class:`InertiaPolynomial`).

    M(q) = M0 + [H q in the omega columns] + [(H q)^T in the omega rows] + [M2 : q q in the omega block];
    with m2q = M2 . q (3, 3, nq) and the symmetry M2[a, d, k, l] = M2[d, a, l, k]:
    dT/dq_k = V^T H[:, :, k] omega + omega^T m2q[:, :, k] omega;
    (dM/dt V) = (H s) omega, plus (H s)^T V + (m2q . s) omega + (m2q . s)^T omega in the omega rows.

    Parameters: m0 (n_v, n_v), h (n_v, 3, nq), m2 (3, 3, nq, nq), v = V (n_v,), q (nq,) [m], s = dq/dt
    (nq,) [m/s]. Returns m (n_v, n_v), dtdq (nq,) [N], mdot_v (n_v,).
    """
    n_v = m0.shape[0]
    nq = q.shape[0]
    m = m0.copy()
    hq = np.zeros((n_v, 3))
    hs = np.zeros((n_v, 3))
    for i in range(n_v):
        for a in range(3):
            acc_q = 0.0
            acc_s = 0.0
            for k in range(nq):
                acc_q += h[i, a, k] * q[k]
                acc_s += h[i, a, k] * s[k]
            hq[i, a] = acc_q
            hs[i, a] = acc_s
    for i in range(n_v):
        for a in range(3):
            m[i, 3 + a] += hq[i, a]
            m[3 + a, i] += hq[i, a]
    m2q = np.zeros((3, 3, nq))
    m2qs = np.zeros((3, 3))  # (M2 . q) . s
    for a in range(3):
        for b in range(3):
            qq = 0.0
            qs = 0.0
            for k in range(nq):
                acc = 0.0
                for l in range(nq):
                    acc += m2[a, b, k, l] * q[l]
                m2q[a, b, k] = acc
                qq += acc * q[k]
                qs += acc * s[k]
            m[3 + a, 3 + b] += qq
            m2qs[a, b] = qs
    w = v[3:6]
    dtdq = np.zeros(nq)
    for k in range(nq):
        acc = 0.0
        for a in range(3):
            vh = 0.0
            for i in range(n_v):
                vh += v[i] * h[i, a, k]
            wm = 0.0
            for b in range(3):
                wm += w[b] * m2q[b, a, k]
            acc += w[a] * (vh + wm)
        dtdq[k] = acc
    mdot = np.empty(n_v)
    for i in range(n_v):
        mdot[i] = hs[i, 0] * w[0] + hs[i, 1] * w[1] + hs[i, 2] * w[2]
    for a in range(3):
        acc = 0.0
        for i in range(n_v):
            acc += hs[i, a] * v[i]
        for b in range(3):
            acc += (m2qs[a, b] + m2qs[b, a]) * w[b]
        mdot[3 + a] += acc
    return m, dtdq, mdot


# ------------------------------------------------------------------ strips (eqs. 25-31)
@_jit
def strip_kinematics(F, I, q, xi, vel, lam, u, wind_c, has_wind):
    """Strip velocities and Chebyshev downwash coefficients (:mod:`flexsim.model.coupling` docstring).

    u0 = -d^T A(q) V [m/s];  w_EA = n^T A(q) V + u0 (alpha_el + alpha_r) [m/s] (down, relative to the air:
    the strip air velocity ``wind_c`` (n_s, 3), component axes, enters when ``has_wind``);
    alpha_dot = p^T B V;  w0 = w_EA - a b alpha_dot + u0 beta f0;  w1 = b alpha_dot + u0 beta f1;
    w2 = u0 beta f2;  lambda0 = 1/2 b^T lambda (unsteady strips, Peters et al. 1995).

    Returns p_mat (n_s, n_v), d_mat (n_s, n_v), alpha_el, u0, w_ea, w34 = w0 + w1/2, wc = w34 - lambda0,
    w_moment = w0 - lambda0 - w2/2, alpha_chord (elastic pitch + rigging + flap camber angle), adot
    (arrays (n_s,) unless noted).
    """
    semichord = _f1(F, I, SEMICHORD)
    ab = _f1(F, I, AB)
    incidence = _f1(F, I, INCIDENCE)
    rel = _f2(F, I, REL)
    proj_p = _f2(F, I, PROJ_P)
    proj_n1 = _f3(F, I, PROJ_N1)
    proj_d1 = _f3(F, I, PROJ_D1)
    d = _f2(F, I, D)
    n = _f2(F, I, N)
    flap_sign = _f1(F, I, FLAP_SIGN)
    flap_index = _i1(I, FLAP_INDEX)
    flap_w = _f2(F, I, FLAP_W)
    col_ptr = _i1(I, STRIP_COL_PTR)
    cols = _i1(I, STRIP_COLS)
    n_s = semichord.shape[0]
    nq = q.shape[0]
    nxi = xi.shape[0]
    p_mat = _f2(F, I, PROJ_N0).copy()
    d_mat = _f2(F, I, PROJ_D0).copy()
    lam0 = np.zeros(n_s)
    if _flag(I, FINITE_STATE):
        nin = _flag(I, N_PER_STRIP)
        b_vec = _f1(F, I, B_VEC)
        idx = _i1(I, INFLOW_IDX)
        for c in range(idx.shape[0]):
            acc = 0.0
            for k in range(nin):
                acc += lam[c * nin + k] * b_vec[k]
            lam0[idx[c]] = 0.5 * acc
    alpha_el = np.empty(n_s)
    u0 = np.empty(n_s)
    w_ea = np.empty(n_s)
    w34 = np.empty(n_s)
    wc = np.empty(n_s)
    w_moment = np.empty(n_s)
    alpha_chord = np.empty(n_s)
    adot = np.empty(n_s)
    for j in range(n_s):
        for a in range(3):
            acc_n = 0.0
            acc_d = 0.0
            for k in range(nq):
                acc_n += proj_n1[j, a, k] * q[k]
                acc_d += proj_d1[j, a, k] * q[k]
            p_mat[j, 3 + a] += acc_n
            d_mat[j, 3 + a] += acc_d
        alpha = incidence[j]
        for k in range(nq):
            alpha += rel[j, k] * q[k]
        for k in range(nxi):
            alpha += rel[j, nq + k] * xi[k]
        uj = 0.0
        wn = 0.0
        ad = 0.0
        for t in range(col_ptr[j], col_ptr[j + 1]):  # the strip's non-zero columns (strip_columns)
            i = cols[t]
            uj -= d_mat[j, i] * vel[i]
            wn += p_mat[j, i] * vel[i]
            ad += proj_p[j, i] * vel[i]
        if has_wind:
            for a in range(3):
                uj += d[j, a] * wind_c[j, a]
                wn -= n[j, a] * wind_c[j, a]
        wea = wn + uj * alpha
        flap = flap_sign[j] * u[flap_index[j]] if flap_index[j] > 0 else 0.0
        ub = uj * flap
        w0 = wea - ab[j] * ad + ub * flap_w[j, 0]
        w1 = semichord[j] * ad + ub * flap_w[j, 1]
        w2 = ub * flap_w[j, 2]
        alpha_el[j] = alpha
        u0[j] = uj
        w_ea[j] = wea
        w34[j] = w0 + 0.5 * w1
        wc[j] = w34[j] - lam0[j]
        w_moment[j] = w0 - lam0[j] - 0.5 * w2
        alpha_chord[j] = alpha + flap * (flap_w[j, 0] + 0.5 * flap_w[j, 1])
        adot[j] = ad
    return p_mat, d_mat, alpha_el, u0, w_ea, w34, wc, w_moment, alpha_chord, adot


@_jit
def compressibility_factor(prandtl_glauert, mach):
    """beta with Cl_alpha(M) = Cl_alpha0 / beta: sqrt(1 - M^2), M capped at 0.95 (Prandtl-Glauert; H. Glauert,
    Proc. R. Soc. Lond. A 118, 113-119, 1928; the paper's "Numerical Model"), or 1 without the correction."""
    return math.sqrt(1.0 - min(mach, _MACH_CAP) ** 2) if prandtl_glauert else 1.0


@_jit
def circulatory(F, I, u0, wc, w_moment, alpha_chord, rho, mach):
    """Circulatory lift, moment about the EA, lift x flow angle, drag per unit span, flow angle.

    L = Cl_a rho b u0 (w0 + w1/2 - lambda0) [N/m];  M_EA = (Cl_a/2) rho b^2 u0 (w0 - lambda0 - w2/2) + a b L
    [N];  Cl_a = Cl_a0 / beta with beta = sqrt(1 - min(M, 0.95)^2) (Prandtl-Glauert, Glauert 1928) or 1
    (compressibility "none"). Flow angle relative to the component axes a0 = (w0 + w1/2 - lambda0)/u0 -
    alpha_chord (formed as products with the lift, without dividing by u0); drag = induced L alpha_e
    (1 - Cl_a0/2 pi) + rho u0^2 b cd0 (module docstring of :mod:`flexsim.model.coupling`).
    """
    beta = compressibility_factor(_flag(I, PRANDTL_GLAUERT) != 0, mach)
    beta_i = 1.0 if _flag(I, PAPER) else beta  # induced angle of the compressible lift (physical formulation)
    b = _f1(F, I, SEMICHORD)
    k0 = _f1(F, I, K0)
    ab = _f1(F, I, AB)
    cd0 = _f1(F, I, CD0)
    n_s = b.shape[0]
    lift = np.empty(n_s)
    moment = np.empty(n_s)
    lift_tilt = np.empty(n_s)
    drag = np.empty(n_s)
    flow_angle = np.empty(n_s)
    for j in range(n_s):
        two_pi_rho_b = 2.0 * np.pi * rho * b[j] * (k0[j] / beta)
        lift[j] = two_pi_rho_b * u0[j] * wc[j]
        moment[j] = 0.5 * two_pi_rho_b * b[j] * u0[j] * w_moment[j] + ab[j] * lift[j]
        flow = wc[j] - u0[j] * alpha_chord[j]  # u0 x flow angle [m/s]
        lift_tilt[j] = two_pi_rho_b * wc[j] * flow
        drag[j] = two_pi_rho_b * wc[j] * wc[j] * (1.0 - k0[j]) / beta_i + rho * u0[j] * u0[j] * b[j] * cd0[j]
        flow_angle[j] = flow / max(u0[j], 1.0)
    return lift, moment, lift_tilt, drag, flow_angle


@_jit
def tail_downwash(wing_weight, u0, wc, speed, beta, gradient):
    """Downwash angle epsilon [rad] of the wing at the horizontal tail (not in the paper;
    :func:`flexsim.model.coupling.tail_downwash`): epsilon = (d epsilon/d alpha)_0 L_w / L_alpha0,w =
    gradient sum_j weight_j u0_j wc_j / (beta max(V, 1)^2) (USAF DATCOM sec. 4.4.1 compressibility scaling)."""
    acc = 0.0
    for j in range(u0.shape[0]):
        acc += wing_weight[j] * (u0[j] * wc[j])
    return gradient * acc / (beta * max(speed, 1.0) ** 2)


@_jit
def downwash_shift(F, I, vel, u0, wc, mach):
    """Change of the tail strips' normal velocity relative to the air in the wing's downwash, (n_s,) [m/s]:
    -epsilon V (n . z_b) (an air velocity epsilon V along body z at the tail; it shifts w_EA, w0 + w1/2 and the
    moment's downwash, not the inflow forcing or the apparent mass). Zero without a downwash gradient."""
    n_s = u0.shape[0]
    out = np.zeros(n_s)
    gradient = _f1(F, I, AERO_FLOATS)[0]
    if gradient == 0.0:
        return out
    speed = math.sqrt(vel[0] * vel[0] + vel[1] * vel[1] + vel[2] * vel[2])
    beta = compressibility_factor(_flag(I, PRANDTL_GLAUERT) != 0, mach)
    eps = tail_downwash(_f1(F, I, DW_WING_WEIGHT), u0, wc, speed, beta, gradient)
    nz = _f1(F, I, DW_TAIL_NZ)
    for j in range(n_s):
        out[j] = -eps * speed * nz[j]
    return out


@_jit
def aero_evaluate(F, I, q, xi, vel, lam, u, rho, mach, wind_c, has_wind):
    """Added mass M_a (n_v, n_v), explicit generalized aerodynamic force Q_a (n_v,) and the inflow terms.

    Eq. (28), force resolution "physical": f = L (-n - a0 d) + D (d - a0 n); "paper" on wing/stabilizer
    strips: f = -L n + L (n_x / d_x) d. Each strip's force and moment enter as width * G^T [f; M_EA p]
    (eqs. 17-24); the tail strips in the wing's downwash (:func:`downwash_shift`). Apparent mass (pi rho b^2,
    reference section 1.4): w_EA_dot = row0 V_dot + w_ea_x, with
    row0 = n^T A - alpha_el d^T A - a b p^T B and the explicit part w_ea_x (omega x q-derivative terms and
    u0 times the elastic pitch rate). M_a = sum_j rho pr_w (n^T A - a b p^T B)^T row0 + rho sum_j pr_w b^2/8
    (p^T B)^T (p^T B), the last sum constant per unit density (field ``apparent_pitch``, built by
    :class:`flexsim.model.coupling.AeroCoupling`).

    Returns m_a, q_a, row0 (n_s, n_v), w_ea_x (n_s,), u0 (n_s,).
    """
    p_mat, d_mat, alpha_el, u0, w_ea, w34, wc, w_moment, alpha_chord, adot = strip_kinematics(
        F, I, q, xi, vel, lam, u, wind_c, has_wind)
    shift = downwash_shift(F, I, vel, u0, wc, mach)  # the tail in the wing's downwash
    for j in range(shift.shape[0]):
        wc[j] += shift[j]
        w_moment[j] += shift[j]
    r_mat = _f2(F, I, PROJ_P)
    ab = _f1(F, I, AB)
    b = _f1(F, I, SEMICHORD)
    lift, moment, lift_tilt, drag, flow_angle = circulatory(F, I, u0, wc, w_moment, alpha_chord, rho, mach)
    w = _f1(F, I, WIDTH)
    rel = _f2(F, I, REL)
    pr_w0 = _f1(F, I, PR_W)
    paper = _f1(F, I, PAPER_STRIPS)
    n_over_d_x = _f1(F, I, N_OVER_D_X)
    proj_n1 = _f3(F, I, PROJ_N1)
    proj_d1 = _f3(F, I, PROJ_D1)
    is_paper = _flag(I, PAPER) != 0
    nq = q.shape[0]
    n_el = rel.shape[1]
    n_s = lift.shape[0]
    n_v = vel.shape[0]
    w_ea_x = np.empty(n_s)
    left = np.empty((n_s, n_v))  # pr_w (n^T A - a b p^T B)
    right = np.empty((n_s, n_v))  # row0
    g_n = np.empty(n_s)
    g_d = np.empty(n_s)
    g_r = np.empty(n_s)
    for j in range(n_s):
        c_n = -lift[j] - drag[j] * flow_angle[j]  # eq. (28): f = L (-n - a0 d) + D (d - a0 n)
        c_d = drag[j] - lift_tilt[j]
        if is_paper and paper[j] != 0.0:  # eq. (28) with d = l alpha_i0: no body-x component
            c_n = -lift[j]
            c_d = lift[j] * n_over_d_x[j]
        pdot = 0.0
        ddot = 0.0
        for a in range(3):
            pn = 0.0
            pd = 0.0
            for k in range(nq):
                pn += proj_n1[j, a, k] * vel[6 + k]
                pd += proj_d1[j, a, k] * vel[6 + k]
            pdot += pn * vel[3 + a]
            ddot += pd * vel[3 + a]
        relv = 0.0
        for e in range(n_el):
            relv += rel[j, e] * vel[6 + e]
        wx = pdot - alpha_el[j] * ddot + u0[j] * relv
        prw = rho * pr_w0[j]
        for i in range(n_v):
            lv = p_mat[j, i] - ab[j] * r_mat[j, i]
            right[j, i] = lv - alpha_el[j] * d_mat[j, i]
            left[j, i] = prw * lv
        w_ea_x[j] = wx
        g_n[j] = w[j] * c_n - prw * wx
        g_d[j] = w[j] * c_d
        g_r[j] = w[j] * moment[j] + ab[j] * prw * wx
    # M_a = left^T right + rho sum_j pr_w b^2/8 (p^T B)^T (p^T B), the second term constant per unit density
    m_a = left.T @ right
    pitch = _f2(F, I, APPARENT_PITCH)
    for i in range(n_v):
        for k in range(n_v):
            m_a[i, k] += rho * pitch[i, k]
    q_a = np.zeros(n_v)
    for j in range(n_s):
        for i in range(n_v):
            q_a[i] += p_mat[j, i] * g_n[j] + d_mat[j, i] * g_d[j] + r_mat[j, i] * g_r[j]
    return m_a, q_a, right, w_ea_x, u0


@_jit
def inflow_rate(F, I, row0, w_ea_x, u0, lam, vdot):
    """Finite-state inflow derivative (reference section 2.1, Peters et al. 1995) with the solved V_dot:
    lambda_dot = A^-1 [c (w0_dot + w1_dot/2) - (u0/b) lambda] for every unsteady strip, with
    w0_dot + w1_dot/2 = (row0 + b/2 p^T B) V_dot + w_ea_x [m/s^2]. Returns (n_u N,) [m/s^2]."""
    nin = _flag(I, N_PER_STRIP)
    idx = _i1(I, INFLOW_IDX)
    semichord = _f1(F, I, SEMICHORD)
    proj_p = _f2(F, I, PROJ_P)
    a_inv = _f2(F, I, A_INV)
    a_inv_c = _f1(F, I, A_INV_C)
    col_ptr = _i1(I, STRIP_COL_PTR)
    cols = _i1(I, STRIP_COLS)
    out = np.empty(idx.shape[0] * nin)
    for c in range(idx.shape[0]):
        j = idx[c]
        forcing = w_ea_x[j]
        for t in range(col_ptr[j], col_ptr[j + 1]):  # the strip's non-zero columns (strip_columns)
            i = cols[t]
            forcing += (row0[j, i] + 0.5 * semichord[j] * proj_p[j, i]) * vdot[i]
        decay = u0[j] / semichord[j]
        for r in range(nin):
            acc = 0.0
            for k in range(nin):
                acc += a_inv[r, k] * lam[c * nin + k]
            out[c * nin + r] = forcing * a_inv_c[r] - decay * acc
    return out


@_jit
def point_velocity(g0, g1, offset, j, q, vel):
    """Velocity v_p (3,) [m/s] of attached point j and the q part g1[j] q (3, 3) of its map A_j(q), component axes:
    v_p = A_j(q) V + omega_sec x rho_j with A_j(q) = g0[j, 0:3] + g1[j] q on the omega columns and omega_sec =
    g0[j, 3:6] V (paper eqs. 5-6, 18; drag items and slender bodies)."""
    n_v = vel.shape[0]
    nq = q.shape[0]
    g1q = np.empty((3, 3))
    for r in range(3):
        for c in range(3):
            acc = 0.0
            for k in range(nq):
                acc += g1[j, r, c, k] * q[k]
            g1q[r, c] = acc
    vp = np.empty(3)
    om0 = om1 = om2 = 0.0
    for i in range(n_v):
        om0 += g0[j, 3, i] * vel[i]
        om1 += g0[j, 4, i] * vel[i]
        om2 += g0[j, 5, i] * vel[i]
    for r in range(3):
        acc = 0.0
        for i in range(n_v):
            acc += g0[j, r, i] * vel[i]
        vp[r] = acc + g1q[r, 0] * vel[3] + g1q[r, 1] * vel[4] + g1q[r, 2] * vel[5]
    rho_j = offset[j]
    vp[0] += om1 * rho_j[2] - om2 * rho_j[1]
    vp[1] += om2 * rho_j[0] - om0 * rho_j[2]
    vp[2] += om0 * rho_j[1] - om1 * rho_j[0]
    return vp, g1q


@_jit
def parasite_drag(F, I, q, vel, rho):
    """Generalized force of the drag items (Raymer 2018 sec. 12.5; :mod:`flexsim.model.drag`), (n_v,).

    f_i = -1/2 rho f |v_p| v_p at the item's point (component axes, :func:`point_velocity`);
    Q = A_i(q)^T f_i + B_i^T (rho_i x f_i) (virtual work, eqs. 17-24) [N, N m].
    """
    n_v = vel.shape[0]
    out = np.zeros(n_v)
    area = _f1(F, I, DRAG_AREA)
    g0 = _f3(F, I, DRAG_G0)
    g1 = _f4(F, I, DRAG_G1)
    offset = _f2(F, I, DRAG_OFFSET)
    for j in range(area.shape[0]):
        vp, g1q = point_velocity(g0, g1, offset, j, q, vel)
        rho_i = offset[j]
        speed = math.sqrt(vp[0] * vp[0] + vp[1] * vp[1] + vp[2] * vp[2])
        c = -0.5 * rho * area[j] * speed
        f0, f1, f2 = c * vp[0], c * vp[1], c * vp[2]
        mu0 = rho_i[1] * f2 - rho_i[2] * f1
        mu1 = rho_i[2] * f0 - rho_i[0] * f2
        mu2 = rho_i[0] * f1 - rho_i[1] * f0
        for i in range(n_v):
            out[i] += g0[j, 0, i] * f0 + g0[j, 1, i] * f1 + g0[j, 2, i] * f2
            out[i] += g0[j, 3, i] * mu0 + g0[j, 4, i] * mu1 + g0[j, 5, i] * mu2
        for a in range(3):  # the q part of A_i(q) on the omega columns
            out[3 + a] += g1q[0, a] * f0 + g1q[1, a] * f1 + g1q[2, a] * f2
    return out


@_jit
def munk_moments(v_p, axis, coeff):
    """Munk moment M = coeff (v . a)(v x a) of each body (k, 3) [N m] (Munk, NACA Report 184, 1924; Newman,
    *Marine Hydrodynamics*, 1977, sec. 4.13): v_p (k, 3) velocity relative to the air [m/s], axis (k, 3) unit
    axes, coeff (k,) = rho Vol (k2 - k1) [kg]; all in one set of axes."""
    out = np.empty((v_p.shape[0], 3))
    for j in range(v_p.shape[0]):
        vp = v_p[j]
        ax = axis[j]
        c = coeff[j] * (vp[0] * ax[0] + vp[1] * ax[1] + vp[2] * ax[2])
        out[j, 0] = c * (vp[1] * ax[2] - vp[2] * ax[1])
        out[j, 1] = c * (vp[2] * ax[0] - vp[0] * ax[2])
        out[j, 2] = c * (vp[0] * ax[1] - vp[1] * ax[0])
    return out


@_jit
def body_moments(F, I, q, vel, rho):
    """Munk moment of every slender body (k, 3) [N m], component axes (:mod:`flexsim.model.bodies`;
    :func:`munk_moments` of the body velocities of :func:`point_velocity`)."""
    vol_dk = _f1(F, I, BODY_VOL_DK)
    g0 = _f3(F, I, BODY_G0)
    g1 = _f4(F, I, BODY_G1)
    offset = _f2(F, I, BODY_OFFSET)
    v_p = np.empty((vol_dk.shape[0], 3))
    for j in range(vol_dk.shape[0]):
        vp, _ = point_velocity(g0, g1, offset, j, q, vel)
        v_p[j, 0], v_p[j, 1], v_p[j, 2] = vp[0], vp[1], vp[2]
    return munk_moments(v_p, _f2(F, I, BODY_AXIS), rho * vol_dk)


@_jit
def body_force(F, I, q, vel, rho):
    """Q_body = sum_i B_i^T M_i (n_v,) [N, N m] of the Munk moments (virtual work, eqs. 17-24)."""
    n_v = vel.shape[0]
    out = np.zeros(n_v)
    mom = body_moments(F, I, q, vel, rho)
    g0 = _f3(F, I, BODY_G0)
    for j in range(mom.shape[0]):
        for i in range(n_v):
            out[i] += g0[j, 3, i] * mom[j, 0] + g0[j, 4, i] * mom[j, 1] + g0[j, 5, i] * mom[j, 2]
    return out


# ------------------------------------------------------------------ wind
@_jit
def gust_profile(s, amplitude, gradient_length, persistent):
    """1-cos gust velocity U(s) [m/s] at penetration distance s [m] (CS-25.341(a); MIL-F-8785C 3.7.3):
    (U_ds/2)(1 - cos(pi s/H)) on [0, 2H] (persistent: on [0, H], then U_ds), 0 elsewhere."""
    end = gradient_length if persistent else 2.0 * gradient_length
    if persistent and s > gradient_length:
        return amplitude
    if 0.0 <= s <= end:
        return 0.5 * amplitude * (1.0 - math.cos(math.pi * s / gradient_length))
    return 0.0


@_jit
def dryden_along_track(grid, spacing, xi):
    """Frozen Dryden field (u, v, w) [m/s] at distance xi [m] along the track: linear interpolation on the
    periodic grid (3, n) of points ``spacing`` apart (MIL-F-8785C 3.7.2, Taylor's hypothesis)."""
    n = grid.shape[1]
    pos = xi / spacing
    cell = math.floor(pos)
    frac = pos - cell
    i0 = int(cell - n * math.floor(cell / n))
    i1 = 0 if i0 + 1 == n else i0 + 1
    out = np.empty(3)
    for c in range(3):
        out[c] = grid[c, i0] * (1.0 - frac) + grid[c, i1] * frac
    return out


@_jit
def gust_profiles(s, amplitude, gradient_length, persistent):
    """:func:`gust_profile` at every penetration distance of s (k,) [m]."""
    out = np.empty(s.shape[0])
    for j in range(s.shape[0]):
        out[j] = gust_profile(s[j], amplitude, gradient_length, persistent)
    return out


@_jit
def dryden_track(grid, spacing, xi):
    """:func:`dryden_along_track` at every distance of xi (k,) [m]: (k, 3) [m/s]."""
    out = np.empty((xi.shape[0], 3))
    for j in range(xi.shape[0]):
        out[j] = dryden_along_track(grid, spacing, xi[j])
    return out


@_jit
def wind_ned(gusts, turb, turb_grid, positions):
    """Air velocity [m/s], NED, at inertial positions (k, 3) [m] of a wind (:class:`WindData` arrays): the sum
    of its 1-cos gusts U(n . (r - r_front)) direction (plane fronts frozen in the air) and its Dryden fields
    sampled at the distance d . (r - origin) along their track and rotated to NED."""
    k = positions.shape[0]
    out = np.zeros((k, 3))
    for g in range(gusts.shape[0]):
        par = gusts[g]
        for j in range(k):
            s = 0.0
            for a in range(3):
                s += (positions[j, a] - par[8 + a]) * par[5 + a]
            val = gust_profile(s, par[0], par[1], par[11] != 0.0)
            for a in range(3):
                out[j, a] += val * par[2 + a]
    for t in range(turb.shape[0]):
        grid = turb_grid[:, int(turb[t, 13]):int(turb[t, 14])]
        ax = turb[t, 0:9].reshape((3, 3))
        for j in range(k):
            xi = 0.0
            for a in range(3):
                xi += (positions[j, a] - turb[t, 9 + a]) * ax[0, a]
            comp = dryden_along_track(grid, turb[t, 12], xi)
            for a in range(3):
                out[j, a] += comp[0] * ax[0, a] + comp[1] * ax[1, a] + comp[2] * ax[2, a]
    return out


@_jit
def strip_positions(F, I, pos, c):
    """Inertial positions R + C^T r of the strips' undeformed EA points (n_s, 3) [m], NED."""
    r = _f2(F, I, STRIP_POS)
    out = np.empty((r.shape[0], 3))
    for j in range(r.shape[0]):
        for a in range(3):
            out[j, a] = pos[a] + r[j, 0] * c[0, a] + r[j, 1] * c[1, a] + r[j, 2] * c[2, a]
    return out


@_jit
def strip_wind(F, I, w_ned, c):
    """Air velocity at the strips in their component axes (n_s, 3) [m/s]: C_i C w_NED."""
    dcm = _f3(F, I, STRIP_DCM)
    out = np.empty_like(w_ned)
    wb = np.empty(3)
    for j in range(w_ned.shape[0]):
        for a in range(3):
            wb[a] = c[a, 0] * w_ned[j, 0] + c[a, 1] * w_ned[j, 1] + c[a, 2] * w_ned[j, 2]
        for a in range(3):
            out[j, a] = dcm[j, a, 0] * wb[0] + dcm[j, a, 1] * wb[1] + dcm[j, a, 2] * wb[2]
    return out


# ------------------------------------------------------------------ the equations of motion
@_jit
def unpack(F, I, x):
    """Full-size (R, Theta, q, xi, V) from x, filling fixed or frozen blocks (AircraftModel.unpack)."""
    n_v, nq, nxi = _flag(I, N_V), _flag(I, NQ), _flag(I, NXI)
    vs = _flag(I, VEL_START)
    rigid = _flag(I, RIGID)
    if rigid:
        pos = x[0:3].copy()
        eul = x[3:6].copy()
    else:
        pos = np.zeros(3)
        eul = _f1(F, I, EULER_FIXED).copy()
    if _flag(I, USE_FROZEN):
        q = _f1(F, I, Q_FROZEN).copy()
        xi = _f1(F, I, XI_FROZEN).copy()
    else:
        q = x[_flag(I, Q_START):_flag(I, Q_START) + nq].copy()
        xi = x[_flag(I, XI_START):_flag(I, XI_START) + nxi].copy()
    if _flag(I, ALL_ACTIVE):
        vel = x[vs:vs + n_v].copy()
    else:
        vel = np.zeros(n_v)
        active = _i1(I, ACTIVE)
        for i in range(active.shape[0]):
            vel[active[i]] = x[vs + i]
        if not rigid:
            vel[0:3] = _f1(F, I, V_FIXED)
    return pos, eul, q, xi, vel


@_jit
def air(F, I, x):
    """(altitude [m] geometric, density of the aerodynamics [kg/m^3], speed of sound [m/s]) at state x:
    the tunnel density, else the fixed aerodynamic density, else ISA at -Z (restrained: altitude_m)."""
    fl = _f1(F, I, FLOATS)
    altitude = -x[2] if _flag(I, RIGID) else fl[1]
    hgp = _geopotential(altitude)
    if not math.isnan(fl[2]):
        rho = fl[2]
    elif not math.isnan(fl[3]):
        rho = fl[3]
    else:
        rho = isa_scalar(hgp)[0]
    return altitude, rho, _sound_speed(hgp)


@_jit
def assemble(F, I, x, u, wind_c, has_wind):
    """E = M(q) + M_a and f of E V_dot = f (full size, paper eq. 33 in velocity form, docs/design.md):

    f = -M_dot V + g(V, p) + [0, 0, dT/dq, 0] - K [0, 0, q, xi] - C_el V_el + M(q)[g_b; 0] + Q_T + Q_a + Q_D
    with p = M V, g_v = -omega x p_v, g_omega = -v x p_v - omega x p_omega (quasi-coordinates, eq. 33),
    g_b = C [0, 0, g] (eq. 32: Q_g = M(q) [g_b; 0] exactly, :mod:`flexsim.structure.loads`),
    Q_T = T_e (t0 + t1 q) (eqs. 17-24), Q_a and M_a from :func:`aero_evaluate`, Q_D from :func:`parasite_drag`,
    the slender bodies' Munk moments from :func:`body_force`.

    Returns m (n_v, n_v), f (n_v,), row0 (n_s, n_v), w_ea_x (n_s,), u0 (n_s,).
    """
    nq = _flag(I, NQ)
    pos, eul, q, xi, vel = unpack(F, I, x)
    m, dtdq, mdot_v = inertia(_f2(F, I, M0), _f3(F, I, H), _f4(F, I, M2), vel, q, vel[6:6 + nq])
    n_v = vel.shape[0]
    nxi = xi.shape[0]
    p = np.empty(n_v)  # M V
    f = np.empty(n_v)
    for i in range(n_v):
        acc = 0.0
        for k in range(n_v):
            acc += m[i, k] * vel[k]
        p[i] = acc
        f[i] = -mdot_v[i]
    v = vel[0:3]
    w = vel[3:6]
    # quasi-coordinate terms (eq. 33): -omega x p_v and -v x p_v - omega x p_omega
    f[0] -= w[1] * p[2] - w[2] * p[1]
    f[1] -= w[2] * p[0] - w[0] * p[2]
    f[2] -= w[0] * p[1] - w[1] * p[0]
    f[3] -= v[1] * p[2] - v[2] * p[1] + w[1] * p[5] - w[2] * p[4]
    f[4] -= v[2] * p[0] - v[0] * p[2] + w[2] * p[3] - w[0] * p[5]
    f[5] -= v[0] * p[1] - v[1] * p[0] + w[0] * p[4] - w[1] * p[3]
    # [0, 0, dT/dq, 0] - K [0, 0, q, xi] (eqs. 15, 33)
    k_b = _f2(F, I, K_BENDING)
    k_t = _f2(F, I, K_TORSION)
    for i in range(nq):
        acc = dtdq[i]
        for k in range(nq):
            acc -= k_b[i, k] * q[k]
        f[6 + i] += acc
    for i in range(nxi):
        acc = 0.0
        for k in range(nxi):
            acc += k_t[i, k] * xi[k]
        f[6 + nq + i] -= acc
    if _flag(I, HAS_DAMPING):
        c_el = _f2(F, I, C_EL)
        n_el = n_v - 6
        for i in range(n_el):
            acc = 0.0
            for k in range(n_el):
                acc += c_el[i, k] * vel[6 + k]
            f[6 + i] -= acc
    g = _f1(F, I, FLOATS)[0]
    if g != 0.0:
        # Q_g = M(q) [g_b; 0], g_b = C [0, 0, g] (eq. 32)
        sf, cf = math.sin(eul[0]), math.cos(eul[0])
        st, ct = math.sin(eul[1]), math.cos(eul[1])
        g0, g1, g2 = -st * g, sf * ct * g, cf * ct * g
        for i in range(n_v):
            f[i] += m[i, 0] * g0 + m[i, 1] * g1 + m[i, 2] * g2
    if u[0] != 0.0:
        # Q_T = T_e (t0 + t1 q) (eqs. 17-24)
        t0 = _f1(F, I, THRUST_T0)
        t1 = _f2(F, I, THRUST_T1)
        for i in range(n_v):
            acc = t0[i]
            for k in range(nq):
                acc += t1[i, k] * q[k]
            f[i] += u[0] * acc
    n_s = _f1(F, I, SEMICHORD).shape[0]
    row0 = np.zeros((n_s, n_v))
    w_ea_x = np.zeros(n_s)
    u0 = np.zeros(n_s)
    if _flag(I, HAS_AERO):
        _, rho, a_sound = air(F, I, x)
        mach = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) / a_sound
        lam = x[_flag(I, INFLOW_START):_flag(I, INFLOW_START) + _flag(I, N_INFLOW)]
        m_a, q_a, row0, w_ea_x, u0 = aero_evaluate(F, I, q, xi, vel, lam, u, rho, mach, wind_c, has_wind)
        for i in range(n_v):
            f[i] += q_a[i]
            for k in range(n_v):
                m[i, k] += m_a[i, k]
        if _flag(I, HAS_DRAG):
            q_d = parasite_drag(F, I, q, vel, rho)
            for i in range(n_v):
                f[i] += q_d[i]
        if _flag(I, HAS_BODIES):
            q_b = body_force(F, I, q, vel, rho)
            for i in range(n_v):
                f[i] += q_b[i]
    return m, f, row0, w_ea_x, u0


@_jit
def aerodynamic_force(F, I, x, u, wind_c, has_wind):
    """Generalized aerodynamic force without the apparent-mass terms (n_v,): strip airloads (explicit part of
    :func:`aero_evaluate`) plus parasite drag and body moments; rows 0-2 force [N] (body), 3-5 moment about o [N m]."""
    pos, eul, q, xi, vel = unpack(F, I, x)
    out = np.zeros(vel.shape[0])
    if not _flag(I, HAS_AERO):
        return out
    _, rho, a_sound = air(F, I, x)
    mach = math.sqrt(vel[0:3] @ vel[0:3]) / a_sound
    lam = x[_flag(I, INFLOW_START):_flag(I, INFLOW_START) + _flag(I, N_INFLOW)]
    _, q_a, _, _, _ = aero_evaluate(F, I, q, xi, vel, lam, u, rho, mach, wind_c, has_wind)
    if _flag(I, HAS_DRAG):
        q_a = q_a + parasite_drag(F, I, q, vel, rho)
    if _flag(I, HAS_BODIES):
        q_a = q_a + body_force(F, I, q, vel, rho)
    return q_a


@_jit
def strip_wind_at(F, I, gusts, turb, turb_grid, x):
    """Strip air velocity (component axes, (n_s, 3) [m/s]) of a wind (:class:`WindData` arrays) at state x,
    and whether there is any."""
    n_s = _f1(F, I, SEMICHORD).shape[0]
    if not _flag(I, HAS_AERO) or (gusts.shape[0] == 0 and turb.shape[0] == 0):
        return np.zeros((n_s, 3)), False
    pos, eul, _, _, _ = unpack(F, I, x)
    c = dcm_321(eul[0], eul[1], eul[2])
    w_ned = wind_ned(gusts, turb, turb_grid, strip_positions(F, I, pos, c))
    return strip_wind(F, I, w_ned, c), True


@_jit
def _gauss(a, b):
    """Overwrite b (n, r) with x of a x = b, a (n, n) overwritten with its LU factors: Gaussian elimination with
    partial pivoting (the LU of LAPACK's gesv, unblocked). Raises ZeroDivisionError on an exactly singular matrix;
    a non-finite a or b gives a non-finite x (no check, so that an integrator sees the non-finite derivative)."""
    n = a.shape[0]
    r = b.shape[1]
    for k in range(n):
        piv = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                piv = i
        if piv != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[piv, j]
                a[piv, j] = tmp
            for j in range(r):
                tmp = b[k, j]
                b[k, j] = b[piv, j]
                b[piv, j] = tmp
        pivot = a[k, k]
        if pivot == 0.0:
            raise ZeroDivisionError("system matrix of the equations of motion is singular")
        inv = 1.0 / pivot
        for i in range(k + 1, n):
            f = a[i, k] * inv
            if f != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= f * a[k, j]
                for j in range(r):
                    b[i, j] -= f * b[k, j]
    for k in range(n - 1, -1, -1):
        for c in range(r):
            acc = b[k, c]
            for j in range(k + 1, n):
                acc -= a[k, j] * b[j, c]
            b[k, c] = acc / a[k, k]


@_jit
def solve(a, b):
    """x with a x = b by Gaussian elimination with partial pivoting (a (n, n), b (n,); :func:`_gauss`).
    Raises ZeroDivisionError on an exactly singular matrix."""
    n = b.shape[0]
    lu = a.copy()
    x = np.empty((n, 1))
    for i in range(n):
        x[i, 0] = b[i]
    _gauss(lu, x)
    return x[:, 0].copy()


@_jit
def blocks_decoupled(m, perm, ptr):
    """Whether the entries of m between different diagonal blocks of :func:`solve_structure` are all zero."""
    nb = ptr.shape[0] - 2
    for b in range(nb):
        for c in range(nb):
            if c == b:
                continue
            for i in range(ptr[b], ptr[b + 1]):
                for j in range(ptr[c], ptr[c + 1]):
                    if m[perm[i], perm[j]] != 0.0:
                        return False
    return True


@_jit
def block_solve(m, f, perm, ptr):
    """V_dot with E V_dot = f over the active entries, by block elimination (:func:`solve_structure`), (n_v,)
    (zero in the inactive entries); m (n_v, n_v) = E, f (n_v,).

    With E ordered [[D, E_dc], [E_cd, E_cc]], D block-diagonal (blocks coupled only through the core c):
    X_b = D_b^-1 [E_bc, f_b] per block (:func:`_gauss`), the Schur complement S = E_cc - sum_b E_cb X_b[:, :-1]
    and g = f_c - sum_b E_cb X_b[:, -1]; V_c = S^-1 g; V_b = X_b[:, -1] - X_b[:, :-1] V_c. The same algebra as one
    elimination of the whole matrix (the GTM: a 10 x 10 core and five 4 x 4 blocks instead of 30 x 30); pivoting
    is within each block and within S, which suffices for E = M(q) + M_a, M(q) symmetric positive definite
    (eq. 33) and the apparent mass small beside it. If an entry between two blocks is not zero (a pattern that
    :func:`solve_structure` did not foresee), one elimination of the whole active matrix (:func:`_gauss`).
    Raises ZeroDivisionError on an exactly singular block or core.
    """
    n_v = m.shape[0]
    nb = ptr.shape[0] - 2
    c0 = ptr[nb]
    n_a = ptr[nb + 1]
    nc = n_a - c0
    if nb == 0 and n_a == n_v:  # no split, every entry active: one elimination of m itself
        return solve(m, f)
    out = np.zeros(n_v)
    if not blocks_decoupled(m, perm, ptr):
        a = np.empty((n_a, n_a))
        x = np.empty((n_a, 1))
        for i in range(n_a):
            x[i, 0] = f[perm[i]]
            for j in range(n_a):
                a[i, j] = m[perm[i], perm[j]]
        _gauss(a, x)
        for i in range(n_a):
            out[perm[i]] = x[i, 0]
        return out
    s = np.empty((nc, nc))
    g = np.empty((nc, 1))
    for i in range(nc):
        g[i, 0] = f[perm[c0 + i]]
        for j in range(nc):
            s[i, j] = m[perm[c0 + i], perm[c0 + j]]
    x = np.empty((c0, nc + 1))
    for b in range(nb):
        lo = ptr[b]
        k = ptr[b + 1] - lo
        d = np.empty((k, k))
        xb = np.empty((k, nc + 1))
        for i in range(k):
            ri = perm[lo + i]
            for j in range(k):
                d[i, j] = m[ri, perm[lo + j]]
            for j in range(nc):
                xb[i, j] = m[ri, perm[c0 + j]]
            xb[i, nc] = f[ri]
        _gauss(d, xb)
        for i in range(nc):
            ri = perm[c0 + i]
            for t in range(k):
                e = m[ri, perm[lo + t]]
                if e != 0.0:
                    for j in range(nc):
                        s[i, j] -= e * xb[t, j]
                    g[i, 0] -= e * xb[t, nc]
        for t in range(k):
            for j in range(nc + 1):
                x[lo + t, j] = xb[t, j]
    _gauss(s, g)
    for i in range(nc):
        out[perm[c0 + i]] = g[i, 0]
    for t in range(c0):
        acc = x[t, nc]
        for j in range(nc):
            acc -= x[t, j] * g[j, 0]
        out[perm[t]] = acc
    return out


@_jit
def _rhs(F, I, x, u, wind_c, has_wind):
    m, f, row0, w_ea_x, u0 = assemble(F, I, x, u, wind_c, has_wind)
    act = _i1(I, ACTIVE)
    full = block_solve(m, f, _i1(I, SOLVE_PERM), _i1(I, SOLVE_PTR))
    dx = np.empty_like(x)
    vs = _flag(I, VEL_START)
    na = act.shape[0]
    for i in range(na):
        dx[vs + i] = full[act[i]]
    n_in = _flag(I, N_INFLOW)
    if n_in:
        i0 = _flag(I, INFLOW_START)
        dx[i0:i0 + n_in] = inflow_rate(F, I, row0, w_ea_x, u0, x[i0:i0 + n_in], full)
    vel = x[vs:vs + na]
    if _flag(I, RIGID):
        phi, theta, psi = x[3], x[4], x[5]
        c = dcm_321(phi, theta, psi)
        for a in range(3):  # R_dot = C^T v (eq. 4)
            dx[a] = c[0, a] * vel[0] + c[1, a] * vel[1] + c[2, a] * vel[2]
        # Euler rates Theta_dot = E^-1 omega (paper eq. 4; kinematics.euler_rate_matrix_inverse)
        sf, cf = math.sin(phi), math.cos(phi)
        tt, sec = math.tan(theta), 1.0 / math.cos(theta)
        p_, q_, r_ = vel[3], vel[4], vel[5]
        dx[3] = p_ + sf * tt * q_ + cf * tt * r_
        dx[4] = cf * q_ - sf * r_
        dx[5] = sf * sec * q_ + cf * sec * r_
    n_el = 0 if _flag(I, USE_FROZEN) else _flag(I, NQ) + _flag(I, NXI)
    if n_el:
        off = 6 if _flag(I, RIGID) else 0
        q0 = _flag(I, Q_START)
        dx[q0:q0 + n_el] = vel[off:off + n_el]
    return dx


@_entry
def rhs(F, I, gusts, turb, turb_grid, x, u):
    """State derivative x_dot of the nonlinear model (paper eqs. 4, 33) with a wind (:class:`WindData`
    arrays; :data:`NO_WIND`: still air).

    Solves E V_dot = f (:func:`solve`), then lambda_dot with the solved accelerations (no acceleration
    lagged), R_dot = C^T v, Theta_dot = E^-1 omega, [q, xi]_dot = [s, eta]. x (n_states,), u (4,)
    [T_e (N), delta_a, delta_e, delta_r (rad)].
    """
    return _rhs_wind(F, I, gusts, turb, turb_grid, x, u)


@_jit
def _rhs_wind(F, I, gusts, turb, turb_grid, x, u):
    wind_c, has_wind = strip_wind_at(F, I, gusts, turb, turb_grid, x)
    return _rhs(F, I, x, u, wind_c, has_wind)


@_entry
def rhs_strip_wind(F, I, x, u, wind_c):
    """:func:`rhs` with the strip air velocity (n_s, 3), component axes [m/s], given (any wind callable)."""
    return _rhs(F, I, x, u, wind_c, True)


@_entry
def rhs_batch(F, I, rows, gusts, turb, turb_grid, xs, us):
    """x_dot of N aircraft of one model in one call: xs (N, n_states), us (N, 4) -> (N, n_states); aircraft i
    sees the gusts rows[i, 0]:rows[i, 1] and Dryden fields rows[i, 2]:rows[i, 3] (:class:`BatchWind`)."""
    out = np.empty_like(xs)
    for i in range(xs.shape[0]):
        out[i] = _rhs_wind(F, I, gusts[rows[i, 0]:rows[i, 1]], turb[rows[i, 2]:rows[i, 3]], turb_grid, xs[i], us[i])
    return out


@_entry
def air_velocity_rows(rows, gusts, turb, turb_grid, pos, eul, v):
    """Velocity of the body origin relative to the air, body axes [m/s], of N aircraft: v - C w(R), with
    pos (N, 3) [m] NED, eul (N, 3) [rad], v (N, 3) [m/s] body, and w the wind (NED, :func:`wind_ned`) of
    aircraft i (``rows[i]`` of a :class:`BatchWind`) at its origin; (N, 3)."""
    out = np.empty_like(v)
    for i in range(v.shape[0]):
        w = wind_ned(gusts[rows[i, 0]:rows[i, 1]], turb[rows[i, 2]:rows[i, 3]], turb_grid, pos[i:i + 1])
        c = dcm_321(eul[i, 0], eul[i, 1], eul[i, 2])
        for a in range(3):
            out[i, a] = v[i, a] - (c[a, 0] * w[0, 0] + c[a, 1] * w[0, 1] + c[a, 2] * w[0, 2])
    return out
