"""Data layout of the compiled kernels: the packed buffers (F, I), their field views, and the compile decorator.

A model's frozen arrays are packed once into one float64 buffer ``F`` and one int64 buffer ``I`` (:func:`pack`;
:class:`KernelData`); a kernel takes views of the fields it needs by name (``_f2(F, I, M0)``: the field's offset
and shape are in the header of ``I``). Two flat arrays compile and dispatch fast; a NamedTuple of ~50 arrays cost
about 1.4 s of compilation per kernel signature and ~10 us per call (measured). :func:`pack` also derives the
sparsity of the strips' rows (:func:`strip_columns`) and the elimination order of E V_dot = f
(:func:`solve_structure`; paper eqs. 8-10, 33).

:data:`kernel` compiles a function with numba (``cache=True``, ``nogil``) and keys its on-disk cache on the source
of every file of this package (:func:`flexsim._numba_cache.depends_on`): the kernels call each other across the
package's files, and numba alone would key a cached function on its own file only.
"""

from __future__ import annotations

import sys
from typing import NamedTuple

import numpy as np
from numba import njit

from flexsim._arrays import frozen_array
from flexsim._numba_cache import depends_on

_numba = njit(cache=True, nogil=True)
_package = depends_on(sys.modules[__package__])


def kernel(function):
    """``numba.njit(cache=True, nogil=True)``, cache keyed on the whole package's source (module docstring)."""
    return _package(_numba(function))


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
    # [wing downwash gradient at the tail at M -> 0, frozen Mach of beta (nan: none)]; wing weights; n . z_body of the tail strips
    ("aero_floats", 1), ("dw_wing_weight", 1), ("dw_tail_nz", 1),
    # parasite drag items
    ("drag_area", 1), ("drag_g0", 3), ("drag_g1", 4), ("drag_offset", 2),
    # slender bodies (Munk moments): rho-free coefficient Vol (k2 - k1) [m^3], maps, offsets, unit axes
    ("body_vol_dk", 1), ("body_g0", 3), ("body_g1", 4), ("body_offset", 2), ("body_axis", 2),
    # the pitch part of the strips' apparent mass per unit density, sum_j pi b^4 w / 8 (p^T B)^T (p^T B) [m^4]
    ("apparent_pitch", 2),
    # terms switched at construction (flexsim.model.terms.Terms): the inertia's offset dq (nq,) [m]; per strip the
    # scales of the lift's tilt and of the drag in the force resolution and the drag per unit lift (n_s,); the
    # velocity offset the strips see (3,) [m/s]
    ("inertia_dq", 1), ("tilt_scale", 1), ("drag_scale", 1), ("drag_per_lift", 1), ("aero_dv", 1),
)
#: Int fields of I: flags and sizes (``ints``, entries below), active entries of V, flap control index per
#: strip, unsteady strips; derived by :func:`pack` (:func:`strip_columns`, :func:`solve_structure`): the columns
#: of V each strip's rows touch (CSR: pointers, indices) and the elimination order of E V_dot = f (order, pointers).
INT_FIELDS = ("ints", "active", "flap_index", "inflow_idx", "strip_col_ptr", "strip_cols", "solve_perm", "solve_ptr")
#: Entries of the ``ints`` field.
INT_NAMES = ("n_v", "nq", "nxi", "rigid", "use_frozen", "all_active", "n_states", "vel_start", "inflow_start", "n_inflow",
             "has_aero", "has_drag", "has_damping", "q_start", "xi_start", "finite_state", "n_inflow_per_strip",
             "prandtl_glauert", "paper", "has_bodies", "has_inertia_offset", "has_aero_dv")
_NF = len(FLOAT_FIELDS)
_HEAD = 5 * _NF + 2 * len(INT_FIELDS)
(FLOATS, EULER_FIXED, V_FIXED, Q_FROZEN, XI_FROZEN, M0, H, M2, K_BENDING, K_TORSION, C_EL, THRUST_T0, THRUST_T1,
 PROJ_N0, PROJ_D0, PROJ_N1, PROJ_D1, PROJ_P, REL, INCIDENCE, SEMICHORD, AB, K0, PR_W, WIDTH, CD0, FLAP_SIGN,
 PAPER_STRIPS, N_OVER_D_X, FLAP_W, D, N, STRIP_DCM, STRIP_POS, A_INV, A_INV_C, B_VEC, AERO_FLOATS, DW_WING_WEIGHT,
 DW_TAIL_NZ, DRAG_AREA, DRAG_G0, DRAG_G1, DRAG_OFFSET, BODY_VOL_DK, BODY_G0, BODY_G1, BODY_OFFSET, BODY_AXIS,
 APPARENT_PITCH, INERTIA_DQ, TILT_SCALE, DRAG_SCALE, DRAG_PER_LIFT, AERO_DV) = range(_NF)
INTS, ACTIVE, FLAP_INDEX, INFLOW_IDX, STRIP_COL_PTR, STRIP_COLS, SOLVE_PERM, SOLVE_PTR = range(len(INT_FIELDS))
(N_V, NQ, NXI, RIGID, USE_FROZEN, ALL_ACTIVE, N_STATES, VEL_START, INFLOW_START, N_INFLOW, HAS_AERO, HAS_DRAG,
 HAS_DAMPING, Q_START, XI_START, FINITE_STATE, N_PER_STRIP, PRANDTL_GLAUERT, PAPER, HAS_BODIES, HAS_INERTIA_OFFSET,
 HAS_AERO_DV) = range(len(INT_NAMES))


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
    (N, N); a_inv_c, b_vec (N,); aero_floats (2,) [d epsilon/d alpha at M -> 0, frozen Mach of the compressibility
    (nan: the flight's)]; dw_wing_weight, dw_tail_nz (n_s,); drag_area (k,); drag_g0
    (k, 6, n_v); drag_g1 (k, 3, 3, nq); drag_offset (k, 3); body_vol_dk (k_b,); body_g0, body_g1, body_offset
    like the drag's; body_axis (k_b, 3); inertia_dq (nq,); tilt_scale, drag_scale, drag_per_lift (n_s,); aero_dv (3,).
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


# ------------------------------------------------------------------ field views
@kernel
def _f1(F, I, k):
    o = I[5 * k]
    return F[o:o + I[5 * k + 1]]


@kernel
def _f2(F, I, k):
    o, a, b = I[5 * k], I[5 * k + 1], I[5 * k + 2]
    return F[o:o + a * b].reshape((a, b))


@kernel
def _f3(F, I, k):
    o, a, b, c = I[5 * k], I[5 * k + 1], I[5 * k + 2], I[5 * k + 3]
    return F[o:o + a * b * c].reshape((a, b, c))


@kernel
def _f4(F, I, k):
    o, a, b, c, d = I[5 * k], I[5 * k + 1], I[5 * k + 2], I[5 * k + 3], I[5 * k + 4]
    return F[o:o + a * b * c * d].reshape((a, b, c, d))


@kernel
def _i1(I, k):
    o = I[5 * _NF + 2 * k]
    return I[o:o + I[5 * _NF + 2 * k + 1]]


@kernel
def _flag(I, k):
    return I[I[5 * _NF] + k]

