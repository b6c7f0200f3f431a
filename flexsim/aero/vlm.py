"""Steady vortex-lattice method (VLM) for spanwise sectional lift-curve slopes.

Tuzcu & Nguyen (*Flutter of Maneuvering Aircraft*, "Numerical Model") replace the strip-theory value
``Clα = 2π`` by sectional slopes from a VLM of wing and horizontal stabiliser solved together (their
Fig. 6), with the Prandtl–Glauert factor ``1/√(1 − M²)``. This module provides that step.

Method
------
Classical horseshoe-vortex lattice (Katz & Plotkin 2001, *Low-Speed Aerodynamics*, 2nd ed., §12.1;
Bertin & Cummings, *Aerodynamics for Engineers*, Ch. 7 "vortex lattice numerical method"): each
planform panel carries a horseshoe vortex whose bound segment lies on the panel quarter-chord line
and whose two trailing legs run to ``x = +∞`` parallel to the x axis (flat, undeflected wake);
the flow-tangency condition is enforced at the three-quarter-chord point of each panel. Induced
velocities come from the Biot–Savart law for straight segments (Katz & Plotkin 2001, Ch. 10,
§10.4.5 "vortex line segment") and its semi-infinite limit, with a small cut-off radius.

Frame (VLM frame, metres): x aft (downstream), y right (starboard), z up. The free stream is
``V∞ = U (cos α, 0, sin α)``. From flexsim body axes (x forward, y right, z down, see
``docs/conventions.md``) the caller converts with ``(x, y, z)_vlm = (−x, y, −z)_body``, a proper
rotation by 180° about y. Positive circulation lifts (+z).

Sections are flat and their chord lines parallel to x (no twist or camber): in this linear model
twist and camber shift the zero-lift angle but do not change ``Clα``. Sectional coefficients are
normal-force coefficients per unit span along the surface, based on the local chord; the sectional
slope is referred to the local incidence ``α_local = α cos Γ_d`` (``Γ_d`` the local dihedral) so that a
strip theory using ``α_local`` does not count the dihedral twice.

Compressibility: Göthert's rule (default) or the plain Prandtl–Glauert factor, see :func:`solve_vlm`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Literal, Sequence, get_args

import numpy as np
from numpy.typing import ArrayLike

from flexsim._arrays import readonly

__all__ = [
    "LiftingSurface", "SurfaceLoads", "VlmResult", "plot_lift_slope", "sectional_lift_slope", "solve_vlm",
]

Spacing = Literal["uniform", "cosine"]
Compressibility = Literal["gothert", "prandtl_glauert"]
_SPACINGS: tuple[str, ...] = get_args(Spacing)
_COMPRESSIBILITY: tuple[str, ...] = get_args(Compressibility)
MAX_PANELS: int = 4000
"""Largest lattice accepted by :func:`solve_vlm` (dense ``O(N²)`` memory and ``O(N³)`` solve)."""
MAX_DIHEDRAL_DEG: float = 45.0
"""Largest segment dihedral (or anhedral) accepted; vertical surfaces are outside this model."""
CORE_RADIUS_FRACTION: float = 1.0e-6
"""Default cut-off radius of the vortex segments as a fraction of the bound-segment length."""
_ROWS_PER_CHUNK_BUDGET: int = 20_000
"""Number of (control point, horseshoe) pairs evaluated at once during assembly: 160 kB per temporary array, which
stays in the processor's cache (``benchmarks/bench_startup.py --parts`` times the lattice solve). The result does
not depend on it: every entry is computed by the same operations."""


def _is_count(value: object) -> bool:
    """True for an integer (not bool) ``>= 1``."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, bool) and value >= 1


