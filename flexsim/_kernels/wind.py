"""Wind fields as arrays and their compiled evaluation: 1-cos gusts and frozen Dryden turbulence (NED [m/s]).

Sources: CS-25.341(a) / MIL-F-8785C 3.7.3 discrete gust; MIL-F-8785C 3.7.2 Dryden turbulence, a frozen field
(Taylor's hypothesis). :mod:`flexsim.sim.disturbances` builds the arrays (:class:`WindData`); the right-hand side
(:mod:`flexsim._kernels.equations`) samples them at the strips. Inertial NED, body and component axes; SI units.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from flexsim._arrays import frozen_array
from flexsim._kernels.isa import dcm_321
from flexsim._kernels.layout import _f2, _f3, kernel
from flexsim._kernels.strips import STRIP_DCM, STRIP_POS


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



@kernel
def gust_profile(s, amplitude, gradient_length, persistent):
    """1-cos gust velocity U(s) [m/s] at penetration distance s [m] (CS-25.341(a); MIL-F-8785C 3.7.3):
    (U_ds/2)(1 - cos(pi s/H)) on [0, 2H] (persistent: on [0, H], then U_ds), 0 elsewhere."""
    end = gradient_length if persistent else 2.0 * gradient_length
    if persistent and s > gradient_length:
        return amplitude
    if 0.0 <= s <= end:
        return 0.5 * amplitude * (1.0 - math.cos(math.pi * s / gradient_length))
    return 0.0


@kernel
def dryden_along_track(grid, spacing, xi):
    """Frozen Dryden field (u, v, w) [m/s] at distance xi [m] along the track: linear interpolation on the
    periodic grid (3, n) of points ``spacing`` apart (MIL-F-8785C 3.7.2, Taylor's hypothesis)."""
    i0, i1, frac = _grid_cell(grid.shape[1], spacing, xi)
    out = np.empty(3)
    for c in range(3):
        out[c] = grid[c, i0] * (1.0 - frac) + grid[c, i1] * frac
    return out


@kernel
def _grid_cell(n, spacing, xi):
    """The points (i0, i1) of the periodic grid of n points ``spacing`` apart around distance xi [m] and the
    fraction of the way from i0 to i1 (:func:`dryden_along_track`)."""
    pos = xi / spacing
    cell = math.floor(pos)
    frac = pos - cell
    i0 = int(cell - n * math.floor(cell / n))
    i1 = 0 if i0 + 1 == n else i0 + 1
    return i0, i1, frac


@kernel
def gust_profiles(s, amplitude, gradient_length, persistent):
    """:func:`gust_profile` at every penetration distance of s (k,) [m]."""
    out = np.empty(s.shape[0])
    for j in range(s.shape[0]):
        out[j] = gust_profile(s[j], amplitude, gradient_length, persistent)
    return out


@kernel
def dryden_track(grid, spacing, xi):
    """:func:`dryden_along_track` at every distance of xi (k,) [m]: (k, 3) [m/s]."""
    out = np.empty((xi.shape[0], 3))
    for j in range(xi.shape[0]):
        out[j] = dryden_along_track(grid, spacing, xi[j])
    return out


@kernel
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
            i0, i1, frac = _grid_cell(grid.shape[1], turb[t, 12], xi)  # dryden_along_track, without an array
            c0 = grid[0, i0] * (1.0 - frac) + grid[0, i1] * frac
            c1 = grid[1, i0] * (1.0 - frac) + grid[1, i1] * frac
            c2 = grid[2, i0] * (1.0 - frac) + grid[2, i1] * frac
            for a in range(3):
                out[j, a] += c0 * ax[0, a] + c1 * ax[1, a] + c2 * ax[2, a]
    return out


@kernel
def strip_positions(F, I, pos, c):
    """Inertial positions R + C^T r of the strips' undeformed EA points (n_s, 3) [m], NED."""
    r = _f2(F, I, STRIP_POS)
    out = np.empty((r.shape[0], 3))
    for j in range(r.shape[0]):
        for a in range(3):
            out[j, a] = pos[a] + r[j, 0] * c[0, a] + r[j, 1] * c[1, a] + r[j, 2] * c[2, a]
    return out


@kernel
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



@kernel
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
