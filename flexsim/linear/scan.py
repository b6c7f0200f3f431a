"""The scan of a flutter search: its points, its step control, and the growth rate it scans.

A flutter (or wind-tunnel) search scans the growth rate g, the largest real part of the oscillatory elastic roots
[1/s] (Tuzcu & Nguyen 2014, "Numerical Model": flutter is where an eigenvalue of the linearised equations crosses the
imaginary axis), over a grid of speeds or Mach numbers, and refines the first sign change with Brent's method
(:mod:`flexsim.linear.flutter`). This module holds the grid (:func:`anchored_grid`: the same points whatever the lower
end of the range) and the step control that looks between two stable scan points (:func:`hidden_crossing`).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from flexsim.trimming.roots import Spectrum

__all__ = ["REFINE_LEVELS", "CURVATURE_SAFETY", "UNSTABLE_DAMPING", "MIN_TRIM_SPEED_M_S", "MAX_MACH_STEP", "MIN_SCAN_STEPS",
           "anchored_grid", "hidden_crossing", "scan_step"]

#: The slowest flight a scan point may ask for (:class:`flexsim.trimming.SteadyManoeuvre`'s lower limit) [m/s].
MIN_TRIM_SPEED_M_S = 1.0
#: Largest Mach step of a flutter scan, and the fewest steps over the range (:func:`scan_step`).
MAX_MACH_STEP = 0.05
MIN_SCAN_STEPS = 8


def scan_step(mach_range: tuple[float, float]) -> float:
    """The Mach step of a flutter scan over ``mach_range``: 0.05, or an eighth of a narrower range [-].

    0.05 on the paper's M 0.5-0.95; a sailplane's envelope (M 0.07-0.24) is scanned at 9 points instead of 4, so a
    crossing that goes unstable and back between two scan points is as unlikely as on the wide range.
    """
    lo, hi = mach_range
    return min(MAX_MACH_STEP, (hi - lo) / MIN_SCAN_STEPS)


#: Halvings of the scan step the step control may make: the smallest interval it looks into is step / 2**4 [-].
REFINE_LEVELS = 4
#: Safety factor on the interpolation-error bound of the step control (:func:`hidden_crossing`) [-].
CURVATURE_SAFETY = 2.0


def anchored_grid(lo: float, hi: float, step: float) -> np.ndarray:
    """The scan points of [lo, hi]: lo, every multiple of ``step`` strictly inside, and hi.

    Anchored at the multiples of the step rather than at ``lo``, so that searches of ranges that start at different
    speeds (or Mach numbers) evaluate the same points above their lower ends, and give the same answer there.
    """
    inner = np.arange(math.floor(lo / step) + 1, math.ceil(hi / step)) * step
    inner = inner[(inner > lo + 1e-9 * step) & (inner < hi - 1e-9 * step)]
    return np.concatenate([[lo], inner, [hi]])


def _second_difference(p0, p1, p2) -> float:
    """|g''| from three points (x, g(x)) of a parabola through them [1/unit^2]."""
    (x0, g0), (x1, g1), (x2, g2) = p0, p1, p2
    return abs(2.0 * ((g2 - g1) / (x2 - x1) - (g1 - g0) / (x1 - x0)) / (x2 - x0))


def hidden_crossing(g: Callable[[float], float], points: list[tuple[float, float]],
                    min_step: float) -> tuple[float, float] | None:
    """The lowest bracket (a, b), g(a) <= 0 < g(b), inside scan points whose values are all <= 0, or None.

    Step control of the flutter scans. Between two scan points a < b with g(a), g(b) <= 0 the linear interpolant of
    the growth rate g (the largest real part of the oscillatory elastic roots, continuous in the speed as the
    roots are) is below zero; g itself differs from it by at most max|g''| (b - a)^2 / 8 (the error of linear
    interpolation: Dahlquist & Bjorck, *Numerical Methods in Scientific Computing*, 2008, eq. 4.2.11). With
    |g''| estimated from the second differences of the neighbouring points (times :data:`CURVATURE_SAFETY`), an
    interval where that bound could reach zero is halved, and its halves checked the same way with the second
    difference of their own three points, down to ``min_step``. So an instability that rises above the axis and
    falls back between two scan points is found whenever it is wider than ``min_step`` and its curvature shows at
    the neighbouring points; it is not missed because of where the range starts.

    Parameters
    ----------
    g : callable
        The growth rate [1/s] at a speed or Mach number.
    points : list of (float, float)
        The scan points evaluated so far, increasing, every value <= 0.
    min_step : float
        The smallest interval halved [unit of the scan].
    """
    for i in range(len(points) - 1):
        near = [_second_difference(*points[j : j + 3]) for j in (i - 1, i) if 0 <= j and j + 2 < len(points)]
        found = _look_into(g, points[i], points[i + 1], CURVATURE_SAFETY * max(near, default=0.0), min_step)
        if found is not None:
            return found
    return None


def _look_into(g, left, right, curvature: float, min_step: float) -> tuple[float, float] | None:
    (a, ga), (b, gb) = left, right
    h = b - a
    if not (math.isfinite(ga) and math.isfinite(gb) and math.isfinite(curvature)):
        return None  # -inf: no oscillatory elastic root at one end, nothing whose damping could be interpolated
    if h <= min_step * (1.0 + 1e-9) or max(ga, gb) + curvature * h * h / 8.0 <= 0.0:
        return None
    c = 0.5 * (a + b)
    gc = g(c)
    if gc > 0.0:
        return _look_into(g, left, (c, gc), 0.0, min_step) or (a, c)
    curvature = max(curvature, CURVATURE_SAFETY * _second_difference(left, (c, gc), right))
    return _look_into(g, left, (c, gc), curvature, min_step) or _look_into(g, (c, gc), right, curvature, min_step)


#: Relative tolerance on "unstable": a real part counts as positive only above this fraction of the
#: mode's |eigenvalue| (damping ratio below -1e-9). Round-off on a neutrally stable mode (e.g. +1e-14 1/s
#: on an undamped structure without aerodynamics) is not an instability.
UNSTABLE_DAMPING = 1e-9


def _growth(spec: Spectrum) -> float:
    """Largest real part of the oscillatory elastic modes, zeroed within round-off of neutral [1/s]."""
    cands = [m for m in spec.of_kind("elastic") if m.frequency_rad_s >= 0.5]
    if not cands:
        return -np.inf
    worst = max(cands, key=lambda m: m.eigenvalue.real)
    re = worst.eigenvalue.real
    return re if abs(re) > UNSTABLE_DAMPING * abs(worst.eigenvalue) else 0.0