@dataclass(frozen=True, eq=False)
class LiftingSurface:
    """A flat lifting surface described by a polyline of spanwise sections.

    Consecutive sections are joined by straight (trapezoidal) segments; each section's chord line
    runs from its leading-edge point in the +x direction. With ``mirror=True`` the sections describe
    the right half (``y ≥ 0``) and the left half is produced by the reflection ``y → −y``.

    Parameters
    ----------
    name : str
        Label used in results and plots (e.g. ``"wing"``, ``"htail"``); unique within a solve.
    le_m : array_like, shape (k, 3)
        Leading-edge points of the ``k ≥ 2`` sections [m], VLM frame (x aft, y right, z up). The
        y coordinates must increase strictly from section to section.
    chord_m : array_like, shape (k,)
        Section chords [m]. Positive; only the first and last section may be zero (pointed tip).
    n_chordwise : int
        Chordwise panels (uniformly spaced), ``≥ 1``.
    n_spanwise : int or sequence of int
        Spanwise panels per segment, ``≥ 1``; a sequence gives one count per segment (length
        ``k − 1``).
    spacing : {"uniform", "cosine"}
        Spanwise panel spacing within every segment; ``"cosine"`` clusters panels towards both ends
        of each segment (tips, kinks and the root).
    mirror : bool
        If True, add the mirror image about the plane ``y = 0``; requires ``le_m[0, 1] ≥ 0``.

    Raises
    ------
    ValueError
        If a field is malformed; the message names the field, the value and the allowed range.
    """

    name: str
    le_m: np.ndarray
    chord_m: np.ndarray
    n_chordwise: int = 4
    n_spanwise: int | tuple[int, ...] = 8
    spacing: Spacing = "uniform"
    mirror: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"name must be a non-empty string, got {self.name!r}")
        le = np.array(self.le_m, dtype=float)
        chord = np.array(self.chord_m, dtype=float)
        if le.ndim != 2 or le.shape[1] != 3 or le.shape[0] < 2:
            raise ValueError(f"le_m must have shape (k, 3) with k >= 2, got shape {le.shape}")
        k = le.shape[0]
        if chord.shape != (k,):
            raise ValueError(f"chord_m must have shape ({k},) to match le_m, got shape {chord.shape}")
        if not (np.all(np.isfinite(le)) and np.all(np.isfinite(chord))):
            raise ValueError("le_m and chord_m must be finite")
        if np.any(chord < 0.0):
            raise ValueError(f"chord_m must be >= 0 m, got min {chord.min():.6g} m")
        if np.any(chord[1:-1] <= 0.0) or np.any(chord[:-1] + chord[1:] <= 0.0):
            raise ValueError("chord_m must be > 0 m except at the first and last section")
        dy, dz = np.diff(le[:, 1]), np.diff(le[:, 2])
        if np.any(dy <= 0.0):
            raise ValueError(f"le_m[:, 1] (y) must increase strictly, got steps {dy.tolist()}")
        dihedral_deg = np.degrees(np.arctan2(np.abs(dz), dy))
        if np.any(dihedral_deg > MAX_DIHEDRAL_DEG):
            raise ValueError(
                f"segment dihedral must be within ±{MAX_DIHEDRAL_DEG:g} deg, got "
                f"{dihedral_deg.max():.3g} deg (vertical surfaces are not supported)"
            )
        if self.mirror and le[0, 1] < 0.0:
            raise ValueError(f"mirror=True requires le_m[0, 1] >= 0 m, got {le[0, 1]:.6g} m")
        if not _is_count(self.n_chordwise):
            raise ValueError(f"n_chordwise must be an int >= 1, got {self.n_chordwise!r}")
        counts = (self.n_spanwise,) * (k - 1) if np.ndim(self.n_spanwise) == 0 else tuple(self.n_spanwise)
        if len(counts) != k - 1 or not all(_is_count(n) for n in counts):
            raise ValueError(
                f"n_spanwise must be an int >= 1 or {k - 1} such ints (one per segment), "
                f"got {self.n_spanwise!r}"
            )
        if self.spacing not in _SPACINGS:
            raise ValueError(f"spacing must be one of {_SPACINGS}, got {self.spacing!r}")
        object.__setattr__(self, "le_m", readonly(le))
        object.__setattr__(self, "chord_m", readonly(chord))
        object.__setattr__(self, "n_chordwise", int(self.n_chordwise))
        object.__setattr__(self, "n_spanwise", tuple(int(n) for n in counts))
        object.__setattr__(self, "mirror", bool(self.mirror))

    @property
    def n_panels(self) -> int:
        """Number of panels of the lattice, both halves included."""
        return (2 if self.mirror else 1) * self.n_chordwise * sum(self.n_spanwise)


