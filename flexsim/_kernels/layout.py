"""Data layout of the compiled kernels: the packed buffers (F, I) generated from the terms' data classes.

Each physical term declares the arrays its kernel reads as a frozen dataclass in its own module (symbols, units,
frames and equations in the field's documentation), registered with :func:`term_data`: e.g. gravity
(:class:`~flexsim._kernels.gravity.GravityData`, eq. 32) beside its kernel. The fields of all registered classes
make the layout: :func:`pack` packs a model's arrays by field name into one float64 buffer ``F`` and one int64
buffer ``I`` (:class:`KernelData`), and a kernel takes views of its fields by the index the registration gave
(``_f2(F, I, M0)``: the field's offset and shape are in the header of ``I``). No list of positions is kept by hand:
a field exists once, in its term's class, and its index is generated from it. Two flat arrays compile and dispatch
fast; a NamedTuple of ~50 arrays cost about 1.4 s of compilation per kernel signature and ~10 us per call
(measured). :func:`pack` also derives the sparsity of the strips' rows (:func:`strip_columns`) and the elimination
order of E V_dot = f (:func:`solve_structure`; paper eqs. 8-10, 33).

Field kinds (:func:`packed`): ``"float"`` an array of F of the given rank; ``"flag"`` an int64 scalar (a size or a
switch, in I's flag array, read with :func:`_flag`); ``"ints"`` an int64 array of I (:func:`_i1`). The header of
I: I[0] = number of float fields n_f, then 5 entries per float field (offset, shape padded to rank 4), then 2 per
int array (offset, size); the flags are int array 0.

:data:`kernel` compiles a function with numba (``cache=True``, ``nogil``) and keys its on-disk cache on the source
of every file of this package (:func:`flexsim._numba_cache.depends_on`): the kernels call each other across the
package's files, and numba alone would key a cached function on its own file only.
"""

from __future__ import annotations

import dataclasses
import sys
from types import MappingProxyType
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


#: ``numba.njit(inline="always")``: a small accessor typed and compiled inside each caller. The field views below
#: are called with module-level constants, which numba types as literals: compiled as kernels of their own they
#: took one compilation per field (84 of them, 9.7 s of CPU in the first ``flexsim flutter``; measured).
inline = njit(inline="always")


# ------------------------------------------------------------------ the terms' data classes
_KINDS = ("float", "flag", "ints")
#: Registered fields by kind, in registration order: (name, rank, owner class name).
_FIELDS: dict[str, list[tuple[str, int, str]]] = {kind: [] for kind in _KINDS}
_FIELDS["ints"].append(("ints", 1, "layout"))  # int array 0: the flags
#: The registered term data classes, in registration order.
TERMS: list[type] = []


def packed(rank: int, doc: str, kind: str = "float"):
    """A field of a term's data class: an array of ``rank`` dimensions in F (``kind="float"``), an int64 scalar flag
    (``"flag"``, rank 0) or an int64 array of I (``"ints"``, rank 1); ``doc``: symbol, unit, frame, equation."""
    if kind not in _KINDS:
        raise ValueError(f"kind = {kind!r}: must be one of {', '.join(_KINDS)}")
    return dataclasses.field(default=None, metadata={"rank": rank, "doc": doc, "kind": kind})


def term_data(cls):
    """Register a term's frozen data class (class decorator): each field gets the next index of its kind, read back
    with ``cls.index[name]`` (module-level constants of the kernels, frozen into their machine code).

    Every class builds its own fields from the model: a static method ``fields_of(model) -> dict`` (its fields by
    name: float arrays, flags and int arrays alike) is called by :func:`fields_of` for
    :class:`flexsim.model.aircraft_model.AircraftModel` when it packs its data (the model's ``terms``, ``structure``,
    ``layout`` and parts ``aero``, ``parasite_drag``, ``bodies`` are set by then). Only :class:`SparsityData`, derived
    by :func:`pack` from the other fields, has none."""
    if not (dataclasses.is_dataclass(cls) and cls.__dataclass_params__.frozen):
        raise TypeError(f"{cls.__name__}: a term's data must be a frozen dataclass")
    taken = {n for fields in _FIELDS.values() for n, _, _ in fields}
    for f in dataclasses.fields(cls):  # all checked before any is registered
        if f.name in taken:
            raise ValueError(f"{cls.__name__}.{f.name}: a field of that name is already registered")
        if f.metadata.get("kind") not in _KINDS:
            raise ValueError(f"{cls.__name__}.{f.name}: declare it with packed(rank, doc, kind)")
    index = {}
    for f in dataclasses.fields(cls):
        kind = f.metadata["kind"]
        index[f.name] = len(_FIELDS[kind])
        _FIELDS[kind].append((f.name, f.metadata["rank"], cls.__name__))
    cls.index = MappingProxyType(index)
    TERMS.append(cls)
    return cls


def float_fields() -> tuple[tuple[str, int], ...]:
    """(name, rank) of every float field of F, in layout order (generated from the registered classes)."""
    return tuple((n, r) for n, r, _ in _FIELDS["float"])


def int_fields() -> tuple[str, ...]:
    """Names of the int arrays of I, in layout order (``ints``, the flags, first)."""
    return tuple(n for n, _, _ in _FIELDS["ints"])


def flag_names() -> tuple[str, ...]:
    """Names of the flags (entries of int array 0), in layout order."""
    return tuple(n for n, _, _ in _FIELDS["flag"])


class KernelData(NamedTuple):
    """The packed frozen data of one model (or of its strips alone): F float64, I int64, both read-only."""

    F: np.ndarray
    I: np.ndarray


