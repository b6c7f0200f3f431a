"""Whether a flutter, divergence or V-g result lies inside the range of the aerodynamics that produced it.

The strip aerodynamics of flexsim are subsonic (Tuzcu & Nguyen 2014, eqs. 23-27: thin-airfoil theory with
Theodorsen's / Peters' wake). Compressibility enters only through the Prandtl-Glauert factor 1/sqrt(1 - M^2) on the
lift slopes (Anderson, *Fundamentals of Aerodynamics*, 5th ed., 2011, sec. 11.4, eq. 11.51), which diverges at
M = 1 and is capped at :data:`MACH_LIMIT` (M 0.95, :mod:`flexsim.model.coupling`): above it the lift slopes are
those of M 0.95, and no transonic effect (shocks, their motion) is modelled. Strips with the correction switched
off ("none": incompressible, e.g. the Goland wing's classical case) have no Mach dependence at all. So a result at
M >= :data:`MACH_LIMIT` is outside the model's range either way, and says so: the notes below are attached to the
result where it is produced (:class:`~flexsim.linear.flutter.FlutterPoint`,
:class:`~flexsim.linear.flutter.WindTunnelResult`, :class:`~flexsim.linear.vg.VgDiagram`) and printed with it.
"""

from __future__ import annotations

from flexsim.model.coupling import _MACH_CAP

__all__ = ["MACH_LIMIT", "mach_note"]

#: Highest Mach number of the model's subsonic strip aerodynamics [-] (the Prandtl-Glauert cap).
MACH_LIMIT = _MACH_CAP


def mach_note(what: str, mach: float, compressibility: str) -> str | None:
    """A note when ``what`` (e.g. "flutter", "divergence") at ``mach`` [-] is outside the aerodynamics' range, else None.

    Parameters
    ----------
    what : str
        The result, in words.
    mach : float
        Its Mach number [-].
    compressibility : {"prandtl-glauert", "none"}
        The correction the strips used.
    """
    if not mach >= MACH_LIMIT:
        return None
    if compressibility == "none":
        model = "incompressible strips (compressibility off)"
    else:
        model = f"lift slopes capped at M {MACH_LIMIT:g} (Prandtl-Glauert)"
    regime = "supersonic" if mach >= 1.0 else "transonic"
    return (f"{what} at M {mach:.4f} is outside the model's range (subsonic strip aerodynamics, M < {MACH_LIMIT:g}): "
            f"it comes from {model} in {regime} flow, which the model does not describe")