@dataclass(frozen=True, eq=False)
class SurfaceLoads:
    """Spanwise strip results of one surface, strips ordered by increasing y.

    Attributes
    ----------
    name : str
        Surface name.
    y_m, z_m : ndarray, shape (n_strips,)
        Strip centre (mid-point of the quarter-chord line) [m], VLM frame.
    eta : ndarray, shape (n_strips,)
        ``y_m / semispan_m``, in [−1, 1].
    chord_m : ndarray, shape (n_strips,)
        Local chord at the strip centre [m].
    width_m : ndarray, shape (n_strips,)
        Strip width measured along the surface in the y–z plane [m].
    dihedral_rad : ndarray, shape (n_strips,)
        Strip dihedral [rad], positive when the surface rises outboard (on either side).
    cl : ndarray, shape (n_strips,)
        Sectional normal-force coefficient at the solved angle of attack (local chord).
    cl_alpha_per_rad : ndarray, shape (n_strips,)
        Sectional lift-curve slope ``d cl / d α_local`` [1/rad], ``α_local = α cos Γ_d``.
    pieces_y_m : tuple of (float, float)
        Spanwise extent ``(y_min, y_max)`` [m] of each connected piece (two for a mirrored surface).
    piece_index : ndarray of int, shape (n_strips,)
        Piece each strip belongs to.
    semispan_m : float
        Largest ``|y|`` of the surface [m].
    area_m2 : float
        Planform area projected on the x–y plane [m²].
    lift_slope_per_rad : float
        Surface lift-curve slope ``dCL/dα`` [1/rad] on its own area, in presence of the other surfaces.
    """

    name: str
    y_m: np.ndarray
    z_m: np.ndarray
    eta: np.ndarray
    chord_m: np.ndarray
    width_m: np.ndarray
    dihedral_rad: np.ndarray
    cl: np.ndarray
    cl_alpha_per_rad: np.ndarray
    pieces_y_m: tuple[tuple[float, float], ...]
    piece_index: np.ndarray
    semispan_m: float
    area_m2: float
    lift_slope_per_rad: float

    def lift_slope_at(self, y_m: ArrayLike) -> np.ndarray:
        """Sectional ``Clα`` [1/rad] at spanwise stations, linearly interpolated between strips.

        Parameters
        ----------
        y_m : array_like, shape (n,)
            Stations [m], VLM frame; each must lie on one piece of the surface. Between the outermost
            strip centre and the piece edge the end value is held (no extrapolation).

        Returns
        -------
        ndarray, shape (n,)
        """
        y = np.atleast_1d(np.asarray(y_m, dtype=float))
        if y.ndim != 1 or not np.all(np.isfinite(y)):
            raise ValueError(f"stations must be a finite 1-D array, got shape {y.shape}")
        out = np.full(y.shape, np.nan)
        tol = 1e-9 * max(self.semispan_m, 1.0)
        for index, (lo, hi) in enumerate(self.pieces_y_m):
            on_piece = (y >= lo - tol) & (y <= hi + tol)
            strips = self.piece_index == index
            out[on_piece] = np.interp(y[on_piece], self.y_m[strips], self.cl_alpha_per_rad[strips])
        if np.any(np.isnan(out)):
            bad = y[np.isnan(out)]
            raise ValueError(
                f"stations {bad.tolist()} m lie outside surface {self.name!r}; "
                f"allowed y ranges: {list(self.pieces_y_m)} m"
            )
        return out