def pack(floats: dict, ints: dict) -> KernelData:
    """Pack named arrays into (F, I) (missing fields are empty arrays of their rank; flags missing are 0).

    ``floats``: arrays by the name of a registered float field (shapes in each term's data class). ``ints``:
    ``ints`` a dict of flags by name, and int arrays by name. An unknown name is refused (ValueError). The
    sparsity fields are derived here from the float fields (:func:`strip_columns`, :func:`solve_structure`).
    """
    f_fields, i_fields, flags_ = float_fields(), int_fields(), flag_names()
    unknown = (set(floats) - {n for n, _ in f_fields}) | (set(ints) - set(i_fields)) | (set(ints.get("ints", {})) - set(flags_))
    if unknown:
        raise ValueError(f"kernel fields {sorted(unknown)}: not fields of any registered term data class")
    strip_ptr, strip_cols = strip_columns(floats)
    perm, ptr = solve_structure(floats, ints.get("active"), strip_ptr, strip_cols)
    ints = {**ints, "strip_col_ptr": strip_ptr, "strip_cols": strip_cols, "solve_perm": perm, "solve_ptr": ptr}
    nf = len(f_fields)
    head = np.zeros(1 + 5 * nf + 2 * len(i_fields), np.int64)
    head[0] = nf
    chunks, off = [], 0
    for k, (name, rank) in enumerate(f_fields):
        a = np.ascontiguousarray(floats.get(name, np.zeros((0,) * rank)), dtype=float)
        if a.ndim != rank:
            raise ValueError(f"kernel field {name}: rank {a.ndim}, expected {rank}")
        shape = a.shape + (1,) * (4 - rank)
        head[1 + 5 * k:1 + 5 * k + 5] = (off, *shape)
        chunks.append(a.ravel())
        off += a.size
    flags = np.zeros(len(flags_), np.int64)
    for name, value in ints.get("ints", {}).items():
        flags[flags_.index(name)] = int(value)
    int_chunks, ioff = [], head.size
    for k, name in enumerate(i_fields):
        a = flags if name == "ints" else np.asarray(ints.get(name, np.zeros(0)), dtype=np.int64).ravel()
        head[1 + 5 * nf + 2 * k:1 + 5 * nf + 2 * k + 2] = (ioff, a.size)
        int_chunks.append(a)
        ioff += a.size
    f = frozen_array(np.concatenate(chunks) if off else np.zeros(0))
    i = frozen_array(np.concatenate([head] + int_chunks), np.int64)
    return KernelData(f, i)


def fields_of(model, terms=None) -> dict:
    """The kernel fields of a model by name: the union of ``fields_of(model)`` of every registered term data class
    (or of ``terms``), each class filling its own fields only (a field of another class is refused, ValueError)."""
    values = {}
    for term in TERMS if terms is None else terms:
        build = getattr(term, "fields_of", None)
        if build is None:
            continue
        data = build(model)
        alien = set(data) - set(term.index)
        if alien:
            raise ValueError(f"{term.__name__}.fields_of: {sorted(alien)} are not fields of {term.__name__}")
        values.update(data)
    return values


def pack_fields(values: dict) -> KernelData:
    """:func:`pack` of fields given by name in one dict (as :func:`fields_of` gives them), each sorted into the float
    fields, the flags or the int arrays by the kind its class declared (an unknown name: ValueError)."""
    kinds = {name: kind for kind, fields in _FIELDS.items() for name, _, _ in fields if name != "ints"}
    floats, flags, ints = {}, {}, {}
    for name, value in values.items():
        kind = kinds.get(name)
        if kind is None:
            raise ValueError(f"kernel field {name!r}: not a field of any registered term data class")
        {"float": floats, "flag": flags, "ints": ints}[kind][name] = value
    return pack(floats, {**ints, "ints": flags})


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


@term_data
@dataclasses.dataclass(frozen=True)
class SparsityData:
    """Derived by :func:`pack` from the other fields: the columns of V each strip's rows touch (CSR) and the
    elimination order of E V_dot = f (paper eqs. 8-10, 33; :func:`strip_columns`, :func:`solve_structure`)."""

    strip_col_ptr: np.ndarray = packed(1, "CSR pointers (n_s + 1,) into strip_cols", "ints")
    strip_cols: np.ndarray = packed(1, "ascending columns of V of each strip's rows", "ints")
    solve_perm: np.ndarray = packed(1, "active entries of V, block after block, then the core", "ints")
    solve_ptr: np.ndarray = packed(1, "block pointers (n_blocks + 2,) into solve_perm", "ints")


STRIP_COL_PTR, STRIP_COLS, SOLVE_PERM, SOLVE_PTR = (SparsityData.index[n] for n in
                                                    ("strip_col_ptr", "strip_cols", "solve_perm", "solve_ptr"))


# ------------------------------------------------------------------ field views
@inline
def _f1(F, I, k):
    o = I[1 + 5 * k]
    return F[o:o + I[2 + 5 * k]]


@inline
def _f2(F, I, k):
    o, a, b = I[1 + 5 * k], I[2 + 5 * k], I[3 + 5 * k]
    return F[o:o + a * b].reshape((a, b))


@inline
def _f3(F, I, k):
    o, a, b, c = I[1 + 5 * k], I[2 + 5 * k], I[3 + 5 * k], I[4 + 5 * k]
    return F[o:o + a * b * c].reshape((a, b, c))


@inline
def _f4(F, I, k):
    o, a, b, c, d = I[1 + 5 * k], I[2 + 5 * k], I[3 + 5 * k], I[4 + 5 * k], I[5 + 5 * k]
    return F[o:o + a * b * c * d].reshape((a, b, c, d))


@inline
def _i1(I, k):
    h = 1 + 5 * I[0] + 2 * k
    o = I[h]
    return I[o:o + I[h + 1]]


@inline
def _flag(I, k):
    return I[I[1 + 5 * I[0]] + k]
