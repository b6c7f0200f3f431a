"""Trend scorecard of flutter studies: what the results say about the manoeuvre and altitude trends.

Source of the trends compared: Tuzcu & Nguyen (2014), text to Figs. 7-16 and Tables 2-3 (held in
:mod:`flexsim.linear.paper_data` and only printed beside the computed values). Everything computed here
comes from flexsim's own study rows (:func:`flexsim.linear.study.run_case`):

* the sign of dM_F/dR and d omega_F/dR (turns) and dM_F/d gamma and d omega_F/d gamma (climbs) per model
  and altitude, from the least-squares slope over the study's points; a change over the whole range
  smaller than the flutter search's resolution (1e-4 in Mach, :data:`MACH_RESOLUTION`; 1e-4 rad/s in
  frequency) is reported as 0 (no resolved trend);
* the QS/US crossover altitude: where M_F(US) - M_F(QS) of level flight changes sign, by linear
  interpolation between neighbouring altitudes [m];
* the critical altitude of the turn trend: where the US dM_F/dR changes sign [m];
* the glide point: the climb curve's T_e = 0 (:func:`flexsim.linear.study.glide_from_climb`).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from flexsim.linear.paper_data import PAPER_TREND_SIGNS

__all__ = ["TrendSign", "trend_signs", "crossover_altitude", "critical_altitude", "MACH_RESOLUTION", "FREQUENCY_RESOLUTION"]

#: Smallest change of M_F over a study's range counted as a trend (the flutter search's tolerance).
MACH_RESOLUTION = 1e-4
#: Smallest change of omega_F [rad/s] over a study's range counted as a trend.
FREQUENCY_RESOLUTION = 1e-4

_X = {"turn": ("turn_radius_m", 1e-3, "R", "1/km"), "climb": ("climb_angle_deg", 1.0, "gamma", "1/deg")}


@dataclass(frozen=True)
class TrendSign:
    """One trend of a study: the sign of a derivative at one altitude, with the paper's.

    Attributes
    ----------
    quantity : str
        e.g. ``"dM_F/dR"``, ``"domega_F/dgamma"``.
    model : {"QS", "US", "FS"}
    altitude_m : float
    slope : float
        Least-squares slope [1/km for R, 1/deg for gamma; rad/s per km or per deg for omega_F].
    change : float
        Fitted change over the study's range (slope x range) [-] or [rad/s].
    sign : int
        -1, 0 or +1 (0: |change| below the resolution).
    paper_sign : int or None
        The paper's sign (its text), None where it states none (FS model).
    match : bool or None
        sign == paper_sign (None without a paper sign).
    n_points : int
    """

    quantity: str
    model: str
    altitude_m: float
    slope: float
    change: float
    sign: int
    paper_sign: int | None
    match: bool | None
    n_points: int

    def as_dict(self) -> dict:
        """Plain dict for JSON."""
        return asdict(self)


def trend_signs(rows: list[dict], kind: str) -> list[TrendSign]:
    """Signs of dM_F/dx and d omega_F/dx per model and altitude of a ``kind`` ("turn" or "climb") study.

    Rows without a flutter point (``error``) are left out; a (model, altitude) with fewer than two points
    gives no trend.
    """
    if kind not in _X:
        raise ValueError(f"kind = {kind!r}: must be \"turn\" or \"climb\"")
    key, scale, symbol, _ = _X[kind]
    out = []
    groups = sorted({(r["model"], r["altitude_m"]) for r in rows if "mach" in r and r.get(key) is not None})
    for model, h in groups:
        pts = sorted((r[key] * scale, r["mach"], r["omega_rad_s"]) for r in rows
                     if r["model"] == model and r["altitude_m"] == h and "mach" in r and r.get(key) is not None
                     and math.isfinite(r[key]))
        if len(pts) < 2:
            continue
        x, m, w = (np.array(c, dtype=float) for c in zip(*pts))
        span = float(x.max() - x.min())
        for name, y, res in ((f"dM_F/d{symbol}", m, MACH_RESOLUTION), (f"domega_F/d{symbol}", w, FREQUENCY_RESOLUTION)):
            slope = float(np.polyfit(x, y, 1)[0])
            change = slope * span
            sign = 0 if abs(change) < res else (1 if change > 0 else -1)
            paper = PAPER_TREND_SIGNS.get((kind, name.split("/")[0], model, float(h)))
            out.append(TrendSign(name, model, float(h), slope, change, sign, paper,
                                 None if paper is None else sign == paper, len(pts)))
    return out


def crossover_altitude(rows: list[dict]) -> float | None:
    """Altitude [m] where level-flight M_F(US) - M_F(QS) changes sign (linear interpolation), or None.

    ``rows``: level-flight rows (``flexsim flutter``) with both QS and US at two or more altitudes.
    """
    def level(model):
        return {r["altitude_m"]: r["mach"] for r in rows if r.get("model") == model and "mach" in r
                and math.isinf(r.get("turn_radius_m", math.inf)) and r.get("climb_angle_deg", 0.0) == 0.0}

    qs, us = level("QS"), level("US")
    common = sorted(set(qs) & set(us))
    diff = [(h, us[h] - qs[h]) for h in common]
    for (h0, d0), (h1, d1) in zip(diff[:-1], diff[1:]):
        if d0 == 0.0:
            return float(h0)
        if d0 * d1 < 0:
            return float(h0 + (h1 - h0) * d0 / (d0 - d1))
    if diff and diff[-1][1] == 0.0:
        return float(diff[-1][0])
    return None


def critical_altitude(signs: list[TrendSign], model: str = "US") -> float | None:
    """Altitude [m] where the turn trend dM_F/dR of ``model`` changes sign (linear interpolation of the
    slopes between neighbouring altitudes), or None."""
    pts = sorted((t.altitude_m, t.slope) for t in signs if t.quantity == "dM_F/dR" and t.model == model)
    for (h0, s0), (h1, s1) in zip(pts[:-1], pts[1:]):
        if s0 * s1 < 0:
            return float(h0 + (h1 - h0) * s0 / (s0 - s1))
    return None