@dataclass(frozen=True, eq=False)
class VlmResult:
    """Solution of :func:`solve_vlm` for all surfaces solved together.

    Attributes
    ----------
    surfaces : tuple of SurfaceLoads
        Per-surface strip results, in input order.
    alpha_rad : float
        Angle of attack of the solve [rad].
    mach : float
        Free-stream Mach number.
    compressibility : str
        Compressibility treatment used (see :func:`solve_vlm`).
    s_ref_m2 : float
        Reference area [m²] of the total coefficients.
    lift_coefficient : float
        Total ``CL`` at ``alpha_rad`` (``CL = CLα sin α`` in this linear model).
    lift_slope_per_rad : float
        Total ``CLα = dCL/dα`` [1/rad] on ``s_ref_m2``.
    n_panels : int
        Number of panels solved.
    """

    surfaces: tuple[SurfaceLoads, ...]
    alpha_rad: float
    mach: float
    compressibility: str
    s_ref_m2: float
    lift_coefficient: float
    lift_slope_per_rad: float
    n_panels: int

    def surface(self, name: str) -> SurfaceLoads:
        """Return the :class:`SurfaceLoads` called ``name`` (``KeyError`` if absent)."""
        for loads in self.surfaces:
            if loads.name == name:
                return loads
        raise KeyError(f"no surface {name!r}; available: {[s.name for s in self.surfaces]}")


@dataclass(frozen=True, eq=False)
class _Lattice:
    """Horseshoe lattice of one surface. Panel arrays have shape (m, 3); strip arrays (n_strips,)."""

    bound_a: np.ndarray
    bound_b: np.ndarray
    control: np.ndarray
    normal: np.ndarray
    strip_of_panel: np.ndarray
    strip_y: np.ndarray
    strip_z: np.ndarray
    strip_chord: np.ndarray
    strip_width: np.ndarray
    strip_dy: np.ndarray
    strip_dihedral: np.ndarray
    strip_piece: np.ndarray
    pieces: tuple[tuple[float, float], ...]


def _edge_stations(surface: LiftingSurface) -> tuple[np.ndarray, np.ndarray]:
    """Leading-edge points (ne, 3) and chords (ne,) at the spanwise panel edges of the given half."""
    points, chords = [surface.le_m[:1]], [surface.chord_m[:1]]
    for seg, count in enumerate(surface.n_spanwise):
        t = np.linspace(0.0, 1.0, count + 1)[1:]
        if surface.spacing == "cosine":
            t = 0.5 * (1.0 - np.cos(math.pi * t))
        le_a, le_b = surface.le_m[seg], surface.le_m[seg + 1]
        c_a, c_b = surface.chord_m[seg], surface.chord_m[seg + 1]
        points.append(le_a + t[:, None] * (le_b - le_a))
        chords.append(c_a + t * (c_b - c_a))
    return np.concatenate(points), np.concatenate(chords)


def _lattice(surface: LiftingSurface) -> _Lattice:
    """Discretise ``surface`` (Katz & Plotkin 2001, §12.1): bound vortex at 1/4, collocation at 3/4."""
    le, chord = _edge_stations(surface)
    halves = [(le, chord)]
    if surface.mirror:
        halves.insert(0, ((le * np.array([1.0, -1.0, 1.0]))[::-1], chord[::-1]))
    nc = surface.n_chordwise
    frac = np.arange(nc, dtype=float) / nc
    keys = [key for key in _Lattice.__dataclass_fields__ if key != "pieces"]
    parts: dict[str, list[np.ndarray]] = {key: [] for key in keys}
    pieces: list[tuple[float, float]] = []
    strip_offset = 0
    x_hat = np.array([1.0, 0.0, 0.0])
    for piece, (edge_le, edge_c) in enumerate(halves):
        ns = edge_le.shape[0] - 1
        # Quarter- and three-quarter-chord points of every chordwise panel at each spanwise edge.
        quarter = edge_le[None] + ((frac + 0.25 / nc)[:, None] * edge_c[None])[..., None] * x_hat
        three_q = edge_le[None] + ((frac + 0.75 / nc)[:, None] * edge_c[None])[..., None] * x_hat
        parts["bound_a"].append(quarter[:, :-1].reshape(-1, 3))
        parts["bound_b"].append(quarter[:, 1:].reshape(-1, 3))
        parts["control"].append((0.5 * (three_q[:, :-1] + three_q[:, 1:])).reshape(-1, 3))
        span = np.diff(edge_le, axis=0)
        width = np.hypot(span[:, 1], span[:, 2])
        normal = np.stack([np.zeros(ns), -span[:, 2], span[:, 1]], axis=1) / width[:, None]
        parts["normal"].append(np.broadcast_to(normal, (nc, ns, 3)).reshape(-1, 3))
        parts["strip_of_panel"].append(np.tile(np.arange(ns) + strip_offset, nc))
        mid = 0.5 * (edge_le[:-1] + edge_le[1:])
        parts["strip_y"].append(mid[:, 1])
        parts["strip_z"].append(mid[:, 2])
        parts["strip_chord"].append(0.5 * (edge_c[:-1] + edge_c[1:]))
        parts["strip_width"].append(width)
        parts["strip_dy"].append(span[:, 1])
        side = np.where(mid[:, 1] < 0.0, -1.0, 1.0)
        parts["strip_dihedral"].append(side * np.arctan2(span[:, 2], span[:, 1]))
        parts["strip_piece"].append(np.full(ns, piece))
        pieces.append((float(edge_le[0, 1]), float(edge_le[-1, 1])))
        strip_offset += ns
    arrays = {key: np.concatenate(value) for key, value in parts.items()}
    return _Lattice(pieces=tuple(pieces), **arrays)


def _segment_velocity(r1, r2, n1, n2, r0, cut2_len0_2):
    """Velocity at points induced by unit-strength segments ``a → b``, as components (x, y, z), each (n, m).

    Biot–Savart law for a straight vortex segment (Katz & Plotkin 2001, §10.4.5):
    ``v = (r1 × r2)/(4π |r1 × r2|²) · r0·(r1/|r1| − r2/|r2|)``, set to zero for points closer to the
    segment line than the cut-off radius. Arguments: ``r1 = p − a``, ``r2 = p − b`` as components, each (n, m)
    [m], their lengths ``n1``, ``n2`` (n, m) [m], ``r0 = b − a`` as components, each (m,) [m], and
    ``cutoff² |r0|²`` (m,) [m⁴]. Sums of three products are formed as ``(x + z) + y`` throughout (the order of
    numpy's ``einsum`` over a last axis of 3, which the assembly used before: the matrix is the same bit for bit).
    """
    (x1, y1, z1), (x2, y2, z2), (x0, y0, z0) = r1, r2, r0
    cx = y1 * z2 - z1 * y2
    cy = z1 * x2 - x1 * z2
    cz = x1 * y2 - y1 * x2
    cross2 = (cx * cx + cz * cz) + cy * cy
    valid = cross2 > cut2_len0_2
    proj = ((x0 * x1 + z0 * z1) + y0 * y1) / np.where(valid, n1, 1.0) - ((x0 * x2 + z0 * z2) + y0 * y2) / np.where(
        valid, n2, 1.0)
    factor = np.where(valid, proj / (4.0 * math.pi * np.where(valid, cross2, 1.0)), 0.0)
    return factor * cx, factor * cy, factor * cz


def _trailing_velocity(r1, n1, cutoff2):
    """Velocity induced by unit semi-infinite segments from ``a`` to ``x = +∞``, as components (x, y, z), each (n, m).

    Limit of :func:`_segment_velocity` for ``b = a + L x̂``, ``L → ∞``:
    ``v = (x̂ × r1)/(4π |x̂ × r1|²) (1 + x̂·r1/|r1|)``, ``x̂ × r1 = (0, −r1_z, r1_y)``; ``r1 = p − a`` as components,
    each (n, m) [m], of length ``n1`` (n, m) [m], with the squared cut-off radius ``cutoff2`` (m,) [m²].
    """
    x1, y1, z1 = r1
    cross2 = y1**2 + z1**2
    valid = cross2 > cutoff2
    ratio = 1.0 + x1 / np.where(valid, n1, 1.0)
    factor = np.where(valid, ratio / (4.0 * math.pi * np.where(valid, cross2, 1.0)), 0.0)
    return factor * 0.0, factor * -z1, factor * y1


def _normalwash_matrix(
    control: np.ndarray, normal: np.ndarray, a: np.ndarray, b: np.ndarray, core_fraction: float
) -> np.ndarray:
    """Influence matrix (n, m): normal velocity at control point i from unit horseshoe j.

    The horseshoe ``∞ → a → b → ∞`` (trailing legs parallel to +x) is assembled from one finite and
    two semi-infinite segments, which share the vectors from their end points to the control points and
    their lengths; the vectors are kept as components (arrays of control points x horseshoes), and control
    points are processed in row chunks small enough for these to stay in the processor's cache
    (:data:`_ROWS_PER_CHUNK_BUDGET`).
    """
    cutoff = core_fraction * np.linalg.norm(b - a, axis=1)
    r0 = np.ascontiguousarray((b - a).T)
    cut2_len0_2 = cutoff**2 * ((r0[0] * r0[0] + r0[2] * r0[2]) + r0[1] * r0[1])
    cutoff2 = cutoff**2
    a_t, b_t = np.ascontiguousarray(a.T), np.ascontiguousarray(b.T)
    n, m = control.shape[0], a.shape[0]
    rows = max(1, _ROWS_PER_CHUNK_BUDGET // max(m, 1))
    out = np.empty((n, m))
    for start in range(0, n, rows):
        p = control[start : start + rows]
        r1 = tuple(p[:, k, None] - a_t[k] for k in range(3))
        r2 = tuple(p[:, k, None] - b_t[k] for k in range(3))
        n1 = np.sqrt((r1[0] * r1[0] + r1[2] * r1[2]) + r1[1] * r1[1])
        n2 = np.sqrt((r2[0] * r2[0] + r2[2] * r2[2]) + r2[1] * r2[1])
        bound = _segment_velocity(r1, r2, n1, n2, r0, cut2_len0_2)
        leg_b = _trailing_velocity(r2, n2, cutoff2)
        leg_a = _trailing_velocity(r1, n1, cutoff2)
        vx, vy, vz = (bound[k] + (leg_b[k] - leg_a[k]) for k in range(3))
        nrm = normal[start : start + rows]
        out[start : start + rows] = (vx * nrm[:, 0, None] + vz * nrm[:, 2, None]) + vy * nrm[:, 1, None]
    return out


def _check_flow(mach: float, alpha_rad: float, compressibility: str) -> float:
    """Validate the flow condition and return the Prandtl–Glauert factor ``β = √(1 − M²)``."""
    if not (math.isfinite(mach) and 0.0 <= mach < 1.0):
        raise ValueError(f"mach must be in [0, 1) (linear subsonic theory), got {mach!r}")
    if not (math.isfinite(alpha_rad) and abs(alpha_rad) < 0.5 * math.pi):
        raise ValueError(f"alpha_rad must be finite with |alpha_rad| < pi/2, got {alpha_rad!r}")
    if compressibility not in _COMPRESSIBILITY:
        raise ValueError(f"compressibility must be one of {_COMPRESSIBILITY}, got {compressibility!r}")
    return math.sqrt(1.0 - mach * mach)


def solve_vlm(
    surfaces: Sequence[LiftingSurface],
    *,
    alpha_rad: float = 0.0,
    mach: float = 0.0,
    compressibility: Compressibility = "gothert",
    s_ref_m2: float | None = None,
    core_radius_fraction: float = CORE_RADIUS_FRACTION,
) -> VlmResult:
    """Solve the steady horseshoe-vortex lattice of all ``surfaces`` together.

    Parameters
    ----------
    surfaces : sequence of LiftingSurface
        Surfaces solved together (e.g. wing and horizontal tail, which then interact through the
        trailing vortices); names must be unique.
    alpha_rad : float
        Angle of attack [rad], free stream ``U (cos α, 0, sin α)``; only ``cl`` and ``CL`` depend on it.
    mach : float
        Free-stream Mach number, ``0 ≤ M < 1``.
    compressibility : {"gothert", "prandtl_glauert"}
        ``"gothert"`` (default): Göthert's rule (Göthert 1946, NACA TM 1105; Bertin & Cummings,
        compressible subsonic flow chapter): the linearised compressible problem is the
        incompressible one for the planform stretched by ``1/β`` in x, with coefficients divided by
        ``β``. It is implemented by stretching all x coordinates before the influence assembly and
        referring loads to the true chords and areas, which yields the ``1/β`` factor exactly. The
        slope then rises less than ``1/β`` on a finite wing (as in DATCOM Eq. 4.1.3.2-a) and tends to
        ``1/β`` as the aspect ratio grows. ``"prandtl_glauert"``: solve incompressible and multiply
        the circulation by ``1/β``, i.e. Tuzcu & Nguyen's procedure ("the Prandtl–Glauert correction
        ``1/√(1−M²)`` is applied to Clα"); it overestimates the rise on low-aspect-ratio surfaces.
    s_ref_m2 : float, optional
        Reference area [m²] of the total coefficients; default the sum of the projected planform
        areas of all surfaces.
    core_radius_fraction : float
        Vortex cut-off radius as a fraction of each bound-segment length; a control point closer to
        a segment line gets no velocity from that segment.

    Returns
    -------
    VlmResult

    Raises
    ------
    ValueError
        For an empty or ill-typed ``surfaces``, duplicate names, more than :data:`MAX_PANELS`
        panels, or a flow condition out of range.

    Notes
    -----
    With sections parallel to x the panel normals have no x component, so the solution is linear
    in ``sin α`` and a single right-hand side ``−n_z`` (unit free stream, ``d/dα`` at α = 0) gives
    all slopes. Strip loads use Kutta–Joukowski on the bound segments with the free stream only
    (Katz & Plotkin 2001, §12.1): the normal force per unit span of a strip is ``ρ U Σ Γ``.
    """
    beta = _check_flow(float(mach), float(alpha_rad), compressibility)
    surfaces = tuple(surfaces)
    if not surfaces or not all(isinstance(s, LiftingSurface) for s in surfaces):
        raise ValueError("surfaces must be a non-empty sequence of LiftingSurface")
    names = [s.name for s in surfaces]
    if len(set(names)) != len(names):
        raise ValueError(f"surface names must be unique, got {names}")
    n_panels = sum(s.n_panels for s in surfaces)
    if n_panels > MAX_PANELS:
        raise ValueError(f"total panel count must be <= {MAX_PANELS}, got {n_panels}")
    if not (math.isfinite(core_radius_fraction) and 0.0 < core_radius_fraction < 0.5):
        raise ValueError(f"core_radius_fraction must be in (0, 0.5), got {core_radius_fraction!r}")

    lattices = [_lattice(s) for s in surfaces]
    a, b, control, normal = (
        np.concatenate([getattr(lat, key) for lat in lattices])
        for key in ("bound_a", "bound_b", "control", "normal")
    )
    stretch = np.array([1.0 / beta if compressibility == "gothert" else 1.0, 1.0, 1.0])
    matrix = _normalwash_matrix(control * stretch, normal, a * stretch, b * stretch, core_radius_fraction)
    gamma_alpha = np.linalg.solve(matrix, -normal[:, 2])
    if compressibility == "prandtl_glauert":
        gamma_alpha = gamma_alpha / beta

    areas = [float(np.sum(lat.strip_chord * lat.strip_dy)) for lat in lattices]
    s_ref = float(sum(areas)) if s_ref_m2 is None else float(s_ref_m2)
    if not (math.isfinite(s_ref) and s_ref > 0.0):
        raise ValueError(f"s_ref_m2 must be a positive finite area in m^2, got {s_ref_m2!r}")

    loads: list[SurfaceLoads] = []
    total_lift_slope = 0.0
    sin_alpha = math.sin(alpha_rad)
    offset = 0
    for surface, lat, area in zip(surfaces, lattices, areas):
        m = lat.bound_a.shape[0]
        strip_gamma = np.bincount(lat.strip_of_panel, weights=gamma_alpha[offset : offset + m])
        offset += m
        # Per unit U: normal force per span 2ΣΓ/(U c) as coefficient; lift (z) uses the y projection.
        cn_alpha = 2.0 * strip_gamma / lat.strip_chord
        cos_dihedral = lat.strip_dy / lat.strip_width
        surface_lift = float(np.sum(2.0 * strip_gamma * lat.strip_dy))
        total_lift_slope += surface_lift / s_ref
        semispan = max(abs(edge) for piece in lat.pieces for edge in piece)
        loads.append(
            SurfaceLoads(
                name=surface.name,
                y_m=readonly(lat.strip_y.copy()),
                z_m=readonly(lat.strip_z.copy()),
                eta=readonly(lat.strip_y / semispan),
                chord_m=readonly(lat.strip_chord.copy()),
                width_m=readonly(lat.strip_width.copy()),
                dihedral_rad=readonly(lat.strip_dihedral.copy()),
                cl=readonly(cn_alpha * sin_alpha),
                cl_alpha_per_rad=readonly(cn_alpha / cos_dihedral),
                pieces_y_m=lat.pieces,
                piece_index=readonly(lat.strip_piece.copy()),
                semispan_m=semispan,
                area_m2=area,
                lift_slope_per_rad=surface_lift / area,
            )
        )
    return VlmResult(
        surfaces=tuple(loads), alpha_rad=float(alpha_rad), mach=float(mach), compressibility=compressibility,
        s_ref_m2=s_ref, lift_coefficient=total_lift_slope * sin_alpha, lift_slope_per_rad=total_lift_slope,
        n_panels=n_panels,
    )


def sectional_lift_slope(
    surfaces: Sequence[LiftingSurface],
    stations_y_m: Sequence[ArrayLike],
    *,
    mach: float = 0.0,
    compressibility: Compressibility = "gothert",
) -> tuple[np.ndarray, ...]:
    """Sectional ``Clα`` [1/rad] at the caller's strip stations of each surface.

    Parameters
    ----------
    surfaces : sequence of LiftingSurface
        Surfaces solved together, see :func:`solve_vlm`.
    stations_y_m : sequence of array_like
        One array of spanwise stations ``y`` [m] (VLM frame) per surface, in the order of
        ``surfaces``.
    mach : float
        Free-stream Mach number, ``0 ≤ M < 1``.
    compressibility : {"gothert", "prandtl_glauert"}
        See :func:`solve_vlm`.

    Returns
    -------
    tuple of ndarray
        ``Clα`` at the stations, one array per surface (see :meth:`SurfaceLoads.lift_slope_at`).
    """
    surfaces = tuple(surfaces)
    stations = tuple(stations_y_m)
    if len(stations) != len(surfaces):
        count = len(surfaces)
        raise ValueError(f"stations_y_m must hold one array per surface ({count}), got {len(stations)}")
    result = solve_vlm(surfaces, mach=mach, compressibility=compressibility)
    return tuple(loads.lift_slope_at(y) for loads, y in zip(result.surfaces, stations))


def plot_lift_slope(result: VlmResult, path: str | Path) -> Path:
    """Plot sectional ``Clα`` against ``η = y / semispan`` for every surface (cf. Tuzcu & Nguyen Fig. 6).

    Parameters
    ----------
    result : VlmResult
        Output of :func:`solve_vlm`.
    path : str or Path
        Output image file; the format follows the suffix (e.g. ``.png``).

    Returns
    -------
    Path
        The written file.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.0, 4.0), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    for index, loads in enumerate(result.surfaces):
        colour = f"C{index}"
        for piece in range(len(loads.pieces_y_m)):
            sel = loads.piece_index == piece
            label = loads.name if piece == 0 else None
            ax.plot(loads.eta[sel], loads.cl_alpha_per_rad[sel], color=colour, marker=".", label=label)
    ax.axhline(2.0 * math.pi, color="k", linestyle="--", linewidth=1.0, label="2π (thin aerofoil)")
    ax.set_xlim(-1.0, 1.0)
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("η = y / semispan")
    ax.set_ylabel("sectional Clα [1/rad]")
    ax.set_title(f"VLM sectional lift-curve slope, M = {result.mach:.2f} ({result.compressibility})")
    ax.grid(True, alpha=0.3)
    ax.legend()
    out = Path(path)
    fig.savefig(out, dpi=120)
    return out
